/* SPDX-License-Identifier: MIT */
/* metric.h -- the Error metrics on the host (metric.c): each metric's
 * transform g, the pairs of mirror samples a metric pass reads, and the
 * passes: the Error under every metric at a point, and the normal equations
 * of the metric's least squares in all of a model's parameters (what the
 * fit under "log" or "cube-root" runs LM on: fit/metric_fit.c). */
#ifndef BRDFFIT_METRIC_H
#define BRDFFIT_METRIC_H

#include "internal.h"

#include <stddef.h>

/* The most parameters the metric fit moves: 6 colours + 4 lobe coordinates. */
#define BF_MT_MAX 10

/* g(v) of a metric at a sample with cos(theta_i) = ci, and g'(v). */
double bf_metric_g(brdffit_metric m, double v, double ci);
double bf_metric_dg(brdffit_metric m, double v, double ci);

/* The samples of a set as the metric passes read them: groups of one or two
 * samples (the mirror pair (i, j, k), (i, j, 180 - k)) with one geometry. */
typedef struct bf_metric_set {
    const brdffit_samples *src;
    size_t n;          /* groups */
    size_t *first;     /* n: the group's sample whose geometry is evaluated */
    size_t *second;    /* n: its mirror partner, or (size_t)-1 */
    double *grho;      /* 6 per sample of src: g(rho_c) under log (c = 0..2),
                        * then cube-root: what every pass would compute again */
} bf_metric_set;

/* The groups of src, kept with src (freed with it). */
brdffit_status bf_metric_set_kept(const brdffit_samples *src, const bf_metric_set **out,
                                  brdffit_error *err);

/* A point of a metric pass: the model, its parameters now, and the lobe
 * coordinates' parameter points for the derivatives (pts[1 + j] at
 * u + h_j e_j, inv_h[j] = 1 / h_j).  ntheta = nlin + nl, the colours
 * first: d_0..2, s_0..2 (d/pi + s K models) or the base colour x_0..2
 * (glTF: f = A + x B), then the lobe coordinates. */
typedef struct bf_metric_point {
    brdffit_model model;
    brdffit_metric metric;
    int gltf;                       /* f = A + x B (1) or d/pi + s K (0) */
    int nl;                         /* lobe coordinates */
    brdffit_params params;          /* at the point (params.p = pts[0]) */
    double lam[3];
    double pts[1 + BRDFFIT_MAX_LOBE_PARAMS][BRDFFIT_MAX_LOBE_PARAMS];
    double inv_h[BRDFFIT_MAX_LOBE_PARAMS];
    unsigned sum_bits;              /* the metrics whose rr a pass sums (0:
                                     * pt->metric's alone) */
} bf_metric_point;

int bf_metric_ntheta(const bf_metric_point *pt);

/* The sums of a pass over every stride-th group. */
typedef struct bf_metric_sums {
    double rr[BRDFFIT_METRIC_COUNT]; /* sum w_s/(3 sum w) (g(rho) - g(f))^2, each metric */
    double jtj[BF_MT_MAX * BF_MT_MAX]; /* of pt->metric, full passes only */
    double jtr[BF_MT_MAX];
} bf_metric_sums;

/* A value pass (full = 0: rr of every metric) or a full pass (full = 1:
 * also J^T J and J^T r of pt->metric's residuals in theta) over every
 * stride-th group, split over the online CPUs.  Fails only to start
 * (BRDFFIT_E_NO_MEMORY when no thread can be made). */
brdffit_status bf_metric_pass(const bf_metric_set *set, size_t stride, const bf_metric_point *pt,
                              int full, bf_metric_sums *out, brdffit_error *err);

/* The metrics a value pass sums (bits 1 << brdffit_metric): full passes and
 * the fit's value passes sum pt->metric's alone, bf_metric_errors log and
 * cube-root; every one when this is set (the tests). */
#define BF_METRIC_ALL_BITS ((1u << BRDFFIT_METRIC_COUNT) - 1u)

#endif /* BRDFFIT_METRIC_H */
