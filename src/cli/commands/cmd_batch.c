/* SPDX-License-Identifier: MIT */
/* cmd_batch.c -- `brdffit batch INPUT... --out DIR`: every model fitted to every
 * material, each fit journaled (fsync'd) before the next starts, the report
 * (pages, index, headline figure) rebuilt from the journal.  Re-running the
 * same command resumes; SIGINT/SIGTERM stop after the fit in progress;
 * --shard K/N takes every N-th material of the sorted list. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ------------------------------------------------------------------ one material */

/* A material's failure: said (and counted). */
static void failure_said(batch_run *R, const fit_record *r)
{
    R->failures++;
    if (R->P.live && !R->P.quiet)
        fputs("\r\033[K", stderr);
    fputs("brdffit: ", stderr);
    plain_string(stderr, r->message);
    fputc('\n', stderr);
}

/* A material's failure: said, journaled. */
static void failure_record(batch_run *R, const fit_record *r)
{
    failure_said(R, r);
    batch_keep(R, r);
}

static void material_failed(batch_run *R, batch_material *m, const brdffit_error *err)
{
    fit_record r;
    batch_fill_key(&r, FR_FAILURE, m, &R->settings);
    if (!m->identified) { /* not even readable: the path as given, no size or hash */
        snprintf(r.id.path, sizeof r.id.path, "%s", m->path);
        r.id.size = -1;
    }
    fr_set_failure(&r, err->status, err);
    if (!m->identified)
        m->id = r.id;
    /* the same failure journaled by an earlier run: said, not journaled again */
    const fit_record *was = batch_find(R, FR_FAILURE, m, "");
    if (was && was->status == r.status && strcmp(was->message, r.message) == 0)
        failure_said(R, &r);
    else
        failure_record(R, &r);
}

static int ensure_context(batch_run *R, brdffit_error *err)
{
    if (R->ctx)
        return 0;
    brdffit_status st = brdffit_context_create(&R->b->common.context, &R->ctx, err);
    if (st != BRDFFIT_OK) {
        err->status = st;
        R->ctx = NULL;
        return -1;
    }
    snprintf(R->backend, sizeof R->backend, "%s", brdffit_context_describe(R->ctx));
    return 0;
}

static brdffit_status load_table(const batch_material *m, brdffit_scale scale, brdffit_table **t,
                                 brdffit_error *err)
{
    if (m->embedded)
        return cli_demo_table(scale, t, err);
    return brdffit_table_read(m->path, t, err);
}

static void published_one(batch_run *R, const batch_material *m, const brdffit_samples *s,
                          brdffit_model model)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    const pub_row *pr = pub_find(&R->pub, m->name, model);
    fit_record r;
    batch_fill_key(&r, FR_PUBLISHED, m, &R->settings);
    snprintf(r.model, sizeof r.model, "%s", mi->name);
    r.params = pr->params;
    r.nparams = mi->nparams;
    r.has_params = 1;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    double e = NAN, t0 = batch_now();
    brdffit_status st = brdffit_params_check(model, &pr->params, &err);
    if (st == BRDFFIT_OK) {
        int note = R->P.quiet ? 0 : kernel_note_begin(stderr, R->ctx, model);
        st = brdffit_error_of(R->ctx, s, model, &pr->params, &e, &err);
        kernel_note_end(stderr, note, R->ctx, model);
    }
    R->seconds_fitting += batch_now() - t0;
    r.error = e;
    r.status = st;
    if (st != BRDFFIT_OK)
        snprintf(r.message, sizeof r.message, "published parameters of %s: %.400s", mi->name,
                 err.message);
    batch_keep(R, &r);
}

