/* SPDX-License-Identifier: MIT */
/* test_table.c -- MERL tables (read/write/validation, bins, weights, scales,
 * lookup) and sample sets. */
#define _POSIX_C_SOURCE 200809L
#include "brdffit.h"
#include "internal.h" /* bf_scale_factors */
#include "samples.h"  /* struct brdffit_samples: the prepared fields */
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define NB ((size_t)BRDFFIT_MERL_BINS)
#define FILE_BYTES ((size_t)12 + 3 * NB * sizeof(double)) /* 34,992,012 */
#define PI 3.14159265358979323846

/* ------------------------------------------------------------------ helpers */

/* Checks inside loops over all 1.4 million bins: Check's ck_assert_* records
 * a mark point (a write to the runner) per call, far too slow there, so such
 * loops count failures and assert once, quoting the first. */
static size_t nbad;
static char first_bad[256];
static void note_bad(const char *what, int line)
{
    if (nbad++ == 0)
        snprintf(first_bad, sizeof first_bad, "line %d: %s", line, what);
}
#define EXPECT(cond) ((cond) ? (void)0 : note_bad(#cond, __LINE__))
#define EXPECT_RESET() (nbad = 0, first_bad[0] = '\0')
#define EXPECT_NONE() \
    ck_assert_msg(nbad == 0, "%zu failed checks, the first at %s", nbad, first_bad)

/* The directions of a (continuous) half/difference angle triple, computed
 * here independently of the library, the way merl-from-nbrdf.c does. */
static void hd_dirs(double th, double td, double pd, double wi[3], double wo[3])
{
    double d[3] = { sin(td) * cos(pd), sin(td) * sin(pd), cos(td) };
    double h[3] = { sin(th), 0.0, cos(th) };
    wi[0] = d[0] * cos(th) + d[2] * sin(th);
    wi[1] = d[1];
    wi[2] = -d[0] * sin(th) + d[2] * cos(th);
    double hd = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
    for (int c = 0; c < 3; c++)
        wo[c] = 2 * hd * h[c] - wi[c];
}

/* Directions of bin (i, j, k), independently of brdffit_bin_directions. */
static void my_bin_dirs(int i, int j, int k, double wi[3], double wo[3])
{
    double u = (double)i / 90, th = u * u * PI / 2;
    hd_dirs(th, (double)j / 90 * PI / 2, (double)k / 180 * PI, wi, wo);
}

/* Directions at continuous grid coordinates (bin units). */
static void grid_dirs(double uh, double ud, double up, double wi[3], double wo[3])
{
    double u = uh / 90;
    hd_dirs(u * u * PI / 2, ud / 90 * PI / 2, up / 180 * PI, wi, wo);
}

static double my_weight(int i, int j)
{
    double a = (double)i / 90, b = (double)(i + 1) / 90;
    double sl = sin(j * PI / 180), sh = sin((j + 1) * PI / 180);
    return (cos(a * a * PI / 2) - cos(b * b * PI / 2)) * (sh * sh - sl * sl) / 2;
}

static const brdffit_params ct_params = {
    .d = { 0.0886, 0.0602, 0.0299 },
    .s = { 0.118, 0.0698, 0.0371 },
    .p = { 0.203, 0.0367 },
};

static brdffit_table *ct_table(brdffit_scale scale)
{
    brdffit_table *t = NULL;
    brdffit_error e;
    ck_assert_int_eq(brdffit_table_create(&t, &e), BRDFFIT_OK);
    ck_assert_ptr_nonnull(t);
    brdffit_status s = brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &ct_params, scale, &e);
    ck_assert_msg(s == BRDFFIT_OK, "fill_model: %s", e.message);
    return t;
}

/* A new table: every value 0 (brdffit_table_create). */
static brdffit_table *zero_table(void)
{
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    return t;
}

/* Write a valid (all-zero) table to a fresh temporary file. */
static void zero_table_file(char *path, size_t len)
{
    ck_assert_ptr_nonnull(tu_tmpfile(path, len));
    brdffit_table *t = zero_table();
    brdffit_error e;
    ck_assert_int_eq(brdffit_table_write(t, path, &e), BRDFFIT_OK);
    brdffit_table_free(t);
}

/* Expect brdffit_table_read(path) to fail with status; the message names
 * the path and contains `want` (when not NULL); *out stays NULL. */
static void expect_read_fail(const char *path, brdffit_status status, const char *want)
{
    brdffit_table *t = (brdffit_table *)&t; /* a non-NULL sentinel */
    brdffit_error e;
    memset(&e, 0, sizeof e);
    brdffit_status s = brdffit_table_read(path, &t, &e);
    ck_assert_msg(s == status, "%s: got status %d (%s: %s), expected %d (%s)", path, (int)s,
                  brdffit_strerror(s), e.message, (int)status, brdffit_strerror(status));
    ck_assert_int_eq(e.status, status);
    ck_assert_ptr_null(t);
    ck_assert_msg(strstr(e.message, path) != NULL, "message '%s' does not name '%s'", e.message,
                  path);
    if (want)
        ck_assert_msg(strstr(e.message, want) != NULL, "message '%s' lacks '%s'", e.message,
                      want);
    /* and without an error report: same status, no crash */
    t = (brdffit_table *)&t;
    ck_assert_int_eq(brdffit_table_read(path, &t, NULL), status);
    ck_assert_ptr_null(t);
}

static void write_header(unsigned char *b, int32_t a, int32_t c, int32_t d)
{
    int32_t dims[3] = { a, c, d };
    memcpy(b, dims, sizeof dims); /* little-endian host */
}

/* Overwrite 8 bytes at value index n (of 3 x BINS) with x. */
static void poke_value(const char *path, size_t n, double x)
{
    FILE *f = fopen(path, "r+b");
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(fseek(f, (long)(12 + 8 * n), SEEK_SET), 0);
    ck_assert_int_eq(fwrite(&x, sizeof x, 1, f), 1);
    ck_assert_int_eq(fclose(f), 0);
}

/* ------------------------------------------------------------------ 1. model tables */

