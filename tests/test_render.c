/* SPDX-License-Identifier: MIT */
/* test_render.c -- renders of the sphere (brdffit_render_table / _model) and
 * the incidence-plane curves, against closed forms written here from the
 * documented conventions, and the image error. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* A table whose every bin holds the Lambertian d/pi (standard scale). */
static brdffit_table *lambert_table(const double d[3])
{
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    double f[3], *v = brdffit_table_values(t);
    brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, f, NULL);
    for (int c = 0; c < 3; c++)
        for (size_t b = 0; b < BRDFFIT_MERL_BINS; b++)
            v[c * (size_t)BRDFFIT_MERL_BINS + b] = d[c] / M_PI / f[c];
    return t;
}

static brdffit_params lambert_params(const double d[3])
{
    brdffit_params p;
    memset(&p, 0, sizeof p);
    memcpy(p.d, d, sizeof p.d);
    p.p[0] = 0.1; /* Ward alpha; s = 0 */
    return p;
}

/* The pixel centre and normal of (col, row) by the documented convention; 0 off the sphere. */
static int pixel_normal(int N, int col, int row, double n[3])
{
    double x = 2.0 * (col + 0.5) / N - 1, y = 1 - 2.0 * (row + 0.5) / N;
    if (x * x + y * y >= 1)
        return 0;
    n[0] = x, n[1] = y, n[2] = sqrt(1 - x * x - y * y);
    return 1;
}

static float *image(int N)
{
    float *img = malloc(sizeof(float) * 4 * (size_t)N * (size_t)N);
    ck_assert_ptr_nonnull(img);
    return img;
}

START_TEST(lambert_one_light)
{
    const double d[3] = { 0.2, 0.5, 0.8 };
    brdffit_table *t = lambert_table(d);
    brdffit_params p = lambert_params(d);
    brdffit_render_options o;
    brdffit_render_options_default(&o);
    o.width = 96;
    o.nlights = 1;
    const double l[3] = { 0.3, -0.4, 0.5 }; /* not unit: the library normalises */
    memcpy(o.lights[0].dir, l, sizeof l);
    const double E[3] = { 2.0, 1.0, 0.5 };
    memcpy(o.lights[0].rgb, E, sizeof E);
    double ll = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    for (int which = 0; which < 2; which++) {
        float *img = image(o.width);
        brdffit_error err;
        brdffit_status st = which == 0 ? brdffit_render_table(t, &o, img, 0, &err)
                                       : brdffit_render_model(BRDFFIT_WARD, &p, &o, img, 0, &err);
        ck_assert_msg(st == BRDFFIT_OK, "%s", err.message);
        int lit = 0, dark = 0;
        for (int row = 0; row < o.width; row++)
            for (int col = 0; col < o.width; col++) {
                const float *px = img + 4 * ((size_t)row * o.width + col);
                double n[3];
                if (!pixel_normal(o.width, col, row, n)) {
                    ck_assert(px[0] == 0 && px[1] == 0 && px[2] == 0 && px[3] == 0);
                    continue;
                }
                ck_assert(px[3] == 1.0f);
                double cosl = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / ll;
                for (int c = 0; c < 3; c++) {
                    double want = d[c] / M_PI * E[c] * fmax(0, cosl);
                    if (want == 0)
                        ck_assert(px[c] == 0);
                    else
                        ck_assert_msg(fabs(px[c] - want) <= 1e-6 * want,
                                      "pixel %d,%d ch %d: %.9g want %.9g", col, row, c, px[c],
                                      want);
                }
                *(cosl > 0 ? &lit : &dark) += 1;
            }
        ck_assert(lit > 1000 && dark > 1000);
        free(img);
    }
    brdffit_table_free(t);
}
END_TEST

