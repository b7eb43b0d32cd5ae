/* SPDX-License-Identifier: MIT */
/* affine_pass.c -- the data pass of the affine engine (affine.h): the sums
 * of the bases A, B and their first-order steps at one lobe point over a
 * sample set, in double, split over threads; and the Error of a model's
 * parameters summed directly.  A host loop (the glTF models have no OpenCL
 * kernel: docs/fitting.md, "The glTF models"), written in blocks of AF_L
 * samples with every quantity an array over the block's lanes, so that the
 * compiler evaluates bf_gltf.h on a block as vectors (docs/performance.md). */
#define _DEFAULT_SOURCE
#include "affine.h"

#include "samples.h"
#include "subsets.h"
#include "bf_gltf.h"

#include <string.h>
#include <unistd.h>

#define AF_MAX_THREADS 16
/* Below this many samples a pass runs in the calling thread alone. */
#define AF_MIN_PER_THREAD 20000
/* Samples a block: one AVX-512 vector of doubles per quantity.  Each lane
 * keeps its own sums, added in lane order at the end: the same sums
 * whatever vectors the compiler takes. */
#define AF_L 8
/* Blocks a tile: a pass adds a tile's products to its sums at once (four
 * blocks' products summed in a fixed order, then added), a quarter of the
 * loads and stores of the sums. */
#define AF_T 4
/* The quantities a sample contributes: A, B, dA_j, dB_j, rho_c. */
#define AF_NY (2 + 2 * AF_NP + 3)
#define AF_NG (AF_NY * (AF_NY + 1) / 2)

/* The clones of the block loops for wider vectors than the build's default
 * (chosen when the library loads: GCC on x86-64). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define AF_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define AF_CLONES
#endif
#define AF_INLINE static inline __attribute__((always_inline))

/* One block of samples: the fields the glTF BRDF reads, the values and the
 * weights; lanes past the end of the run repeat its last sample with
 * weight 0. */
typedef struct af_block {
    double iz[AF_L], oz[AF_L], nh[AF_L], vh[AF_L];
    double rho[3][AF_L], w[AF_L];
} af_block;

AF_INLINE void load_block(const brdffit_samples *s, size_t i, size_t end, af_block *b)
{
    static const int fields[8] = { BF_F_IZ, BF_F_OZ, BF_F_NH, BF_F_VH,
                                   BF_F_R,  BF_F_G,  BF_F_B,  BF_F_A2 };
    double *dst[8] = { b->iz, b->oz, b->nh, b->vh, b->rho[0], b->rho[1], b->rho[2], b->w };
    const size_t nl = i < end ? end - i : 0; /* lanes in the run */
    for (int k = 0; k < 8; k++) {
        const double *field = s->data + (size_t)fields[k] * s->npad;
        if (nl >= AF_L) { /* a whole block: one vector */
            memcpy(dst[k], field + i, AF_L * sizeof(double));
            continue;
        }
        for (size_t l = 0; l < AF_L; l++)
            dst[k][l] = l < nl ? field[i + l] : k == 7 ? 0.0 : field[end - 1];
    }
}

/* The geometry bf_gltf.h reads (N.L, N.V, N.H, V.H) of lane l. */
AF_INLINE bf_geom lane_geom(const af_block *b, int l)
{
    bf_geom g = { 0.0, 0.0, b->iz[l], 0.0, 0.0, b->oz[l], b->nh[l], b->vh[l] };
    return g;
}

typedef struct af_job {
    const brdffit_samples *samples;
    bf_gltf_pt pt;                   /* the point (a fit's pass)          */
    double coef[AF_NP][AF_NP];       /* (p_j - p_0)_k / h_j               */
    int np;
    const brdffit_params *params;    /* the parameters (an Error's sum)   */
    size_t i0, i1;
    double g[AF_NG];                 /* a pass: sum a^2 y_a y_b, a <= b   */
    double rr;                       /* an Error's sum                    */
} af_job;

/* Row y[0 .. ny-1] of a block: A, B, dA_j, dB_j (j < np), rho_c; dX_j the
 * partials' first-order step to the neighbour p_j (as bf_pass_partials
 * takes a lobe's). */
