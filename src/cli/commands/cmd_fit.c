/* SPDX-License-Identifier: MIT */
/* cmd_fit.c -- `brdffit fit` and `brdffit demo`: each table (read, or
 * synthesised) fitted by the one loop of fit_pipeline.h with ONE context,
 * each fit shown as a table row or a JSON record (fit_record.h); the next
 * file's table is read in a thread while one is fitted (prefetch.h). */
#include "cli.h"
#include "fit_pipeline.h"
#include "prefetch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct runner {
    const cli_options *o;
    fp_job job;
    brdffit_context *ctx;    /* created at the first sample set, reused for every fit */
    brdffit_error ctx_err;   /* why no context could be made: each later material fails with it */
    int failures;            /* files and fits that failed */
    int fits_ok;
    table_prefetch pre;      /* the next file's sample set, made meanwhile */
    /* the material being fitted */
    const cli_material *m;
    const char *next;        /* the file after it, read meanwhile (NULL: none) */
    int first;
    /* its best fit */
    int found;
    brdffit_model best_model;
    double best_error;
    /* demo: the generating model and parameters (the "truth" row) */
    const brdffit_params *truth;
    brdffit_model truth_model;
} runner;

static void runner_init(runner *R, const cli_options *o)
{
    memset(R, 0, sizeof *R);
    R->o = o;
    R->job.models = o->models;
    R->job.nmodels = o->nmodels;
    R->job.sample = &o->sample;
    R->job.fit = &o->fit;
    bj_settings_make(&R->job.settings, &o->sample, &o->fit);
    R->job.kernel_notes = 1;
}

/* One record on stdout (--json). */
static void print_record(const fit_record *r)
{
    fr_write_json(stdout, r);
    putchar('\n');
    fflush(stdout);
}

/* Under AUTO, a context on the host path says why on stderr (a device that
 * matches nothing, an unusable PoCL cache directory, no OpenCL at all). */
static void warn_fallback(const runner *R)
{
    brdffit_error why;
    memset(&why, 0, sizeof why);
    if (R->o->context.backend == BRDFFIT_BACKEND_AUTO &&
        brdffit_context_fallback(R->ctx, &why) != BRDFFIT_OK)
        cli_error("warning: fitting on the host (C, one thread), not OpenCL: %s", why.message);
}

/* The context, made for the first material that needs one.  When it cannot
 * be made, this material and every later one fail with the reason (1). */
static int get_context(void *user, brdffit_context **ctx, brdffit_error *err_out)
{
    runner *R = user;
    if (!R->ctx && R->ctx_err.status == BRDFFIT_OK) {
        brdffit_error err;
        memset(&err, 0, sizeof err);
        brdffit_status st = brdffit_context_create(&R->o->context, &R->ctx, &err);
        if (st == BRDFFIT_OK) {
            warn_fallback(R);
        } else {
            R->ctx = NULL;
            R->ctx_err.status = st;
            snprintf(R->ctx_err.message, sizeof R->ctx_err.message,
                     "cannot set up the %s backend: %.1900s",
                     R->o->context.backend == BRDFFIT_BACKEND_OPENCL ? "OpenCL" : "fitting",
                     err.message[0] ? err.message : brdffit_strerror(st));
        }
    }
    *ctx = R->ctx;
    if (R->ctx)
        return 0;
    const cli_material *m = R->m;
    char shown[512];
    *err_out = R->ctx_err;
    snprintf(err_out->message, sizeof err_out->message, "%s: not fitted: %.1500s",
             m->file ? cli_brief(m->file, shown, sizeof shown) : m->name, R->ctx_err.message);
    return 1;
}

/* "brdffit: MATERIAL: fitting MODEL failed: why" on stderr; a build log keeps its lines. */
static void fit_failed_message(const cli_material *m, const fit_record *r)
{
    char head[1200];
    snprintf(head, sizeof head, "%s: fitting %s failed: ", m->name, r->model);
    fputs("brdffit: ", stderr);
    plain_string(stderr, head);
    if (r->status == BRDFFIT_E_KERNEL_BUILD)
        plain_lines(stderr, r->message);
    else
        plain_string(stderr, r->message);
    putc('\n', stderr);
}

/* The sample set and the context are there: read the next file meanwhile,
 * and (the table) the header and, for the demo, the generating parameters' row. */
