/* SPDX-License-Identifier: MIT */
/* prefetch.c -- a material's identity, table and sample set read in a
 * thread while the material before it is fitted (prefetch.h). */
#define _POSIX_C_SOURCE 200809L
#include "prefetch.h"

#include <string.h>

static void *prefetch_main(void *arg)
{
    table_prefetch *P = arg;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    if (P->identify && !(P->identified = bj_identify(P->path, &P->id, &err) == 0))
        return NULL;
    if (brdffit_table_read(P->path, &P->table, &err) != BRDFFIT_OK) {
        P->table = NULL;
        return NULL;
    }
    if (brdffit_samples_create(P->table, &P->sample, &P->samples, &err) != BRDFFIT_OK)
        P->samples = NULL;
    else
        samples_prepare(P->samples, P->models, P->nmodels);
    return NULL;
}

void samples_prepare(const brdffit_samples *s, const brdffit_model *models, int nmodels)
{
    brdffit_error err;
    memset(&err, 0, sizeof err);
    for (int k = 0; k < nmodels; k++)
        (void)brdffit_samples_prepare(s, models[k], &err);
}

void prefetch_drop(table_prefetch *P)
{
    if (P->running)
        pthread_join(P->thread, NULL);
    brdffit_samples_free(P->samples);
    brdffit_table_free(P->table);
    memset(P, 0, sizeof *P);
}

void prefetch_start(table_prefetch *P, const char *path, const brdffit_sample_options *sample,
                    int identify, const brdffit_model *models, int nmodels)
{
    prefetch_drop(P);
    if (strlen(path) >= sizeof P->path)
        return;
    memcpy(P->path, path, strlen(path) + 1);
    P->sample = *sample;
    P->identify = identify;
    P->nmodels = nmodels < BRDFFIT_MODEL_COUNT ? nmodels : BRDFFIT_MODEL_COUNT;
    memcpy(P->models, models, (size_t)P->nmodels * sizeof *models);
    P->running = pthread_create(&P->thread, NULL, prefetch_main, P) == 0;
    if (!P->running)
        P->path[0] = '\0';
}

int prefetch_wait(table_prefetch *P, const char *path)
{
    if (!P->path[0] || strcmp(P->path, path) != 0)
        return 0;
    if (P->running)
        pthread_join(P->thread, NULL);
    P->running = 0;
    return 1;
}
