/* SPDX-License-Identifier: MIT */
/* test_metric.c -- the Error metrics (ngan-l2, log, cube-root): each one's
 * value against a loop over the samples written here, a table made by a
 * model fitted back to its parameters under each, no NaN at the models'
 * bounds, names and refusals. */
#define _DEFAULT_SOURCE /* mkdtemp */
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

/* A table made by model m at p, with every 7th bin masked (-1) and every
 * 5th scaled by 1.3 (so that no model fits it exactly), sampled with cutoff. */
static brdffit_samples *table_samples(brdffit_model m, const brdffit_params *p, int perturb,
                                      double cutoff)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_fill_model(t, m, p, BRDFFIT_SCALE_STANDARD, &err) == BRDFFIT_OK,
                  "%s", err.message);
    if (perturb) {
        double *v = brdffit_table_values(t);
        for (size_t b = 0; b < 3 * (size_t)BRDFFIT_MERL_BINS; b++) {
            if (b % 7 == 3)
                v[b] = -1.0;
            else if (b % 5 == 1)
                v[b] *= 1.3;
        }
    }
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.cutoff_deg = cutoff;
    brdffit_samples *s = NULL;
    ck_assert_msg(brdffit_samples_create(t, &so, &s, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
    return s;
}

/* The metric as docs/metrics.md defines it, summed here sample by sample. */
static double direct_error(const brdffit_samples *s, brdffit_model m, const brdffit_params *p,
                           brdffit_metric metric)
{
    size_t n = brdffit_samples_count(s);
    double sum = 0.0, sum_w = 0.0;
    for (size_t i = 0; i < n; i++) {
        brdffit_sample x;
        brdffit_sample_init(&x);
        ck_assert_int_eq(brdffit_samples_get(s, i, &x, NULL), BRDFFIT_OK);
        double f[3];
        ck_assert_int_eq(brdffit_eval(m, p, x.wi, x.wo, f, NULL), BRDFFIT_OK);
        double ci = x.wi[2];
        for (int c = 0; c < 3; c++) {
            double r;
            if (metric == BRDFFIT_METRIC_LOG)
                r = log(1.0 + x.rgb[c] * ci) - log(1.0 + f[c] * ci);
            else if (metric == BRDFFIT_METRIC_CUBE_ROOT)
                r = cbrt(x.rgb[c] + 1e-6) - cbrt(f[c] + 1e-6);
            else
                r = (x.rgb[c] - f[c]) * ci;
            sum += x.weight * r * r;
        }
        sum_w += x.weight;
    }
    return sqrt(sum / (3.0 * sum_w));
}

static brdffit_params ggx_params(void)
{
    brdffit_params p;
    memset(&p, 0, sizeof p);
    const double d[3] = { 0.1, 0.08, 0.05 }, sp[3] = { 0.2, 0.16, 0.15 };
    memcpy(p.d, d, sizeof d);
    memcpy(p.s, sp, sizeof sp);
    p.p[0] = 0.07;
    p.p[1] = 0.05;
    return p;
}

/* Each metric's Error (brdffit_error_metric, and a fit's errors[]) equals
 * the direct sum to 1e-12, on a table with masked and perturbed bins,
 * for a closed-form model, He and glTF. */
START_TEST(metric_values_match_a_direct_sum)
{
    brdffit_context *ctx = make_context();
    brdffit_params truth = ggx_params();
    brdffit_samples *s = table_samples(BRDFFIT_GGX, &truth, 1, 70);
    struct {
        brdffit_model m;
        double p[4];
    } cases[] = {
        { BRDFFIT_COOK_TORRANCE, { 0.1, 0.12 } },
        { BRDFFIT_WARD_DUER, { 0.2 } },
        { BRDFFIT_HE, { 3.0, 0.4, 2.0 } },
        { BRDFFIT_GLTF, { 0.3, 0.4, 1.5, 1.0 } },
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        brdffit_params p = truth;
        memcpy(p.p, cases[k].p, sizeof p.p);
        if (cases[k].m == BRDFFIT_GLTF)
            for (int c = 0; c < 3; c++)
                p.s[c] = 1.0;
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
            double e = -1, want = direct_error(s, cases[k].m, &p, (brdffit_metric)m);
            brdffit_error err;
            ck_assert_msg(brdffit_error_metric(ctx, s, cases[k].m, &p, (brdffit_metric)m, &e,
                                               &err) == BRDFFIT_OK, "%s", err.message);
            ck_assert_msg(tu_reldiff(e, want) < 1e-12, "%s %s: %.17g, direct %.17g",
                          brdffit_model_get(cases[k].m)->name,
                          brdffit_metric_get_name((brdffit_metric)m), e, want);
        }
    }
    brdffit_samples_free(s);
    brdffit_context_free(ctx);
}
END_TEST

