/* SPDX-License-Identifier: MIT */
/* prefetch.h -- the batch (and `brdffit fit`) reads the next material's
 * table while the current one is fitted: its identity (path, size, hash; the
 * batch's journal needs it, fit does not ask for it), the table and its
 * sample set, in a thread of their own.  Each step either succeeds or leaves
 * its result empty; the caller then does that step itself, in order, so
 * that a failure is reported exactly as without the prefetch.  The sample
 * set is prepared for the models to be fitted (brdffit_samples_prepare: its
 * screening subsets), so that no fit spends its time making them.  At most
 * one prefetch is in flight; it holds one more table and sample set in
 * memory (~160 MB for a MERL table, the subsets of all models included). */
#ifndef BRDFFIT_PREFETCH_H
#define BRDFFIT_PREFETCH_H

#include "batch.h"

#include <pthread.h>

typedef struct table_prefetch {
    pthread_t thread;
    int running;                  /* a thread to join                        */
    char path[BJ_PATH_MAX];       /* the file ("" when none was started)     */
    brdffit_sample_options sample;
    int identify;                 /* 1: identify the file first              */
    brdffit_model models[BRDFFIT_MODEL_COUNT]; /* to prepare the sample set for */
    int nmodels;
    int identified;               /* id holds the file's identity            */
    bj_identity id;
    brdffit_table *table;         /* NULL when not read                      */
    brdffit_samples *samples;     /* NULL when not made                      */
} table_prefetch;

/* Start reading path (a table file), after its identity when identify is
 * set, and making its sample set with these options, prepared for the
 * nmodels models (samples_prepare); waits for and drops any prefetch still
 * held.  Without a thread to be had it does nothing (the caller then reads
 * the table itself). */
void prefetch_start(table_prefetch *P, const char *path, const brdffit_sample_options *sample,
                    int identify, const brdffit_model *models, int nmodels);

/* brdffit_samples_prepare of s for each of the models.  A failure is left
 * to the fits: each makes what it needs itself and reports what fails. */
void samples_prepare(const brdffit_samples *s, const brdffit_model *models, int nmodels);

/* Wait for the prefetch of path, if it is the one held; 1 then (its results
 * are P's to take: set what is taken to NULL), else 0 (nothing held for it). */
int prefetch_wait(table_prefetch *P, const char *path);

/* Wait for any prefetch and free what it holds. */
void prefetch_drop(table_prefetch *P);

#endif /* BRDFFIT_PREFETCH_H */
