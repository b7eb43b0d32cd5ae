/* SPDX-License-Identifier: MIT */
/* bench_metric.c -- part 2's fits under each Error metric: per model, the
 * three fits alternately (a burst of load on the shared machine hits all
 * three), the fastest of each, and log's and cube-root's against ngan-l2's
 * (docs/metrics.md, docs/performance.md). */
#include "bench_metric.h"
#include "bench_record.h"

#include <stdio.h>
#include <string.h>

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
