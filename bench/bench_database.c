/* SPDX-License-Identifier: MIT */
/* bench_database.c -- `make bench-database` (bench_brdffit --database): the
 * whole database's figures, from one command, as docs/performance.md reports them.
 * `brdffit fit` over every table of ../shared/tools/merl-table --list
 * x every model, --scale flat --json, the program as a user runs it (one
 * process, one context, every table read and sampled, every kernel built
 * once):
 *   - once as it runs by default, the next table read while one is fitted:
 *     its wall time (target: the 100 tables x every model in 3 minutes);
 *   - then `rounds` times with --no-read-ahead, each fit having the two
 *     cores to itself (the thread reading ahead slows the fits beside it,
 *     Cook-Torrance's median by 1.4-1.7x: docs/performance.md): each run's
 *     per-model medians and He / Cook-Torrance, then the same from each
 *     table's fastest fit over the rounds, which takes most of the shared
 *     machine's noise out of each fit (target: He's median at most 3x
 *     Cook-Torrance's), and the He fits either side of the median;
 *   - every fit of every run against a stored run's Error (--baseline):
 *     how many end above it by more than 1e-9 relative (target: none).
 * The figures are printed, not judged: the exit status says only whether
 * every run completed.  Last, a summary: the wall time reading ahead and
 * each model's median fit.  Recorded (bench_record.c) as database/MODELS
 * (MODELS: the --model list, or every-model) and database/MODEL. */
#define _POSIX_C_SOURCE 200809L
#include "bench_database.h"
#include "bench_metric.h"
#include "bench_record.h"
#include "cli_run.h"
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_TABLES = 256 };

/* A fit above the stored run's Error by more than this (relative) is worse
 * (bench/fidelity.c's WORSE_TOL). */
#define WORSE_TOL 1e-9

typedef struct stored {
    char material[64];
    brdffit_model model;
    double error;
} stored;

typedef struct baseline {
    stored *rows;
    int n;
    /* over the runs checked: fits compared, worse, and the highest ratio */
    int compared, worse;
    double worst;
    char worst_fit[96];
} baseline;

/* The stored run's rows (material, model, Error) from path; 0, or -1 after
 * printing why. */
static int baseline_read(const char *path, baseline *b)
{
    memset(b, 0, sizeof *b);
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "bench: cannot open the stored run %s\n", path);
        return -1;
    }
    char line[4096], *fl[8];
    int cap = 0, rc = 0;
    while (tu_tsv_next(f, line, sizeof line, fl, 8) >= 3) {
        stored r;
        if (brdffit_model_from_name(fl[1], &r.model, NULL) != BRDFFIT_OK)
            continue; /* the header */
        snprintf(r.material, sizeof r.material, "%.63s", fl[0]);
        r.error = atof(fl[2]);
        if (b->n == cap) {
            cap = cap ? 2 * cap : 1024;
            stored *grown = realloc(b->rows, (size_t)cap * sizeof *grown);
            if (!grown) {
                rc = -1;
                break;
            }
            b->rows = grown;
        }
        b->rows[b->n++] = r;
    }
    fclose(f);
    if (rc != 0 || b->n == 0)
        fprintf(stderr, "bench: %s: %s\n", path, rc ? "out of memory" : "no rows");
    return rc != 0 || b->n == 0 ? -1 : 0;
}

/* Every fit of r that the stored run has, compared with it. */
static void baseline_check(baseline *b, const cli_run *r)
{
    for (int i = 0; i < r->n; i++) {
        const cli_fit *f = &r->fits[i];
        for (int k = 0; k < b->n; k++) {
            const stored *s = &b->rows[k];
            if (s->model != f->model || strcmp(s->material, f->material) != 0 || !(s->error > 0))
                continue;
            double ratio = f->error / s->error;
            b->compared++;
            b->worse += ratio > 1.0 + WORSE_TOL;
            if (b->compared == 1 || ratio > b->worst) {
                b->worst = ratio;
                snprintf(b->worst_fit, sizeof b->worst_fit, "%s %s", f->material,
                         brdffit_model_get(f->model)->name);
            }
            break;
        }
    }
}