/* A fit's errors[] are its parameters' Errors under each metric, the one it
 * minimised its error; an ngan-l2 fit has the others (NaN otherwise) only
 * with all_errors, its parameters and Error the same; a fit under log or
 * cube-root has all three, lower under its metric than the ngan-l2 fit
 * (which it starts from). */
START_TEST(fit_errors_under_every_metric)
{
    brdffit_context *ctx = make_context();
    brdffit_params truth = ggx_params();
    brdffit_samples *s = table_samples(BRDFFIT_GGX, &truth, 1, 70);
    brdffit_fit_result base;
    brdffit_error err;
    brdffit_fit_result_init(&base);
    brdffit_fit_result plain;
    brdffit_fit_result_init(&plain);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_COOK_TORRANCE, NULL, &plain, &err) == BRDFFIT_OK,
                  "%s", err.message);
    ck_assert(plain.errors[0] == plain.error && isnan(plain.errors[1]) && isnan(plain.errors[2]));
    brdffit_fit_options all;
    brdffit_fit_options_default(&all);
    all.all_errors = 1;
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_COOK_TORRANCE, &all, &base, &err) == BRDFFIT_OK,
                  "%s", err.message);
    ck_assert_int_eq(base.metric, BRDFFIT_METRIC_NGAN_L2);
    ck_assert(base.errors[0] == base.error && base.error == plain.error);
    ck_assert(memcmp(&base.params, &plain.params, sizeof base.params) == 0);
    all.all_errors = 2;
    ck_assert_int_eq(brdffit_fit(ctx, s, BRDFFIT_COOK_TORRANCE, &all, &plain, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_msg(strstr(err.message, "all_errors = 2") != NULL, "%s", err.message);
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
        double e;
        ck_assert_int_eq(brdffit_error_metric(ctx, s, BRDFFIT_COOK_TORRANCE, &base.params,
                                              (brdffit_metric)m, &e, &err), BRDFFIT_OK);
        ck_assert_msg(e == base.errors[m], "%d: %.17g vs %.17g", m, e, base.errors[m]);
    }
    for (int m = 1; m < BRDFFIT_METRIC_COUNT; m++) {
        brdffit_fit_options o;
        brdffit_fit_options_default(&o);
        o.metric = m;
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_COOK_TORRANCE, &o, &r, &err) == BRDFFIT_OK,
                      "%s", err.message);
        ck_assert_int_eq(r.metric, m);
        ck_assert(r.error == r.errors[m]);
        ck_assert_msg(r.errors[m] < base.errors[m], "%s: %g not below the ngan-l2 fit's %g",
                      brdffit_metric_get_name((brdffit_metric)m), r.errors[m], base.errors[m]);
        ck_assert(r.errors[0] >= base.errors[0]);
        for (int k = 0; k < BRDFFIT_METRIC_COUNT; k++) {
            double e;
            ck_assert_int_eq(brdffit_error_metric(ctx, s, BRDFFIT_COOK_TORRANCE, &r.params,
                                                  (brdffit_metric)k, &e, &err), BRDFFIT_OK);
            ck_assert_msg(tu_reldiff(e, r.errors[k]) < 1e-12, "%d/%d: %.17g vs %.17g", m, k, e,
                          r.errors[k]);
        }
        ck_assert_int_eq(brdffit_params_check(BRDFFIT_COOK_TORRANCE, &r.params, NULL), BRDFFIT_OK);
    }
    brdffit_samples_free(s);
    brdffit_context_free(ctx);
}
END_TEST

