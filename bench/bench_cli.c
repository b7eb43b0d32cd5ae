/* SPDX-License-Identifier: MIT */
/* bench_cli.c -- `make bench` part 3: the program end to end.  One
 * `brdffit fit TABLE... --model all --scale flat --json` over the bench's
 * materials (the program, $BRDFFIT_CLI, as a user runs it: one process, one
 * context, every table read and sampled, every kernel built once), timed
 * from outside; its JSON records give each fit's seconds (kernel builds
 * included: `seconds_build`), so that the rest of the wall time is what lies
 * outside the fits (start-up, reading the tables, sample sets, output).
 * The projection to the database's 100 tables scales the per-table part
 * and adds the one-time part (the builds) once. */
#define _POSIX_C_SOURCE 200809L
#include "bench_cli.h"
#include "internal.h"
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_FITS = 1024, DATABASE_TABLES = 100 };

typedef struct fit_times {
    double *seconds[BRDFFIT_MODEL_COUNT]; /* per model, one per table */
    int n[BRDFFIT_MODEL_COUNT];
    double in_fits, builds;
    int fits, failed;
} fit_times;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* One JSON record of `fit --json` into T. */
static void take_record(const char *line, fit_times *T)
{
    char name[64], status[32];
    double sec = 0, build = 0;
    brdffit_model m;
    if (!tu_json_get_string(line, "model", name, sizeof name) ||
        brdffit_model_from_name(name, &m, NULL) != BRDFFIT_OK ||
        !tu_json_get_string(line, "status", status, sizeof status) ||
        !tu_json_get_number(line, "seconds", &sec)) {
        T->failed++;
        return;
    }
    if (strcmp(status, "ok") != 0 && strcmp(status, "limit") != 0) {
        T->failed++;
        return;
    }
    tu_json_get_number(line, "seconds_build", &build);
    T->fits++;
    T->in_fits += sec;
    T->builds += build;
    if (T->n[m] < MAX_FITS)
        T->seconds[m][T->n[m]++] = sec;
}

/* The command: the program, the tables, the options. */
static int make_command(const char *const *materials, int nmat, const char *models, char *cmd,
                        size_t len)
{
    const char *cli = getenv("BRDFFIT_CLI");
    if (!cli || !*cli) {
        fprintf(stderr, "bench: part 3 needs BRDFFIT_CLI (make bench sets it)\n");
        return -1;
    }
    size_t o = (size_t)snprintf(cmd, len, "'%s' fit", cli);
    for (int i = 0; i < nmat && o < len; i++) {
        char path[1024];
        if (!tu_merl_table(materials[i], path, sizeof path)) {
            fprintf(stderr, "bench: merl-table %s failed\n", materials[i]);
            return -1;
        }
        o += (size_t)snprintf(cmd + o, len - o, " '%s'", path);
    }
    if (o < len)
        o += (size_t)snprintf(cmd + o, len - o, " --model %s --scale flat --json", models ? models : "all");
    return o < len ? 0 : -1;
}

static void print_times(fit_times *T, int nmat, double wall)
{
    double outside = wall - T->in_fits, sum_med = 0.0;
    printf("  %d fits in %.1f s wall: %.1f s inside the fits (of which %.1f s kernel builds),\n"
           "  %.1f s outside them (start-up, reading %d tables, their sample sets, output)\n",
           T->fits, wall, T->in_fits, T->builds, outside, nmat);
    printf("  median fit seconds:");
    double med[BRDFFIT_MODEL_COUNT] = { 0 };
    for (int m = 0; m < brdffit_model_count(); m++)
        if (T->n[m]) {
            med[m] = median(T->seconds[m], T->n[m]);
            sum_med += med[m];
            printf(" %s %.3f", brdffit_model_get((brdffit_model)m)->name, med[m]);
        }
    if (med[BRDFFIT_HE] > 0 && med[BRDFFIT_COOK_TORRANCE] > 0)
        printf("\n  he / cook-torrance, medians: %.1fx", med[BRDFFIT_HE] / med[BRDFFIT_COOK_TORRANCE]);
    double per_table = (wall - T->builds) / nmat;
    printf("\n  projected to the %d tables: %.0f s = %d x %.2f s per table (all but the builds)\n"
           "  + %.1f s of builds once; from the medians: %d x (%.2f s of fits + %.2f s outside)\n"
           "  + builds = %.0f s\n",
           DATABASE_TABLES, DATABASE_TABLES * per_table + T->builds, DATABASE_TABLES, per_table,
           T->builds, DATABASE_TABLES, sum_med, outside / nmat,
           DATABASE_TABLES * (sum_med + outside / nmat) + T->builds);
}

int bench_cli_fit(const char *const *materials, int nmat, const char *models)
{
    static char cmd[65536];
    fit_times T;
    memset(&T, 0, sizeof T);
    int rc = -1;
    FILE *p = NULL;
    if (make_command(materials, nmat, models, cmd, sizeof cmd) != 0)
        goto done;
    for (int m = 0; m < brdffit_model_count(); m++)
        if (!(T.seconds[m] = malloc(MAX_FITS * sizeof(double))))
            goto done;
    printf("\n3. brdffit fit end to end: %d tables (", nmat);
    for (int i = 0; i < nmat; i++)
        printf("%s%s", i ? ", " : "", materials[i]);
    printf(") x %s, --scale flat --json\n", models ? models : "every model");
    fflush(stdout);
    double t0 = bf_now();
    if (!(p = popen(cmd, "r"))) {
        fprintf(stderr, "bench: cannot run %s\n", cmd);
        goto done;
    }
    static char line[65536];
    while (fgets(line, sizeof line, p))
        take_record(line, &T);
    int status = pclose(p);
    double wall = bf_now() - t0;
    p = NULL;
    if (status != 0 || T.failed || T.fits == 0) {
        fprintf(stderr, "bench: brdffit fit exited %d with %d fits, %d failed\n", status, T.fits, T.failed);
        goto done;
    }
    print_times(&T, nmat, wall);
    rc = 0;
done:
    if (p)
        pclose(p);
    for (int m = 0; m < brdffit_model_count(); m++)
        free(T.seconds[m]);
    return rc;
}