/* Each table's fastest fit per model over the runs: best[t][m], 0 = none. */
typedef double fastest[MAX_TABLES][BRDFFIT_MODEL_COUNT];

static void take_fastest(const cli_run *r, char (*names)[64], int ntab, fastest best)
{
    for (int i = 0; i < r->n; i++) {
        const cli_fit *f = &r->fits[i];
        for (int t = 0; t < ntab; t++)
            if (strcmp(names[t], f->material) == 0) {
                double *b = &best[t][f->model];
                if (*b == 0.0 || f->seconds < *b)
                    *b = f->seconds;
                break;
            }
    }
}

/* med's models (0: none) after a space each, then He / Cook-Torrance. */
static void print_medians(const double *med)
{
    for (int m = 0; m < brdffit_model_count(); m++)
        if (med[m] > 0)
            printf(" %s %.4f", brdffit_model_get((brdffit_model)m)->name, med[m]);
    if (med[BRDFFIT_HE] > 0 && med[BRDFFIT_COOK_TORRANCE] > 0)
        printf("; he / cook-torrance %.2fx", med[BRDFFIT_HE] / med[BRDFFIT_COOK_TORRANCE]);
    printf("\n");
}

/* The medians of each table's fastest fits into med, printed and recorded
 * (database/MODEL), and He's fits either side of its median (the median of
 * 100 is the mean of the 50th and 51st). */
static void print_fastest(fastest best, char (*names)[64], int ntab, int rounds,
                          double med[BRDFFIT_MODEL_COUNT])
{
    double v[MAX_TABLES];
    int idx[MAX_TABLES], nhe = 0;
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        int k = 0;
        for (int t = 0; t < ntab; t++)
            if (best[t][m] > 0)
                v[k++] = best[t][m];
        med[m] = cli_median(v, k);
    }
    printf("  each table's fastest fit over the %d runs alone:\n    medians:", rounds);
    print_medians(med);
    bench_record_models("database", NULL, "median fastest-fit seconds", med);
    if (med[BRDFFIT_HE] > 0 && med[BRDFFIT_COOK_TORRANCE] > 0)
        bench_record("database/he", "median fastest-fit / cook-torrance's ratio",
                     med[BRDFFIT_HE] / med[BRDFFIT_COOK_TORRANCE]);
    for (int t = 0; t < ntab; t++)
        if (best[t][BRDFFIT_HE] > 0)
            idx[nhe++] = t;
    for (int i = 1; i < nhe; i++) /* by time: insertion, n <= MAX_TABLES */
        for (int j = i; j > 0 && best[idx[j]][BRDFFIT_HE] < best[idx[j - 1]][BRDFFIT_HE]; j--) {
            int x = idx[j];
            idx[j] = idx[j - 1];
            idx[j - 1] = x;
        }
    if (nhe >= 4) {
        int lo = nhe / 2 - 2;
        printf("    he's fits %d-%d of %d by time:", lo + 1, lo + 4, nhe);
        for (int i = lo; i < lo + 4; i++)
            printf(" %s %.4f", names[idx[i]], best[idx[i]][BRDFFIT_HE]);
        printf("\n");
    }
}

/* One run of cmd: its figures printed and recorded under `benchmark` (the
 * metrics' last words: `how`), its wall time into *wall, its fits into best
 * and b. */
