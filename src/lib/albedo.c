/* SPDX-License-Identifier: MIT */
/* albedo.c -- the directional albedo a(theta_o) = integral of f(wi, wo)
 * cos theta_i d wi of a model or a measured table (include/brdffit.h), by
 * the quadrature of albedo.h. */
#include "albedo.h"
#include "registry.h"

#include "bf_gltf.h"
#include "bf_lobe.h"

#include <math.h>
#include <stdlib.h>

/* The rule's resolution (docs/library.md states the accuracy it gives):
 * phi points by theta_o (default_nphi), Gauss-Legendre points per radial
 * interval. */
#define MODEL_NPHI_MAX 24
#define MODEL_ORDER 8
/* He's lobe is smooth in theta_h and costs ~1 us an evaluation: 4 points an
 * interval keep it within the accuracy of 8 (its limit is phi's) at half the cost. */
#define HE_ORDER 4
#define TABLE_NPHI 24
#define TABLE_ORDER 2
#define MIN_WIDTH 1e-7

static double clampd(double v, double lo, double hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* The width of a cos^n lobe, e^(-n x^2 / 2). */
static double cos_power_width(double n)
{
    return sqrt(2.0 / (n + 2.0));
}

/* The finest angular scale of a model's lobe at params (theta_h, or the
 * angle from Lafortune's axis): the quadrature resolves it. */
static double lobe_width(brdffit_model model, const brdffit_params *pa)
{
    const double *p = pa->p;
    double lam[3];
    bf_lambdas(pa, lam);
    switch (model) {
    case BRDFFIT_WARD:
    case BRDFFIT_WARD_DUER: return p[0];
    case BRDFFIT_BLINN_PHONG: return cos_power_width(p[0]);
    case BRDFFIT_LAFORTUNE: return cos_power_width(p[2]);
    case BRDFFIT_COOK_TORRANCE:
    case BRDFFIT_GGX: return p[1];
    case BRDFFIT_ASHIKHMIN_SHIRLEY: return cos_power_width(p[1]);
    case BRDFFIT_HE: { /* the series' terms m ~ g dominate, each |v_xy| ~ sqrt(m) lam / (pi tau)
                        * wide, g = (2 pi sigma v_z / lam)^2 with sigma <= sigma0 */
        double l = fmin(lam[0], fmin(lam[1], lam[2]));
        return l / (2.0 * BF_PI * p[0]) * fmax(1.0, 2.0 * BF_PI * p[1] / fmax(lam[0], fmax(lam[1], lam[2])));
    }
    case BRDFFIT_GLTF:
    case BRDFFIT_GLTF_EXT: {
        double r = fmax(p[1], BF_GLTF_ROUGHNESS_MIN);
        return r * r;
    }
    default: return MIN_WIDTH; /* a model this file does not know: the finest */
    }
}

/* Lafortune's lobe (max(0, wi . u))^n, u = (Cxy vx, Cxy vy, Cz vz) / max(|Cxy|, |Cz|):
 * its axis for wo, or the normal when u is 0. */
static void lafortune_axis(const double *p, const double wo[3], double axis[3])
{
    double m = fmax(fabs(p[0]), fabs(p[1]));
    double u[3] = { p[0] * wo[0] / m, 0.0, p[1] * wo[2] / m };
    double len = sqrt(u[0] * u[0] + u[2] * u[2]);
    axis[0] = len > 1e-300 ? u[0] / len : 0.0;
    axis[1] = 0.0;
    axis[2] = len > 1e-300 ? u[2] / len : 1.0;
}

/* Points in phi at theta_o: 1 at the normal (every integrand is then the
 * same at every phi: the lobes are isotropic), more as the integrand's
 * dependence on phi and the horizon's swing grow with theta_o. */
static int default_nphi(double theta_o_deg)
{
    return theta_o_deg == 0 ? 1 : theta_o_deg < 32.5 ? 8 : theta_o_deg < 57.5 ? 16 : MODEL_NPHI_MAX;
}

static void model_rule(brdffit_model model, const brdffit_params *params, double theta_o_deg,
                       const double wo[3], int nphi, int order, aq_rule *rule)
{
    if (nphi <= 0)
        nphi = default_nphi(theta_o_deg);
    if (order <= 0)
        order = model == BRDFFIT_HE ? HE_ORDER : MODEL_ORDER;
    rule->kind = model == BRDFFIT_LAFORTUNE ? AQ_POLE : AQ_HALF;
    if (model == BRDFFIT_LAFORTUNE)
        lafortune_axis(params->p, wo, rule->pole);
    rule->width = clampd(lobe_width(model, params), MIN_WIDTH, 1.0);
    rule->nphi = nphi;
    rule->order = order;
}

static void view_direction(double theta_o_deg, double wo[3])
{
    double t = theta_o_deg * (BF_PI / 180.0);
    wo[0] = sin(t);
    wo[1] = 0.0;
    wo[2] = cos(t);
}

static brdffit_status angles_check(const char *fn, size_t n, const double *theta_o_deg,
                                   const double *rgb, brdffit_error *err)
{
    if (n > 0 && (!theta_o_deg || !rgb))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: %s is NULL", fn,
                       !theta_o_deg ? "theta_o_deg" : "rgb");
    for (size_t k = 0; k < n; k++)
        if (!(theta_o_deg[k] >= 0 && theta_o_deg[k] < 90))
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "%s: theta_o_deg[%zu] = %g (must be in [0, 90))", fn, k,
                           theta_o_deg[k]);
    return BRDFFIT_OK;
}

