/* SPDX-License-Identifier: MIT */
/* batch_plan.c -- a batch's records (found in the journal, journaled and
 * kept) and what is left to do for a material. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <string.h>

void batch_fill_key(fit_record *r, fr_kind kind, const batch_material *m, const bj_settings *s)
{
    fr_init(r, kind);
    snprintf(r->material, sizeof r->material, "%s", m->name);
    r->id = m->id;
    r->settings = *s;
}

/* The record of this key already journaled (last one), or NULL. */
const fit_record *batch_find(const batch_run *R, fr_kind kind, const batch_material *m,
                             const char *model)
{
    for (int i = R->all.n - 1; i >= 0; i--) {
        const fit_record *r = &R->all.r[i];
        if (r->kind == kind && strcmp(r->model, model) == 0 && strcmp(r->material, m->name) == 0 &&
            bj_identity_equal(&r->id, &m->id) && bj_settings_equal(&r->settings, &R->settings))
            return r;
    }
    return NULL;
}

/* Journal a record and keep it; a failure to write stops the batch. */
int batch_keep(batch_run *R, const fit_record *r)
{
    if (bj_journal_append(&R->journal, r, &R->out_err) != 0) {
        R->out_failed = 1;
        return -1;
    }
    cli_fault_point("record");
    if (bj_records_push(&R->all, r) != 0) {
        R->out_err.status = BRDFFIT_E_NO_MEMORY;
        snprintf(R->out_err.message, sizeof R->out_err.message, "out of memory");
        R->out_failed = 1;
        return -1;
    }
    return 0;
}

/* What a material's renders and plots depend on; "rf2" names the set of files
 * assets.c writes, so a journal whose assets were made by another set redraws them. */
void batch_assets_key(const batch_run *R, char *buf, size_t len)
{
    const batch_options *b = R->b;
    size_t used = (size_t)snprintf(buf, len, "rf2:render=%d,plot=%d:", !b->no_render, !b->no_plot);
    for (int i = 0; i < b->common.nmodels && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? "," : "",
                                 brdffit_model_get(b->common.models[i])->name);
}

static int want_assets(const batch_run *R)
{
    return !R->b->no_render || !R->b->no_plot;
}

static int same_params(const brdffit_params *a, const brdffit_params *b, int np)
{
    for (int c = 0; c < 3; c++)
        if (a->d[c] != b->d[c] || a->s[c] != b->s[c])
            return 0;
    for (int k = 0; k < np; k++)
        if (a->p[k] != b->p[k])
            return 0;
    return 1;
}

/* A fit journaled and not to be done again (fr_retry: by its status code). */
static int done_fit(const fit_record *r)
{
    return r && !fr_retry(r);
}

todo batch_plan(const batch_run *R, const batch_material *m)
{
    todo t;
    memset(&t, 0, sizeof t);
    const cli_options *o = &R->b->common;
    for (int i = 0; i < o->nmodels; i++) {
        const char *mn = brdffit_model_get(o->models[i])->name;
        t.fits[i] = !done_fit(batch_find(R, FR_FIT, m, mn));
        const pub_row *pr = R->have_pub ? pub_find(&R->pub, m->name, o->models[i]) : NULL;
        if (pr) {
            const fit_record *pb = batch_find(R, FR_PUBLISHED, m, mn);
            t.published[i] =
                !pb || !same_params(&pb->params, &pr->params, brdffit_model_get(o->models[i])->nparams);
        }
        t.any |= t.fits[i] | t.published[i];
    }
    if (want_assets(R)) {
        char key[BJ_MSG_MAX];
        batch_assets_key(R, key, sizeof key);
        const fit_record *a = batch_find(R, FR_ASSETS, m, "");
        t.assets = !a || strcmp(a->assets_key, key) != 0;
        t.any |= t.assets;
    }
    return t;
}
