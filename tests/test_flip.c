/* SPDX-License-Identifier: MIT */
/* test_flip.c -- brdffit_flip (LDR FLIP): its means on synthetic pairs
 * against NVIDIA's implementation (values from the flip-evaluator package,
 * python/tests/test_flip.py checks renders against it directly), the ranking
 * of images made worse step by step, the reuse of a reference, bad input. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define W 48
#define H 40

/* The synthetic reference: two ramps and a checker, 8-bit codes. */
static void base(float *img)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = img + 3 * ((size_t)y * W + (size_t)x);
            p[0] = (float)(((x * 5 + y * 3) % 256) / 255.0);
            p[1] = (float)(((x * x + 2 * y) % 256) / 255.0);
            p[2] = (float)(((x / 4 + y / 4) % 2 * 200 + 20) / 255.0);
        }
}

/* flip_evaluator.evaluate(ref, test, "LDR")[1] for the pairs of mean_matches. */
START_TEST(mean_matches_nvidia)
{
    static float ref[3 * W * H], t[3][3 * W * H];
    base(ref);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                size_t i = 3 * ((size_t)y * W + (size_t)x) + (size_t)c;
                t[0][i] = ref[3 * ((size_t)y * W + (size_t)(W - 1 - x)) + (size_t)c];
                float v = ref[i] * 0.8f + 0.1f;
                t[1][i] = v < 0 ? 0 : v > 1 ? 1 : v;
                t[2][i] = ref[3 * ((size_t)((y + H - 3) % H) * W + (size_t)x) + (size_t)c];
            }
    const double want[3] = { 0.7555756, 0.2568649, 0.3755016 };
    for (int k = 0; k < 3; k++) {
        double m = -1;
        ck_assert_int_eq(brdffit_flip(ref, t[k], W, H, 0, 0, NULL, &m, NULL), BRDFFIT_OK);
        ck_assert_msg(fabs(m - want[k]) < 1e-4, "pair %d: FLIP %.7f, NVIDIA's %.7f", k, m, want[k]);
    }
}
END_TEST

START_TEST(identical_is_zero)
{
    static float ref[3 * W * H], map[W * H];
    base(ref);
    double m = -1;
    ck_assert_int_eq(brdffit_flip(ref, ref, W, H, 0, 0, map, &m, NULL), BRDFFIT_OK);
    ck_assert(m == 0);
    for (int i = 0; i < W * H; i++)
        ck_assert(map[i] == 0);
}
END_TEST

/* Deterministic noise in [-1, 1]. */
static float noise(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)((*s >> 8) & 0xffff) / 32767.5f - 1.0f;
}

/* Noise of growing amplitude, then a box blur of growing radius: each step
 * ranks worse than the one before. */
START_TEST(worse_ranks_worse)
{
    static float ref[3 * W * H], t[3 * W * H];
    base(ref);
    double last = 0;
    for (int k = 1; k <= 5; k++) {
        unsigned s = 7;
        for (int i = 0; i < 3 * W * H; i++) {
            float v = ref[i] + 0.04f * (float)k * noise(&s);
            t[i] = v < 0 ? 0 : v > 1 ? 1 : v;
        }
        double m;
        ck_assert_int_eq(brdffit_flip(ref, t, W, H, 0, 0, NULL, &m, NULL), BRDFFIT_OK);
        ck_assert_msg(m > last, "noise %d: FLIP %g, not above %g", k, m, last);
        last = m;
    }
    last = 0;
    for (int r = 1; r <= 4; r++) {
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < 3; c++) {
                    float s = 0;
                    int n = 0;
                    for (int dx = -r; dx <= r; dx++) {
                        int xx = x + dx;
                        if (xx >= 0 && xx < W)
                            s += ref[3 * ((size_t)y * W + (size_t)xx) + (size_t)c], n++;
                    }
                    t[3 * ((size_t)y * W + (size_t)x) + (size_t)c] = s / (float)n;
                }
        double m;
        ck_assert_int_eq(brdffit_flip(ref, t, W, H, 0, 0, NULL, &m, NULL), BRDFFIT_OK);
        ck_assert_msg(m > last, "blur %d: FLIP %g, not above %g", r, m, last);
        last = m;
    }
}
END_TEST