/* The albedo of a model at one theta_o: the lobe's integral I (DS models:
 * a = d + s I) or f's (glTF). */
static void model_albedo(brdffit_model model, const brdffit_params *params, const double lam[3],
                         const aq_rule *rule, const double wo[3], aq_point *pts, double rgb[3])
{
    int ds = brdffit_model_get(model)->colour_form == BRDFFIT_COLOUR_DS;
    size_t np = aq_points(rule, wo, pts);
    double acc[3] = { 0, 0, 0 };
    for (size_t q = 0; q < np; q++) {
        const double *v = pts[q].wi;
        bf_geom g = { v[0], v[1], v[2], wo[0], wo[1], wo[2], 0, 0 };
        double f[3];
        bf_geom_derive(&g);
        if (pts[q].nh > 0) { /* N.H and V.H of h itself: a few roundings fewer */
            g.nh = pts[q].nh;
            g.vh = pts[q].vh;
        }
        if (ds)
            bf_lobe((int)model, &g, params->p, lam, f);
        else
            bf_model_value(model, &g, params, lam, f);
        for (int c = 0; c < 3; c++)
            acc[c] += pts[q].w * f[c];
    }
    for (int c = 0; c < 3; c++)
        rgb[c] = ds ? params->d[c] + (params->s[c] == 0 ? 0.0 : params->s[c] * acc[c]) : acc[c];
}

brdffit_status bf_albedo_model_rule(brdffit_model model, const brdffit_params *params, size_t n,
                                    const double *theta_o_deg, double *rgb, int nphi, int order,
                                    brdffit_error *err)
{
    static const char fn[] = "brdffit_albedo_model";
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st == BRDFFIT_OK)
        st = angles_check(fn, n, theta_o_deg, rgb, err);
    if (st != BRDFFIT_OK)
        return st;
    aq_rule rule;
    double wo[3] = { 0, 0, 1 }, lam[3];
    model_rule(model, params, 0, wo, nphi > 0 ? nphi : MODEL_NPHI_MAX, order, &rule);
    size_t cap = aq_max_points(&rule);
    aq_point *pts = malloc(cap * sizeof *pts);
    if (!pts)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "%s: no memory for %zu points", fn, cap);
    bf_lambdas(params, lam);
    for (size_t k = 0; k < n; k++) {
        view_direction(theta_o_deg[k], wo);
        model_rule(model, params, theta_o_deg[k], wo, nphi, order, &rule);
        model_albedo(model, params, lam, &rule, wo, pts, rgb + 3 * k);
    }
    free(pts);
    for (size_t k = 0; k < 3 * n; k++)
        if (!isfinite(rgb[k]))
            return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                           "%s: the albedo at theta_o %g deg, channel %zu, is %g (d or s too large)",
                           fn, theta_o_deg[k / 3], k % 3, rgb[k]);
    bf_ok(err);
    return BRDFFIT_OK;
}

brdffit_status brdffit_albedo_model(brdffit_model model, const brdffit_params *params, size_t n,
                                    const double *theta_o_deg, double *rgb, brdffit_error *err)
{
    return bf_albedo_model_rule(model, params, n, theta_o_deg, rgb, 0, 0, err);
}

/* The table's albedo at one theta_o, masked channels counting 0 (as the
 * renders take them); *masked the share of the weight that met a masked bin. */
static void table_albedo(const brdffit_table *table, brdffit_scale scale, brdffit_interp interp,
                         const aq_rule *rule, const double wo[3], aq_point *pts,
                         double rgb[3], double *masked)
{
    size_t np = aq_points(rule, wo, pts);
    double acc[3] = { 0, 0, 0 }, all = 0, hit = 0;
    for (size_t q = 0; q < np; q++) {
        double f[3];
        if (brdffit_table_lookup(table, pts[q].wi, wo, scale, interp, f, NULL) != BRDFFIT_OK)
            f[0] = f[1] = f[2] = -1.0; /* no value: as masked (not met above the horizon) */
        int bad = 0;
        for (int c = 0; c < 3; c++) {
            if (f[c] < 0)
                bad = 1;
            else
                acc[c] += pts[q].w * f[c];
        }
        all += pts[q].w;
        hit += bad ? pts[q].w : 0.0;
    }
    for (int c = 0; c < 3; c++)
        rgb[c] = acc[c];
    if (masked)
        *masked = all > 0 ? hit / all : 0.0;
}

brdffit_status brdffit_albedo_table(const brdffit_table *table, brdffit_scale scale,
                                    brdffit_interp interp, size_t n, const double *theta_o_deg,
                                    double *rgb, double *masked, brdffit_error *err)
{
    static const char fn[] = "brdffit_albedo_table";
    brdffit_status st = bf_lookup_check(fn, table, scale, interp, err);
    if (st == BRDFFIT_OK)
        st = angles_check(fn, n, theta_o_deg, rgb, err);
    if (st != BRDFFIT_OK)
        return st;
    aq_rule rule = { AQ_TABLE, { 0, 0, 1 }, MIN_WIDTH, TABLE_NPHI, TABLE_ORDER };
    size_t cap = aq_max_points(&rule);
    aq_point *pts = malloc(cap * sizeof *pts);
    if (!pts)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "%s: no memory for %zu points", fn, cap);
    for (size_t k = 0; k < n; k++) {
        double wo[3];
        view_direction(theta_o_deg[k], wo);
        table_albedo(table, scale, interp, &rule, wo, pts, rgb + 3 * k, masked ? masked + k : NULL);
    }
    free(pts);
    bf_ok(err);
    return BRDFFIT_OK;
}
