/* SPDX-License-Identifier: MIT */
/* api.c -- the fit's API: brdffit_fit (its options checked, the drivers
 * opened, the stages run in order: screen.c, refine.c; the result filled
 * in) and brdffit_error_of.  The passes on all samples read the set's
 * mirror set (samples_mirror.c: the same sums from about half the
 * samples), so that a fit's Error is brdffit_error_of's to the bit.  What
 * the caller sees, apart from how the fit gets there; docs/fitting.md,
 * "Result and status". */
#include "affine.h"

#include "samples.h"

#include <math.h>
#include <string.h>

void brdffit_fit_options_init(brdffit_fit_options *opt, size_t size)
{
    brdffit_fit_options d;
    memset(&d, 0, sizeof d);
    d.size = sizeof d;
    d.starts = 0; /* the model's default_starts */
    d.refine = 1;
    d.ftol = 1e-8;
    d.xtol = 1e-8;
    d.gtol = 0.0;
    d.max_evals = 200;
    bf_options_init(BRDFFIT_STRUCT_FIT_OPTIONS, &d, opt, size);
}

const char *brdffit_metric_name(void)
{
    return "ngan-l2";
}

static brdffit_status check_fit_options(const brdffit_fit_options *o, brdffit_error *err)
{
    if (o->starts < 0 || o->starts > 1000)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "starts = %d must be in [1, 1000] (or 0: the model's default)", o->starts);
    if (o->refine < 1)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "refine = %d must be >= 1", o->refine);
    if (!(o->ftol >= 0) || !(o->xtol >= 0) || !(o->gtol >= 0) || !isfinite(o->ftol) ||
        !isfinite(o->xtol) || !isfinite(o->gtol))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "tolerances must be finite and >= 0");
    if (o->metric < 0 || o->metric >= BRDFFIT_METRIC_COUNT)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "metric = %d is not a metric (0 ngan-l2, 1 log, 2 cube-root)", o->metric);
    if (o->all_errors != 0 && o->all_errors != 1)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "all_errors = %d must be 0 or 1",
                       o->all_errors);
    if (o->max_evals < 1)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "max_evals = %d must be >= 1", o->max_evals);
    for (int c = 0; c < 3; c++)
        if (o->lambda_um[c] != 0.0 && !(o->lambda_um[c] >= 0.1 && o->lambda_um[c] <= 10.0))
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "lambda_um[%d] = %g must be 0 (default) or in [0.1, 10]", c, o->lambda_um[c]);
    return BRDFFIT_OK;
}

#define ROUNDED_AWAY 1e-12

/* Which parameters of the result are on a bound (brdffit_fit_result.at_bound). */
static unsigned bound_mask(const fitmap *fm, const double *u, const bf_linear *lin)
{
    unsigned mask = 0;
    /* a coefficient round-off left a hair above 0 (below 1e-12 of the
     * channel's other one: s = 6e-31 beside d = 0.2 on a material with no
     * specular part) is on its bound as well */
    for (int c = 0; c < 3; c++) {
        double d = lin->d[c], s = lin->s[c];
        if (d == 0.0 || d <= ROUNDED_AWAY * s)
            mask |= (unsigned)BRDFFIT_AT_BOUND_D_R << c;
        if (s == 0.0 || s <= ROUNDED_AWAY * d)
            mask |= (unsigned)BRDFFIT_AT_BOUND_S_R << c;
    }
    unsigned on = bf_on_bounds(fm, u);
    for (int j = 0; j < fm->nl; j++)
        if (on & (1u << j))
            mask |= (unsigned)BRDFFIT_AT_BOUND_P0 << fm->param[j];
    return mask;
}

/* r^T r of the result from one value pass at its own d, s, p: the fit's
 * Error is then brdffit_error_of's of the returned parameters, to the bit
 * (the LM's r^T r comes from moments taken near, not at, the point). */
static brdffit_status exact_error(lmstate *S, lmrun *best)
{
    bf_pass_par pp;
    memset(&pp, 0, sizeof pp);
    memcpy(pp.d, best->lin.d, sizeof pp.d);
    memcpy(pp.s, best->lin.s, sizeof pp.s);
    memcpy(pp.lam, S->lam, sizeof pp.lam);
    bf_coords_to_params(&S->fm, best->x, pp.p[0]);
    double mom[BF_NMOM_MAX], rr = 0.0;
    brdffit_status st = bf_driver_run(S->ps, 0, &pp, mom, S->err);
    if (st != BRDFFIT_OK)
        return st;
    for (int c = 0; c < 3; c++)
        rr += mom[bf_mom_chan(c, S->ps->nk, 0) + BF_MC_SEE];
    best->rr = fmax(rr, 0.0);
    return BRDFFIT_OK;
}

