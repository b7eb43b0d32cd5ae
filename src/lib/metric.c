/* SPDX-License-Identifier: MIT */
/* metric.c -- the Error metrics on the host: each metric's transform g, the
 * mirror pairs a metric pass reads (kept with the set), and the passes
 * (the Error under every metric; the normal equations of one metric's least
 * squares in all of a model's parameters).  docs/metrics.md. */
#include "metric.h"

#include "registry.h"
#include "samples.h"

#include "bf_models.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

double bf_metric_g(brdffit_metric m, double v, double ci)
{
    switch (m) {
    case BRDFFIT_METRIC_LOG:
        return log1p(v * ci);
    case BRDFFIT_METRIC_CUBE_ROOT:
        return cbrt(v + BRDFFIT_CUBE_ROOT_EPS);
    default:
        return v * ci;
    }
}

double bf_metric_dg(brdffit_metric m, double v, double ci)
{
    switch (m) {
    case BRDFFIT_METRIC_LOG:
        return ci / (1.0 + v * ci);
    case BRDFFIT_METRIC_CUBE_ROOT: {
        double t = cbrt(v + BRDFFIT_CUBE_ROOT_EPS);
        return 1.0 / (3.0 * t * t);
    }
    default:
        return ci;
    }
}

/* ---- the pairs */

static void metric_set_free(void *data)
{
    bf_metric_set *s = data;
    if (!s)
        return;
    free(s->first);
    free(s->second);
    free(s->grho);
    free(s);
}

/* Bin (i, j, k) with 1 <= k <= 89 and (i, j, 180 - k) make one group when
 * both are samples; every other sample is a group of its own. */
static brdffit_status make_metric_set(const brdffit_samples *src, const int key[3], void **out,
                                      brdffit_error *err)
{
    (void)key;
    bf_metric_set *s = calloc(1, sizeof *s);
    int *at = malloc(sizeof(int) * BRDFFIT_MERL_BINS);
    size_t n = src->n ? src->n : 1;
    if (s) {
        s->first = malloc(n * sizeof *s->first);
        s->second = malloc(n * sizeof *s->second);
        s->grho = malloc(6 * n * sizeof *s->grho);
    }
    if (!s || !at || !s->first || !s->second || !s->grho) {
        free(at);
        metric_set_free(s);
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "no memory for the metric pairs of %zu samples",
                       src->n);
    }
    s->src = src;
    for (size_t b = 0; b < BRDFFIT_MERL_BINS; b++)
        at[b] = -1;
    const size_t np = src->npad;
    for (size_t i = 0; i < src->n; i++) {
        at[src->bin[i]] = (int)i;
        double ci = src->data[BF_F_IZ * np + i];
        for (int c = 0; c < 3; c++) {
            double rho = src->data[(BF_F_R + c) * np + i];
            s->grho[6 * i + c] = bf_metric_g(BRDFFIT_METRIC_LOG, rho, ci);
            s->grho[6 * i + 3 + c] = bf_metric_g(BRDFFIT_METRIC_CUBE_ROOT, rho, ci);
        }
    }
    for (size_t i = 0; i < src->n; i++) {
        int b = src->bin[i], k = b % BRDFFIT_MERL_NPD;
        int mate = (k >= 1 && k <= 89) || (k >= 91) ? at[b - k + (BRDFFIT_MERL_NPD - k)] : -1;
        if (k >= 91 && mate >= 0)
            continue; /* in its partner's group */
        s->first[s->n] = i;
        s->second[s->n] = mate >= 0 ? (size_t)mate : (size_t)-1;
        s->n++;
    }
    free(at);
    *out = s;
    return BRDFFIT_OK;
}

brdffit_status bf_metric_set_kept(const brdffit_samples *src, const bf_metric_set **out,
                                  brdffit_error *err)
{
    const int key[3] = { 0, 0, 0 };
    const void *d = NULL;
    brdffit_status st = bf_derived_get(src, BF_DERIVED_METRIC, key, make_metric_set,
                                       metric_set_free, &d, err);
    *out = d;
    return st;
}

int bf_metric_ntheta(const bf_metric_point *pt)
{
    return (pt->gltf ? 3 : 6) + pt->nl;
}

/* ---- the passes */

/* The basis of f at a geometry: f_c = A_c + sum_k x_kc B_kc (d/pi + s K:
 * A = 0, B_0 = 1/pi, B_1 = K; glTF: A, B_0 = B), for lobe parameters p. */
