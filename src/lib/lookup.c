/* SPDX-License-Identifier: MIT */
/* lookup.c -- brdffit_table_lookup: a table's value at a direction pair,
 * nearest bin or trilinear in the grid coordinates. */
#include "internal.h"
#include "grid.h"

#include <math.h>

/* Lookup snaps grid coordinates this close to an integer onto it, so that
 * the directions of a bin map back to exactly that bin despite rounding. */
#define GRID_EPS 1e-9

static int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* floor for an index, robust to values that should be exact integers */
static int index_of(double u, int n)
{
    double f = floor(u + GRID_EPS);
    if (!(f >= 0))
        return 0;
    if (f > n - 1)
        return n - 1;
    return (int)f;
}

static double snap(double u)
{
    double r = nearbyint(u);
    return fabs(u - r) < GRID_EPS ? r : u;
}

brdffit_status bf_lookup_check(const char *fn, const brdffit_table *table, brdffit_scale scale,
                               brdffit_interp interp, brdffit_error *err)
{
    if (!table)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: table is NULL", fn);
    if (!bf_scale_known(scale))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: unknown scale %d (0 standard, 1 flat)",
                       fn, (int)scale);
    if (interp != BRDFFIT_INTERP_NEAREST && interp != BRDFFIT_INTERP_TRILINEAR)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s: unknown interp %d (0 nearest, 1 trilinear)", fn, (int)interp);
    return BRDFFIT_OK;
}

brdffit_status brdffit_table_lookup(const brdffit_table *table, const double wi[3],
                                    const double wo[3], brdffit_scale scale,
                                    brdffit_interp interp, double rgb[3], brdffit_error *err)
{
    static const char fn[] = "brdffit_table_lookup";
    brdffit_status st = bf_lookup_check(fn, table, scale, interp, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!wi || !wo || !rgb)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: %s is NULL", fn,
                       !wi ? "wi" : !wo ? "wo" : "rgb");
    double u[3];
    if (!bf_grid_coords(wi, wo, u))
        return bf_fail_pair(err, fn, wi, wo);
    bf_ok(err);
    double f[3];
    bf_scale_factors(scale, f);

    if (interp == BRDFFIT_INTERP_NEAREST) {
        size_t b = brdffit_bin_index(index_of(u[0], BF_NTH), index_of(u[1], BF_NTD),
                                     index_of(u[2], BF_NPD));
        for (int c = 0; c < 3; c++) {
            double v = table->v[c * BF_NBINS + b];
            rgb[c] = v < 0 ? -1.0 : v * f[c];
        }
        return BRDFFIT_OK;
    }

    /* trilinear: clamped in theta_h and theta_d, periodic in phi_d */
    double uh = fmin(fmax(snap(u[0]), 0.0), BF_NTH - 1);
    double ud = fmin(fmax(snap(u[1]), 0.0), BF_NTD - 1);
    double up = snap(u[2]);
    int ih = (int)floor(uh), id = (int)floor(ud), ip = (int)floor(up);
    double fh = uh - ih, fd = ud - id, fp = up - ip;
    int ih1 = clampi(ih + 1, 0, BF_NTH - 1), id1 = clampi(id + 1, 0, BF_NTD - 1);
    ip = ((ip % BF_NPD) + BF_NPD) % BF_NPD;
    int ip1 = (ip + 1) % BF_NPD;
    const int hh[2] = { ih, ih1 }, dd[2] = { id, id1 }, pp[2] = { ip, ip1 };
    const double wh[2] = { 1 - fh, fh }, wd[2] = { 1 - fd, fd }, wp[2] = { 1 - fp, fp };
    double sum[3] = { 0, 0, 0 };
    int masked[3] = { 0, 0, 0 };
    for (int a = 0; a < 2; a++) {
        for (int b = 0; b < 2; b++) {
            for (int c = 0; c < 2; c++) {
                double w = wh[a] * wd[b] * wp[c];
                if (w == 0)
                    continue;
                size_t bin = brdffit_bin_index(hh[a], dd[b], pp[c]);
                for (int ch = 0; ch < 3; ch++) {
                    double v = table->v[ch * BF_NBINS + bin];
                    if (v < 0)
                        masked[ch] = 1;
                    else
                        sum[ch] += w * v;
                }
            }
        }
    }
    for (int c = 0; c < 3; c++)
        rgb[c] = masked[c] ? -1.0 : sum[c] * f[c];
    return BRDFFIT_OK;
}
