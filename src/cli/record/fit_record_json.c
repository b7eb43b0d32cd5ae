/* SPDX-License-Identifier: MIT */
/* fit_record_json.c -- the fit record's JSON writer and reader.  The field
 * names are written here and nowhere else; docs/fit-record.md describes them. */
#define _POSIX_C_SOURCE 200809L
#include "fit_record.h"
#include "fit_record_parts.h"
#include "batch.h"
#include "cli.h"

#include <limits.h>
#include <math.h>
#include <string.h>

static const char *const kind_names[] = { "fit", "failure", "published", "assets" };

/* ------------------------------------------------------------------ JSON writer */

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

static void json_count(FILE *f, const char *key, int have, long long v)
{
    fprintf(f, ",\"%s\":", key);
    if (have)
        fprintf(f, "%lld", v);
    else
        fputs("null", f);
}

static void json_text(FILE *f, const char *key, const char *s)
{
    fprintf(f, ",\"%s\":", key);
    json_string(f, s && s[0] ? s : NULL);
}

void fr_write_json(FILE *f, const fit_record *r)
{
    brdffit_model model;
    int known = fr_record_model(r, &model);
    const brdffit_model_info *mi = known ? brdffit_model_get(model) : NULL;
    fputs("{\"kind\":", f);
    json_string(f, kind_names[r->kind]);
    fputs(",\"material\":", f);
    json_string(f, r->material);
    json_text(f, "file", r->id.path);
    json_count(f, "size", r->id.size >= 0, r->id.size);
    json_text(f, "hash", r->id.hash);
    fputs(",\"settings\":{\"version\":", f);
    json_string(f, r->settings.version);
    fputs(",\"metric\":", f);
    json_string(f, r->settings.metric[0] ? r->settings.metric : brdffit_metric_name());
    fputs(",\"scale\":", f);
    json_string(f, r->settings.scale);
    fputs(",\"cutoff_deg\":", f);
    json_number(f, r->settings.cutoff_deg);
    fprintf(f, ",\"starts\":%d}", r->settings.starts);
    json_text(f, "model", r->model);
    fputs(",\"param_names\":", f);
    if (mi) {
        putc('[', f);
        for (int k = 0; k < mi->nparams; k++) {
            if (k)
                putc(',', f);
            json_string(f, mi->params[k].name);
        }
        putc(']', f);
    } else {
        fputs("null", f);
    }
    fputs(",\"colour_names\":", f);
    if (mi) {
        putc('[', f);
        json_string(f, mi->colour_names[0]);
        putc(',', f);
        json_string(f, mi->colour_names[1]);
        putc(']', f);
    } else {
        fputs("null", f);
    }
    fputs(",\"status\":", f);
    json_string(f, fr_status_text(r));
    fprintf(f, ",\"status_code\":%d,\"message\":", (int)r->status);
    json_string(f, r->message);
    if (r->has_params) {
        fputs(",\"d\":", f);
        json_numbers(f, r->params.d, 3);
        fputs(",\"s\":", f);
        json_numbers(f, r->params.s, 3);
        fputs(",\"p\":", f);
        json_numbers(f, r->params.p, r->nparams);
        fputs(",\"lambda_um\":", f);
        const double *l = r->params.lambda_um;
        if ((mi && mi->chromatic) || l[0] != 0 || l[1] != 0 || l[2] != 0)
            json_numbers(f, l, 3);
        else
            fputs("null", f);
    } else {
        fputs(",\"d\":null,\"s\":null,\"p\":null,\"lambda_um\":null", f);
    }
    fputs(",\"error\":", f);
    json_number(f, r->error);
    fputs(",\"errors\":", f);
    if (isfinite(r->errors[0]) || isfinite(r->errors[1]) || isfinite(r->errors[2])) {
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
            fprintf(f, "%s\"%s\":", m ? "," : "{", brdffit_metric_get_name((brdffit_metric)m));
            json_number(f, r->errors[m]);
        }
        putc('}', f);
    } else {
        fputs("null", f);
    }
    json_count(f, "iterations", r->has_counts, r->iterations);
    json_count(f, "passes", r->has_counts, r->passes);
    json_count(f, "cminpack_info", r->has_counts, r->cminpack_info);
    if (r->has_counts) {
        json_list l = { f, 0 };
        fputs(",\"flags\":[", f);
        if (r->flags & BRDFFIT_FIT_LIMIT)
            json_list_put("limit", &l);
        fputs("],\"at_bound\":[", f);
        l.n = 0;
        fr_at_bound_names(known ? model : BRDFFIT_WARD, known ? r->at_bound : r->at_bound & ~(unsigned)BRDFFIT_AT_BOUND_LOBE, 1,
                          json_list_put, &l);
        putc(']', f);
    } else {
        fputs(",\"flags\":null,\"at_bound\":null", f);
    }
    fputs(",\"seconds\":", f);
    json_number(f, r->seconds);
    fputs(",\"seconds_solver\":", f);
    json_number(f, r->seconds_solver);
    fputs(",\"seconds_passes\":", f);
    json_number(f, r->seconds_passes);
    fputs(",\"seconds_build\":", f);
    json_number(f, r->seconds_build);
    json_count(f, "samples", r->samples >= 0, r->samples);
    json_text(f, "backend", r->backend);
    json_text(f, "backend_description", r->backend_description);
    json_text(f, "assets_key", r->kind == FR_ASSETS ? r->assets_key : NULL);
    json_text(f, "assets", r->kind == FR_ASSETS ? r->assets : NULL);
    fr_albedo_write_json(f, r);
    putc('}', f);
}

