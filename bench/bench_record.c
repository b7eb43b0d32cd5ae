/* SPDX-License-Identifier: MIT */
/* bench_record.c -- see bench_record.h.  The row's format (date, commit,
 * machine, benchmark, metric, value) is bench/record's alone: this runs it. */
#define _POSIX_C_SOURCE 200809L
#include "bench_record.h"

#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>

extern char **environ;

static const char *record_script;

void bench_record_use(const char *script)
{
    record_script = script;
}

int bench_record(const char *benchmark, const char *metric, double value)
{
    if (!record_script)
        return 0;
    if (!isfinite(value)) {
        fprintf(stderr, "bench: %s %s is not a number; not recorded\n", benchmark, metric);
        return -1;
    }
    char text[32];
    snprintf(text, sizeof text, "%.6g", value);
    char *argv[] = { (char *)record_script, (char *)benchmark, (char *)metric, text, NULL };
    fflush(stdout); /* the child's messages after what was printed */
    pid_t pid;
    int status = -1;
    int rc = posix_spawn(&pid, record_script, NULL, NULL, argv, environ);
    if (rc == 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0)
        return 0;
    fprintf(stderr, "bench: %s %s %s: %s failed (%s)\n", benchmark, metric, text, record_script,
            rc ? strerror(rc) : "its exit status");
    return -1;
}

int bench_record_all(const char *benchmark, const bench_figure *f, int n)
{
    int rc = 0;
    for (int i = 0; i < n; i++)
        if (bench_record(benchmark, f[i].metric, f[i].value) != 0)
            rc = -1;
    return rc;
}

int bench_record_models(const char *what, const char *where, const char *metric,
                        const double v[BRDFFIT_MODEL_COUNT])
{
    int rc = 0;
    for (int m = 0; m < brdffit_model_count(); m++) {
        if (!(v[m] > 0))
            continue;
        char benchmark[256];
        snprintf(benchmark, sizeof benchmark, "%s/%s%s%s", what, brdffit_model_get((brdffit_model)m)->name,
                 where ? "/" : "", where ? where : "");
        if (bench_record(benchmark, metric, v[m]) != 0)
            rc = -1;
    }
    return rc;
}
