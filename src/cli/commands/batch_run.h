/* SPDX-License-Identifier: MIT */
/* batch_run.h -- what the files of `brdffit batch` share: its options, its
 * materials, its progress, the run and the render job (cmd_batch.c and the
 * batch_*.c files beside it). */
#ifndef BRDFFIT_BATCH_RUN_H
#define BRDFFIT_BATCH_RUN_H

#include "batch.h"
#include "cli.h"
#include "fit_pipeline.h"
#include "prefetch.h"

#include <pthread.h>

/* The options of batch (batch_options.c). */
typedef struct batch_options {
    cli_options common;      /* --model --scale --cutoff --starts --backend --device, INPUT... */
    const char *out;
    const char *published;
    int shard_k, shard_n;    /* 1-based; 1/1 unsharded */
    int quiet, no_render, no_plot, demo;
    int allow_scale_mismatch; /* --allow-scale-mismatch: a --published file of another scale */
} batch_options;

/* A material of the inputs (batch_inputs.c). */
typedef struct batch_material {
    char name[BJ_NAME_MAX];
    char path[BJ_PATH_MAX];   /* as given ("" for the embedded material) */
    int embedded;
    bj_identity id;
    int identified;
} batch_material;

typedef struct material_list {
    batch_material *m;
    int n, cap;
} material_list;

/* The progress shown (batch_progress.c). */
typedef struct progress {
    int live;            /* stderr is a terminal */
    int quiet;
    double t0;
    int total_fits, done_fits, fitted_now;
    double fit_seconds;  /* of the fits of this run (for the ETA) */
} progress;

/* A batch in progress. */
typedef struct batch_run {
    const batch_options *b;
    bj_settings settings;
    out_dir out;             /* --out, open; its lock held for the run        */
    od_lock lock;
    bj_journal journal;
    bj_records all;          /* the journal's records, then this run's       */
    pub_table pub;
    int have_pub;
    char scale_note[BRDFFIT_MESSAGE_MAX]; /* the --published file's scale is not --scale's, or "" */
    brdffit_context *ctx;
    progress P;
    int failures;            /* materials and fits that failed */
    int out_failed;          /* --out could not be written: stop */
    brdffit_error out_err;
    char backend[256];
    double seconds_fitting;  /* inside brdffit_fit and brdffit_error_of */
    double seconds_render;   /* of the render jobs (in their thread)   */
    struct render_job *job;  /* the renders and plots in flight        */
    table_prefetch *pre;     /* the next material's table, read meanwhile */
    fp_job fit_job;          /* the models and settings of every material's fits */
    struct metric_summary *summary; /* --metric all: this metric's model table, or NULL */
} batch_run;

/* --metric all: one metric's model table, for DIR/index.html (cmd_batch.c). */
typedef struct metric_summary {
    int nmodels, nmaterials;
    brdffit_model models[BJ_MAX_MODELS];
    double median[BJ_MAX_MODELS];  /* NAN: no fit */
    int nbest[BJ_MAX_MODELS], nfit[BJ_MAX_MODELS];
    int sort_model;                /* the slot of the lowest median, or -1 */
} metric_summary;

/* What is left to do for a material. */
typedef struct todo {
    int fits[BJ_MAX_MODELS];   /* by slot of the run's models */
    int published[BJ_MAX_MODELS];
    int assets;
    int any;
} todo;

/* The renders and plots of a material run in a thread of their own while the
 * next material is fitted (a fit keeps about one core busy; the machine has
 * more).  One job at a time; the main thread journals its record when it is
 * collected, so the record still comes after the files. */
typedef struct render_job {
    pthread_t thread;
    int running;                   /* a job to collect               */
    int threaded;                  /* in its own thread (to join)    */
    out_dir dir;                   /* the material's, inside --out  */
    brdffit_table *table;          /* owned: freed when collected   */
    brdffit_sample_options sample;
    fit_record *fits;               /* copies (the records array may move) */
    int nfits, render, plot;
    fit_record rec;                 /* the FR_ASSETS record to journal */
    int rc;
    brdffit_error err;
    double seconds;
} render_job;

/* ---- batch_options.c ---- */

/* The batch's own options are taken out; the rest go to cli_parse_options. */
int batch_parse_options(int argc, char **argv, batch_options *b);

/* ---- batch_inputs.c ---- */

/* The materials of the inputs, sorted by name, without repeats; then this shard's share. */
int batch_collect(const batch_options *b, material_list *L);

/* ---- batch_signals.c ---- */

/* The signal that stops the batch (0: none yet). */
extern _Atomic int batch_stop_signal;
void batch_install_signals(void);

/* ---- batch_progress.c ---- */

double batch_now(void);
void batch_progress_live(progress *P, int i, int n, const char *material, const char *model);
void batch_progress_material(progress *P, int i, int n, const char *material, const char *what);

/* ---- batch_plan.c ---- */

void batch_fill_key(fit_record *r, fr_kind kind, const batch_material *m, const bj_settings *s);
/* The record of this key already journaled (last one), or NULL. */
const fit_record *batch_find(const batch_run *R, fr_kind kind, const batch_material *m,
                             const char *model);
/* Journal a record and keep it; a failure to write stops the batch. */
int batch_keep(batch_run *R, const fit_record *r);
/* What a material's renders and plots depend on. */
void batch_assets_key(const batch_run *R, char *buf, size_t len);
todo batch_plan(const batch_run *R, const batch_material *m);

/* ---- batch_render.c ---- */

/* Wait for the job in flight (if any), journal its record or report its failure. */
void batch_render_collect(batch_run *R, render_job *J);
/* Start the renders and plots of material m (its table t is handed over). */
void batch_render_start(batch_run *R, render_job *J, const batch_material *m, brdffit_table *t);

/* ---- batch_report.c ---- */

/* The report of this run's materials, from the records. */
int batch_write_report(batch_run *R, const material_list *L);

#endif
