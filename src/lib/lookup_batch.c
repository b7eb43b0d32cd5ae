/* SPDX-License-Identifier: MIT */
/* lookup_batch.c -- brdffit_table_lookup over n direction pairs in one call. */
#include "brdffit.h"

brdffit_status brdffit_table_lookup_batch(const brdffit_table *table, size_t n,
                                          const double *wi, const double *wo,
                                          brdffit_scale scale, brdffit_interp interp,
                                          double *rgb)
{
    if (!table || (n > 0 && (!wi || !wo || !rgb)))
        return BRDFFIT_E_INVALID_ARGUMENT;
    const double centre[3] = { 0, 0, 1 };
    double probe[3];
    /* the table, scale and interpolation are checked once, on a valid pair */
    brdffit_status st = brdffit_table_lookup(table, centre, centre, scale, interp, probe);
    if (st != BRDFFIT_OK)
        return st;
    for (size_t i = 0; i < n; i++) {
        double *out = rgb + 3 * i;
        if (brdffit_table_lookup(table, wi + 3 * i, wo + 3 * i, scale, interp, out) != BRDFFIT_OK) {
            out[0] = out[1] = out[2] = -1.0;
            st = BRDFFIT_E_INVALID_ARGUMENT;
        }
    }
    return st;
}