START_TEST(lambert_constant_environment)
{
    const double d[3] = { 0.2, 0.5, 0.8 };
    brdffit_table *t = lambert_table(d);
    brdffit_params p = lambert_params(d);
    enum { EW = 16, EH = 8 };
    float env[EW * EH * 3];
    for (int i = 0; i < EW * EH * 3; i++)
        env[i] = 1.0f;
    brdffit_render_options o;
    brdffit_render_options_default(&o);
    o.width = 48;
    o.nlights = 0;
    o.env = env;
    o.env_width = EW;
    o.env_height = EH;
    o.env_samples = 64;
    for (int which = 0; which < 2; which++) {
        float *img = image(o.width);
        brdffit_error err;
        brdffit_status st = which == 0 ? brdffit_render_table(t, &o, img, 0, &err)
                                       : brdffit_render_model(BRDFFIT_WARD, &p, &o, img, 0, &err);
        ck_assert_msg(st == BRDFFIT_OK, "%s", err.message);
        double worst = 0;
        for (int row = 0; row < o.width; row++)
            for (int col = 0; col < o.width; col++) {
                double n[3];
                const float *px = img + 4 * ((size_t)row * o.width + col);
                if (!pixel_normal(o.width, col, row, n))
                    continue;
                for (int c = 0; c < 3; c++)
                    worst = fmax(worst, fabs(px[c] - d[c]) / d[c]);
            }
        ck_assert_msg(worst <= 0.01, "worst relative deviation from d: %g", worst);
        free(img);
    }
    brdffit_table_free(t);
}
END_TEST

/* A rough Cook-Torrance material (m = 0.3), as brdffit_table_fill_model fills tables. */
static brdffit_params rough_ct(void)
{
    brdffit_params p;
    memset(&p, 0, sizeof p);
    const double d[3] = { 0.05, 0.08, 0.12 }, s[3] = { 0.3, 0.25, 0.2 };
    memcpy(p.d, d, sizeof d);
    memcpy(p.s, s, sizeof s);
    p.p[0] = 0.6; /* F0 */
    p.p[1] = 0.3; /* m  */
    return p;
}

/* Image errors of a table filled from the rough Cook-Torrance against that
 * model's own render, default lights, 256^2, trilinear lookup.  Measured:
 * image error 0.000540 over 50260 covered pixels, 1208 of the 51468 sphere
 * pixels masked (at the rim, where a trilinear neighbour bin is below the
 * horizon); the bounds are those rounded up. */
#define CT_TABLE_IMAGE_ERROR 0.00055
START_TEST(table_from_model_matches_model)
{
    brdffit_params p = rough_ct();
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &p,
                                              BRDFFIT_SCALE_STANDARD, NULL), BRDFFIT_OK);
    int N = 256;
    float *ref = image(N), *mod = image(N);
    brdffit_error err;
    ck_assert_msg(brdffit_render_table(t, NULL, ref, 0, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, NULL, mod, 0, &err) ==
                      BRDFFIT_OK, "%s", err.message);
    double e = -1;
    size_t covered = 0, sphere = 0, masked = 0;
    ck_assert_int_eq(brdffit_image_error(ref, mod, N, N, 0, &e, &covered, NULL), BRDFFIT_OK);
    for (size_t i = 0; i < (size_t)N * N; i++) {
        sphere += ref[4 * i + 3] > 0;
        masked += ref[4 * i + 3] == BRDFFIT_COVERAGE_MASKED;
    }
    fprintf(stderr, "render: CT table vs CT model image error %.6g, covered %zu of %zu, masked %zu\n",
            e, covered, sphere, masked);
    ck_assert_msg(e <= CT_TABLE_IMAGE_ERROR, "image error %g > %g", e, CT_TABLE_IMAGE_ERROR);
    ck_assert_uint_eq(covered + masked, sphere);
    ck_assert_uint_le(masked, 1250);
    /* the model with other parameters is far off: the error measures something */
    p.p[1] = 0.15;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, NULL, mod, 0, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_image_error(ref, mod, N, N, 0, &e, NULL, NULL), BRDFFIT_OK);
    ck_assert_msg(e > 20 * CT_TABLE_IMAGE_ERROR, "other m: image error %g", e);
    free(ref);
    free(mod);
    brdffit_table_free(t);
}
END_TEST