/* ------------------------------------------------------------------ JSON reader */

/* A string member (or null/absent: ""); -1 when too long or of another type
 * (required: absent or null is -1 too). */
static int get_str(const jr_object *o, const jr_member *in, const char *key, char *out, size_t len,
                   int required)
{
    const jr_member *m = in ? jr_get_in(o, in, key) : jr_get(o, key);
    out[0] = '\0';
    if (!m || m->type == JR_NULL)
        return required ? -1 : 0;
    if (m->type != JR_STRING || strlen(m->str) >= len)
        return -1;
    strcpy(out, m->str);
    return 0;
}

/* A number (null: NAN); absent: NAN, or -1 when required. */
static int get_num(const jr_object *o, const jr_member *in, const char *key, double *x,
                   int required)
{
    const jr_member *m = in ? jr_get_in(o, in, key) : jr_get(o, key);
    *x = NAN;
    if (!m)
        return required ? -1 : 0;
    if (m->type != JR_NUMBER && m->type != JR_NULL)
        return -1;
    *x = m->num;
    return 0;
}

/* A whole number in [lo, hi]: 1 read, 0 null or absent, -1 anything else. */
static int get_whole(const jr_object *o, const jr_member *in, const char *key, double lo,
                     double hi, long long *v)
{
    const jr_member *m = in ? jr_get_in(o, in, key) : jr_get(o, key);
    if (!m || m->type == JR_NULL)
        return 0;
    double x = m->num;
    if (m->type != JR_NUMBER || !(x >= lo && x <= hi) || x != floor(x))
        return -1;
    *v = (long long)x;
    return 1;
}

/* An array of numbers (at most max): 1 read, 0 null or absent, -1 anything else. */
static int get_arr(const jr_object *o, const char *key, double *x, int max, int *n)
{
    const jr_member *m = jr_get(o, key);
    if (!m || m->type == JR_NULL)
        return 0;
    if (m->type != JR_ARRAY || m->narr > max || m->str)
        return -1;
    for (int i = 0; i < m->narr; i++)
        x[i] = m->arr[i];
    if (n)
        *n = m->narr;
    return 1;
}

