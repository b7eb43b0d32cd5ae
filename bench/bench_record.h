/* SPDX-License-Identifier: MIT */
/* bench_record.h -- a benchmark's figures appended to bench/results.tsv
 * through bench/record, the one writer of that file's format (bench_record.c). */
#ifndef BRDFFIT_BENCH_RECORD_H
#define BRDFFIT_BENCH_RECORD_H

#include "brdffit.h"

/* The script that appends a figure (bench/record), or NULL: figures are
 * then only printed.  bench_brdffit --record SCRIPT sets it. */
void bench_record_use(const char *script);

/* Append the figure (benchmark: slash-separated, fit/ggx/alum-bronze;
 * metric: what was measured and its unit, "fit seconds") by running
 * `SCRIPT BENCHMARK METRIC VALUE` (argv, no shell).  Nothing without a
 * script; a non-finite value is not recorded.  0, or -1 after printing why
 * (the benchmark goes on). */
int bench_record(const char *benchmark, const char *metric, double value);

/* A metric and its value. */
typedef struct bench_figure {
    const char *metric;
    double value;
} bench_figure;

/* The n figures of one benchmark; 0, or -1 when one was not recorded. */
int bench_record_all(const char *benchmark, const bench_figure *f, int n);

/* One figure per model m with v[m] > 0, under "what/MODEL/where" ("what/MODEL"
 * when where is NULL); 0, or -1 when one was not recorded. */
int bench_record_models(const char *what, const char *where, const char *metric,
                        const double v[BRDFFIT_MODEL_COUNT]);

#endif
