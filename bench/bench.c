/* SPDX-License-Identifier: MIT */
/* bench.c -- `make bench`: the figures docs/performance.md reports.
 *
 *  1. per model, on the full alum-bronze table: its kernel build time
 *     (brdffit_context_prepare), then one OpenCL data pass (value + Jacobian
 *     moments) over the table's mirror set (what a fit's passes on all
 *     samples read) against the same sums from the plain single-threaded C loop
 *     (compiled -O2), measured back to back in one run (ratio); the value
 *     and full passes against a streaming read of the same buffer
 *     (bench_stream.c: the memory-bandwidth bound), and the host's memcpy and
 *     sum of it;
 *  2. per model, one complete fit (the fastest of 3 identical runs, kernels
 *     built beforehand): wall time, passes, share inside cminpack; then the
 *     He / Cook-Torrance ratio from 3 more runs of each, alternating (the
 *     fastest of each); then each model's fit under ngan-l2, log and
 *     cube-root in turn, the fastest of each and their ratios
 *     (bench_metric.c, docs/metrics.md);
 *  3. `brdffit fit` over 10 materials x every model end to end (bench_cli.c):
 *     wall time, inside and outside the fits, median fits, the projection to
 *     the 100 tables;
 *  4. `brdffit batch` on the same materials (bench_batch.c): its time and the
 *     share outside fitting;
 *  5. a material's renders and plots (bench_render.c; --renders: this alone);
 *  6. only with --database (`make bench-database`, a few minutes): `brdffit fit`
 *     over all 100 tables x every model, once reading ahead and --rounds N
 *     (3) times each fit alone: the wall time, per-model medians, He /
 *     Cook-Torrance and the fits against a stored run (bench_database.c).
 *
 * Then, after parts 1-2, the figures for README (bench_summary.c).  With
 * --record SCRIPT (bench/record) every figure printed is also appended to
 * bench/results.tsv, one row a figure (bench_record.c names them).
 *
 * Tables come from ../shared/tools/merl-table (BRDFFIT_SHARED overrides).
 * Usage: bench_brdffit [--quick] [--models a,b,...] [--materials N] [--parts 1,3,...]
 *                      [--renders] [--record SCRIPT] (--renders: --parts 5)
 *        bench_brdffit --database [--rounds N] [--baseline FILE] [--models a,b,...]
 *                      [--record SCRIPT]
 */
#define _POSIX_C_SOURCE 200809L
#include "pass.h"
#include "testutil.h"
#include "bench_batch.h"
#include "bench_cli.h"
#include "bench_database.h"
#include "bench_metric.h"
#include "bench_record.h"
#include "bench_render.h"
#include "bench_stream.h"
#include "bench_summary.h"
#include "registry.h"
#include "samples.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const materials[10] = {
    "alum-bronze", "blue-rubber", "gold-metallic-paint", "green-metallic-paint2", "chrome",
    "chrome-steel", "blue-acrylic", "red-fabric", "white-marble", "black-oxidized-steel",
};

/* The sample set of a material (tests/testutil.c reads the tables). */
static brdffit_samples *load(const char *name)
{
    brdffit_error err;
    brdffit_samples *s = NULL;
    if (tu_merl_samples(name, NULL, &s, &err) != BRDFFIT_OK) {
        fprintf(stderr, "bench: %s\n", err.message);
        return NULL;
    }
    return s;
}

/* A pass point: lobe parameters p (fit: the fit's d and s, else NULL: d =
 * 0.05, s = 0.1), with forward-difference neighbours 1e-7 away. */
static void point_at(brdffit_model m, const double *p, const brdffit_params *fit, bf_pass_par *pp)
{
    memset(pp, 0, sizeof *pp);
    for (int c = 0; c < 3; c++) {
        pp->d[c] = fit ? fit->d[c] : 0.05;
        pp->s[c] = fit ? fit->s[c] : 0.1;
    }
    pp->lam[0] = 0.645, pp->lam[1] = 0.526, pp->lam[2] = 0.444;
    int np = bf_model_ncoords(m);
    for (int j = 0; j <= np; j++) {
        memcpy(pp->p[j], p, sizeof pp->p[j]);
        if (j > 0) {
            int k = bf_model_coord_param(m, j - 1); /* a parameter coordinate j-1 moves */
            pp->p[j][k] *= 1 + 1e-7;
            pp->inv_h[j - 1] = 1e7;
        }
    }
}

