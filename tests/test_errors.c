/* SPDX-License-Identifier: MIT */
/* test_errors.c -- every fallible public function fills a brdffit_error: given
 * a bad argument it returns its status and err holds the same status and a
 * message naming the argument, the index and the value; on success err is
 * marked OK; err may be NULL. */
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* call returns want_st, err holds the same status and a message equal to want. */
#define EXPECT_ERR(call, want_st, want)                                                         \
    do {                                                                                       \
        brdffit_error e_;                                                                      \
        memset(&e_, 0x7f, sizeof e_);                                                          \
        brdffit_error *err = &e_;                                                              \
        brdffit_status st_ = (call);                                                           \
        ck_assert_int_eq(st_, (want_st));                                                      \
        ck_assert_int_eq(e_.status, (want_st));                                                \
        ck_assert_str_eq(e_.message, (want));                                                  \
    } while (0)

/* The call succeeds and marks err OK (status 0, empty message). */
#define EXPECT_OK(call)                                                                        \
    do {                                                                                       \
        brdffit_error e_;                                                                      \
        memset(&e_, 0x7f, sizeof e_);                                                          \
        brdffit_error *err = &e_;                                                              \
        ck_assert_msg((call) == BRDFFIT_OK, "%s", e_.message);                                 \
        ck_assert_int_eq(e_.status, BRDFFIT_OK);                                               \
        ck_assert_str_eq(e_.message, "");                                                      \
    } while (0)

static const brdffit_params ward_p = { { 0.1, 0.1, 0.1 }, { 0.2, 0.2, 0.2 }, { 0.3, 0, 0 }, { 0 } };

