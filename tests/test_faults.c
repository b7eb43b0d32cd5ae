/* SPDX-License-Identifier: MIT */
/* test_faults.c -- degenerate data and hostile input get a clear status and
 * a message that says what is wrong: a huge finite stored value (named at
 * read time and by the sample set), sample sets too small for a model's
 * unknowns, device indices out of range (never wrapped), a long path that
 * keeps the reason in the message. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define NB ((size_t)BRDFFIT_MERL_BINS)

/* A Ward-Duer table (all bins above the horizon filled). */
static brdffit_table *ward_table(void)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_params p = { { 0.05, 0.04, 0.03 }, { 0.04, 0.03, 0.02 }, { 0.15, 0, 0 }, { 0 } };
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_fill_model(t, BRDFFIT_WARD_DUER, &p, BRDFFIT_SCALE_STANDARD, &err) ==
                      BRDFFIT_OK,
                  "%s", err.message);
    return t;
}

static brdffit_context *host_context(void)
{
    brdffit_error err;
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    co.backend = BRDFFIT_BACKEND_HOST;
    brdffit_context *ctx = NULL;
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_OK);
    return ctx;
}

/* ------------------------------------------------------------------ huge values */

/* One huge but finite value (bin 45,10,20, channel G): refused at read time
 * with the bin, the channel, the byte and the value named, not every model
 * failing later with "non-finite sum". */
START_TEST(huge_value_named_at_read)
{
    brdffit_table *t = ward_table();
    size_t bin = 20 + 180 * (10 + 90 * 45);
    brdffit_table_values(t)[NB + bin] = 1e100;
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    brdffit_error err;
    ck_assert_int_eq(brdffit_table_write(t, path, &err), BRDFFIT_OK);
    brdffit_table *back = (brdffit_table *)&err;
    ck_assert_int_eq(brdffit_table_read(path, &back, &err), BRDFFIT_E_VALUE_RANGE);
    ck_assert_ptr_null(back);
    ck_assert_int_eq(err.status, BRDFFIT_E_VALUE_RANGE);
    char want[1024];
    snprintf(want, sizeof want, "%s: value 1e+100 at byte %zu (index %zu, channel G, bin 45,10,20)", path,
             12 + 8 * (NB + bin), NB + bin);
    ck_assert_msg(strstr(err.message, want), "message: %s\nwanted: %s", err.message, want);
    /* a value at the limit is still a table */
    brdffit_table_values(t)[NB + bin] = BRDFFIT_VALUE_MAX;
    ck_assert_int_eq(brdffit_table_write(t, path, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_read(path, &back, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(back);
    unlink(path);
    brdffit_table_free(t);
}
END_TEST

/* The same value put in memory: the sample set refuses it, naming the bin;
 * a huge NEGATIVE value is a masked bin as any negative one. */
START_TEST(huge_value_named_by_samples)
{
    brdffit_table *t = ward_table();
    size_t bin = 7 + 180 * (3 + 90 * 2);
    brdffit_table_values(t)[2 * NB + bin] = 3e300;
    brdffit_error err;
    brdffit_samples *s = (brdffit_samples *)&err;
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, &err), BRDFFIT_E_VALUE_RANGE);
    ck_assert_ptr_null(s);
    ck_assert_msg(strstr(err.message, "3.0000000000000002e+300 (channel B, bin 2,3,7), above 1e+20"), "%s",
                  err.message);
    brdffit_table_values(t)[2 * NB + bin] = -1e300;
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, &err), BRDFFIT_OK);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* ------------------------------------------------------------------ too few samples */

static brdffit_status fit_on(brdffit_samples *s, brdffit_model m, brdffit_fit_result *r,
                             brdffit_error *err)
{
    brdffit_context *ctx = host_context();
    brdffit_fit_options fo;
    brdffit_fit_options_default(&fo);
    fo.starts = 2;
    brdffit_status st = brdffit_fit(ctx, s, m, &fo, r, err);
    brdffit_context_free(ctx);
    return st;
}

