/* SPDX-License-Identifier: MIT */
/* bench_database.h -- `make bench-database`: `brdffit fit` over the whole
 * database, its wall time and per-model medians (bench_database.c). */
#ifndef BRDFFIT_BENCH_DATABASE_H
#define BRDFFIT_BENCH_DATABASE_H

/* Run `$BRDFFIT_CLI fit` over every table of ../shared/tools/merl-table
 * --list x the models (a --model list, or NULL for all), --scale flat
 * --json: once reading ahead, then rounds times with --no-read-ahead; print
 * the wall times, each run's per-model medians and He / Cook-Torrance, the
 * same from each table's fastest fit over the rounds, and (baseline not
 * NULL: a stored run's TSV of material, model, Error) how many fits of the
 * runs end above the stored Error by more than 1e-9 relative.  0 when every
 * run completed, or -1 after printing why. */
int bench_database(int rounds, const char *models, const char *baseline);

#endif