/* A table made by a model is fitted back to the model's parameters under
 * every metric (Error ~0, d, s and the lobe within 1e-3 relative). */
static const struct {
    brdffit_model m;
    double p[4];
} back_cases[] = {
    { BRDFFIT_GGX, { 0.07, 0.05 } },
    { BRDFFIT_WARD, { 0.15 } },
    { BRDFFIT_COOK_TORRANCE, { 0.3, 0.2 } },
    { BRDFFIT_BLINN_PHONG, { 200 } },
};

START_TEST(table_of_a_model_fitted_back)
{
    brdffit_context *ctx = make_context();
    brdffit_model model = back_cases[_i].m;
    brdffit_params truth = ggx_params();
    memcpy(truth.p, back_cases[_i].p, sizeof truth.p);
    brdffit_samples *s = table_samples(model, &truth, 0, 60);
    const brdffit_model_info *mi = brdffit_model_get(model);
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
        brdffit_fit_options o;
        brdffit_fit_options_default(&o);
        o.metric = m;
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        brdffit_error err;
        ck_assert_msg(brdffit_fit(ctx, s, model, &o, &r, &err) == BRDFFIT_OK, "%s", err.message);
        const char *mn = brdffit_metric_get_name((brdffit_metric)m);
        ck_assert_msg(r.error < 1e-6, "%s/%s: Error %g", mi->name, mn, r.error);
        for (int c = 0; c < 3; c++) {
            ck_assert_msg(tu_reldiff(r.params.d[c], truth.d[c]) < 1e-3, "%s/%s d[%d] %.8g vs %.8g",
                          mi->name, mn, c, r.params.d[c], truth.d[c]);
            ck_assert_msg(tu_reldiff(r.params.s[c], truth.s[c]) < 1e-3, "%s/%s s[%d] %.8g vs %.8g",
                          mi->name, mn, c, r.params.s[c], truth.s[c]);
        }
        for (int k = 0; k < mi->nparams; k++)
            ck_assert_msg(tu_reldiff(r.params.p[k], truth.p[k]) < 1e-3, "%s/%s p[%d] %.8g vs %.8g",
                          mi->name, mn, k, r.params.p[k], truth.p[k]);
    }
    brdffit_samples_free(s);
    brdffit_context_free(ctx);
}
END_TEST

/* Every model with every lobe parameter at its lower, then its upper bound,
 * d and s at 0, then large: a finite Error under every metric. */
START_TEST(bounds_never_nan)
{
    brdffit_context *ctx = make_context();
    brdffit_params truth = ggx_params();
    brdffit_samples *s = table_samples(BRDFFIT_GGX, &truth, 1, 45);
    for (int k = 0; k < brdffit_model_count(); k++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)k);
        for (int end = 0; end < 2; end++) {
            brdffit_params p;
            memset(&p, 0, sizeof p);
            for (int j = 0; j < mi->nparams; j++)
                p.p[j] = end ? mi->params[j].upper : mi->params[j].lower;
            for (int c = 0; c < 3; c++) {
                p.d[c] = mi->colour_form == BRDFFIT_COLOUR_GLTF ? end : end * 1e3;
                p.s[c] = mi->colour_form == BRDFFIT_COLOUR_GLTF ? 1.0 : end * 1e3;
            }
            for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
                double e = NAN;
                brdffit_error err;
                brdffit_status st = brdffit_error_metric(ctx, s, (brdffit_model)k, &p,
                                                         (brdffit_metric)m, &e, &err);
                if (st == BRDFFIT_E_PARAM_RANGE)
                    continue; /* a direction pair off its unit norm (Lafortune) */
                ck_assert_msg(st == BRDFFIT_OK, "%s: %s", mi->name, err.message);
                ck_assert_msg(isfinite(e) && e >= 0, "%s at its %s bounds, %s: %g", mi->name,
                              end ? "upper" : "lower", brdffit_metric_get_name((brdffit_metric)m),
                              e);
            }
        }
    }
    brdffit_samples_free(s);
    brdffit_context_free(ctx);
}
END_TEST

