/* SPDX-License-Identifier: MIT */
/* bench.c -- `make bench`: the figures README.md reports.
 *
 *  1. per model, on the full alum-bronze table: one OpenCL data pass (value +
 *     Jacobian moments) against the same sums from the plain single-threaded
 *     C loop (compiled -O2), measured back to back in one run (ratio);
 *  2. per model, one complete fit (the fastest of 3 identical runs): wall
 *     time, passes, share inside cminpack; then the He / Cook-Torrance ratio
 *     from 3 more runs of each, alternating (the fastest of each);
 *  3. all models on 10 materials end to end;
 *  4. `brdffit batch` on the same materials (bench_batch.c): its time and the
 *     share outside fitting.
 *
 * Tables come from ../shared/tools/merl-table (BRDFFIT_SHARED overrides).
 * Usage: bench_brdffit [--quick] [--models a,b,...] [--materials N]
 */
#define _POSIX_C_SOURCE 200809L
#include "pass.h"
#include "testutil.h"
#include "bench_batch.h"
#include "bench_render.h"

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

/* A representative pass point: the model's typical start. */
static void point_of(brdffit_model m, bf_pass_par *pp)
{
    const brdffit_model_info *mi = brdffit_model_get(m);
    memset(pp, 0, sizeof *pp);
    for (int c = 0; c < 3; c++) {
        pp->d[c] = 0.05;
        pp->s[c] = 0.1;
    }
    pp->lam[0] = 0.645, pp->lam[1] = 0.526, pp->lam[2] = 0.444;
    int np = bf_model_ncoords(m);
    for (int j = 0; j <= np; j++) {
        memcpy(pp->p[j], mi->start, sizeof pp->p[j]);
        if (j > 0) {
            int k = (m == BRDFFIT_LAFORTUNE) ? j : j - 1; /* perturb a real parameter */
            pp->p[j][k] *= 1 + 1e-7;
            pp->inv_h[j - 1] = 1e7;
        }
    }
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

int main(int argc, char **argv)
{
    int quick = 0, nmat = 10;
    double fit_seconds[BRDFFIT_MODEL_COUNT] = { 0 };
    const char *models = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            quick = 1, nmat = 2;
        else if (!strcmp(argv[i], "--renders"))
            return bench_renders(0) == 0 ? 0 : 1; /* part 5 alone */
        else if (!strcmp(argv[i], "--models") && i + 1 < argc)
            models = argv[++i];
        else if (!strcmp(argv[i], "--materials") && i + 1 < argc)
            nmat = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: %s [--quick] [--models a,b] [--materials N] [--renders]\n", argv[0]);
            return 2;
        }
    }
    if (nmat < 1 || nmat > 10)
        nmat = 10;

    brdffit_error err;
    brdffit_context *ctx = NULL;
    if (brdffit_context_create(NULL, &ctx, &err) != BRDFFIT_OK) {
        fprintf(stderr, "bench: %s\n", err.message);
        return 1;
    }
    printf("brdffit %s bench -- %s\n", brdffit_version(), brdffit_context_describe(ctx));
    brdffit_samples *s = load("alum-bronze");
    if (!s)
        return 1;
    printf("alum-bronze: %zu valid samples (cutoff 80 deg, standard scale)\n\n", brdffit_samples_count(s));

    /* 1. one pass: kernel vs plain C loop */
    printf("1. one data pass (value + Jacobian moments), alum-bronze\n");
    printf("%-18s %12s %12s %8s\n", "model", "C loop ms", "kernel ms", "ratio");
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        if (!model_selected(models, (brdffit_model)m))
            continue;
        bf_pass_driver dr;
        if (bf_driver_open(&dr, ctx, s, (brdffit_model)m, &err) != BRDFFIT_OK) {
            fprintf(stderr, "bench: %s\n", err.message);
            return 1;
        }
        bf_pass_par pp;
        point_of((brdffit_model)m, &pp);
        double mom[BF_NMOM_MAX], ref[BF_NMOM_MAX];
        bf_driver_run(&dr, 1, &pp, mom, &err); /* warm-up (build, first touch) */
        int reps = quick ? 2 : 5, creps = quick ? 1 : 2;
        double tk = 1e30, tc = 1e30;
        for (int r = 0; r < reps; r++) {
            double t0 = bf_now();
            if (bf_driver_run(&dr, 1, &pp, mom, &err) != BRDFFIT_OK) {
                fprintf(stderr, "bench: %s\n", err.message);
                return 1;
            }
            tk = fmin(tk, bf_now() - t0);
        }
        for (int r = 0; r < creps; r++) {
            double t0 = bf_now();
            bf_host_loop(s, (brdffit_model)m, dr.nk, dr.np, &pp, ref);
            tc = fmin(tc, bf_now() - t0);
        }
        printf("%-18s %12.1f %12.1f %7.1fx\n", brdffit_model_get((brdffit_model)m)->name, tc * 1e3,
               tk * 1e3, tc / tk);
        bf_driver_close(&dr);
    }

    /* 2. one full fit per model (its kernels already built: a build is once per
     * context and model, ~1 s cold, not part of a fit) */
    printf("\n2. one complete fit, alum-bronze (default options; kernels built beforehand;\n"
           "   the fastest of %d runs)\n", quick ? 1 : 3);
    printf("%-18s %10s %7s %7s %10s %10s %12s\n", "model", "Error", "passes", "LM it", "fit s",
           "passes s", "cminpack %");
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        if (!model_selected(models, (brdffit_model)m))
            continue;
        bf_pass_driver warm;
        bf_pass_par wp;
        double wmom[BF_NMOM_MAX];
        point_of((brdffit_model)m, &wp);
        if (bf_driver_open(&warm, ctx, s, (brdffit_model)m, &err) != BRDFFIT_OK ||
            bf_driver_run(&warm, 1, &wp, wmom, &err) != BRDFFIT_OK ||
            bf_driver_run(&warm, 0, &wp, wmom, &err) != BRDFFIT_OK) {
            fprintf(stderr, "bench: %s\n", err.message);
            return 1;
        }
        bf_driver_close(&warm);
        brdffit_fit_result r;
        if (!fit_fastest(ctx, s, (brdffit_model)m, quick ? 1 : 3, &r, fit_seconds))
            return 1;
        printf("%-18s %10.3e %7d %7d %10.3f %10.3f %11.3f%%\n", brdffit_model_get((brdffit_model)m)->name,
               r.error, r.evaluations, r.iterations, r.seconds, r.seconds_passes,
               100.0 * r.seconds_solver / r.seconds);
    }

    /* The He / Cook-Torrance ratio: the two fits alternately (so that a burst
     * of load on the shared machine hits both), the fastest of each. */
    if (fit_seconds[BRDFFIT_COOK_TORRANCE] > 0 && fit_seconds[BRDFFIT_HE] > 0) {
        int pairs = quick ? 1 : 3;
        brdffit_fit_result r;
        for (int rep = 0; rep < pairs; rep++)
            if (!fit_fastest(ctx, s, BRDFFIT_COOK_TORRANCE, 1, &r, fit_seconds) ||
                !fit_fastest(ctx, s, BRDFFIT_HE, 1, &r, fit_seconds))
                return 1;
        printf("he fit / cook-torrance fit: %.1fx (%.3f s / %.3f s, the fastest of %d more runs\n"
               "  each, alternating, and the above)\n",
               fit_seconds[BRDFFIT_HE] / fit_seconds[BRDFFIT_COOK_TORRANCE],
               fit_seconds[BRDFFIT_HE], fit_seconds[BRDFFIT_COOK_TORRANCE], pairs);
    }
    brdffit_samples_free(s);

    /* 3. every model on nmat materials, end to end (read + prepare + fit) */
    printf("\n3. end to end: %d materials x the models (read, prepare, fit)\n", nmat);
    double t0 = bf_now();
    int fits = 0;
    for (int i = 0; i < nmat; i++) {
        double tm = bf_now();
        brdffit_samples *ms = load(materials[i]);
        if (!ms)
            return 1;
        for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
            if (!model_selected(models, (brdffit_model)m))
                continue;
            brdffit_fit_result r;
            if (brdffit_fit(ctx, ms, (brdffit_model)m, NULL, &r, &err) != BRDFFIT_OK) {
                fprintf(stderr, "bench: %s: %s\n", materials[i], err.message);
                return 1;
            }
            fits++;
        }
        printf("  %-24s %6.2f s\n", materials[i], bf_now() - tm);
        brdffit_samples_free(ms);
    }
    double total = bf_now() - t0;
    printf("  total %d fits in %.2f s (%.2f s per fit)\n", fits, total, fits ? total / fits : 0.0);
    brdffit_context_free(ctx);
    int rc = bench_batch(materials, nmat, models) == 0 ? 0 : 1;
    return bench_renders(quick) == 0 ? rc : 1;
}