/* Say when a file changed since its records were journaled. */
static void note_changed(const batch_run *R, const batch_material *m)
{
    for (int i = R->all.n - 1; i >= 0; i--) {
        const fit_record *r = &R->all.r[i];
        if (strcmp(r->material, m->name) != 0 || r->id.size < 0 || m->embedded ||
            !bj_settings_equal(&r->settings, &R->settings))
            continue;
        if (!bj_identity_equal(&r->id, &m->id)) {
            cli_error("%s: the table changed since it was journaled "
                      "(%s, %lld bytes, hash %s; now %s, %lld bytes, hash %s): fitted again",
                      m->name, r->id.path, r->id.size, r->id.hash, m->id.path, m->id.size, m->id.hash);
        }
        return;
    }
}

/* Fit what is left of one material.  Returns 0 to go on, -1 to stop. */
/* The material's identity (file identity, or its bytes for the embedded
 * table, which is loaded here into *t).  0 when identified; otherwise the
 * failure is recorded and shown, and the result is do_material's. */
static int identify_material(batch_run *R, batch_material *m, int i, int n, brdffit_table **t)
{
    const cli_options *o = &R->b->common;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    if (m->embedded) {
        m->identified = 1; /* identified when its table is made */
        if (load_table(m, o->sample.scale, t, &err) != BRDFFIT_OK) {
            material_failed(R, m, &err);
            return R->out_failed ? -1 : 1;
        }
        bj_identify_bytes("(embedded)", brdffit_table_values_const(*t),
                          3 * (size_t)BRDFFIT_MERL_BINS * sizeof(double), &m->id);
        return 0;
    }
    int have = prefetch_wait(R->pre, m->path) && R->pre->identified;
    if (have)
        m->id = R->pre->id;
    if (have || bj_identify(m->path, &m->id, &err) == 0) {
        m->identified = 1;
        note_changed(R, m);
        return 0;
    }
    material_failed(R, m, &err);
    R->P.done_fits += o->nmodels;
    batch_progress_material(&R->P, i, n, m->name, "failed");
    return R->out_failed ? -1 : 1;
}

/* The hooks of one material's fits (fit_pipeline.h). */
typedef struct batch_fits {
    batch_run *R;
    batch_material *m;
    const batch_material *next;
    int i, n;
    const todo *td;
    double t0;                 /* the fit in progress started */
} batch_fits;

static int fits_context(void *user, brdffit_context **ctx, brdffit_error *err)
{
    batch_fits *F = user;
    if (ensure_context(F->R, err) != 0) {
        cli_error("cannot set up the fitting backend: %s", err->message);
        F->R->failures++;
        return -1;
    }
    *ctx = F->R->ctx;
    return 0;
}

static void fits_ready(void *user, const brdffit_samples *s, brdffit_context *ctx)
{
    batch_fits *F = user;
    const cli_options *o = &F->R->b->common;
    (void)s;
    (void)ctx;
    if (F->next && !F->next->embedded && o->read_ahead)
        prefetch_start(F->R->pre, F->next->path, &o->sample, 1, o->models, o->nmodels);
}

/* The fits the plan asks for. */
static int fits_before(void *user, int k)
{
    batch_fits *F = user;
    batch_run *R = F->R;
    if (R->out_failed || batch_stop_signal)
        return -1;
    if (!F->td->fits[k]) {
        R->P.done_fits++;
        return 0;
    }
    batch_progress_live(&R->P, F->i, F->n, F->m->name,
                  brdffit_model_get(R->b->common.models[k])->name);
    F->t0 = batch_now();
    return 1;
}

static void fits_record(void *user, const fit_record *r, const brdffit_fit_result *res)
{
    batch_fits *F = user;
    batch_run *R = F->R;
    if (r->kind == FR_FAILURE) { /* the table could not be read or sampled */
        failure_record(R, r);
        R->P.done_fits += R->b->common.nmodels;
        batch_progress_material(&R->P, F->i, F->n, F->m->name, "failed");
        return;
    }
    double dt = batch_now() - F->t0;
    R->seconds_fitting += dt;
    R->P.fit_seconds += dt;
    R->P.fitted_now++;
    if (!res) {
        R->failures++;
        fputs(R->P.live && !R->P.quiet ? "\r\033[K" : "", stderr);
        cli_error("%s: fitting %s failed: %s", F->m->name, r->model, r->message);
    }
    batch_keep(R, r);
    R->P.done_fits++;
}

