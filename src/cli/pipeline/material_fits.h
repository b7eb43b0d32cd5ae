/* SPDX-License-Identifier: MIT */
/* material_fits.h -- the fitted models `render` and `plot` draw for a table
 * (material_fits.c). */
#ifndef BRDFFIT_MATERIAL_FITS_H
#define BRDFFIT_MATERIAL_FITS_H

#include "cli.h"
#include "render_files.h"

/* The scale the tables are read with, and whether a TSV of fits stating
 * another ("# scale: S") is used anyway (--allow-scale-mismatch). */
typedef struct mf_scale {
    brdffit_scale scale;
    int allow_mismatch;
} mf_scale;

/* The fits of material in the nmodels models from path: the JSON Lines of
 * `brdffit fit --json` (records with status "ok"; a record fitted with
 * another scale than sc->scale is refused), or, for a path ending in ".tsv",
 * the ngan2005-fits.tsv format (Error NAN: mf_score; a file stating another
 * scale is refused unless sc->allow_mismatch, then said on stderr).  A later
 * fit of a model replaces an earlier one.  0, or -1 with err (the line and
 * what is wrong; no fit of the material at all is an error too). */
int mf_read(const char *path, const char *material, const brdffit_model *models, int nmodels,
            const mf_scale *sc, rf_fit *fits, int *nfits, brdffit_error *err);

/* The Error on the table (sampled with sample, as `brdffit score` does) of
 * each fit whose Error is NAN.  0, or -1 with err. */
int mf_score(const brdffit_table *table, const brdffit_sample_options *sample,
             const brdffit_context_options *copt, rf_fit *fits, int nfits, brdffit_error *err);

/* Fit the models to the table now (one context).  Failures are printed and
 * the other models still fitted.  0 all fitted, 1 some failed, -1 nothing
 * could be fitted (no samples, no context). */
int mf_fit(const brdffit_table *table, const char *material, const brdffit_model *models,
           int nmodels, const brdffit_sample_options *sample, const brdffit_fit_options *fit,
           const brdffit_context_options *copt, rf_fit *fits, int *nfits);

#endif