START_TEST(test_fill_model_values)
{
    brdffit_table *t = ct_table(BRDFFIT_SCALE_STANDARD);
    const double *v = brdffit_table_values_const(t);
    double f[3];
    ck_assert_int_eq(brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, f, NULL), BRDFFIT_OK);
    size_t above = 0, below = 0;
    EXPECT_RESET();
    for (int i = 0; i < 90; i++)
        for (int j = 0; j < 90; j++)
            for (int k = 0; k < 180; k++) {
                double wi[3], wo[3], lib_wi[3], lib_wo[3];
                my_bin_dirs(i, j, k, wi, wo);
                EXPECT(brdffit_bin_directions(i, j, k, lib_wi, lib_wo, NULL) == BRDFFIT_OK);
                EXPECT(memcmp(wi, lib_wi, sizeof wi) == 0 && memcmp(wo, lib_wo, sizeof wo) == 0);
                size_t b = brdffit_bin_index(i, j, k);
                EXPECT(b == (size_t)k + 180 * ((size_t)j + 90 * (size_t)i));
                if (wi[2] > 0 && wo[2] > 0) {
                    above++;
                    /* spot check one bin in 97 against brdffit_eval */
                    if (b % 97 == 0) {
                        double rgb[3];
                        EXPECT(brdffit_eval(BRDFFIT_COOK_TORRANCE, &ct_params, wi, wo, rgb, NULL) ==
                               BRDFFIT_OK);
                        for (int c = 0; c < 3; c++)
                            EXPECT(tu_reldiff(v[c * NB + b] * f[c], rgb[c]) <= 1e-14);
                    }
                    for (int c = 0; c < 3; c++)
                        EXPECT(v[c * NB + b] > 0.0);
                } else {
                    below++;
                    for (int c = 0; c < 3; c++)
                        EXPECT(v[c * NB + b] == -1.0);
                }
            }
    EXPECT_NONE();
    ck_assert_uint_gt(above, NB / 2);
    ck_assert_uint_gt(below, 0);
    /* at normal incidence the value exceeds the diffuse part d/pi / scale */
    size_t b0 = brdffit_bin_index(0, 0, 0);
    ck_assert_double_gt(v[b0], ct_params.d[0] / PI / f[0]);
    brdffit_table_free(t);
}
END_TEST

START_TEST(test_fill_model_errors)
{
    brdffit_table *t = NULL;
    brdffit_error e;
    ck_assert_int_eq(brdffit_table_create(&t, &e), BRDFFIT_OK);
    brdffit_params p = ct_params;
    p.p[1] = -1; /* m out of range */
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &p, BRDFFIT_SCALE_STANDARD,
                                              &e), BRDFFIT_E_PARAM_RANGE);
    ck_assert_int_eq(e.status, BRDFFIT_E_PARAM_RANGE);
    p = ct_params;
    p.d[1] = NAN;
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &p, BRDFFIT_SCALE_STANDARD,
                                              &e), BRDFFIT_E_PARAM_RANGE);
    ck_assert_int_eq(brdffit_table_fill_model(t, (brdffit_model)99, &ct_params,
                                              BRDFFIT_SCALE_STANDARD, &e),
                     BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, &ct_params,
                                              (brdffit_scale)5, &e),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_COOK_TORRANCE, NULL,
                                              BRDFFIT_SCALE_STANDARD, &e),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_fill_model(NULL, BRDFFIT_COOK_TORRANCE, &ct_params,
                                              BRDFFIT_SCALE_STANDARD, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    /* a failed fill leaves the table untouched (all zeros still) */
    const double *v = brdffit_table_values_const(t);
    for (size_t n = 0; n < 3 * NB; n++)
        if (v[n] != 0.0)
            ck_abort_msg("value %zu changed by a failed fill", n);
    brdffit_table_free(t);
}
END_TEST

START_TEST(test_write_read_roundtrip)
{
    brdffit_table *t = ct_table(BRDFFIT_SCALE_STANDARD), *r = NULL;
    char path[512];
    brdffit_error e;
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    ck_assert_int_eq(brdffit_table_write(t, path, &e), BRDFFIT_OK);
    ck_assert_int_eq(e.status, BRDFFIT_OK);
    /* the file is exactly the MERL layout */
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    int32_t dims[3];
    ck_assert_int_eq(fread(dims, sizeof dims, 1, f), 1);
    ck_assert_int_eq(dims[0], 90);
    ck_assert_int_eq(dims[1], 90);
    ck_assert_int_eq(dims[2], 180);
    ck_assert_int_eq(fseek(f, 0, SEEK_END), 0);
    ck_assert_int_eq(ftell(f), (long)FILE_BYTES);
    fclose(f);

    brdffit_status s = brdffit_table_read(path, &r, &e);
    ck_assert_msg(s == BRDFFIT_OK, "%s", e.message);
    ck_assert_ptr_nonnull(r);
    ck_assert_int_eq(memcmp(brdffit_table_values_const(t), brdffit_table_values_const(r),
                            3 * NB * sizeof(double)), 0);
    brdffit_table_free(r);
    brdffit_table_free(t);
    unlink(path);
}
END_TEST

