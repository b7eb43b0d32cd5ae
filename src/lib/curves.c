/* SPDX-License-Identifier: MIT */
/* curves.c -- BRDF values along the incidence plane, measured and modelled,
 * into caller buffers (the data of the cube-root plots).  Directions:
 * include/brdffit.h, brdffit_curve_options. */
#include "internal.h"

#include <math.h>
#include <string.h>

#define MAX_POINTS 100000

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void brdffit_curve_options_init(brdffit_curve_options *opt, size_t size)
{
    static const double dflt[4] = { 20, 40, 60, 75 };
    brdffit_curve_options d;
    memset(&d, 0, sizeof d);
    d.size = sizeof d;
    d.ntheta_i = 4;
    memcpy(d.theta_i_deg, dflt, sizeof dflt);
    d.npoints = 180;
    d.interp = BRDFFIT_INTERP_TRILINEAR;
    d.scale = BRDFFIT_SCALE_STANDARD;
    bf_options_init(BRDFFIT_STRUCT_CURVE_OPTIONS, &d, opt, size);
}

/* The options in effect, checked: opt's members inside opt->size over the defaults. */
static brdffit_status read_options(const brdffit_curve_options *opt, brdffit_curve_options *o,
                                   brdffit_error *err)
{
    brdffit_curve_options_default(o);
    brdffit_status st = bf_options_read(BRDFFIT_STRUCT_CURVE_OPTIONS, opt, o, err);
    if (st != BRDFFIT_OK)
        return st;
    if (o->ntheta_i < 1 || o->ntheta_i > BRDFFIT_CURVE_MAX_THETA_I)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "curves: ntheta_i = %d (1..%d)",
                       o->ntheta_i, BRDFFIT_CURVE_MAX_THETA_I);
    for (int a = 0; a < o->ntheta_i; a++)
        if (!(o->theta_i_deg[a] >= 0 && o->theta_i_deg[a] < 90))
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "curves: theta_i = %g deg (must be in [0, 90))", o->theta_i_deg[a]);
    if (o->npoints < 2 || o->npoints > MAX_POINTS)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "curves: npoints = %d (2..%d)",
                       o->npoints, MAX_POINTS);
    if ((o->interp != BRDFFIT_INTERP_NEAREST && o->interp != BRDFFIT_INTERP_TRILINEAR) ||
        (o->scale != BRDFFIT_SCALE_STANDARD && o->scale != BRDFFIT_SCALE_FLAT))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "curves: unknown interp %d or scale %d",
                       (int)o->interp, (int)o->scale);
    return BRDFFIT_OK;
}

static double theta_o_deg(const brdffit_curve_options *o, int k)
{
    return -90.0 + 180.0 * (k + 0.5) / o->npoints;
}

brdffit_status brdffit_curve_theta_o(const brdffit_curve_options *opt, double *out,
                                     brdffit_error *err)
{
    brdffit_curve_options o;
    brdffit_status st = read_options(opt, &o, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_curve_theta_o: theta_o_deg is NULL");
    for (int k = 0; k < o.npoints; k++)
        out[k] = theta_o_deg(&o, k);
    bf_ok(err);
    return BRDFFIT_OK;
}

static void directions(const brdffit_curve_options *o, int a, int k, double wi[3], double wo[3])
{
    double ti = o->theta_i_deg[a] * (M_PI / 180), to = theta_o_deg(o, k) * (M_PI / 180);
    wi[0] = -sin(ti);
    wi[1] = 0;
    wi[2] = cos(ti);
    wo[0] = sin(to);
    wo[1] = 0;
    wo[2] = cos(to);
}

/* Fill every curve through a table (when table is set) or a model. */
static brdffit_status curves(const brdffit_table *table, brdffit_model model,
                             const brdffit_params *params, const brdffit_curve_options *opt,
                             double *rgb, size_t stride, brdffit_error *err)
{
    brdffit_curve_options o;
    brdffit_status st = read_options(opt, &o, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!rgb)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "curves: rgb is NULL");
    size_t row = 3 * (size_t)o.npoints;
    if (stride == 0)
        stride = row;
    if (stride < row)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "curves: stride %zu < 3 x npoints %d",
                       stride, o.npoints);
    for (int a = 0; a < o.ntheta_i; a++) {
        for (int k = 0; k < o.npoints; k++) {
            double wi[3], wo[3], *out = rgb + (size_t)a * stride + 3 * (size_t)k;
            directions(&o, a, k, wi, wo);
            brdffit_error why;
            st = table ? brdffit_table_lookup(table, wi, wo, o.scale, o.interp, out, &why)
                       : brdffit_eval(model, params, wi, wo, out, &why);
            if (st != BRDFFIT_OK)
                return bf_fail(err, st, "curves: theta_i %g, theta_o %g: %s", o.theta_i_deg[a],
                               theta_o_deg(&o, k), why.message);
        }
    }
    bf_ok(err);
    return BRDFFIT_OK;
}

brdffit_status brdffit_curve_table(const brdffit_table *table, const brdffit_curve_options *opt,
                                   double *rgb, size_t stride, brdffit_error *err)
{
    if (!table)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_curve_table: table is NULL");
    return curves(table, BRDFFIT_WARD, NULL, opt, rgb, stride, err);
}

brdffit_status brdffit_curve_model(brdffit_model model, const brdffit_params *params,
                                   const brdffit_curve_options *opt, double *rgb, size_t stride,
                                   brdffit_error *err)
{
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st != BRDFFIT_OK)
        return st;
    return curves(NULL, model, params, opt, rgb, stride, err);
}