START_TEST(renders_are_deterministic)
{
    /* the same bytes with 1, 2 and 5 threads, with lights and an environment */
    brdffit_params p = rough_ct();
    enum { EW = 32, EH = 16 };
    static float env[EW * EH * 3];
    for (int j = 0; j < EH; j++)
        for (int i = 0; i < EW; i++)
            for (int c = 0; c < 3; c++)
                env[3 * (j * EW + i) + c] = (float)(0.5 + 0.5 * sin(i * 0.7 + c) * cos(j * 0.3));
    brdffit_render_options o;
    brdffit_render_options_default(&o);
    o.width = 40;
    o.env = env;
    o.env_width = EW;
    o.env_height = EH;
    o.env_samples = 32;
    size_t bytes = sizeof(float) * 4 * 40 * 40;
    float *a = image(40), *b = image(40);
    const int threads[3] = { 1, 2, 5 };
    for (int k = 0; k < 3; k++) {
        o.threads = threads[k];
        ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &o, k ? b : a, 0, NULL),
                         BRDFFIT_OK);
        if (k)
            ck_assert_int_eq(memcmp(a, b, bytes), 0);
    }
    /* the environment adds light: brighter than the lights alone */
    o.env = NULL;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &o, b, 0, NULL), BRDFFIT_OK);
    double sa = 0, sb = 0;
    for (size_t i = 0; i < 40 * 40; i++)
        sa += a[4 * i], sb += b[4 * i];
    ck_assert(sa > sb * 1.1);
    free(a);
    free(b);
}
END_TEST

START_TEST(masked_bins_marked_in_coverage)
{
    /* a Lambertian table with every bin of theta_h index >= 64 (45.5 deg) masked (-1) */
    const double d[3] = { 0.5, 0.5, 0.5 };
    brdffit_table *t = lambert_table(d);
    double *v = brdffit_table_values(t);
    for (int i = 0; i < BRDFFIT_MERL_NTH; i++)
        for (int j = 0; j < BRDFFIT_MERL_NTD; j++)
            for (int k = 0; k < BRDFFIT_MERL_NPD; k++)
                if (i >= 64)
                v[BRDFFIT_MERL_BINS + brdffit_bin_index(i, j, k)] = -1; /* G only */
    brdffit_render_options o;
    brdffit_render_options_default(&o);
    o.width = 64;
    o.nlights = 1;
    const double l[3] = { 0, 0, 1 }; /* head-on: H = (0, 0, 1), theta_h = theta_o */
    memcpy(o.lights[0].dir, l, sizeof l);
    o.lights[0].rgb[0] = o.lights[0].rgb[1] = o.lights[0].rgb[2] = 1;
    float *img = image(64), *mod = image(64);
    ck_assert_int_eq(brdffit_render_table(t, &o, img, 0, NULL), BRDFFIT_OK);
    brdffit_params p = lambert_params(d);
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_WARD, &p, &o, mod, 0, NULL), BRDFFIT_OK);
    int masked = 0, full = 0;
    for (int row = 0; row < 64; row++)
        for (int col = 0; col < 64; col++) {
            double n[3];
            const float *px = img + 4 * (row * 64 + col);
            if (!pixel_normal(64, col, row, n))
                continue;
            ck_assert(mod[4 * (row * 64 + col) + 3] == 1.0f); /* models: never masked */
            double th = acos(n[2]) * 180 / M_PI; /* theta_h */
            /* trilinear meets bin 64 beyond index 63, theta_h = (63/90)^2 90 = 44.1 deg */
            if (th > 45.6) {
                ck_assert(px[3] == BRDFFIT_COVERAGE_MASKED);
                ck_assert(px[1] == 0);        /* the masked channel counts 0 */
                ck_assert(px[0] > 0);         /* the others are kept */
                masked++;
            } else if (th < 43.5) {
                ck_assert(px[3] == 1.0f);
                full++;
            }
        }
    ck_assert(masked > 100 && full > 100);
    /* the image error counts only the fully covered pixels */
    double e;
    size_t covered;
    ck_assert_int_eq(brdffit_image_error(img, mod, 64, 64, 0, &e, &covered, NULL), BRDFFIT_OK);
    ck_assert(e < 1e-6);
    ck_assert(covered >= (size_t)full);
    free(img);
    free(mod);
    brdffit_table_free(t);
}
END_TEST