START_TEST(test_write_errors)
{
    brdffit_table *t = NULL;
    brdffit_error e;
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    const char *nodir = "/nonexistent-brdffit-dir/x.binary";
    ck_assert_int_eq(brdffit_table_write(t, nodir, &e), BRDFFIT_E_FILE_WRITE);
    ck_assert_ptr_nonnull(strstr(e.message, nodir));
    if (access("/dev/full", W_OK) == 0) {
        ck_assert_int_eq(brdffit_table_write(t, "/dev/full", &e), BRDFFIT_E_FILE_WRITE);
        ck_assert_ptr_nonnull(strstr(e.message, "/dev/full"));
    }
    ck_assert_int_eq(brdffit_table_write(NULL, "/tmp/x", &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_write(t, NULL, &e), BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_table_free(t);
}
END_TEST

/* Nearest (and trilinear) lookup at each bin's own directions gives that bin,
 * for every bin: above the horizon on the model table, and, on a table whose
 * values are the bin indices, for every bin at all. */
START_TEST(test_lookup_own_bins)
{
    brdffit_table *t = ct_table(BRDFFIT_SCALE_STANDARD);
    const double *v = brdffit_table_values_const(t);
    double f[3];
    brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, f, NULL);
    size_t checked = 0, bad_near = 0, bad_tri = 0;
    EXPECT_RESET();
    for (int i = 0; i < 90; i++)
        for (int j = 0; j < 90; j++)
            for (int k = 0; k < 180; k++) {
                double wi[3], wo[3], a[3], b[3];
                brdffit_bin_directions(i, j, k, wi, wo, NULL);
                if (!(wi[2] > 0 && wo[2] > 0))
                    continue;
                size_t n = brdffit_bin_index(i, j, k);
                EXPECT(brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_STANDARD,
                                            BRDFFIT_INTERP_NEAREST, a, NULL) == BRDFFIT_OK);
                EXPECT(brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_STANDARD,
                                            BRDFFIT_INTERP_TRILINEAR, b, NULL) == BRDFFIT_OK);
                checked++;
                for (int c = 0; c < 3; c++) {
                    double want = v[c * NB + n] * f[c];
                    if (a[c] != want)
                        bad_near++;
                    /* at theta_d = 0 phi_d is undefined: the k of that row are
                     * the same directions and values, interpolation may round */
                    if (j > 0 ? b[c] != want : tu_reldiff(b[c], want) > 1e-14)
                        bad_tri++;
                }
            }
    EXPECT_NONE();
    ck_assert_uint_gt(checked, NB / 2);
    ck_assert_uint_eq(bad_near, 0);
    ck_assert_uint_eq(bad_tri, 0);

    /* every bin, horizon or not: R = the bin index + 1, G = B = 1 */
    double *w = brdffit_table_values(t);
    for (size_t n = 0; n < NB; n++) {
        w[n] = (double)n + 1;
        w[NB + n] = 1;
        w[2 * NB + n] = 1;
    }
    size_t wrong = 0;
    for (int i = 0; i < 90; i++)
        for (int j = 0; j < 90; j++)
            for (int k = 0; k < 180; k++) {
                double wi[3], wo[3], a[3];
                brdffit_bin_directions(i, j, k, wi, wo, NULL);
                EXPECT(brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT,
                                            BRDFFIT_INTERP_NEAREST, a, NULL) == BRDFFIT_OK);
                size_t got = (size_t)llround(a[0] * 1500.0) - 1;
                size_t want = brdffit_bin_index(i, j, k);
                /* theta_d = 0: any bin (i, 0, k') is the same pair of directions */
                if (j == 0 ? got / 180 != want / 180 : got != want)
                    wrong++;
            }
    EXPECT_NONE();
    ck_assert_uint_eq(wrong, 0);
    brdffit_table_free(t);
}
END_TEST

/* A table of a smooth, non-linear pattern with distinct values (*v: its values). */
static brdffit_table *interp_table(double **v)
{
    brdffit_table *t = zero_table();
    *v = brdffit_table_values(t);
    for (int i = 0; i < 90; i++)
        for (int j = 0; j < 90; j++)
            for (int k = 0; k < 180; k++) {
                size_t n = brdffit_bin_index(i, j, k);
                (*v)[n] = 1 + i + 0.01 * j * j + 0.001 * k;
                (*v)[NB + n] = 2 + 0.5 * i;
                (*v)[2 * NB + n] = 3 + sin(0.1 * k);
            }
    return t;
}

START_TEST(test_lookup_interp)
{
    double *v, f[3], wi[3], wo[3], a[3], b[3];
    brdffit_table *t = interp_table(&v);
    brdffit_scale_factors(BRDFFIT_SCALE_FLAT, f, NULL);

    /* the middle of a cell: the mean of its 8 corners; nearest: the lower corner */
    grid_dirs(10.5, 20.5, 30.5, wi, wo);
    ck_assert_int_eq(brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR,
                                          a, NULL), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST,
                                          b, NULL), BRDFFIT_OK);
    for (int c = 0; c < 3; c++) {
        double mean = 0;
        for (int di = 0; di < 2; di++)
            for (int dj = 0; dj < 2; dj++)
                for (int dk = 0; dk < 2; dk++)
                    mean += v[c * NB + brdffit_bin_index(10 + di, 20 + dj, 30 + dk)] / 8;
        ck_assert_double_le(tu_reldiff(a[c], mean * f[c]), 1e-9);
        ck_assert_double_eq(b[c], v[c * NB + brdffit_bin_index(10, 20, 30)] * f[c]);
    }

    /* a quarter of the way along theta_d only */
    grid_dirs(40, 30.25, 100, wi, wo);
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, a, NULL);
    {
        double lo = v[brdffit_bin_index(40, 30, 100)], hi = v[brdffit_bin_index(40, 31, 100)];
        ck_assert_double_le(tu_reldiff(a[0], (0.75 * lo + 0.25 * hi) * f[0]), 1e-9);
    }

    /* phi_d wraps: between k = 179 and k = 0 */
    grid_dirs(5, 50, 179.5, wi, wo);
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, a, NULL);
    {
        double lo = v[2 * NB + brdffit_bin_index(5, 50, 179)];
        double hi = v[2 * NB + brdffit_bin_index(5, 50, 0)];
        ck_assert_double_le(tu_reldiff(a[2], 0.5 * (lo + hi) * f[2]), 1e-9);
    }

    /* clamped beyond the last theta_h bin centre (89 < uh < 90) */
    grid_dirs(89.5, 10, 20, wi, wo);
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, a, NULL);
    ck_assert_double_eq(a[1], v[NB + brdffit_bin_index(89, 10, 20)] * f[1]);
    brdffit_table_free(t);
}
END_TEST

START_TEST(test_lookup_symmetries)
{
    double *v, wi[3], wo[3];
    brdffit_table *t = interp_table(&v);

    /* reciprocity: phi_d + pi is the same bin */
    double wi2[3], wo2[3], c1[3], c2[3];
    grid_dirs(33.2, 44.7, 55.3, wi, wo);
    grid_dirs(33.2, 44.7, 55.3 + 180, wi2, wo2);
    for (int m = 0; m < 2; m++) {
        brdffit_interp in = m ? BRDFFIT_INTERP_TRILINEAR : BRDFFIT_INTERP_NEAREST;
        brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, in, c1, NULL);
        brdffit_table_lookup(t, wi2, wo2, BRDFFIT_SCALE_FLAT, in, c2, NULL);
        for (int c = 0; c < 3; c++)
            ck_assert_double_le(tu_reldiff(c1[c], c2[c]), 1e-9);
    }
    /* swapping wi and wo (reciprocity) gives the same value */
    brdffit_table_lookup(t, wo, wi, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, c2, NULL);
    for (int c = 0; c < 3; c++)
        ck_assert_double_le(tu_reldiff(c1[c], c2[c]), 1e-9);

    /* directions need not be unit vectors */
    double wi3[3], wo3[3];
    grid_dirs(12.3, 45.6, 78.9, wi, wo);
    for (int c = 0; c < 3; c++) {
        wi3[c] = 3 * wi[c];
        wo3[c] = 0.5 * wo[c];
    }
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, c1, NULL);
    brdffit_table_lookup(t, wi3, wo3, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, c2, NULL);
    for (int c = 0; c < 3; c++)
        ck_assert_double_le(tu_reldiff(c1[c], c2[c]), 1e-12);
    brdffit_table_free(t);
}
END_TEST