static void fill_result(const lmstate *S, const lmrun *best, brdffit_fit_result *result)
{
    memset(result, 0, sizeof *result);
    result->size = sizeof *result;
    result->model = S->fm.model;
    memcpy(result->params.d, best->lin.d, sizeof result->params.d);
    memcpy(result->params.s, best->lin.s, sizeof result->params.s);
    bf_coords_to_params(&S->fm, best->x, result->params.p);
    if (brdffit_model_get(S->fm.model)->chromatic)
        memcpy(result->params.lambda_um, S->lam, sizeof S->lam);
    result->error = sqrt(best->rr);
    result->cminpack_info = best->info;
    result->iterations = best->njev;
    result->flags = best->info == 5 ? BRDFFIT_FIT_LIMIT : 0u;
    result->at_bound = bound_mask(&S->fm, best->x, &best->lin);
}

/* Each channel has d, s and the lobe's coordinates to determine: with fewer
 * distinct geometries than that the fit is underdetermined (one sample, or
 * a cutoff so small that only the normal is left), and LM would return any
 * of infinitely many answers. */
static brdffit_status check_enough_samples(const brdffit_samples *samples, brdffit_model model,
                                           brdffit_error *err)
{
    size_t unknowns = 2 + (size_t)bf_model_ncoords(model);
    size_t found = bf_samples_geometries(samples, unknowns);
    if (found >= unknowns)
        return BRDFFIT_OK;
    return bf_fail(err, BRDFFIT_E_TOO_FEW_SAMPLES,
                   "%zu sample%s at %zu distinct geometr%s (up to rotation about the normal and "
                   "exchange of wi and wo): too few for %s, which has %zu unknowns per channel "
                   "(d, s and %d lobe parameter%s)",
                   brdffit_samples_count(samples), brdffit_samples_count(samples) == 1 ? "" : "s",
                   found, found == 1 ? "y" : "ies", brdffit_model_get(model)->name, unknowns,
                   bf_model_ncoords(model), bf_model_ncoords(model) == 1 ? "" : "s");
}

/* The driver of a fit's (and brdffit_error_of's) passes on all samples: over
 * the set's mirror set (samples_mirror.c), so that a fit's Error is
 * brdffit_error_of's to the bit.  Close it whatever this returns. */
static brdffit_status open_all_samples(bf_pass_driver *ps, brdffit_context *ctx,
                                       const brdffit_samples *samples, brdffit_model model,
                                       brdffit_error *err)
{
    memset(ps, 0, sizeof *ps);
    const brdffit_samples *all = NULL;
    brdffit_status st = bf_samples_mirror_kept(samples, &all, err);
    return st == BRDFFIT_OK ? bf_driver_open(ps, ctx, all, model, err) : st;
}

/* r holds the "ngan-l2" fit of o: its Errors under the other metrics (when
 * o asks for all_errors; NaN otherwise, so that a default fit makes no more
 * passes), or,
 * for another metric, the fit under it from there (metric_fit.c) and the
 * "ngan-l2" Error of what that fit returns. */
static brdffit_status metric_finish(brdffit_context *ctx, const brdffit_samples *samples,
                                    brdffit_model model, const brdffit_fit_options *o,
                                    brdffit_fit_result *r, brdffit_error *err)
{
    r->errors[BRDFFIT_METRIC_NGAN_L2] = r->error;
    r->metric = BRDFFIT_METRIC_NGAN_L2;
    r->metric_iterations = 0;
    if (o->metric == BRDFFIT_METRIC_NGAN_L2) {
        if (o->all_errors)
            return bf_metric_errors(samples, model, &r->params, r->errors, err);
        for (int m = 1; m < BRDFFIT_METRIC_COUNT; m++)
            r->errors[m] = NAN;
        return BRDFFIT_OK;
    }
    brdffit_status st = bf_metric_refit(samples, model, (brdffit_metric)o->metric, r, err);
    if (st == BRDFFIT_OK)
        st = brdffit_error_of(ctx, samples, model, &r->params,
                              &r->errors[BRDFFIT_METRIC_NGAN_L2], err);
    r->error = r->errors[o->metric];
    return st;
}

/* brdffit_fit of a model without a lobe (the glTF models: affine.c). */
static brdffit_status affine_fit(brdffit_context *ctx, const brdffit_samples *samples,
                                 brdffit_model model, const brdffit_fit_options *o,
                                 brdffit_fit_result *result, double t_start, brdffit_error *err)
{
    brdffit_fit_result r; /* the library's whole struct; the caller gets its size of it */
    brdffit_status st = bf_affine_fit(ctx, samples, model, o, &r, err);
    if (st == BRDFFIT_OK)
        st = metric_finish(ctx, samples, model, o, &r, err);
    if (st != BRDFFIT_OK)
        return st;
    r.seconds = bf_now() - t_start;
    st = bf_options_write(BRDFFIT_STRUCT_FIT_RESULT, &r, result, err);
    if (st == BRDFFIT_OK)
        bf_ok(err);
    return st;
}