/* Then the published parameters' scores. */
static void fits_after(void *user, const brdffit_samples *s, brdffit_context *ctx)
{
    batch_fits *F = user;
    batch_run *R = F->R;
    (void)ctx;
    for (int k = 0; k < R->b->common.nmodels && !R->out_failed && !batch_stop_signal; k++)
        if (F->td->published[k])
            published_one(R, F->m, s, R->b->common.models[k]);
}

/* How many of m's fits the journal holds as failed (a run counts each). */
static int journaled_failed_fits(const batch_run *R, const batch_material *m)
{
    int failed = 0;
    for (int k = 0; k < R->b->common.nmodels; k++) {
        const fit_record *r = batch_find(R, FR_FIT, m, brdffit_model_get(R->b->common.models[k])->name);
        failed += r && !fr_ok(r);
    }
    return failed;
}

/* next: the material after m, whose table is read while m is fitted (NULL: none). */
static int do_material(batch_run *R, batch_material *m, const batch_material *next, int i, int n)
{
    const cli_options *o = &R->b->common;
    brdffit_table *t = NULL;
    int rc = identify_material(R, m, i, n, &t);
    if (rc != 0)
        goto done;
    todo td = batch_plan(R, m);
    const fit_record *f = batch_find(R, FR_FAILURE, m, "");
    if (!td.any || f) {
        R->P.done_fits += o->nmodels;
        int failed = f ? 1 : journaled_failed_fits(R, m);
        R->failures += failed;
        batch_progress_material(&R->P, i, n, m->name,
                                f || failed == o->nmodels ? "failed (journaled)"
                                                          : "done (journaled)");
        goto done;
    }
    fp_source src;
    memset(&src, 0, sizeof src);
    src.name = m->name;
    src.path = m->embedded ? NULL : m->path;
    src.shown = m->embedded ? m->name : m->path;
    src.id = m->id;
    if (!t && prefetch_wait(R->pre, m->path) && R->pre->table) { /* read meanwhile */
        t = R->pre->table;
        src.samples = R->pre->samples;
        R->pre->table = NULL;
        R->pre->samples = NULL;
    }
    src.table = t;
    batch_fits F = { R, m, next, i, n, &td, 0 };
    fp_hooks h = { &F, fits_context, fits_ready, fits_before, fits_record, fits_after };
    rc = fp_fit_table(&R->fit_job, &src, &h);
    t = src.table; /* read by fp_fit_table (kept for the renders), or ours */
    if (rc != 0) {
        rc = rc < 0 || R->out_failed ? -1 : 1;
        goto done;
    }
    if (td.assets && !R->out_failed && !batch_stop_signal) {
        batch_render_start(R, R->job, m, t); /* t is the job's now */
        t = NULL;
    }
    if (!R->out_failed)
        batch_progress_material(&R->P, i, n, m->name, batch_stop_signal ? "interrupted" : "done");
    rc = R->out_failed ? -1 : 0;
done:
    if (prefetch_wait(R->pre, m->path)) /* m's, not taken (journaled, failed) */
        prefetch_drop(R->pre);
    brdffit_table_free(t);
    return rc < 0 ? -1 : 0;
}

/* ------------------------------------------------------------------ start and finish */

/* Say (once) that journaled records of other settings are not reused. */
static void note_other_settings(const batch_run *R)
{
    int other = 0;
    char diff[512] = "";
    for (int i = 0; i < R->all.n; i++)
        if (!bj_settings_equal(&R->all.r[i].settings, &R->settings)) {
            if (!other++)
                bj_settings_diff(&R->all.r[i].settings, &R->settings, diff, sizeof diff);
        }
    if (other)
        cli_error("%s: %d journaled record%s made with other settings (%s): not reused; "
                  "those fits are done again",
                  R->journal.path, other, other == 1 ? " was" : "s were", diff);
}

