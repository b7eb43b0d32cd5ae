/* SPDX-License-Identifier: MIT */
/* batch.h -- what the files of `brdffit batch`, `report` and `score` share.
 *
 *   journal.c      the journal DIR/journal.jsonl: settings, material identity,
 *                  append (fsync'd) and load (a torn last line ignored) of the
 *                  records of fit_record.h
 *   jsonread.c     a small reader for the JSON objects the journal holds
 *   published.c    the published-fits TSV (material, model, d, s, p0..p2)
 *   outdir.c       the output directory, its lock, names checked (outdir.h);
 *                  outfile.c files written whole (temporary + rename)
 *   html_report.c  the report's pages: the pieces they share (html_report.h);
 *                  html_material.c per material params.tsv, params.json,
 *                  index.html; html_index.c DIR/index.html, DIR/fits.tsv and
 *                  the headline figure (SVG)
 *   cmd_batch.c    `brdffit batch`: fits, resume; beside it (batch_run.h)
 *                  batch_options.c, batch_inputs.c (inputs, shards),
 *                  batch_signals.c, batch_progress.c, batch_plan.c (what is
 *                  left to do), batch_render.c, batch_report.c
 *   prefetch.c     the next material's identity, table and sample set, read in a
 *                  thread while the current one is fitted (prefetch.h; `fit` too)
 *   cmd_report.c   `brdffit report DIR...`: shard journals merged into one report
 *   cmd_score.c    `brdffit score`: the Error of given parameters
 *   report_data.c  the materials of a report chosen from the records; medians, best
 *   demo_material.c, assets.c, fault.c  (see cli.h, below)
 */
#ifndef BRDFFIT_BATCH_H
#define BRDFFIT_BATCH_H

#include "brdffit.h"
#include "fit_record.h"
#include "outdir.h"

#include <stdio.h>

#define BJ_MAX_MODELS 32   /* model ids below this (the registry has fewer) */

void bj_settings_make(bj_settings *s, const brdffit_sample_options *so, const brdffit_fit_options *fo);
int bj_settings_equal(const bj_settings *a, const bj_settings *b);
/* The differences of b from a, in words ("scale flat (this run: standard)"), into buf. */
const char *bj_settings_diff(const bj_settings *journal, const bj_settings *run, char *buf,
                             size_t len);

/* Identify the file at path (reads it whole).  0, or -1 with err filled. */
int bj_identify(const char *path, bj_identity *id, brdffit_error *err);
/* The identity of bytes in memory (the embedded material). */
void bj_identify_bytes(const char *label, const void *data, size_t len, bj_identity *id);
int bj_identity_equal(const bj_identity *a, const bj_identity *b);

/* A growing array of records. */
typedef struct bj_records {
    fit_record *r;
    int n, cap;
} bj_records;

int bj_records_push(bj_records *rs, const fit_record *r);
void bj_records_free(bj_records *rs);

/* The journal of an output directory, open for appending. */
typedef struct bj_journal {
    int fd;
    char path[BJ_PATH_MAX];
} bj_journal;

/* Open (create) journal.jsonl in dir for appending (a link there is refused).
 * A torn last line (a kill in the middle of a write) is cut off first; *torn
 * says so.  0 or -1 (err). */
int bj_journal_open(bj_journal *j, const out_dir *dir, int *torn, brdffit_error *err);
/* Append one record as one line, then fsync: 0, or -1 with err filled. */
int bj_journal_append(bj_journal *j, const fit_record *r, brdffit_error *err);
void bj_journal_close(bj_journal *j);

/* Read the records of a journal file into rs (appended).  A missing file is
 * no record; a path that is not a regular file is refused (err).  A line
 * that is not a record this program writes (it does not parse, or fr_check
 * refuses its values) is skipped, said on stderr with its line number and
 * why ("PATH: line N: WHY: ignored"; the first BJ_BAD_SHOWN of them, then
 * how many more), and counted in *bad; a torn last line sets *torn.  0, or -1
 * when the file cannot be read (err). */
#define BJ_BAD_SHOWN 10
int bj_journal_load(const char *path, bj_records *rs, int *bad, int *torn, brdffit_error *err);

/* ---- jsonread.c ---- */

typedef enum jr_type { JR_NULL = 0, JR_BOOL, JR_NUMBER, JR_STRING, JR_ARRAY, JR_OBJECT } jr_type;

#define JR_MAX_MEMBERS 64
#define JR_MAX_ARRAY 64

/* A flat JSON object: members whose values are null, true/false, numbers,
 * strings, arrays of up to JR_MAX_ARRAY numbers, or a flat object (settings). */
typedef struct jr_member {
    char key[32];
    jr_type type;
    double num;
    double arr[JR_MAX_ARRAY];
    int narr;
    char *str;            /* JR_STRING: decoded, NUL-terminated (owned);
                             JR_ARRAY: its string elements, one a line, or NULL */
    int sub;              /* JR_OBJECT: index of its first member; nsub members follow */
    int nsub;
} jr_member;

typedef struct jr_object {
    jr_member m[JR_MAX_MEMBERS];
    int n;
} jr_object;

/* Parse s (one object, nothing but white space after it): 0 or -1. */
int jr_parse(const char *s, jr_object *o);
void jr_free(jr_object *o);
/* The member named key among the top-level members (or inside obj, a member index), or NULL. */
const jr_member *jr_get(const jr_object *o, const char *key);
const jr_member *jr_get_in(const jr_object *o, const jr_member *obj, const char *key);

/* ---- published.c ---- */

typedef struct pub_row {
    char material[BJ_NAME_MAX];
    brdffit_model model;
    brdffit_params params;
    int line;          /* its line in the file */
} pub_row;

