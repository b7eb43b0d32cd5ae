/* SPDX-License-Identifier: MIT */
/* testutil.c -- see testutil.h. */
#define _XOPEN_SOURCE 700 /* nftw */
#define _DEFAULT_SOURCE  /* M_PI */
#include "testutil.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <ftw.h>
#include <sys/wait.h>
#include <unistd.h>

const char *tu_shared(const char *rel, char *buf, size_t len)
{
    const char *root = getenv("BRDFFIT_SHARED");
    snprintf(buf, len, "%s/%s", root && *root ? root : "../shared", rel);
    return buf;
}

int tu_shared_present(char *why, size_t len)
{
    static const char *const need[] = { "tools/merl-table", "data/ngan2005-fits.tsv",
                                        "data/model-reference.tsv", "data/he-reference.tsv" };
    const char *root = getenv("BRDFFIT_SHARED");
    char path[1024];
    for (size_t i = 0; i < sizeof need / sizeof need[0]; i++) {
        tu_shared(need[i], path, sizeof path);
        if (access(path, i == 0 ? X_OK : R_OK) != 0) {
            snprintf(why, len,
                     "%s not found%s: the MERL tables and reference data come from the shared "
                     "data folder beside the checkout (../shared, described by its README.md; "
                     "BRDFFIT_SHARED=DIR points elsewhere); running only the tests that need "
                     "no data, then failing",
                     path, root && *root ? " (BRDFFIT_SHARED)" : "");
            return 0;
        }
    }
    return 1;
}

const char *tu_merl_table(const char *name, char *buf, size_t len)
{
    char tool[1024], cmd[2048];
    tu_shared("tools/merl-table", tool, sizeof tool);
    snprintf(cmd, sizeof cmd, "'%s' '%s'", tool, name);
    FILE *p = popen(cmd, "r");
    if (!p)
        return NULL;
    char *got = fgets(buf, (int)len, p);
    int rc = pclose(p);
    if (!got || rc != 0)
        return NULL;
    buf[strcspn(buf, "\r\n")] = '\0';
    return buf;
}

const char *tu_tmpfile(char *buf, size_t len)
{
    const char *dir = getenv("TMPDIR");
    snprintf(buf, len, "%s/brdffit-test-XXXXXX", dir && *dir ? dir : "/tmp");
    int fd = mkstemp(buf);
    if (fd < 0)
        return NULL;
    close(fd);
    return buf;
}

int tu_write_bytes(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t w = len ? fwrite(data, 1, len, f) : 0;
    return (fclose(f) == 0 && w == len) ? 0 : -1;
}

int tu_tsv_next(void *file, char *line, size_t len, char **fields, int maxfields)
{
    while (fgets(line, (int)len, (FILE *)file)) {
        if (line[0] == '#' || line[0] == '\n')
            continue;
        line[strcspn(line, "\r\n")] = '\0';
        int n = 0;
        char *p = line;
        while (n < maxfields) {
            fields[n++] = p;
            char *tab = strchr(p, '\t');
            if (!tab)
                break;
            *tab = '\0';
            p = tab + 1;
        }
        return n;
    }
    return 0;
}

void tu_params_from_row(char **fields, brdffit_params *p)
{
    memset(p, 0, sizeof *p);
    for (int c = 0; c < 3; c++) {
        p->d[c] = atof(fields[2 + c]);
        p->s[c] = atof(fields[5 + c]);
    }
    for (int k = 0; k < 3; k++)
        p->p[k] = fields[8 + k][0] ? atof(fields[8 + k]) : 0.0;
}

/* Walk ngan2005-fits.tsv: each row of model (and of material, when given). */
static int published_rows(const char *material, brdffit_model model, brdffit_params *params,
                          char (*names)[64], int max)
{
    char path[1024], line[4096];
    FILE *f = fopen(tu_shared("data/ngan2005-fits.tsv", path, sizeof path), "r");
    if (!f)
        return 0;
    char *fl[16];
    int n = 0;
    while (n < max && tu_tsv_next(f, line, sizeof line, fl, 16) >= 11) {
        brdffit_model m;
        if ((material && strcmp(fl[0], material) != 0) ||
            brdffit_model_from_name(fl[1], &m, NULL) != BRDFFIT_OK || m != model)
            continue;
        tu_params_from_row(fl, &params[n]);
        if (names)
            snprintf(names[n], 64, "%s", fl[0]);
        n++;
    }
    fclose(f);
    return n;
}

int tu_published(const char *material, brdffit_model model, brdffit_params *p)
{
    return published_rows(material, model, p, NULL, 1);
}

int tu_published_all(brdffit_model model, brdffit_params *params, char (*names)[64], int max)
{
    return published_rows(NULL, model, params, names, max);
}

