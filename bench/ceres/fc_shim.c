/* SPDX-License-Identifier: MIT */
/* fc_shim.c -- the Ceres fitter's residuals, Jacobian and start, from the
 * library's samples and the kernel headers' lobes (see fc_shim.h).  No model
 * formula is written here: K and its partials in p are bf_lobe / bf_lobe_vdk
 * (kernels/bf_lobe.h, bf_lobe_pass.h, compiled as C with BF_REAL = double), f = d / pi + s K
 * is the library's form of every model, and d p / d theta is the registry's
 * parameter map. */
#define _DEFAULT_SOURCE /* M_PI, M_SQRT1_2, M_SQRT2 */
#include "fc_shim.h"

#include "linear.h"
#include "pass.h"
#include "registry.h"
#include "samples.h"
#include "subsets.h"

#include "bf_lobe_pass.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int fc_has_partials(brdffit_model model)
{
    return brdffit_model_get(model) && bf_lobe_fd_kind((int)model) == BF_FD_KIND_PARTIALS;
}

/* The registry's map of lobe coordinate j and its first parameter. */
static brdffit_param_map coord_map(brdffit_model model, int j, int *k)
{
    *k = bf_model_coord_param(model, j);
    return brdffit_model_param(model, *k)->map;
}

int fc_coords(brdffit_model model, double lo[3], double hi[3], int bounded[3])
{
    int nc = bf_model_ncoords(model);
    for (int j = 0; j < nc; j++) {
        int k;
        brdffit_param_map map = coord_map(model, j, &k);
        const brdffit_param_info *pi = brdffit_model_param(model, k);
        bounded[j] = map != BRDFFIT_MAP_DIRECTION;
        lo[j] = map == BRDFFIT_MAP_LOG ? log(pi->lower) : pi->lower;
        hi[j] = map == BRDFFIT_MAP_LOG ? log(pi->upper) : pi->upper;
    }
    return nc;
}

void fc_params_of(brdffit_model model, const double *theta, double p[3])
{
    p[0] = p[1] = p[2] = 0.0;
    for (int j = 0; j < bf_model_ncoords(model); j++) {
        int k;
        switch (coord_map(model, j, &k)) {
        case BRDFFIT_MAP_LOG: p[k] = exp(theta[j]); break;
        case BRDFFIT_MAP_LINEAR: p[k] = theta[j]; break;
        case BRDFFIT_MAP_DIRECTION:
            p[k] = cos(theta[j]) * M_SQRT1_2;
            p[k + 1] = sin(theta[j]);
            break;
        }
    }
}

void fc_theta_of(brdffit_model model, const double p[3], double *theta)
{
    for (int j = 0; j < bf_model_ncoords(model); j++) {
        int k;
        switch (coord_map(model, j, &k)) {
        case BRDFFIT_MAP_LOG: theta[j] = log(p[k]); break;
        case BRDFFIT_MAP_LINEAR: theta[j] = p[k]; break;
        case BRDFFIT_MAP_DIRECTION: theta[j] = atan2(p[k + 1], p[k] * M_SQRT2); break;
        }
    }
}

/* d p_k / d theta_j into dp[j][k] (zero elsewhere). */
static void param_partials(brdffit_model model, const double *theta, const double p[3],
                           double dp[3][3])
{
    memset(dp, 0, 9 * sizeof(double));
    for (int j = 0; j < bf_model_ncoords(model); j++) {
        int k;
        switch (coord_map(model, j, &k)) {
        case BRDFFIT_MAP_LOG: dp[j][k] = p[k]; break;
        case BRDFFIT_MAP_LINEAR: dp[j][k] = 1.0; break;
        case BRDFFIT_MAP_DIRECTION:
            dp[j][k] = -sin(theta[j]) * M_SQRT1_2;
            dp[j][k + 1] = cos(theta[j]);
            break;
        }
    }
}

const brdffit_samples *fc_fitted_set(const brdffit_samples *s, int mirror)
{
    if (!mirror)
        return s;
    const brdffit_samples *m = NULL;
    brdffit_error err;
    if (bf_samples_mirror_kept(s, &m, &err) != BRDFFIT_OK) {
        fprintf(stderr, "bench-ceres: %s\n", err.message);
        return NULL;
    }
    return m;
}

size_t fc_count(const brdffit_samples *set)
{
    return set->n;
}

double fc_pair_see(const brdffit_samples *set)
{
    return set->pair_see[0] + set->pair_see[1] + set->pair_see[2];
}

