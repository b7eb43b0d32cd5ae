/* SPDX-License-Identifier: MIT */
/* cmd_fit.c -- `brdffit fit` and `brdffit demo`: read (or synthesise) each
 * table, make its sample set, and fit the requested models with ONE context;
 * the next file's table is read in a thread while one is fitted (prefetch.h). */
#include "cli.h"
#include "prefetch.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct runner {
    const cli_options *o;
    brdffit_context *ctx;    /* created at the first sample set, reused for every fit */
    brdffit_error ctx_err;   /* why no context could be made: each later material fails with it */
    int failures;            /* files and fits that failed */
    int fits_ok;
    table_prefetch pre;      /* the next file's sample set, made meanwhile */
} runner;

/* The best fit of one material. */
typedef struct best_fit {
    int found;
    brdffit_model model;
    double error;
} best_fit;

/* Report a failure that stops a whole material (stderr, and a JSON record). */
static void material_failed(runner *R, const cli_material *m, const brdffit_error *err)
{
    R->failures++;
    cli_error("%s", err->message[0] ? err->message : brdffit_strerror(err->status));
    if (R->o->json)
        report_json_failure(stdout, m, err->status, err);
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
 * be made, this material and every later one get a failure record with the
 * reason (-1). */
static int ensure_context(runner *R, const cli_material *m)
{
    if (!R->ctx && R->ctx_err.status == BRDFFIT_OK) {
        brdffit_error err;
        memset(&err, 0, sizeof err);
        brdffit_status st = brdffit_context_create(&R->o->context, &R->ctx, &err);
        if (st == BRDFFIT_OK) {
            warn_fallback(R);
            return 0;
        }
        R->ctx = NULL;
        R->ctx_err.status = st;
        snprintf(R->ctx_err.message, sizeof R->ctx_err.message, "cannot set up the %s backend: %.1900s",
                 R->o->context.backend == BRDFFIT_BACKEND_OPENCL ? "OpenCL" : "fitting",
                 err.message[0] ? err.message : brdffit_strerror(st));
    }
    if (R->ctx)
        return 0;
    brdffit_error err = R->ctx_err;
    char shown[512];
    snprintf(err.message, sizeof err.message, "%s: not fitted: %.1500s",
             m->file ? cli_brief(m->file, shown, sizeof shown) : m->name, R->ctx_err.message);
    material_failed(R, m, &err);
    return -1;
}

/* "brdffit: MATERIAL: fitting MODEL failed: why" on stderr; a build log keeps its lines. */
static void fit_failed_message(const cli_material *m, brdffit_model model, const brdffit_error *err)
{
    char head[1200];
    snprintf(head, sizeof head, "%s: fitting %s failed: ", m->name, brdffit_model_get(model)->name);
    fputs("brdffit: ", stderr);
    plain_string(stderr, head);
    const char *why = err->message[0] ? err->message : brdffit_strerror(err->status);
    if (err->status == BRDFFIT_E_KERNEL_BUILD)
        plain_lines(stderr, why);
    else
        plain_string(stderr, why);
    putc('\n', stderr);
}

/* Fit every requested model to one sample set and report each fit. */
static best_fit fit_models(runner *R, const cli_material *m, const brdffit_samples *s)
{
    const cli_options *o = R->o;
    best_fit best = { 0, BRDFFIT_WARD, INFINITY };
    for (int i = 0; i < o->nmodels; i++) {
        brdffit_model model = o->models[i];
        brdffit_fit_result r;
        brdffit_error err;
        brdffit_fit_result_init(&r);
        memset(&err, 0, sizeof err);
        int note = kernel_note_begin(stderr, R->ctx, model);
        brdffit_status st = brdffit_fit(R->ctx, s, model, &o->fit, &r, &err);
        kernel_note_end(stderr, note, R->ctx, model);
        if (st != BRDFFIT_OK) {
            err.status = st;
            R->failures++;
            fit_failed_message(m, model, &err);
        } else {
            R->fits_ok++;
            if (r.error < best.error) {
                best.found = 1;
                best.model = model;
                best.error = r.error;
            }
        }
        if (o->json)
            report_json_fit(stdout, m, R->ctx, s, model, st, &err, st == BRDFFIT_OK ? &r : NULL);
        else if (st == BRDFFIT_OK)
            report_row(stdout, NULL, brdffit_model_get(model), &r.params, r.error, &r);
        else
            report_row_failed(stdout, model, &err);
    }
    return best;
}

static void print_best(const best_fit *b, int nmodels, double seconds)
{
    if (b->found)
        printf("  best: %s (Error %.5g); %d model%s in %.1f s\n", brdffit_model_get(b->model)->name,
               b->error, nmodels, nmodels == 1 ? "" : "s", seconds);
    else
        printf("  no model could be fitted\n");
}

/* ------------------------------------------------------------------ fit */

/* The sample set of one MERL file, or NULL (failure reported): the
 * prefetch's when it made it, else made here (where a failure is reported). */
static brdffit_samples *file_samples(runner *R, const cli_material *m)
{
    brdffit_error err;
    memset(&err, 0, sizeof err);
    brdffit_samples *taken = NULL;
    if (prefetch_wait(&R->pre, m->file)) {
        taken = R->pre.samples;
        R->pre.samples = NULL;
    }
    prefetch_drop(&R->pre); /* what it held besides: its table */
    if (taken)
        return taken;
    brdffit_table *table = NULL;
    brdffit_status st = brdffit_table_read(m->file, &table, &err);
    if (st != BRDFFIT_OK) {
        err.status = st;
        material_failed(R, m, &err);
        cli_hint_unreadable_table(m->file);
        return NULL;
    }
    brdffit_samples *samples = NULL;
    st = brdffit_samples_create(table, &R->o->sample, &samples, &err);
    brdffit_table_free(table); /* 35 MB; the sample set holds what the fits need */
    if (st != BRDFFIT_OK) {
        err.status = st;
        /* the library's sample messages do not name the file: add it */
        char msg[BRDFFIT_MESSAGE_MAX], shown[512];
        snprintf(msg, sizeof msg, "%s: %.1500s", cli_brief(m->file, shown, sizeof shown), err.message);
        memcpy(err.message, msg, sizeof msg);
        material_failed(R, m, &err);
        return NULL;
    }
    samples_prepare(samples, R->o->models, R->o->nmodels); /* as the prefetch does */
    return samples;
}

/* Fit and report one file (its failures reported, whatever they are),
 * reading the next one (NULL: none) meanwhile. */
static void fit_file(runner *R, const char *path, const char *next, int first)
{
    const cli_options *o = R->o;
    char name[1024];
    cli_material m = { cli_material_name(path, name, sizeof name), path, NULL, o->sample };
    double t0 = brdffit_seconds();
    brdffit_samples *samples = file_samples(R, &m);
    if (!samples)
        return;
    if (ensure_context(R, &m) != 0) {
        brdffit_samples_free(samples);
        return;
    }
    if (next && o->read_ahead) /* after the first context: its set-up may set POCL_CACHE_DIR */
        prefetch_start(&R->pre, next, &o->sample, 0, o->models, o->nmodels);
    if (!o->json) {
        if (!first)
            putchar('\n');
        report_header(stdout, &m, samples, R->ctx, &o->fit);
    }
    best_fit best = fit_models(R, &m, samples);
    if (!o->json) {
        report_legend(stdout, o->models, o->nmodels);
        print_best(&best, o->nmodels, brdffit_seconds() - t0);
    }
    brdffit_samples_free(samples);
}

static int run_fit(const cli_options *o)
{
    runner R;
    memset(&R, 0, sizeof R);
    R.o = o;
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
    memset(&R, 0, sizeof R);
    R.o = o;
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
    brdffit_error err;
    memset(&err, 0, sizeof err);

    brdffit_table *table = NULL;
    brdffit_samples *samples = NULL;
    brdffit_status st = cli_demo_table(o->sample.scale, &table, &err);
    if (st == BRDFFIT_OK)
        st = brdffit_samples_create(table, &o->sample, &samples, &err);
    brdffit_table_free(table);
    if (st != BRDFFIT_OK) {
        err.status = st;
        material_failed(&R, &m, &err);
        return CLI_FAILED;
    }
    if (ensure_context(&R, &m) != 0) {
        brdffit_samples_free(samples);
        return CLI_FAILED;
    }

    if (!o->json) {
        report_header(stdout, &m, samples, R.ctx, &o->fit);
        double e0 = NAN;
        int note = kernel_note_begin(stderr, R.ctx, demo_model);
        st = brdffit_error_of(R.ctx, samples, demo_model, truth, &e0, &err);
        kernel_note_end(stderr, note, R.ctx, demo_model);
        if (st != BRDFFIT_OK) {
            R.failures++;
            cli_error("the Error of the generating parameters: %s", err.message);
        }
        report_row(stdout, "truth", gi, truth, e0, NULL);
    }
    best_fit best = fit_models(&R, &m, samples);
    double total = brdffit_seconds() - t0;
    if (!o->json) {
        report_legend(stdout, o->models, o->nmodels);
        printf("\nsummary: %d of %d models fitted in %.1f s on %s",
               R.fits_ok, o->nmodels, total,
               brdffit_context_backend(R.ctx) == BRDFFIT_BACKEND_OPENCL ? "OpenCL" : "the host");
        if (best.found)
            printf("; best %s, Error %.3g%s%s%s\n", brdffit_model_get(best.model)->name, best.error,
                   best.model == demo_model ? " (the generating model, as it should be)"
                                            : " (the data came from ",
                   best.model == demo_model ? "" : gi->name, best.model == demo_model ? "" : ")");
        else
            printf("; no model could be fitted\n");
    }
    brdffit_samples_free(samples);
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
