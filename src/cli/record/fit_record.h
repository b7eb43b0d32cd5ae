/* SPDX-License-Identifier: MIT */
/* fit_record.h -- the fit record: what one fit of one model to one material
 * gave (or why it failed), and the one place its fields are named.  Every
 * file the program writes about fits uses it: `fit --json` (one record a
 * line), the batch journal DIR/journal.jsonl, the report's params.json,
 * params.tsv and fits.tsv.  docs/fit-record.md describes every field.
 *
 *   fit_record.c       filling a record, the retry decision of a resumed
 *                      batch, the names of the at_bound bits
 *   fit_record_json.c  the JSON writer and reader
 *   fit_record_check.c the values of a record read back judged
 *   fit_record_tsv.c   the TSV writer
 */
#ifndef BRDFFIT_FIT_RECORD_H
#define BRDFFIT_FIT_RECORD_H

#include "brdffit.h"

#include <stdio.h>

#define BJ_PATH_MAX 4096
#define BJ_NAME_MAX 256
#define BJ_MSG_MAX 512
#define BJ_MODEL_NAME_MAX 32
#define BJ_ASSETS_MAX 4096

/* The settings a fit depends on besides the material and the model.  Records
 * made with other settings are not reused. */
typedef struct bj_settings {
    char version[32];      /* brdffit_version()                       */
    char scale[16];        /* "standard" | "flat"                     */
    double cutoff_deg;
    int starts;            /* --starts; 0 = each model's own default  */
    char metric[16];       /* --metric: the metric the fits minimise  */
} bj_settings;

/* A material's identity: its path (made absolute), size and a hash of its bytes
 * (64-bit FNV-1a over 8-byte words, hex).  The embedded demo material has path
 * "(embedded)".  size -1 and hash "": not known (a file that could not be
 * read; `fit`, which does not hash its files). */
typedef struct bj_identity {
    char path[BJ_PATH_MAX];
    long long size;
    char hash[20];
} bj_identity;

typedef enum fr_kind {
    FR_FIT = 0,         /* a model fitted (or its fit failed: status not OK)     */
    FR_FAILURE = 1,     /* the material could not be read, sampled or fitted at all */
    FR_PUBLISHED = 2,   /* the Error of a material's published parameters       */
    FR_ASSETS = 3       /* the renders and plots of a material are written      */
} fr_kind;

/* The energy fields (fit_record_albedo.c): the directional albedo on the
 * grid theta_o = 0, 5, ..., 85 deg, per channel. */
#define FR_ALBEDO_N 18
#define FR_ALBEDO_STEP_DEG 5.0
/* A fit "exceeds 1" when its albedo_max is above this (1 and the
 * quadrature's tolerance), and "departs" from the measured table when its
 * albedo_departure is above FR_ALBEDO_DEPARTS; the departure's denominator
 * is at least FR_ALBEDO_FLOOR (a nearly black table). */
#define FR_ALBEDO_MAX_OK 1.0001
#define FR_ALBEDO_DEPARTS 0.10
#define FR_ALBEDO_FLOOR 0.01

typedef struct fit_record {
    fr_kind kind;
    char material[BJ_NAME_MAX];
    bj_identity id;                 /* "file", "size", "hash"               */
    bj_settings settings;
    char model[BJ_MODEL_NAME_MAX];  /* FR_FIT, FR_PUBLISHED; else ""        */
    brdffit_status status;          /* BRDFFIT_OK or why it failed          */
    char message[BRDFFIT_MESSAGE_MAX]; /* why it failed ("" when it did not) */
    int has_params;                 /* params hold parameters (a fit that
                                       succeeded, published parameters)    */
    brdffit_params params;          /* d, s, p (nparams), lambda_um (He)    */
    int nparams;
    double error;                   /* NAN: none; under settings.metric     */
    double errors[BRDFFIT_METRIC_COUNT]; /* the Error under each brdffit_metric
                                       (NAN: none, a record without them)   */
    int has_counts;                 /* iterations .. cminpack_info, flags, at_bound
                                       are a fit's (FR_FIT that succeeded)  */
    int iterations, passes, cminpack_info;
    unsigned flags;                 /* brdffit_fit_flag bits                */
    unsigned at_bound;              /* brdffit_at_bound bits (the library's) */
    double seconds, seconds_solver, seconds_passes, seconds_build; /* NAN: none */
    long long samples;              /* -1: not known                        */
    int has_albedo;                 /* albedo holds the fitted model's      */
    double albedo[FR_ALBEDO_N][3];  /* a_c(theta_o) of the fitted model     */
    double albedo_max, albedo_max_theta_o; /* max over theta_o and channels, and where; NAN: none */
    int has_albedo_measured;        /* albedo_measured holds the table's    */
    double albedo_measured[FR_ALBEDO_N][3];
    double albedo_departure, albedo_departure_theta_o; /* max over theta_o <= the cutoff of
                                       |Y_fit - Y_table| / max(Y_table, FR_ALBEDO_FLOOR),
                                       Y the luminance, and where; NAN: none */
    double seconds_albedo;          /* what computing albedo took; NAN: none */
    char backend[16];               /* "opencl" | "host" | ""               */
    char backend_description[256];
    char assets_key[BJ_MSG_MAX];    /* FR_ASSETS: what was drawn ("rf2:render=1,plot=1:ward,he") */
    char assets[BJ_ASSETS_MAX];     /* FR_ASSETS: lines "kind<TAB>file<TAB>caption"   */
    int origin;                     /* not written: which journal it came from        */
    int line;                       /* not written: its line in that journal (1..)    */
} fit_record;

