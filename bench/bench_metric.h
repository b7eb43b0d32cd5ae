/* SPDX-License-Identifier: MIT */
/* bench_metric.h -- part 2's fits under each Error metric (bench_metric.c). */
#ifndef BRDFFIT_BENCH_METRIC_H
#define BRDFFIT_BENCH_METRIC_H

#include "brdffit.h"

/* Per model selected by `models` (NULL: all), its fit under ngan-l2, log
 * and cube-root in turn, `rounds` times, the fastest of each printed and
 * recorded (fit/MODEL/alum-bronze/METRIC: fit seconds, the ratio to the
 * ngan-l2 fit, the Error).  0, or 1 after printing why. */
int bench_metric_fits(brdffit_context *ctx, const brdffit_samples *s, const char *models,
                      int rounds);

/* `brdffit batch --metric all --no-render --no-plot` over the first few of
 * the ntab tables names (of models, NULL: the default set), timed from
 * outside; printed with its projection to all ntab tables and recorded
 * (database/metric-all).  0, or 1 after printing why. */
int bench_metric_batch(char (*names)[64], int ntab, const char *models);

#endif