START_TEST(test_lookup_masked_corner)
{
    double *v, f[3], wi[3], wo[3], a[3];
    brdffit_table *t = interp_table(&v);
    brdffit_scale_factors(BRDFFIT_SCALE_FLAT, f, NULL);

    /* a masked corner: -1 in that channel only, for trilinear; nearest of the
     * lower corner is unaffected unless it is the masked one */
    v[NB + brdffit_bin_index(11, 21, 31)] = -1;
    grid_dirs(10.5, 20.5, 30.5, wi, wo);
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, a, NULL);
    ck_assert_double_eq(a[1], -1.0);
    ck_assert_double_gt(a[0], 0.0);
    ck_assert_double_gt(a[2], 0.0);
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST, a, NULL);
    ck_assert_double_gt(a[1], 0.0);
    /* ... but a masked bin with zero weight does not matter */
    grid_dirs(10, 20, 30, wi, wo);
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_TRILINEAR, a, NULL);
    ck_assert_double_eq(a[1], v[NB + brdffit_bin_index(10, 20, 30)] * f[1]);
    grid_dirs(11, 21, 31, wi, wo);
    brdffit_table_lookup(t, wi, wo, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST, a, NULL);
    ck_assert_double_eq(a[1], -1.0);
    brdffit_table_free(t);
}
END_TEST