static void on_ready(void *user, const brdffit_samples *s, brdffit_context *ctx)
{
    runner *R = user;
    const cli_options *o = R->o;
    if (R->next && o->read_ahead) /* after the first context: its set-up may set POCL_CACHE_DIR */
        prefetch_start(&R->pre, R->next, &o->sample, 0, o->models, o->nmodels);
    if (o->json)
        return;
    if (!R->first)
        putchar('\n');
    report_header(stdout, R->m, s, ctx, &o->fit);
    if (R->truth) {
        const brdffit_model_info *gi = brdffit_model_get(R->truth_model);
        brdffit_error err;
        memset(&err, 0, sizeof err);
        double e0 = NAN;
        int note = kernel_note_begin(stderr, ctx, R->truth_model);
        brdffit_status st = brdffit_error_of(ctx, s, R->truth_model, R->truth, &e0, &err);
        kernel_note_end(stderr, note, ctx, R->truth_model);
        if (st != BRDFFIT_OK) {
            R->failures++;
            cli_error("the Error of the generating parameters: %s", err.message);
        }
        report_row(stdout, "truth", gi, R->truth, e0, NULL);
    }
}

/* A record: a failed material, or a fit; shown as a table row or a JSON line. */
static void on_record(void *user, const fit_record *r, const brdffit_fit_result *res)
{
    runner *R = user;
    const cli_options *o = R->o;
    if (r->kind == FR_FAILURE) {
        R->failures++;
        cli_error("%s", r->message);
        if (o->json)
            print_record(r);
        if (R->m->file && r->status != BRDFFIT_OK)
            cli_hint_unreadable_table(R->m->file);
        return;
    }
    brdffit_model model = R->job.models[0];
    brdffit_model_from_name(r->model, &model, NULL);
    if (!res) {
        R->failures++;
        fit_failed_message(R->m, r);
    } else {
        R->fits_ok++;
        if (res->error < R->best_error) {
            R->found = 1;
            R->best_model = model;
            R->best_error = res->error;
        }
    }
    if (o->json) {
        print_record(r);
    } else if (res) {
        report_row(stdout, NULL, brdffit_model_get(model), &res->params, res->error, res);
    } else {
        brdffit_error err;
        err.status = r->status;
        snprintf(err.message, sizeof err.message, "%s", r->message);
        report_row_failed(stdout, model, &err);
    }
}

/* Fit one material (its failures reported, whatever they are): 0 fitted, else 1. */
static int fit_material(runner *R, const cli_material *m, fp_source *src)
{
    R->m = m;
    R->found = 0;
    R->best_error = INFINITY;
    fp_hooks h = { R, get_context, on_ready, NULL, on_record, NULL };
    return fp_fit_table(&R->job, src, &h) == 0 ? 0 : 1;
}

static void print_best(const runner *R, double seconds)
{
    int n = R->o->nmodels;
    if (R->found)
        printf("  best: %s (Error %.5g); %d model%s in %.1f s\n",
               brdffit_model_get(R->best_model)->name, R->best_error, n, n == 1 ? "" : "s",
               seconds);
    else
        printf("  no model could be fitted\n");
}

/* ------------------------------------------------------------------ fit */

/* Fit and report one file, reading the next one (NULL: none) meanwhile. */
static void fit_file(runner *R, const char *path, const char *next, int first)
{
    const cli_options *o = R->o;
    char name[1024];
    cli_material m = { cli_material_name(path, name, sizeof name), path, NULL, o->sample };
    double t0 = brdffit_seconds();
    fp_source src;
    memset(&src, 0, sizeof src);
    src.name = m.name;
    src.path = path;
    snprintf(src.id.path, sizeof src.id.path, "%s", path);
    src.id.size = -1;
    if (prefetch_wait(&R->pre, path)) { /* its table and sample set, made meanwhile */
        src.samples = R->pre.samples;
        src.table = R->pre.table; /* the records' measured albedo */
        R->pre.samples = NULL;
        R->pre.table = NULL;
    }
    prefetch_drop(&R->pre);
    R->next = next;
    R->first = first;
    int failed = fit_material(R, &m, &src) != 0;
    brdffit_table_free(src.table);
    if (failed || o->json)
        return;
    report_legend(stdout, o->models, o->nmodels, (brdffit_metric)o->fit.metric);
    print_best(R, brdffit_seconds() - t0);
}

