/* SPDX-License-Identifier: MIT */
/* test_gltf_fit.c -- the fit of the glTF models (src/lib/fit/affine.c): a
 * table filled from a glTF material fits back to its parameters, metal,
 * dielectric and between, core and extended; the Error the fit reports is
 * brdffit_error_of's; the affine engine's pass sums against a direct loop,
 * and the same on its workers, in the calling thread and after fork. */
#define _DEFAULT_SOURCE
#include "testutil.h"

#include "fit/affine.h"
#include "samples.h"
#include "bf_gltf.h"

#include <check.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct gltf_case {
    brdffit_model model;
    double base[3];
    double p[4]; /* metallic, roughness, ior, specular */
} gltf_case;

/* Dielectric and metal on their bounds, a mix between, a sharp and a rough
 * lobe; the extended model away from the core's ior and specular. */
static const gltf_case cases[] = {
    { BRDFFIT_GLTF, { 0.6, 0.4, 0.2 }, { 0.0, 0.3, 1.5, 1.0 } },
    { BRDFFIT_GLTF, { 0.9, 0.7, 0.3 }, { 1.0, 0.2, 1.5, 1.0 } },
    { BRDFFIT_GLTF, { 0.3, 0.5, 0.7 }, { 0.4, 0.6, 1.5, 1.0 } },
    { BRDFFIT_GLTF, { 0.05, 0.05, 0.05 }, { 0.0, 0.08, 1.5, 1.0 } },
    { BRDFFIT_GLTF_EXT, { 0.5, 0.3, 0.1 }, { 0.2, 0.25, 2.0, 0.7 } },
    { BRDFFIT_GLTF_EXT, { 0.2, 0.2, 0.25 }, { 0.0, 0.15, 1.3, 0.4 } },
};
#define NCASES (int)(sizeof cases / sizeof cases[0])

static brdffit_params case_params(const gltf_case *k)
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