/* A representative pass point: the model's typical start. */
static void point_of(brdffit_model m, bf_pass_par *pp)
{
    double p[BRDFFIT_MAX_LOBE_PARAMS];
    bf_model_start_params(m, p, BRDFFIT_MAX_LOBE_PARAMS);
    point_at(m, p, NULL, pp);
}

static int model_selected(const char *list, brdffit_model m)
{
    if (!list)
        return 1;
    const char *name = brdffit_model_get(m)->name;
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ',') && (p[n] == ',' || p[n] == '\0'))
            return 1;
    return 0;
}

/* Fit model `runs` times (the fit is deterministic) and keep in *best the
 * fastest so far (fit_seconds[m] > 0 once there is one): the fastest run is
 * the least disturbed by the machine's other load. */
static int fit_fastest(brdffit_context *ctx, const brdffit_samples *s, brdffit_model m, int runs,
                       brdffit_fit_result *best, double *fit_seconds)
{
    for (int rep = 0; rep < runs; rep++) {
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        brdffit_error err;
        if (brdffit_fit(ctx, s, m, NULL, &r, &err) != BRDFFIT_OK) {
            fprintf(stderr, "bench: %s\n", err.message);
            return 0;
        }
        if (fit_seconds[m] <= 0 || r.seconds < fit_seconds[m]) {
            *best = r;
            fit_seconds[m] = r.seconds;
        }
    }
    return 1;
}

typedef struct bench_args {
    int quick;            /* --quick: fewer repetitions, 2 materials */
    int nmat;             /* --materials N (1..10)                    */
    const char *models;   /* --models a,b,... or NULL: all            */
    unsigned parts;       /* bit k: part k runs (--parts 1,3; --renders: 5;
                           * --database: 6) */
    int rounds;           /* --rounds N: part 6's runs each fit alone (1..20) */
    const char *baseline; /* --baseline FILE: part 6 compares with its Errors */
    const char *record;   /* --record SCRIPT: each figure appended through it */
} bench_args;

#define PART(k) (1u << (k))

/* "1,3,5": the parts' bits into *parts; 1, or 0 when the list is not one. */
static int parse_parts(const char *list, unsigned *parts)
{
    *parts = 0;
    for (const char *p = list; *p; p++) {
        if (*p >= '1' && *p <= '5' && (p[1] == ',' || p[1] == '\0'))
            *parts |= PART(*p - '0');
        else if (*p != ',')
            return 0;
    }
    return *parts != 0;
}

/* 0, or 2 after printing the usage. */
static int parse_args(int argc, char **argv, bench_args *a)
{
    a->quick = 0;
    a->nmat = 10;
    a->models = NULL;
    a->parts = PART(1) | PART(2) | PART(3) | PART(4) | PART(5);
    a->rounds = 3;
    a->baseline = NULL;
    a->record = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            a->quick = 1, a->nmat = 2;
        else if (!strcmp(argv[i], "--renders"))
            a->parts = PART(5);
        else if (!strcmp(argv[i], "--database"))
            a->parts = PART(6);
        else if (!strcmp(argv[i], "--rounds") && i + 1 < argc)
            a->rounds = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--baseline") && i + 1 < argc)
            a->baseline = argv[++i];
        else if (!strcmp(argv[i], "--record") && i + 1 < argc)
            a->record = argv[++i];
        else if (!strcmp(argv[i], "--parts") && i + 1 < argc && parse_parts(argv[++i], &a->parts))
            ;
        else if (!strcmp(argv[i], "--models") && i + 1 < argc)
            a->models = argv[++i];
        else if (!strcmp(argv[i], "--materials") && i + 1 < argc)
            a->nmat = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: %s [--quick] [--models a,b] [--materials N] [--parts 1,2,..] [--renders]\n"
                            "          [--record SCRIPT]\n"
                            "       %s --database [--rounds N] [--baseline FILE] [--models a,b] [--record SCRIPT]\n",
                    argv[0], argv[0]);
            return 2;
        }
    }
    if (a->nmat < 1 || a->nmat > 10)
        a->nmat = 10;
    if (a->rounds < 1 || a->rounds > 20) {
        fprintf(stderr, "%s: --rounds takes 1 to 20\n", argv[0]);
        return 2;
    }
    return 0;
}