/* One valid sample: every model refuses it (not ok with s up to 3.6e35). */
START_TEST(one_sample_refused)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    double *v = brdffit_table_values(t);
    for (size_t n = 0; n < 3 * NB; n++)
        v[n] = -1;
    size_t bin = 30 + 180 * (20 + 90 * 40);
    v[bin] = v[NB + bin] = v[2 * NB + bin] = 0.5;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, &err), BRDFFIT_OK);
    ck_assert_uint_eq(brdffit_samples_count(s), 1);
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        ck_assert_int_eq(fit_on(s, (brdffit_model)m, &r, &err), BRDFFIT_E_TOO_FEW_SAMPLES);
        ck_assert_int_eq(err.status, BRDFFIT_E_TOO_FEW_SAMPLES);
        ck_assert_msg(strstr(err.message, "1 sample at 1 distinct geometry"), "%s", err.message);
        ck_assert_ptr_nonnull(strstr(err.message, brdffit_model_get((brdffit_model)m)->name));
    }
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* A cutoff so small that only the normal is left: 180 samples, one
 * geometry (wi = wo = N whatever phi_d is). */
START_TEST(tiny_cutoff_refused)
{
    brdffit_table *t = ward_table();
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.cutoff_deg = 1e-300;
    brdffit_error err;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_samples_create(t, &so, &s, &err), BRDFFIT_OK);
    ck_assert_uint_gt(brdffit_samples_count(s), 1);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_int_eq(fit_on(s, BRDFFIT_WARD, &r, &err), BRDFFIT_E_TOO_FEW_SAMPLES);
    ck_assert_msg(strstr(err.message, "at 1 distinct geometry"), "%s", err.message);
    ck_assert_msg(strstr(err.message, "3 unknowns per channel"), "%s", err.message);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* Just enough distinct geometries for a one-parameter lobe (3), and one too
 * few for He (5 unknowns): the rule counts geometries, not samples. */
START_TEST(geometries_counted_per_model)
{
    brdffit_table *t = ward_table();
    double *v = brdffit_table_values(t);
    /* keep the theta_h = 0 bins of theta_d bins 10, 20, 30, 40 only: each
     * theta_d bin is one geometry (phi_d only turns it about the normal) */
    for (size_t b = 0; b < NB; b++) {
        size_t j = (b / 180) % 90, i = b / (180 * 90);
        if (i != 0 || (j != 10 && j != 20 && j != 30 && j != 40))
            v[b] = v[NB + b] = v[2 * NB + b] = -1;
    }
    brdffit_error err;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, &err), BRDFFIT_OK);
    ck_assert_uint_eq(brdffit_samples_count(s), 4 * 180);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    brdffit_status st = fit_on(s, BRDFFIT_WARD_DUER, &r, &err);
    ck_assert_msg(st != BRDFFIT_E_TOO_FEW_SAMPLES, "%s", err.message);
    ck_assert_int_eq(fit_on(s, BRDFFIT_HE, &r, &err), BRDFFIT_E_TOO_FEW_SAMPLES);
    ck_assert_msg(strstr(err.message, "720 samples at 4 distinct geometries"), "%s", err.message);
    ck_assert_msg(strstr(err.message, "5 unknowns per channel (d, s and 3 lobe parameters)"), "%s",
                  err.message);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* A material with no specular part at all: the fit ends with s = 0, on its
 * bound, and the result says so for each channel (the degenerate case of
 * brdffit_fit_result.at_bound). */
START_TEST(no_specular_ends_on_bound)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_params p = { { 0.3, 0.2, 0.1 }, { 0, 0, 0 }, { 0.15, 0, 0 }, { 0 } };
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_WARD_DUER, &p, BRDFFIT_SCALE_STANDARD, &err),
                     BRDFFIT_OK);
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.cutoff_deg = 30;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_samples_create(t, &so, &s, &err), BRDFFIT_OK);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(fit_on(s, BRDFFIT_WARD_DUER, &r, &err) == BRDFFIT_OK, "%s", err.message);
    unsigned sbits = BRDFFIT_AT_BOUND_S_R | BRDFFIT_AT_BOUND_S_G | BRDFFIT_AT_BOUND_S_B;
    ck_assert_msg((r.at_bound & sbits) == sbits, "at_bound %#x, s %g %g %g", r.at_bound, r.params.s[0],
                  r.params.s[1], r.params.s[2]);
    ck_assert_msg((r.at_bound & (BRDFFIT_AT_BOUND_D_R | BRDFFIT_AT_BOUND_D_G | BRDFFIT_AT_BOUND_D_B)) == 0,
                  "at_bound %#x", r.at_bound);
    for (int c = 0; c < 3; c++)
        ck_assert_msg(tu_reldiff(r.params.d[c], p.d[c]) < 1e-6, "d_%d %g", c, r.params.d[c]);
    ck_assert(r.error < 1e-9);
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

