/* SPDX-License-Identifier: MIT */
/* lookup_batch.c -- brdffit_table_lookup over n direction pairs in one call. */
#include "internal.h"

brdffit_status brdffit_table_lookup_batch(const brdffit_table *table, size_t n,
                                          const double *wi, const double *wo,
                                          brdffit_scale scale, brdffit_interp interp,
                                          double *rgb, brdffit_error *err)
{
    static const char fn[] = "brdffit_table_lookup_batch";
    brdffit_status st = bf_lookup_check(fn, table, scale, interp, err);
    if (st != BRDFFIT_OK)
        return st;
    if (n > 0 && (!wi || !wo || !rgb))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: %s is NULL", fn,
                       !wi ? "wi" : !wo ? "wo" : "rgb");
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < n; i++) {
        double *out = rgb + 3 * i;
        if (brdffit_table_lookup(table, wi + 3 * i, wo + 3 * i, scale, interp, out, NULL) !=
            BRDFFIT_OK) {
            out[0] = out[1] = out[2] = -1.0;
            if (bad++ == 0)
                first = i;
        }
    }
    if (bad == 0) {
        bf_ok(err);
        return BRDFFIT_OK;
    }
    return bf_fail_pairs(err, fn, first, n, bad, "-1", wi, wo);
}