START_TEST(test_lookup_invalid_arguments)
{
    double *v, f[3], a[3];
    brdffit_table *t = interp_table(&v);
    brdffit_scale_factors(BRDFFIT_SCALE_FLAT, f, NULL);
    const double zero[3] = { 0, 0, 0 }, nan3[3] = { NAN, 0, 1 }, inf3[3] = { 0, INFINITY, 1 };
    const double up[3] = { 0, 0, 1 }, down[3] = { 0, 0, -1 };
    ck_assert_int_eq(brdffit_table_lookup(t, zero, up, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST,
                                          a, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(t, up, nan3, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST,
                                          a, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(t, inf3, up, BRDFFIT_SCALE_FLAT,
                                          BRDFFIT_INTERP_TRILINEAR, a, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(t, up, down, BRDFFIT_SCALE_FLAT,
                                          BRDFFIT_INTERP_TRILINEAR, a, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(NULL, up, up, BRDFFIT_SCALE_FLAT,
                                          BRDFFIT_INTERP_NEAREST, a, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(t, NULL, up, BRDFFIT_SCALE_FLAT,
                                          BRDFFIT_INTERP_NEAREST, a, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(t, up, up, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST,
                                          NULL, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(t, up, up, (brdffit_scale)9, BRDFFIT_INTERP_NEAREST,
                                          a, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_lookup(t, up, up, BRDFFIT_SCALE_FLAT, (brdffit_interp)9, a, NULL),
                     BRDFFIT_E_INVALID_ARGUMENT);
    /* and the valid call after them */
    ck_assert_int_eq(brdffit_table_lookup(t, up, up, BRDFFIT_SCALE_FLAT, BRDFFIT_INTERP_NEAREST,
                                          a, NULL), BRDFFIT_OK);
    ck_assert_double_eq(a[0], v[0] * f[0]);
    brdffit_table_free(t);
}
END_TEST

/* ------------------------------------------------------------------ 2. MERL tables */

/* A table's bins counted independently of the library: valid ones (n,
 * their sums of the solid-angle weight w and of w cos^2 ti), masked ones
 * and those beyond the 80-degree cutoff. */
typedef struct bin_count {
    size_t n, masked, beyond;
    double sw, swc;
} bin_count;

static bin_count count_bins(const double *v)
{
    const double cosc = cos(80.0 * PI / 180.0) - 1e-12;
    bin_count bc = { 0, 0, 0, 0.0, 0.0 };
    for (int i = 0; i < 90; i++)
        for (int j = 0; j < 90; j++)
            for (int k = 0; k < 180; k++) {
                size_t b = (size_t)k + 180 * ((size_t)j + 90 * (size_t)i);
                if (v[b] < 0 || v[NB + b] < 0 || v[2 * NB + b] < 0) {
                    bc.masked++;
                    continue;
                }
                double wi[3], wo[3];
                my_bin_dirs(i, j, k, wi, wo);
                if (wi[2] > 0 && wo[2] > 0 && wi[2] >= cosc && wo[2] >= cosc) {
                    bc.n++;
                    double w = my_weight(i, j);
                    bc.sw += w;
                    bc.swc += w * wi[2] * wi[2];
                } else {
                    bc.beyond++;
                }
            }
    return bc;
}

/* Each sample of sm (n valid, the table's values v, sum of weights sw): its
 * bin once and in table order, its directions, standard-scaled values,
 * weight, N.H, V.H and a^2; the padding past n neutral. */
static void check_sample_block(const brdffit_samples *sm, const double *v, size_t n, double sw)
{
    double f[3];
    brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, f, NULL);
    const size_t np = sm->npad;
    int prev = -1;
    EXPECT_RESET();
    for (size_t m = 0; m < n; m++) {
        brdffit_sample x;
        brdffit_sample_init(&x);
        EXPECT(brdffit_samples_get(sm, m, &x, NULL) == BRDFFIT_OK);
        int b = (int)brdffit_bin_index(x.i, x.j, x.k);
        EXPECT(b > prev); /* each bin once, in table order */
        prev = b;
        double wi[3], wo[3];
        my_bin_dirs(x.i, x.j, x.k, wi, wo);
        for (int c = 0; c < 3; c++) {
            EXPECT(x.wi[c] == wi[c]);
            EXPECT(x.wo[c] == wo[c]);
            EXPECT(x.rgb[c] == v[c * NB + (size_t)b] * f[c]);
            EXPECT(x.rgb[c] >= 0.0);
        }
        EXPECT(tu_reldiff(x.weight, my_weight(x.i, x.j)) <= 1e-13);
        /* N.H = cos theta_h and V.H = cos theta_d of the bin */
        double u = x.i / 90.0;
        EXPECT(fabs(sm->data[BF_F_NH * np + m] - cos(u * u * PI / 2)) <= 1e-12);
        EXPECT(fabs(sm->data[BF_F_VH * np + m] - cos(x.j / 90.0 * PI / 2)) <= 1e-12);
        EXPECT(tu_reldiff(sm->data[BF_F_A2 * np + m], x.weight * wi[2] * wi[2] / (3 * sw)) <=
               1e-12);
    }
    for (size_t m = n; m < np; m++) {
        EXPECT(sm->data[BF_F_IZ * np + m] == 1.0);
        EXPECT(sm->data[BF_F_OZ * np + m] == 1.0);
        EXPECT(sm->data[BF_F_IX * np + m] == 0.0);
        EXPECT(sm->data[BF_F_R * np + m] == 0.0);
        EXPECT(sm->data[BF_F_A2 * np + m] == 0.0);
        EXPECT(sm->data[BF_F_NH * np + m] == 1.0);
        EXPECT(sm->data[BF_F_VH * np + m] == 1.0);
    }
    EXPECT_NONE();
}

static void check_material(const char *name)
{
    brdffit_table *t = NULL;
    brdffit_error e;
    brdffit_status s = tu_merl_read(name, &t, &e);
    ck_assert_msg(s == BRDFFIT_OK, "%s: %s", name, e.message);
    const double *v = brdffit_table_values_const(t);
    const bin_count bc = count_bins(v);
    const size_t n = bc.n;

    brdffit_samples *sm = NULL;
    s = brdffit_samples_create(t, NULL, &sm, &e);
    ck_assert_msg(s == BRDFFIT_OK, "%s: %s", name, e.message);
    ck_assert_uint_gt(n, 0);
    ck_assert_uint_gt(bc.masked, 0);
    ck_assert_uint_eq(brdffit_samples_count(sm), n);
    ck_assert_uint_eq(brdffit_samples_masked(sm), bc.masked);
    ck_assert_uint_eq(brdffit_samples_beyond_cutoff(sm), bc.beyond);
    ck_assert_uint_eq(n + bc.masked + bc.beyond, NB);

    /* the prepared block */
    ck_assert_uint_eq(sm->n, n);
    ck_assert_uint_eq(sm->npad % BF_PAD, 0);
    ck_assert_uint_ge(sm->npad, n);
    ck_assert_uint_lt(sm->npad - n, BF_PAD);
    ck_assert_uint_eq((uintptr_t)sm->data % 64, 0);
    ck_assert_double_le(tu_reldiff(sm->sum_w, bc.sw), 1e-12);
    double sa2 = 0;
    for (size_t m = 0; m < sm->npad; m++)
        sa2 += sm->data[BF_F_A2 * sm->npad + m];
    ck_assert_double_le(tu_reldiff(sa2, bc.swc / (3 * bc.sw)), 1e-12);
    check_sample_block(sm, v, n, bc.sw);

    brdffit_sample x;
    brdffit_sample_init(&x);
    ck_assert_int_eq(brdffit_samples_get(sm, n, &x, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_samples_get(sm, 0, NULL, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_samples_get(NULL, 0, &x, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_samples_free(sm);
    brdffit_table_free(t);
}

START_TEST(test_merl_blue_rubber) { check_material("blue-rubber"); }
END_TEST
START_TEST(test_merl_alum_bronze) { check_material("alum-bronze"); }
END_TEST
START_TEST(test_merl_gold_metallic_paint) { check_material("gold-metallic-paint"); }
END_TEST

START_TEST(test_bin_weights)
{
    double sum = 0;
    EXPECT_RESET();
    for (int i = 0; i < 90; i++)
        for (int j = 0; j < 90; j++) {
            double w = brdffit_bin_weight(i, j);
            EXPECT(w > 0.0);
            EXPECT(tu_reldiff(w, my_weight(i, j)) <= 1e-13);
            for (int k = 0; k < 180; k++)
                sum += w;
        }
    EXPECT_NONE();
    /* sum_ij w = (1 - cos(pi/2)) (sin^2(pi/2) - 0) / 2 = 1/2 per phi_d bin */
    ck_assert_double_le(tu_reldiff(sum, 90.0), 1e-12);
    ck_assert_double_eq(brdffit_bin_weight(-1, 0), 0.0);
    ck_assert_double_eq(brdffit_bin_weight(0, 90), 0.0);

    double wi[3], wo[3];
    ck_assert_int_eq(brdffit_bin_directions(90, 0, 0, wi, wo, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_bin_directions(0, -1, 0, wi, wo, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_bin_directions(0, 0, 180, wi, wo, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_bin_directions(0, 0, 0, NULL, wo, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_bin_directions(89, 89, 179, wi, wo, NULL), BRDFFIT_OK);
    ck_assert_uint_eq(brdffit_bin_index(89, 89, 179), NB - 1);
    /* bin (0, 0, 0): both directions along the normal */
    ck_assert_int_eq(brdffit_bin_directions(0, 0, 0, wi, wo, NULL), BRDFFIT_OK);
    ck_assert_double_eq(wi[2], 1.0);
    ck_assert_double_eq(wo[2], 1.0);
}
END_TEST

/* ------------------------------------------------------------------ 3. bad files */

START_TEST(test_read_missing_dir_empty)
{
    expect_read_fail("/nonexistent-brdffit-dir/none.binary", BRDFFIT_E_FILE_OPEN,
                     "No such file");
    char dir[512];
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s", tmp && *tmp ? tmp : "/tmp");
    expect_read_fail(dir, BRDFFIT_E_FILE_NOT_REGULAR, NULL);
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path)); /* exists, 0 bytes */
    expect_read_fail(path, BRDFFIT_E_FILE_EMPTY, NULL);
    unlink(path);
}
END_TEST

START_TEST(test_read_truncated)
{
    char path[512], want[128];
    size_t full = FILE_BYTES;
    unsigned char *buf = calloc(1, full + 1);
    ck_assert_ptr_nonnull(buf);
    write_header(buf, 90, 90, 180);
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    const size_t lens[] = { 5, 12, 12 + (full - 12) / 2, full - 1 };
    for (size_t q = 0; q < sizeof lens / sizeof lens[0]; q++) {
        ck_assert_int_eq(tu_write_bytes(path, buf, lens[q]), 0);
        snprintf(want, sizeof want, "truncated at byte %zu of 34992012 expected", lens[q]);
        expect_read_fail(path, BRDFFIT_E_FILE_TRUNCATED, want);
    }
    /* one extra byte */
    ck_assert_int_eq(tu_write_bytes(path, buf, full + 1), 0);
    expect_read_fail(path, BRDFFIT_E_FILE_TRAILING, NULL);
    /* exactly right: reads */
    ck_assert_int_eq(tu_write_bytes(path, buf, full), 0);
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_read(path, &t, NULL), BRDFFIT_OK);
    brdffit_table_free(t);
    free(buf);
    unlink(path);
}
END_TEST

START_TEST(test_read_dims)
{
    char path[512];
    size_t full = FILE_BYTES;
    unsigned char *buf = calloc(1, full);
    ck_assert_ptr_nonnull(buf);
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    write_header(buf, 90, 90, 360);
    ck_assert_int_eq(tu_write_bytes(path, buf, full), 0); /* right size, wrong dims */
    expect_read_fail(path, BRDFFIT_E_FILE_DIMS, "dims 90x90x360, expected 90x90x180");
    ck_assert_int_eq(tu_write_bytes(path, buf, 12), 0); /* dims are checked before size */
    expect_read_fail(path, BRDFFIT_E_FILE_DIMS, "dims 90x90x360");
    write_header(buf, 180, 90, 90);
    ck_assert_int_eq(tu_write_bytes(path, buf, full), 0);
    expect_read_fail(path, BRDFFIT_E_FILE_DIMS, "dims 180x90x90");
    write_header(buf, -1, 90, 180);
    ck_assert_int_eq(tu_write_bytes(path, buf, full), 0);
    expect_read_fail(path, BRDFFIT_E_FILE_DIMS, "dims -1x90x180");
    free(buf);
    unlink(path);
}
END_TEST

/* A file that is not a table at all is said to be one, its first bytes shown. */
START_TEST(test_read_not_merl)
{
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    const char list[] = "/data/merl/\"a\"\tb.binary\n/data/merl/c.binary\n";
    ck_assert_int_eq(tu_write_bytes(path, list, sizeof list - 1), 0);
    expect_read_fail(path, BRDFFIT_E_FILE_DIMS,
                     ": not a MERL table: it begins with \"/data/merl/\\\"\", where");
    const unsigned char png[16] = { 0x89, 'P', 'N', 'G', 13, 10, 26, 10, 0, 0, 0, 13, 'I', 'H', 'D', 'R' };
    ck_assert_int_eq(tu_write_bytes(path, png, sizeof png), 0);
    expect_read_fail(path, BRDFFIT_E_FILE_DIMS,
                     ": not a MERL table: it begins with bytes 89 50 4e 47 0d 0a 1a 0a 00 00 00 0d, "
                     "where a MERL .binary begins with the int32 dimensions 90 90 180");
    const char crlf[] = "a.binary\r\n\tb.binary\r\n";
    ck_assert_int_eq(tu_write_bytes(path, crlf, sizeof crlf - 1), 0);
    expect_read_fail(path, BRDFFIT_E_FILE_DIMS, "begins with \"a.binary\\r\\n\\tb\"");
    unlink(path);
}
END_TEST

START_TEST(test_read_nonfinite)
{
    char path[512];
    zero_table_file(path, sizeof path);
    /* G plane, bin (3, 4, 5) */
    size_t b = brdffit_bin_index(3, 4, 5), n = NB + b;
    poke_value(path, n, NAN);
    char want[128];
    snprintf(want, sizeof want, "NaN at index %zu (channel G, bin 3,4,5)", n);
    expect_read_fail(path, BRDFFIT_E_FILE_NONFINITE, want);
    /* +inf in the B plane, last bin */
    poke_value(path, n, 0.0);
    poke_value(path, 3 * NB - 1, INFINITY);
    expect_read_fail(path, BRDFFIT_E_FILE_NONFINITE, "(channel B, bin 89,89,179)");
    expect_read_fail(path, BRDFFIT_E_FILE_NONFINITE, "inf");
    poke_value(path, 3 * NB - 1, -INFINITY);
    poke_value(path, 0, NAN); /* the first one found is reported */
    expect_read_fail(path, BRDFFIT_E_FILE_NONFINITE, "(channel R, bin 0,0,0)");
    unlink(path);
}
END_TEST

START_TEST(test_null_arguments)
{
    brdffit_error e;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_read(NULL, &t, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(e.status, BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_read("/tmp/x", NULL, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_table_create(NULL, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_null(brdffit_table_values(NULL));
    ck_assert_ptr_null(brdffit_table_values_const(NULL));
    brdffit_table_free(NULL);
    brdffit_samples_free(NULL);
    ck_assert_int_eq(brdffit_table_create(&t, NULL), BRDFFIT_OK);
    brdffit_samples *s = (brdffit_samples *)&s;
    ck_assert_int_eq(brdffit_samples_create(NULL, NULL, &s, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_null(s);
    ck_assert_int_eq(brdffit_samples_create(t, NULL, NULL, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_uint_eq(brdffit_samples_count(NULL), 0);
    ck_assert_uint_eq(brdffit_samples_masked(NULL), 0);
    ck_assert_uint_eq(brdffit_samples_beyond_cutoff(NULL), 0);
    brdffit_sample_options o;
    brdffit_sample_options_default(&o);
    o.cutoff_deg = 0;
    o.scale = BRDFFIT_SCALE_FLAT;
    ck_assert_int_eq(brdffit_samples_options(NULL, &o, &e), BRDFFIT_OK);
    ck_assert_double_eq(o.cutoff_deg, 80.0);
    ck_assert_int_eq(o.scale, BRDFFIT_SCALE_STANDARD);
    ck_assert_int_eq(brdffit_samples_options(NULL, NULL, &e), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_ptr_nonnull(strstr(e.message, "out is NULL"));
    brdffit_sample_options_default(NULL);
    ck_assert_int_eq(brdffit_scale_factors(BRDFFIT_SCALE_FLAT, NULL, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_scale_from_name(NULL, NULL, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_table_free(t);
}
END_TEST

/* ------------------------------------------------------------------ 4. scales */

START_TEST(test_scales)
{
    double f[3];
    ck_assert_int_eq(brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, f, NULL), BRDFFIT_OK);
    ck_assert_double_le(tu_reldiff(f[0], 1.0 / 1500), 1e-15);
    ck_assert_double_le(tu_reldiff(f[1], 1.15 / 1500), 1e-15);
    ck_assert_double_le(tu_reldiff(f[2], 1.66 / 1500), 1e-15);
    ck_assert_int_eq(brdffit_scale_factors(BRDFFIT_SCALE_FLAT, f, NULL), BRDFFIT_OK);
    for (int c = 0; c < 3; c++)
        ck_assert_double_le(tu_reldiff(f[c], 1.0 / 1500), 1e-15);
    ck_assert_int_eq(brdffit_scale_factors((brdffit_scale)2, f, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_str_eq(brdffit_scale_name(BRDFFIT_SCALE_STANDARD), "standard");
    ck_assert_str_eq(brdffit_scale_name(BRDFFIT_SCALE_FLAT), "flat");
    ck_assert_ptr_nonnull(brdffit_scale_name((brdffit_scale)7));
    brdffit_scale sc = (brdffit_scale)5;
    ck_assert_int_eq(brdffit_scale_from_name("flat", &sc, NULL), BRDFFIT_OK);
    ck_assert_int_eq(sc, BRDFFIT_SCALE_FLAT);
    ck_assert_int_eq(brdffit_scale_from_name("standard", &sc, NULL), BRDFFIT_OK);
    ck_assert_int_eq(sc, BRDFFIT_SCALE_STANDARD);
    ck_assert_int_eq(brdffit_scale_from_name("merl", &sc, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_scale_from_name("", &sc, NULL), BRDFFIT_E_INVALID_ARGUMENT);
    double g[3];
    bf_scale_factors(BRDFFIT_SCALE_STANDARD, g);
    brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, f, NULL);
    ck_assert_int_eq(memcmp(f, g, sizeof f), 0);

    /* the same table under both scales: rgb = stored x factor */
    brdffit_table *t = ct_table(BRDFFIT_SCALE_STANDARD);
    const double *v = brdffit_table_values_const(t);
    brdffit_samples *ss = NULL, *sf = NULL;
    brdffit_sample_options o;
    brdffit_sample_options_default(&o);
    ck_assert_int_eq(brdffit_samples_create(t, &o, &ss, NULL), BRDFFIT_OK);
    o.scale = BRDFFIT_SCALE_FLAT;
    ck_assert_int_eq(brdffit_samples_create(t, &o, &sf, NULL), BRDFFIT_OK);
    ck_assert_uint_eq(brdffit_samples_count(ss), brdffit_samples_count(sf));
    ck_assert_int_eq(brdffit_samples_options(sf, &o, NULL), BRDFFIT_OK);
    ck_assert_int_eq(o.scale, BRDFFIT_SCALE_FLAT);
    double fs[3], ff[3];
    brdffit_scale_factors(BRDFFIT_SCALE_STANDARD, fs, NULL);
    brdffit_scale_factors(BRDFFIT_SCALE_FLAT, ff, NULL);
    EXPECT_RESET();
    for (size_t m = 0; m < brdffit_samples_count(ss); m++) {
        brdffit_sample a, b;
        brdffit_sample_init(&a);
        brdffit_sample_init(&b);
        EXPECT(brdffit_samples_get(ss, m, &a, NULL) == BRDFFIT_OK);
        EXPECT(brdffit_samples_get(sf, m, &b, NULL) == BRDFFIT_OK);
        size_t n = brdffit_bin_index(a.i, a.j, a.k);
        for (int c = 0; c < 3; c++) {
            EXPECT(a.rgb[c] == v[c * NB + n] * fs[c]);
            EXPECT(b.rgb[c] == v[c * NB + n] * ff[c]);
        }
        EXPECT(tu_reldiff(a.rgb[1] / b.rgb[1], 1.15) <= 1e-13);
        EXPECT(tu_reldiff(a.rgb[2] / b.rgb[2], 1.66) <= 1e-13);
        /* the table was filled under the standard scale: it gives back f */
        if (m % 101 == 0) {
            double rgb[3];
            EXPECT(brdffit_eval(BRDFFIT_COOK_TORRANCE, &ct_params, a.wi, a.wo, rgb, NULL) ==
                   BRDFFIT_OK);
            for (int c = 0; c < 3; c++)
                EXPECT(tu_reldiff(a.rgb[c], rgb[c]) <= 1e-13);
        }
    }
    EXPECT_NONE();
    brdffit_samples_free(ss);
    brdffit_samples_free(sf);

    /* a table filled under the flat scale stores different numbers for G, B */
    brdffit_table *t2 = ct_table(BRDFFIT_SCALE_FLAT);
    size_t b0 = brdffit_bin_index(10, 10, 10);
    const double *v2 = brdffit_table_values_const(t2);
    ck_assert_double_eq(v2[b0], v[b0]);
    ck_assert_double_le(tu_reldiff(v2[NB + b0], 1.15 * v[NB + b0]), 1e-13);
    ck_assert_double_le(tu_reldiff(v2[2 * NB + b0], 1.66 * v[2 * NB + b0]), 1e-13);
    brdffit_table_free(t2);
    brdffit_table_free(t);
}
END_TEST

/* ------------------------------------------------------------------ 5. sample options */

START_TEST(test_sample_options)
{
    brdffit_table *t = zero_table();
    brdffit_error e;
    brdffit_samples *s = NULL;
    brdffit_sample_options o;
    const double bad[] = { 0, 91, NAN, -5, INFINITY, 90.0000001 };
    for (size_t q = 0; q < sizeof bad / sizeof bad[0]; q++) {
        brdffit_sample_options_default(&o);
        o.cutoff_deg = bad[q];
        s = (brdffit_samples *)&s;
        ck_assert_int_eq(brdffit_samples_create(t, &o, &s, &e), BRDFFIT_E_INVALID_ARGUMENT);
        ck_assert_int_eq(e.status, BRDFFIT_E_INVALID_ARGUMENT);
        ck_assert_ptr_null(s);
    }
    brdffit_sample_options_default(&o);
    ck_assert_double_eq(o.cutoff_deg, 80.0);
    ck_assert_int_eq(o.scale, BRDFFIT_SCALE_STANDARD);
    o.scale = (brdffit_scale)3;
    ck_assert_int_eq(brdffit_samples_create(t, &o, &s, &e), BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_table_free(t);
}
END_TEST

/* The valid samples of t with the cutoff cutoff_deg. */
static size_t count_at_cutoff(const brdffit_table *t, double cutoff_deg)
{
    brdffit_sample_options o;
    brdffit_sample_options_default(&o);
    o.cutoff_deg = cutoff_deg;
    brdffit_samples *s = NULL;
    brdffit_error e;
    ck_assert_int_eq(brdffit_samples_create(t, &o, &s, &e), BRDFFIT_OK);
    size_t n = brdffit_samples_count(s);
    brdffit_samples_free(s);
    return n;
}

START_TEST(test_sample_cutoffs)
{
    brdffit_table *t = zero_table();
    brdffit_error e;
    brdffit_samples *s = NULL;
    brdffit_sample_options o;

    /* all zeros: every bin above the horizon is valid; cutoff 90 keeps them all */
    size_t above = 0;
    for (int i = 0; i < 90; i++)
        for (int j = 0; j < 90; j++)
            for (int k = 0; k < 180; k++) {
                double wi[3], wo[3];
                my_bin_dirs(i, j, k, wi, wo);
                above += wi[2] > 0 && wo[2] > 0;
            }
    brdffit_sample_options_default(&o);
    o.cutoff_deg = 90;
    ck_assert_int_eq(brdffit_samples_create(t, &o, &s, &e), BRDFFIT_OK);
    ck_assert_uint_eq(brdffit_samples_count(s), above);
    ck_assert_uint_eq(brdffit_samples_masked(s), 0);
    ck_assert_uint_eq(brdffit_samples_beyond_cutoff(s), NB - above);
    brdffit_sample_options got;
    brdffit_sample_options_default(&got);
    ck_assert_int_eq(brdffit_samples_options(s, &got, &e), BRDFFIT_OK);
    ck_assert_double_eq(got.cutoff_deg, 90.0);
    size_t n90 = brdffit_samples_count(s);
    brdffit_samples_free(s);
    /* smaller cutoffs keep fewer, and only samples within them */
    size_t n80 = count_at_cutoff(t, 80);
    o.cutoff_deg = 30;
    ck_assert_int_eq(brdffit_samples_create(t, &o, &s, &e), BRDFFIT_OK);
    size_t n30 = brdffit_samples_count(s);
    EXPECT_RESET();
    for (size_t m = 0; m < n30; m++) {
        brdffit_sample x;
        brdffit_sample_init(&x);
        EXPECT(brdffit_samples_get(s, m, &x, NULL) == BRDFFIT_OK);
        EXPECT(x.wi[2] >= cos(30 * PI / 180) - 1e-12);
        EXPECT(x.wo[2] >= cos(30 * PI / 180) - 1e-12);
    }
    EXPECT_NONE();
    brdffit_samples_free(s);
    ck_assert_uint_lt(n80, n90);
    ck_assert_uint_lt(n30, n80);
    ck_assert_uint_gt(n30, 0);
    brdffit_table_free(t);
}
END_TEST

START_TEST(test_sample_masking)
{
    brdffit_table *t = zero_table();
    brdffit_error e;
    brdffit_samples *s = NULL;
    const size_t n80 = count_at_cutoff(t, 80);

    /* one masked channel masks the bin */
    double *v = brdffit_table_values(t);
    v[2 * NB + 0] = -1;
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, &e), BRDFFIT_OK);
    ck_assert_uint_eq(brdffit_samples_masked(s), 1);
    ck_assert_uint_eq(brdffit_samples_count(s), n80 - 1);
    brdffit_samples_free(s);

    /* a non-finite value is refused, not fitted, with the status a file read gives it */
    v[NB + 7] = NAN;
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, &e), BRDFFIT_E_FILE_NONFINITE);
    ck_assert_ptr_null(s);

    /* all negative: no samples */
    for (size_t n = 0; n < 3 * NB; n++)
        v[n] = -1;
    s = (brdffit_samples *)&s;
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, &e), BRDFFIT_E_NO_SAMPLES);
    ck_assert_int_eq(e.status, BRDFFIT_E_NO_SAMPLES);
    ck_assert_ptr_null(s);
    ck_assert_int_eq(brdffit_samples_create(t, NULL, &s, NULL), BRDFFIT_E_NO_SAMPLES);
    brdffit_table_free(t);
}
END_TEST

Suite *table_suite(void)
{
    Suite *s = suite_create("table");
    TCase *tc = tcase_create("model");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_fill_model_values);
    tcase_add_test(tc, test_fill_model_errors);
    tcase_add_test(tc, test_write_read_roundtrip);
    tcase_add_test(tc, test_write_errors);
    tcase_add_test(tc, test_lookup_own_bins);
    tcase_add_test(tc, test_lookup_interp);
    tcase_add_test(tc, test_lookup_symmetries);
    tcase_add_test(tc, test_lookup_masked_corner);
    tcase_add_test(tc, test_lookup_invalid_arguments);
    suite_add_tcase(s, tc);

    tc = tcase_create("merl");
    tcase_set_timeout(tc, 300);
    tcase_set_tags(tc, TU_NEEDS_SHARED);
    tcase_add_test(tc, test_merl_blue_rubber);
    tcase_add_test(tc, test_merl_alum_bronze);
    tcase_add_test(tc, test_merl_gold_metallic_paint);
    suite_add_tcase(s, tc);

    tc = tcase_create("weights");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_bin_weights);
    suite_add_tcase(s, tc);

    tc = tcase_create("files");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_read_missing_dir_empty);
    tcase_add_test(tc, test_read_truncated);
    tcase_add_test(tc, test_read_dims);
    tcase_add_test(tc, test_read_not_merl);
    tcase_add_test(tc, test_read_nonfinite);
    tcase_add_test(tc, test_null_arguments);
    suite_add_tcase(s, tc);

    tc = tcase_create("samples");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_scales);
    tcase_add_test(tc, test_sample_options);
    tcase_add_test(tc, test_sample_cutoffs);
    tcase_add_test(tc, test_sample_masking);
    suite_add_tcase(s, tc);
    return s;
}
