/* SPDX-License-Identifier: MIT */
/* bench_cli.h -- part 3 of `make bench`: `brdffit fit` end to end (bench_cli.c). */
#ifndef BRDFFIT_BENCH_CLI_H
#define BRDFFIT_BENCH_CLI_H

/* Run `$BRDFFIT_CLI fit` over the nmat materials' tables x the models (a
 * --model list, or NULL for all) with --scale flat --json; print its wall
 * time, the time inside and outside the fits, each model's median fit and
 * the projection to the 100 tables.  0, or -1 after printing why. */
int bench_cli_fit(const char *const *materials, int nmat, const char *models);

#endif
