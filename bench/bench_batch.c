/* SPDX-License-Identifier: MIT */
/* bench_batch.c -- `make bench` part 4: `brdffit batch` over the bench's
 * materials end to end (the program, $BRDFFIT_CLI, into a fresh directory),
 * and the share of its time spent outside fitting (reading and hashing the
 * tables, sample sets, renders, plots, pages), as the batch itself reports
 * it on stderr.  Target: <= 10% of the total.  Recorded as
 * program-batch/MODELS/N-tables (MODELS: the --model list, or every-model). */
#define _POSIX_C_SOURCE 200809L
#include "bench_batch.h"
#include "bench_record.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int bench_batch(const char *const *materials, int nmat, const char *models)
{
    const char *cli = getenv("BRDFFIT_CLI");
    const char *root = getenv("BRDFFIT_SHARED");
    const char *tmp = getenv("TMPDIR");
    char dir[1024], list[1200], cmd[8192], log[1200];
    snprintf(dir, sizeof dir, "%s/brdffit-bench-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!cli || !*cli || !mkdtemp(dir)) {
        fprintf(stderr, "bench: the batch part needs BRDFFIT_CLI (make bench sets it)\n");
        return -1;
    }
    snprintf(list, sizeof list, "%s/list", dir);
    snprintf(log, sizeof log, "%s/stderr", dir);
    FILE *l = fopen(list, "w");
    if (!l)
        return -1;
    for (int i = 0; i < nmat; i++) {
        snprintf(cmd, sizeof cmd, "'%s/tools/merl-table' '%s'", root && *root ? root : "../shared",
                 materials[i]);
        FILE *p = popen(cmd, "r");
        char path[1024] = "";
        if (!p || !fgets(path, sizeof path, p) || pclose(p) != 0) {
            fprintf(stderr, "bench: merl-table %s failed\n", materials[i]);
            fclose(l);
            return -1;
        }
        fputs(path, l);
    }
    fclose(l);
    snprintf(cmd, sizeof cmd, "'%s' batch @'%s' --out '%s/report' %s%s >/dev/null 2>'%s'", cli,
             list, dir, models ? "--model " : "", models ? models : "", log);
    printf("\n4. brdffit batch: %d materials x %s, renders, plots and pages\n", nmat,
           models ? models : "every model");
    fflush(stdout);
    int rc = system(cmd);
    FILE *e = fopen(log, "r");
    char line[2048];
    double total = -1, fitting = -1;
    int fits = 0;
    while (e && fgets(line, sizeof line, e)) {
        const char *p = strstr(line, " fits this run; "), *q1 = strstr(line, " fit this run; ");
        if (!p)
            p = q1; /* "1 fit this run" */
        if (p && sscanf(strstr(p, " this run; "), " this run; %lf s, of which %lf s fitting", &total,
                        &fitting) == 2) {
            const char *q = p;
            while (q > line && q[-1] >= '0' && q[-1] <= '9')
                q--;
            fits = atoi(q);
        }
    }
    if (e)
        fclose(e);
    if (rc != 0 || total <= 0) {
        fprintf(stderr, "bench: the batch failed (exit %d); its stderr is in %s\n", rc, log);
        return -1;
    }
    printf("  %d fits in %.1f s, of which %.1f s fitting: %.1f%% outside fitting (reading, renders,\n"
           "  plots, pages; target <= 10%%)\n",
           fits, total, fitting, 100 * (total - fitting) / total);
    const bench_figure f[] = {
        { "fits count", fits },
        { "wall seconds", total },
        { "fitting seconds", fitting },
        { "outside fitting percent", 100 * (total - fitting) / total },
    };
    char benchmark[256];
    snprintf(benchmark, sizeof benchmark, "program-batch/%s/%d-tables", models ? models : "every-model",
             nmat);
    bench_record_all(benchmark, f, (int)(sizeof f / sizeof f[0]));
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "bench: could not remove %s\n", dir);
    return 0;
}