void tu_start_params(brdffit_model model, double p[BRDFFIT_MAX_LOBE_PARAMS])
{
    for (int k = 0; k < BRDFFIT_MAX_LOBE_PARAMS; k++) {
        const brdffit_param_info *pi = brdffit_model_param(model, k);
        p[k] = pi ? pi->start : 0.0;
    }
}

double tu_reldiff(double a, double b)
{
    double m = fmax(fmax(fabs(a), fabs(b)), 1e-300);
    return fabs(a - b) / m;
}

/* ------------------------------------------------------------------ tables, samples, contexts */

brdffit_status tu_merl_read(const char *material, brdffit_table **out, brdffit_error *err)
{
    char path[1024];
    *out = NULL;
    if (!tu_merl_table(material, path, sizeof path)) {
        if (err) {
            err->status = BRDFFIT_E_FILE_OPEN;
            snprintf(err->message, sizeof err->message, "%s %s failed",
                     tu_shared("tools/merl-table", path, sizeof path), material);
        }
        return BRDFFIT_E_FILE_OPEN;
    }
    return brdffit_table_read(path, out, err);
}

brdffit_status tu_merl_samples(const char *material, const brdffit_sample_options *opt,
                               brdffit_samples **out, brdffit_error *err)
{
    brdffit_table *t = NULL;
    *out = NULL;
    brdffit_status st = tu_merl_read(material, &t, err);
    if (st == BRDFFIT_OK)
        st = brdffit_samples_create(t, opt, out, err);
    brdffit_table_free(t);
    return st;
}

brdffit_status tu_ward_duer_samples(double cutoff_deg, brdffit_samples **out, brdffit_error *err)
{
    brdffit_table *t = NULL;
    brdffit_params p = { { 0.05, 0.04, 0.03 }, { 0.04, 0.03, 0.02 }, { 0.15, 0, 0 }, { 0 } };
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    if (cutoff_deg > 0)
        so.cutoff_deg = cutoff_deg;
    *out = NULL;
    brdffit_status st = brdffit_table_create(&t, err);
    if (st == BRDFFIT_OK)
        st = brdffit_table_fill_model(t, BRDFFIT_WARD_DUER, &p, BRDFFIT_SCALE_STANDARD, err);
    if (st == BRDFFIT_OK)
        st = brdffit_samples_create(t, &so, out, err);
    brdffit_table_free(t);
    return st;
}

brdffit_status tu_context(brdffit_backend backend, brdffit_context **out, brdffit_error *err)
{
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    co.backend = backend;
    return brdffit_context_create(&co, out, err);
}

/* ------------------------------------------------------------------ random directions */

double tu_urand(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return ((*state >> 8) + 0.5) / 16777216.0;
}

void tu_dir_at(double theta_deg, double phi_deg, double w[3])
{
    double t = theta_deg * M_PI / 180, p = phi_deg * M_PI / 180;
    w[0] = sin(t) * cos(p);
    w[1] = sin(t) * sin(p);
    w[2] = cos(t);
}

void tu_rand_dir(unsigned *state, double zmin, double w[3])
{
    double z = zmin + (1 - zmin) * tu_urand(state), phi = 2 * M_PI * tu_urand(state);
    double r = sqrt(fmax(0.0, 1 - z * z));
    w[0] = r * cos(phi);
    w[1] = r * sin(phi);
    w[2] = z;
}

/* ------------------------------------------------------------------ the environment */

static const char *const env_names[TU_ENV_N] = { "OCL_ICD_VENDORS", "HOME", "XDG_CACHE_HOME",
                                                 "POCL_CACHE_DIR", "BRDFFIT_DEVICE",
                                                 "BRDFFIT_CL_OPTIONS" };

void tu_env_get(tu_env *e)
{
    for (int i = 0; i < TU_ENV_N; i++) {
        const char *v = getenv(env_names[i]);
        e->value[i] = v ? strdup(v) : NULL;
    }
}

void tu_env_put(tu_env *e)
{
    for (int i = 0; i < TU_ENV_N; i++) {
        if (e->value[i])
            setenv(env_names[i], e->value[i], 1);
        else
            unsetenv(env_names[i]);
        free(e->value[i]);
        e->value[i] = NULL;
    }
}

static tu_env fixture_env;

void tu_env_save(void)
{
    tu_env_get(&fixture_env);
}

void tu_env_restore(void)
{
    tu_env_put(&fixture_env);
}

static int remove_one(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(path);
}

int tu_remove_tree(const char *path)
{
    return nftw(path, remove_one, 16, FTW_DEPTH | FTW_PHYS);
}

