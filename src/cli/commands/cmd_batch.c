/* SPDX-License-Identifier: MIT */
/* cmd_batch.c -- `brdffit batch INPUT... --out DIR`: every model fitted to every
 * material, each fit journaled (fsync'd) before the next starts, the report
 * (pages, index, headline figure) rebuilt from the journal.  Re-running the
 * same command resumes; SIGINT/SIGTERM stop after the fit in progress;
 * --shard K/N takes every N-th material of the sorted list. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"
#include "fit_pipeline.h"
#include "prefetch.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* ------------------------------------------------------------------ options */

typedef struct batch_options {
    cli_options common;      /* --model --scale --cutoff --starts --backend --device, INPUT... */
    const char *out;
    const char *published;
    int shard_k, shard_n;    /* 1-based; 1/1 unsharded */
    int quiet, no_render, no_plot, demo;
} batch_options;

static int parse_shard(const char *v, int *k, int *n)
{
    const char *slash = strchr(v, '/');
    char a[32];
    if (!slash || (size_t)(slash - v) >= sizeof a)
        return -1;
    memcpy(a, v, (size_t)(slash - v));
    a[slash - v] = '\0';
    if (cli_parse_int(slash + 1, 1, 1000000, n) != 0 || cli_parse_int(a, 1, *n, k) != 0)
        return -1;
    return 0;
}

/* The batch's own options are taken out; the rest go to cli_parse_options. */
static int parse_batch(int argc, char **argv, batch_options *b)
{
    memset(b, 0, sizeof *b);
    b->shard_k = b->shard_n = 1;
    char **rest = malloc((size_t)(argc + 1) * sizeof *rest);
    if (!rest) {
        fputs("brdffit: out of memory\n", stderr);
        return CLI_FAILED;
    }
    int nrest = 0, rc = CLI_OK;
    for (int i = 0; i < argc && rc == CLI_OK; i++) {
        const char *a = argv[i];
        const char **dst = NULL;
        if (strcmp(a, "--") == 0) {
            while (i < argc)
                rest[nrest++] = argv[i++];
            break;
        }
        if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0)
            b->quiet = 1;
        else if (strcmp(a, "--no-render") == 0)
            b->no_render = 1;
        else if (strcmp(a, "--no-plot") == 0)
            b->no_plot = 1;
        else if (strcmp(a, "--demo") == 0)
            b->demo = 1;
        else if (strcmp(a, "--json") == 0)
            rc = cli_usage_error("batch writes its JSON into --out DIR; --json is for fit");
        else if (strncmp(a, "--out", 5) == 0 && (a[5] == '\0' || a[5] == '='))
            dst = &b->out;
        else if (strncmp(a, "--published", 11) == 0 && (a[11] == '\0' || a[11] == '='))
            dst = &b->published;
        else if (strncmp(a, "--shard", 7) == 0 && (a[7] == '\0' || a[7] == '=')) {
            const char *v = a[7] == '=' ? a + 8 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v || parse_shard(v, &b->shard_k, &b->shard_n) != 0)
                rc = cli_usage_error("--shard '%s': expected K/N with 1 <= K <= N", v ? v : "");
        } else
            rest[nrest++] = argv[i];
        if (dst) {
            const char *eq = strchr(a, '=');
            const char *v = eq ? eq + 1 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v || !*v)
                rc = cli_usage_error("%.11s needs a value", a);
            else
                *dst = v;
        }
    }
    if (rc == CLI_OK) {
        rc = cli_parse_options(nrest, rest, &b->common);
        if (rc == CLI_OK && !b->out)
            rc = cli_usage_error("batch needs --out DIR");
        else if (rc == CLI_OK && b->common.nfiles == 0 && !b->demo)
            rc = cli_usage_error("batch needs INPUT: a table, a directory of *.binary or @LIST");
    }
    free(rest);
    return rc;
}

