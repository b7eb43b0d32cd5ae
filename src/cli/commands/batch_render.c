/* SPDX-License-Identifier: MIT */
/* batch_render.c -- a material's renders and plots, in a thread of their own
 * while the next material is fitted; their record journaled when collected. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <stdlib.h>
#include <string.h>

static void *render_main(void *arg)
{
    render_job *J = arg;
    const fit_record *fits[BJ_MAX_MODELS];
    for (int i = 0; i < J->nfits; i++)
        fits[i] = &J->fits[i];
    double t0 = batch_now();
    J->rc = batch_assets(&J->dir, J->rec.material, J->table, &J->sample, fits, J->nfits, J->render,
                         J->plot, J->rec.assets, sizeof J->rec.assets, &J->err);
    J->seconds = batch_now() - t0;
    return NULL;
}

/* Wait for the job in flight (if any), journal its record or report its failure. */
void batch_render_collect(batch_run *R, render_job *J)
{
    if (!J->running)
        return;
    if (J->threaded)
        pthread_join(J->thread, NULL);
    J->running = J->threaded = 0;
    R->seconds_render += J->seconds;
    brdffit_table_free(J->table);
    free(J->fits);
    od_close(&J->dir);
    J->table = NULL;
    J->fits = NULL;
    if (J->rc != 0) {
        if (J->err.status == BRDFFIT_E_FILE_WRITE) { /* the output directory: stop */
            R->out_err = J->err;
            R->out_failed = 1;
        } else {
            R->failures++;
            fputs(R->P.live && !R->P.quiet ? "\r\033[K" : "", stderr);
            cli_error("%s: renders and plots: %s", J->rec.material, J->err.message);
        }
        return;
    }
    J->rec.status = BRDFFIT_OK;
    cli_fault_point("asset");
    if (!R->out_failed)
        batch_keep(R, &J->rec);
}

/* Start the renders and plots of material m (its table t is handed over). */
void batch_render_start(batch_run *R, render_job *J, const batch_material *m, brdffit_table *t)
{
    batch_render_collect(R, J);
    const cli_options *o = &R->b->common;
    memset(&J->err, 0, sizeof J->err);
    J->table = t;
    J->sample = o->sample;
    J->render = !R->b->no_render;
    J->plot = !R->b->no_plot;
    J->nfits = 0;
    J->fits = malloc((size_t)(o->nmodels > 0 ? o->nmodels : 1) * sizeof *J->fits);
    batch_fill_key(&J->rec, FR_ASSETS, m, &R->settings);
    batch_assets_key(R, J->rec.assets_key, sizeof J->rec.assets_key);
    J->dir.fd = -1;
    if (!J->fits || od_sub(&J->dir, &R->out, m->name, &R->out_err) != 0) {
        if (!J->fits)
            snprintf(R->out_err.message, sizeof R->out_err.message, "out of memory");
        R->out_failed = 1;
        free(J->fits);
        J->fits = NULL;
        brdffit_table_free(t);
        J->table = NULL;
        return;
    }
    od_sweep(&J->dir);
    for (int i = 0; i < o->nmodels; i++) {
        const fit_record *f = batch_find(R, FR_FIT, m, brdffit_model_get(o->models[i])->name);
        if (f && fr_ok(f))
            J->fits[J->nfits++] = *f;
    }
    J->threaded = pthread_create(&J->thread, NULL, render_main, J) == 0;
    if (!J->threaded)
        render_main(J); /* no thread to be had: here, then */
    J->running = 1;
}