/* --out opened (made), locked for this run, the temporaries a killed run
 * left removed, the journal opened (its torn line cut) and read. */
static int open_out(batch_run *R)
{
    brdffit_error *err = &R->out_err;
    int torn = 0, torn2 = 0, bad = 0;
    if (od_open(&R->out, R->b->out, 1, err) != 0 ||
        od_lock_take(&R->lock, &R->out, 0, "batch", err) != 0)
        return -1;
    od_sweep(&R->out);
    if (bj_journal_open(&R->journal, &R->out, &torn2, err) != 0)
        return -1;
    const char *path = R->journal.path;
    if (bj_journal_load(path, &R->all, &bad, &torn, err) != 0)
        return -1;
    if (torn || torn2)
        cli_error("%s: its last line was cut short (a run killed while writing "
                  "it): ignored, that fit is done again", path);
    note_other_settings(R);
    return 0;
}

static int run_batch(batch_run *R, material_list *L)
{
    const batch_options *b = R->b;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    if (b->published) {
        if (pub_read(b->published, &R->pub, &err) != 0) {
            cli_error("--published: %s", err.message);
            return CLI_USAGE;
        }
        R->have_pub = 1;
        char why[BRDFFIT_MESSAGE_MAX];
        if (pub_scale_mismatch(&R->pub, b->common.sample.scale, why, sizeof why)) {
            if (!b->allow_scale_mismatch) {
                cli_error("--published: %s; %s", why, pub_scale_advice(&R->pub));
                return CLI_USAGE;
            }
            snprintf(R->scale_note, sizeof R->scale_note, "%.1500s: %s", why, PUB_SCALE_NOTE);
            cli_error("warning: --published: %s", R->scale_note);
        }
    }
    if (open_out(R) != 0) {
        cli_error("%s", R->out_err.message);
        return CLI_FAILED;
    }
    R->P.total_fits = L->n * b->common.nmodels;
    batch_install_signals();
    double t0 = batch_now();
    for (int i = 0; i < L->n && !batch_stop_signal; i++) {
        batch_material *m = &L->m[i];
        if (do_material(R, m, i + 1 < L->n ? &L->m[i + 1] : NULL, i, L->n) != 0)
            break;
    }
    prefetch_drop(R->pre);
    batch_render_collect(R, R->job);
    if (R->P.live && !b->quiet)
        fputs("\r\033[K", stderr);
    if (R->out_failed) {
        cli_error("%s; stopped (what is in %s is kept)", R->out_err.message,
                  R->journal.path);
        return CLI_FAILED;
    }
    double t_fits = batch_now();
    if (batch_write_report(R, L) != 0) {
        cli_error("%s; stopped (what is in %s is kept)", R->out_err.message,
                  R->journal.path);
        return CLI_FAILED;
    }
    double total = batch_now() - t0;
    char index[BJ_PATH_MAX];
    out_join(index, sizeof index, b->out, "index.html");
    if (!b->quiet)
        fprintf(stderr, "brdffit: %d material%s, %d fit%s this run; %.1f s, of which %.1f s "
                        "fitting (%.1f%% outside: reading, renders, plots, pages; renders and plots "
                        "%.1f s beside the fits; the report %.2f s)\n",
                L->n, L->n == 1 ? "" : "s", R->P.fitted_now, R->P.fitted_now == 1 ? "" : "s", total,
                R->seconds_fitting, total > 0 ? 100 * (total - R->seconds_fitting) / total : 0.0,
                R->seconds_render, batch_now() - t_fits);
    printf("%s\n", index);
    if (batch_stop_signal) {
        int sig = batch_stop_signal;
        cli_error("interrupted (signal %d): the report holds what was done; run the "
                  "same command again to go on", sig);
        return 128 + sig;
    }
    if (R->failures)
        fprintf(stderr, "brdffit: %d failure%s (see the report)\n", R->failures,
                R->failures == 1 ? "" : "s");
    return R->failures ? CLI_FAILED : CLI_OK;
}

