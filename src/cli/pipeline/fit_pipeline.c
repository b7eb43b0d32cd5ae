/* SPDX-License-Identifier: MIT */
/* fit_pipeline.c -- read a table, make its sample set, fit the models, one
 * record each (fit_pipeline.h). */
#define _POSIX_C_SOURCE 200809L
#include "fit_pipeline.h"
#include "cli.h"
#include "prefetch.h"

#include <stdlib.h>
#include <string.h>

void fp_record(fit_record *r, fr_kind kind, const fp_job *job, const fp_source *src)
{
    fr_init(r, kind);
    snprintf(r->material, sizeof r->material, "%s", src->name);
    r->id = src->id;
    r->settings = job->settings;
}

/* The material failed with err: its record. */
static int material_failed(const fp_job *job, const fp_source *src, const fp_hooks *h,
                           const brdffit_error *err)
{
    fit_record *r = malloc(sizeof *r);
    if (!r) {
        cli_error("%s: out of memory", src->name);
        return 1;
    }
    fp_record(r, FR_FAILURE, job, src);
    fr_set_failure(r, err->status, err);
    h->record(h->user, r, NULL);
    free(r);
    return 1;
}

/* The table's albedo into the source, once (the fits' records carry it). */
static void measure_albedo(const fp_job *job, fp_source *src, const brdffit_table *t)
{
    if (src->has_albedo || !t)
        return;
    brdffit_scale scale = job->sample ? job->sample->scale : BRDFFIT_SCALE_STANDARD;
    src->has_albedo = fr_albedo_measure(t, scale, src->albedo) == 0;
}

/* The source's sample set into *s (the table read first unless given). */
static brdffit_status make_samples(const fp_job *job, fp_source *src, brdffit_samples **s,
                                   brdffit_error *err)
{
    *s = src->samples;
    src->samples = NULL;
    measure_albedo(job, src, src->table);
    if (*s)
        return BRDFFIT_OK;
    brdffit_table *read = NULL;
    const brdffit_table *t = src->table;
    brdffit_status st = BRDFFIT_OK;
    if (!t) {
        st = brdffit_table_read(src->path, &read, err);
        t = read;
    }
    if (st == BRDFFIT_OK)
        st = brdffit_samples_create(t, job->sample, s, err);
    if (st == BRDFFIT_OK)
        measure_albedo(job, src, t);
    if (read && job->keep_table && st == BRDFFIT_OK)
        src->table = read;
    else
        brdffit_table_free(read); /* 35 MB; the sample set holds what the fits need */
    if (st != BRDFFIT_OK) {
        *s = NULL;
        err->status = st;
        /* the library's sample messages do not name the file: name it */
        const char *shown = src->shown ? src->shown : src->path ? src->path : src->name;
        if (!src->path || !strstr(err->message, src->path)) {
            char msg[BRDFFIT_MESSAGE_MAX], brief[512];
            snprintf(msg, sizeof msg, "%s: %.1500s", cli_brief(shown, brief, sizeof brief),
                     err->message);
            memcpy(err->message, msg, sizeof msg);
        }
        return st;
    }
    samples_prepare(*s, job->models, job->nmodels);
    return BRDFFIT_OK;
}

int fp_fit_table(const fp_job *job, fp_source *src, const fp_hooks *h)
{
    brdffit_error err;
    memset(&err, 0, sizeof err);
    brdffit_samples *s = NULL;
    if (make_samples(job, src, &s, &err) != BRDFFIT_OK)
        return material_failed(job, src, h, &err);
    brdffit_context *ctx = NULL;
    int c = h->context ? h->context(h->user, &ctx, &err) : -1;
    if (c != 0) {
        brdffit_samples_free(s);
        return c > 0 ? material_failed(job, src, h, &err) : -1;
    }
    if (h->ready)
        h->ready(h->user, s, ctx);
    fit_record *r = malloc(sizeof *r);
    for (int k = 0; r && k < job->nmodels; k++) {
        int go = h->before ? h->before(h->user, k) : 1;
        if (go < 0)
            break;
        if (go == 0)
            continue;
        brdffit_model model = job->models[k];
        brdffit_fit_result res;
        brdffit_fit_result_init(&res);
        memset(&err, 0, sizeof err);
        int note = job->kernel_notes ? kernel_note_begin(stderr, ctx, model) : 0;
        brdffit_status st = brdffit_fit(ctx, s, model, job->fit, &res, &err);
        kernel_note_end(stderr, note, ctx, model);
        if (st != BRDFFIT_OK)
            err.status = st;
        fp_record(r, FR_FIT, job, src);
        fr_set_fit(r, model, st, &err, st == BRDFFIT_OK ? &res : NULL, ctx, s);
        if (st == BRDFFIT_OK)
            fr_set_albedo(r, model, src->has_albedo ? (const double(*)[3])src->albedo : NULL);
        h->record(h->user, r, st == BRDFFIT_OK ? &res : NULL);
    }
    if (!r)
        cli_error("%s: out of memory", src->name);
    free(r);
    if (h->after)
        h->after(h->user, s, ctx);
    brdffit_samples_free(s);
    return 0;
}
