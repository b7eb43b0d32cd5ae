/* SPDX-License-Identifier: MIT */
/* test_abi.c -- the ABI introspection an FFI mirror checks itself against
 * (sizes and member offsets of the public structs), and the batch lookup. */
#include "testutil.h"

#include <check.h>
#include <stddef.h>
#include <stdint.h>

START_TEST(struct_sizes)
{
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_ERROR), sizeof(brdffit_error));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_MODEL_INFO), sizeof(brdffit_model_info));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_PARAMS), sizeof(brdffit_params));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_SAMPLE_OPTIONS),
                      sizeof(brdffit_sample_options));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_SAMPLE), sizeof(brdffit_sample));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_CONTEXT_OPTIONS),
                      sizeof(brdffit_context_options));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_FIT_OPTIONS), sizeof(brdffit_fit_options));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_FIT_RESULT), sizeof(brdffit_fit_result));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_PARAM_INFO), sizeof(brdffit_param_info));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_LIGHT), sizeof(brdffit_light));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_RENDER_OPTIONS),
                      sizeof(brdffit_render_options));
    ck_assert_uint_eq(brdffit_struct_size(BRDFFIT_STRUCT_CURVE_OPTIONS),
                      sizeof(brdffit_curve_options));
    ck_assert_uint_eq(brdffit_struct_size((brdffit_struct_kind)12), 0);
    ck_assert_uint_eq(brdffit_struct_size((brdffit_struct_kind)999), 0);
    ck_assert_uint_eq(brdffit_struct_size((brdffit_struct_kind)-1), 0);
}
END_TEST

START_TEST(struct_offsets)
{
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_ERROR, "message"),
                      offsetof(brdffit_error, message));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_PARAMS, "lambda_um"),
                      offsetof(brdffit_params, lambda_um));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_FIT_RESULT, "params"),
                      offsetof(brdffit_fit_result, params));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_FIT_RESULT, "backend"),
                      offsetof(brdffit_fit_result, backend));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_SAMPLE, "k"), offsetof(brdffit_sample, k));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_CONTEXT_OPTIONS, "device"),
                      offsetof(brdffit_context_options, device));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_LIGHT, "rgb"), offsetof(brdffit_light, rgb));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_RENDER_OPTIONS, "threads"),
                      offsetof(brdffit_render_options, threads));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_RENDER_OPTIONS, "env_stride"),
                      offsetof(brdffit_render_options, env_stride));
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_CURVE_OPTIONS, "scale"),
                      offsetof(brdffit_curve_options, scale));
    /* a member of another struct, an unknown name, NULL, an unknown kind */
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_PARAMS, "message"), SIZE_MAX);
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_FIT_RESULT, "no_such"), SIZE_MAX);
    ck_assert_uint_eq(brdffit_struct_offset(BRDFFIT_STRUCT_FIT_RESULT, NULL), SIZE_MAX);
    ck_assert_uint_eq(brdffit_struct_offset((brdffit_struct_kind)999, "params"), SIZE_MAX);
}
END_TEST

/* The batch lookup gives what brdffit_table_lookup gives pair by pair; a bad
 * pair gets -1 and the status, the others are still looked up. */
START_TEST(lookup_batch)
{
    brdffit_table *t = NULL;
    brdffit_params p = { { 0.1, 0.2, 0.3 }, { 0.5, 0.4, 0.3 }, { 0.2, 0.1, 0 }, { 0, 0, 0 } };
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &p, BRDFFIT_SCALE_STANDARD,
                                              NULL),
                     BRDFFIT_OK);
    enum { N = 5 };
    double wi[3 * N] = { 0, 0, 1, 0.6, 0, 0.8, 0.3, 0.4, 0.866, 0, 0, 0, 0.1, -0.2, 0.97 };
    double wo[3 * N] = { 0, 0, 1, -0.6, 0, 0.8, 0.5, -0.1, 0.86, 0, 0, 1, 0.6, 0.6, 0.529 };
    for (int interp = 0; interp < 2; interp++) {
        double rgb[3 * N];
        ck_assert_int_eq(brdffit_table_lookup_batch(t, N, wi, wo, BRDFFIT_SCALE_STANDARD,
                                                    (brdffit_interp)interp, rgb, NULL),
                         BRDFFIT_E_INVALID_ARGUMENT);
        for (int s = 0; s < N; s++) {
            double one[3];
            brdffit_status st = brdffit_table_lookup(t, wi + 3 * s, wo + 3 * s,
                                                     BRDFFIT_SCALE_STANDARD,
                                                     (brdffit_interp)interp, one, NULL);
            for (int c = 0; c < 3; c++)
                ck_assert(rgb[3 * s + c] == (st == BRDFFIT_OK ? one[c] : -1.0));
            ck_assert_int_eq(st, s == 3 ? BRDFFIT_E_INVALID_ARGUMENT : BRDFFIT_OK);
        }
        ck_assert_int_eq(brdffit_table_lookup_batch(t, 3, wi, wo, BRDFFIT_SCALE_FLAT,
                                                    (brdffit_interp)interp, rgb, NULL),
                         BRDFFIT_OK);
    }
    double rgb[3];
    ck_assert_int_eq(brdffit_table_lookup_batch(t, 0, NULL, NULL, BRDFFIT_SCALE_FLAT,
                                                BRDFFIT_INTERP_NEAREST, NULL, NULL),
                     BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_lookup_batch(NULL, 1, wi, wo, BRDFFIT_SCALE_FLAT,
                                                BRDFFIT_INTERP_NEAREST, rgb, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup_batch(t, 1, wi, wo, (brdffit_scale)7,
                                                BRDFFIT_INTERP_NEAREST, rgb, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup_batch(t, 1, wi, wo, BRDFFIT_SCALE_FLAT,
                                                (brdffit_interp)7, rgb, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_table_free(t);
}
END_TEST

Suite *abi_suite(void)
{
    Suite *s = suite_create("abi");
    TCase *tc = tcase_create("abi");
    tcase_add_test(tc, struct_sizes);
    tcase_add_test(tc, struct_offsets);
    tcase_add_test(tc, lookup_batch);
    suite_add_tcase(s, tc);
    return s;
}
