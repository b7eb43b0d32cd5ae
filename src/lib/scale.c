/* SPDX-License-Identifier: MIT */
/* scale.c -- the channel scales: stored value x factor = BRDF value (1/sr). */
#include "internal.h"

#include <string.h>

int bf_scale_known(brdffit_scale scale)
{
    return scale == BRDFFIT_SCALE_STANDARD || scale == BRDFFIT_SCALE_FLAT;
}

void bf_scale_factors(brdffit_scale scale, double factors[3])
{
    /* Anything but FLAT gives the standard factors; public callers validate. */
    if (scale == BRDFFIT_SCALE_FLAT) {
        factors[0] = factors[1] = factors[2] = 1.0 / 1500.0;
    } else {
        factors[0] = 1.0 / 1500.0;
        factors[1] = 1.15 / 1500.0;
        factors[2] = 1.66 / 1500.0;
    }
}

brdffit_status brdffit_scale_factors(brdffit_scale scale, double factors[3], brdffit_error *err)
{
    if (!factors)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_scale_factors: factors is NULL");
    if (!bf_scale_known(scale))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "brdffit_scale_factors: unknown scale %d (0 standard, 1 flat)", (int)scale);
    bf_scale_factors(scale, factors);
    bf_ok(err);
    return BRDFFIT_OK;
}

const char *brdffit_scale_name(brdffit_scale scale)
{
    switch (scale) {
    case BRDFFIT_SCALE_STANDARD: return "standard";
    case BRDFFIT_SCALE_FLAT: return "flat";
    }
    return "unknown";
}

brdffit_status brdffit_scale_from_name(const char *name, brdffit_scale *out, brdffit_error *err)
{
    if (!name || !out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_scale_from_name: %s is NULL",
                       !name ? "name" : "out");
    for (int s = BRDFFIT_SCALE_STANDARD; s <= BRDFFIT_SCALE_FLAT; s++)
        if (strcmp(name, brdffit_scale_name((brdffit_scale)s)) == 0) {
            *out = (brdffit_scale)s;
            bf_ok(err);
            return BRDFFIT_OK;
        }
    return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                   "no scale named '%.200s' (scales: standard, flat)", name);
}