/* An empty record of this kind: numbers NAN, counts unknown, status OK. */
void fr_init(fit_record *r, fr_kind kind);
/* The result of a fit (brdffit_fit's status, err and, when it succeeded, res)
 * into r (kind, material, identity and settings are left as they are). */
void fr_set_fit(fit_record *r, brdffit_model model, brdffit_status st, const brdffit_error *err,
                const brdffit_fit_result *res, const brdffit_context *ctx,
                const brdffit_samples *s);
/* A failure: status st and err's message (or the status's text). */
void fr_set_failure(fit_record *r, brdffit_status st, const brdffit_error *err);

/* The energy fields (fit_record_albedo.c).  The grid's angles; the
 * luminance 0.2126 R + 0.7152 G + 0.0722 B; the table's albedo on the grid
 * (trilinear lookups; 0, or -1 when the library refuses); the fitted
 * model's albedo (r's model and params; a fit that failed gets none), its
 * maximum and its departure from measured (NULL: not known); whether a
 * record's fit exceeds 1 / departs from the table; their JSON members
 * (written after the others, read from o: 0, or -1 when malformed) and TSV
 * columns (after the others). */
void fr_albedo_angles(double theta_o_deg[FR_ALBEDO_N]);
double fr_luminance(const double rgb[3]);
int fr_albedo_measure(const brdffit_table *table, brdffit_scale scale,
                      double out[FR_ALBEDO_N][3]);
void fr_set_albedo(fit_record *r, brdffit_model model, const double measured[FR_ALBEDO_N][3]);
int fr_albedo_exceeds(const fit_record *r);
int fr_albedo_departs(const fit_record *r);
void fr_albedo_write_json(FILE *f, const fit_record *r);
struct jr_object;
int fr_albedo_read_json(const struct jr_object *o, fit_record *r);
void fr_albedo_tsv_header(FILE *f);
void fr_albedo_tsv_row(FILE *f, const fit_record *r);

/* The "status" text of a record: "ok", "limit" (fitted, but the LM run kept
 * stopped on its evaluation limit), or brdffit_strerror(status). */
const char *fr_status_text(const fit_record *r);
/* 1 when the record holds a result (status BRDFFIT_OK). */
int fr_ok(const fit_record *r);

/* Resume: 1 when a record journaled by an earlier run is to be done again,
 * decided by its kind and status code only (never its message): a fit that
 * failed for a reason outside the data (no memory, no device, OpenCL, a
 * kernel build, the kernel cache) is fitted again; a fit that succeeded or
 * failed on the data, and a material that could not be read (its identity
 * decides: a changed file is a new material), are kept. */
int fr_retry(const fit_record *r);

/* The names of the at_bound bits of a model's record: lobe parameters by
 * name, then d_r, d_g, d_b, s_r, s_g, s_b; each passed to put(name, user).
 * with_linear 0: the lobe parameters only. */
void fr_at_bound_names(brdffit_model model, unsigned at_bound, int with_linear,
                       void (*put)(const char *name, void *user), void *user);
/* The same joined by sep into buf. */
const char *fr_at_bound_text(brdffit_model model, unsigned at_bound, const char *sep, char *buf,
                             size_t len);

/* One record as a JSON object (no newline) onto f: every field, null where
 * it does not apply (docs/fit-record.md). */
void fr_write_json(FILE *f, const fit_record *r);

/* What the reader requires. */
typedef enum fr_need {
    FR_NEED_KEY = 1,    /* the journal: kind, material, file identity, settings */
    FR_NEED_FIT = 0     /* a file of fits (`fit --json` output): material, model, status */
} fr_need;

/* Parse one JSON object into r: 0, or -1 when it is not a record.  Reads the
 * records this program writes and those earlier versions wrote (the journal's
 * "ok", "status" text, "on_bound", "file" {path, size, hash}; fit --json's
 * "error_message", "metric"). */
int fr_read_json(const char *line, fit_record *r, fr_need need);

/* A record's values judged as this program writes them (fit_record_check.c):
 * NULL, or why it is not one of its records (why may hold the text): the
 * material a file name, the file's size and 16-hex-digit hash (a failure to
 * read it may have neither), known settings, one of this version's models
 * by its name, a fit that succeeded with d, s and p as the model takes them
 * (brdffit_params_check: exactly its count of p, all finite and in bounds)
 * and a finite Error >= 0, a failure with its message and no Error. */
const char *fr_check(const fit_record *r, char *why, size_t len);

/* The TSV of fits (params.tsv, fits.tsv): the header line, then one row per
 * record; pub (may be NULL) is the published record of the same material
 * and model (columns published_error, ratio). */
void fr_write_tsv_header(FILE *f);
void fr_write_tsv_row(FILE *f, const fit_record *r, const fit_record *pub);
/* A text field of the TSV, escaped so that it reads back exactly: "\\" for a
 * backslash, "\t", "\n", "\r" for tab, line feed, carriage return; "-" for
 * an empty (or no) text and "\-" for the text "-". */
void fr_write_tsv_text(FILE *f, const char *s);
/* error / published error, or NAN. */
double fr_ratio(const fit_record *fit, const fit_record *pub);

#endif