/* Part 1's figures of one model, each the fastest of its repetitions. */
typedef struct pass_times {
    double c_loop, value, full, stream; /* seconds */
} pass_times;

/* One model's passes on an open driver: the C loop (full pass), and, in turn
 * so that a burst of load hits all three, the kernel's value pass, its full
 * pass and the streaming read of the same buffer (bs, opened here on first
 * use).  0, or 1 after printing why. */
static int time_passes(bf_pass_driver *dr, const bf_pass_par *at, bench_stream *bs, int reps,
                       int creps, pass_times *t)
{
    brdffit_error err;
    bf_pass_par pp = *at;
    double mom[BF_NMOM_MAX], ref[BF_NMOM_MAX], t0;
    if (!bs->kernel && bench_stream_open(bs, dr->ctx, dr->samples, dr->items) != 0)
        return 1;
    if (bf_driver_run(dr, 0, &pp, mom, &err) != BRDFFIT_OK || /* warm-up: first touch */
        bf_driver_run(dr, 1, &pp, mom, &err) != BRDFFIT_OK)
        goto failed;
    if (bench_stream_run(bs, dr, &t0) != 0)
        return 1;
    t->c_loop = t->value = t->full = t->stream = 1e30;
    for (int r = 0; r < reps; r++) {
        double ts;
        t0 = bf_now();
        if (bf_driver_run(dr, 0, &pp, mom, &err) != BRDFFIT_OK)
            goto failed;
        t->value = fmin(t->value, bf_now() - t0);
        t0 = bf_now();
        if (bf_driver_run(dr, 1, &pp, mom, &err) != BRDFFIT_OK)
            goto failed;
        t->full = fmin(t->full, bf_now() - t0);
        if (bench_stream_run(bs, dr, &ts) != 0)
            return 1;
        t->stream = fmin(t->stream, ts);
    }
    for (int r = 0; r < creps; r++) {
        t0 = bf_now();
        bf_host_loop(dr->samples, &dr->bins, dr->model, dr->nk, dr->np, &pp, ref);
        t->c_loop = fmin(t->c_loop, bf_now() - t0);
    }
    return 0;
failed:
    fprintf(stderr, "bench: %s\n", err.message);
    return 1;
}

/* Part 1's figures of model m at its typical start or at its fit (at_fit),
 * recorded: pass/MODEL/alum-bronze/start|fit, and the kernel build once,
 * build/MODEL. */
static void record_pass(brdffit_model m, int at_fit, double build_s, const pass_times *t, double bytes)
{
    const char *name = brdffit_model_get(m)->name;
    char benchmark[96];
    if (!at_fit) {
        snprintf(benchmark, sizeof benchmark, "build/%s", name);
        bench_record(benchmark, "kernel build seconds", build_s);
    }
    const bench_figure f[] = {
        { "C loop ms", t->c_loop * 1e3 },
        { "value pass ms", t->value * 1e3 },
        { "full pass ms", t->full * 1e3 },
        { "stream ms", t->stream * 1e3 },
        { "value/stream ratio", t->value / t->stream },
        { "full/stream ratio", t->full / t->stream },
        { "C loop/full ratio", t->c_loop / t->full },
        { "stream GB/s", bytes / t->stream * 1e-9 },
    };
    snprintf(benchmark, sizeof benchmark, "pass/%s/alum-bronze/%s", name, at_fit ? "fit" : "start");
    bench_record_all(benchmark, f, (int)(sizeof f / sizeof f[0]));
}

/* Part 1's row of model m at point pp (its typical start, or its fit:
 * at_fit), printed and recorded; full / stream at the start into sum.  0, or
 * 1 after printing why. */
