/* SPDX-License-Identifier: MIT */
/* material_fits.c -- the fitted models `render` and `plot` draw for a table:
 * read from a file of fits (the JSON Lines of `brdffit fit --json`, or a TSV
 * of the ngan2005-fits.tsv format), or fitted now. */
#define _POSIX_C_SOURCE 200809L
#include "material_fits.h"
#include "batch.h"

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

/* One JSON Lines record of `fit --json` into f when it is an "ok" fit of the
 * material in a wanted model.  1 taken, 0 not for us, -1 malformed (why). */
static int take_record(const jr_object *o, const char *material, const brdffit_model *models,
                       int nmodels, brdffit_scale scale, rf_fit *f, const char **why)
{
    const jr_member *mat = jr_get(o, "material"), *mod = jr_get(o, "model");
    const jr_member *st = jr_get(o, "status"), *met = jr_get(o, "metric");
    *why = "not a record of brdffit fit --json (material, model, status)";
    if (!mat || mat->type != JR_STRING || !mod || !st || st->type != JR_STRING)
        return -1;
    if (strcmp(mat->str, material) != 0 || strcmp(st->str, "ok") != 0 || mod->type != JR_STRING)
        return 0;
    brdffit_model m;
    *why = "unknown model";
    if (brdffit_model_from_name(mod->str, &m, NULL) != BRDFFIT_OK)
        return -1;
    if (!wanted(models, nmodels, m))
        return 0;
    const jr_member *sc = met ? jr_get_in(o, met, "scale") : NULL;
    brdffit_scale rs;
    if (sc && sc->type == JR_STRING && brdffit_scale_from_name(sc->str, &rs, NULL) == BRDFFIT_OK &&
        rs != scale) {
        *why = scale == BRDFFIT_SCALE_FLAT ? "fitted with --scale standard (pass it)"
                                           : "fitted with --scale flat (pass it)";
        return -1;
    }
    const jr_member *d = jr_get(o, "d"), *s = jr_get(o, "s"), *p = jr_get(o, "p");
    const jr_member *e = jr_get(o, "error"), *lam = jr_get(o, "lambda_um");
    const brdffit_model_info *mi = brdffit_model_get(m);
    *why = "d, s (3 numbers) and p (the model's parameters) expected";
    if (!d || !s || !p || d->type != JR_ARRAY || s->type != JR_ARRAY || p->type != JR_ARRAY ||
        d->narr != 3 || s->narr != 3 || p->narr != mi->nparams)
        return -1;
    memset(f, 0, sizeof *f);
    f->model = m;
    for (int c = 0; c < 3; c++) {
        f->params.d[c] = d->arr[c];
        f->params.s[c] = s->arr[c];
        if (lam && lam->type == JR_ARRAY && lam->narr == 3)
            f->params.lambda_um[c] = lam->arr[c];
    }
    for (int k = 0; k < mi->nparams; k++)
        f->params.p[k] = p->arr[k];
    f->error = e && e->type == JR_NUMBER ? e->num : NAN;
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
    FILE *in = fopen(path, "r");
    if (!in) {
        err->status = BRDFFIT_E_FILE_OPEN;
        snprintf(err->message, sizeof err->message, "%s: cannot open", path);
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0;
    int rc = 0;
    while (rc == 0 && getline(&line, &cap, in) > 0) {
        lineno++;
        if (strspn(line, " \t\r\n") == strlen(line))
            continue;
        jr_object o;
        const char *why = "not a JSON object";
        rf_fit f;
        int got = jr_parse(line, &o) == 0 ? take_record(&o, material, models, nmodels, scale,
                                                        &f, &why)
                                          : -1;
        if (got < 0) {
            err->status = BRDFFIT_E_FILE_READ;
            snprintf(err->message, sizeof err->message, "%s: line %ld: %s", path, lineno, why);
            rc = -1;
        } else if (got > 0) {
            keep(fits, nfits, &f);
        }
        jr_free(&o);
    }
    free(line);
    fclose(in);
    return rc;
}

static int read_tsv(const char *path, const char *material, const brdffit_model *models,
                    int nmodels, rf_fit *fits, int *nfits, brdffit_error *err)
{
    pub_table t;
    if (pub_read(path, &t, err) != 0)
        return -1;
    for (int k = 0; k < nmodels; k++) {
        const pub_row *row = pub_find(&t, material, models[k]);
        if (!row)
            continue;
        rf_fit f;
        memset(&f, 0, sizeof f);
        f.model = models[k];
        f.params = row->params;
        f.error = NAN; /* a TSV of parameters holds no Error of this table */
        keep(fits, nfits, &f);
    }
    pub_free(&t);
    return 0;
}

int mf_read(const char *path, const char *material, const brdffit_model *models, int nmodels,
            brdffit_scale scale, rf_fit *fits, int *nfits, brdffit_error *err)
{
    *nfits = 0;
    int rc = ends_with(path, ".tsv")
                 ? read_tsv(path, material, models, nmodels, fits, nfits, err)
                 : read_jsonl(path, material, models, nmodels, scale, fits, nfits, err);
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

int mf_fit(const brdffit_table *table, const char *material, const brdffit_model *models,
           int nmodels, const brdffit_sample_options *sample, const brdffit_fit_options *fit,
           const brdffit_context_options *copt, rf_fit *fits, int *nfits)
{
    brdffit_error err;
    brdffit_samples *s = NULL;
    brdffit_context *ctx = NULL;
    int failed = 0;
    *nfits = 0;
    if (brdffit_samples_create(table, sample, &s, &err) != BRDFFIT_OK ||
        brdffit_context_create(copt, &ctx, &err) != BRDFFIT_OK) {
        cli_error("%s: %s", material, err.message);
        brdffit_samples_free(s);
        return -1;
    }
    for (int k = 0; k < nmodels && *nfits < RF_MAX_FITS; k++) {
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        int note = kernel_note_begin(stderr, ctx, models[k]);
        brdffit_status st = brdffit_fit(ctx, s, models[k], fit, &r, &err);
        kernel_note_end(stderr, note, ctx, models[k]);
        if (st != BRDFFIT_OK) {
            cli_error("%s: %s fit failed: %s", material, brdffit_model_get(models[k])->name,
                      err.message);
            failed = 1;
            continue;
        }
        rf_fit *f = &fits[(*nfits)++];
        memset(f, 0, sizeof *f);
        f->model = models[k];
        f->params = r.params;
        f->error = r.error;
    }
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
    return failed ? 1 : 0;
}
