/* SPDX-License-Identifier: MIT */
/* batch_report.c -- the report of a batch's materials, from the records. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <time.h>

static void utc_now(char *buf, size_t len)
{
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* The report of this run's materials, from the records. */
int batch_write_report(batch_run *R, const material_list *L)
{
    const cli_options *o = &R->b->common;
    rp_report rep;
    if (rp_init(&rep, o->models, o->nmodels, &R->settings) != 0)
        return -1;
    utc_now(rep.started, sizeof rep.started);
    snprintf(rep.backend, sizeof rep.backend, "%s",
             R->ctx ? R->backend : "none started in this run (every fit was in the journal)");
    if (R->have_pub) {
        rep.have_published = 1;
        snprintf(rep.published_path, sizeof rep.published_path, "%s", R->pub.path);
        snprintf(rep.scale_note, sizeof rep.scale_note, "%s", R->scale_note);
    }
    const char *dirs[1] = { R->b->out };
    int rc = 0;
    for (int i = 0; i < L->n && rc == 0; i++)
        if (L->m[i].identified || L->m[i].id.size < 0)
            rc = rp_add(&rep, L->m[i].name, &L->m[i].id, &R->all, dirs, 1);
    if (rc == 0 && R->summary) {
        metric_summary *S = R->summary;
        S->nmodels = rep.nmodels;
        S->nmaterials = rep.n;
        S->sort_model = rp_sort_model(&rep);
        for (int k = 0; k < rep.nmodels; k++) {
            S->models[k] = rep.models[k];
            S->median[k] = rp_median(&rep, k, &S->nbest[k], &S->nfit[k]);
        }
    }
    if (rc == 0)
        rc = rp_write(&rep, &R->out, &R->out_err);
    else
        snprintf(R->out_err.message, sizeof R->out_err.message, "out of memory");
    rp_free(&rep);
    return rc;
}