static int pass_row(brdffit_context *ctx, const brdffit_samples *s, brdffit_model m,
                    const bf_pass_par *pp, int at_fit, bench_stream *bs, int reps, int creps,
                    bench_summary *sum)
{
    double bytes = (double)BF_NFIELDS * sizeof(double) * (double)s->npad;
    brdffit_error err;
    bf_pass_driver dr;
    memset(&dr, 0, sizeof dr); /* closed below whatever happens */
    pass_times t;
    int rc = 0;
    if (brdffit_context_prepare(ctx, m, &err) != BRDFFIT_OK ||
        bf_driver_open(&dr, ctx, s, m, &err) != BRDFFIT_OK) {
        fprintf(stderr, "bench: %s\n", err.message);
        rc = 1;
    } else {
        rc = time_passes(&dr, pp, bs, reps, creps, &t);
    }
    bf_driver_close(&dr);
    if (rc == 0) {
        char name[32];
        snprintf(name, sizeof name, "%s%s", brdffit_model_get(m)->name, at_fit ? " @fit" : "");
        printf("%-18s %7.2f %7.1f %9.1f %9.1f %9.1f %9.1f %7.2fx %7.2fx %6.1fx %9.1f\n", name,
               brdffit_context_build_seconds(ctx, m), bytes / (double)s->n, t.c_loop * 1e3,
               t.value * 1e3, t.full * 1e3, t.stream * 1e3, t.value / t.stream, t.full / t.stream,
               t.c_loop / t.full, bytes / t.stream * 1e-9);
        record_pass(m, at_fit, brdffit_context_build_seconds(ctx, m), &t, bytes);
        if (!at_fit)
            sum->full_per_read[m] = t.full / t.stream;
    }
    return rc;
}

/* 1. per model: its kernel build (brdffit_context_prepare), then one pass of
 * the kernel against the plain C loop, and the kernel's value and full
 * passes against a streaming read of the same bytes (bench_stream.c), at the
 * model's typical start, and He's also at its fit of the table; the host's
 * memcpy and sum of the buffer for context. */
static int bench_passes(brdffit_context *ctx, const brdffit_samples *set, const bench_args *a,
                        bench_summary *sum)
{
    int reps = a->quick ? 2 : 20, creps = a->quick ? 1 : 2; /* passes of ~1 ms: the machine's
                                                              * hiccups need many to miss */
    const brdffit_samples *s = NULL; /* the mirror set: what a fit's passes on all samples read */
    brdffit_error err;
    if (bf_samples_mirror_kept(set, &s, &err) != BRDFFIT_OK) {
        fprintf(stderr, "bench: %s\n", err.message);
        return 1;
    }
    double bytes = (double)BF_NFIELDS * sizeof(double) * (double)s->npad, copy_s, sum_s;
    if (bench_host_memory(s, reps, &copy_s, &sum_s) != 0)
        return 1;
    printf("1. one data pass, alum-bronze: its mirror set, %zu samples for the table's %zu (a fit's\n"
           "   passes on all samples read it); kernel build first.  A pass reads %d doubles per sample:\n"
           "   %.1f bytes per valid sample (padding included), %.1f MB; the host, one thread: memcpy\n"
           "   %.1f ms (%.1f GB/s copied), sum %.1f ms (%.1f GB/s read).  stream: an OpenCL kernel\n"
           "   reading the same buffer as the pass does, and only adding it up (the memory bound).\n"
           "   Each model at its typical start; he @fit at alum-bronze's own He fit, where most\n"
           "   samples are flat and served from the pass's bin rows\n",
           s->n, set->n, (int)BF_NFIELDS, bytes / (double)s->n, bytes * 1e-6, copy_s * 1e3,
           bytes / copy_s * 1e-9,
           sum_s * 1e3, bytes / sum_s * 1e-9);
    const bench_figure host[] = {
        { "memcpy ms", copy_s * 1e3 },
        { "memcpy GB/s", bytes / copy_s * 1e-9 },
        { "sum ms", sum_s * 1e3 },
        { "sum GB/s", bytes / sum_s * 1e-9 },
    };
    bench_record_all("host-memory/alum-bronze", host, (int)(sizeof host / sizeof host[0]));
    printf("%-18s %7s %7s %9s %9s %9s %9s %8s %8s %7s %9s\n", "model", "build s", "B/smp", "C loop ms",
           "value ms", "full ms", "stream ms", "value/st", "full/st", "C/full", "stream GB/s");
    bench_stream bs;
    memset(&bs, 0, sizeof bs);
    int rc = 0;
    for (int m = 0; m < brdffit_model_count() && rc == 0; m++) {
        if (!model_selected(a->models, (brdffit_model)m) || !bf_model_has_lobe((brdffit_model)m))
            continue; /* the glTF models have no data-pass kernel: part 2 times their fits */
        bf_pass_par pp;
        point_of((brdffit_model)m, &pp);
        rc = pass_row(ctx, s, (brdffit_model)m, &pp, 0, &bs, reps, creps, sum);
        if (rc == 0 && m == BRDFFIT_HE) { /* and at its fit, where most samples are flat */
            brdffit_fit_result r;
            brdffit_fit_result_init(&r);
            if (brdffit_fit(ctx, set, BRDFFIT_HE, NULL, &r, &err) != BRDFFIT_OK) {
                fprintf(stderr, "bench: %s\n", err.message);
                rc = 1;
            } else {
                point_at(BRDFFIT_HE, r.params.p, &r.params, &pp);
                rc = pass_row(ctx, s, BRDFFIT_HE, &pp, 1, &bs, reps, creps, sum);
            }
        }
    }
    bench_stream_close(&bs);
    return rc;
}