/* The names of a list ("n,d_r" or, from an array of strings, "n\nd_r") as
 * at_bound bits of model: 0, or -1 when a name is not one of its parameters. */
static int bound_bits(brdffit_model model, int known, const char *list, const char *seps,
                      int cut_at_eq, unsigned *bits)
{
    *bits = 0;
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, seps);
        size_t name = cut_at_eq ? strcspn(p, "=") : n;
        if (name > n)
            name = n;
        if (n > 0) {
            unsigned b = known || name == 3 ? fr_bound_bit(model, p, name) : 0;
            if (!b || (!known && b < BRDFFIT_AT_BOUND_D_R))
                return -1;
            *bits |= b;
        }
        p += n;
        if (*p)
            p++;
    }
    return 0;
}

/* The status code of a record without "status_code" (an earlier version's):
 * from its "status" text and "ok". */
static brdffit_status status_of_text(const char *text, int ok, int *limit)
{
    *limit = strcmp(text, "limit") == 0;
    if (ok > 0 || strcmp(text, "ok") == 0 || *limit)
        return BRDFFIT_OK;
    for (int s = 1; s < BRDFFIT_STATUS_COUNT; s++)
        if (strcmp(text, brdffit_strerror((brdffit_status)s)) == 0)
            return (brdffit_status)s;
    return BRDFFIT_E_FIT_FAILED;
}