const cli_help_block *cli_batch_help(void)
{
    static const cli_help_item items[] = {
        { "--out DIR", "the report: DIR/index.html, DIR/<material>/, fits.tsv,\n"
                       "journal.jsonl (re-run the same command to resume)" },
        { "--published FITS.tsv", "also the Error of published parameters (the format\n"
                                  "of ngan2005-fits.tsv) on each table, and the ratio" },
        { "--shard K/N", "only every N-th material of the sorted list, from the\n"
                         "K-th (merge the shards with `brdffit report`)" },
        { "--no-render, --no-plot", "leave out the renders / the incidence-plane plots" },
        { "--demo", "add the embedded synthetic material" },
        { "--quiet", "no progress on stderr (a live line on a terminal,\n"
                     "else one line per material)" },
    };
    static const cli_help_block block = CLI_HELP_BLOCK(
        "Options of batch",
        "and the options of fit but --json; INPUT is a MERL table,\n"
        "a directory of *.binary, or @LIST: a text file naming one table a line",
        items);
    return &block;
}

/* ------------------------------------------------------------------ materials */

typedef struct batch_material {
    char name[BJ_NAME_MAX];
    char path[BJ_PATH_MAX];   /* as given ("" for the embedded material) */
    int embedded;
    bj_identity id;
    int identified;
} batch_material;

typedef struct material_list {
    batch_material *m;
    int n, cap;
} material_list;

static int add_material(material_list *L, const char *path, int embedded)
{
    if (L->n == L->cap) {
        int cap = L->cap ? L->cap * 2 : 64;
        batch_material *g = realloc(L->m, (size_t)cap * sizeof *g);
        if (!g)
            return -1;
        L->m = g;
        L->cap = cap;
    }
    batch_material *m = &L->m[L->n++];
    memset(m, 0, sizeof *m);
    m->embedded = embedded;
    if (embedded) {
        snprintf(m->name, sizeof m->name, "%s", cli_demo_name());
    } else {
        snprintf(m->path, sizeof m->path, "%s", path);
        cli_material_name(path, m->name, sizeof m->name);
    }
    return 0;
}

static int has_suffix(const char *s, const char *suf)
{
    size_t n = strlen(s), k = strlen(suf);
    return n > k && strcmp(s + n - k, suf) == 0;
}

static int add_directory(material_list *L, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        cli_error("cannot read the directory %s: %s", dir, strerror(errno));
        return -1;
    }
    struct dirent *e;
    int rc = 0, found = 0;
    while ((e = readdir(d)) != NULL && rc == 0) {
        if (e->d_name[0] == '.' || !has_suffix(e->d_name, ".binary"))
            continue;
        char path[BJ_PATH_MAX];
        if (out_join(path, sizeof path, dir, e->d_name) != 0 || add_material(L, path, 0) != 0)
            rc = -1;
        found++;
    }
    closedir(d);
    if (rc == 0 && found == 0)
        cli_error("note: no *.binary file in %s", dir);
    return rc;
}

static int add_list_file(material_list *L, const char *list)
{
    FILE *f = fopen(list, "r");
    if (!f) {
        cli_error("cannot read the list %s: %s", list, strerror(errno));
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    int rc = 0;
    while (rc == 0 && getline(&line, &cap, f) > 0) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '\0' || line[0] == '#')
            continue;
        rc = add_material(L, line, 0);
    }
    free(line);
    fclose(f);
    return rc;
}

static int by_name(const void *a, const void *b)
{
    const batch_material *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    return c ? c : strcmp(x->path, y->path);
}