static void basis(const bf_metric_point *pt, const bf_geom *g, const double *p, double A[3],
                  double B[3])
{
    brdffit_params q = pt->params;
    memcpy(q.p, p, sizeof q.p);
    for (int c = 0; c < 3; c++)
        q.d[c] = 0.0;
    if (pt->gltf) {
        double ab[3];
        bf_model_value(pt->model, g, &q, pt->lam, A);
        for (int c = 0; c < 3; c++)
            q.d[c] = 1.0;
        bf_model_value(pt->model, g, &q, pt->lam, ab);
        for (int c = 0; c < 3; c++)
            B[c] = ab[c] - A[c];
    } else {
        for (int c = 0; c < 3; c++)
            q.s[c] = 1.0;
        bf_model_value(pt->model, g, &q, pt->lam, B);
        for (int c = 0; c < 3; c++)
            A[c] = 0.0;
    }
}

static double f_of(const bf_metric_point *pt, int c, double A, double B)
{
    if (pt->gltf)
        return A + pt->params.d[c] * B;
    return pt->params.d[c] / BF_PI + pt->params.s[c] * B;
}

typedef struct mt_job {
    const bf_metric_set *set;
    const bf_metric_point *pt;
    size_t stride, g0, g1; /* groups g0, g0 + stride, ... below g1 */
    int full;
    bf_metric_sums sums;
} mt_job;

/* One sample of a group: its value, weight and cos(theta_i). */
static void member(const brdffit_samples *s, size_t i, double rho[3], double *wn, double *ci)
{
    const size_t np = s->npad;
    rho[0] = s->data[BF_F_R * np + i];
    rho[1] = s->data[BF_F_G * np + i];
    rho[2] = s->data[BF_F_B * np + i];
    *ci = s->data[BF_F_IZ * np + i];
    *wn = s->w[i] / (3.0 * s->sum_w);
}

/* g(rho_c) of sample i under metric m. */
static double g_rho(const bf_metric_set *set, brdffit_metric m, size_t i, int c, double rho,
                    double ci)
{
    if (m == BRDFFIT_METRIC_LOG)
        return set->grho[6 * i + c];
    if (m == BRDFFIT_METRIC_CUBE_ROOT)
        return set->grho[6 * i + 3 + c];
    return rho * ci;
}

/* g(f_c) under metric m at a sample with cos(theta_i) = ci (cube-root: the
 * group's, gcube, which does not depend on ci). */
static double g_f(brdffit_metric m, double f, double ci, double gcube)
{
    return m == BRDFFIT_METRIC_CUBE_ROOT ? gcube : bf_metric_g(m, f, ci);
}

/* Adds sample i's residuals under the metrics summed (rr) and, for a full
 * pass, its rows of J under pt->metric: df[c][t] = d f_c / d theta_t. */
static void add_member(mt_job *jb, size_t i, const double f[3], const double gcube[3],
                       const double df[3][BF_MT_MAX], int nt)
{
    const brdffit_samples *s = jb->set->src;
    const brdffit_metric mm = jb->pt->metric;
    const unsigned bits = jb->pt->sum_bits ? jb->pt->sum_bits : 1u << mm;
    double rho[3], wn, ci;
    member(s, i, rho, &wn, &ci);
    for (int c = 0; c < 3; c++) {
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
            if (!(bits & (1u << m)))
                continue;
            double r = g_rho(jb->set, (brdffit_metric)m, i, c, rho[c], ci) -
                       g_f((brdffit_metric)m, f[c], ci, gcube[c]);
            jb->sums.rr[m] += wn * r * r;
        }
        if (!jb->full)
            continue;
        double r = g_rho(jb->set, mm, i, c, rho[c], ci) - g_f(mm, f[c], ci, gcube[c]);
        double gp = mm == BRDFFIT_METRIC_CUBE_ROOT ? 1.0 / (3.0 * gcube[c] * gcube[c])
                                                   : bf_metric_dg(mm, f[c], ci);
        double row[BF_MT_MAX];
        for (int t = 0; t < nt; t++)
            row[t] = -gp * df[c][t];
        for (int t = 0; t < nt; t++) {
            if (row[t] == 0.0)
                continue;
            double wr = wn * row[t];
            jb->sums.jtr[t] += wr * r;
            for (int u = t; u < nt; u++)
                jb->sums.jtj[t * BF_MT_MAX + u] += wr * row[u];
        }
    }
}