START_TEST(render_rejects_bad_options)
{
    brdffit_params p = rough_ct();
    brdffit_render_options o;
    brdffit_render_options_default(&o);
    ck_assert_uint_eq(o.size, sizeof o);
    ck_assert_int_eq(o.width, 256);
    ck_assert_int_eq(o.env_samples, 256);
    o.width = 8;
    float img[4 * 8 * 8 + 64];
    brdffit_error err;
    brdffit_render_options b = o;
    b.size = 0;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, &err),
                     BRDFFIT_E_OPTIONS_SIZE);
    ck_assert_ptr_nonnull(strstr(err.message, "brdffit_render_options: size 0"));
    b.size = sizeof b + 8;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL),
                     BRDFFIT_E_OPTIONS_SIZE);
    b = o;
    b.nlights = 1;
    b.lights[0].dir[0] = NAN;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_nonnull(strstr(err.message, "light 0"));
    b.lights[0].dir[0] = 0, b.lights[0].dir[1] = 0, b.lights[0].dir[2] = 0;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    b.lights[0].dir[2] = 1;
    b.lights[0].rgb[1] = -1;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    b = o;
    b.nlights = 17;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    b = o;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 31, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT); /* stride < 4 x 8 */
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, NULL, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    b.width = 0;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    float env[6] = { 1, 1, 1, 1, NAN, 1 };
    b = o;
    b.env = env;
    b.env_width = 2;
    b.env_height = 1;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, &err),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_nonnull(strstr(err.message, "texel (1, 0)"));
    env[4] = 1;
    b.env_samples = 0;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    b.env_samples = 4;
    b.env_stride = 5;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    b.env_stride = 0;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &b, img, 0, NULL), BRDFFIT_OK);
    p.p[1] = 7; /* m out of bounds */
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &o, img, 0, NULL),
                     BRDFFIT_E_PARAM_RANGE);
    ck_assert_int_eq(brdffit_render_table(NULL, &o, img, 0, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    /* a stride wider than a row leaves the gap untouched */
    float wide[8 * 40];
    for (int i = 0; i < 8 * 40; i++)
        wide[i] = -7;
    p = rough_ct();
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &o, wide, 40, NULL), BRDFFIT_OK);
    for (int row = 0; row < 8; row++)
        for (int i = 32; i < 40; i++)
            ck_assert(wide[row * 40 + i] == -7);
    brdffit_light dl[2];
    ck_assert_int_eq(brdffit_render_default_lights(dl), 2);
    ck_assert(dl[1].dir[2] < 0); /* the rim light is behind the sphere */
}
END_TEST

START_TEST(image_error_values)
{
    float ref[4 * 3] = { 1, 1, 1, 1, 2, 2, 2, 1, 9, 9, 9, 0.5f };
    float img[4 * 3] = { 1, 1, 2, 1, 2, 2, 2, 1, 0, 0, 0, 1 };
    double e;
    size_t n;
    ck_assert_int_eq(brdffit_image_error(ref, img, 3, 1, 0, &e, &n, NULL), BRDFFIT_OK);
    ck_assert_uint_eq(n, 2);                        /* the masked pixel is left out */
    ck_assert_double_eq_tol(e, sqrt(1.0 / 15.0), 1e-15); /* sum d^2 = 1, sum ref^2 = 3 + 12 */
    float black[4 * 3] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    ck_assert_int_eq(brdffit_image_error(black, img, 3, 1, 0, &e, &n, NULL), BRDFFIT_E_NO_SAMPLES);
    ck_assert_int_eq(brdffit_image_error(ref, img, 3, 1, 11, &e, &n, NULL), BRDFFIT_E_INVALID_ARGUMENT);
}
END_TEST