/* The materials of the inputs, sorted by name, without repeats; then this shard's share. */
static int collect(const batch_options *b, material_list *L)
{
    for (int i = 0; i < b->common.nfiles; i++) {
        const char *in = b->common.files[i];
        struct stat st;
        int rc;
        if (in[0] == '@')
            rc = add_list_file(L, in + 1);
        else if (stat(in, &st) == 0 && S_ISDIR(st.st_mode))
            rc = add_directory(L, in);
        else if (cli_is_text_file(in))
            return cli_usage_error("%s is a text file, not a MERL table: did you mean @%s (a list "
                                   "of tables, one a line)?", in, in);
        else
            rc = add_material(L, in, 0); /* a missing file becomes a failure row */
        if (rc != 0)
            return CLI_USAGE;
    }
    if (b->demo && add_material(L, NULL, 1) != 0)
        return CLI_FAILED;
    qsort(L->m, (size_t)L->n, sizeof *L->m, by_name);
    int w = 0;
    for (int i = 0; i < L->n; i++) {
        if (w > 0 && strcmp(L->m[w - 1].name, L->m[i].name) == 0) {
            if (strcmp(L->m[w - 1].path, L->m[i].path) == 0)
                continue; /* the same file twice */
            return cli_usage_error("two inputs are named '%s' (%s and %s): the report has one "
                                   "page per name",
                                   L->m[i].name, L->m[w - 1].path, L->m[i].path);
        }
        if (strcmp(L->m[i].name, ".") == 0 || strcmp(L->m[i].name, "..") == 0 || !L->m[i].name[0]
            || strchr(L->m[i].name, '/'))
            return cli_usage_error("'%s' cannot name a material (its page directory)", L->m[i].path);
        L->m[w++] = L->m[i];
    }
    L->n = w;
    /* the shard: every N-th of the sorted list, from the K-th */
    w = 0;
    for (int i = 0; i < L->n; i++)
        if (i % b->shard_n == b->shard_k - 1)
            L->m[w++] = L->m[i];
    L->n = w;
    return CLI_OK;
}

/* ------------------------------------------------------------------ signals */

/* SIGINT and SIGTERM are blocked in every thread (PoCL's included: they are
 * made after this) and taken by one thread with sigwait, so that no library
 * call is interrupted: the fit in progress finishes and is journaled, then the
 * batch stops.  A second signal stops the program at once (the journal is
 * whole up to its last synced record; a torn line is ignored next time). */
static _Atomic int stop_signal = 0;

static void *signal_waiter(void *arg)
{
    const sigset_t *set = arg;
    for (;;) {
        int sig = 0;
        if (sigwait(set, &sig) != 0)
            continue;
        if (stop_signal)
            _exit(128 + sig);
        stop_signal = sig;
    }
    return NULL;
}

static void install_signals(void)
{
    static sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_t t;
    if (pthread_sigmask(SIG_BLOCK, &set, NULL) == 0 &&
        pthread_create(&t, NULL, signal_waiter, &set) == 0)
        pthread_detach(t);
    /* a file-size limit then makes a write fail with EFBIG, reported like a full disk */
    signal(SIGXFSZ, SIG_IGN);
}

/* ------------------------------------------------------------------ progress */

static double now(void)
{
    return brdffit_seconds();
}

typedef struct progress {
    int live;            /* stderr is a terminal */
    int quiet;
    double t0;
    int total_fits, done_fits, fitted_now;
    double fit_seconds;  /* of the fits of this run (for the ETA) */
} progress;

static void hms(char *buf, size_t len, double s)
{
    if (!isfinite(s) || s < 0)
        snprintf(buf, len, "--:--");
    else if (s >= 3600)
        snprintf(buf, len, "%d:%02d:%02d", (int)(s / 3600), (int)fmod(s / 60, 60), (int)fmod(s, 60));
    else
        snprintf(buf, len, "%d:%02d", (int)(s / 60), (int)fmod(s, 60));
}

static void progress_live(progress *P, int i, int n, const char *material, const char *model)
{
    if (P->quiet || !P->live)
        return;
    char el[32], eta[32];
    double elapsed = now() - P->t0;
    double per = P->fitted_now ? P->fit_seconds / P->fitted_now : NAN;
    hms(el, sizeof el, elapsed);
    hms(eta, sizeof eta, per * (P->total_fits - P->done_fits));
    fprintf(stderr, "\r\033[K[%d/%d] ", i + 1, n);
    plain_string(stderr, material);
    fprintf(stderr, " %s  fits %d/%d  %s elapsed  ETA %s", model, P->done_fits, P->total_fits, el, eta);
    fflush(stderr);
}

