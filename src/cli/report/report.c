/* SPDX-License-Identifier: MIT */
/* report.c -- the paper-style table of the fits (their JSON records: fit_record.h). */
#include "cli.h"
#include "fit_record.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------------ table */

/* Column layout: model, d_rgb, s_rgb, p0..p3, Error, iterations, seconds. */
#define ROW_FMT "%-17s  %9s %9s %9s  %9s %9s %9s  %10s %10s %10s %10s  %11s %5s %8s%s\n"

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
    fprintf(f, "  metric %s, cutoff %g deg, scale %s\n",
            brdffit_metric_get_name((brdffit_metric)(fo ? fo->metric : 0)),
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
    fprintf(f, ROW_FMT, "model", "d_r", "d_g", "d_b", "s_r", "s_g", "s_b", "p0", "p1", "p2", "p3",
            "Error", "iter", "seconds", "");
    fflush(f);
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
        fr_at_bound_names(r->model, r->at_bound, 0, note_put, &nb);
    }
    return buf;
}

void report_row(FILE *f, const char *label, const brdffit_model_info *mi,
                const brdffit_params *p, double error, const brdffit_fit_result *r)
{
    char d[3][32], s[3][32], q[BRDFFIT_MAX_LOBE_PARAMS][32], e[32], it[32], sec[32];
    for (int c = 0; c < 3; c++) {
        num(d[c], sizeof d[c], "%.4g", p->d[c]);
        num(s[c], sizeof s[c], "%.4g", p->s[c]);
    }
    for (int k = 0; k < BRDFFIT_MAX_LOBE_PARAMS; k++) {
        if (k < mi->nparams)
            num(q[k], sizeof q[k], "%.4g", p->p[k]);
        else
            strcpy(q[k], "-");
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
            q[2], q[3], e, it, sec, row_note(r, note, sizeof note));
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

void report_legend(FILE *f, const brdffit_model *models, int nmodels, brdffit_metric metric)
{
    fputs("\n  p0..p3:", f);
    for (int i = 0; i < nmodels; i++) {
        const brdffit_model_info *mi = brdffit_model_get(models[i]);
        fprintf(f, "%s %s", i ? ";" : "", mi->name);
        for (int k = 0; k < mi->nparams; k++) {
            const brdffit_param_info *pi = &mi->params[k];
            fprintf(f, " %s%s%s%s", pi->name, *pi->unit ? "[" : "", pi->unit, *pi->unit ? "]" : "");
        }
    }
    for (int i = 0; i < nmodels; i++)
        if (brdffit_model_get(models[i])->colour_form == BRDFFIT_COLOUR_GLTF) {
            fputs("\n  gltf, gltf-ext: d = base_color, s = specular_color (linear sRGB);"
                  " roughness = sqrt(alpha)", f);
            break;
        }
    for (int i = 0; i < nmodels; i++)
        if (brdffit_model_get(models[i])->colour_form == BRDFFIT_COLOUR_OPENPBR) {
            fputs("\n  openpbr: d = base_color, s = specular_color (linear sRGB);"
                  " alpha = specular_roughness^2; base_weight 1, base_diffuse_roughness 0", f);
            break;
        }
    fprintf(f, "\n  d = Lambertian albedo (diffuse = d/pi), s = specular coefficient rho_s;"
               " Error = %s (1/sr);\n  iter = Jacobian evaluations of the LM run kept,"
               " seconds = wall time of the fit\n",
            brdffit_metric_get_name(metric));
}