/* Part 2's figures of model m's fastest fit r, recorded: fit/MODEL/alum-bronze. */
static void record_fit(brdffit_model m, const brdffit_fit_result *r)
{
    const bench_figure f[] = {
        { "fit seconds", r->seconds },
        { "passes count", r->passes },
        { "LM iterations count", r->iterations },
        { "passes seconds", r->seconds_passes },
        { "cminpack percent", 100.0 * r->seconds_solver / r->seconds },
        { "Error", r->error },
    };
    char benchmark[96];
    snprintf(benchmark, sizeof benchmark, "fit/%s/alum-bronze", brdffit_model_get(m)->name);
    bench_record_all(benchmark, f, (int)(sizeof f / sizeof f[0]));
}

/* The glTF models' fits against GGX's, alternating as above: the fastest of
 * each, printed and recorded (fit/gltf/alum-bronze, fit/gltf-ext/...). */
static int gltf_ratios(brdffit_context *ctx, const brdffit_samples *s, const bench_args *a,
                       double *fit_seconds)
{
    static const brdffit_model gm[2] = { BRDFFIT_GLTF, BRDFFIT_GLTF_EXT };
    for (int k = 0; k < 2; k++) {
        if (!(fit_seconds[BRDFFIT_GGX] > 0 && fit_seconds[gm[k]] > 0))
            continue;
        int pairs = a->quick ? 1 : 3;
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        for (int rep = 0; rep < pairs; rep++)
            if (!fit_fastest(ctx, s, BRDFFIT_GGX, 1, &r, fit_seconds) ||
                !fit_fastest(ctx, s, gm[k], 1, &r, fit_seconds))
                return 1;
        const char *name = brdffit_model_get(gm[k])->name;
        double ratio = fit_seconds[gm[k]] / fit_seconds[BRDFFIT_GGX];
        printf("%s fit / ggx fit: %.1fx (%.3f s / %.3f s, the fastest of %d more runs each,\n"
               "  alternating, and the above)\n",
               name, ratio, fit_seconds[gm[k]], fit_seconds[BRDFFIT_GGX], pairs);
        char benchmark[96];
        snprintf(benchmark, sizeof benchmark, "fit/%s/alum-bronze", name);
        bench_record(benchmark, "fit / ggx's fit ratio", ratio);
    }
    return 0;
}

/* 2. per model one complete fit (kernels built beforehand), the fastest of
 * 3; then the He / Cook-Torrance ratio.  Printed, recorded, and into sum. */
