/* SPDX-License-Identifier: MIT */
/* report.c -- the paper-style table and the JSON Lines records of the fits. */
#include "cli.h"

#include <math.h>
#include <string.h>

static const char *backend_name(const brdffit_context *ctx)
{
    return brdffit_context_backend(ctx) == BRDFFIT_BACKEND_OPENCL ? "opencl" : "host";
}

/* ------------------------------------------------------------------ table */

/* Column layout: model, d_rgb, s_rgb, p0..p2, Error, iterations, seconds. */
#define ROW_FMT "%-17s  %9s %9s %9s  %9s %9s %9s  %10s %10s %10s  %11s %5s %8s%s\n"

static const char *num(char *buf, size_t len, const char *fmt, double x)
{
    snprintf(buf, len, fmt, x);
    return buf;
}

void report_header(FILE *f, const cli_material *m, const brdffit_samples *s,
                   const brdffit_context *ctx, const brdffit_fit_options *fo)
{
    fputs("material ", f);
    plain_string(f, m->name);
    if (m->file) {
        fputs("  (", f);
        plain_string(f, m->file);
        fputs(")", f);
    }
    fputc('\n', f);
    if (m->about)
        fprintf(f, "  %s\n", m->about);
    fprintf(f, "  metric %s, cutoff %g deg, scale %s\n", brdffit_metric_name(),
            m->sample.cutoff_deg, brdffit_scale_name(m->sample.scale));
    fputs("  backend ", f);
    plain_string(f, brdffit_context_describe(ctx));
    fputc('\n', f);
    fprintf(f, "  samples %zu fitted (%zu bins masked, %zu beyond the cutoff)\n"
               "  fit: ",
            brdffit_samples_count(s), brdffit_samples_masked(s), brdffit_samples_beyond_cutoff(s));
    char dflt[256];
    if (fo->starts > 0)
        fprintf(f, "%d starts screened per model", fo->starts);
    else
        fprintf(f, "the model's default starts screened (%s)", cli_default_starts(dflt, sizeof dflt));
    fprintf(f, ", the best %d refined by Levenberg-Marquardt (cminpack lmder)\n\n", fo->refine);
    fprintf(f, ROW_FMT, "model", "d_r", "d_g", "d_b", "s_r", "s_g", "s_b", "p0", "p1", "p2",
            "Error", "iter", "seconds", "");
    fflush(f);
}

/* The names of the parameters a result has on a bound (lobe ones only, or
 * also d_c = 0 and s_c = 0), each passed to put(name, user). */
static void bound_names(const brdffit_fit_result *r, int with_linear,
                        void (*put)(const char *name, void *user), void *user)
{
    const brdffit_model_info *mi = brdffit_model_get(r->model);
    static const char *const dn[3] = { "d_r", "d_g", "d_b" }, *const sn[3] = { "s_r", "s_g", "s_b" };
    for (int k = 0; k < mi->nparams; k++)
        if (r->at_bound & ((unsigned)BRDFFIT_AT_BOUND_P0 << k))
            put(mi->params[k].name, user);
    for (int c = 0; with_linear && c < 3; c++)
        if (r->at_bound & ((unsigned)BRDFFIT_AT_BOUND_D_R << c))
            put(dn[c], user);
    for (int c = 0; with_linear && c < 3; c++)
        if (r->at_bound & ((unsigned)BRDFFIT_AT_BOUND_S_R << c))
            put(sn[c], user);
}

typedef struct note_buf {
    char *buf;
    size_t len;
    int n;
} note_buf;

static void note_put(const char *name, void *user)
{
    note_buf *nb = user;
    size_t o = strlen(nb->buf);
    snprintf(nb->buf + o, nb->len - o, "%s%s", nb->n++ ? ", " : " on a bound: ", name);
}

/* The table row's trailing note: "  stopped on the evaluation limit", "  on a bound: m". */
static const char *row_note(const brdffit_fit_result *r, char *buf, size_t len)
{
    buf[0] = '\0';
    if (!r)
        return buf;
    note_buf nb = { buf, len, 0 };
    if (r->flags & BRDFFIT_FIT_LIMIT)
        snprintf(buf, len, "  stopped on the evaluation limit");
    if (r->at_bound & BRDFFIT_AT_BOUND_LOBE) {
        size_t o = strlen(buf);
        snprintf(buf + o, len - o, " ");
        bound_names(r, 0, note_put, &nb);
    }
    return buf;
}

void report_row(FILE *f, const char *label, const brdffit_model_info *mi,
                const brdffit_params *p, double error, const brdffit_fit_result *r)
{
    char d[3][32], s[3][32], q[3][32], e[32], it[32], sec[32];
    for (int c = 0; c < 3; c++) {
        num(d[c], sizeof d[c], "%.4g", p->d[c]);
        num(s[c], sizeof s[c], "%.4g", p->s[c]);
        if (c < mi->nparams)
            num(q[c], sizeof q[c], "%.4g", p->p[c]);
        else
            strcpy(q[c], "-");
    }
    if (isfinite(error))
        num(e, sizeof e, "%.5g", error);
    else
        strcpy(e, "-");
    if (r) {
        snprintf(it, sizeof it, "%d", r->iterations);
        num(sec, sizeof sec, "%.2f", r->seconds);
    } else {
        strcpy(it, "-");
        strcpy(sec, "-");
    }
    char note[256];
    fprintf(f, ROW_FMT, label ? label : mi->name, d[0], d[1], d[2], s[0], s[1], s[2], q[0], q[1],
            q[2], e, it, sec, row_note(r, note, sizeof note));
    fflush(f);
}