void fc_residuals(const brdffit_samples *set, size_t i0, size_t n, brdffit_model model,
                  const double d[3], const double s[3], const double *theta, double *r,
                  double *jd, double *js, double *jt)
{
    const size_t npad = set->npad;
    const double *f = set->data;
    const int m = (int)model, nc = bf_model_ncoords(model);
    const double lam[3] = { 0.645, 0.526, 0.444 }; /* unused: no chromatic lobe here */
    double p[3], dp[3][3];
    fc_params_of(model, theta, p);
    param_partials(model, theta, p, dp);
    const double dpi[3] = { d[0] / M_PI, d[1] / M_PI, d[2] / M_PI };
    for (size_t q = 0; q < n; q++) {
        const size_t i = i0 + q;
        bf_geom g = { f[BF_F_IX * npad + i], f[BF_F_IY * npad + i], f[BF_F_IZ * npad + i],
                      f[BF_F_OX * npad + i], f[BF_F_OY * npad + i], f[BF_F_OZ * npad + i],
                      f[BF_F_NH * npad + i], f[BF_F_VH * npad + i] };
        const double a = sqrt(f[BF_F_A2 * npad + i]);
        double K, dK[3], dth[3] = { 0.0, 0.0, 0.0 };
        if (jd) {
            K = bf_lobe_vdk(m, &g, p, dK);
            for (int j = 0; j < nc; j++)
                dth[j] = -a * ((dK[0] * dp[j][0] + dK[1] * dp[j][1]) + dK[2] * dp[j][2]);
        } else {
            double Kc[3];
            bf_lobe(m, &g, p, lam, Kc);
            K = Kc[0];
        }
        for (int c = 0; c < 3; c++) {
            const size_t row = 3 * q + (size_t)c;
            r[row] = a * (f[(BF_F_R + c) * npad + i] - dpi[c] - s[c] * K);
            if (!jd)
                continue;
            double *rd = jd + 3 * row, *rs = js + 3 * row, *rt = jt + (size_t)nc * row;
            rd[0] = rd[1] = rd[2] = 0.0;
            rs[0] = rs[1] = rs[2] = 0.0;
            rd[c] = -a / M_PI;
            rs[c] = -a * K;
            for (int j = 0; j < nc; j++)
                rt[j] = s[c] * dth[j];
        }
    }
}

void fc_residuals_channel(const brdffit_samples *set, size_t i0, size_t n, brdffit_model model,
                          int c, const double ds[2], const double *theta, double *r, double *jds,
                          double *jt)
{
    const size_t npad = set->npad;
    const double *f = set->data, *rho = f + (size_t)(BF_F_R + c) * npad;
    const int m = (int)model, nc = bf_model_ncoords(model);
    const double lam[3] = { 0.645, 0.526, 0.444 }; /* unused: no chromatic lobe here */
    double p[3], dp[3][3];
    fc_params_of(model, theta, p);
    param_partials(model, theta, p, dp);
    const double dpi = ds[0] / M_PI, sc = ds[1];
    for (size_t q = 0; q < n; q++) {
        const size_t i = i0 + q;
        bf_geom g = { f[BF_F_IX * npad + i], f[BF_F_IY * npad + i], f[BF_F_IZ * npad + i],
                      f[BF_F_OX * npad + i], f[BF_F_OY * npad + i], f[BF_F_OZ * npad + i],
                      f[BF_F_NH * npad + i], f[BF_F_VH * npad + i] };
        const double a = sqrt(f[BF_F_A2 * npad + i]);
        double K;
        if (jds) {
            double dK[3];
            K = bf_lobe_vdk(m, &g, p, dK);
            jds[2 * q] = -a / M_PI;
            jds[2 * q + 1] = -a * K;
            for (int j = 0; j < nc; j++)
                jt[(size_t)nc * q + (size_t)j] =
                    -a * sc * ((dK[0] * dp[j][0] + dK[1] * dp[j][1]) + dK[2] * dp[j][2]);
        } else {
            double Kc[3];
            bf_lobe(m, &g, p, lam, Kc);
            K = Kc[0];
        }
        r[q] = a * (rho[i] - dpi - sc * K);
    }
}

double fc_error(const brdffit_samples *set, brdffit_model model, const double d[3],
                const double s[3], const double p[3])
{
    double theta[3] = { 0.0, 0.0, 0.0 }, r[3 * 1024], rr = 0.0;
    fc_theta_of(model, p, theta);
    for (size_t i0 = 0; i0 < set->n; i0 += 1024) {
        size_t n = set->n - i0 < 1024 ? set->n - i0 : 1024;
        fc_residuals(set, i0, n, model, d, s, theta, r, NULL, NULL, NULL);
        for (size_t q = 0; q < 3 * n; q++)
            rr += r[q] * r[q];
    }
    return sqrt(rr + fc_pair_see(set));
}

