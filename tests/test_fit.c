/* SPDX-License-Identifier: MIT */
/* test_fit.c -- acceptance of brdffit_fit: recovery of known parameters, the
 * published Ngan et al. fits as a bar to clear, degenerate data, bad input. */
#define _DEFAULT_SOURCE /* M_PI */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static brdffit_context *make_context(void)
{
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_AUTO, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    return ctx;
}

static brdffit_samples *samples_of(brdffit_table *t, brdffit_scale scale)
{
    brdffit_error err;
    brdffit_samples *s = NULL;
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.scale = scale;
    ck_assert_msg(brdffit_samples_create(t, &so, &s, &err) == BRDFFIT_OK, "%s", err.message);
    return s;
}

/* The flat-scale sample set of a ../shared/tools/merl-table material. */
static brdffit_samples *merl_samples(const char *material)
{
    brdffit_error err;
    brdffit_samples *s = NULL;
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.scale = BRDFFIT_SCALE_FLAT;
    ck_assert_msg(tu_merl_samples(material, &so, &s, &err) == BRDFFIT_OK, "%s", err.message);
    return s;
}

static void assert_finite_result(const brdffit_fit_result *r)
{
    ck_assert(isfinite(r->error) && r->error >= 0);
    for (int c = 0; c < 3; c++)
        ck_assert(isfinite(r->params.d[c]) && r->params.d[c] >= 0 && isfinite(r->params.s[c]) &&
                  r->params.s[c] >= 0);
    const brdffit_model_info *mi = brdffit_model_get(r->model);
    for (int k = 0; k < mi->nparams; k++)
        ck_assert_msg(r->params.p[k] >= mi->params[k].lower && r->params.p[k] <= mi->params[k].upper,
                      "%s: %s = %g out of bounds", mi->name, mi->params[k].name, r->params.p[k]);
    ck_assert_int_eq(brdffit_params_check(r->model, &r->params, NULL), BRDFFIT_OK);
}

/* The sample set of a table made by model m at truth (standard scale), and
 * the data's RMS in the metric (the Error of d = s = 0).  The fit's Error of
 * truth itself is checked to be ~0 (the table's round trip through 1/scale). */
static brdffit_samples *model_samples(brdffit_context *ctx, brdffit_model m,
                                      const brdffit_params *truth, double *rms)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_fill_model(t, m, truth, BRDFFIT_SCALE_STANDARD, &err) == BRDFFIT_OK,
                  "%s", err.message);
    brdffit_samples *s = samples_of(t, BRDFFIT_SCALE_STANDARD);
    brdffit_table_free(t);
    /* the data's RMS: the Error of f = 0, Ward's at d = s = 0 (a glTF
     * material is never 0) */
    brdffit_params zero = *truth;
    memset(zero.d, 0, sizeof zero.d);
    memset(zero.s, 0, sizeof zero.s);
    tu_start_params(BRDFFIT_WARD, zero.p);
    double e_truth = 1;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_WARD, &zero, rms, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_error_of(ctx, s, m, truth, &e_truth, &err), BRDFFIT_OK);
    ck_assert_msg(*rms > 0 && e_truth <= 1e-10 * *rms, "truth Error %g of rms %g", e_truth, *rms);
    return s;
}

/* Fit model m to s (made at truth): a finite result, Error below 1e-6 of the
 * data's RMS, and d, s within 1e-3 relative.  The lobe parameters are the
 * caller's to check. */
static brdffit_fit_result fit_recovered(brdffit_context *ctx, const brdffit_samples *s,
                                        brdffit_model m, const brdffit_params *truth, double rms,
                                        const char *material)
{
    const char *name = brdffit_model_get(m)->name;
    brdffit_error err;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, m, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
    assert_finite_result(&r);
    ck_assert_msg(r.error < 1e-6 * rms, "%s/%s: Error %g, rms %g", material, name, r.error, rms);
    for (int c = 0; c < 3; c++) {
        ck_assert_msg(tu_reldiff(r.params.d[c], truth->d[c]) < 1e-3, "%s/%s d[%d] %.6g vs %.6g", material,
                      name, c, r.params.d[c], truth->d[c]);
        ck_assert_msg(tu_reldiff(r.params.s[c], truth->s[c]) < 1e-3, "%s/%s s[%d] %.6g vs %.6g", material,
                      name, c, r.params.s[c], truth->s[c]);
    }
    return r;
}

