/* SPDX-License-Identifier: MIT */
/* map.c -- the fit's coordinate map: a model's lobe parameters <-> the lobe
 * coordinates u that LM moves, as the model registry maps each parameter
 * (brdffit_param_map): a bounded parameter is v = lo + (hi-lo)(1+sin u)/2
 * (lo, hi and v in log units for LOG); a DIRECTION pair (Lafortune's Cxy,
 * Cz) is one angle phi, (a, b) = (cos phi / sqrt 2, sin phi).  Also where
 * a point stands in each coordinate's range: its bounds, its place, and when
 * two points are one.  Every stage of the fit reads these and they take no
 * pass, so they stand apart (docs/fitting.md, "Parameter maps"). */
#define _DEFAULT_SOURCE /* M_SQRT2, M_SQRT1_2 */
#include "fit_internal.h"

#include "refine_select.h"

#include <math.h>
#include <string.h>

_Static_assert(2 * NX_MAX <= BF_END_PLACES, "bf_coord_places fits a bf_run_end");

void bf_fitmap_init(fitmap *fm, brdffit_model model)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    memset(fm, 0, sizeof *fm);
    fm->model = model;
    fm->nl = bf_model_ncoords(model);
    for (int j = 0; j < fm->nl; j++) {
        int k = bf_model_coord_param(model, j);
        const brdffit_param_info *pi = &mi->params[k];
        fm->param[j] = k;
        fm->kind[j] = pi->map;
        fm->lo[j] = pi->map == BRDFFIT_MAP_LOG ? log(pi->lower) : pi->lower;
        fm->hi[j] = pi->map == BRDFFIT_MAP_LOG ? log(pi->upper) : pi->upper;
    }
}

static double map_fwd(const fitmap *fm, int j, double u)
{
    double v = fm->lo[j] + (fm->hi[j] - fm->lo[j]) * 0.5 * (1.0 + sin(u));
    return fm->kind[j] == BRDFFIT_MAP_LOG ? exp(v) : v;
}

static double map_inv(const fitmap *fm, int j, double v)
{
    if (fm->kind[j] == BRDFFIT_MAP_LOG)
        v = log(v);
    double t = 2.0 * (v - fm->lo[j]) / (fm->hi[j] - fm->lo[j]) - 1.0;
    return asin(fmin(fmax(t, -1.0), 1.0));
}

/* p gets BF_MAX_NP entries for a model with a lobe (the pass's points),
 * BRDFFIT_MAX_LOBE_PARAMS for the others; a held parameter (one whose bounds
 * are equal: bf_model_coord_param) its value. */
void bf_coords_to_params(const fitmap *fm, const double *u, double *p)
{
    double start[BRDFFIT_MAX_LOBE_PARAMS];
    bf_model_start_params(fm->model, start, BRDFFIT_MAX_LOBE_PARAMS);
    memcpy(p, start, (bf_model_has_lobe(fm->model) ? BF_MAX_NP : BRDFFIT_MAX_LOBE_PARAMS) * sizeof *p);
    for (int j = 0; j < fm->nl; j++) {
        int k = fm->param[j];
        if (fm->kind[j] == BRDFFIT_MAP_DIRECTION) {
            p[k] = cos(u[j]) * M_SQRT1_2;
            p[k + 1] = sin(u[j]);
        } else {
            p[k] = map_fwd(fm, j, u[j]);
        }
    }
}

void bf_params_to_coords(const fitmap *fm, const double *p, double *u)
{
    for (int j = 0; j < fm->nl; j++) {
        int k = fm->param[j];
        if (fm->kind[j] == BRDFFIT_MAP_DIRECTION)
            u[j] = atan2(p[k + 1], p[k] * M_SQRT2);
        else
            u[j] = map_inv(fm, j, p[k]);
    }
}

/* Where lobe coordinate j stands in its range: 0 at the lower bound, 1 at
 * the upper; -1 for a direction (no bounds). */
double bf_coord_position(const fitmap *fm, int j, double u)
{
    return fm->kind[j] == BRDFFIT_MAP_DIRECTION ? -1.0 : 0.5 * (1.0 + sin(u));
}

/* A coordinate within this of an end of its range is on its bound. */
#define ON_BOUND 1e-6

/* Two points whose lobe coordinates lie within SAME_POINT of each other in
 * their place in the range (directions: in cos and sin) are one point
 * (bf_same_coords; with r^T r within SAME_RR, one minimum: problem.c,
 * same_end). */
#define SAME_POINT 1e-4

/* The places of lobe coordinates x, two a coordinate (see BF_END_PLACES):
 * its place in its range and 0, or a direction's cosine and sine. */
void bf_coord_places(const fitmap *fm, const double *x, double *place)
{
    for (int j = 0; j < fm->nl; j++) {
        double t = bf_coord_position(fm, j, x[j]);
        place[2 * j] = t < 0.0 ? cos(x[j]) : t;
        place[2 * j + 1] = t < 0.0 ? sin(x[j]) : 0.0;
    }
}

int bf_same_coords(const fitmap *fm, const double *xa, const double *xb)
{
    double pa[BF_END_PLACES], pb[BF_END_PLACES];
    bf_coord_places(fm, xa, pa);
    bf_coord_places(fm, xb, pb);
    return bf_places_within(pa, pb, 2 * fm->nl, SAME_POINT);
}

unsigned bf_on_bounds(const fitmap *fm, const double *x)
{
    unsigned mask = 0;
    for (int j = 0; j < fm->nl; j++) {
        double t = bf_coord_position(fm, j, x[j]);
        if (t >= 0.0 && (t < ON_BOUND || t > 1.0 - ON_BOUND))
            mask |= 1u << j;
    }
    return mask;
}
