/* SPDX-License-Identifier: MIT */
/* fit_record_check.c -- a journaled record judged as this program writes it:
 * well-typed JSON is not enough (fit_record_json.c reads the types; here
 * the values).  A record that fails is ignored and its fit done again, so a
 * tampered or damaged journal never shows a negative Error as the best fit,
 * nor keeps parameters the renders cannot take. */
#define _POSIX_C_SOURCE 200809L
#include "fit_record.h"
#include "fit_record_parts.h"

#include <math.h>
#include <string.h>

static int is_hash(const char *h)
{
    if (strlen(h) != 16)
        return 0;
    for (int i = 0; i < 16; i++)
        if (!strchr("0123456789abcdef", h[i]))
            return 0;
    return 1;
}

/* The name of a material as the program gives it: a file's base name. */
static int is_name(const char *s)
{
    return s[0] && !strchr(s, '/') && strcmp(s, ".") != 0 && strcmp(s, "..") != 0;
}

static const char *check_key(const fit_record *r)
{
    brdffit_scale sc;
    if (!is_name(r->material))
        return "the material name is empty or not a file name";
    if (!r->id.path[0])
        return "no file";
    if (r->id.size >= 0 || r->id.hash[0]) { /* a file that was read: its size and hash */
        if (r->id.size < 0 || !is_hash(r->id.hash))
            return "the file's size or hash is not one this program writes";
    } else if (r->kind != FR_FAILURE) {
        return "no size and hash of the file (only a failure to read it has none)";
    }
    if (!r->settings.version[0] ||
        brdffit_scale_from_name(r->settings.scale, &sc, NULL) != BRDFFIT_OK ||
        strcmp(r->settings.scale, brdffit_scale_name(sc)) != 0)
        return "the settings name no version or no known scale";
    if (!(r->settings.cutoff_deg > 0 && r->settings.cutoff_deg <= 90))
        return "the cutoff is not in (0, 90] degrees";
    return NULL;
}

/* The model of a fit or published record: one of this version's, by its name. */
static const brdffit_model_info *model_of(const fit_record *r)
{
    brdffit_model m;
    if (!fr_record_model(r, &m))
        return NULL;
    const brdffit_model_info *mi = brdffit_model_get(m);
    return mi && strcmp(mi->name, r->model) == 0 ? mi : NULL;
}

static const char *check_params(const fit_record *r, const brdffit_model_info *mi, char *why,
                                size_t len)
{
    if (!r->has_params)
        return "no parameters";
    if (r->nparams != mi->nparams) {
        snprintf(why, len, "p holds %d numbers, %s has %d parameters", r->nparams, mi->name,
                 mi->nparams);
        return why;
    }
    for (int c = 0; c < 3; c++)
        if (!isfinite(r->params.d[c]) || !isfinite(r->params.s[c]) ||
            !isfinite(r->params.lambda_um[c]))
            return "d, s or lambda_um holds a number that is not finite";
    for (int k = 0; k < r->nparams; k++)
        if (!isfinite(r->params.p[k]))
            return "p holds a number that is not finite";
    return NULL;
}

/* A result: parameters the model takes, an Error that is a finite number >= 0. */
static const char *check_result(const fit_record *r, const brdffit_model_info *mi, char *why,
                                size_t len)
{
    const char *bad = check_params(r, mi, why, len);
    if (bad)
        return bad;
    brdffit_error e;
    if (brdffit_params_check(mi->id, &r->params, &e) != BRDFFIT_OK) {
        snprintf(why, len, "parameters out of range (%.200s)", e.message);
        return why;
    }
    if (!(isfinite(r->error) && r->error >= 0))
        return "the Error is not a finite number >= 0";
    return NULL;
}

/* A fit's metric is one of the metrics; its Errors under them, each a
 * finite number >= 0 or absent (NaN: not computed, or a record of a version
 * without them), the one of its metric, when present, its Error. */
static const char *check_errors(const fit_record *r, char *why, size_t len)
{
    brdffit_metric m;
    if (brdffit_metric_from_name(r->settings.metric, &m, NULL) != BRDFFIT_OK) {
        snprintf(why, len, "metric \"%.32s\" is not a metric", r->settings.metric);
        return why;
    }
    for (int k = 0; k < BRDFFIT_METRIC_COUNT; k++)
        if (!isnan(r->errors[k]) && !(isfinite(r->errors[k]) && r->errors[k] >= 0)) {
            snprintf(why, len, "the Error under %s is not a finite number >= 0",
                     brdffit_metric_get_name((brdffit_metric)k));
            return why;
        }
    if (!isnan(r->errors[m]) && r->errors[m] != r->error) {
        snprintf(why, len, "the Error %.17g is not its Error under its metric %s, %.17g",
                 r->error, r->settings.metric, r->errors[m]);
        return why;
    }
    return NULL;
}

/* The energy fields: a successful fit's only, curves of numbers >= 0. */
static const char *check_albedo(const fit_record *r)
{
    int ok_fit = r->kind == FR_FIT && r->status == BRDFFIT_OK;
    if ((r->has_albedo || r->has_albedo_measured) && !ok_fit)
        return "an albedo where no fit succeeded";
    for (int k = 0; k < FR_ALBEDO_N; k++)
        for (int c = 0; c < 3; c++)
            if ((r->has_albedo && !(r->albedo[k][c] >= 0)) ||
                (r->has_albedo_measured && !(r->albedo_measured[k][c] >= 0)))
                return "an albedo below 0";
    if (!isnan(r->seconds_albedo) && !(r->seconds_albedo >= 0 && r->has_albedo))
        return "seconds_albedo without an albedo, or below 0";
    return NULL;
}

static const char *check_failed(const fit_record *r)
{
    if (!r->message[0])
        return "a failure without its message";
    if (!isnan(r->error))
        return "a failure with an Error";
    return NULL;
}

const char *fr_check(const fit_record *r, char *why, size_t len)
{
    const char *bad = check_key(r);
    if (!bad)
        bad = check_albedo(r);
    if (bad)
        return bad;
    const brdffit_model_info *mi = NULL;
    if (r->kind == FR_FIT || r->kind == FR_PUBLISHED) {
        if (!(mi = model_of(r)))
            return "no model of this version";
    } else if (r->model[0]) {
        return "a model where none belongs";
    }
    switch (r->kind) {
    case FR_FIT:
        if (r->status != BRDFFIT_OK)
            return r->has_params ? "a failed fit with parameters" : check_failed(r);
        if (!r->has_counts)
            return "a fit without its iterations and passes";
        if ((bad = check_result(r, mi, why, len)) != NULL)
            return bad;
        return check_errors(r, why, len);
    case FR_PUBLISHED: /* parameters as published, in range or not (then its status says) */
        if (r->status != BRDFFIT_OK)
            return (bad = check_params(r, mi, why, len)) ? bad : check_failed(r);
        return check_result(r, mi, why, len);
    case FR_FAILURE:
        if (r->status == BRDFFIT_OK)
            return "a failure with the status ok";
        return r->has_params ? "a failure with parameters" : check_failed(r);
    case FR_ASSETS:
        return r->assets_key[0] ? NULL : "renders without what was drawn (assets_key)";
    }
    return "an unknown kind";
}