static int one_run(const char *cmd, const char *label, const char *benchmark, const char *how,
                   char (*names)[64], int ntab, fastest best, baseline *b, double *wall)
{
    cli_run r;
    double med[BRDFFIT_MODEL_COUNT];
    if (cli_run_take(cmd, &r) != 0) {
        cli_run_free(&r);
        return -1;
    }
    printf("  %s: %d fits, %.1f s wall, %.1f s inside the fits (%.1f s of kernel builds)\n",
           label, r.n, r.wall, r.in_fits, r.builds);
    char metric[3][64];
    snprintf(metric[0], sizeof metric[0], "wall seconds %s", how);
    snprintf(metric[1], sizeof metric[1], "inside fits seconds %s", how);
    snprintf(metric[2], sizeof metric[2], "kernel builds seconds %s", how);
    const bench_figure f[] = { { metric[0], r.wall }, { metric[1], r.in_fits }, { metric[2], r.builds } };
    bench_record_all(benchmark, f, 3);
    *wall = r.wall;
    if (best && cli_model_medians(&r, med) == 0) {
        printf("    medians:");
        print_medians(med);
        take_fastest(&r, names, ntab, best);
    }
    if (b->rows)
        baseline_check(b, &r);
    cli_run_free(&r);
    fflush(stdout);
    return 0;
}

/* The figures against the stored run, printed and recorded under benchmark. */
static void print_baseline(const baseline *b, const char *path, int runs, const char *benchmark)
{
    printf("  against the stored run %s: %d fits compared over the %d runs, %d above it by more\n"
           "  than 1e-9 relative; the highest %s, 1 %+.1e\n",
           path, b->compared, runs, b->worse, b->worst_fit, b->worst - 1.0);
    const bench_figure f[] = {
        { "fits compared with the stored run count", b->compared },
        { "fits above the stored run count", b->worse },
        { "highest Error / stored - 1", b->worst - 1.0 }, /* as printed: the ratio to 6 digits is 1 */
    };
    bench_record_all(benchmark, f, b->compared > 0 ? 3 : 1);
}

/* The summary: the wall time as it runs by default, each model's median fit. */
static void print_summary(int ntab, const char *models, double wall, const double *med, int rounds)
{
    printf("\nthe whole database, %d tables x %s: %.1f s wall (reading ahead, as it runs by\n"
           "default); median seconds per fit (each table's fastest of %d runs alone):\n ",
           ntab, models ? models : "every model", wall, rounds);
    print_medians(med);
}

int bench_database(int rounds, const char *models, const char *baseline_path)
{
    static char names[MAX_TABLES][64];
    static fastest best;
    baseline b = { 0 };
    char benchmark[256];
    double wall_ahead = 0.0, wall, med[BRDFFIT_MODEL_COUNT] = { 0 };
    snprintf(benchmark, sizeof benchmark, "database/%s", models ? models : "every-model");
    char *cmd = NULL, *alone = NULL;
    const char *list[MAX_TABLES];
    int rc = -1, ntab = cli_material_list(names, MAX_TABLES);
    if (ntab < 0 || (baseline_path && baseline_read(baseline_path, &b) != 0))
        goto done;
    for (int t = 0; t < ntab; t++)
        list[t] = names[t];
    if (cli_command(list, ntab, models, &cmd, &alone) != 0)
        goto done;
    memset(best, 0, sizeof best);
    printf("\nthe whole database: brdffit fit over the %d tables x %s, --scale flat --json\n", ntab,
           models ? models : "every model");
    fflush(stdout);
    if (one_run(cmd, "reading ahead (as it runs by default)", benchmark, "reading ahead", names, ntab,
                NULL, &b, &wall_ahead) != 0)
        goto done;
    for (int k = 0; k < rounds; k++) {
        char label[64];
        snprintf(label, sizeof label, "each fit alone (--no-read-ahead), run %d of %d", k + 1, rounds);
        if (one_run(alone, label, benchmark, "alone", names, ntab, best, &b, &wall) != 0)
            goto done;
    }
    print_fastest(best, names, ntab, rounds, med);
    if (b.rows)
        print_baseline(&b, baseline_path, rounds + 1, benchmark);
    print_summary(ntab, models, wall_ahead, med, rounds);
    if (bench_metric_batch(names, ntab, models) != 0)
        goto done;
    rc = 0;
done:
    free(b.rows);
    free(cmd);
    free(alone);
    return rc;
}
