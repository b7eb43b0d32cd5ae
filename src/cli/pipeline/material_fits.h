/* SPDX-License-Identifier: MIT */
/* material_fits.h -- the fitted models `render` and `plot` draw for a table
 * (material_fits.c). */
#ifndef BRDFFIT_MATERIAL_FITS_H
#define BRDFFIT_MATERIAL_FITS_H

#include "cli.h"
#include "render_files.h"

/* The fits of material in the nmodels models from path: the JSON Lines of
 * `brdffit fit --json` (records with status "ok"; a record fitted with
 * another scale than scale is refused), or, for a path ending in ".tsv", the
 * ngan2005-fits.tsv format (no Error).  A later fit of a model replaces an
 * earlier one.  0, or -1 with err (the line and what is wrong; no fit of
 * the material at all is an error too). */
int mf_read(const char *path, const char *material, const brdffit_model *models, int nmodels,
            brdffit_scale scale, rf_fit *fits, int *nfits, brdffit_error *err);

/* Fit the models to the table now (one context).  Failures are printed and
 * the other models still fitted.  0 all fitted, 1 some failed, -1 nothing
 * could be fitted (no samples, no context). */
int mf_fit(const brdffit_table *table, const char *material, const brdffit_model *models,
           int nmodels, const brdffit_sample_options *sample, const brdffit_fit_options *fit,
           const brdffit_context_options *copt, rf_fit *fits, int *nfits);

#endif
