/* SPDX-License-Identifier: MIT */
/* bench_summary.h -- the figures for README that `make bench` prints last
 * (bench_summary.c). */
#ifndef BRDFFIT_BENCH_SUMMARY_H
#define BRDFFIT_BENCH_SUMMARY_H

#include "brdffit.h"

/* Per model on alum-bronze (0: not measured in this run). */
typedef struct bench_summary {
    double fit_seconds[BRDFFIT_MODEL_COUNT]; /* part 2: one complete fit, the fastest */
    int passes[BRDFFIT_MODEL_COUNT];         /* part 2: that fit's data passes */
    double full_per_read[BRDFFIT_MODEL_COUNT]; /* part 1: full pass / streaming read, typical start */
    double he_per_ct;                        /* part 2: He's fit / Cook-Torrance's, alternated */
} bench_summary;

/* "figures for README": a line per model measured, then He / Cook-Torrance;
 * nothing when no fit was measured. */
void bench_summary_print(const bench_summary *s);

#endif
