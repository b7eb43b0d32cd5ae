/* SPDX-License-Identifier: MIT */
/* report_data.c -- the materials of a report chosen from journal records: per
 * material the records of one identity and the report's settings, the last of
 * each kind and model; and the summary figures (median Error, how often best). */
#include "batch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int rp_init(rp_report *rep, const brdffit_model *models, int nmodels, const bj_settings *s)
{
    memset(rep, 0, sizeof *rep);
    if (nmodels > BJ_MAX_MODELS)
        return -1;
    memcpy(rep->models, models, (size_t)nmodels * sizeof *models);
    rep->nmodels = nmodels;
    rep->settings = *s;
    return 0;
}

void rp_free(rp_report *rep)
{
    free(rep->m);
    rep->m = NULL;
    rep->n = 0;
}

static int slot_of(const rp_report *rep, const char *model)
{
    for (int k = 0; k < rep->nmodels; k++)
        if (strcmp(brdffit_model_get(rep->models[k])->name, model) == 0)
            return k;
    return -1;
}

int rp_add(rp_report *rep, const char *name, const bj_identity *id, const bj_records *rs,
           const char *const *origin_dirs, int ndirs)
{
    const bj_identity *use = id;
    for (int i = rs->n - 1; !use && i >= 0; i--)
        if (strcmp(rs->r[i].material, name) == 0 &&
            bj_settings_equal(&rs->r[i].settings, &rep->settings))
            use = &rs->r[i].id;
    if (!use)
        return 0; /* nothing of this material with these settings */
    rp_material *g = realloc(rep->m, (size_t)(rep->n + 1) * sizeof *g);
    if (!g)
        return -1;
    rep->m = g;
    rp_material *m = &rep->m[rep->n++];
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    m->id = *use;
    for (int i = 0; i < rs->n; i++) {
        const fit_record *r = &rs->r[i];
        if (strcmp(r->material, name) != 0 || !bj_identity_equal(&r->id, &m->id) ||
            !bj_settings_equal(&r->settings, &rep->settings))
            continue;
        int k = slot_of(rep, r->model);
        switch (r->kind) {
        case FR_FAILURE: m->failure = r; break;
        case FR_FIT:
            if (k >= 0) {
                m->fit[k] = r;
                m->failure = NULL;
            }
            break;
        case FR_PUBLISHED:
            if (k >= 0)
                m->published[k] = r;
            break;
        case FR_ASSETS:
            m->assets = r;
            if (r->origin >= 0 && r->origin < ndirs)
                snprintf(m->asset_dir, sizeof m->asset_dir, "%s/%s", origin_dirs[r->origin], name);
            break;
        }
    }
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The slot of the material's best fit, or -1. */
static int best_slot(const rp_report *rep, const rp_material *m)
{
    int best = -1;
    for (int k = 0; k < rep->nmodels; k++) {
        const fit_record *f = m->fit[k];
        if (f && fr_ok(f) && isfinite(f->error) && (best < 0 || f->error < m->fit[best]->error))
            best = k;
    }
    return best;
}

int rp_best(const rp_report *rep, int i)
{
    return best_slot(rep, &rep->m[i]);
}

/* The median of e[0..n) (sorted in place), NAN when n is 0. */
static double median_of(double *e, int n)
{
    if (n <= 0)
        return NAN;
    qsort(e, (size_t)n, sizeof *e, cmp_double);
    return n % 2 ? e[n / 2] : 0.5 * (e[n / 2 - 1] + e[n / 2]);
}

double rp_median(const rp_report *rep, int k, int *nbest, int *nfitted)
{
    double *e = malloc((size_t)(rep->n > 0 ? rep->n : 1) * sizeof *e);
    int n = 0, best = 0;
    for (int i = 0; i < rep->n; i++) {
        const fit_record *f = rep->m[i].fit[k];
        if (f && fr_ok(f) && isfinite(f->error) && e)
            e[n++] = f->error;
        if (best_slot(rep, &rep->m[i]) == k)
            best++;
    }
    double med = median_of(e, n);
    free(e);
    if (nbest)
        *nbest = best;
    if (nfitted)
        *nfitted = n;
    return med;
}

double rp_median_ratio(const rp_report *rep, int k, int *n)
{
    double *e = malloc((size_t)(rep->n > 0 ? rep->n : 1) * sizeof *e);
    int m = 0;
    for (int i = 0; i < rep->n && e; i++) {
        double r = fr_ratio(rep->m[i].fit[k], rep->m[i].published[k]);
        if (isfinite(r))
            e[m++] = r;
    }
    double med = median_of(e, m);
    free(e);
    if (n)
        *n = m;
    return med;
}

int rp_sort_model(const rp_report *rep)
{
    int best = -1;
    double bm = INFINITY;
    for (int k = 0; k < rep->nmodels; k++) {
        double med = rp_median(rep, k, NULL, NULL);
        if (isfinite(med) && med < bm) {
            bm = med;
            best = k;
        }
    }
    return best;
}