static void progress_material(progress *P, int i, int n, const char *material, const char *what)
{
    if (P->quiet)
        return;
    char el[32];
    hms(el, sizeof el, now() - P->t0);
    if (P->live)
        fputs("\r\033[K", stderr);
    fprintf(stderr, "[%d/%d] ", i + 1, n);
    plain_string(stderr, material);
    fprintf(stderr, ": %s (fits %d/%d, %s)\n", what, P->done_fits, P->total_fits, el);
}

/* ------------------------------------------------------------------ the run */

typedef struct batch_run {
    const batch_options *b;
    bj_settings settings;
    bj_journal journal;
    bj_records all;          /* the journal's records, then this run's       */
    pub_table pub;
    int have_pub;
    brdffit_context *ctx;
    progress P;
    int failures;            /* materials and fits that failed */
    int out_failed;          /* --out could not be written: stop */
    brdffit_error out_err;
    char backend[256];
    double seconds_fitting;  /* inside brdffit_fit and brdffit_error_of */
    double seconds_render;   /* of the render jobs (in their thread)   */
    struct render_job *job;  /* the renders and plots in flight        */
    table_prefetch *pre;     /* the next material's table, read meanwhile */
    fp_job fit_job;          /* the models and settings of every material's fits */
} batch_run;

static void fill_key(fit_record *r, fr_kind kind, const batch_material *m, const bj_settings *s)
{
    fr_init(r, kind);
    snprintf(r->material, sizeof r->material, "%s", m->name);
    r->id = m->id;
    r->settings = *s;
}