AF_INLINE int block_rows(const af_job *jb, const af_block *b, double y[AF_NY][AF_L])
{
    double pa[AF_NP][AF_L], pb[AF_NP][AF_L];
    const int np = jb->np, ny = 2 + 2 * np + 3;
    for (int c = 0; c < 3; c++)
        memcpy(y[ny - 3 + c], b->rho[c], sizeof y[0]);
    if (np == 0) { /* the value alone */
        for (int l = 0; l < AF_L; l++) {
            bf_geom g = lane_geom(b, l);
            bf_gltf_terms k;
            bf_gltf_affine_at(&g, &jb->pt, &y[0][l], &y[1][l], &k);
        }
        return ny;
    }
    for (int l = 0; l < AF_L; l++) {
        bf_geom g = lane_geom(b, l);
        double A, B, dA[AF_NP], dB[AF_NP];
        bf_gltf_affine_grad_at(&g, &jb->pt, &A, &B, dA, dB);
        y[0][l] = A;
        y[1][l] = B;
        pa[0][l] = dA[0], pa[1][l] = dA[1], pa[2][l] = dA[2], pa[3][l] = dA[3];
        pb[0][l] = dB[0], pb[1][l] = dB[1], pb[2][l] = dB[2], pb[3][l] = dB[3];
    }
    for (int j = 0; j < np; j++) {
        const double c0 = jb->coef[j][0], c1 = jb->coef[j][1], c2 = jb->coef[j][2],
                     c3 = jb->coef[j][3];
        double *ya = y[2 + j], *yb = y[2 + np + j];
        for (int l = 0; l < AF_L; l++)
            ya[l] = ((pa[0][l] * c0 + pa[1][l] * c1) + pa[2][l] * c2) + pa[3][l] * c3;
        for (int l = 0; l < AF_L; l++)
            yb[l] = ((pb[0][l] * c0 + pb[1][l] * c1) + pb[2][l] * c2) + pb[3][l] * c3;
    }
    return ny;
}

AF_CLONES static void pass_range(af_job *jb)
{
    double acc[AF_NG][AF_L];
    memset(acc, 0, sizeof acc);
    for (size_t i = jb->i0; i < jb->i1; i += AF_T * AF_L) {
        af_block b[AF_T];
        double y[AF_T][AF_NY][AF_L];
        int ny = 0;
        for (int t = 0; t < AF_T; t++) {
            load_block(jb->samples, i + (size_t)t * AF_L, jb->i1, &b[t]);
            ny = block_rows(jb, &b[t], y[t]);
        }
        int k = 0;
        for (int a = 0; a < ny; a++) {
            double wy[AF_T][AF_L];
            for (int t = 0; t < AF_T; t++)
                for (int l = 0; l < AF_L; l++)
                    wy[t][l] = b[t].w[l] * y[t][a][l];
            for (int c = a; c < ny; c++, k++)
                for (int l = 0; l < AF_L; l++)
                    acc[k][l] += ((wy[0][l] * y[0][c][l] + wy[1][l] * y[1][c][l])
                                  + wy[2][l] * y[2][c][l]) + wy[3][l] * y[3][c][l];
        }
    }
    for (int k = 0; k < AF_NG; k++) {
        double v = 0.0;
        for (int l = 0; l < AF_L; l++)
            v += acc[k][l];
        jb->g[k] = v;
    }
}

AF_CLONES static void rr_range(af_job *jb)
{
    double acc[3][AF_L];
    memset(acc, 0, sizeof acc);
    const brdffit_params *q = jb->params;
    for (size_t i = jb->i0; i < jb->i1; i += AF_L) {
        af_block b;
        load_block(jb->samples, i, jb->i1, &b);
        for (int l = 0; l < AF_L; l++) {
            bf_geom g = lane_geom(&b, l);
            double f[3];
            bf_gltf(&g, q->p, q->d, q->s, f);
            double e0 = b.rho[0][l] - f[0], e1 = b.rho[1][l] - f[1], e2 = b.rho[2][l] - f[2];
            acc[0][l] += b.w[l] * e0 * e0;
            acc[1][l] += b.w[l] * e1 * e1;
            acc[2][l] += b.w[l] * e2 * e2;
        }
    }
    double rr = 0.0;
    for (int c = 0; c < 3; c++)
        for (int l = 0; l < AF_L; l++)
            rr += acc[c][l];
    jb->rr = rr;
}

static void af_run(void *arg)
{
    af_job *jb = arg;
    if (jb->params)
        rr_range(jb);
    else
        pass_range(jb);
}

