/* SPDX-License-Identifier: MIT */
/* grid.c -- the MERL grid: bin index, bin <-> direction mapping (both ways)
 * and the bins' solid-angle weights. */
#define _DEFAULT_SOURCE /* M_PI */
#include "grid.h"
#include "internal.h"

#include <float.h>
#include <math.h>

const char bf_channel_name[3] = { 'R', 'G', 'B' };

size_t brdffit_bin_index(int i, int j, int k)
{
    return (size_t)k + (size_t)BF_NPD * ((size_t)j + (size_t)BF_NTD * (size_t)i);
}

void bf_bin_ijk(size_t b, int *i, int *j, int *k)
{
    *k = (int)(b % BF_NPD);
    *j = (int)((b / BF_NPD) % BF_NTD);
    *i = (int)(b / ((size_t)BF_NPD * BF_NTD));
}

/* The directions from the sines and cosines of theta_h, theta_d and phi_d:
 * the same arithmetic, in the same order, as ../shared/tools/merl-from-nbrdf.c,
 * so that directions (and the horizon test) agree bit for bit. */
static void dirs_from(double sth, double cth, double std, double ctd, double spd, double cpd,
                      double wi[3], double wo[3])
{
    double d[3] = { std * cpd, std * spd, ctd };
    double h[3] = { sth, 0.0, cth };
    wi[0] = d[0] * cth + d[2] * sth;
    wi[1] = d[1];
    wi[2] = -d[0] * sth + d[2] * cth;
    double hd = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
    for (int c = 0; c < 3; c++)
        wo[c] = 2 * hd * h[c] - wi[c];
}

static double theta_h(int i)
{
    double u = (double)i / BF_NTH;
    return u * u * M_PI / 2;
}

static double theta_d(int j)
{
    return (double)j / BF_NTD * M_PI / 2;
}

static double phi_d(int k)
{
    return (double)k / BF_NPD * M_PI;
}

void bf_bin_dirs(int i, int j, int k, double wi[3], double wo[3])
{
    double th = theta_h(i), td = theta_d(j), pd = phi_d(k);
    dirs_from(sin(th), cos(th), sin(td), cos(td), sin(pd), cos(pd), wi, wo);
}

void bf_grid_trig_init(bf_grid_trig *g)
{
    for (int i = 0; i < BF_NTH; i++) {
        g->sth[i] = sin(theta_h(i));
        g->cth[i] = cos(theta_h(i));
        for (int j = 0; j < BF_NTD; j++)
            g->w[i][j] = brdffit_bin_weight(i, j);
    }
    for (int j = 0; j < BF_NTD; j++) {
        g->std[j] = sin(theta_d(j));
        g->ctd[j] = cos(theta_d(j));
    }
    for (int k = 0; k < BF_NPD; k++) {
        g->spd[k] = sin(phi_d(k));
        g->cpd[k] = cos(phi_d(k));
    }
}

void bf_bin_dirs_trig(const bf_grid_trig *g, int i, int j, int k, double wi[3], double wo[3])
{
    dirs_from(g->sth[i], g->cth[i], g->std[j], g->ctd[j], g->spd[k], g->cpd[k], wi, wo);
}

brdffit_status brdffit_bin_directions(int i, int j, int k, double wi[3], double wo[3],
                                      brdffit_error *err)
{
    if (!wi || !wo)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_bin_directions: %s is NULL",
                       !wi ? "wi" : "wo");
    const int idx[3] = { i, j, k }, dim[3] = { BF_NTH, BF_NTD, BF_NPD };
    static const char *const name[3] = { "i (theta_h)", "j (theta_d)", "k (phi_d)" };
    for (int a = 0; a < 3; a++)
        if (idx[a] < 0 || idx[a] >= dim[a])
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "brdffit_bin_directions: bin (%d, %d, %d): %s = %d outside 0..%d", i,
                           j, k, name[a], idx[a], dim[a] - 1);
    bf_bin_dirs(i, j, k, wi, wo);
    bf_ok(err);
    return BRDFFIT_OK;
}

double brdffit_bin_weight(int i, int j)
{
    if (i < 0 || i >= BF_NTH || j < 0 || j >= BF_NTD)
        return 0.0;
    double ul = (double)i / BF_NTH, uh = (double)(i + 1) / BF_NTH;
    double thl = ul * ul * M_PI / 2, thh = uh * uh * M_PI / 2;
    double tdl = (double)j * M_PI / 180, tdh = (double)(j + 1) * M_PI / 180;
    double sl = sin(tdl), sh = sin(tdh);
    return (cos(thl) - cos(thh)) * (sh * sh - sl * sl) / 2;
}

/* MERL's std_coords_to_half_diff_coords, written with the components of H
 * instead of acos and trigonometric round trips (better conditioned near
 * theta = 0), as continuous grid coordinates: uh = sqrt(theta_h/(pi/2))*90,
 * ud = theta_d/(pi/2)*90, up = phi_d/pi*180 with phi_d folded into [0, pi].
 * Returns 0 for a non-finite or zero direction or for wo = -wi. */
int bf_grid_coords(const double wi_in[3], const double wo_in[3], double u[3])
{
    double a[3], b[3];
    double la = sqrt(wi_in[0] * wi_in[0] + wi_in[1] * wi_in[1] + wi_in[2] * wi_in[2]);
    double lb = sqrt(wo_in[0] * wo_in[0] + wo_in[1] * wo_in[1] + wo_in[2] * wo_in[2]);
    if (!isfinite(la) || !isfinite(lb) || !(la > 0) || !(lb > 0))
        return 0;
    /* Vectors already unit up to rounding are used as given: dividing by a
     * length of 1 +- 1 ulp would perturb them, and at small theta_h phi_h
     * (hence phi_d) is sensitive to the slightest asymmetry of wi and wo. */
    if (fabs(la - 1) <= 4 * DBL_EPSILON)
        la = 1;
    if (fabs(lb - 1) <= 4 * DBL_EPSILON)
        lb = 1;
    for (int c = 0; c < 3; c++) {
        a[c] = wi_in[c] / la;
        b[c] = wo_in[c] / lb;
    }
    double h[3] = { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
    double hxy = hypot(h[0], h[1]);
    double hl = hypot(hxy, h[2]);
    if (!(hl > 1e-300))
        return 0;
    double theta_h = atan2(hxy, h[2]);
    double cp = 1.0, sp = 0.0; /* cos, sin phi_h */
    if (hxy > 0) {
        cp = h[0] / hxy;
        sp = h[1] / hxy;
    }
    double ct = h[2] / hl, st = hxy / hl; /* cos, sin theta_h */
    /* rotate wi by -phi_h about z, then by -theta_h about y */
    double t0 = a[0] * cp + a[1] * sp, t1 = -a[0] * sp + a[1] * cp, t2 = a[2];
    double d0 = t0 * ct - t2 * st, d1 = t1, d2 = t0 * st + t2 * ct;
    double theta_d = atan2(hypot(d0, d1), d2);
    double phi_d = atan2(d1, d0);
    if (phi_d < 0)
        phi_d += M_PI;
    u[0] = sqrt(theta_h / (M_PI / 2)) * BF_NTH;
    u[1] = theta_d / (M_PI / 2) * BF_NTD;
    u[2] = phi_d / M_PI * BF_NPD;
    return 1;
}