static int bench_fits(brdffit_context *ctx, const brdffit_samples *s, const bench_args *a,
                      bench_summary *sum)
{
    double fit_seconds[BRDFFIT_MODEL_COUNT] = { 0 };
    printf("\n2. one complete fit, alum-bronze (default options; kernels built and the set's\n"
           "   screening subsets made beforehand by brdffit_context_prepare and\n"
           "   brdffit_samples_prepare; the fastest of %d runs)\n", a->quick ? 1 : 3);
    printf("%-18s %10s %7s %7s %10s %10s %12s\n", "model", "Error", "passes", "LM it", "fit s",
           "passes s", "cminpack %");
    for (int m = 0; m < brdffit_model_count(); m++) {
        if (!model_selected(a->models, (brdffit_model)m))
            continue;
        brdffit_error err;
        if (brdffit_context_prepare(ctx, (brdffit_model)m, &err) != BRDFFIT_OK ||
            brdffit_samples_prepare(s, (brdffit_model)m, &err) != BRDFFIT_OK) {
            fprintf(stderr, "bench: %s\n", err.message);
            return 1;
        }
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        if (!fit_fastest(ctx, s, (brdffit_model)m, a->quick ? 1 : 3, &r, fit_seconds))
            return 1;
        printf("%-18s %10.3e %7d %7d %10.3f %10.3f %11.3f%%\n", brdffit_model_get((brdffit_model)m)->name,
               r.error, r.passes, r.iterations, r.seconds, r.seconds_passes,
               100.0 * r.seconds_solver / r.seconds);
        record_fit((brdffit_model)m, &r);
        sum->fit_seconds[m] = r.seconds;
        sum->passes[m] = r.passes;
    }

    /* The He / Cook-Torrance ratio: the two fits alternately (so that a burst
     * of load on the shared machine hits both), the fastest of each. */
    if (fit_seconds[BRDFFIT_COOK_TORRANCE] > 0 && fit_seconds[BRDFFIT_HE] > 0) {
        int pairs = a->quick ? 1 : 3;
        brdffit_fit_result r;
        brdffit_fit_result_init(&r);
        for (int rep = 0; rep < pairs; rep++)
            if (!fit_fastest(ctx, s, BRDFFIT_COOK_TORRANCE, 1, &r, fit_seconds) ||
                !fit_fastest(ctx, s, BRDFFIT_HE, 1, &r, fit_seconds))
                return 1;
        printf("he fit / cook-torrance fit: %.1fx (%.3f s / %.3f s, the fastest of %d more runs\n"
               "  each, alternating, and the above)\n",
               fit_seconds[BRDFFIT_HE] / fit_seconds[BRDFFIT_COOK_TORRANCE],
               fit_seconds[BRDFFIT_HE], fit_seconds[BRDFFIT_COOK_TORRANCE], pairs);
        sum->he_per_ct = fit_seconds[BRDFFIT_HE] / fit_seconds[BRDFFIT_COOK_TORRANCE];
        bench_record("fit/he/alum-bronze", "fit / cook-torrance's fit ratio", sum->he_per_ct);
    }
    if (gltf_ratios(ctx, s, a, fit_seconds) != 0)
        return 1;
    return bench_metric_fits(ctx, s, a->models, a->quick ? 1 : 3);
}

int main(int argc, char **argv)
{
    bench_args a;
    if (parse_args(argc, argv, &a) != 0)
        return 2;
    bench_record_use(a.record);
    bench_summary sum;
    memset(&sum, 0, sizeof sum);
    brdffit_error err;
    brdffit_context *ctx = NULL;
    brdffit_samples *s = NULL;
    int rc = 1;
    if (a.parts & (PART(1) | PART(2))) {
        if (brdffit_context_create(NULL, &ctx, &err) != BRDFFIT_OK) {
            fprintf(stderr, "bench: %s\n", err.message);
            goto done;
        }
        printf("brdffit %s bench -- %s\n", brdffit_version(), brdffit_context_describe(ctx));
    }
    if (a.parts & (PART(1) | PART(2))) {
        if (!(s = load("alum-bronze")))
            goto done;
        printf("alum-bronze: %zu valid samples (cutoff 80 deg, standard scale)\n\n", brdffit_samples_count(s));
    }
    if (((a.parts & PART(1)) && bench_passes(ctx, s, &a, &sum) != 0) ||
        ((a.parts & PART(2)) && bench_fits(ctx, s, &a, &sum) != 0))
        goto done;
    brdffit_samples_free(s);
    s = NULL;
    brdffit_context_free(ctx); /* parts 3 and 4 run the program */
    ctx = NULL;
    rc = 0;
    if ((a.parts & PART(3)) && bench_cli_fit(materials, a.nmat, a.models) != 0)
        rc = 1;
    if ((a.parts & PART(4)) && bench_batch(materials, a.nmat, a.models) != 0)
        rc = 1;
    if ((a.parts & PART(5)) && bench_renders(a.quick) != 0)
        rc = 1;
    if ((a.parts & PART(6)) && bench_database(a.rounds, a.models, a.baseline) != 0)
        rc = 1;
    bench_summary_print(&sum);
done:
    brdffit_samples_free(s);
    brdffit_context_free(ctx);
    return rc;
}