/* ------------------------------------------------------------------ devices */

/* Indices past 2^32 are out of range, not wrapped to 0:0; so are indices
 * too large for any integer type. */
START_TEST(device_index_out_of_range)
{
    static const char *const bad[] = { "4294967296:0", "0:4294967296", "18446744073709551616:0",
                                       "99999999999999999999999:1", "1:0", "0:7" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        brdffit_error err;
        brdffit_context_options co;
        brdffit_context_options_default(&co);
        co.backend = BRDFFIT_BACKEND_OPENCL;
        co.device = bad[i];
        brdffit_context *ctx = NULL;
        ck_assert_msg(brdffit_context_create(&co, &ctx, &err) == BRDFFIT_E_NO_DEVICE, "%s: %s", bad[i],
                      brdffit_context_describe(ctx));
        ck_assert_ptr_null(ctx);
        ck_assert_msg(strstr(err.message, "out of range"), "%s: %s", bad[i], err.message);
        ck_assert_msg(strstr(err.message, "devices: 0:0 "), "%s: %s", bad[i], err.message);
        /* under AUTO: the host, and the reason kept for the caller */
        co.backend = BRDFFIT_BACKEND_AUTO;
        ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_OK);
        ck_assert_int_eq(brdffit_context_backend(ctx), BRDFFIT_BACKEND_HOST);
        ck_assert_int_eq(brdffit_context_fallback(ctx, &err), BRDFFIT_E_NO_DEVICE);
        ck_assert_msg(strstr(err.message, bad[i]), "%s", err.message);
        brdffit_context_free(ctx);
    }
    /* the one device there is, by index */
    brdffit_error err;
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    co.backend = BRDFFIT_BACKEND_OPENCL;
    co.device = "0:0";
    brdffit_context *ctx = NULL;
    ck_assert_msg(brdffit_context_create(&co, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_int_eq(brdffit_context_fallback(ctx, &err), BRDFFIT_OK);
    ck_assert_str_eq(err.message, "");
    brdffit_context_free(ctx);
}
END_TEST

/* ------------------------------------------------------------------ long paths */

/* A path of 3000 bytes (more than a message holds): the message keeps the
 * path's start and end and, after it, the reason. */
START_TEST(long_path_keeps_reason)
{
    char path[3100];
    int n = snprintf(path, sizeof path, "/nonexistent-brdffit-dir/");
    while (n < 3000)
        n += snprintf(path + n, sizeof path - (size_t)n, "deep-directory-name/");
    snprintf(path + n, sizeof path - (size_t)n, "material.binary");
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_read(path, &t, &err), BRDFFIT_E_FILE_OPEN);
    ck_assert_msg(strstr(err.message, "material.binary: cannot open: "), "%s", err.message);
    ck_assert(strncmp(err.message, "/nonexistent-brdffit-dir/", 25) == 0);
    ck_assert_ptr_nonnull(strstr(err.message, "..."));
    ck_assert_uint_lt(strlen(err.message), BRDFFIT_MESSAGE_MAX - 1);
    t = ward_table();
    ck_assert_int_eq(brdffit_table_write(t, path, &err), BRDFFIT_E_FILE_WRITE);
    ck_assert_msg(strstr(err.message, "material.binary: cannot open for writing: "), "%s",
                  err.message);
    brdffit_table_free(t);
}
END_TEST

Suite *faults_suite(void)
{
    Suite *s = suite_create("faults");
    TCase *tc = tcase_create("faults");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, huge_value_named_at_read);
    tcase_add_test(tc, huge_value_named_by_samples);
    tcase_add_test(tc, one_sample_refused);
    tcase_add_test(tc, tiny_cutoff_refused);
    tcase_add_test(tc, geometries_counted_per_model);
    tcase_add_test(tc, no_specular_ends_on_bound);
    tcase_add_test(tc, device_index_out_of_range);
    tcase_add_test(tc, long_path_keeps_reason);
    suite_add_tcase(s, tc);
    return s;
}
