/* SPDX-License-Identifier: MIT */
/* cli_run.h -- `brdffit fit` run as a user runs it, and the fits its --json
 * records report (cli_run.c): what `make bench` part 3 (bench_cli.c) and
 * the whole-database run (bench_database.c) time. */
#ifndef BRDFFIT_CLI_RUN_H
#define BRDFFIT_CLI_RUN_H

#include "brdffit.h"

/* One fit's record (status "ok" or "limit"). */
typedef struct cli_fit {
    char material[64];
    brdffit_model model;
    double seconds; /* the record's seconds less seconds_build */
    double build;   /* seconds_build (0 but for a model's first fit) */
    double error;
} cli_fit;

/* One run of the program. */
typedef struct cli_run {
    cli_fit *fits;
    int n, cap;
    int failed;     /* records that are not a fit (a failed one, or unreadable) */
    double wall;    /* seconds, timed from outside */
    double in_fits; /* the records' seconds, builds included */
    double builds;  /* of which kernel builds */
} cli_run;

/* Into *cmd: "'$BRDFFIT_CLI' fit TABLE... --model MODELS --scale flat
 * --json", the tables from ../shared/tools/merl-table, MODELS "all" when
 * models is NULL; into *alone the same with --no-read-ahead (each fit with
 * the machine to itself).  Both malloc'ed (free them); 0, or -1 after
 * printing why (both NULL). */
int cli_command(const char *const *materials, int nmat, const char *models, char **cmd,
                char **alone);

/* Run cmd (cli_command's, and any options after it) and take its records
 * into *r (cleared first; cli_run_free it).  0 when it exited 0 with at
 * least one fit and no failed record, else -1 after printing why. */
int cli_run_take(const char *cmd, cli_run *r);

void cli_run_free(cli_run *r);

/* The median of v[0..n-1] (sorted in place); 0 when n = 0. */
double cli_median(double *v, int n);

/* Each model's median fit seconds in r into med[model] (0 for a model with
 * no fit); 0, or -1 out of memory (med then all 0). */
int cli_model_medians(const cli_run *r, double med[BRDFFIT_MODEL_COUNT]);

/* The materials of ../shared/tools/merl-table --list into names (up to
 * max); how many, or -1 after printing why. */
int cli_material_list(char (*names)[64], int max);

#endif