/* One batch of b's materials under b's metric into b->out; its model
 * table into *summary when not NULL. */
static int batch_once(batch_options *bp, material_list *Lp, metric_summary *summary)
{
    batch_options b = *bp;
    material_list L = *Lp;
    int rc;
    {
        batch_run R;
        static render_job job;
        static table_prefetch pre;
        memset(&job, 0, sizeof job); /* --metric all: a batch after another */
        memset(&pre, 0, sizeof pre);
        memset(&R, 0, sizeof R);
        R.summary = summary;
        R.b = &b;
        R.job = &job;
        R.pre = &pre;
        R.journal.fd = -1;
        R.out.fd = R.lock.fd = -1;
        bj_settings_make(&R.settings, &b.common.sample, &b.common.fit);
        R.fit_job.models = b.common.models;
        R.fit_job.nmodels = b.common.nmodels;
        R.fit_job.sample = &b.common.sample;
        R.fit_job.fit = &b.common.fit;
        R.fit_job.settings = R.settings;
        R.fit_job.kernel_notes = !b.quiet;
        R.fit_job.keep_table = 1;
        R.P.live = isatty(STDERR_FILENO);
        R.P.quiet = b.quiet;
        R.P.t0 = batch_now();
        rc = run_batch(&R, &L);
        bj_journal_close(&R.journal);
        od_lock_release(&R.lock);
        od_close(&R.out);
        bj_records_free(&R.all);
        pub_free(&R.pub);
        brdffit_context_free(R.ctx);
    }
    return rc;
}

int batch_metrics_page(const char *out, const metric_summary *sums);

/* --metric all: the batch under each metric in turn, into OUT/METRIC (each a
 * report of its own: its model table and headline under that metric; every
 * record carries its Errors under all three).  The worst status. */
static int batch_all_metrics(batch_options *b, material_list *L)
{
    const char *out = b->out;
    if (mkdir(out, 0777) != 0 && errno != EEXIST) {
        cli_error("%s: cannot make the directory: %s", out, strerror(errno));
        return CLI_FAILED;
    }
    int worst = CLI_OK;
    metric_summary sums[BRDFFIT_METRIC_COUNT];
    memset(sums, 0, sizeof sums);
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
        char dir[BJ_PATH_MAX];
        const char *name = brdffit_metric_get_name((brdffit_metric)m);
        if ((size_t)snprintf(dir, sizeof dir, "%s/%s", out, name) >= sizeof dir) {
            cli_error("%s: the path is too long", out);
            return CLI_FAILED;
        }
        b->out = dir;
        b->common.fit.metric = m;
        int rc = batch_once(b, L, &sums[m]);
        b->out = out;
        if (rc > worst)
            worst = rc;
        if (rc >= 128 || batch_stop_signal) /* stopped by a signal: not the next metric */
            return rc;
    }
    if (batch_metrics_page(out, sums) != 0)
        return CLI_FAILED;
    char index[BJ_PATH_MAX];
    snprintf(index, sizeof index, "%s/index.html", out);
    printf("%s\n", index);
    return worst;
}

int cmd_batch(int argc, char **argv)
{
    batch_options b;
    int rc = batch_parse_options(argc, argv, &b);
    if (rc != CLI_OK) { /* CLI_HELP too: main prints the usage */
        cli_options_free(&b.common);
        return rc;
    }
    material_list L = { NULL, 0, 0 };
    rc = batch_collect(&b, &L);
    if (rc == CLI_OK)
        rc = b.common.all_metrics ? batch_all_metrics(&b, &L) : batch_once(&b, &L, NULL);
    free(L.m);
    cli_options_free(&b.common);
    return rc;
}
