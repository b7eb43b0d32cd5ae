/* SPDX-License-Identifier: MIT */
/* test_fidelity.c -- the fit's bounds and limits: every published parameter
 * inside the bounds, a parameter stuck on its bound is flagged (library and
 * program), a channel whose true d is 0 fits back without stalling. */
#define _DEFAULT_SOURCE /* M_PI */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { MAX_ROWS = 128 };

/* Margin a log-scale bound keeps from every published value. */
#define LOG_MARGIN 1.5

/* Every published parameter of every model lies inside the model's bounds
 * (brdffit_params_check accepts the row), log-scale parameters with a factor
 * LOG_MARGIN to spare from both bounds.  A lower bound that is the
 * parameter's physical limit cannot be cleared: He's refractive index n >= 1
 * (n = 1: no Fresnel reflection; the paper prints 1.0 for some materials). */
static int physical_lower_limit(brdffit_model m, int k)
{
    return m == BRDFFIT_HE && k == 2;
}

START_TEST(bounds_admit_published)
{
    brdffit_model m = (brdffit_model)_i;
    const brdffit_model_info *mi = brdffit_model_get(m);
    static brdffit_params rows[MAX_ROWS];
    static char names[MAX_ROWS][64];
    int n = tu_published_all(m, rows, names, MAX_ROWS);
    if (_i == 0) { /* the paper fitted seven of the registry's models */
        int fitted = 0;
        for (int k = 0; k < brdffit_model_count(); k++)
            fitted += tu_published_all((brdffit_model)k, rows, names, MAX_ROWS) > 0;
        ck_assert_int_eq(fitted, 7);
        n = tu_published_all(m, rows, names, MAX_ROWS);
    }
    if (n == 0)
        return; /* a model the paper did not fit (ggx): no published rows to check */
    ck_assert_msg(n >= 80, "%s: %d published rows (../shared/data/ngan2005-fits.tsv)", mi->name, n);
    for (int r = 0; r < n; r++) {
        brdffit_error err;
        ck_assert_msg(brdffit_params_check(m, &rows[r], &err) == BRDFFIT_OK, "%s/%s: %s", names[r],
                      mi->name, err.message);
        for (int k = 0; k < mi->nparams; k++) {
            double v = rows[r].p[k], lo = mi->params[k].lower, hi = mi->params[k].upper;
            int log_scale = mi->params[k].map == BRDFFIT_MAP_LOG;
            if (!log_scale)
                continue;
            ck_assert_msg(physical_lower_limit(m, k) || v >= LOG_MARGIN * lo, "%s/%s: %s = %g too near the lower bound %g",
                          names[r], mi->name, mi->params[k].name, v, lo);
            ck_assert_msg(v <= hi / LOG_MARGIN, "%s/%s: %s = %g too near the upper bound %g", names[r],
                          mi->name, mi->params[k].name, v, hi);
        }
    }
}
END_TEST

static brdffit_context *make_context(void)
{
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(brdffit_context_create(NULL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    return ctx;
}

static brdffit_samples *samples_of(const brdffit_table *t)
{
    brdffit_error err;
    brdffit_samples *s = NULL;
    ck_assert_msg(brdffit_samples_create(t, NULL, &s, &err) == BRDFFIT_OK, "%s", err.message);
    return s;
}

/* A table of Ward's formula (written out here), no diffuse term, at an alpha
 * beyond the bounds: s exp(-tan^2 delta / a^2) / (4 pi a^2 sqrt(cos ti cos to)). */
static brdffit_table *wide_ward_table(double alpha)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    double *v = brdffit_table_values(t), f[3];
    static const double d[3] = { 0, 0, 0 }, s[3] = { 0.3, 0.25, 0.2 }, scale[3] = {
        1.0 / 1500, 1.15 / 1500, 1.66 / 1500
    };
    for (int i = 0; i < BRDFFIT_MERL_NTH; i++)
        for (int j = 0; j < BRDFFIT_MERL_NTD; j++)
            for (int k = 0; k < BRDFFIT_MERL_NPD; k++) {
                double wi[3], wo[3];
                size_t b = brdffit_bin_index(i, j, k);
                ck_assert_int_eq(brdffit_bin_directions(i, j, k, wi, wo, NULL), BRDFFIT_OK);
                int above = wi[2] > 0 && wo[2] > 0;
                double h[3] = { wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2] };
                double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]), ch = h[2] / hl;
                double tan2 = (1.0 - ch * ch) / (ch * ch);
                double K = above ? exp(-tan2 / (alpha * alpha)) /
                                       (4 * M_PI * alpha * alpha * sqrt(wi[2] * wo[2]))
                                 : 0.0;
                for (int c = 0; c < 3; c++) {
                    f[c] = d[c] / M_PI + s[c] * K;
                    v[c * (size_t)BRDFFIT_MERL_BINS + b] = above ? f[c] / scale[c] : -1.0;
                }
            }
    return t;
}

/* Data whose optimum lies far beyond a parameter's bound: the fit ends on
 * the bound and says so (at_bound names the parameter), and the program's
 * JSON and table output say which parameter. */