static brdffit_samples *filled(brdffit_model m, const brdffit_params *q)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_msg(brdffit_table_fill_model(t, m, q, BRDFFIT_SCALE_STANDARD, &err) == BRDFFIT_OK,
                  "%s", err.message);
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    ck_assert_msg(brdffit_samples_create(t, &so, &s, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
    return s;
}

/* A table made by a glTF material fits back: Error below 1e-6 of the data's
 * RMS, every parameter within 1e-4 absolute (they are all of order 1), the
 * specular colour white, the Error brdffit_error_of's. */
START_TEST(recovery)
{
    const gltf_case *k = &cases[_i];
    const brdffit_params truth = case_params(k);
    brdffit_samples *s = filled(k->model, &truth);
    brdffit_context *ctx = NULL;
    brdffit_error err;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_AUTO, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_params dark = truth;
    memset(dark.d, 0, sizeof dark.d);
    dark.p[0] = 0.0;
    double rms = 0, e = 1;
    ck_assert_int_eq(brdffit_error_of(ctx, s, k->model, &dark, &rms, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_error_of(ctx, s, k->model, &truth, &e, &err), BRDFFIT_OK);
    /* the table keeps the values to rounding (a sharp lobe's peak is ~1e5
     * times the RMS) */
    ck_assert_msg(rms > 0 && e < 1e-7 * rms, "truth's Error %g of %g", e, rms);

    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, k->model, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
    const char *name = brdffit_model_get(k->model)->name;
    ck_assert_msg(r.error < 1e-6 * rms, "case %d (%s): Error %g of rms %g", _i, name, r.error, rms);
    for (int c = 0; c < 3; c++) {
        ck_assert_msg(fabs(r.params.d[c] - truth.d[c]) < 1e-4, "case %d base %d: %.8g vs %.8g", _i,
                      c, r.params.d[c], truth.d[c]);
        ck_assert(r.params.s[c] == 1.0);
    }
    for (int j = 0; j < 4; j++)
        ck_assert_msg(fabs(r.params.p[j] - truth.p[j]) < 1e-4, "case %d (%s) %s: %.8g vs %.8g", _i,
                      name, brdffit_model_param(k->model, j)->name, r.params.p[j], truth.p[j]);
    double e_fit = -1;
    ck_assert_int_eq(brdffit_error_of(ctx, s, k->model, &r.params, &e_fit, &err), BRDFFIT_OK);
    ck_assert(e_fit == r.error);
    ck_assert(r.cminpack_info >= 1 && r.cminpack_info <= 4);
    ck_assert(r.passes > 0 && r.iterations > 0 && r.seconds > 0);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* The pass's sums at a point and its differences equal a direct loop's over
 * the same samples (the sums that give r^T r, g and H). */
START_TEST(pass_sums)
{
    const brdffit_params q = case_params(&cases[4]);
    brdffit_samples *s = filled(BRDFFIT_GLTF_EXT, &q);
    const double white[3] = { 1, 1, 1 };
    double pts[3][AF_NP] = { { 0.3, 0.4, 1.7, 0.8 }, { 0.3001, 0.4, 1.7, 0.8 },
                             { 0.3, 0.4, 1.7, 0.8002 } };
    double inv_h[2] = { 1e4, 5e3 };
    af_mom m;
    brdffit_error err;
    ck_assert_int_eq(bf_affine_pass(s, BRDFFIT_GLTF_EXT, (const double (*)[AF_NP])pts, 2, inv_h,
                                    &m, &err),
                     BRDFFIT_OK);
    double bb = 0, rb = 0, dbdb = 0, rda = 0;
    const size_t n = s->npad;
    for (size_t i = 0; i < s->n; i++) {
        const double *f = s->data;
        bf_geom g = { f[BF_F_IX * n + i], f[BF_F_IY * n + i], f[BF_F_IZ * n + i],
                      f[BF_F_OX * n + i], f[BF_F_OY * n + i], f[BF_F_OZ * n + i],
                      f[BF_F_NH * n + i], f[BF_F_VH * n + i] };
        double a2 = f[BF_F_A2 * n + i], A[3][3], B[3][3];
        for (int j = 0; j < 3; j++)
            bf_gltf_affine(&g, pts[j], white, A[j], B[j]);
        /* the pass takes the partials' step: the difference quotient to
         * first order (its second-order term is ~1e-4 of it at these h) */
        double db1 = (B[2][0] - B[0][0]) * inv_h[1], da0 = (A[1][0] - A[0][0]) * inv_h[0];
        bb += a2 * B[0][0] * B[0][0];
        rb += a2 * f[BF_F_G * n + i] * B[0][0];
        dbdb += a2 * db1 * db1;
        rda += a2 * f[BF_F_B * n + i] * da0;
    }
    ck_assert_msg(tu_reldiff(m.bb, bb) < 1e-12, "bb %.17g vs %.17g", m.bb, bb);
    ck_assert_msg(tu_reldiff(m.rb[1], rb) < 1e-12, "rb %.17g vs %.17g", m.rb[1], rb);
    ck_assert_msg(tu_reldiff(m.dbdb[1][1], dbdb) < 1e-3, "dbdb %.17g vs %.17g", m.dbdb[1][1], dbdb);
    ck_assert_msg(tu_reldiff(m.rda[2][0], rda) < 1e-3, "rda %.17g vs %.17g", m.rda[2][0], rda);
    brdffit_samples_free(s);
}
END_TEST

/* A pass with two partials at a fixed point into m. */
static void pass_at(const brdffit_samples *s, af_mom *m)
{
    const double pts[3][AF_NP] = { { 0.3, 0.4, 1.7, 0.8 }, { 0.3001, 0.4, 1.7, 0.8 },
                                   { 0.3, 0.4, 1.7, 0.8002 } };
    const double inv_h[2] = { 1e4, 5e3 };
    brdffit_error err;
    ck_assert_int_eq(bf_affine_pass(s, BRDFFIT_GLTF_EXT, pts, 2, inv_h, m, &err), BRDFFIT_OK);
}

/* The sums of two passes equal to the bit. */
static int same_sums(const af_mom *a, const af_mom *b)
{
    return memcmp(&a->aa, &b->aa, sizeof *a - offsetof(af_mom, aa)) == 0;
}

static const brdffit_samples *workers_set;
static af_mom workers_m[4];

static void *workers_thread(void *arg)
{
    pass_at(workers_set, &workers_m[(intptr_t)arg]);
    return NULL;
}

/* A pass gives the same sums on the pass workers, in the calling thread
 * (passes from four threads at once: those that find the workers in use run
 * there) and in a child process made by fork after the workers were made
 * (which makes its own). */
START_TEST(pass_workers)
{
    const brdffit_params q = case_params(&cases[4]);
    brdffit_samples *s = filled(BRDFFIT_GLTF_EXT, &q);
    af_mom m0;
    pass_at(s, &m0);
    ck_assert(m0.bb > 0);
    workers_set = s;
    pthread_t t[4];
    for (intptr_t k = 0; k < 4; k++)
        ck_assert_int_eq(pthread_create(&t[k], NULL, workers_thread, (void *)k), 0);
    for (int k = 0; k < 4; k++) {
        pthread_join(t[k], NULL);
        ck_assert_msg(same_sums(&workers_m[k], &m0), "thread %d's sums differ", k);
    }
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        af_mom m;
        pass_at(s, &m);
        _exit(same_sums(&m, &m0) ? 0 : 3);
    }
    int status = 0;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the child's pass: status %d", status);
    brdffit_samples_free(s);
}
END_TEST

/* The partials of A and B against central differences of bf_gltf_affine,
 * over directions and parameters that reach the corners (metal, dielectric,
 * sharp and rough, ior near 1), to 1e-6 relative of the larger of the two
 * (plus the differences' rounding, 1e-9 of A or B). */
START_TEST(partials)
{
    static const double ps[][4] = { { 0.0, 0.3, 1.5, 1.0 }, { 1.0, 0.05, 1.5, 1.0 },
                                    { 0.4, 0.9, 2.5, 0.3 }, { 0.7, 0.2, 1.05, 0.8 } };
    static const double dirs[][6] = { { 0.3, 0.1, 0.95, -0.2, 0.05, 0.97 },
                                      { 0.9, 0.0, 0.43, -0.6, 0.3, 0.74 },
                                      { 0.0, 0.0, 1.0, 0.0, 0.0, 1.0 },
                                      { 0.99, 0.0, 0.14, 0.5, 0.5, 0.707 } };
    const double white[3] = { 1, 1, 1 };
    for (size_t a = 0; a < sizeof ps / sizeof ps[0]; a++)
        for (size_t d = 0; d < sizeof dirs / sizeof dirs[0]; d++) {
            const double *v = dirs[d];
            double ni = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            double no = sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
            bf_geom g = { v[0] / ni, v[1] / ni, v[2] / ni, v[3] / no, v[4] / no, v[5] / no, 0, 0 };
            bf_geom_derive(&g);
            double A, B, dA[4], dB[4], A3[3], B3[3];
            bf_gltf_affine_grad(&g, ps[a], &A, &B, dA, dB);
            bf_gltf_affine(&g, ps[a], white, A3, B3);
            ck_assert(tu_reldiff(A, A3[0]) < 1e-14 && tu_reldiff(B, B3[0]) < 1e-14);
            for (int k = 0; k < 4; k++) {
                double h = 1e-6, hi[4], lo[4], Ah[3], Bh[3], Al[3], Bl[3];
                memcpy(hi, ps[a], sizeof hi);
                memcpy(lo, ps[a], sizeof lo);
                hi[k] += h;
                lo[k] -= h;
                bf_gltf_affine(&g, hi, white, Ah, Bh);
                bf_gltf_affine(&g, lo, white, Al, Bl);
                double fa = (Ah[0] - Al[0]) / (2 * h), fb = (Bh[0] - Bl[0]) / (2 * h);
                /* the differences' rounding: ~1e-16 X / h */
                double sa = fmax(fabs(fa), fabs(dA[k])) + 1e-3 * fabs(A);
                double sb = fmax(fabs(fb), fabs(dB[k])) + 1e-3 * fabs(B);
                ck_assert_msg(fabs(fa - dA[k]) <= 1e-6 * sa, "p %zu dir %zu dA[%d] %.10g vs %.10g", a,
                              d, k, dA[k], fa);
                ck_assert_msg(fabs(fb - dB[k]) <= 1e-6 * sb, "p %zu dir %zu dB[%d] %.10g vs %.10g", a,
                              d, k, dB[k], fb);
            }
        }
}
END_TEST

Suite *gltf_fit_suite(void)
{
    Suite *s = suite_create("gltf_fit");
    TCase *tc = tcase_create("gltf_fit");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, recovery, 0, NCASES);
    tcase_add_test(tc, pass_sums);
    tcase_add_test(tc, pass_workers);
    tcase_add_test(tc, partials);
    suite_add_tcase(s, tc);
    return s;
}