START_TEST(model_from_name_errors)
{
    brdffit_model m;
    char want[1024] = "no model named 'phong' (models: ";
    for (int k = 0; k < brdffit_model_count(); k++) {
        strcat(want, k ? ", " : "");
        strcat(want, brdffit_model_get((brdffit_model)k)->name);
    }
    strcat(want, ")");
    EXPECT_ERR(brdffit_model_from_name("phong", &m, err), BRDFFIT_E_UNKNOWN_MODEL, want);
    EXPECT_ERR(brdffit_model_from_name(NULL, &m, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_model_from_name: name is NULL");
    EXPECT_ERR(brdffit_model_from_name("ward", NULL, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_model_from_name: out is NULL");
    EXPECT_OK(brdffit_model_from_name("ashikhmin_shirley", &m, err));
    ck_assert_int_eq(m, BRDFFIT_ASHIKHMIN_SHIRLEY);
    ck_assert_int_eq(brdffit_model_from_name("phong", &m, NULL), BRDFFIT_E_UNKNOWN_MODEL);
}
END_TEST

START_TEST(eval_errors)
{
    double up[3] = { 0, 0, 1 }, zero[3] = { 0, 0, 0 }, nan3[3] = { 0.5, NAN, 1 }, rgb[3];
    EXPECT_ERR(brdffit_eval(BRDFFIT_WARD, &ward_p, zero, up, rgb, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_eval: wi = (0, 0, 0) is not a finite, non-zero direction");
    EXPECT_ERR(brdffit_eval(BRDFFIT_WARD, &ward_p, up, nan3, rgb, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_eval: wo = (0.5, nan, 1) is not a finite, non-zero direction");
    EXPECT_ERR(brdffit_eval(BRDFFIT_WARD, &ward_p, up, up, NULL, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_eval: rgb is NULL");
    brdffit_params bad = ward_p;
    bad.s[2] = -1;
    EXPECT_ERR(brdffit_eval(BRDFFIT_WARD, &bad, up, up, rgb, err), BRDFFIT_E_PARAM_RANGE,
               "ward: s_B = -1 must be finite and >= 0");
    EXPECT_ERR(brdffit_eval((brdffit_model)99, &ward_p, up, up, rgb, err), BRDFFIT_E_UNKNOWN_MODEL,
               "model id 99 is not a model");
    EXPECT_OK(brdffit_eval(BRDFFIT_WARD, &ward_p, up, up, rgb, err));
    ck_assert_int_eq(brdffit_eval(BRDFFIT_WARD, &ward_p, zero, up, rgb, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
}
END_TEST

START_TEST(eval_batch_errors)
{
    double wi[12] = { 0, 0, 1, 0, 0, 1, 0, 0, 0, INFINITY, 0, 1 };
    double wo[12] = { 0, 0, 1, 0.6, 0, 0.8, 0, 0, 1, 0, 0, 1 };
    double rgb[12];
    EXPECT_ERR(brdffit_eval_batch(BRDFFIT_WARD, &ward_p, 4, wi, wo, rgb, err),
               BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_eval_batch: pair 2 of 4 (2 bad pairs, rgb 0 there): wi = (0, 0, 0) is not "
               "a finite, non-zero direction");
    ck_assert(rgb[6] == 0 && rgb[9] == 0 && rgb[0] > 0 && rgb[3] > 0);
    EXPECT_ERR(brdffit_eval_batch(BRDFFIT_WARD, &ward_p, 4, wi, NULL, rgb, err),
               BRDFFIT_E_INVALID_ARGUMENT, "brdffit_eval_batch: wo is NULL");
    EXPECT_OK(brdffit_eval_batch(BRDFFIT_WARD, &ward_p, 2, wi, wo, rgb, err));
    EXPECT_OK(brdffit_eval_batch(BRDFFIT_WARD, &ward_p, 0, NULL, NULL, NULL, err));
}
END_TEST

START_TEST(scale_errors)
{
    double f[3];
    brdffit_scale s;
    EXPECT_ERR(brdffit_scale_factors((brdffit_scale)7, f, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_scale_factors: unknown scale 7 (0 standard, 1 flat)");
    EXPECT_ERR(brdffit_scale_factors(BRDFFIT_SCALE_FLAT, NULL, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_scale_factors: factors is NULL");
    EXPECT_OK(brdffit_scale_factors(BRDFFIT_SCALE_FLAT, f, err));
    EXPECT_ERR(brdffit_scale_from_name("merl", &s, err), BRDFFIT_E_INVALID_ARGUMENT,
               "no scale named 'merl' (scales: standard, flat)");
    EXPECT_ERR(brdffit_scale_from_name(NULL, &s, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_scale_from_name: name is NULL");
    EXPECT_OK(brdffit_scale_from_name("flat", &s, err));
    ck_assert_int_eq(s, BRDFFIT_SCALE_FLAT);
}
END_TEST

START_TEST(bin_directions_errors)
{
    double wi[3], wo[3];
    EXPECT_ERR(brdffit_bin_directions(90, 0, 0, wi, wo, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_bin_directions: bin (90, 0, 0): i (theta_h) = 90 outside 0..89");
    EXPECT_ERR(brdffit_bin_directions(3, -1, 0, wi, wo, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_bin_directions: bin (3, -1, 0): j (theta_d) = -1 outside 0..89");
    EXPECT_ERR(brdffit_bin_directions(3, 4, 180, wi, wo, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_bin_directions: bin (3, 4, 180): k (phi_d) = 180 outside 0..179");
    EXPECT_ERR(brdffit_bin_directions(3, 4, 5, wi, NULL, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_bin_directions: wo is NULL");
    EXPECT_OK(brdffit_bin_directions(3, 4, 5, wi, wo, err));
}
END_TEST

START_TEST(table_lookup_errors)
{
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    double up[3] = { 0, 0, 1 }, a[3] = { 0.6, 0, 0.8 }, b[3] = { -0.6, 0, -0.8 };
    double bad[3] = { NAN, 0, 1 }, rgb[3];
    const brdffit_scale S = BRDFFIT_SCALE_STANDARD;
    const brdffit_interp N = BRDFFIT_INTERP_NEAREST;
    EXPECT_ERR(brdffit_table_lookup(t, up, bad, S, N, rgb, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup: wo = (nan, 0, 1) is not a finite, non-zero direction");
    EXPECT_ERR(brdffit_table_lookup(t, a, b, S, N, rgb, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup: wo = (-0.6, 0, -0.8) is opposite to wi: no half vector");
    EXPECT_ERR(brdffit_table_lookup(t, up, up, (brdffit_scale)3, N, rgb, err),
               BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup: unknown scale 3 (0 standard, 1 flat)");
    EXPECT_ERR(brdffit_table_lookup(t, up, up, S, (brdffit_interp)9, rgb, err),
               BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup: unknown interp 9 (0 nearest, 1 trilinear)");
    EXPECT_ERR(brdffit_table_lookup(NULL, up, up, S, N, rgb, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup: table is NULL");
    EXPECT_ERR(brdffit_table_lookup(t, NULL, up, S, N, rgb, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup: wi is NULL");
    EXPECT_OK(brdffit_table_lookup(t, up, a, S, N, rgb, err));
    brdffit_table_free(t);
}
END_TEST

START_TEST(table_lookup_batch_errors)
{
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    double wi[9] = { 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    double wo[9] = { 0, 0, 1, 0.6, 0, 0.8, 0, 0, 0 };
    double rgb[9];
    EXPECT_ERR(brdffit_table_lookup_batch(t, 3, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST,
                                          rgb, err),
               BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup_batch: pair 2 of 3 (1 bad pair, rgb -1 there): wo = (0, 0, 0) "
               "is not a finite, non-zero direction");
    ck_assert(rgb[6] == -1 && rgb[7] == -1 && rgb[8] == -1 && rgb[0] == 0);
    EXPECT_ERR(brdffit_table_lookup_batch(t, 3, wi, wo, (brdffit_scale)4, BRDFFIT_INTERP_NEAREST,
                                          rgb, err),
               BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_table_lookup_batch: unknown scale 4 (0 standard, 1 flat)");
    EXPECT_ERR(brdffit_table_lookup_batch(t, 3, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST,
                                          NULL, err),
               BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_lookup_batch: rgb is NULL");
    EXPECT_OK(brdffit_table_lookup_batch(t, 2, wi, wo, BRDFFIT_SCALE_FLAT,
                                         BRDFFIT_INTERP_TRILINEAR, rgb, err));
    brdffit_table_free(t);
}
END_TEST

START_TEST(samples_errors)
{
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, NULL), BRDFFIT_OK);
    size_t n = brdffit_samples_count(s);
    ck_assert(n > 0);
    brdffit_sample one;
    brdffit_sample_init(&one);
    char want[128];
    snprintf(want, sizeof want, "brdffit_samples_get: index %zu, but the set has %zu samples", n,
             n);
    EXPECT_ERR(brdffit_samples_get(s, n, &one, err), BRDFFIT_E_INVALID_ARGUMENT, want);
    EXPECT_ERR(brdffit_samples_get(s, 0, NULL, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_samples_get: out is NULL");
    EXPECT_ERR(brdffit_samples_get(NULL, 0, &one, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_samples_get: samples is NULL");
    EXPECT_OK(brdffit_samples_get(s, n - 1, &one, err));
    brdffit_sample_options o;
    brdffit_sample_options_default(&o);
    o.size = 0;
    EXPECT_ERR(brdffit_samples_options(s, &o, err), BRDFFIT_E_OPTIONS_SIZE,
               "brdffit_sample_options: size 0 (set it with brdffit_sample_options_default(): "
               "the struct's size as the caller was compiled; 24 bytes in this library)");
    brdffit_samples_free(s);
    brdffit_table_free(t);
}
END_TEST

START_TEST(image_error_errors)
{
    float ref[2 * 4] = { 1, 1, 1, 1, 0.5f, 0.5f, 0.5f, 1 }, img[2 * 4];
    memcpy(img, ref, sizeof img);
    double e;
    size_t covered;
    EXPECT_ERR(brdffit_image_error(ref, img, 0, 1, 0, &e, &covered, err),
               BRDFFIT_E_INVALID_ARGUMENT, "brdffit_image_error: 0 x 1 pixels (both must be >= 1)");
    EXPECT_ERR(brdffit_image_error(ref, img, 2, 1, 7, &e, &covered, err),
               BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_image_error: stride 7 floats is less than a row's 4 x 2");
    EXPECT_ERR(brdffit_image_error(ref, NULL, 2, 1, 0, &e, &covered, err),
               BRDFFIT_E_INVALID_ARGUMENT, "brdffit_image_error: img is NULL");
    img[6] = INFINITY;
    EXPECT_ERR(brdffit_image_error(ref, img, 2, 1, 0, &e, &covered, err),
               BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_image_error: img pixel (col 1, row 0) channel B = inf");
    img[6] = 0.5f;
    float black[8] = { 0, 0, 0, 1, 0, 0, 0, 1 }, bare[8] = { 1, 1, 1, 0, 1, 1, 1, 0.5f };
    EXPECT_ERR(brdffit_image_error(black, img, 2, 1, 0, &e, &covered, err), BRDFFIT_E_NO_SAMPLES,
               "brdffit_image_error: the reference is black on all 2 covered pixels");
    EXPECT_ERR(brdffit_image_error(bare, img, 2, 1, 0, &e, &covered, err), BRDFFIT_E_NO_SAMPLES,
               "brdffit_image_error: no pixel of the reference is covered (A = 1)");
    EXPECT_OK(brdffit_image_error(ref, img, 2, 1, 0, &e, &covered, err));
    ck_assert(e == 0 && covered == 2);
}
END_TEST

START_TEST(curve_theta_o_errors)
{
    brdffit_curve_options o;
    brdffit_curve_options_default(&o);
    double th[180];
    EXPECT_ERR(brdffit_curve_theta_o(&o, NULL, err), BRDFFIT_E_INVALID_ARGUMENT,
               "brdffit_curve_theta_o: theta_o_deg is NULL");
    o.npoints = 1;
    EXPECT_ERR(brdffit_curve_theta_o(&o, th, err), BRDFFIT_E_INVALID_ARGUMENT,
               "curves: npoints = 1 (2..100000)");
    o.npoints = 180;
    EXPECT_OK(brdffit_curve_theta_o(&o, th, err));
    ck_assert_double_eq(th[0], -89.5);
}
END_TEST

Suite *errors_suite(void)
{
    Suite *s = suite_create("errors");
    TCase *tc = tcase_create("errors");
    tcase_add_test(tc, model_from_name_errors);
    tcase_add_test(tc, eval_errors);
    tcase_add_test(tc, eval_batch_errors);
    tcase_add_test(tc, scale_errors);
    tcase_add_test(tc, bin_directions_errors);
    tcase_add_test(tc, table_lookup_errors);
    tcase_add_test(tc, table_lookup_batch_errors);
    tcase_add_test(tc, samples_errors);
    tcase_add_test(tc, image_error_errors);
    tcase_add_test(tc, curve_theta_o_errors);
    suite_add_tcase(s, tc);
    return s;
}
