/* SPDX-License-Identifier: MIT */
/* table_fill.c -- brdffit_table_fill_model: a table made from a model. */
#include "internal.h"
#include "grid.h"

brdffit_status brdffit_table_fill_model(brdffit_table *table, brdffit_model model,
                                        const brdffit_params *params, brdffit_scale scale,
                                        brdffit_error *err)
{
    if (!table || !params)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_fill_model: %s is NULL",
                       !table ? "table" : "params");
    if (!bf_scale_known(scale))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "brdffit_table_fill_model: unknown scale %d", (int)scale);
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st != BRDFFIT_OK)
        return st;
    double f[3];
    bf_scale_factors(scale, f);
    double wi[3 * BF_NPD], wo[3 * BF_NPD], rgb[3 * BF_NPD];
    for (int i = 0; i < BF_NTH; i++) {
        for (int j = 0; j < BF_NTD; j++) {
            for (int k = 0; k < BF_NPD; k++)
                bf_bin_dirs(i, j, k, wi + 3 * k, wo + 3 * k);
            st = brdffit_eval_batch(model, params, BF_NPD, wi, wo, rgb, NULL);
            if (st != BRDFFIT_OK)
                return bf_fail(err, st, "brdffit_table_fill_model: evaluating bin row %d,%d: %s",
                               i, j, brdffit_strerror(st));
            size_t base = brdffit_bin_index(i, j, 0);
            for (int k = 0; k < BF_NPD; k++) {
                int above = wi[3 * k + 2] > 0 && wo[3 * k + 2] > 0;
                for (int c = 0; c < 3; c++)
                    table->v[c * BF_NBINS + base + (size_t)k] = above ? rgb[3 * k + c] / f[c] : -1.0;
            }
        }
    }
    bf_ok(err);
    return BRDFFIT_OK;
}

