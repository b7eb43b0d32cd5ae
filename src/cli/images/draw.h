/* SPDX-License-Identifier: MIT */
/* draw.h -- what `render` and `plot` share (draw.c): their options beside
 * the fit options, the table, the fits, the files and the printed summary. */
#ifndef BRDFFIT_DRAW_H
#define BRDFFIT_DRAW_H

#include "cli.h"
#include "render_files.h"

typedef struct draw_job {
    cli_options o;         /* TABLE, --model and the options of fit        */
    const char *out;       /* --out DIR                                    */
    const char *fits;      /* --fits FILE, or NULL: fit now                */
    const char *env;       /* --env FILE.exr, or NULL                      */
    int allow_scale_mismatch; /* --allow-scale-mismatch                    */
    rf_settings s;         /* what to draw and how                         */
    char **rest;           /* the arguments left for cli_parse_options     */
    int nrest;
} draw_job;

/* Start a job for argc arguments (defaults; s.render / s.plot set by the caller). */
int draw_init(draw_job *j, int argc);
/* argv[*i] is "--name VALUE" or "--name=VALUE": 1 and *value (stepping *i),
 * 0 when it is another argument, CLI_USAGE (printed) when the value is missing. */
int draw_option(int argc, char **argv, int *i, const char *name, const char **value);
/* --out, --fits, --interp, --allow-scale-mismatch: CLI_OK, CLI_USAGE (printed), or 1 when argv[*i]
 * is none of them. */
int draw_common_option(draw_job *j, int argc, char **argv, int *i);
/* Up to n comma-separated finite numbers of s into v: how many, or -1. */
int draw_numbers(const char *s, double *v, int n);
/* The value of --light, X,Y,Z[:R,G,B] (irradiance 1,1,1 unless given), into
 * l: CLI_OK, or CLI_USAGE with the message printed.  render and export
 * --format mitsuba take it alike. */
int draw_light(const char *v, brdffit_light *l);
/* Keep argv[i] for the fit options. */
void draw_keep(draw_job *j, char *arg);
/* Parse what was kept (TABLE, --model, --scale, ...), then read the table
 * (and the environment), get the fits, write the files into --out and print
 * what was written.  An exit status. */
int draw_run(draw_job *j, const char *command);
void draw_free(draw_job *j);

#endif