typedef struct pub_table {
    pub_row *rows;
    int n;
    char path[BJ_PATH_MAX];
    int scale_line;       /* the line of its "# scale: NAME" comment, or 0 */
    brdffit_scale scale;  /* the scale it states (when scale_line > 0)    */
} pub_table;

/* Read a TSV of the ngan2005-fits.tsv format: header line "material model
 * d_r ... p2", '#' comments, an empty p is 0 (a p beyond the model's count
 * must be empty); a comment "# scale: standard|flat" states the scale of the
 * tables the parameters were fitted to.  0, or -1 with err (names the line):
 * a malformed row, a second row of the same material and model (both lines
 * named), an unknown or second, different scale, a file without a header or
 * empty. */
int pub_read(const char *path, pub_table *t, brdffit_error *err);
/* 1 when t states a scale other than scale (why, naming the file and both
 * scales, into msg), else 0. */
int pub_scale_mismatch(const pub_table *t, brdffit_scale scale, char *msg, size_t len);
/* What to do about a mismatch: the --scale to pass, or the override flag. */
const char *pub_scale_advice(const pub_table *t);
/* What a report and the program say when published fits of another scale
 * are compared anyway. */
#define PUB_SCALE_NOTE "the published Errors and ratios are computed on data the published " \
                       "parameters were not fitted to (--allow-scale-mismatch)"

void pub_free(pub_table *t);
/* The row of material and model, or NULL. */
const pub_row *pub_find(const pub_table *t, const char *material, brdffit_model model);

/* ---- fault.c: fault injection for the tests (BRDFFIT_FAULT=POINT:N) ----
 * Only in the test build of the program (build/brdffit-faults, compiled
 * -DBRDFFIT_FAULTS); in the program that is installed the hooks are no-ops
 * and the environment is not read. */

#ifdef BRDFFIT_FAULTS
/* 1 when this pass of point is the one BRDFFIT_FAULT names. */
int cli_fault_hit(const char *point);
/* SIGKILL the program when this pass of point is the one BRDFFIT_FAULT names. */
void cli_fault_point(const char *point);
#else
static inline int cli_fault_hit(const char *point)
{
    (void)point;
    return 0;
}
static inline void cli_fault_point(const char *point)
{
    (void)point;
}
#endif

/* ---- assets.c ---- */

/* Write the renders and plots of a material (its table, the fits that
 * succeeded) into dir (open: outdir.h); list the files written as lines
 * "kind<TAB>file<TAB>caption" (kind: image, plot, data) into list.
 * 0, or -1 with err (BRDFFIT_E_FILE_WRITE when dir could not be written). */
int batch_assets(const out_dir *dir, const char *material, const brdffit_table *table,
                 const brdffit_sample_options *sample, const fit_record *const *fits, int nfits,
                 int render, int plot, char *list, size_t len, brdffit_error *err);

/* ---- report_data.c ---- */

/* The report's materials, chosen from journal records. */

/* ---- html_report.c ---- */

/* One material of the report: its records, selected for the report's settings. */
typedef struct rp_material {
    char name[BJ_NAME_MAX];
    bj_identity id;
    const fit_record *failure;       /* the material could not be read: why    */
    const fit_record *fit[BJ_MAX_MODELS];       /* by slot of rp_report.models, or NULL */
    const fit_record *published[BJ_MAX_MODELS]; /* by slot, or NULL                     */
    const fit_record *assets;
    char asset_dir[BJ_PATH_MAX];    /* where its renders and plots are (report: a shard) */
} rp_material;

typedef struct rp_report {
    rp_material *m;
    int n;
    brdffit_model models[BJ_MAX_MODELS];
    int nmodels;
    bj_settings settings;
    char backend[256];              /* a description of the backend            */
    char published_path[BJ_PATH_MAX]; /* --published, or ""                    */
    int have_published;
    char started[64];               /* date of the report (UTC ISO 8601)       */
    const char *extra_note;         /* a line for the settings table, or NULL  */
    char scale_note[BRDFFIT_MESSAGE_MAX + 256]; /* the published fits are of another
                                       scale (--allow-scale-mismatch): on every page; or "" */
} rp_report;

/* An empty report of these models and settings: 0 or -1 (no memory). */
int rp_init(rp_report *rep, const brdffit_model *models, int nmodels, const bj_settings *s);
/* Add the material name: its records among rs with these settings and the
 * identity id (NULL: that of the material's last record).  A record's assets
 * are in origin_dirs[record origin]/name.  0 or -1 (no memory). */
int rp_add(rp_report *rep, const char *name, const bj_identity *id, const bj_records *rs,
           const char *const *origin_dirs, int ndirs);
void rp_free(rp_report *rep);

/* Write every page of the report into dir (open): DIR/<material>/params.tsv,
 * params.json, index.html; DIR/index.html, DIR/fits.tsv, DIR/headline.svg.
 * 0, or -1 with err (the path that could not be written and why). */
int rp_write(const rp_report *rep, const out_dir *dir, brdffit_error *err);

/* The slot of material i's best fit (lowest Error), or -1. */
int rp_best(const rp_report *rep, int i);
/* The model sorted by (for the headline figure): the one with the lowest
 * median Error; -1 when no model has an Error. */
int rp_sort_model(const rp_report *rep);
/* Median Error of model slot k over the materials it was fitted to, and how
 * often it is the best; NAN / 0 when none. */
double rp_median(const rp_report *rep, int k, int *nbest, int *nfitted);
/* Median of Error / published Error of model slot k over the materials with
 * both (n: how many); NAN when none. */
double rp_median_ratio(const rp_report *rep, int k, int *n);

#endif