brdffit_status brdffit_fit(brdffit_context *ctx, const brdffit_samples *samples, brdffit_model model,
                           const brdffit_fit_options *opt, brdffit_fit_result *result,
                           brdffit_error *err)
{
    double t_start = bf_now();
    if (!ctx || !samples || !result)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_fit: NULL context, samples or result");
    brdffit_status st = bf_sized_check(BRDFFIT_STRUCT_FIT_RESULT, result, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!brdffit_model_get(model))
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    brdffit_fit_options o;
    brdffit_fit_options_default(&o);
    st = bf_options_read(BRDFFIT_STRUCT_FIT_OPTIONS, opt, &o, err);
    if (st != BRDFFIT_OK)
        return st;
    st = check_fit_options(&o, err);
    if (st != BRDFFIT_OK)
        return st;
    st = check_enough_samples(samples, model, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!bf_model_has_lobe(model))
        return affine_fit(ctx, samples, model, &o, result, t_start, err);

    bf_pass_driver ps, sd, bd; /* all samples (their mirror set); the screening's
                                * subset and its bin subset */
    memset(&sd, 0, sizeof sd);
    memset(&bd, 0, sizeof bd);
    st = open_all_samples(&ps, ctx, samples, model, err);
    if (st != BRDFFIT_OK)
        goto done;
    lmstate S;
    memset(&S, 0, sizeof S);
    S.joined = -1;
    S.ps = &ps;
    S.err = err;
    fitsubsets D = { .sub = NULL, .bins = &bd, .bins_open = 0 };
    bf_fitmap_init(&S.fm, model);
    S.nx = S.fm.nl;
    S.secant_use = bf_model_def_get(model)->secant;
    brdffit_params lp;
    memset(&lp, 0, sizeof lp);
    memcpy(lp.lambda_um, o.lambda_um, sizeof lp.lambda_um);
    bf_lambdas(&lp, S.lam);

    start keep[MAX_KEEP];
    int nkeep = 0, refine = o.refine < MAX_KEEP ? o.refine : MAX_KEEP;
    int nstarts = o.starts ? o.starts : brdffit_model_get(model)->default_starts;
    st = bf_screen_kept(&S, &D, ctx, samples, nstarts, refine, keep, &nkeep, &sd);
    if (st != BRDFFIT_OK)
        goto done;
    lmrun best = { .rr = INFINITY };
    double solver_seconds = 0.0;
    st = bf_refine_kept(&S, &D, &o, keep, nkeep, &best, &solver_seconds);
    if (st != BRDFFIT_OK)
        goto done;
    if (!isfinite(best.rr)) {
        st = bf_fail(err, BRDFFIT_E_FIT_FAILED, "no start gave a finite Error");
        goto done;
    }
    st = bf_polish(&S, &o, &best, &solver_seconds);
    if (st == BRDFFIT_OK)
        st = exact_error(&S, &best);
    if (st != BRDFFIT_OK)
        goto done;
    brdffit_fit_result r; /* the library's whole struct; the caller gets its size of it */
    fill_result(&S, &best, &r);
    r.passes = ps.passes + sd.passes + bd.passes;
    r.seconds_build = ps.seconds_build;
    r.samples = samples->n;
    r.backend = brdffit_context_backend(ctx);
    r.seconds_passes = ps.seconds + sd.seconds + bd.seconds;
    r.seconds_solver = solver_seconds;
    st = metric_finish(ctx, samples, model, &o, &r, err);
    if (st != BRDFFIT_OK)
        goto done;
    r.seconds = bf_now() - t_start;
    st = bf_options_write(BRDFFIT_STRUCT_FIT_RESULT, &r, result, err);
    if (st == BRDFFIT_OK)
        bf_ok(err);
done:
    bf_driver_close(&bd);
    bf_driver_close(&sd);
    bf_driver_close(&ps);
    return st;
}

brdffit_status brdffit_error_of(brdffit_context *ctx, const brdffit_samples *samples,
                                brdffit_model model, const brdffit_params *params, double *error,
                                brdffit_error *err)
{
    if (!ctx || !samples || !error)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_error_of: NULL argument");
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!bf_model_has_lobe(model)) { /* summed directly (affine_pass.c) */
        const brdffit_samples *all = NULL;
        st = bf_affine_all(samples, model, &all, err);
        if (st == BRDFFIT_OK) {
            *error = sqrt(fmax(bf_model_rr(all, model, params), 0.0));
            bf_ok(err);
        }
        return st;
    }
    bf_pass_driver ps;
    st = open_all_samples(&ps, ctx, samples, model, err);
    if (st == BRDFFIT_OK) {
        bf_pass_par pp;
        memset(&pp, 0, sizeof pp);
        memcpy(pp.d, params->d, sizeof pp.d);
        memcpy(pp.s, params->s, sizeof pp.s);
        bf_lambdas(params, pp.lam);
        memcpy(pp.p[0], params->p, sizeof pp.p[0]);
        double mom[BF_NMOM_MAX];
        st = bf_driver_run(&ps, 0, &pp, mom, err);
        if (st == BRDFFIT_OK) {
            double rr = 0.0;
            for (int c = 0; c < 3; c++)
                rr += mom[bf_mom_chan(c, ps.nk, 0) + BF_MC_SEE];
            *error = sqrt(fmax(rr, 0.0));
            bf_ok(err);
        }
    }
    bf_driver_close(&ps);
    return st;
}
