/* SPDX-License-Identifier: MIT */
/* test_openpbr.c -- the openpbr model's fit and its albedo table
 * (kernels/bf_openpbr.h, src/lib/openpbr_albedo.c): tables filled from
 * OpenPBR materials (metal, dielectric, between; sharp and rough; specular_ior
 * 1 to 10) fit back to their parameters; the fit holds specular_weight and
 * the specular colour; the table is made in under 0.5 s of CPU time; a pass's
 * slice of it gives the direct lookup's values; the affine pass's sums
 * against a direct loop.  The BRDF itself against the specification:
 * python/tests/test_openpbr_model.py. */
#define _DEFAULT_SOURCE
#include "testutil.h"

#include "fit/affine.h"
#include "samples.h"
#include "bf_openpbr.h"

#include <check.h>
#include <math.h>
#include <string.h>
#include <time.h>

typedef struct opbr_case {
    double base[3];
    double p[4]; /* base_metalness, specular_roughness, specular_ior, specular_weight */
} opbr_case;

static const opbr_case cases[] = {
    { { 0.6, 0.4, 0.2 }, { 0.0, 0.3, 1.5, 1.0 } },
    { { 0.95, 0.64, 0.54 }, { 1.0, 0.2, 1.5, 1.0 } },
    { { 0.3, 0.5, 0.7 }, { 0.4, 0.7, 2.5, 1.0 } },
    { { 0.05, 0.05, 0.05 }, { 0.0, 0.08, 1.3, 1.0 } },
    { { 0.8, 0.1, 0.3 }, { 0.6, 0.95, 8.0, 1.0 } },
};
#define NCASES (int)(sizeof cases / sizeof cases[0])

static brdffit_params case_params(const opbr_case *k)
{
    brdffit_params q;
    memset(&q, 0, sizeof q);
    for (int c = 0; c < 3; c++) {
        q.d[c] = k->base[c];
        q.s[c] = 1.0;
    }
    memcpy(q.p, k->p, sizeof k->p);
    return q;
}

static brdffit_samples *filled(const brdffit_params *q)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_fill_model(t, BRDFFIT_OPENPBR, q, BRDFFIT_SCALE_STANDARD, &err) ==
                      BRDFFIT_OK, "%s", err.message);
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    ck_assert_msg(brdffit_samples_create(t, &so, &s, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
    return s;
}

/* A table made by an OpenPBR material fits back: Error below 1e-6 of the
 * data's RMS, the base colour and every fitted parameter within 1e-4 absolute
 * (specular_ior but for a full metal, which has no dielectric), specular_weight 1 and the specular
 * colour white (held), the Error brdffit_error_of's, every value finite. */
START_TEST(recovery)
{
    const opbr_case *k = &cases[_i];
    const brdffit_params truth = case_params(k);
    brdffit_samples *s = filled(&truth);
    brdffit_context *ctx = NULL;
    brdffit_error err;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_AUTO, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_params dark = truth;
    memset(dark.d, 0, sizeof dark.d);
    dark.p[0] = 0.0;
    double rms = 0, e = 1;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_OPENPBR, &dark, &rms, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_OPENPBR, &truth, &e, &err), BRDFFIT_OK);
    ck_assert_msg(e < 1e-7 * rms, "the truth's own Error %g (scale %g)", e, rms);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_OPENPBR, NULL, &r, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert_msg(r.error < 1e-6 * rms, "case %d: Error %g, scale %g", _i, r.error, rms);
    for (int c = 0; c < 3; c++) {
        ck_assert_msg(fabs(r.params.d[c] - truth.d[c]) < 1e-4, "case %d base_color %d %.8g vs %.8g",
                      _i, c, r.params.d[c], truth.d[c]);
        ck_assert(r.params.s[c] == 1.0);
    }
    /* a full metal has no dielectric: its specular_ior is not seen */
    for (int j = 0; j < (truth.p[0] == 1.0 ? 2 : 3); j++)
        ck_assert_msg(fabs(r.params.p[j] - truth.p[j]) < 1e-4, "case %d %s %.8g vs %.8g", _i,
                      brdffit_model_param(BRDFFIT_OPENPBR, j)->name, r.params.p[j], truth.p[j]);
    ck_assert(r.params.p[3] == 1.0);
    for (int j = 0; j < 4; j++)
        ck_assert(isfinite(r.params.p[j]));
    double e_fit = -1;
    ck_assert_int_eq(brdffit_error_of(ctx, s, BRDFFIT_OPENPBR, &r.params, &e_fit, &err), BRDFFIT_OK);
    ck_assert(e_fit == r.error);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* The table is made on the first lookup, in under 0.5 s of CPU time (the
 * test runs in a process of its own), and a slice at one roughness and F0
 * gives the direct lookup's E and Ess to rounding, over cosines and
 * roughnesses that reach the ends (the slice is the same tensor product
 * taken in another order), and both kept to 0 <= E <= Ess <= 1. */
