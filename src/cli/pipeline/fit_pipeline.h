/* SPDX-License-Identifier: MIT */
/* fit_pipeline.h -- the one loop that reads a table, makes its sample set and
 * fits models to it, handing each result to its caller as a fit record
 * (fit_record.h): `fit`, `demo`, `batch`, and `render` / `plot` when they fit
 * now (material_fits.c) all go through fp_fit_table (fit_pipeline.c). */
#ifndef BRDFFIT_FIT_PIPELINE_H
#define BRDFFIT_FIT_PIPELINE_H

#include "fit_record.h"

/* The table to fit. */
typedef struct fp_source {
    const char *name;          /* the material's name                              */
    const char *path;          /* its file, or NULL when table is given             */
    const char *shown;         /* how a message names it (NULL: path, else name)    */
    brdffit_table *table;      /* in: a table already in memory (the caller's: never
                                  freed here); out: the table read here, when the
                                  job keeps it (then the caller's to free)          */
    brdffit_samples *samples;  /* in: a sample set made ahead (taken: freed here)   */
    bj_identity id;            /* the records' file, size, hash                     */
    int has_albedo;            /* in/out: albedo holds the table's directional albedo
                                  (fr_albedo_measure), made here from the table when
                                  not given                                        */
    double albedo[FR_ALBEDO_N][3];
} fp_source;

/* What to fit it with. */
typedef struct fp_job {
    const brdffit_model *models;
    int nmodels;
    const brdffit_sample_options *sample;
    const brdffit_fit_options *fit;
    bj_settings settings;      /* the records' settings (bj_settings_make)          */
    int kernel_notes;          /* a line on stderr while kernels compile (kernel_note.h) */
    int keep_table;            /* hand a table read here back in source->table      */
} fp_job;

/* The caller's part.  Every hook but record may be NULL. */
typedef struct fp_hooks {
    void *user;
    /* The context to fit with, asked once the sample set is made: 0, 1 the
     * material fails with err (a failure record follows), -1 stop (no record). */
    int (*context)(void *user, brdffit_context **ctx, brdffit_error *err);
    /* The sample set and the context are ready; the fits follow. */
    void (*ready)(void *user, const brdffit_samples *s, brdffit_context *ctx);
    /* Before the fit of models[k]: 1 fit it, 0 leave it out, -1 stop fitting. */
    int (*before)(void *user, int k);
    /* A record: the material's failure (FR_FAILURE: it could not be read or
     * sampled, or no context), or one fit (FR_FIT; res is its result when it
     * succeeded, else NULL). */
    void (*record)(void *user, const fit_record *r, const brdffit_fit_result *res);
    /* After the fits, the sample set still there. */
    void (*after)(void *user, const brdffit_samples *s, brdffit_context *ctx);
} fp_hooks;

/* Read (unless given) the source's table, make its sample set (unless
 * given), get the context and fit the job's models in order, each record to
 * hooks->record.  0 fitted (fits that failed have their records), 1 the
 * material failed (its record given), -1 stopped by the context hook. */
int fp_fit_table(const fp_job *job, fp_source *src, const fp_hooks *hooks);

/* A record of this kind for the source and job (material, identity,
 * settings), the rest empty (fr_init). */
void fp_record(fit_record *r, fr_kind kind, const fp_job *job, const fp_source *src);

#endif
