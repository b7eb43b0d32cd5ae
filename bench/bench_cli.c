/* SPDX-License-Identifier: MIT */
/* bench_cli.c -- `make bench` part 3: the program end to end.  One
 * `brdffit fit TABLE... --model all --scale flat --json` over the bench's
 * materials (the program, $BRDFFIT_CLI, as a user runs it: one process, one
 * context, every table read and sampled, every kernel built once), timed
 * from outside; its JSON records give each fit's seconds (kernel builds
 * included: `seconds_build`), so that the rest of the wall time is what lies
 * outside the fits (start-up, reading the tables, sample sets, output).
 * The projection to the database's 100 tables scales the per-table part
 * and adds the one-time part (the builds) once.  The program reads the next
 * table in a thread while it fits one, and that thread shares the two cores
 * with the fits it runs beside (over the 100 tables, Cook-Torrance's
 * median fit took 1.4-1.7x its time alone), so the per-model medians come from a
 * second run with --no-read-ahead, where each fit has the machine to itself;
 * the first run's are printed beside them. */
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
    double in_fits, builds, wall;
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
        T->seconds[m][T->n[m]++] = sec - build;
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

/* Run cmd and take its records into T (T->seconds allocated), timing it. */
static int run_cli(const char *cmd, fit_times *T)
{
    static char line[65536];
    double t0 = bf_now();
    FILE *p = popen(cmd, "r");
    if (!p) {
        fprintf(stderr, "bench: cannot run %s\n", cmd);
        return -1;
    }
    while (fgets(line, sizeof line, p))
        take_record(line, T);
    int status = pclose(p);
    T->wall = bf_now() - t0;
    if (status != 0 || T->failed || T->fits == 0) {
        fprintf(stderr, "bench: brdffit fit exited %d with %d fits, %d failed\n", status, T->fits,
                T->failed);
        return -1;
    }
    return 0;
}

/* The per-model medians of T (0 for a model not fitted) into med, printed. */
static double print_medians(fit_times *T, double *med)
{
    double sum = 0.0;
    for (int m = 0; m < brdffit_model_count(); m++) {
        med[m] = T->n[m] ? median(T->seconds[m], T->n[m]) : 0.0;
        sum += med[m];
        if (T->n[m])
            printf(" %s %.3f", brdffit_model_get((brdffit_model)m)->name, med[m]);
    }
    return sum;
}

/* T: the run as a user makes it (reading ahead); A: each fit alone. */
static void print_times(fit_times *T, fit_times *A, int nmat)
{
    double wall = T->wall, outside = wall - T->in_fits, alone_out = A->wall - A->in_fits;
    printf("  %d fits in %.1f s wall: %.1f s inside the fits (of which %.1f s kernel builds),\n"
           "  %.1f s outside them (start-up, reading %d tables, their sample sets, output)\n",
           T->fits, wall, T->in_fits, T->builds, outside, nmat);
    double med[BRDFFIT_MODEL_COUNT], ahead[BRDFFIT_MODEL_COUNT];
    printf("  median fit seconds, builds left out, each fit alone (--no-read-ahead, %.1f s wall):\n ",
           A->wall);
    double sum_med = print_medians(A, med);
    printf("\n  the same in the run above, the next table read beside the fits:\n ");
    print_medians(T, ahead);
    if (med[BRDFFIT_HE] > 0 && med[BRDFFIT_COOK_TORRANCE] > 0 && ahead[BRDFFIT_COOK_TORRANCE] > 0)
        printf("\n  he / cook-torrance, medians: %.1fx alone (%.1fx in the run above)",
               med[BRDFFIT_HE] / med[BRDFFIT_COOK_TORRANCE],
               ahead[BRDFFIT_HE] / ahead[BRDFFIT_COOK_TORRANCE]);
    double per_table = (wall - T->builds) / nmat;
    printf("\n  projected to the %d tables: %.0f s = %d x %.2f s per table (all but the builds)\n"
           "  + %.1f s of builds once; without reading ahead, from the medians: %d x (%.2f s of\n"
           "  fits + %.2f s outside them) + builds = %.0f s\n",
           DATABASE_TABLES, DATABASE_TABLES * per_table + T->builds, DATABASE_TABLES, per_table,
           T->builds, DATABASE_TABLES, sum_med, alone_out / nmat,
           DATABASE_TABLES * (sum_med + alone_out / nmat) + T->builds);
}

int bench_cli_fit(const char *const *materials, int nmat, const char *models)
{
    static char cmd[65536], alone[65600];
    fit_times T, A;
    memset(&T, 0, sizeof T);
    memset(&A, 0, sizeof A);
    int rc = -1;
    if (make_command(materials, nmat, models, cmd, sizeof cmd) != 0)
        goto done;
    snprintf(alone, sizeof alone, "%s --no-read-ahead", cmd);
    for (int m = 0; m < brdffit_model_count(); m++)
        if (!(T.seconds[m] = malloc(MAX_FITS * sizeof(double)))
            || !(A.seconds[m] = malloc(MAX_FITS * sizeof(double))))
            goto done;
    printf("\n3. brdffit fit end to end: %d tables (", nmat);
    for (int i = 0; i < nmat; i++)
        printf("%s%s", i ? ", " : "", materials[i]);
    printf(") x %s, --scale flat --json\n", models ? models : "every model");
    fflush(stdout);
    if (run_cli(cmd, &T) != 0 || run_cli(alone, &A) != 0)
        goto done;
    print_times(&T, &A, nmat);
    rc = 0;
done:
    for (int m = 0; m < brdffit_model_count(); m++) {
        free(T.seconds[m]);
        free(A.seconds[m]);
    }
    return rc;
}