static int run_fit(const cli_options *o)
{
    runner R;
    runner_init(&R, o);
    for (int fi = 0; fi < o->nfiles; fi++)
        fit_file(&R, o->files[fi], fi + 1 < o->nfiles ? o->files[fi + 1] : NULL, fi == 0);
    prefetch_drop(&R.pre);
    brdffit_context_free(R.ctx);
    if (R.failures)
        fprintf(stderr, "brdffit: %d failure%s (see above); %d fit%s done\n", R.failures,
                R.failures == 1 ? "" : "s", R.fits_ok, R.fits_ok == 1 ? "" : "s");
    return R.failures ? CLI_FAILED : CLI_OK;
}

/* ------------------------------------------------------------------ demo */

static int run_demo(const cli_options *o)
{
    runner R;
    runner_init(&R, o);
    R.first = 1;
    double t0 = brdffit_seconds();
    brdffit_model demo_model;
    const brdffit_params *truth = cli_demo_truth(&demo_model);
    const brdffit_model_info *gi = brdffit_model_get(demo_model);
    char about[512];
    snprintf(about, sizeof about,
             "synthetic, no file: Lambertian + %s lobe at the published Ngan et al. 2005 %s fit\n"
             "  of MERL alum-bronze, stored as a MERL table (%s scale) and fitted back;\n"
             "  row 'truth' = those generating parameters",
             gi->title, gi->title, brdffit_scale_name(o->sample.scale));
    cli_material m = { cli_demo_name(), NULL, about, o->sample };
    R.truth = truth;
    R.truth_model = demo_model;

    fp_source src;
    memset(&src, 0, sizeof src);
    src.name = m.name;
    src.id.size = -1;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    brdffit_status st = cli_demo_table(o->sample.scale, &src.table, &err);
    if (st != BRDFFIT_OK) {
        fit_record r;
        R.m = &m;
        fp_record(&r, FR_FAILURE, &R.job, &src);
        fr_set_failure(&r, st, &err);
        on_record(&R, &r, NULL);
        return CLI_FAILED;
    }
    int failed = fit_material(&R, &m, &src);
    brdffit_table_free(src.table);
    if (failed) {
        brdffit_context_free(R.ctx);
        return CLI_FAILED;
    }
    double total = brdffit_seconds() - t0;
    if (!o->json) {
        report_legend(stdout, o->models, o->nmodels, (brdffit_metric)o->fit.metric);
        printf("\nsummary: %d of %d models fitted in %.1f s on %s",
               R.fits_ok, o->nmodels, total,
               brdffit_context_backend(R.ctx) == BRDFFIT_BACKEND_OPENCL ? "OpenCL" : "the host");
        if (R.found)
            printf("; best %s, Error %.3g%s%s%s\n", brdffit_model_get(R.best_model)->name,
                   R.best_error,
                   R.best_model == demo_model ? " (the generating model, as it should be)"
                                              : " (the data came from ",
                   R.best_model == demo_model ? "" : gi->name,
                   R.best_model == demo_model ? "" : ")");
        else
            printf("; no model could be fitted\n");
    }
    brdffit_context_free(R.ctx);
    return R.failures ? CLI_FAILED : CLI_OK;
}

/* ------------------------------------------------------------------ the subcommands */

static int fit_or_demo(int argc, char **argv, int demo)
{
    cli_options o;
    int rc = cli_parse_options(argc, argv, &o);
    if (rc == CLI_OK) {
        if (demo && o.nfiles > 0)
            rc = cli_usage_error("demo takes no files (got '%s')", o.files[0]);
        else if (!demo && o.nfiles == 0)
            rc = cli_usage_error("fit needs at least one MERL .binary file");
        else if (o.all_metrics)
            rc = cli_usage_error("--metric all is batch's; %s takes one of ngan-l2, log, cube-root",
                                 demo ? "demo" : "fit");
        else
            rc = demo ? run_demo(&o) : run_fit(&o);
    }
    cli_options_free(&o);
    return rc;
}

int cmd_fit(int argc, char **argv)
{
    return fit_or_demo(argc, argv, 0);
}

int cmd_demo(int argc, char **argv)
{
    return fit_or_demo(argc, argv, 1);
}
