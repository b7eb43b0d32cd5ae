/* SPDX-License-Identifier: MIT */
/* fit_record.c -- the fit record (fit_record.h): filling it, its status, the
 * retry decision of a resumed batch, the names of its at_bound bits.  Its
 * JSON is fit_record_json.c, its TSV fit_record_tsv.c. */
#define _POSIX_C_SOURCE 200809L
#include "fit_record.h"
#include "fit_record_parts.h"
#include "batch.h"
#include "cli.h"

#include <math.h>
#include <string.h>

/* ------------------------------------------------------------------ filling */

void fr_init(fit_record *r, fr_kind kind)
{
    memset(r, 0, sizeof *r);
    r->kind = kind;
    r->status = BRDFFIT_OK;
    r->id.size = -1;
    r->error = NAN;
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
        r->errors[m] = NAN;
    r->seconds = r->seconds_solver = r->seconds_passes = r->seconds_build = NAN;
    r->albedo_max = r->albedo_max_theta_o = r->albedo_departure = NAN;
    r->albedo_departure_theta_o = r->seconds_albedo = NAN;
    r->samples = -1;
}

void fr_set_failure(fit_record *r, brdffit_status st, const brdffit_error *err)
{
    r->status = st;
    snprintf(r->message, sizeof r->message, "%s",
             err && err->message[0] ? err->message : brdffit_strerror(st));
}

void fr_set_fit(fit_record *r, brdffit_model model, brdffit_status st, const brdffit_error *err,
                const brdffit_fit_result *res, const brdffit_context *ctx,
                const brdffit_samples *s)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    snprintf(r->model, sizeof r->model, "%s", mi->name);
    r->nparams = mi->nparams;
    if (s)
        r->samples = (long long)brdffit_samples_count(s);
    if (ctx) {
        snprintf(r->backend, sizeof r->backend, "%s",
                 brdffit_context_backend(ctx) == BRDFFIT_BACKEND_OPENCL ? "opencl" : "host");
        snprintf(r->backend_description, sizeof r->backend_description, "%s",
                 brdffit_context_describe(ctx));
    }
    if (st != BRDFFIT_OK || !res) {
        fr_set_failure(r, st != BRDFFIT_OK ? st : BRDFFIT_E_FIT_FAILED, err);
        return;
    }
    r->status = BRDFFIT_OK;
    r->message[0] = '\0';
    r->has_params = 1;
    r->params = res->params;
    r->error = res->error;
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
        r->errors[m] = res->errors[m];
    r->has_counts = 1;
    r->iterations = res->iterations;
    r->passes = res->passes;
    r->cminpack_info = res->cminpack_info;
    r->flags = res->flags;
    r->at_bound = res->at_bound;
    r->seconds = res->seconds;
    r->seconds_solver = res->seconds_solver;
    r->seconds_passes = res->seconds_passes;
    r->seconds_build = res->seconds_build;
    r->samples = (long long)res->samples;
    if (res->backend == BRDFFIT_BACKEND_HOST && strcmp(r->backend, "host") != 0) {
        /* a model the kernel does not have (the glTF models): the C loop */
        snprintf(r->backend, sizeof r->backend, "host");
        snprintf(r->backend_description, sizeof r->backend_description,
                 "host: C loop in threads (%s has no OpenCL kernel)", mi->name);
    }
}

int fr_ok(const fit_record *r)
{
    return r->status == BRDFFIT_OK;
}

const char *fr_status_text(const fit_record *r)
{
    if (r->status != BRDFFIT_OK)
        return brdffit_strerror(r->status);
    return r->flags & BRDFFIT_FIT_LIMIT ? "limit" : "ok";
}

int fr_retry(const fit_record *r)
{
    static const brdffit_status transient[] = { BRDFFIT_E_NO_MEMORY, BRDFFIT_E_NO_DEVICE,
                                                BRDFFIT_E_OPENCL, BRDFFIT_E_KERNEL_BUILD,
                                                BRDFFIT_E_CACHE_DIR };
    if (r->kind != FR_FIT || r->status == BRDFFIT_OK)
        return 0;
    for (size_t i = 0; i < sizeof transient / sizeof transient[0]; i++)
        if (r->status == transient[i])
            return 1;
    return 0;
}

/* ------------------------------------------------------------------ at_bound */

static const unsigned linear_bits[6] = { BRDFFIT_AT_BOUND_D_R, BRDFFIT_AT_BOUND_D_G,
                                         BRDFFIT_AT_BOUND_D_B, BRDFFIT_AT_BOUND_S_R,
                                         BRDFFIT_AT_BOUND_S_G, BRDFFIT_AT_BOUND_S_B };

/* The name of colour c (0 .. 5: the first colour's r, g, b, the second's)
 * of model: "d_r", ..., "s_b", or the glTF models' "base_color_r", ...
 * (brdffit_model_info.colour_names). */
static const char *linear_name(brdffit_model model, int c, char *buf, size_t len)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    snprintf(buf, len, "%s_%c", mi ? mi->colour_names[c / 3] : c < 3 ? "d" : "s", "rgb"[c % 3]);
    return buf;
}

void fr_at_bound_names(brdffit_model model, unsigned at_bound, int with_linear,
                       void (*put)(const char *name, void *user), void *user)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    for (int k = 0; mi && k < mi->nparams; k++)
        if (at_bound & ((unsigned)BRDFFIT_AT_BOUND_P0 << k))
            put(mi->params[k].name, user);
    char name[64];
    for (int c = 0; with_linear && c < 6; c++)
        if (at_bound & linear_bits[c])
            put(linear_name(model, c, name, sizeof name), user);
}

typedef struct text_buf {
    char *buf;
    size_t len;
    const char *sep;
    int n;
} text_buf;

static void text_put(const char *name, void *user)
{
    text_buf *t = user;
    size_t o = strlen(t->buf);
    snprintf(t->buf + o, t->len - o, "%s%s", t->n++ ? t->sep : "", name);
}

const char *fr_at_bound_text(brdffit_model model, unsigned at_bound, const char *sep, char *buf,
                             size_t len)
{
    buf[0] = '\0';
    text_buf t = { buf, len, sep, 0 };
    fr_at_bound_names(model, at_bound, 1, text_put, &t);
    return buf;
}

/* The bit of the parameter named name (len bytes) of model, or 0. */
unsigned fr_bound_bit(brdffit_model model, const char *name, size_t len)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    for (int k = 0; mi && k < mi->nparams; k++)
        if (strlen(mi->params[k].name) == len && strncmp(mi->params[k].name, name, len) == 0)
            return (unsigned)BRDFFIT_AT_BOUND_P0 << k;
    char lin[64];
    for (int c = 0; c < 6; c++) {
        linear_name(model, c, lin, sizeof lin);
        if (strlen(lin) == len && strncmp(lin, name, len) == 0)
            return linear_bits[c];
    }
    return 0;
}

/* The model the record names: 1 when it is one of brdffit's. */
int fr_record_model(const fit_record *r, brdffit_model *m)
{
    return r->model[0] && brdffit_model_from_name(r->model, m, NULL) == BRDFFIT_OK;
}
