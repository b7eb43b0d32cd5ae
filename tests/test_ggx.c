/* SPDX-License-Identifier: MIT */
/* test_ggx.c -- the GGX model: reference values of an independent
 * implementation, an evaluation of pbrt-v4's formula written here in long
 * double, fits that give a GGX table's parameters back, and the program
 * fitting every model (`fit --model all`) to a GGX table.  Reciprocity,
 * finiteness and kernel = host loop are the registry-wide tests
 * (test_models.c, test_pass.c). */
#define _DEFAULT_SOURCE /* M_PI */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

START_TEST(reference_values)
{
    char path[1024], line[4096];
    FILE *f = fopen(tu_shared("data/ggx-reference.tsv", path, sizeof path), "r");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    char *fl[32];
    int rows = 0, header = 0;
    double worst = 0;
    while (tu_tsv_next(f, line, sizeof line, fl, 32) > 0) {
        if (!header) {
            ck_assert_str_eq(fl[0], "model");
            header = 1;
            continue;
        }
        brdffit_model m;
        ck_assert_int_eq(brdffit_model_from_name(fl[0], &m, NULL), BRDFFIT_OK);
        ck_assert_int_eq(m, BRDFFIT_GGX);
        brdffit_params p;
        tu_params_from_row(fl, &p);
        double wi[3], wo[3], rgb[3];
        for (int k = 0; k < 3; k++) {
            wi[k] = atof(fl[11 + k]);
            wo[k] = atof(fl[14 + k]);
        }
        ck_assert_int_eq(brdffit_eval(m, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
        for (int c = 0; c < 3; c++) {
            double ref = atof(fl[17 + c]), rd = tu_reldiff(rgb[c], ref);
            worst = fmax(worst, rd);
            ck_assert_msg(rd <= 1e-12, "%s row %d channel %d: %.17g vs reference %.17g (rel %g)",
                          fl[1], rows, c, rgb[c], ref, rd);
        }
        rows++;
    }
    fclose(f);
    ck_assert_int_eq(rows, 64);
    fprintf(stderr, "ggx: worst relative difference from ggx-reference.tsv %.2g\n", worst);
}
END_TEST

/* pbrt-v4's TrowbridgeReitzDistribution (isotropic), in long double, from
 * the formula as printed: D with tan^2 and cos^4 of the half vector, Lambda
 * with tan^2 of each direction, Schlick's F at wo.wm. */
static long double pbrt_ggx(long double f0, long double a, const double wi[3], const double wo[3])
{
    long double h[3], len = 0;
    for (int k = 0; k < 3; k++)
        h[k] = (long double)wi[k] + wo[k], len += h[k] * h[k];
    len = sqrtl(len);
    for (int k = 0; k < 3; k++)
        h[k] /= len;
    long double c2 = h[2] * h[2], t2 = (1 - c2) / c2;
    long double e = 1 + t2 / (a * a);
    long double D = 1 / (M_PI * a * a * c2 * c2 * e * e);
    long double li = (sqrtl(1 + a * a * (1 - (long double)wi[2] * wi[2]) / ((long double)wi[2] * wi[2])) - 1) / 2;
    long double lo = (sqrtl(1 + a * a * (1 - (long double)wo[2] * wo[2]) / ((long double)wo[2] * wo[2])) - 1) / 2;
    long double G2 = 1 / (1 + li + lo);
    long double vh = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
    long double F = f0 + (1 - f0) * powl(1 - vh, 5);
    return D * G2 * F / (4 * (long double)wi[2] * wo[2]);
}

/* Away from the grazing and peak directions (where 1 - cos^2 in the printed
 * formula loses digits even in long double) the library equals it to 1e-13. */
START_TEST(formula_as_printed)
{
    static const double alphas[] = { 0.01, 0.05, 0.2, 0.5, 1.0 };
    unsigned st = 777;
    brdffit_params p;
    memset(&p, 0, sizeof p);
    p.s[0] = p.s[1] = p.s[2] = 1;
    for (size_t ai = 0; ai < sizeof alphas / sizeof alphas[0]; ai++)
        for (int t = 0; t < 2000; t++) {
            double wi[3], wo[3], rgb[3];
            tu_rand_dir(&st, 0.05, wi);
            tu_rand_dir(&st, 0.05, wo);
            p.p[0] = tu_urand(&st);
            p.p[1] = alphas[ai];
            ck_assert_int_eq(brdffit_eval(BRDFFIT_GGX, &p, wi, wo, rgb, NULL), BRDFFIT_OK);
            double want = (double)pbrt_ggx(p.p[0], p.p[1], wi, wo);
            ck_assert_msg(tu_reldiff(rgb[0], want) <= 1e-13, "alpha %g F0 %g: %.17g vs %.17g",
                          p.p[1], p.p[0], rgb[0], want);
            ck_assert(rgb[0] == rgb[1] && rgb[1] == rgb[2]);
        }
}
END_TEST

/* The four parameter sets of ggx-reference.tsv, d and s as there. */
static const brdffit_params ggx_sets[] = {
    { { 0.3, 0.2, 0.1 }, { 0.5, 0.5, 0.5 }, { 0.04, 0.35 }, { 0 } },        /* rough plastic */
    { { 0.02, 0.04, 0.03 }, { 0.2, 0.2, 0.15 }, { 0.1, 0.12 }, { 0 } },     /* glossy paint  */
    { { 0.005, 0.004, 0.003 }, { 0.9, 0.7, 0.4 }, { 0.9, 0.03 }, { 0 } },   /* sharp metal   */
    { { 0.01, 0.01, 0.01 }, { 1.0, 1.0, 1.0 }, { 0.95, 0.005 }, { 0 } },    /* near mirror   */
};
#define NSETS (int)(sizeof ggx_sets / sizeof ggx_sets[0])

/* A table made by GGX fits back from the default starts: Error below 1e-6
 * of the data's RMS, d, s, F0 and alpha within 1e-3 relative. */
START_TEST(fits_its_own_table)
{
    const brdffit_params *truth = &ggx_sets[_i];
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    brdffit_context *ctx = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_fill_model(t, BRDFFIT_GGX, truth, BRDFFIT_SCALE_STANDARD, &err) ==
                      BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(brdffit_samples_create(t, NULL, &s, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_AUTO, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_params zero = *truth;
    memset(zero.d, 0, sizeof zero.d);
    memset(zero.s, 0, sizeof zero.s);
    double rms = 0;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_GGX, &zero, &rms, &err), BRDFFIT_OK);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_GGX, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(r.error < 1e-6 * rms, "set %d: Error %g of rms %g", _i, r.error, rms);
    for (int c = 0; c < 3; c++) {
        ck_assert_msg(tu_reldiff(r.params.d[c], truth->d[c]) < 1e-3, "set %d d[%d] %.6g vs %.6g", _i,
                      c, r.params.d[c], truth->d[c]);
        ck_assert_msg(tu_reldiff(r.params.s[c], truth->s[c]) < 1e-3, "set %d s[%d] %.6g vs %.6g", _i,
                      c, r.params.s[c], truth->s[c]);
    }
    for (int k = 0; k < 2; k++)
        ck_assert_msg(tu_reldiff(r.params.p[k], truth->p[k]) < 1e-3, "set %d p%d %.6g vs %.6g", _i, k,
                      r.params.p[k], truth->p[k]);
    ck_assert_int_eq(brdffit_params_check(BRDFFIT_GGX, &r.params, NULL), BRDFFIT_OK);
    brdffit_samples_free(s);
    brdffit_context_free(ctx);
}
END_TEST

/* `brdffit fit --model all` on a GGX table: one record per model of the
 * registry, every fit ok, and GGX (the model that made the data) the best,
 * with its parameters back. */
START_TEST(program_fits_all_models)
{
    char table[512];
    ck_assert_ptr_nonnull(tu_tmpfile(table, sizeof table));
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_GGX, &ggx_sets[1], BRDFFIT_SCALE_STANDARD, &err),
                     BRDFFIT_OK);
    ck_assert_msg(brdffit_table_write(t, table, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
    const char *cli = getenv("BRDFFIT_CLI");
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "'%s' fit --json --model all --cutoff 50 --starts 4 '%s'",
             cli && *cli ? cli : "./build/brdffit", table);
    FILE *p = popen(cmd, "r");
    ck_assert_ptr_nonnull(p);
    static char line[1 << 16];
    int n = 0, seen[BRDFFIT_MODEL_COUNT] = { 0 };
    double best = INFINITY, ggx_error = NAN, f0 = NAN, alpha = NAN;
    while (fgets(line, sizeof line, p)) {
        ck_assert_msg(tu_json_object_line(line), "%s", line);
        char name[64], status[64];
        ck_assert(tu_json_get_string(line, "model", name, sizeof name));
        ck_assert(tu_json_get_string(line, "status", status, sizeof status));
        ck_assert_msg(strcmp(status, "ok") == 0, "%s: %s", name, line);
        brdffit_model m;
        ck_assert_int_eq(brdffit_model_from_name(name, &m, NULL), BRDFFIT_OK);
        seen[m]++;
        double e;
        ck_assert(tu_json_get_number(line, "error", &e));
        if (m == BRDFFIT_GGX) {
            ggx_error = e;
            ck_assert(tu_json_get_element(line, "p", 0, &f0) && tu_json_get_element(line, "p", 1, &alpha));
        } else {
            best = fmin(best, e);
        }
        n++;
    }
    ck_assert_int_eq(pclose(p), 0);
    unlink(table);
    ck_assert_int_eq(n, brdffit_model_count());
    for (int m = 0; m < brdffit_model_count(); m++)
        ck_assert_msg(seen[m] == 1, "model %s: %d records", brdffit_model_get((brdffit_model)m)->name,
                      seen[m]);
    ck_assert_msg(ggx_error < 1e-3 * best, "ggx Error %g, best other %g", ggx_error, best);
    ck_assert_msg(tu_reldiff(f0, ggx_sets[1].p[0]) < 1e-3 && tu_reldiff(alpha, ggx_sets[1].p[1]) < 1e-3,
                  "F0 %g alpha %g", f0, alpha);
}
END_TEST

Suite *ggx_suite(void)
{
    Suite *s = suite_create("ggx");
    TCase *tr = tcase_create("reference");
    tcase_set_tags(tr, TU_NEEDS_SHARED);
    tcase_add_test(tr, reference_values);
    suite_add_tcase(s, tr);
    TCase *tc = tcase_create("ggx");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, formula_as_printed);
    tcase_add_loop_test(tc, fits_its_own_table, 0, NSETS);
    tcase_add_test(tc, program_fits_all_models);
    suite_add_tcase(s, tc);
    return s;
}
