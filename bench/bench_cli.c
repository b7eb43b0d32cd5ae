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
 * median fit takes 1.4-1.7x its time alone), so the per-model medians come from a
 * second run with --no-read-ahead, where each fit has the machine to itself;
 * the first run's are printed beside them. */
#define _POSIX_C_SOURCE 200809L
#include "bench_cli.h"
#include "bench_record.h"
#include "cli_run.h"

#include <stdio.h>
#include <stdlib.h>

enum { DATABASE_TABLES = 100 };

/* r's per-model medians into med, printed after a space each; their sum. */
static double print_medians(const cli_run *r, double *med)
{
    double sum = 0.0;
    if (cli_model_medians(r, med) != 0)
        return 0.0;
    for (int m = 0; m < brdffit_model_count(); m++) {
        sum += med[m];
        if (med[m] > 0)
            printf(" %s %.3f", brdffit_model_get((brdffit_model)m)->name, med[m]);
    }
    return sum;
}

/* The figures print_times prints, recorded: program-fit/MODELS/N-tables
 * (MODELS: the --model list, or every-model), program-fit/MODEL/N-tables,
 * and the projection program-fit/MODELS/100-tables. */
static void record_times(const cli_run *T, const cli_run *A, const char *models, int nmat,
                         const double *med, const double *ahead, double projected,
                         double projected_alone)
{
    char where[32], benchmark[256];
    snprintf(where, sizeof where, "%d-tables", nmat);
    snprintf(benchmark, sizeof benchmark, "program-fit/%s/%s", models ? models : "every-model", where);
    const bench_figure f[] = {
        { "wall seconds", T->wall },
        { "inside fits seconds", T->in_fits },
        { "kernel builds seconds", T->builds },
        { "outside fits seconds", T->wall - T->in_fits },
        { "wall seconds alone", A->wall },
    };
    bench_record_all(benchmark, f, (int)(sizeof f / sizeof f[0]));
    bench_record_models("program-fit", where, "median fit seconds alone", med);
    bench_record_models("program-fit", where, "median fit seconds reading ahead", ahead);
    if (med[BRDFFIT_HE] > 0 && med[BRDFFIT_COOK_TORRANCE] > 0) {
        snprintf(benchmark, sizeof benchmark, "program-fit/he/%s", where);
        bench_record(benchmark, "median fit / cook-torrance's ratio alone",
                     med[BRDFFIT_HE] / med[BRDFFIT_COOK_TORRANCE]);
    }
    snprintf(benchmark, sizeof benchmark, "program-fit/%s/%d-tables", models ? models : "every-model",
             DATABASE_TABLES);
    bench_record(benchmark, "projected wall seconds", projected);
    bench_record(benchmark, "projected wall seconds alone", projected_alone);
}

/* T: the run as a user makes it (reading ahead); A: each fit alone.
 * Printed and recorded. */
static void print_times(const cli_run *T, const cli_run *A, const char *models, int nmat)
{
    double wall = T->wall, outside = wall - T->in_fits, alone_out = A->wall - A->in_fits;
    printf("  %d fits in %.1f s wall: %.1f s inside the fits (of which %.1f s kernel builds),\n"
           "  %.1f s outside them (start-up, reading %d tables, their sample sets, output)\n",
           T->n, wall, T->in_fits, T->builds, outside, nmat);
    double med[BRDFFIT_MODEL_COUNT] = { 0 }, ahead[BRDFFIT_MODEL_COUNT] = { 0 };
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
    double projected = DATABASE_TABLES * per_table + T->builds;
    double projected_alone = DATABASE_TABLES * (sum_med + alone_out / nmat) + T->builds;
    printf("\n  projected to the %d tables: %.0f s = %d x %.2f s per table (all but the builds)\n"
           "  + %.1f s of builds once; without reading ahead, from the medians: %d x (%.2f s of\n"
           "  fits + %.2f s outside them) + builds = %.0f s\n",
           DATABASE_TABLES, projected, DATABASE_TABLES, per_table, T->builds, DATABASE_TABLES,
           sum_med, alone_out / nmat, projected_alone);
    record_times(T, A, models, nmat, med, ahead, projected, projected_alone);
}

int bench_cli_fit(const char *const *materials, int nmat, const char *models)
{
    cli_run T = { 0 }, A = { 0 };
    char *cmd = NULL, *alone = NULL;
    int rc = -1;
    if (cli_command(materials, nmat, models, &cmd, &alone) != 0)
        goto done;
    printf("\n3. brdffit fit end to end: %d tables (", nmat);
    for (int i = 0; i < nmat; i++)
        printf("%s%s", i ? ", " : "", materials[i]);
    printf(") x %s, --scale flat --json\n", models ? models : "every model");
    fflush(stdout);
    if (cli_run_take(cmd, &T) != 0 || cli_run_take(alone, &A) != 0)
        goto done;
    print_times(&T, &A, models, nmat);
    rc = 0;
done:
    cli_run_free(&T);
    cli_run_free(&A);
    free(cmd);
    free(alone);
    return rc;
}