START_TEST(table)
{
    double t0 = cpu_seconds(), e, ess;
    bf_openpbr_albedo(0.5, 0.3, 0.04, &e, &ess);
    double made = cpu_seconds() - t0;
    ck_assert_msg(made < 0.5, "the albedo table took %g s", made);
    ck_assert(e > 0.04 && e < ess && ess <= 1.0);
    const double rs[] = { 0.0, 1e-3, 0.017, 0.3, 0.99, 1.0 }, f0s[] = { 0.0, 0.04, 0.25, 0.67 };
    const double mus[] = { 1e-6, 0.01, 0.05, 0.3, 0.777, 1.0 };
    for (size_t a = 0; a < sizeof rs / sizeof rs[0]; a++)
        for (size_t b = 0; b < sizeof f0s / sizeof f0s[0]; b++) {
            bf_openpbr_slice sl;
            bf_openpbr_albedo_slice(rs[a], f0s[b], &sl);
            for (size_t c = 0; c < sizeof mus / sizeof mus[0]; c++) {
                double e1, s1, e2, s2;
                bf_openpbr_albedo(mus[c], rs[a], f0s[b], &e1, &s1);
                bf_openpbr_slice_at(&sl, mus[c], &e2, &s2);
                ck_assert_msg(fabs(e1 - e2) < 1e-14 && fabs(s1 - s2) < 1e-14,
                              "r %g F0 %g mu %g: E %.17g vs %.17g, Ess %.17g vs %.17g", rs[a], f0s[b],
                              mus[c], e1, e2, s1, s2);
                ck_assert_msg(isfinite(e1) && e1 >= 0.0 && e1 <= s1 && s1 <= 1.0 && s1 > 0.0,
                              "r %g F0 %g mu %g: E %.17g Ess %.17g", rs[a], f0s[b], mus[c], e1, s1);
            }
        }
}
END_TEST

/* The pass's sums at a point and its neighbours (one in base_metalness
 * alone, one in specular_roughness) equal a direct loop's over bf_openpbr_form. */
START_TEST(pass_sums)
{
    const brdffit_params q = case_params(&cases[2]);
    brdffit_samples *s = filled(&q);
    double pts[3][AF_NP] = { { 0.3, 0.4, 1.7, 1.0 }, { 0.3001, 0.4, 1.7, 1.0 },
                             { 0.3, 0.4002, 1.7, 1.0 } };
    double inv_h[2] = { 1e4, 5e3 };
    af_qmom m;
    brdffit_error err;
    ck_assert_int_eq(bf_affine_pass_openpbr(s, (const double (*)[AF_NP])pts, 2, inv_h, &m, &err),
                     BRDFFIT_OK);
    ck_assert_int_eq(m.nb, 3);
    double qq = 0, rq = 0, dq1dq1 = 0, rda0 = 0;
    const size_t n = s->npad;
    const double *f = s->data;
    for (size_t i = 0; i < s->n; i++) {
        bf_geom g = { f[BF_F_IX * n + i], f[BF_F_IY * n + i], f[BF_F_IZ * n + i],
                      f[BF_F_OX * n + i], f[BF_F_OY * n + i], f[BF_F_OZ * n + i],
                      f[BF_F_NH * n + i], f[BF_F_VH * n + i] };
        double a2 = f[BF_F_A2 * n + i], A[3], B[3], Q[3];
        for (int j = 0; j < 3; j++)
            bf_openpbr_form(&g, pts[j], &A[j], &B[j], &Q[j]);
        double dq1 = (Q[2] - Q[0]) * inv_h[1], da0 = (A[1] - A[0]) * inv_h[0];
        qq += a2 * Q[0] * Q[0];
        rq += a2 * f[BF_F_G * n + i] * Q[0];
        dq1dq1 += a2 * dq1 * dq1;
        rda0 += a2 * f[BF_F_B * n + i] * da0;
    }
    /* row j nb + X: the difference of base X (A 0, B 1, Q 2) to neighbour j */
    ck_assert_msg(tu_reldiff(m.gg[2][2], qq) < 1e-12, "QQ %.17g vs %.17g", m.gg[2][2], qq);
    ck_assert_msg(tu_reldiff(m.rg[1][2], rq) < 1e-12, "rho Q %.17g vs %.17g", m.rg[1][2], rq);
    ck_assert_msg(tu_reldiff(m.dd[5][5], dq1dq1) < 1e-9, "dQ dQ %.17g vs %.17g", m.dd[5][5], dq1dq1);
    ck_assert_msg(tu_reldiff(m.rd[2][0], rda0) < 1e-9, "rho dA %.17g vs %.17g", m.rd[2][0], rda0);
    brdffit_samples_free(s);
}
END_TEST

Suite *openpbr_suite(void)
{
    Suite *s = suite_create("openpbr");
    TCase *tc = tcase_create("openpbr");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, recovery, 0, NCASES);
    tcase_add_test(tc, table);
    tcase_add_test(tc, pass_sums);
    suite_add_tcase(s, tc);
    return s;
}
