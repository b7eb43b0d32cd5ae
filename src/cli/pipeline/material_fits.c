/* SPDX-License-Identifier: MIT */
/* material_fits.c -- the fitted models `render` and `plot` draw for a table:
 * read from a file of fits (the JSON Lines of `brdffit fit --json`, records
 * of fit_record.h, or a TSV of the ngan2005-fits.tsv format), or fitted now
 * (the one loop of fit_pipeline.h). */
#define _POSIX_C_SOURCE 200809L
#include "material_fits.h"
#include "batch.h"
#include "fit_pipeline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int wanted(const brdffit_model *models, int nmodels, brdffit_model m)
{
    for (int k = 0; k < nmodels; k++)
        if (models[k] == m)
            return 1;
    return 0;
}

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), t = strlen(tail);
    return n >= t && strcmp(s + n - t, tail) == 0;
}

/* One record of a file of fits (fit_record.h) into f when it is a fit of the
 * material in a wanted model that succeeded.  1 taken, 0 not for us, -1
 * malformed (why). */
static int take_record(const fit_record *r, const char *material, const brdffit_model *models,
                       int nmodels, brdffit_scale scale, rf_fit *f, const char **why)
{
    /* status "ok" only: a fit stopped on its evaluation limit is not drawn */
    if (r->kind != FR_FIT || strcmp(r->material, material) != 0 || !fr_ok(r) ||
        (r->flags & BRDFFIT_FIT_LIMIT))
        return 0;
    brdffit_model m;
    *why = "unknown model";
    if (brdffit_model_from_name(r->model, &m, NULL) != BRDFFIT_OK)
        return -1;
    if (!wanted(models, nmodels, m))
        return 0;
    brdffit_scale rs;
    if (r->settings.scale[0] && brdffit_scale_from_name(r->settings.scale, &rs, NULL) == BRDFFIT_OK &&
        rs != scale) {
        *why = scale == BRDFFIT_SCALE_FLAT ? "fitted with --scale standard (pass it)"
                                           : "fitted with --scale flat (pass it)";
        return -1;
    }
    const brdffit_model_info *mi = brdffit_model_get(m);
    *why = "d, s (3 numbers) and p (the model's parameters) expected";
    if (!r->has_params || r->nparams != mi->nparams)
        return -1;
    *why = "parameters out of the model's bounds (brdffit models)";
    if (brdffit_params_check(m, &r->params, NULL) != BRDFFIT_OK)
        return -1;
    memset(f, 0, sizeof *f);
    f->model = m;
    f->params = r->params;
    f->error = r->error;
    return 1;
}

/* Put f in fits (a later fit of the same model replaces an earlier one). */
static void keep(rf_fit *fits, int *nfits, const rf_fit *f)
{
    for (int k = 0; k < *nfits; k++)
        if (fits[k].model == f->model) {
            fits[k] = *f;
            return;
        }
    if (*nfits < RF_MAX_FITS)
        fits[(*nfits)++] = *f;
}

static int read_jsonl(const char *path, const char *material, const brdffit_model *models,
                      int nmodels, brdffit_scale scale, rf_fit *fits, int *nfits,
                      brdffit_error *err)
{
    FILE *in = cli_fopen_regular(path, err);
    if (!in)
        return -1;
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0;
    int rc = 0;
    fit_record *r = malloc(sizeof *r);
    if (!r) {
        fclose(in);
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "%s: out of memory", path);
        return -1;
    }
    while (rc == 0 && getline(&line, &cap, in) > 0) {
        lineno++;
        if (strspn(line, " \t\r\n") == strlen(line))
            continue;
        const char *why = "not a record of brdffit fit --json (material, model, status)";
        rf_fit f;
        int got = fr_read_json(line, r, FR_NEED_FIT) == 0
                      ? take_record(r, material, models, nmodels, scale, &f, &why)
                      : -1;
        if (got < 0) {
            err->status = BRDFFIT_E_FILE_READ;
            snprintf(err->message, sizeof err->message, "%s: line %ld: %s", path, lineno, why);
            rc = -1;
        } else if (got > 0) {
            keep(fits, nfits, &f);
        }
    }
    free(r);
    free(line);
    fclose(in);
    return rc;
}

static int read_tsv(const char *path, const char *material, const brdffit_model *models,
                    int nmodels, const mf_scale *sc, rf_fit *fits, int *nfits, brdffit_error *err)
{
    pub_table t;
    if (pub_read(path, &t, err) != 0)
        return -1;
    char why[BRDFFIT_MESSAGE_MAX];
    if (pub_scale_mismatch(&t, sc->scale, why, sizeof why)) {
        if (!sc->allow_mismatch) {
            err->status = BRDFFIT_E_INVALID_ARGUMENT;
            snprintf(err->message, sizeof err->message, "%.1500s; %s", why, pub_scale_advice(&t));
            pub_free(&t);
            return -1;
        }
        cli_error("warning: --fits %s: %s", why, PUB_SCALE_NOTE);
    }
    for (int k = 0; k < nmodels; k++) {
        const pub_row *row = pub_find(&t, material, models[k]);
        if (!row)
            continue;
        rf_fit f;
        memset(&f, 0, sizeof f);
        f.model = models[k];
        f.params = row->params;
        f.error = NAN; /* a TSV of parameters holds no Error of this table: mf_score */
        keep(fits, nfits, &f);
    }
    pub_free(&t);
    return 0;
}