int tu_in_child(void (*fn)(void *arg, void *out, size_t len), void *arg, void *out, size_t len)
{
    int fds[2];
    if (pipe(fds) != 0)
        return -1;
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        close(fds[0]);
        memset(out, 0, len);
        fn(arg, out, len);
        const char *p = out;
        size_t left = len;
        while (left > 0) {
            ssize_t w = write(fds[1], p, left);
            if (w <= 0)
                _exit(120);
            p += w;
            left -= (size_t)w;
        }
        _exit(0);
    }
    close(fds[1]);
    char *p = out;
    size_t got = 0;
    while (got < len) {
        ssize_t r = read(fds[0], p + got, len - got);
        if (r <= 0)
            break;
        got += (size_t)r;
    }
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    if (WIFSIGNALED(status))
        return 128 + WTERMSIG(status);
    if (!WIFEXITED(status))
        return -1;
    if (WEXITSTATUS(status) != 0)
        return WEXITSTATUS(status);
    return got == len ? 0 : 121;
}

int tu_capture_begin(tu_capture *c)
{
    c->saved = -1;
    if (!tu_tmpfile(c->path, sizeof c->path))
        return -1;
    fflush(stderr);
    int fd = open(c->path, O_WRONLY | O_TRUNC);
    c->saved = fd < 0 ? -1 : dup(2);
    if (fd < 0 || c->saved < 0 || dup2(fd, 2) < 0) {
        if (fd >= 0)
            close(fd);
        if (c->saved >= 0)
            close(c->saved);
        c->saved = -1;
        unlink(c->path);
        return -1;
    }
    close(fd);
    return 0;
}

char *tu_capture_end(tu_capture *c)
{
    if (c->saved < 0)
        return strdup("");
    fflush(stderr);
    dup2(c->saved, 2);
    close(c->saved);
    c->saved = -1;
    char *text = tu_slurp(c->path);
    unlink(c->path);
    return text ? text : strdup("");
}

char *tu_slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    if (!f || !buf) {
        if (f)
            fclose(f);
        free(buf);
        return NULL;
    }
    size_t got;
    while ((got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        if (cap - n - 1 == 0) {
            char *bigger = realloc(buf, cap * 2);
            if (!bigger)
                break;
            buf = bigger;
            cap *= 2;
        }
    }
    buf[n] = '\0';
    fclose(f);
    return buf;
}

const char *tu_cli(void)
{
    const char *cli = getenv("BRDFFIT_CLI");
    return cli && *cli ? cli : "./build/brdffit";
}

const char *tu_cli_faults(void)
{
    const char *cli = getenv("BRDFFIT_CLI_FAULTS");
    return cli && *cli ? cli : "./build/brdffit-faults";
}

static tu_run_out run_program(const char *cli, const char *env, const char *args)
{
    tu_run_out r = { -1, NULL, NULL };
    char out[512], err[512];
    if (!tu_tmpfile(out, sizeof out) || !tu_tmpfile(err, sizeof err))
        return r;
    size_t len = strlen(args) + strlen(env) + 2048;
    char *cmd = malloc(len);
    if (!cmd)
        return r;
    snprintf(cmd, len, "%s '%s' %s >'%s' 2>'%s' </dev/null", env, cli, args, out, err);
    int rc = system(cmd);
    free(cmd);
    r.status = rc == -1 ? -1 : WIFEXITED(rc) ? WEXITSTATUS(rc) : 128 + WTERMSIG(rc);
    r.out = tu_slurp(out);
    r.err = tu_slurp(err);
    unlink(out);
    unlink(err);
    return r;
}

tu_run_out tu_run_cli(const char *env, const char *args)
{
    return run_program(tu_cli(), env, args);
}

tu_run_out tu_run_cli_faults(const char *env, const char *args)
{
    return run_program(tu_cli_faults(), env, args);
}

int tu_count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

void tu_run_free(tu_run_out *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

static char fixture_table[512];

void tu_table_fixture_make(void)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_params p = { { 0.05, 0.04, 0.03 }, { 0.04, 0.03, 0.02 }, { 0.15, 0, 0 }, { 0 } };
    if (brdffit_table_create(&t, &err) != BRDFFIT_OK ||
        brdffit_table_fill_model(t, BRDFFIT_WARD_DUER, &p, BRDFFIT_SCALE_STANDARD, &err) != BRDFFIT_OK ||
        !tu_tmpfile(fixture_table, sizeof fixture_table) ||
        brdffit_table_write(t, fixture_table, &err) != BRDFFIT_OK)
        fixture_table[0] = '\0';
    brdffit_table_free(t);
}

void tu_table_fixture_remove(void)
{
    if (fixture_table[0])
        unlink(fixture_table);
}

const char *tu_table_fixture(void)
{
    if (!fixture_table[0]) { /* the test errs (a signal) with this said */
        fprintf(stderr, "tu_table_fixture: the fixture could not write its table\n");
        abort();
    }
    return fixture_table;
}