int fr_read_json(const char *line, fit_record *r, fr_need need)
{
    jr_object o;
    if (jr_parse(line, &o) != 0)
        return -1;
    fr_init(r, FR_FIT);
    int rc = -1;
    long long v;
    char text[64];

    /* kind: "fit" when absent (fit --json of earlier versions) and a model is named */
    const jr_member *km = jr_get(&o, "kind"), *mm = jr_get(&o, "model");
    if (km) {
        if (get_str(&o, NULL, "kind", text, sizeof text, 1) != 0)
            goto done;
        r->kind = (fr_kind)-1;
        for (int k = 0; k < 4; k++)
            if (strcmp(text, kind_names[k]) == 0)
                r->kind = (fr_kind)k;
        if ((int)r->kind < 0)
            goto done;
    } else if (need == FR_NEED_KEY) {
        goto done;
    } else {
        r->kind = mm && mm->type == JR_STRING && mm->str[0] ? FR_FIT : FR_FAILURE;
    }
    if (get_str(&o, NULL, "material", r->material, sizeof r->material, 1) != 0 ||
        get_str(&o, NULL, "model", r->model, sizeof r->model, need == FR_NEED_KEY && !mm) != 0)
        goto done;
    if (need == FR_NEED_FIT && !mm)
        goto done;
    brdffit_model model = BRDFFIT_WARD;
    int known = fr_record_model(r, &model);

    /* the file: "file", "size", "hash"; earlier journals: "file": {path, size, hash} */
    const jr_member *file = jr_get(&o, "file");
    const jr_member *idin = file && file->type == JR_OBJECT ? file : NULL;
    int sized = 0;
    if (idin) {
        if (get_str(&o, idin, "path", r->id.path, sizeof r->id.path, 1) != 0 ||
            get_str(&o, idin, "hash", r->id.hash, sizeof r->id.hash, 1) != 0)
            goto done;
        sized = get_whole(&o, idin, "size", -1, 9.0e15, &v);
    } else {
        if (get_str(&o, NULL, "file", r->id.path, sizeof r->id.path, 0) != 0 ||
            get_str(&o, NULL, "hash", r->id.hash, sizeof r->id.hash, 0) != 0)
            goto done;
        sized = get_whole(&o, NULL, "size", -1, 9.0e15, &v);
    }
    if (sized < 0 || (idin && sized == 0))
        goto done;
    if (sized > 0)
        r->id.size = v;
    /* a size is known for a file that was read; only a failure may lack it */
    if (need == FR_NEED_KEY && (r->kind != FR_FAILURE ? r->id.size < 0 || !r->id.hash[0]
                                                      : !r->id.path[0]))
        goto done;

    /* the settings; fit --json of earlier versions: "metric" {scale, cutoff_deg} */
    const jr_member *set = jr_get(&o, "settings");
    if (set && set->type == JR_OBJECT) {
        if (get_str(&o, set, "version", r->settings.version, sizeof r->settings.version, 1) != 0 ||
            get_str(&o, set, "scale", r->settings.scale, sizeof r->settings.scale, 1) != 0 ||
            get_num(&o, set, "cutoff_deg", &r->settings.cutoff_deg, 1) != 0 ||
            get_whole(&o, set, "starts", 0, INT_MAX, &v) != 1)
            goto done;
        r->settings.starts = (int)v;
        /* "metric": the one the fits minimised ("ngan-l2" before there were others) */
        if (get_str(&o, set, "metric", r->settings.metric, sizeof r->settings.metric, 0) != 0)
            goto done;
    } else if (need == FR_NEED_KEY) {
        goto done;
    } else {
        const jr_member *met = jr_get(&o, "metric");
        if (met && met->type == JR_OBJECT &&
            (get_str(&o, met, "scale", r->settings.scale, sizeof r->settings.scale, 0) != 0 ||
             get_num(&o, met, "cutoff_deg", &r->settings.cutoff_deg, 0) != 0))
            goto done;
    }

    if (!r->settings.metric[0])
        snprintf(r->settings.metric, sizeof r->settings.metric, "%s", brdffit_metric_name());

    /* the status: "status_code"; earlier versions: the "status" text and "ok" */
    int limit = 0;
    int coded = get_whole(&o, NULL, "status_code", 0, BRDFFIT_STATUS_COUNT - 1, &v);
    if (coded < 0)
        goto done;
    if (coded) {
        r->status = (brdffit_status)v;
    } else {
        const jr_member *ok = jr_get(&o, "ok");
        if (get_str(&o, NULL, "status", text, sizeof text, 1) != 0 ||
            (ok && ok->type != JR_BOOL))
            goto done;
        r->status = status_of_text(text, ok ? (int)ok->num : -1, &limit);
    }
    const jr_member *msg = jr_get(&o, "message") ? jr_get(&o, "message") : jr_get(&o, "error_message");
    if (msg && get_str(&o, NULL, msg->key, r->message, sizeof r->message, 0) != 0)
        goto done;

    /* the parameters and the Error */
    int hd = get_arr(&o, "d", r->params.d, 3, NULL);
    int hs = hd < 0 ? -1 : get_arr(&o, "s", r->params.s, 3, NULL);
    int hp = hs < 0 ? -1 : get_arr(&o, "p", r->params.p, BRDFFIT_MAX_LOBE_PARAMS, &r->nparams);
    int n3 = 3;
    int hl = hp < 0 ? -1 : get_arr(&o, "lambda_um", r->params.lambda_um, 3, &n3);
    if (hd < 0 || hs < 0 || hp < 0 || hl < 0 || n3 != 3)
        goto done;
    if (hd && hs && hp) {
        const jr_member *dm = jr_get(&o, "d"), *sm = jr_get(&o, "s");
        if (dm->narr != 3 || sm->narr != 3)
            goto done;
        r->nparams = jr_get(&o, "p")->narr;
        r->has_params = r->kind != FR_FIT || r->status == BRDFFIT_OK;
    } else {
        memset(&r->params, 0, sizeof r->params);
        r->nparams = 0;
        if (hd || hs || hp)
            goto done;
    }
    if (!r->has_params) {
        /* no parameters kept: their count is the model's, as the writer
         * gives it (none for a model this version does not know) */
        memset(&r->params, 0, sizeof r->params);
        r->nparams = known ? brdffit_model_get(model)->nparams : 0;
    }
    if (get_num(&o, NULL, "error", &r->error, 0) != 0)
        goto done;
    const jr_member *errs = jr_get(&o, "errors");
    if (errs && errs->type == JR_OBJECT) {
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
            if (get_num(&o, errs, brdffit_metric_get_name((brdffit_metric)m), &r->errors[m], 0) != 0)
                goto done;
    } else if (errs && errs->type != JR_NULL) {
        goto done;
    }

    /* what the fit did */
    long long it = 0, np = 0, info = 0;
    int hi = get_whole(&o, NULL, "iterations", 0, INT_MAX, &it);
    int hn = get_whole(&o, NULL, "passes", 0, INT_MAX, &np);
    int hf = get_whole(&o, NULL, "cminpack_info", INT_MIN, INT_MAX, &info);
    if (hi < 0 || hn < 0 || hf < 0)
        goto done;
    r->has_counts = hi > 0;
    r->iterations = (int)it;
    r->passes = (int)np;
    r->cminpack_info = (int)info;
    const jr_member *fl = jr_get(&o, "flags");
    if (fl && fl->type == JR_ARRAY && fl->narr > 0) {
        if (!fl->str)
            goto done;
        for (const char *p = fl->str; *p;) {
            size_t n = strcspn(p, "\n");
            if (n == 5 && strncmp(p, "limit", 5) == 0)
                r->flags |= BRDFFIT_FIT_LIMIT;
            else
                goto done;
            p += n + (p[n] != '\0');
        }
    } else if (fl && fl->type != JR_NULL && fl->type != JR_ARRAY) {
        goto done;
    }
    if (limit)
        r->flags |= BRDFFIT_FIT_LIMIT;
    const jr_member *ab = jr_get(&o, "at_bound"), *ob = jr_get(&o, "on_bound");
    if (ab && ab->type == JR_ARRAY && ab->narr > 0) {
        if (!ab->str || ab->narr > 10 || bound_bits(model, known, ab->str, "\n", 0, &r->at_bound) != 0)
            goto done;
    } else if (ab && ab->type != JR_NULL && ab->type != JR_ARRAY) {
        goto done;
    } else if (ob) { /* earlier journals: "n=upper,d_b=0" */
        char list[128];
        if (get_str(&o, NULL, "on_bound", list, sizeof list, 0) != 0 ||
            bound_bits(model, known, list, ",", 1, &r->at_bound) != 0)
            goto done;
    }
    if (!r->has_counts) { /* what a fit did is known of a fit that succeeded only */
        r->iterations = r->passes = r->cminpack_info = 0;
        r->flags = r->at_bound = 0;
    }
    if (get_num(&o, NULL, "seconds", &r->seconds, 0) != 0 ||
        get_num(&o, NULL, "seconds_solver", &r->seconds_solver, 0) != 0 ||
        get_num(&o, NULL, "seconds_passes", &r->seconds_passes, 0) != 0 ||
        get_num(&o, NULL, "seconds_build", &r->seconds_build, 0) != 0)
        goto done;
    int hsm = get_whole(&o, NULL, "samples", 0, 9.0e15, &v);
    if (hsm < 0)
        goto done;
    if (hsm > 0)
        r->samples = v;
    if (get_str(&o, NULL, "backend", r->backend, sizeof r->backend, 0) != 0 ||
        get_str(&o, NULL, "backend_description", r->backend_description,
                sizeof r->backend_description, 0) != 0)
        goto done;
    if (r->kind == FR_ASSETS &&
        (get_str(&o, NULL, "assets_key", r->assets_key, sizeof r->assets_key, 0) != 0 ||
         get_str(&o, NULL, "assets", r->assets, sizeof r->assets, 0) != 0))
        goto done;
    if (fr_albedo_read_json(&o, r) != 0)
        goto done;
    rc = 0;
done:
    jr_free(&o);
    return rc;
}