/* ---------------------------------------------------------------- recovery */

/* The closed-form models of the registry (He has its own tests below), in id order. */
static int closed_form(brdffit_model *out)
{
    int n = 0;
    for (int m = 0; m < brdffit_model_count(); m++)
        if (!brdffit_model_get((brdffit_model)m)->chromatic)
            out[n++] = (brdffit_model)m;
    return n;
}

static const char *const recovery_materials[] = { "alum-bronze", "blue-rubber" };
#define NRECOVERY (int)(sizeof recovery_materials / sizeof recovery_materials[0])

/* A table made by a model at published parameters fits back: Error below
 * 1e-6 of the data's RMS, parameters within 1e-3 relative (a direction pair:
 * its ratio and its scale 2a^2 + b^2 = 1), from the default starts.  A model
 * the paper did not fit is made at its registry start values with the
 * material's Ward d and s. */
START_TEST(recovery)
{
    brdffit_model ms[BRDFFIT_MODEL_COUNT];
    int nclosed = closed_form(ms);
    brdffit_model m = ms[_i % nclosed];
    const char *material = recovery_materials[_i / nclosed];
    const brdffit_model_info *mi = brdffit_model_get(m);
    brdffit_params truth;
    if (!tu_published(material, m, &truth)) {
        ck_assert(tu_published(material, BRDFFIT_WARD, &truth));
        tu_start_params(m, truth.p);
    }
    if (mi->colour_form != BRDFFIT_COLOUR_DS) {
        /* a glTF or OpenPBR material: Ward's d as the base colour (within
         * [0, 1]), a white specular colour (the core glTF material's, what
         * the OpenPBR fit holds), part metal */
        for (int c = 0; c < 3; c++) {
            truth.d[c] = fmin(4 * truth.d[c], 1.0);
            truth.s[c] = 1.0;
        }
        truth.p[0] = 0.4; /* part metal */
    }
    brdffit_context *ctx = make_context();
    double rms;
    brdffit_samples *s = model_samples(ctx, m, &truth, &rms);

    brdffit_fit_result r = fit_recovered(ctx, s, m, &truth, rms, material);
    for (int k = 0; k < mi->nparams; k++) {
        const double *q = r.params.p, *t = truth.p;
        if (mi->params[k].map == BRDFFIT_MAP_DIRECTION) {
            ck_assert_msg(tu_reldiff(q[k] / q[k + 1], t[k] / t[k + 1]) < 1e-3, "%s/%s %s/%s %.6g vs %.6g",
                          material, mi->name, mi->params[k].name, mi->params[k + 1].name,
                          q[k] / q[k + 1], t[k] / t[k + 1]);
            ck_assert(fabs(2 * q[k] * q[k] + q[k + 1] * q[k + 1] - 1) < 1e-12);
            k++;
            continue;
        }
        ck_assert_msg(tu_reldiff(q[k], t[k]) < 1e-3, "%s/%s %s %.6g vs %.6g", material, mi->name,
                      mi->params[k].name, q[k], t[k]);
    }
    ck_assert(r.cminpack_info >= 1 && r.cminpack_info <= 4);
    ck_assert(r.passes > 0 && r.iterations > 0 && r.seconds > 0);
    ck_assert_int_eq(r.samples, brdffit_samples_count(s));
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* ---------------------------------------------------------------- the paper */

static const char *const paper_materials[] = {
    "alum-bronze", "blue-rubber", "gold-metallic-paint", "green-metallic-paint2",
};

/* On real-shaped tables, with the data Ngan et al. fitted (flat scale), the
 * fitted Error is no worse than the Error of their published parameters on
 * the same table with the same metric. */
START_TEST(beats_published)
{
    const char *material = paper_materials[_i];
    brdffit_error err;
    brdffit_samples *s = merl_samples(material);
    brdffit_context *ctx = make_context();
    brdffit_model ms[BRDFFIT_MODEL_COUNT];
    int nclosed = closed_form(ms), compared = 0;
    for (int i = 0; i < nclosed; i++) {
        brdffit_model m = ms[i];
        brdffit_params pub;
        if (!tu_published(material, m, &pub))
            continue; /* a model the paper did not fit */
        compared++;
        double e_pub;
        ck_assert_msg(brdffit_error_of(ctx, s, m, &pub, &e_pub, &err) == BRDFFIT_OK, "%s", err.message);
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        ck_assert_msg(brdffit_fit(ctx, s, m, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
        assert_finite_result(&r);
        ck_assert_msg(r.error <= e_pub, "%s/%s: fitted Error %.6g > published %.6g", material,
                      brdffit_model_get(m)->name, r.error, e_pub);
    }
    ck_assert_int_eq(compared, 6); /* the paper fitted six closed-form models */
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* ---------------------------------------------------------------- degenerate data */

enum { DATA_ZERO, DATA_LAMBERT, DATA_ONE_BIN, DATA_KINDS };

START_TEST(degenerate_data)
{
    int kind = _i / brdffit_model_count();
    brdffit_model m = (brdffit_model)(_i % brdffit_model_count());
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    double *v = brdffit_table_values(t);
    if (kind == DATA_LAMBERT) {
        brdffit_params lam = { { 0.3, 0.2, 0.1 }, { 0, 0, 0 }, { 0.1, 0, 0 }, { 0 } };
        ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_WARD, &lam, BRDFFIT_SCALE_STANDARD, &err),
                         BRDFFIT_OK);
    } else if (kind == DATA_ONE_BIN) {
        size_t b = brdffit_bin_index(10, 20, 30);
        for (int c = 0; c < 3; c++)
            v[c * (size_t)BRDFFIT_MERL_BINS + b] = 500.0;
    }
    brdffit_samples *s = samples_of(t, BRDFFIT_SCALE_STANDARD);
    brdffit_context *ctx = make_context();
    brdffit_fit_options fo;
    brdffit_fit_options_default(&fo);
    fo.starts = 3;
    fo.refine = 1;
    fo.max_evals = 60;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, m, &fo, &r, &err) == BRDFFIT_OK, "%s", err.message);
    assert_finite_result(&r);
    /* zero and Lambertian data are a d/pi + s K model's at s = 0, and a glTF
     * model's at specular factor 0 and metallic 0 where its bounds let it
     * (gltf-ext; the core material always has its specular) */
    const brdffit_model_info *mi = brdffit_model_get(m);
    const int has_lambert = mi->colour_form == BRDFFIT_COLOUR_DS ||
                            (mi->colour_form == BRDFFIT_COLOUR_GLTF && mi->params[3].lower == 0);
    /* OpenPBR's dielectric at specular_ior 1 has no lobe, but its diffuse
     * keeps the albedo scaling 1 - E(N.V), E > 0: zero data only */
    const int has_zero = has_lambert || mi->colour_form == BRDFFIT_COLOUR_OPENPBR;
    if (kind == DATA_ZERO && has_zero)
        ck_assert_msg(r.error < 1e-12, "all-zero data: Error %g", r.error);
    if (kind == DATA_LAMBERT && has_lambert) {
        ck_assert_msg(r.error < 1e-6 * 0.3 / M_PI, "Lambertian data: Error %g", r.error);
        ck_assert_msg(fabs(r.params.d[0] - 0.3) < 1e-4, "d_r %g", r.params.d[0]);
    }
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* ---------------------------------------------------------------- bad input */

START_TEST(bad_arguments)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    brdffit_samples *s = samples_of(t, BRDFFIT_SCALE_STANDARD);
    brdffit_context *ctx = make_context();
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    brdffit_fit_options fo;
    brdffit_fit_options_default(&fo);
    ck_assert_int_eq(brdffit_fit(NULL, s, BRDFFIT_WARD, NULL, &r, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_fit(ctx, NULL, BRDFFIT_WARD, NULL, &r, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_fit(ctx, s, BRDFFIT_WARD, NULL, NULL, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_fit(ctx, s, (brdffit_model)77, NULL, &r, &err), BRDFFIT_E_UNKNOWN_MODEL);
    fo.starts = -1;
    ck_assert_int_eq(brdffit_fit(ctx, s, BRDFFIT_WARD, &fo, &r, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_nonnull(strstr(err.message, "starts"));
    brdffit_fit_options_default(&fo);
    fo.ftol = NAN;
    ck_assert_int_eq(brdffit_fit(ctx, s, BRDFFIT_WARD, &fo, &r, &err), BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_fit_options_default(&fo);
    fo.lambda_um[1] = -1;
    ck_assert_int_eq(brdffit_fit(ctx, s, BRDFFIT_HE, &fo, &r, &err), BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_params p = { { 0.1, 0.1, 0.1 }, { 0.1, 0.1, 0.1 }, { NAN, 0, 0 }, { 0 } };
    double e = -1;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_WARD, &p, &e, &err), BRDFFIT_E_PARAM_RANGE);
    ck_assert(e == -1); /* untouched */
    p.p[0] = 0.1;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_WARD, &p, &e, &err), BRDFFIT_OK);
    ck_assert(e > 0 && isfinite(e));
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST


/* ---------------------------------------------------------------- He */

/* Recovery from a table the He model made.  Smooth surface (alum-bronze's
 * published fit): tau, sigma0, n, d, s all come back.  Rough surface
 * (blue-rubber's): where g >= 19 on every sample, the rough-surface limit makes
 * K depend on tau and sigma0 only through tau/sigma0 (D ~ (tau/sigma)^2
 * e^(-a/g) with a/g ~ (tau/sigma)^2; S and sigma/sigma0 depend on tau/sigma0),
 * so only that ratio is identifiable: the test checks the ratio, n, d, s and
 * the Error, and that scaling (tau, sigma0) leaves the Error at ~0. */
START_TEST(he_recovery)
{
    const char *material = _i == 0 ? "blue-rubber" : "alum-bronze";
    brdffit_params truth;
    ck_assert(tu_published(material, BRDFFIT_HE, &truth));
    brdffit_error err;
    brdffit_context *ctx = make_context();
    double rms;
    brdffit_samples *s = model_samples(ctx, BRDFFIT_HE, &truth, &rms);
    brdffit_fit_result r = fit_recovered(ctx, s, BRDFFIT_HE, &truth, rms, material);
    static const char *const names[3] = { "tau", "sigma0", "n" };
    if (_i == 1) {
        for (int k = 0; k < 3; k++)
            ck_assert_msg(tu_reldiff(r.params.p[k], truth.p[k]) < 1e-3, "he/%s %s %.6g vs %.6g", material,
                          names[k], r.params.p[k], truth.p[k]);
    } else {
        ck_assert_msg(tu_reldiff(r.params.p[0] / r.params.p[1], truth.p[0] / truth.p[1]) < 1e-3,
                      "he/%s tau/sigma0 %.6g vs %.6g", material, r.params.p[0] / r.params.p[1],
                      truth.p[0] / truth.p[1]);
        ck_assert_msg(tu_reldiff(r.params.p[2], truth.p[2]) < 1e-3, "he/%s n %.6g vs %.6g", material,
                      r.params.p[2], truth.p[2]);
        brdffit_params scaled = truth;
        scaled.p[0] *= 0.5;
        scaled.p[1] *= 0.5;
        double e_scaled;
        ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_HE, &scaled, &e_scaled, &err), BRDFFIT_OK);
        ck_assert_msg(e_scaled < 1e-10 * rms, "rough he: (tau, sigma0)/2 gives Error %g of rms %g", e_scaled,
                      rms);
    }
    for (int c = 0; c < 3; c++)
        ck_assert(r.params.lambda_um[c] > 0.4 && r.params.lambda_um[c] < 0.7);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* A He fit of s (material names it in messages) with `starts` starts (0: the
 * model's default): it succeeds and its result is finite and in bounds. */
static brdffit_fit_result fit_he(brdffit_context *ctx, const brdffit_samples *s,
                                 const char *material, int starts)
{
    brdffit_error err;
    brdffit_fit_options o;
    brdffit_fit_options_default(&o);
    o.starts = starts;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_HE, &o, &r, &err) == BRDFFIT_OK, "he/%s: %s", material,
                  err.message);
    assert_finite_result(&r);
    return r;
}

/* On the alum-bronze and blue-rubber tables (flat scale) the fitted He Error
 * is no worse than that of the published He parameters. */
START_TEST(he_beats_published)
{
    const char *material = _i == 0 ? "alum-bronze" : "blue-rubber";
    brdffit_error err;
    brdffit_samples *s = merl_samples(material);
    brdffit_context *ctx = make_context();
    brdffit_params pub;
    ck_assert(tu_published(material, BRDFFIT_HE, &pub));
    double e_pub;
    ck_assert_msg(brdffit_error_of(ctx, s, BRDFFIT_HE, &pub, &e_pub, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_fit_result r = fit_he(ctx, s, material, 0);
    ck_assert_msg(r.error <= e_pub, "he/%s: fitted Error %.6g > published %.6g", material, r.error, e_pub);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* Every published He row gives finite values on every valid sample of a
 * table: a data pass sums f over all of them and refuses a non-finite sum. */
START_TEST(he_published_rows_finite)
{
    brdffit_error err;
    brdffit_samples *s = merl_samples("chrome");
    brdffit_context *ctx = make_context();
    static brdffit_params rows[128];
    static char names[128][64];
    int n = tu_published_all(BRDFFIT_HE, rows, names, 128);
    ck_assert_int_eq(n, 86);
    for (int r = 0; r < n; r++) {
        double e = NAN;
        ck_assert_msg(brdffit_error_of(ctx, s, BRDFFIT_HE, &rows[r], &e, &err) == BRDFFIT_OK, "%s: %s",
                      names[r], err.message);
        ck_assert_msg(isfinite(e) && e > 0, "%s: Error %g", names[r], e);
    }
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* The starts of a smaller count are among those of a larger one, so more
 * starts should not give a worse fit (though only the kept starts within
 * SUBSET_MARGIN of the lowest subset Error go on to all samples, so this is
 * measured, not guaranteed); on these two tables they do not.  42 starts
 * reach the sixth sigma0 round, 30 (the upper bound), where two faults can
 * arise.  On ipswich-pine-221 the start tau = 4, sigma0 = 30 can lead LM to
 * a point whose r^T r the pass's moments put at 0 by cancellation (the
 * reference's s ~1e5 times the data's), and that point would win: an Error
 * 5.8 times the 14 starts'.  On green-fabric lmder can carry a coordinate to
 * u ~ 1e8, where a difference step relative to |u| would overflow He's
 * carried neighbour and fail the fit. */
START_TEST(he_more_starts_no_worse)
{
    const char *material = _i == 0 ? "ipswich-pine-221" : "green-fabric";
    brdffit_error err;
    brdffit_samples *s = merl_samples(material);
    brdffit_context *ctx = make_context();
    brdffit_fit_result rd = fit_he(ctx, s, material, 0), r42 = fit_he(ctx, s, material, 42);
    ck_assert_msg(r42.error <= rd.error * (1 + 1e-12),
                  "he/%s: 42 starts Error %.12g > the default starts' %.12g", material, r42.error,
                  rd.error);
    double e42;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_HE, &r42.params, &e42, &err), BRDFFIT_OK);
    ck_assert_msg(e42 == r42.error, "reported %.17g, scored %.17g", r42.error, e42);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* The Error of material / model in the stored run (bench/baseline-errors.tsv:
 * material, model, Error, ... per line), or -1. */
static double stored_error(const char *material, const char *model)
{
    FILE *f = fopen("bench/baseline-errors.tsv", "r");
    ck_assert_msg(f != NULL, "bench/baseline-errors.tsv: cannot open (run from the checkout)");
    char line[512], mat[128], mod[64];
    double e = -1.0, v;
    while (e < 0 && fgets(line, sizeof line, f))
        if (line[0] != '#' && sscanf(line, "%127[^\t]\t%63[^\t]\t%lf", mat, mod, &v) == 3 &&
            strcmp(mat, material) == 0 && strcmp(mod, model) == 0)
            e = v;
    fclose(f);
    return e;
}

/* Two He fits that need the start grid's third sigma0 round (pickled-oak-260:
 * its minimum at tau ~ 1, sigma0 ~ 0.012, 8% below the stored run) and the
 * polish's tighter tolerances (blue-metallic-paint: the stored run's minimum,
 * 1.3e-10 below it here; with the caller's tolerances 2.6e-8 above) to come
 * to the stored run reach it or go below.  blue-metallic-paint gets 1e-8 of
 * room: nearby minima along He's valley differ by ~1e-9, and another CPU's
 * vector code may settle in a neighbour.  black-soft-plastic's tau
 * ends on its lower bound: there the fit holds tau on the bound for a last
 * run (with the bound restart on the subset alone and no such run, it would
 * end 6.1e-6 above the stored run), so tau is the bound exactly. */
static const char *const stored_cases[] = { "pickled-oak-260", "blue-metallic-paint",
                                            "black-soft-plastic" };

START_TEST(he_at_or_below_stored_run)
{
    const char *material = stored_cases[_i];
    const double room = _i == 1 ? 1e-8 : 1e-9;
    double stored = stored_error(material, "he");
    ck_assert_msg(stored > 0, "%s/he: not in bench/baseline-errors.tsv", material);
    brdffit_samples *s = merl_samples(material);
    brdffit_context *ctx = make_context();
    brdffit_fit_result r = fit_he(ctx, s, material, 0);
    ck_assert_msg(r.error <= stored * (1 + room), "he/%s: Error %.12g above the stored run's %.12g",
                  material, r.error, stored);
    if (_i == 2) {
        double lower = brdffit_model_get(BRDFFIT_HE)->params[0].lower;
        ck_assert_msg((r.at_bound & BRDFFIT_AT_BOUND_P0) && r.params.p[0] == lower,
                      "he/%s: tau %.17g, its bound %.17g (at_bound 0x%x)", material, r.params.p[0],
                      lower, r.at_bound);
    }
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

Suite *fit_suite(void)
{
    Suite *s = suite_create("fit");
    TCase *tr = tcase_create("recovery");
    tcase_set_timeout(tr, 300);
    tcase_set_tags(tr, TU_NEEDS_SHARED);
    brdffit_model ms[BRDFFIT_MODEL_COUNT];
    tcase_add_loop_test(tr, recovery, 0, NRECOVERY * closed_form(ms));
    suite_add_tcase(s, tr);
    TCase *tp = tcase_create("paper");
    tcase_set_timeout(tp, 600);
    tcase_set_tags(tp, TU_NEEDS_SHARED);
    tcase_add_loop_test(tp, beats_published, 0, (int)(sizeof paper_materials / sizeof paper_materials[0]));
    suite_add_tcase(s, tp);
    TCase *td = tcase_create("degenerate");
    tcase_set_timeout(td, 300);
    tcase_add_loop_test(td, degenerate_data, 0, DATA_KINDS * brdffit_model_count());
    tcase_add_test(td, bad_arguments);
    suite_add_tcase(s, td);
    TCase *th = tcase_create("he");
    tcase_set_timeout(th, 900);
    tcase_set_tags(th, TU_NEEDS_SHARED);
    tcase_add_loop_test(th, he_recovery, 0, 2);
    tcase_add_loop_test(th, he_beats_published, 0, 2);
    tcase_add_test(th, he_published_rows_finite);
    tcase_add_loop_test(th, he_more_starts_no_worse, 0, 2);
    tcase_add_loop_test(th, he_at_or_below_stored_run, 0,
                        (int)(sizeof stored_cases / sizeof stored_cases[0]));
    suite_add_tcase(s, th);
    return s;
}