/* f and, for a full pass, its partials in theta at one geometry. */
static void values(const bf_metric_point *pt, const bf_geom *g, int full, double f[3],
                   double df[3][BF_MT_MAX])
{
    double A[3], B[3];
    basis(pt, g, pt->pts[0], A, B);
    for (int c = 0; c < 3; c++)
        f[c] = f_of(pt, c, A[c], B[c]);
    if (!full)
        return;
    const int nlin = pt->gltf ? 3 : 6;
    memset(df, 0, 3 * sizeof df[0]);
    for (int c = 0; c < 3; c++) {
        if (pt->gltf) {
            df[c][c] = B[c];
        } else {
            df[c][c] = 1.0 / BF_PI;
            df[c][3 + c] = B[c];
        }
    }
    for (int j = 0; j < pt->nl; j++) {
        double Aj[3], Bj[3];
        basis(pt, g, pt->pts[1 + j], Aj, Bj);
        for (int c = 0; c < 3; c++)
            df[c][nlin + j] = (f_of(pt, c, Aj[c], Bj[c]) - f[c]) * pt->inv_h[j];
    }
}

static void *mt_run(void *arg)
{
    mt_job *jb = arg;
    const brdffit_samples *s = jb->set->src;
    const size_t np = s->npad;
    const int nt = bf_metric_ntheta(jb->pt);
    const unsigned bits = jb->pt->sum_bits ? jb->pt->sum_bits : 1u << jb->pt->metric;
    const int cube = (bits & (1u << BRDFFIT_METRIC_CUBE_ROOT)) ||
                     jb->pt->metric == BRDFFIT_METRIC_CUBE_ROOT;
    for (size_t k = jb->g0; k < jb->g1; k += jb->stride) {
        size_t i = jb->set->first[k], i2 = jb->set->second[k];
        const double *d = s->data;
        bf_geom g = { d[BF_F_IX * np + i], d[BF_F_IY * np + i], d[BF_F_IZ * np + i],
                      d[BF_F_OX * np + i], d[BF_F_OY * np + i], d[BF_F_OZ * np + i],
                      d[BF_F_NH * np + i], d[BF_F_VH * np + i] };
        double f[3], df[3][BF_MT_MAX], gcube[3] = { 0, 0, 0 };
        values(jb->pt, &g, jb->full, f, df);
        if (cube)
            for (int c = 0; c < 3; c++)
                gcube[c] = bf_metric_g(BRDFFIT_METRIC_CUBE_ROOT, f[c], 1.0);
        add_member(jb, i, f, gcube, df, nt);
        if (i2 != (size_t)-1)
            add_member(jb, i2, f, gcube, df, nt);
    }
    return NULL;
}

#define MT_MAX_THREADS 8
#define MT_MIN_PER_THREAD 4096

static int mt_threads(size_t groups)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    long by_size = (long)(groups / MT_MIN_PER_THREAD);
    long t = cpus < by_size ? cpus : by_size;
    return t < 1 ? 1 : t > MT_MAX_THREADS ? MT_MAX_THREADS : (int)t;
}

brdffit_status bf_metric_pass(const bf_metric_set *set, size_t stride, const bf_metric_point *pt,
                              int full, bf_metric_sums *out, brdffit_error *err)
{
    (void)err;
    mt_job jobs[MT_MAX_THREADS];
    pthread_t tid[MT_MAX_THREADS];
    const size_t ng = (set->n + stride - 1) / stride;
    const int nt = mt_threads(ng);
    int started = 0;
    for (int k = 0; k < nt; k++) {
        mt_job *jb = &jobs[k];
        memset(jb, 0, sizeof *jb);
        jb->set = set;
        jb->pt = pt;
        jb->stride = stride;
        jb->full = full;
        jb->g0 = ng * (size_t)k / (size_t)nt * stride;
        jb->g1 = ng * (size_t)(k + 1) / (size_t)nt * stride;
        if (jb->g1 > set->n)
            jb->g1 = set->n;
        if (k > 0 && pthread_create(&tid[k], NULL, mt_run, jb) == 0)
            started |= 1 << k;
    }
    mt_run(&jobs[0]);
    for (int k = 1; k < nt; k++) {
        if (started & (1 << k))
            pthread_join(tid[k], NULL);
        else
            mt_run(&jobs[k]);
    }
    memset(out, 0, sizeof *out);
    const int ntheta = bf_metric_ntheta(pt);
    for (int k = 0; k < nt; k++) {
        for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
            out->rr[m] += jobs[k].sums.rr[m];
        for (int t = 0; t < ntheta; t++) {
            out->jtr[t] += jobs[k].sums.jtr[t];
            for (int u = t; u < ntheta; u++)
                out->jtj[t * BF_MT_MAX + u] += jobs[k].sums.jtj[t * BF_MT_MAX + u];
        }
    }
    for (int t = 0; t < ntheta; t++)
        for (int u = 0; u < t; u++)
            out->jtj[t * BF_MT_MAX + u] = out->jtj[u * BF_MT_MAX + t];
    return BRDFFIT_OK;
}