static int af_threads(size_t n)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    long by_size = (long)(n / AF_MIN_PER_THREAD);
    long t = cpus < by_size ? cpus : by_size;
    return t < 1 ? 1 : t > AF_MAX_THREADS ? AF_MAX_THREADS : (int)t;
}

/* Run the jobs, their sample ranges filled in here in whole tiles, on the
 * pass workers (affine_pool.c). */
static void run_jobs(const brdffit_samples *s, af_job *jobs, int nt)
{
    const size_t tile = AF_T * AF_L, tiles = (s->n + tile - 1) / tile;
    for (int k = 0; k < nt; k++) {
        jobs[k].i0 = tile * (tiles * (size_t)k / (size_t)nt);
        jobs[k].i1 = tile * (tiles * (size_t)(k + 1) / (size_t)nt);
        if (jobs[k].i1 > s->n)
            jobs[k].i1 = s->n;
    }
    bf_affine_run(af_run, jobs, sizeof *jobs, nt, af_threads(~(size_t)0 >> 1));
}

/* The index of sum y_a y_c (a <= c) among ny rows' sums. */
static int gix(int ny, int a, int c)
{
    return a * ny - a * (a - 1) / 2 + (c - a);
}

/* The pass's sums g (ny rows) as m's moments. */
static void to_moments(const double *g, int np, af_mom *m)
{
    const int ny = 2 + 2 * np + 3, A = 0, B = 1, R = ny - 3;
#define DA(j) (2 + (j))
#define DB(j) (2 + np + (j))
    m->aa = g[gix(ny, A, A)];
    m->ab = g[gix(ny, A, B)];
    m->bb = g[gix(ny, B, B)];
    for (int j = 0; j < np; j++) {
        m->daa[j] = g[gix(ny, A, DA(j))];
        m->dab[j] = g[gix(ny, B, DA(j))];
        m->dba[j] = g[gix(ny, A, DB(j))];
        m->dbb[j] = g[gix(ny, B, DB(j))];
        for (int l = 0; l < np; l++) {
            m->dadb[j][l] = g[gix(ny, DA(j), DB(l))];
            if (l >= j) {
                m->dada[j][l] = g[gix(ny, DA(j), DA(l))];
                m->dbdb[j][l] = g[gix(ny, DB(j), DB(l))];
            }
        }
    }
    for (int c = 0; c < 3; c++) {
        m->rr[c] = g[gix(ny, R + c, R + c)];
        m->ra[c] = g[gix(ny, A, R + c)];
        m->rb[c] = g[gix(ny, B, R + c)];
        for (int j = 0; j < np; j++) {
            m->rda[c][j] = g[gix(ny, DA(j), R + c)];
            m->rdb[c][j] = g[gix(ny, DB(j), R + c)];
        }
    }
#undef DA
#undef DB
}

brdffit_status bf_affine_pass(const brdffit_samples *samples, brdffit_model model,
                              const double (*pts)[AF_NP], int np, const double *inv_h, af_mom *m,
                              brdffit_error *err)
{
    (void)model; /* one affine model today: the glTF BRDF */
    (void)err;
    af_job jobs[AF_MAX_THREADS];
    const int nt = af_threads(samples->n);
    for (int k = 0; k < nt; k++) {
        af_job *jb = &jobs[k];
        memset(jb, 0, sizeof *jb);
        jb->samples = samples;
        jb->pt = bf_gltf_point(pts[0]);
        jb->np = np;
        for (int j = 0; j < np; j++)
            for (int i = 0; i < AF_NP; i++)
                jb->coef[j][i] = (pts[1 + j][i] - pts[0][i]) * inv_h[j];
    }
    run_jobs(samples, jobs, nt);
    double g[AF_NG] = { 0 };
    for (int k = 0; k < nt; k++)
        for (int i = 0; i < AF_NG; i++)
            g[i] += jobs[k].g[i];
    memset(m, 0, sizeof *m);
    m->np = np;
    to_moments(g, np, m);
    for (int c = 0; c < 3; c++)
        m->rr[c] += samples->pair_see[c];
    return BRDFFIT_OK;
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
    (void)model; /* one affine model today: the glTF BRDF */
    af_job jobs[AF_MAX_THREADS];
    const int nt = af_threads(samples->n);
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
