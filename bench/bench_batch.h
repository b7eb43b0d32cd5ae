/* SPDX-License-Identifier: MIT */
/* bench_batch.h -- part 4 of `make bench`: the batch program end to end (bench_batch.c). */
#ifndef BRDFFIT_BENCH_BATCH_H
#define BRDFFIT_BENCH_BATCH_H

/* Run `$BRDFFIT_CLI batch` over the nmat materials (models: a --model list or
 * NULL for all) and print its time and the share outside fitting; 0 or -1. */
int bench_batch(const char *const *materials, int nmat, const char *models);

#endif
