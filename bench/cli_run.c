/* SPDX-License-Identifier: MIT */
/* cli_run.c -- see cli_run.h. */
#define _POSIX_C_SOURCE 200809L
#include "cli_run.h"
#include "internal.h"
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_command(const char *const *materials, int nmat, const char *models, char **cmd,
                char **alone)
{
    *cmd = *alone = NULL;
    const char *cli = getenv("BRDFFIT_CLI");
    if (!cli || !*cli) {
        fprintf(stderr, "bench: running the program needs BRDFFIT_CLI (make bench sets it)\n");
        return -1;
    }
    size_t len = strlen(cli) + 128 + (models ? strlen(models) : 0) + (size_t)nmat * 1040;
    char *s = malloc(len);
    if (!s) {
        fprintf(stderr, "bench: out of memory for the command\n");
        return -1;
    }
    size_t o = (size_t)snprintf(s, len, "'%s' fit", cli);
    for (int i = 0; i < nmat; i++) {
        char path[1024];
        if (!tu_merl_table(materials[i], path, sizeof path)) {
            fprintf(stderr, "bench: merl-table %s failed\n", materials[i]);
            free(s);
            return -1;
        }
        o += (size_t)snprintf(s + o, len - o, " '%s'", path);
    }
    o += (size_t)snprintf(s + o, len - o, " --model %s --scale flat --json", models ? models : "all");
    char *a = malloc(o + sizeof " --no-read-ahead");
    if (!a) {
        fprintf(stderr, "bench: out of memory for the command\n");
        free(s);
        return -1;
    }
    snprintf(a, o + sizeof " --no-read-ahead", "%s --no-read-ahead", s);
    *cmd = s;
    *alone = a;
    return 0;
}

/* One --json record into r: 1 taken, 0 not a fit, -1 out of memory. */
static int take_record(const char *line, cli_run *r)
{
    cli_fit f;
    char name[64], status[32];
    memset(&f, 0, sizeof f);
    if (!tu_json_get_string(line, "model", name, sizeof name) ||
        brdffit_model_from_name(name, &f.model, NULL) != BRDFFIT_OK ||
        !tu_json_get_string(line, "status", status, sizeof status) ||
        !tu_json_get_string(line, "material", f.material, sizeof f.material) ||
        !tu_json_get_number(line, "seconds", &f.seconds) ||
        !tu_json_get_number(line, "error", &f.error))
        return 0;
    if (strcmp(status, "ok") != 0 && strcmp(status, "limit") != 0)
        return 0;
    tu_json_get_number(line, "seconds_build", &f.build);
    r->in_fits += f.seconds;
    r->builds += f.build;
    f.seconds -= f.build;
    if (r->n == r->cap) {
        int cap = r->cap ? 2 * r->cap : 256;
        cli_fit *grown = realloc(r->fits, (size_t)cap * sizeof *grown);
        if (!grown)
            return -1;
        r->fits = grown;
        r->cap = cap;
    }
    r->fits[r->n++] = f;
    return 1;
}

int cli_run_take(const char *cmd, cli_run *r)
{
    static char line[65536];
    memset(r, 0, sizeof *r);
    double t0 = bf_now();
    FILE *p = popen(cmd, "r");
    if (!p) {
        fprintf(stderr, "bench: cannot run the program\n");
        return -1;
    }
    int oom = 0;
    while (fgets(line, sizeof line, p)) {
        int got = take_record(line, r);
        oom |= got < 0;
        r->failed += got == 0;
    }
    int status = pclose(p);
    r->wall = bf_now() - t0;
    if (oom || status != 0 || r->failed || r->n == 0) {
        fprintf(stderr, "bench: brdffit fit exited %d with %d fits, %d other records%s\n", status,
                r->n, r->failed, oom ? " (out of memory for them)" : "");
        return -1;
    }
    return 0;
}

void cli_run_free(cli_run *r)
{
    free(r->fits);
    memset(r, 0, sizeof *r);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double cli_median(double *v, int n)
{
    if (n <= 0)
        return 0.0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int cli_model_medians(const cli_run *r, double med[BRDFFIT_MODEL_COUNT])
{
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++)
        med[m] = 0.0;
    double *v = malloc((size_t)(r->n > 0 ? r->n : 1) * sizeof *v);
    if (!v)
        return -1;
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        int k = 0;
        for (int i = 0; i < r->n; i++)
            if (r->fits[i].model == (brdffit_model)m)
                v[k++] = r->fits[i].seconds;
        med[m] = cli_median(v, k);
    }
    free(v);
    return 0;
}

int cli_material_list(char (*names)[64], int max)
{
    char tool[1024], cmd[1100], line[256];
    tu_shared("tools/merl-table", tool, sizeof tool);
    snprintf(cmd, sizeof cmd, "'%s' --list", tool);
    FILE *p = popen(cmd, "r");
    int n = 0;
    while (p && fgets(line, sizeof line, p)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] && n < max)
            snprintf(names[n++], 64, "%.63s", line);
    }
    int status = p ? pclose(p) : -1;
    if (status != 0 || n == 0) {
        fprintf(stderr, "bench: %s --list failed\n", tool);
        return -1;
    }
    return n;
}
