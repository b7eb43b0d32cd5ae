/* SPDX-License-Identifier: MIT */
/* bench_metric.c -- part 2's fits under each Error metric: per model, the
 * three fits alternately (a burst of load on the shared machine hits all
 * three), the fastest of each, and log's and cube-root's against ngan-l2's
 * (docs/metrics.md, docs/performance.md); and `batch --metric all` over a
 * few tables, projected to the database (make bench-database). */
#define _DEFAULT_SOURCE /* mkdtemp */
#include "bench_metric.h"
#include "bench_record.h"
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int selected(const char *list, brdffit_model m)
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

/* The fastest of `rounds` fits of m under each metric, alternating. */
static int fastest(brdffit_context *ctx, const brdffit_samples *s, brdffit_model m, int rounds,
                   brdffit_fit_result best[BRDFFIT_METRIC_COUNT])
{
    for (int k = 0; k < BRDFFIT_METRIC_COUNT; k++)
        best[k].seconds = 0;
    for (int r = 0; r < rounds; r++)
        for (int k = 0; k < BRDFFIT_METRIC_COUNT; k++) {
            brdffit_fit_options o;
            brdffit_fit_options_default(&o);
            o.metric = k;
            brdffit_fit_result res;
            brdffit_fit_result_init(&res);
            brdffit_error err;
            if (brdffit_fit(ctx, s, m, &o, &res, &err) != BRDFFIT_OK) {
                fprintf(stderr, "bench: %s\n", err.message);
                return 1;
            }
            if (best[k].seconds <= 0 || res.seconds < best[k].seconds)
                best[k] = res;
        }
    return 0;
}

int bench_metric_fits(brdffit_context *ctx, const brdffit_samples *s, const char *models,
                      int rounds)
{
    printf("\n2b. the fit under each metric, alum-bronze (docs/metrics.md): ngan-l2, log and\n"
           "   cube-root in turn, the fastest of %d each; log and cube-root / ngan-l2\n", rounds);
    printf("%-18s %10s %10s %10s %8s %8s %11s %11s\n", "model", "ngan-l2 s", "log s",
           "cube-root s", "log/l2", "cube/l2", "Error log", "Error cube");
    for (int m = 0; m < brdffit_model_count(); m++) {
        if (!selected(models, (brdffit_model)m))
            continue;
        brdffit_fit_result best[BRDFFIT_METRIC_COUNT];
        if (fastest(ctx, s, (brdffit_model)m, rounds, best) != 0)
            return 1;
        const char *name = brdffit_model_get((brdffit_model)m)->name;
        double l2 = best[0].seconds;
        printf("%-18s %10.3f %10.3f %10.3f %8.2f %8.2f %11.4g %11.4g\n", name, l2,
               best[1].seconds, best[2].seconds, best[1].seconds / l2, best[2].seconds / l2,
               best[1].error, best[2].error);
        for (int k = 0; k < BRDFFIT_METRIC_COUNT; k++) {
            char benchmark[128];
            snprintf(benchmark, sizeof benchmark, "fit/%s/alum-bronze/%s", name,
                     brdffit_metric_get_name((brdffit_metric)k));
            bench_record(benchmark, "fit seconds", best[k].seconds);
            bench_record(benchmark, "Error", best[k].error);
            if (k > 0)
                bench_record(benchmark, "fit / ngan-l2 fit ratio", best[k].seconds / l2);
        }
    }
    return 0;
}

#define BATCH_TABLES 4

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int bench_metric_batch(char (*names)[64], int ntab, const char *models)
{
    const char *cli = getenv("BRDFFIT_CLI");
    char dir[] = "/tmp/brdffit-bench-metric-XXXXXX", cmd[8192], path[1024];
    int n = ntab < BATCH_TABLES ? ntab : BATCH_TABLES;
    if (!cli || n < 1 || !mkdtemp(dir)) {
        fprintf(stderr, "bench: batch --metric all needs BRDFFIT_CLI, tables and a temporary folder\n");
        return 1;
    }
    size_t used = (size_t)snprintf(cmd, sizeof cmd, "'%s' batch", cli);
    for (int t = 0; t < n; t++) {
        if (!tu_merl_table(names[t], path, sizeof path)) {
            fprintf(stderr, "bench: no table %s\n", names[t]);
            tu_remove_tree(dir);
            return 1;
        }
        used += (size_t)snprintf(cmd + used, sizeof cmd - used, " '%s'", path);
    }
    snprintf(cmd + used, sizeof cmd - used,
             " --out '%s/o' --metric all --no-render --no-plot --quiet%s%s >/dev/null", dir,
             models ? " --model " : "", models ? models : "");
    double t0 = wall_now();
    int rc = system(cmd);
    double wall = wall_now() - t0;
    tu_remove_tree(dir);
    if (rc != 0) {
        fprintf(stderr, "bench: %s: exit status %d\n", cmd, rc);
        return 1;
    }
    double all = wall * (double)ntab / (double)n;
    printf("\nbatch --metric all --no-render --no-plot, %d tables x %s: %.1f s wall; the %d tables\n"
           "  at that rate: %.0f s (%.1f min)\n", n, models ? models : "the default models", wall,
           ntab, all, all / 60.0);
    bench_record("database/metric-all", "first tables wall seconds", wall);
    bench_record("database/metric-all", "projected all tables seconds", all);
    return 0;
}
