/* SPDX-License-Identifier: MIT */
/* affine_pass_openpbr.c -- the data pass of the affine engine (affine.h) for
 * OpenPBR: the sums of the bases A, B, Q and their forward differences at
 * one lobe point over a sample set, in double, on the pass workers
 * (affine_pool.c); and the Error of its parameters summed directly.  Its
 * albedo is a table (kernels/bf_openpbr.h): the model is evaluated at every
 * point, each point's albedo looked up in its own slice. */
#define _DEFAULT_SOURCE
#include "affine.h"

#include "samples.h"
#include "bf_gltf.h"
#include "bf_openpbr.h"

#include <math.h>
#include <string.h>
#include <unistd.h>

#define OP_MAX_THREADS 16
/* Below this many samples a pass runs in the calling thread alone. */
#define OP_MIN_PER_THREAD 20000

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
static void op_add(af_qmom *m, double a2, const double *rho, const double *bv, const double *dv)
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

typedef struct op_job {
    const brdffit_samples *samples;
    const bf_openpbr_slice *slices;    /* the albedo at each point            */
    int same_lobe[AF_NP];              /* neighbour j's lobe is p_0's (2), has
                                        * its roughness (1), or neither (0)  */
    const double (*pts)[AF_NP];
    const double *inv_h;
    const brdffit_params *params;      /* the parameters (an Error's sum)     */
    size_t i0, i1;
    af_qmom m;                         /* a pass's sums                       */
    double rr;                         /* an Error's sum                      */
} op_job;

/* The bases A, B, Q at p_0 and their forward differences to the neighbours,
 * the albedo looked up in each point's slice; a neighbour that differs in
 * base_metalness alone has p_0's lobe, one of p_0's roughness its D Vis. */
static void openpbr_steps(const op_job *jb, const bf_geom *g, double *bv, double *dv)
{
    bf_openpbr_lobe L0;
    double e, ess;
    bf_openpbr_slice_at(&jb->slices[0], g->oz, &e, &ess);
    bf_openpbr_lobe_with(g, jb->pts[0], e, ess, &L0);
    bf_openpbr_form_of(&L0, jb->pts[0], &bv[0], &bv[1], &bv[2]);
    for (int j = 0; j < jb->m.np; j++) {
        const double *pj = jb->pts[1 + j];
        double b[3];
        if (jb->same_lobe[j] == 2) {
            bf_openpbr_form_of(&L0, pj, &b[0], &b[1], &b[2]);
        } else {
            bf_openpbr_lobe L;
            bf_openpbr_slice_at(&jb->slices[1 + j], g->oz, &e, &ess);
            if (jb->same_lobe[j] == 1)
                bf_openpbr_lobe_f0(&L0, g, pj, e, ess, &L);
            else
                bf_openpbr_lobe_with(g, pj, e, ess, &L);
            bf_openpbr_form_of(&L, pj, &b[0], &b[1], &b[2]);
        }
        for (int x = 0; x < 3; x++)
            dv[3 * j + x] = (b[x] - bv[x]) * jb->inv_h[j];
    }
}

static void pass_range(op_job *jb)
{
    for (size_t i = jb->i0; i < jb->i1; i++) {
        bf_geom g;
        double rho[3], bv[AF_NB], dv[AF_ND];
        double a2 = sample_at(jb->samples, i, &g, rho);
        openpbr_steps(jb, &g, bv, dv);
        op_add(&jb->m, a2, rho, bv, dv);
    }
}

static void rr_range(op_job *jb)
{
    double lam[3], rr = 0.0;
    bf_lambdas(jb->params, lam);
    for (size_t i = jb->i0; i < jb->i1; i++) {
        bf_geom g;
        double rho[3], f[3];
        double a2 = sample_at(jb->samples, i, &g, rho);
        bf_model_value(BRDFFIT_OPENPBR, &g, jb->params, lam, f);
        for (int c = 0; c < 3; c++)
            rr += a2 * (rho[c] - f[c]) * (rho[c] - f[c]);
    }
    jb->rr = rr;
}

static void op_run(void *arg)
{
    op_job *jb = arg;
    if (jb->params)
        rr_range(jb);
    else
        pass_range(jb);
}

static int op_threads(size_t n)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    long by_size = (long)(n / OP_MIN_PER_THREAD);
    long t = cpus < by_size ? cpus : by_size;
    return t < 1 ? 1 : t > OP_MAX_THREADS ? OP_MAX_THREADS : (int)t;
}

/* Run nt jobs, each a contiguous share of the samples, on the pass workers. */
static void run_jobs(const brdffit_samples *s, op_job *jobs, int nt)
{
    for (int k = 0; k < nt; k++) {
        jobs[k].i0 = s->n * (size_t)k / (size_t)nt;
        jobs[k].i1 = s->n * (size_t)(k + 1) / (size_t)nt;
    }
    bf_affine_run(op_run, jobs, sizeof *jobs, nt, op_threads(~(size_t)0 >> 1));
}

/* m += t (the sums of one job). */
static void op_sum(af_qmom *m, const af_qmom *t)
{
    const double *src = &t->gg[0][0];
    double *dst = &m->gg[0][0];
    const size_t n = (sizeof *m - offsetof(af_qmom, gg)) / sizeof(double);
    for (size_t k = 0; k < n; k++)
        dst[k] += src[k];
}

brdffit_status bf_affine_pass_openpbr(const brdffit_samples *samples, const double (*pts)[AF_NP],
                                      int np, const double *inv_h, af_qmom *m, brdffit_error *err)
{
    (void)err;
    op_job jobs[OP_MAX_THREADS];
    bf_openpbr_slice slices[1 + AF_NP];
    int same_lobe[AF_NP] = { 0 };
    for (int k = 0; k <= np; k++)
        bf_openpbr_albedo_slice(fmax(pts[k][1], BF_GLTF_ROUGHNESS_MIN),
                                bf_openpbr_f0(pts[k][2], pts[k][3]), &slices[k]);
    for (int j = 0; j < np; j++)
        same_lobe[j] = pts[1 + j][1] != pts[0][1]                                    ? 0
                       : pts[1 + j][2] == pts[0][2] && pts[1 + j][3] == pts[0][3] ? 2
                                                                                      : 1;
    const int nt = op_threads(samples->n);
    for (int k = 0; k < nt; k++) {
        op_job *jb = &jobs[k];
        memset(jb, 0, sizeof *jb);
        jb->samples = samples;
        jb->slices = slices;
        memcpy(jb->same_lobe, same_lobe, sizeof same_lobe);
        jb->pts = pts;
        jb->inv_h = inv_h;
        jb->m.np = np;
        jb->m.nb = AF_NB;
    }
    run_jobs(samples, jobs, nt);
    memset(m, 0, sizeof *m);
    m->np = np;
    m->nb = AF_NB;
    for (int k = 0; k < nt; k++)
        op_sum(m, &jobs[k].m);
    for (int c = 0; c < 3; c++)
        m->rr[c] += samples->pair_see[c];
    return BRDFFIT_OK;
}

double bf_openpbr_rr(const brdffit_samples *samples, const brdffit_params *params)
{
    op_job jobs[OP_MAX_THREADS];
    const int nt = op_threads(samples->n);
    for (int k = 0; k < nt; k++) {
        memset(&jobs[k], 0, sizeof jobs[k]);
        jobs[k].samples = samples;
        jobs[k].params = params;
    }
    run_jobs(samples, jobs, nt);
    double rr = 0.0;
    for (int k = 0; k < nt; k++)
        rr += jobs[k].rr;
    for (int c = 0; c < 3; c++)
        rr += samples->pair_see[c];
    return rr;
}
