/* SPDX-License-Identifier: MIT */
/* models.c -- parameter checks and the plain-C evaluators.  The models
 * themselves are registry.c's; their maths is in kernels/ (shared with the
 * OpenCL kernel). */
#include "registry.h"

#include "bf_gltf.h"
#include "bf_openpbr.h"
#include "bf_lobe.h"

#include <math.h>
#include <string.h>

void bf_lambdas(const brdffit_params *params, double lam[3])
{
    static const double dflt[3] = { 0.645, 0.526, 0.444 };
    for (int c = 0; c < 3; c++)
        lam[c] = (params && params->lambda_um[c] != 0.0) ? params->lambda_um[c] : dflt[c];
}

void bf_model_value(brdffit_model model, const bf_geom *g, const brdffit_params *params,
                    const double lam[3], double rgb[3])
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (mi && mi->colour_form == BRDFFIT_COLOUR_GLTF) {
        bf_gltf(g, params->p, params->d, params->s, rgb);
        return;
    }
    if (mi && mi->colour_form == BRDFFIT_COLOUR_OPENPBR) {
        bf_openpbr(g, params->p, params->d, params->s, rgb);
        return;
    }
    double K[3];
    bf_lobe((int)model, g, params->p, lam, K);
    for (int c = 0; c < 3; c++)
        rgb[c] = params->d[c] / BF_PI + params->s[c] * K[c];
}

/* The glTF and OpenPBR models' colours: the base colour in [0, 1], the
 * specular colour >= 0 (the core glTF model: 1, its value there; OpenPBR:
 * at most 1, its specification's range). */
static brdffit_status gltf_colours_check(const brdffit_model_info *mi,
                                         const brdffit_params *params, brdffit_error *err)
{
    static const char ch[3] = { 'r', 'g', 'b' };
    for (int c = 0; c < 3; c++) {
        double b = params->d[c], sc = params->s[c];
        if (!(b >= 0 && b <= 1))
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE, "%s: base_color_%c = %g outside [0, 1]",
                           mi->name, ch[c], b);
        if (mi->id == BRDFFIT_GLTF && sc != 1.0)
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE,
                           "%s: specular_color_%c = %g must be 1 (the core material; "
                           "gltf-ext takes others)", mi->name, ch[c], sc);
        if (!(isfinite(sc) && sc >= 0))
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE,
                           "%s: specular_color_%c = %g must be finite and >= 0", mi->name, ch[c], sc);
        if (mi->colour_form == BRDFFIT_COLOUR_OPENPBR && sc > 1)
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE, "%s: specular_color_%c = %g outside [0, 1]",
                           mi->name, ch[c], sc);
    }
    return BRDFFIT_OK;
}

brdffit_status brdffit_params_check(brdffit_model model, const brdffit_params *params,
                                    brdffit_error *err)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (!mi)
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    if (!params)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "params is NULL");
    static const char ch[3] = { 'R', 'G', 'B' };
    if (mi->colour_form != BRDFFIT_COLOUR_DS) {
        brdffit_status st = gltf_colours_check(mi, params, err);
        if (st != BRDFFIT_OK)
            return st;
    }
    for (int c = 0; c < 3 && mi->colour_form == BRDFFIT_COLOUR_DS; c++) {
        if (!isfinite(params->d[c]) || params->d[c] < 0)
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE, "%s: d_%c = %g must be finite and >= 0",
                           mi->name, ch[c], params->d[c]);
        if (!isfinite(params->s[c]) || params->s[c] < 0)
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE, "%s: s_%c = %g must be finite and >= 0",
                           mi->name, ch[c], params->s[c]);
        if (mi->chromatic && params->lambda_um[c] != 0.0 &&
            !(params->lambda_um[c] >= 0.1 && params->lambda_um[c] <= 10.0))
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE,
                           "%s: lambda_%c = %g um must be 0 (default) or in [0.1, 10]", mi->name,
                           ch[c], params->lambda_um[c]);
    }
    for (int k = 0; k < mi->nparams; k++) {
        const brdffit_param_info *pi = &mi->params[k];
        double v = params->p[k];
        if (!(v >= pi->lower && v <= pi->upper))
            return bf_fail(err, BRDFFIT_E_PARAM_RANGE, "%s: %s = %g outside [%g, %g]", mi->name,
                           pi->name, v, pi->lower, pi->upper);
    }
    /* a direction pair has a direction only when one of its two is not 0 */
    for (int k = 0; k + 1 < mi->nparams; k++)
        if (mi->params[k].map == BRDFFIT_MAP_DIRECTION) {
            if (fmax(fabs(params->p[k]), fabs(params->p[k + 1])) < 1e-12)
                return bf_fail(err, BRDFFIT_E_PARAM_RANGE, "%s: %s and %s are both 0", mi->name,
                               mi->params[k].name, mi->params[k + 1].name);
            k++;
        }
    bf_ok(err);
    return BRDFFIT_OK;
}

/* Normalise a direction; 0 when it is not finite or has no length. */
static int unit(const double v[3], double u[3])
{
    if (!bf_direction_ok(v))
        return 0;
    double inv = 1.0 / sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        u[k] = v[k] * inv;
    return 1;
}

/* f for one pair of checked parameters; returns 0 for a bad direction. */
static int eval_one(brdffit_model model, const brdffit_params *params, const double lam[3],
                    const double *wi, const double *wo, double *rgb)
{
    double a[3], b[3];
    if (!unit(wi, a) || !unit(wo, b))
        return 0;
    if (a[2] <= 0 || b[2] <= 0) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return 1;
    }
    bf_geom g = { a[0], a[1], a[2], b[0], b[1], b[2], 0, 0 };
    bf_geom_derive(&g);
    bf_model_value(model, &g, params, lam, rgb);
    return 1;
}

/* n pairs for the function `fn` (its name in messages; `batch`: it takes n). */
static brdffit_status eval_pairs(const char *fn, int batch, brdffit_model model,
                                 const brdffit_params *params, size_t n, const double *wi,
                                 const double *wo, double *rgb, brdffit_error *err)
{
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st != BRDFFIT_OK)
        return st;
    if (n > 0 && (!wi || !wo || !rgb))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "%s: %s is NULL", fn,
                       !wi ? "wi" : !wo ? "wo" : "rgb");
    double lam[3];
    bf_lambdas(params, lam);
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < n; i++) {
        if (!eval_one(model, params, lam, wi + 3 * i, wo + 3 * i, rgb + 3 * i)) {
            rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = 0;
            if (bad++ == 0)
                first = i;
        }
    }
    if (bad == 0) {
        bf_ok(err);
        return BRDFFIT_OK;
    }
    if (batch)
        return bf_fail_pairs(err, fn, first, n, bad, "0", wi, wo);
    return bf_fail_pair(err, fn, wi + 3 * first, wo + 3 * first);
}

brdffit_status brdffit_eval_batch(brdffit_model model, const brdffit_params *params, size_t n,
                                  const double *wi, const double *wo, double *rgb,
                                  brdffit_error *err)
{
    return eval_pairs("brdffit_eval_batch", 1, model, params, n, wi, wo, rgb, err);
}

brdffit_status brdffit_eval(brdffit_model model, const brdffit_params *params, const double wi[3],
                            const double wo[3], double rgb[3], brdffit_error *err)
{
    return eval_pairs("brdffit_eval", 0, model, params, 1, wi, wo, rgb, err);
}