/* Start i of n of a model whose start grid is one round (period 0, no
 * round_param: every model with partials), as fit/screen.c's start_params makes
 * it from the registry's grid: the grid's parameter at the i-th of n points
 * spaced evenly (LINEAR) or geometrically (LOG) over lo .. hi, the others at
 * their typical start. */
static void grid_start(brdffit_model model, int i, int n, double p[3])
{
    const bf_start_grid *gr = &bf_model_def_get(model)->grid;
    bf_model_start_params(model, p);
    double v;
    if (n > 1)
        v = gr->spacing == BRDFFIT_MAP_LOG ? gr->lo * pow(gr->hi / gr->lo, (double)i / (n - 1))
                                           : gr->lo + (gr->hi - gr->lo) * i / (n - 1);
    else
        v = gr->spacing == BRDFFIT_MAP_LOG ? gr->lo * pow(gr->hi / gr->lo, 0.5)
                                           : 0.5 * (gr->lo + gr->hi);
    p[gr->param] = v;
}

int fc_best_start(brdffit_context *ctx, const brdffit_samples *samples, brdffit_model model,
                  double *theta, double d[3], double s[3])
{
    const bf_start_grid *gr = &bf_model_def_get(model)->grid;
    if (gr->period != 0 || gr->round_param >= 0) {
        fprintf(stderr, "bench-ceres: %s's starts come in rounds; not taken here\n",
                brdffit_model_get(model)->name);
        return 1;
    }
    brdffit_error err;
    const brdffit_samples *sub = NULL, *bins = NULL, *on = NULL;
    if (bf_screen_subsets(samples, model, &sub, &bins, &err) != BRDFFIT_OK ||
        (!sub && bf_samples_mirror_kept(samples, &on, &err) != BRDFFIT_OK)) {
        fprintf(stderr, "bench-ceres: %s\n", err.message);
        return 1;
    }
    if (sub)
        on = sub;
    bf_pass_driver dr;
    memset(&dr, 0, sizeof dr);
    int rc = 0;
    if (bf_driver_open(&dr, ctx, on, model, &err) != BRDFFIT_OK) {
        rc = 1;
    } else {
        const int n = brdffit_model_get(model)->default_starts;
        const bf_linear zero = { { 0, 0, 0 }, { 0, 0, 0 } };
        double best = INFINITY, p[3] = { 0.0, 0.0, 0.0 };
        for (int i = 0; i < n && rc == 0; i++) {
            bf_pass_par pp;
            memset(&pp, 0, sizeof pp);
            grid_start(model, i, n, pp.p[0]);
            double mom[BF_NMOM_MAX];
            if (bf_driver_run(&dr, 0, &pp, mom, &err) != BRDFFIT_OK) {
                rc = 1;
                break;
            }
            bf_linear lin;
            double cost = bf_linear_best(mom, dr.nk, 0, &zero, &lin);
            if (cost < best) {
                best = cost;
                memcpy(p, pp.p[0], sizeof p);
            }
        }
        /* the kept start taken again on all samples (their mirror set), as
         * brdffit's LM run starts from it: the best d, s there */
        bf_driver_close(&dr);
        memset(&dr, 0, sizeof dr);
        bf_pass_par pp;
        memset(&pp, 0, sizeof pp);
        memcpy(pp.p[0], p, sizeof p);
        double mom[BF_NMOM_MAX];
        bf_linear lin;
        if (rc == 0 && (bf_samples_mirror_kept(samples, &on, &err) != BRDFFIT_OK ||
                        bf_driver_open(&dr, ctx, on, model, &err) != BRDFFIT_OK ||
                        bf_driver_run(&dr, 0, &pp, mom, &err) != BRDFFIT_OK)) {
            rc = 1;
        } else if (rc == 0) {
            bf_linear_best(mom, dr.nk, 0, &zero, &lin);
            fc_theta_of(model, p, theta);
            memcpy(d, lin.d, sizeof lin.d);
            memcpy(s, lin.s, sizeof lin.s);
        }
    }
    bf_driver_close(&dr);
    if (rc)
        fprintf(stderr, "bench-ceres: %s\n", err.message);
    return rc;
}