START_TEST(bound_is_flagged)
{
    const brdffit_model_info *mi = brdffit_model_get(BRDFFIT_WARD);
    double alpha = 1.5 * mi->params[0].upper;
    brdffit_table *t = wide_ward_table(alpha);
    brdffit_samples *s = samples_of(t);
    brdffit_context *ctx = make_context();
    brdffit_error err;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_WARD, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(r.at_bound & BRDFFIT_AT_BOUND_P0, "alpha %g (truth %g): at_bound 0x%x", r.params.p[0],
                  alpha, r.at_bound);
    ck_assert_msg(tu_reldiff(r.params.p[0], mi->params[0].upper) < 1e-4, "alpha %g", r.params.p[0]);
    ck_assert(!(r.at_bound & (BRDFFIT_AT_BOUND_P1 | BRDFFIT_AT_BOUND_P2)));
    ck_assert(!(r.at_bound & (BRDFFIT_AT_BOUND_D_R | BRDFFIT_AT_BOUND_D_G | BRDFFIT_AT_BOUND_D_B)));

    /* the program says so too */
    char path[512], cmd[2048], buf[8192];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    ck_assert_msg(brdffit_table_write(t, path, &err) == BRDFFIT_OK, "%s", err.message);
    const char *cli = getenv("BRDFFIT_CLI");
    for (int json = 0; json < 2; json++) {
        snprintf(cmd, sizeof cmd, "'%s' fit '%s' --model ward %s 2>/dev/null",
                 cli && *cli ? cli : "./build/brdffit", path, json ? "--json" : "");
        FILE *p = popen(cmd, "r");
        ck_assert_ptr_nonnull(p);
        size_t n = fread(buf, 1, sizeof buf - 1, p);
        buf[n] = '\0';
        ck_assert_int_eq(pclose(p), 0);
        const char *want = json ? "\"at_bound\":[\"alpha\"]" : "on a bound: alpha";
        ck_assert_msg(strstr(buf, want) != NULL, "no %s in:\n%s", want, buf);
    }
    unlink(path);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* A table made by Ashikhmin-Shirley (dark-blue-paint's published lobe) with
 * d = 0 in the red and green channels: the fit comes back to it exactly, d_r
 * and d_g = 0 flagged as on their bound, converged (not on the evaluation
 * limit), in few iterations. */
START_TEST(zero_diffuse_channel)
{
    brdffit_params truth;
    ck_assert(tu_published("dark-blue-paint", BRDFFIT_ASHIKHMIN_SHIRLEY, &truth));
    truth.d[0] = truth.d[1] = 0.0;
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_fill_model(t, BRDFFIT_ASHIKHMIN_SHIRLEY, &truth, BRDFFIT_SCALE_STANDARD,
                                           &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_samples *s = samples_of(t);
    brdffit_context *ctx = make_context();
    brdffit_params zero = truth;
    memset(zero.d, 0, sizeof zero.d);
    memset(zero.s, 0, sizeof zero.s);
    double rms;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_ASHIKHMIN_SHIRLEY, &zero, &rms, &err), BRDFFIT_OK);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_ASHIKHMIN_SHIRLEY, NULL, &r, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert_msg(r.error < 1e-6 * rms, "Error %g, rms %g", r.error, rms);
    ck_assert_msg(!(r.flags & BRDFFIT_FIT_LIMIT) && r.cminpack_info >= 1 && r.cminpack_info <= 4,
                  "stopped: info %d, flags 0x%x", r.cminpack_info, r.flags);
    ck_assert_msg(r.iterations <= 40, "%d iterations", r.iterations);
    ck_assert_msg(r.params.d[0] == 0.0 && r.params.d[1] == 0.0, "d %g %g", r.params.d[0], r.params.d[1]);
    ck_assert(r.at_bound & BRDFFIT_AT_BOUND_D_R);
    ck_assert(r.at_bound & BRDFFIT_AT_BOUND_D_G);
    ck_assert(!(r.at_bound & (BRDFFIT_AT_BOUND_D_B | BRDFFIT_AT_BOUND_LOBE)));
    ck_assert_msg(tu_reldiff(r.params.d[2], truth.d[2]) < 1e-3, "d_b %g vs %g", r.params.d[2], truth.d[2]);
    for (int c = 0; c < 3; c++)
        ck_assert_msg(tu_reldiff(r.params.s[c], truth.s[c]) < 1e-3, "s[%d] %g vs %g", c, r.params.s[c],
                      truth.s[c]);
    for (int k = 0; k < 2; k++)
        ck_assert_msg(tu_reldiff(r.params.p[k], truth.p[k]) < 1e-3, "p[%d] %g vs %g", k, r.params.p[k],
                      truth.p[k]);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

Suite *fidelity_suite(void)
{
    Suite *su = suite_create("fidelity");
    TCase *tb = tcase_create("bounds");
    tcase_set_tags(tb, TU_NEEDS_SHARED);
    tcase_add_loop_test(tb, bounds_admit_published, 0, brdffit_model_count());
    suite_add_tcase(su, tb);
    TCase *tf = tcase_create("flags");
    tcase_set_timeout(tf, 300);
    tcase_add_test(tf, bound_is_flagged);
    suite_add_tcase(su, tf);
    TCase *tz = tcase_create("zero_d");
    tcase_set_tags(tz, TU_NEEDS_SHARED);
    tcase_set_timeout(tz, 300);
    tcase_add_test(tz, zero_diffuse_channel);
    suite_add_tcase(su, tz);
    return su;
}