/* The record of this key already journaled (last one), or NULL. */
static const fit_record *find(const batch_run *R, fr_kind kind, const batch_material *m,
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
static int keep(batch_run *R, const fit_record *r)
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

/* What a material's renders and plots depend on; "rf1" names the set of files
 * assets.c writes, so a journal whose assets were made by another set redraws them. */
static void assets_key(const batch_run *R, char *buf, size_t len)
{
    const batch_options *b = R->b;
    size_t used = (size_t)snprintf(buf, len, "rf1:render=%d,plot=%d:", !b->no_render, !b->no_plot);
    for (int i = 0; i < b->common.nmodels && used < len; i++)
        used += (size_t)snprintf(buf + used, len - used, "%s%s", i ? "," : "",
                                 brdffit_model_get(b->common.models[i])->name);
}

static int want_assets(const batch_run *R)
{
    return !R->b->no_render || !R->b->no_plot;
}

/* What is left to do for a material. */
typedef struct todo {
    int fits[BJ_MAX_MODELS];   /* by slot of the run's models */
    int published[BJ_MAX_MODELS];
    int assets;
    int any;
} todo;

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

static todo plan(const batch_run *R, const batch_material *m)
{
    todo t;
    memset(&t, 0, sizeof t);
    const cli_options *o = &R->b->common;
    for (int i = 0; i < o->nmodels; i++) {
        const char *mn = brdffit_model_get(o->models[i])->name;
        t.fits[i] = !done_fit(find(R, FR_FIT, m, mn));
        const pub_row *pr = R->have_pub ? pub_find(&R->pub, m->name, o->models[i]) : NULL;
        if (pr) {
            const fit_record *pb = find(R, FR_PUBLISHED, m, mn);
            t.published[i] =
                !pb || !same_params(&pb->params, &pr->params, brdffit_model_get(o->models[i])->nparams);
        }
        t.any |= t.fits[i] | t.published[i];
    }
    if (want_assets(R)) {
        char key[BJ_MSG_MAX];
        assets_key(R, key, sizeof key);
        const fit_record *a = find(R, FR_ASSETS, m, "");
        t.assets = !a || strcmp(a->assets_key, key) != 0;
        t.any |= t.assets;
    }
    return t;
}

/* ------------------------------------------------------------------ one material */

/* A material's failure: said, journaled. */
static void failure_record(batch_run *R, const fit_record *r)
{
    R->failures++;
    if (R->P.live && !R->P.quiet)
        fputs("\r\033[K", stderr);
    fputs("brdffit: ", stderr);
    plain_string(stderr, r->message);
    fputc('\n', stderr);
    keep(R, r);
}

static void material_failed(batch_run *R, batch_material *m, const brdffit_error *err)
{
    fit_record r;
    fill_key(&r, FR_FAILURE, m, &R->settings);
    if (!m->identified) { /* not even readable: the path as given, no size or hash */
        snprintf(r.id.path, sizeof r.id.path, "%s", m->path);
        r.id.size = -1;
    }
    fr_set_failure(&r, err->status, err);
    if (!m->identified)
        m->id = r.id;
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
    fill_key(&r, FR_PUBLISHED, m, &R->settings);
    snprintf(r.model, sizeof r.model, "%s", mi->name);
    r.params = pr->params;
    r.nparams = mi->nparams;
    r.has_params = 1;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    double e = NAN, t0 = now();
    brdffit_status st = brdffit_params_check(model, &pr->params, &err);
    if (st == BRDFFIT_OK) {
        int note = R->P.quiet ? 0 : kernel_note_begin(stderr, R->ctx, model);
        st = brdffit_error_of(R->ctx, s, model, &pr->params, &e, &err);
        kernel_note_end(stderr, note, R->ctx, model);
    }
    R->seconds_fitting += now() - t0;
    r.error = e;
    r.status = st;
    if (st != BRDFFIT_OK)
        snprintf(r.message, sizeof r.message, "published parameters of %s: %.400s", mi->name,
                 err.message);
    keep(R, &r);
}

/* The renders and plots of a material run in a thread of their own while the
 * next material is fitted (a fit keeps about one core busy; the machine has
 * more).  One job at a time; the main thread journals its record when it is
 * collected, so the record still comes after the files. */
typedef struct render_job {
    pthread_t thread;
    int running;                   /* a job to collect               */
    int threaded;                  /* in its own thread (to join)    */
    char dir[BJ_PATH_MAX];
    brdffit_table *table;          /* owned: freed when collected   */
    brdffit_sample_options sample;
    fit_record *fits;               /* copies (the records array may move) */
    int nfits, render, plot;
    fit_record rec;                 /* the FR_ASSETS record to journal */
    int rc;
    brdffit_error err;
    double seconds;
} render_job;

static void *render_main(void *arg)
{
    render_job *J = arg;
    const fit_record *fits[BJ_MAX_MODELS];
    for (int i = 0; i < J->nfits; i++)
        fits[i] = &J->fits[i];
    double t0 = now();
    J->rc = batch_assets(J->dir, J->rec.material, J->table, &J->sample, fits, J->nfits, J->render,
                         J->plot, J->rec.assets, sizeof J->rec.assets, &J->err);
    J->seconds = now() - t0;
    return NULL;
}

/* Wait for the job in flight (if any), journal its record or report its failure. */
static void render_collect(batch_run *R, render_job *J)
{
    if (!J->running)
        return;
    if (J->threaded)
        pthread_join(J->thread, NULL);
    J->running = J->threaded = 0;
    R->seconds_render += J->seconds;
    brdffit_table_free(J->table);
    free(J->fits);
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
        keep(R, &J->rec);
}

/* Start the renders and plots of material m (its table t is handed over). */
static void render_start(batch_run *R, render_job *J, const batch_material *m, brdffit_table *t)
{
    render_collect(R, J);
    const cli_options *o = &R->b->common;
    memset(&J->err, 0, sizeof J->err);
    J->table = t;
    J->sample = o->sample;
    J->render = !R->b->no_render;
    J->plot = !R->b->no_plot;
    J->nfits = 0;
    J->fits = malloc((size_t)(o->nmodels > 0 ? o->nmodels : 1) * sizeof *J->fits);
    fill_key(&J->rec, FR_ASSETS, m, &R->settings);
    assets_key(R, J->rec.assets_key, sizeof J->rec.assets_key);
    if (!J->fits || out_join(J->dir, sizeof J->dir, R->b->out, m->name) != 0 ||
        out_mkdir(J->dir, &R->out_err) != 0) {
        if (!J->fits)
            snprintf(R->out_err.message, sizeof R->out_err.message, "out of memory");
        R->out_failed = 1;
        free(J->fits);
        J->fits = NULL;
        brdffit_table_free(t);
        J->table = NULL;
        return;
    }
    for (int i = 0; i < o->nmodels; i++) {
        const fit_record *f = find(R, FR_FIT, m, brdffit_model_get(o->models[i])->name);
        if (f && fr_ok(f))
            J->fits[J->nfits++] = *f;
    }
    J->threaded = pthread_create(&J->thread, NULL, render_main, J) == 0;
    if (!J->threaded)
        render_main(J); /* no thread to be had: here, then */
    J->running = 1;
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
    progress_material(&R->P, i, n, m->name, "failed");
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
    if (R->out_failed || stop_signal)
        return -1;
    if (!F->td->fits[k]) {
        R->P.done_fits++;
        return 0;
    }
    progress_live(&R->P, F->i, F->n, F->m->name,
                  brdffit_model_get(R->b->common.models[k])->name);
    F->t0 = now();
    return 1;
}

static void fits_record(void *user, const fit_record *r, const brdffit_fit_result *res)
{
    batch_fits *F = user;
    batch_run *R = F->R;
    if (r->kind == FR_FAILURE) { /* the table could not be read or sampled */
        failure_record(R, r);
        R->P.done_fits += R->b->common.nmodels;
        progress_material(&R->P, F->i, F->n, F->m->name, "failed");
        return;
    }
    double dt = now() - F->t0;
    R->seconds_fitting += dt;
    R->P.fit_seconds += dt;
    R->P.fitted_now++;
    if (!res) {
        R->failures++;
        fputs(R->P.live && !R->P.quiet ? "\r\033[K" : "", stderr);
        cli_error("%s: fitting %s failed: %s", F->m->name, r->model, r->message);
    }
    keep(R, r);
    R->P.done_fits++;
}

/* Then the published parameters' scores. */
static void fits_after(void *user, const brdffit_samples *s, brdffit_context *ctx)
{
    batch_fits *F = user;
    batch_run *R = F->R;
    (void)ctx;
    for (int k = 0; k < R->b->common.nmodels && !R->out_failed && !stop_signal; k++)
        if (F->td->published[k])
            published_one(R, F->m, s, R->b->common.models[k]);
}

/* next: the material after m, whose table is read while m is fitted (NULL: none). */
static int do_material(batch_run *R, batch_material *m, const batch_material *next, int i, int n)
{
    const cli_options *o = &R->b->common;
    brdffit_table *t = NULL;
    int rc = identify_material(R, m, i, n, &t);
    if (rc != 0)
        goto done;
    todo td = plan(R, m);
    const fit_record *f = find(R, FR_FAILURE, m, "");
    if (!td.any || f) {
        R->P.done_fits += o->nmodels;
        if (f)
            R->failures++;
        progress_material(&R->P, i, n, m->name, f ? "failed (journaled)" : "done (journaled)");
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
    if (td.assets && !R->out_failed && !stop_signal) {
        render_start(R, R->job, m, t); /* t is the job's now */
        t = NULL;
    }
    if (!R->out_failed)
        progress_material(&R->P, i, n, m->name, stop_signal ? "interrupted" : "done");
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

static int open_out(batch_run *R)
{
    const char *out = R->b->out;
    brdffit_error *err = &R->out_err;
    if (out_mkdir(out, err) != 0)
        return -1;
    char path[BJ_PATH_MAX];
    int bad = 0, torn = 0;
    if (out_join(path, sizeof path, out, "journal.jsonl") != 0 ||
        bj_journal_load(path, &R->all, &bad, &torn, err) != 0)
        return -1;
    if (bad)
        cli_error("%s: %d line%s that are not journal records ignored", path, bad,
                  bad == 1 ? "" : "s");
    int torn2 = 0;
    if (bj_journal_open(&R->journal, out, &torn2, err) != 0)
        return -1;
    if (torn || torn2)
        cli_error("%s: its last line was cut short (a run killed while writing "
                  "it): ignored, that fit is done again", path);
    note_other_settings(R);
    return 0;
}

static void utc_now(char *buf, size_t len)
{
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm);
}

/* The report of this run's materials, from the records. */
static int write_report(batch_run *R, const material_list *L)
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
    }
    const char *dirs[1] = { R->b->out };
    int rc = 0;
    for (int i = 0; i < L->n && rc == 0; i++)
        if (L->m[i].identified || L->m[i].id.size < 0)
            rc = rp_add(&rep, L->m[i].name, &L->m[i].id, &R->all, dirs, 1);
    if (rc == 0)
        rc = rp_write(&rep, R->b->out, &R->out_err);
    else
        snprintf(R->out_err.message, sizeof R->out_err.message, "out of memory");
    rp_free(&rep);
    return rc;
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
    }
    if (open_out(R) != 0) {
        cli_error("%s", R->out_err.message);
        return CLI_FAILED;
    }
    R->P.total_fits = L->n * b->common.nmodels;
    install_signals();
    double t0 = now();
    for (int i = 0; i < L->n && !stop_signal; i++) {
        batch_material *m = &L->m[i];
        if (do_material(R, m, i + 1 < L->n ? &L->m[i + 1] : NULL, i, L->n) != 0)
            break;
    }
    prefetch_drop(R->pre);
    render_collect(R, R->job);
    if (R->P.live && !b->quiet)
        fputs("\r\033[K", stderr);
    if (R->out_failed) {
        cli_error("%s; stopped (what is in %s is kept)", R->out_err.message,
                  R->journal.path);
        return CLI_FAILED;
    }
    double t_fits = now();
    if (write_report(R, L) != 0) {
        cli_error("%s; stopped (what is in %s is kept)", R->out_err.message,
                  R->journal.path);
        return CLI_FAILED;
    }
    double total = now() - t0;
    char index[BJ_PATH_MAX];
    out_join(index, sizeof index, b->out, "index.html");
    if (!b->quiet)
        fprintf(stderr, "brdffit: %d material%s, %d fit%s this run; %.1f s, of which %.1f s "
                        "fitting (%.1f%% outside: reading, renders, plots, pages; renders and plots "
                        "%.1f s beside the fits; the report %.2f s)\n",
                L->n, L->n == 1 ? "" : "s", R->P.fitted_now, R->P.fitted_now == 1 ? "" : "s", total,
                R->seconds_fitting, total > 0 ? 100 * (total - R->seconds_fitting) / total : 0.0,
                R->seconds_render, now() - t_fits);
    printf("%s\n", index);
    if (stop_signal) {
        int sig = stop_signal;
        cli_error("interrupted (signal %d): the report holds what was done; run the "
                  "same command again to go on", sig);
        return 128 + sig;
    }
    if (R->failures)
        fprintf(stderr, "brdffit: %d failure%s (see the report)\n", R->failures,
                R->failures == 1 ? "" : "s");
    return R->failures ? CLI_FAILED : CLI_OK;
}

int cmd_batch(int argc, char **argv)
{
    batch_options b;
    int rc = parse_batch(argc, argv, &b);
    if (rc != CLI_OK) { /* CLI_HELP too: main prints the usage */
        cli_options_free(&b.common);
        return rc;
    }
    material_list L = { NULL, 0, 0 };
    rc = collect(&b, &L);
    if (rc == CLI_OK) {
        batch_run R;
        static render_job job;
        static table_prefetch pre;
        memset(&R, 0, sizeof R);
        R.b = &b;
        R.job = &job;
        R.pre = &pre;
        R.journal.fd = -1;
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
        R.P.t0 = now();
        rc = run_batch(&R, &L);
        bj_journal_close(&R.journal);
        bj_records_free(&R.all);
        pub_free(&R.pub);
        brdffit_context_free(R.ctx);
    }
    free(L.m);
    cli_options_free(&b.common);
    return rc;
}