/* Names both ways; an unknown name or number refused with a message. */
START_TEST(names_and_refusals)
{
    const char *names[] = { "ngan-l2", "log", "cube-root" };
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
        ck_assert_str_eq(brdffit_metric_get_name((brdffit_metric)m), names[m]);
        brdffit_metric got = (brdffit_metric)-1;
        ck_assert_int_eq(brdffit_metric_from_name(names[m], &got, NULL), BRDFFIT_OK);
        ck_assert_int_eq(got, m);
    }
    brdffit_metric got;
    ck_assert_int_eq(brdffit_metric_from_name("CUBE_ROOT", &got, NULL), BRDFFIT_OK);
    ck_assert_int_eq(got, BRDFFIT_METRIC_CUBE_ROOT);
    ck_assert_ptr_null(brdffit_metric_get_name((brdffit_metric)3));
    brdffit_error err;
    ck_assert_int_eq(brdffit_metric_from_name("l2", &got, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_msg(strstr(err.message, "ngan-l2, log, cube-root"), "%s", err.message);
    ck_assert_str_eq(brdffit_metric_name(), "ngan-l2");

    brdffit_context *ctx = make_context();
    brdffit_params truth = ggx_params();
    brdffit_samples *s = table_samples(BRDFFIT_GGX, &truth, 0, 30);
    brdffit_fit_options o;
    brdffit_fit_options_default(&o);
    ck_assert_int_eq(o.metric, BRDFFIT_METRIC_NGAN_L2);
    o.metric = 3;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_int_eq(brdffit_fit(ctx, s, BRDFFIT_GGX, &o, &r, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_msg(strstr(err.message, "metric = 3"), "%s", err.message);
    double e;
    ck_assert_int_eq(brdffit_error_metric(ctx, s, BRDFFIT_GGX, &truth, (brdffit_metric)-1, &e, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_samples_free(s);
    brdffit_context_free(ctx);
}
END_TEST

/* The program: --metric picks the metric of fit, its JSON record carries
 * the Errors under all three (its metric's its Error), the text names it. */
START_TEST(cli_metric_records)
{
    char args[1024];
    snprintf(args, sizeof args, "fit '%s' --model ward --starts 1 --cutoff 40 --metric log --json",
             tu_table_fixture());
    tu_run_out r = tu_run_cli("", args);
    TU_EXPECT_STATUS(r, 0, args);
    ck_assert_msg(strstr(r.out, "\"metric\":\"log\""), "%s", r.out);
    const char *e = strstr(r.out, "\"error\":"), *es = strstr(r.out, "\"errors\":{\"ngan-l2\":");
    ck_assert_msg(e && es, "%s", r.out);
    double err1 = strtod(e + 8, NULL);
    const char *lg = strstr(es, "\"log\":");
    ck_assert_ptr_nonnull(lg);
    ck_assert(err1 == strtod(lg + 6, NULL));
    ck_assert_ptr_nonnull(strstr(es, "\"cube-root\":"));
    tu_run_free(&r);
    snprintf(args, sizeof args, "fit '%s' --model ward --starts 1 --cutoff 40 --metric cube-root",
             tu_table_fixture());
    r = tu_run_cli("", args);
    TU_EXPECT_STATUS(r, 0, args);
    ck_assert_msg(strstr(r.out, "metric cube-root") && strstr(r.out, "Error = cube-root"), "%s",
                  r.out);
    tu_run_free(&r);
}
END_TEST

/* batch --metric all: three reports, OUT/METRIC, each's records of its
 * metric with the Errors under all three; fit and score refuse all. */
START_TEST(cli_batch_all_metrics)
{
    char dir[] = "/tmp/brdffit-metric-XXXXXX", args[2048], path[1200];
    ck_assert_ptr_nonnull(mkdtemp(dir));
    snprintf(args, sizeof args,
             "batch '%s' --out '%s/o' --model ward --starts 1 --cutoff 40 --metric all "
             "--no-render --no-plot --quiet", tu_table_fixture(), dir);
    tu_run_out r = tu_run_cli("", args);
    TU_EXPECT_STATUS(r, 0, args);
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
        const char *name = brdffit_metric_get_name((brdffit_metric)m);
        snprintf(path, sizeof path, "%s/o/%s/index.html", dir, name);
        ck_assert_msg(strstr(r.out, path), "%s not in\n%s", path, r.out);
        char *html = tu_slurp(path);
        ck_assert_ptr_nonnull(html);
        ck_assert_msg(strstr(html, "median Error") && strstr(html, name), "%s", path);
        free(html);
        snprintf(path, sizeof path, "%s/o/%s/journal.jsonl", dir, name);
        char *j = tu_slurp(path), want[64];
        ck_assert_ptr_nonnull(j);
        snprintf(want, sizeof want, "\"metric\":\"%s\"", name);
        ck_assert_msg(strstr(j, want) && strstr(j, "\"errors\":{\"ngan-l2\":"), "%s", j);
        free(j);
    }
    snprintf(path, sizeof path, "%s/o/index.html", dir);
    ck_assert_msg(strstr(r.out, path), "%s not in\n%s", path, r.out);
    char *top = tu_slurp(path);
    ck_assert_ptr_nonnull(top);
    ck_assert_msg(strstr(top, "<td>ward</td>") && strstr(top, "href=\"log/index.html\"") &&
                      strstr(top, "src=\"cube-root/headline.svg\""),
                  "%s", top);
    free(top);
    tu_run_free(&r);
    ck_assert_int_eq(tu_remove_tree(dir), 0);
    const char *refused[] = { "fit", "score" };
    for (int k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "%s '%s' --model ward --metric all%s", refused[k],
                 tu_table_fixture(), k ? " --params 0.1,0.1,0.1,0.1,0.1,0.1,0.1" : "");
        r = tu_run_cli("", args);
        TU_EXPECT_STATUS(r, 2, args);
        ck_assert_msg(strstr(r.err, "--metric all is batch's"), "%s", r.err);
        tu_run_free(&r);
    }
}
END_TEST

static void fixture_up(void)
{
    tu_table_fixture_make();
}

static void fixture_down(void)
{
    tu_table_fixture_remove();
}

Suite *metric_suite(void)
{
    Suite *s = suite_create("metric");
    TCase *tc = tcase_create("metric");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, metric_values_match_a_direct_sum);
    tcase_add_test(tc, fit_errors_under_every_metric);
    tcase_add_loop_test(tc, table_of_a_model_fitted_back, 0,
                        (int)(sizeof back_cases / sizeof back_cases[0]));
    tcase_add_test(tc, bounds_never_nan);
    tcase_add_test(tc, names_and_refusals);
    suite_add_tcase(s, tc);
    TCase *cli = tcase_create("metric_cli");
    tcase_set_timeout(cli, 600);
    tcase_add_unchecked_fixture(cli, fixture_up, fixture_down);
    tcase_add_test(cli, cli_metric_records);
    tcase_add_test(cli, cli_batch_all_metrics);
    suite_add_tcase(s, cli);
    return s;
}