int mf_read(const char *path, const char *material, const brdffit_model *models, int nmodels,
            const mf_scale *sc, rf_fit *fits, int *nfits, brdffit_error *err)
{
    *nfits = 0;
    int rc = ends_with(path, ".tsv")
                 ? read_tsv(path, material, models, nmodels, sc, fits, nfits, err)
                 : read_jsonl(path, material, models, nmodels, sc->scale, fits, nfits, err);
    if (rc == 0 && *nfits == 0) {
        err->status = BRDFFIT_E_NO_SAMPLES;
        snprintf(err->message, sizeof err->message,
                 "%s: no successful fit of material '%s' in the models asked", path, material);
        return -1;
    }
    for (int k = 0; rc == 0 && k < *nfits; k++)
        if (brdffit_params_check(fits[k].model, &fits[k].params, err) != BRDFFIT_OK) {
            char why[BRDFFIT_MESSAGE_MAX];
            snprintf(why, sizeof why, "%s", err->message);
            snprintf(err->message, sizeof err->message, "%.500s: %.1500s", path, why);
            rc = -1;
        }
    return rc;
}

int mf_score(const brdffit_table *table, const brdffit_sample_options *sample,
             const brdffit_context_options *copt, rf_fit *fits, int nfits, brdffit_error *err)
{
    int missing = 0;
    for (int k = 0; k < nfits; k++)
        missing += isnan(fits[k].error);
    if (!missing)
        return 0;
    brdffit_samples *s = NULL;
    brdffit_context *ctx = NULL;
    int rc = brdffit_samples_create(table, sample, &s, err) == BRDFFIT_OK &&
                     brdffit_context_create(copt, &ctx, err) == BRDFFIT_OK
                 ? 0 : -1;
    for (int k = 0; rc == 0 && k < nfits; k++) {
        if (!isnan(fits[k].error))
            continue;
        double e = NAN;
        if (brdffit_error_of(ctx, s, fits[k].model, &fits[k].params, &e, err) != BRDFFIT_OK) {
            char why[BRDFFIT_MESSAGE_MAX];
            snprintf(why, sizeof why, "%s", err->message);
            snprintf(err->message, sizeof err->message, "%s: the Error of the parameters: %.1800s",
                     brdffit_model_get(fits[k].model)->name, why);
            rc = -1;
        }
        fits[k].error = e;
    }
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
    return rc;
}

typedef struct mf_run {
    const brdffit_context_options *copt;
    brdffit_context *ctx;
    const char *material;
    rf_fit *fits;
    int *nfits;
    int failed;
} mf_run;

static int mf_context(void *user, brdffit_context **ctx, brdffit_error *err)
{
    mf_run *M = user;
    if (brdffit_context_create(M->copt, &M->ctx, err) != BRDFFIT_OK) {
        char msg[BRDFFIT_MESSAGE_MAX];
        snprintf(msg, sizeof msg, "%.200s: %.1800s", M->material, err->message);
        memcpy(err->message, msg, sizeof msg);
        return 1;
    }
    *ctx = M->ctx;
    return 0;
}

static int mf_before(void *user, int k)
{
    mf_run *M = user;
    (void)k;
    return *M->nfits < RF_MAX_FITS ? 1 : -1;
}

static void mf_record(void *user, const fit_record *r, const brdffit_fit_result *res)
{
    mf_run *M = user;
    if (r->kind == FR_FAILURE) {
        cli_error("%s", r->message);
        M->failed = -1;
        return;
    }
    if (!res) {
        cli_error("%s: %s fit failed: %s", M->material, r->model, r->message);
        M->failed = 1;
        return;
    }
    rf_fit *f = &M->fits[(*M->nfits)++];
    memset(f, 0, sizeof *f);
    f->model = res->model;
    f->params = res->params;
    f->error = res->error;
}

int mf_fit(const brdffit_table *table, const char *material, const brdffit_model *models,
           int nmodels, const brdffit_sample_options *sample, const brdffit_fit_options *fit,
           const brdffit_context_options *copt, rf_fit *fits, int *nfits)
{
    *nfits = 0;
    mf_run M = { copt, NULL, material, fits, nfits, 0 };
    fp_job job;
    memset(&job, 0, sizeof job);
    job.models = models;
    job.nmodels = nmodels;
    job.sample = sample;
    job.fit = fit;
    bj_settings_make(&job.settings, sample, fit);
    job.kernel_notes = 1;
    fp_source src;
    memset(&src, 0, sizeof src);
    src.name = material;
    src.table = (brdffit_table *)table; /* the caller's: never freed there */
    src.id.size = -1;
    fp_hooks h = { &M, mf_context, NULL, mf_before, mf_record, NULL };
    fp_fit_table(&job, &src, &h);
    brdffit_context_free(M.ctx);
    return M.failed;
}