void report_row_failed(FILE *f, brdffit_model model, const brdffit_error *err)
{
    fprintf(f, "%-17s  FAILED: %s: ", brdffit_model_get(model)->name, brdffit_strerror(err->status));
    /* the first line of the message only (a kernel build log follows on stderr) */
    const char *msg = err->message;
    size_t n = strcspn(msg, "\n");
    char line[256];
    snprintf(line, sizeof line, "%.*s", (int)(n < 255 ? n : 255), msg);
    plain_string(f, line);
    fputc('\n', f);
    fflush(f);
}

void report_legend(FILE *f, const brdffit_model *models, int nmodels)
{
    fputs("\n  p0..p2:", f);
    for (int i = 0; i < nmodels; i++) {
        const brdffit_model_info *mi = brdffit_model_get(models[i]);
        fprintf(f, "%s %s", i ? ";" : "", mi->name);
        for (int k = 0; k < mi->nparams; k++) {
            const brdffit_param_info *pi = &mi->params[k];
            fprintf(f, " %s%s%s%s", pi->name, *pi->unit ? "[" : "", pi->unit, *pi->unit ? "]" : "");
        }
    }
    fprintf(f, "\n  d = Lambertian albedo (diffuse = d/pi), s = specular coefficient rho_s;"
               " Error = %s (1/sr);\n  iter = Jacobian evaluations of the LM run kept,"
               " seconds = wall time of the fit\n",
            brdffit_metric_name());
}

/* ------------------------------------------------------------------ JSON */

typedef struct json_list {
    FILE *f;
    int n;
} json_list;

static void json_list_put(const char *name, void *user)
{
    json_list *l = user;
    if (l->n++)
        putc(',', l->f);
    json_string(l->f, name);
}

static void json_metric(FILE *f, const cli_material *m)
{
    fputs("\"metric\":{\"name\":", f);
    json_string(f, brdffit_metric_name());
    fputs(",\"cutoff_deg\":", f);
    json_number(f, m->sample.cutoff_deg);
    fputs(",\"scale\":", f);
    json_string(f, brdffit_scale_name(m->sample.scale));
    fputc('}', f);
}

static void json_head(FILE *f, const cli_material *m)
{
    fputs("{\"material\":", f);
    json_string(f, m->name);
    fputs(",\"file\":", f);
    json_string(f, m->file);
}

void report_json_fit(FILE *f, const cli_material *m, const brdffit_context *ctx,
                     const brdffit_samples *s, brdffit_model model, brdffit_status st,
                     const brdffit_error *err, const brdffit_fit_result *r)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    json_head(f, m);
    fputs(",\"model\":", f);
    json_string(f, mi->name);
    fputs(",\"status\":", f);
    json_string(f, st != BRDFFIT_OK ? brdffit_strerror(st)
                   : r && (r->flags & BRDFFIT_FIT_LIMIT) ? "limit" : "ok");
    if (st != BRDFFIT_OK || !r) {
        fputs(",\"error_message\":", f);
        json_string(f, err ? err->message : "");
    }
    fputs(",\"param_names\":[", f);
    for (int k = 0; k < mi->nparams; k++) {
        if (k)
            putc(',', f);
        json_string(f, mi->params[k].name);
    }
    putc(']', f);
    if (r && st == BRDFFIT_OK) {
        fputs(",\"d\":", f);
        json_numbers(f, r->params.d, 3);
        fputs(",\"s\":", f);
        json_numbers(f, r->params.s, 3);
        fputs(",\"p\":", f);
        json_numbers(f, r->params.p, mi->nparams);
        if (mi->chromatic) {
            fputs(",\"lambda_um\":", f);
            json_numbers(f, r->params.lambda_um, 3);
        }
        fputs(",\"error\":", f);
        json_number(f, r->error);
    } else {
        fputs(",\"d\":null,\"s\":null,\"p\":null,\"error\":null", f);
    }
    putc(',', f);
    json_metric(f, m);
    if (r && st == BRDFFIT_OK) {
        fprintf(f, ",\"iterations\":%d,\"passes\":%d,\"cminpack_info\":%d", r->iterations,
                r->passes, r->cminpack_info);
        json_list lst = { f, 0 };
        fputs(",\"at_bound\":[", f);
        bound_names(r, 1, json_list_put, &lst);
        fputs("],\"flags\":[", f);
        lst.n = 0;
        if (r->flags & BRDFFIT_FIT_LIMIT)
            json_list_put("limit", &lst);
        putc(']', f);
    } else {
        fputs(",\"iterations\":null,\"passes\":null,\"cminpack_info\":null,"
              "\"at_bound\":null,\"flags\":null", f);
    }
    fputs(",\"seconds\":", f);
    json_number(f, r && st == BRDFFIT_OK ? r->seconds : NAN);
    fputs(",\"seconds_solver\":", f);
    json_number(f, r && st == BRDFFIT_OK ? r->seconds_solver : NAN);
    fputs(",\"seconds_passes\":", f);
    json_number(f, r && st == BRDFFIT_OK ? r->seconds_passes : NAN);
    fputs(",\"seconds_build\":", f);
    json_number(f, r && st == BRDFFIT_OK ? r->seconds_build : NAN);
    fputs(",\"backend\":", f);
    json_string(f, backend_name(ctx));
    fputs(",\"backend_description\":", f);
    json_string(f, brdffit_context_describe(ctx));
    fprintf(f, ",\"samples\":%zu}\n", brdffit_samples_count(s));
    fflush(f);
}

void report_json_failure(FILE *f, const cli_material *m, brdffit_status st,
                         const brdffit_error *err)
{
    json_head(f, m);
    fputs(",\"model\":null,\"status\":", f);
    json_string(f, brdffit_strerror(st));
    fputs(",\"error_message\":", f);
    json_string(f, err ? err->message : "");
    putc(',', f);
    json_metric(f, m);
    fputs("}\n", f);
    fflush(f);
}
