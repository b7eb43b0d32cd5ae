/* SPDX-License-Identifier: MIT */
/* affine_pass.c -- the data pass of the affine engine (affine.h): the sums
 * of the bases A, B and their forward differences at one lobe point over a
 * sample set, in double, split over threads; and the Error of a model's
 * parameters summed directly.  A host loop: the glTF and OpenPBR models
 * have no OpenCL kernel (docs/fitting.md, "The glTF models"). */
#define _DEFAULT_SOURCE
#include "affine.h"

#include "samples.h"
#include "subsets.h"
#include "bf_gltf.h"
#include "bf_openpbr.h"

#include <pthread.h>
#include <string.h>
#include <unistd.h>

#define AF_MAX_THREADS 16
/* Below this many samples a pass runs in the calling thread alone. */
#define AF_MIN_PER_THREAD 20000

/* Sample i's geometry, values and weight. */
static double sample_at(const brdffit_samples *s, size_t i, bf_geom *g, double *rho)
{
    const size_t n = s->npad;
    const double *f = s->data;
    bf_geom t = { f[BF_F_IX * n + i], f[BF_F_IY * n + i], f[BF_F_IZ * n + i],
                  f[BF_F_OX * n + i], f[BF_F_OY * n + i], f[BF_F_OZ * n + i],
                  f[BF_F_NH * n + i], f[BF_F_VH * n + i] };
    *g = t;
    rho[0] = f[BF_F_R * n + i];
    rho[1] = f[BF_F_G * n + i];
    rho[2] = f[BF_F_B * n + i];
    return f[BF_F_A2 * n + i];
}

/* Add one sample (weight a2, values rho) with bases bv[X] at p_0 and their
 * differences dv[j nb + X] to m. */
static void af_add(af_mom *m, double a2, const double *rho, const double *bv, const double *dv)
{
    const int nb = m->nb, nd = m->np * nb;
    for (int x = 0; x < nb; x++)
        for (int y = x; y < nb; y++)
            m->gg[x][y] += a2 * bv[x] * bv[y];
    for (int f = 0; f < nd; f++) {
        double adf = a2 * dv[f];
        for (int y = 0; y < nb; y++)
            m->dg[f][y] += adf * bv[y];
        for (int h = f; h < nd; h++)
            m->dd[f][h] += adf * dv[h];
    }
    for (int c = 0; c < 3; c++) {
        double ar = a2 * rho[c];
        m->rr[c] += ar * rho[c];
        for (int x = 0; x < nb; x++)
            m->rg[c][x] += ar * bv[x];
        for (int f = 0; f < nd; f++)
            m->rd[c][f] += ar * dv[f];
    }
}

typedef struct af_job {
    const brdffit_samples *samples;
    int openpbr;                       /* the model: OpenPBR (else glTF) */
    const double (*pts)[AF_NP];
    const double *inv_h;
    size_t i0, i1;
    af_mom m;
} af_job;

/* dX_j from the partials in p: dX / dp . (p_j - p_0) / h_j, the first-order
 * step to the neighbour p_j (as bf_pass_partials takes a lobe's), each
 * coefficient (p_j - p_0) / h_j a number of the pass (coef). */
static double af_step(const double *dX, const double *coef)
{
    double v = 0.0;
    for (int k = 0; k < AF_NP; k++)
        v += dX[k] * coef[k];
    return v;
}

/* OpenPBR's bases A, B, Q at p_0 and their forward differences to the
 * neighbours (its albedo is a table: no partials in closed form). */
static void openpbr_steps(const af_job *jb, const bf_geom *g, double *bv, double *dv)
{
    bf_openpbr_form(g, jb->pts[0], &bv[0], &bv[1], &bv[2]);
    for (int j = 0; j < jb->m.np; j++) {
        double b[3];
        bf_openpbr_form(g, jb->pts[1 + j], &b[0], &b[1], &b[2]);
        for (int x = 0; x < 3; x++)
            dv[3 * j + x] = (b[x] - bv[x]) * jb->inv_h[j];
    }
}

/* glTF's bases A, B at p_0 and their steps to the neighbours. */
static void gltf_steps(const af_job *jb, const bf_geom *g, const double (*coef)[AF_NP],
                       double *bv, double *dv)
{
    double pA[AF_NP], pB[AF_NP];
    bf_gltf_affine_grad(g, jb->pts[0], &bv[0], &bv[1], pA, pB);
    for (int j = 0; j < jb->m.np; j++) {
        dv[2 * j] = af_step(pA, coef[j]);
        dv[2 * j + 1] = af_step(pB, coef[j]);
    }
}