START_TEST(curves_equal_eval_and_lookup)
{
    brdffit_params p = rough_ct();
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &p,
                                              BRDFFIT_SCALE_STANDARD, NULL), BRDFFIT_OK);
    brdffit_curve_options o;
    brdffit_curve_options_default(&o);
    ck_assert_int_eq(o.ntheta_i, 4);
    ck_assert_double_eq(o.theta_i_deg[3], 75);
    ck_assert_int_eq(o.npoints, 180);
    double th[180];
    ck_assert_int_eq(brdffit_curve_theta_o(&o, th, NULL), BRDFFIT_OK);
    ck_assert_double_eq_tol(th[0], -89.5, 1e-12);
    ck_assert_double_eq_tol(th[179], 89.5, 1e-12);
    size_t stride = 3 * 180 + 5;
    double *m = malloc(sizeof(double) * 4 * stride), *r = malloc(sizeof(double) * 4 * stride);
    ck_assert_int_eq(brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &o, m, stride, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_curve_table(t, &o, r, stride, NULL), BRDFFIT_OK);
    int masked = 0;
    for (int a = 0; a < 4; a++) {
        double ti = o.theta_i_deg[a] * (M_PI / 180); /* as documented: deg x (pi/180) */
        double wi[3] = { -sin(ti), 0, cos(ti) };
        int peak = 0;
        for (int k = 0; k < 180; k++) {
            double to = th[k] * (M_PI / 180);
            double wo[3] = { sin(to), 0, cos(to) }, f[3], g[3];
            ck_assert_int_eq(brdffit_eval(BRDFFIT_COOK_TORRANCE, &p, wi, wo, f, NULL), BRDFFIT_OK);
            ck_assert_int_eq(brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_STANDARD,
                                                  BRDFFIT_INTERP_TRILINEAR, g, NULL), BRDFFIT_OK);
            for (int c = 0; c < 3; c++) {
                ck_assert(m[a * stride + 3 * k + c] == f[c]);
                ck_assert_msg(r[a * stride + 3 * k + c] == g[c], "a %d k %d c %d: %.17g %.17g", a, k, c, r[a * stride + 3 * k + c], g[c]);
                masked += g[c] < 0;
            }
            if (m[a * stride + 3 * k] > m[a * stride + 3 * peak])
                peak = k;
        }
        /* the highlight is on the mirror side (rough Cook-Torrance peaks off-specular,
         * beyond theta_i) */
        ck_assert_msg(th[peak] >= o.theta_i_deg[a] - 1, "theta_i %g: peak at %g",
                      o.theta_i_deg[a], th[peak]);
    }
    ck_assert(masked > 0); /* near the horizon the trilinear lookup meets masked bins */
    o.ntheta_i = 0;
    ck_assert_int_eq(brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &o, m, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    o.ntheta_i = 1;
    o.theta_i_deg[0] = 90;
    ck_assert_int_eq(brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &o, m, 0, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    o.theta_i_deg[0] = 10;
    ck_assert_int_eq(brdffit_curve_model(BRDFFIT_COOK_TORRANCE, &p, &o, m, 10, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    o.size = 0;
    ck_assert_int_eq(brdffit_curve_table(t, &o, r, 0, NULL), BRDFFIT_E_OPTIONS_SIZE);
    free(m);
    free(r);
    brdffit_table_free(t);
}
END_TEST

/* Every value of an N x N image is 0. */
static void expect_cleared(const float *img, int n)
{
    for (int i = 0; i < 4 * n * n; i++)
        ck_assert_msg(img[i] == 0.0f, "value %d is %g", i, (double)img[i]);
}

/* Every value of an N x N image is finite. */
static void expect_finite(const float *img, int n)
{
    for (int i = 0; i < 4 * n * n; i++)
        ck_assert_msg(isfinite(img[i]), "value %d is %g", i, (double)img[i]);
}

/* What a render cannot represent is refused with BRDFFIT_E_VALUE_RANGE naming
 * it, the image cleared; the largest accepted inputs give finite pixels. */
START_TEST(render_refuses_overflow)
{
    enum { N = 8, EW = 4, EH = 2 };
    static float img[4 * N * N];
    float env[3 * EW * EH];
    for (int i = 0; i < 3 * EW * EH; i++)
        env[i] = 1.0f;
    const double d[3] = { 0.5, 0.5, 0.5 };
    brdffit_params p = lambert_params(d);
    brdffit_render_options o;
    brdffit_render_options_default(&o);
    o.width = N;
    o.env = env;
    o.env_width = EW;
    o.env_height = EH;
    o.env_samples = 8;
    brdffit_error err;
    /* a finite texel too bright (1e36: finite as a float) */
    env[3 * (1 * EW + 2) + 1] = 1e36f;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_WARD, &p, &o, img, 0, &err), BRDFFIT_E_VALUE_RANGE);
    ck_assert_msg(strstr(err.message, "texel (2, 1) channel 1 is 1e+36, above BRDFFIT_RADIANCE_MAX (1e+20)"),
                  "%s", err.message);
    env[3 * (1 * EW + 2) + 1] = 1.0f;
    /* a light too bright */
    o.nlights = 1;
    o.lights[0] = (brdffit_light){ { 0, 0, 1 }, { 1, 2e20, 1 } };
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_WARD, &p, &o, img, 0, &err), BRDFFIT_E_VALUE_RANGE);
    ck_assert_msg(strstr(err.message, "light 0: irradiance (1, 2e+20, 1) is above BRDFFIT_RADIANCE_MAX"),
                  "%s", err.message);
    /* accepted inputs, but d so large that pixels go past the largest float */
    o.lights[0].rgb[1] = 1;
    p.d[2] = 1e300;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_WARD, &p, &o, img, 0, &err), BRDFFIT_E_VALUE_RANGE);
    ck_assert_msg(strstr(err.message, "channel B would be ") && strstr(err.message, "beyond the largest float"),
                  "%s", err.message);
    expect_cleared(img, N);
    /* s so large that the BRDF itself is infinite */
    p = rough_ct();
    p.s[0] = 1.7e308;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &o, img, 0, &err),
                     BRDFFIT_E_VALUE_RANGE);
    ck_assert_msg(strstr(err.message, "the model's value in channel R is inf"), "%s", err.message);
    expect_cleared(img, N);
    /* the same pixel is named with any number of threads */
    char first[BRDFFIT_MESSAGE_MAX];
    snprintf(first, sizeof first, "%s", err.message);
    o.threads = 3;
    ck_assert_int_eq(brdffit_render_model(BRDFFIT_COOK_TORRANCE, &p, &o, img, 0, &err),
                     BRDFFIT_E_VALUE_RANGE);
    ck_assert_str_eq(err.message, first);
    /* the largest table values, lights and texels accepted: every pixel finite */
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    double *v = brdffit_table_values(t);
    for (size_t b = 0; b < 3 * (size_t)BRDFFIT_MERL_BINS; b++)
        v[b] = BRDFFIT_VALUE_MAX;
    for (int i = 0; i < 3 * EW * EH; i++)
        env[i] = (float)BRDFFIT_RADIANCE_MAX;
    o.nlights = BRDFFIT_RENDER_MAX_LIGHTS;
    for (int k = 0; k < o.nlights; k++)
        o.lights[k] = (brdffit_light){ { 0, 0, 1 },
                                       { BRDFFIT_RADIANCE_MAX, BRDFFIT_RADIANCE_MAX, BRDFFIT_RADIANCE_MAX } };
    ck_assert_msg(brdffit_render_table(t, &o, img, 0, &err) == BRDFFIT_OK, "%s", err.message);
    expect_finite(img, N);
    ck_assert(img[4 * (N / 2 * N + N / 2)] > 1e37f);
    /* a table set in memory beyond BRDFFIT_VALUE_MAX: refused at the pixel */
    for (size_t b = 0; b < 3 * (size_t)BRDFFIT_MERL_BINS; b++)
        v[b] = 1e30;
    ck_assert_int_eq(brdffit_render_table(t, &o, img, 0, &err), BRDFFIT_E_VALUE_RANGE);
    ck_assert_msg(strstr(err.message, "beyond the largest float"), "%s", err.message);
    expect_cleared(img, N);
    brdffit_table_free(t);
}
END_TEST

Suite *render_suite(void)
{
    Suite *s = suite_create("render");
    TCase *tc = tcase_create("render");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, lambert_one_light);
    tcase_add_test(tc, lambert_constant_environment);
    tcase_add_test(tc, table_from_model_matches_model);
    tcase_add_test(tc, renders_are_deterministic);
    tcase_add_test(tc, masked_bins_marked_in_coverage);
    tcase_add_test(tc, render_rejects_bad_options);
    tcase_add_test(tc, render_refuses_overflow);
    tcase_add_test(tc, image_error_values);
    tcase_add_test(tc, curves_equal_eval_and_lookup);
    suite_add_tcase(s, tc);
    return s;
}