/* A reference made once, compared twice with a row stride: the same map and
 * mean as brdffit_flip. */
START_TEST(reference_reused)
{
    enum { S = 3 * W + 6 };
    static float ref[3 * W * H], t[3 * W * H], rs[S * H], ts[S * H], m1[W * H], m2[W * H];
    base(ref);
    for (int i = 0; i < 3 * W * H; i++)
        t[i] = 1.0f - ref[i];
    for (int y = 0; y < H; y++) {
        memcpy(rs + (size_t)y * S, ref + 3 * (size_t)y * W, sizeof(float) * 3 * W);
        memcpy(ts + (size_t)y * S, t + 3 * (size_t)y * W, sizeof(float) * 3 * W);
    }
    double a, b, c;
    ck_assert_int_eq(brdffit_flip(ref, t, W, H, 0, 0, m1, &a, NULL), BRDFFIT_OK);
    brdffit_flip_ref *R = NULL;
    ck_assert_int_eq(brdffit_flip_ref_create(rs, W, H, S, BRDFFIT_FLIP_PPD, &R, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_flip_compare(R, ts, S, m2, &b, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_flip_compare(R, rs, S, NULL, &c, NULL), BRDFFIT_OK);
    brdffit_flip_ref_free(R);
    ck_assert(a == b && a > 0.5 && c == 0);
    ck_assert_int_eq(memcmp(m1, m2, sizeof m1), 0);
}
END_TEST

START_TEST(bad_input)
{
    static float ref[3 * W * H], t[3 * W * H];
    base(ref);
    memcpy(t, ref, sizeof t);
    double m;
    brdffit_error e;
    ck_assert_int_eq(brdffit_flip(NULL, t, W, H, 0, 0, NULL, &m, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(e.message, "brdffit_flip: ref is NULL");
    ck_assert_int_eq(brdffit_flip(ref, t, 0, H, 0, 0, NULL, &m, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(e.message, "brdffit_flip: 0 x 40 pixels (each must be in 1..65536)");
    ck_assert_int_eq(brdffit_flip(ref, t, W, H, 5, 0, NULL, &m, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(e.message, "brdffit_flip: stride 5 floats is less than a row's 3 x 48");
    ck_assert_int_eq(brdffit_flip(ref, t, W, H, 0, -3, NULL, &m, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(e.message,
                     "brdffit_flip: -3 pixels per degree (must be in 1..1000, or 0: the default)");
    t[3 * (2 * W + 5) + 1] = NAN;
    ck_assert_int_eq(brdffit_flip(ref, t, W, H, 0, 0, NULL, &m, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(e.message, "brdffit_flip: test pixel (col 5, row 2) channel G is not finite");
    ck_assert_int_eq(brdffit_flip(ref, t, W, H, 0, 0, NULL, NULL, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(e.message, "brdffit_flip: mean is NULL");
    brdffit_flip_ref *R = (brdffit_flip_ref *)&m;
    ck_assert_int_eq(brdffit_flip_ref_create(ref, -1, H, 0, 0, &R, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_null(R);
    ck_assert_int_eq(brdffit_flip_compare(NULL, t, 0, NULL, &m, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(e.message, "brdffit_flip: ref is NULL");
    brdffit_flip_ref_free(NULL);
}
END_TEST

Suite *flip_suite(void)
{
    Suite *s = suite_create("flip");
    TCase *tc = tcase_create("flip");
    tcase_add_test(tc, mean_matches_nvidia);
    tcase_add_test(tc, identical_is_zero);
    tcase_add_test(tc, worse_ranks_worse);
    tcase_add_test(tc, reference_reused);
    tcase_add_test(tc, bad_input);
    suite_add_tcase(s, tc);
    return s;
}