static void *af_run(void *arg)
{
    af_job *jb = arg;
    const int np = jb->m.np;
    double coef[AF_NP][AF_NP];
    for (int j = 0; j < np; j++)
        for (int k = 0; k < AF_NP; k++)
            coef[j][k] = (jb->pts[1 + j][k] - jb->pts[0][k]) * jb->inv_h[j];
    for (size_t i = jb->i0; i < jb->i1; i++) {
        bf_geom g;
        double rho[3], bv[AF_NB], dv[AF_ND];
        double a2 = sample_at(jb->samples, i, &g, rho);
        if (jb->openpbr)
            openpbr_steps(jb, &g, bv, dv);
        else
            gltf_steps(jb, &g, (const double (*)[AF_NP])coef, bv, dv);
        af_add(&jb->m, a2, rho, bv, dv);
    }
    return NULL;
}

/* m += t (the sums of one thread's run). */
static void af_sum(af_mom *m, const af_mom *t)
{
    const double *src = &t->gg[0][0];
    double *dst = &m->gg[0][0];
    const size_t n = (sizeof *m - offsetof(af_mom, gg)) / sizeof(double);
    for (size_t k = 0; k < n; k++)
        dst[k] += src[k];
}

static int af_threads(size_t n)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    long by_size = (long)(n / AF_MIN_PER_THREAD);
    long t = cpus < by_size ? cpus : by_size;
    return t < 1 ? 1 : t > AF_MAX_THREADS ? AF_MAX_THREADS : (int)t;
}

brdffit_status bf_affine_pass(const brdffit_samples *samples, brdffit_model model,
                              const double (*pts)[AF_NP], int np, const double *inv_h, af_mom *m,
                              brdffit_error *err)
{
    af_job jobs[AF_MAX_THREADS];
    pthread_t tid[AF_MAX_THREADS];
    const int nt = af_threads(samples->n);
    int started = 0;
    for (int k = 0; k < nt; k++) {
        af_job *jb = &jobs[k];
        memset(jb, 0, sizeof *jb);
        jb->samples = samples;
        jb->openpbr = brdffit_model_get(model)->colour_form == BRDFFIT_COLOUR_OPENPBR;
        jb->pts = pts;
        jb->inv_h = inv_h;
        jb->m.np = np;
        jb->m.nb = jb->openpbr ? 3 : 2;
        jb->i0 = samples->n * (size_t)k / (size_t)nt;
        jb->i1 = samples->n * (size_t)(k + 1) / (size_t)nt;
        if (k > 0 && pthread_create(&tid[k], NULL, af_run, jb) == 0)
            started |= 1 << k;
    }
    af_run(&jobs[0]);
    for (int k = 1; k < nt; k++) {
        if (started & (1 << k))
            pthread_join(tid[k], NULL);
        else
            af_run(&jobs[k]); /* no thread: run it here */
    }
    memset(m, 0, sizeof *m);
    m->np = np;
    m->nb = jobs[0].m.nb;
    for (int k = 0; k < nt; k++)
        af_sum(m, &jobs[k].m);
    for (int c = 0; c < 3; c++)
        m->rr[c] += samples->pair_see[c];
    (void)err;
    return BRDFFIT_OK;
}

brdffit_status bf_affine_all(const brdffit_samples *samples, brdffit_model model,
                             const brdffit_samples **out, brdffit_error *err)
{
    if (bf_model_def_get(model)->nonreciprocal) {
        *out = samples;
        return BRDFFIT_OK;
    }
    return bf_samples_mirror_kept(samples, out, err);
}

brdffit_status bf_affine_subset(const brdffit_samples *mirror, brdffit_model model,
                                const brdffit_samples **out, brdffit_error *err)
{
    size_t stride = (size_t)bf_model_def_get(model)->screen_stride;
    *out = mirror;
    if (stride <= 1 || mirror->n / stride < BF_SCREEN_MIN_SAMPLES)
        return BRDFFIT_OK;
    return bf_samples_every_kept(mirror, stride, out, err);
}

double bf_model_rr(const brdffit_samples *samples, brdffit_model model,
                   const brdffit_params *params)
{
    double lam[3], rr = 0.0;
    bf_lambdas(params, lam);
    for (size_t i = 0; i < samples->n; i++) {
        bf_geom g;
        double rho[3], f[3];
        double a2 = sample_at(samples, i, &g, rho);
        bf_model_value(model, &g, params, lam, f);
        for (int c = 0; c < 3; c++)
            rr += a2 * (rho[c] - f[c]) * (rho[c] - f[c]);
    }
    for (int c = 0; c < 3; c++)
        rr += samples->pair_see[c];
    return rr;
}
