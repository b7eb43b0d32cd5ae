/* SPDX-License-Identifier: MIT */
/* fidelity.c -- `make fidelity`: fit every material of the published Ngan et al.
 * fits with every model (flat scale, as they fitted), score the published
 * parameters on the same tables, and compare each fit with them and with a
 * stored run's Errors.  One line per fit, then a summary; exit status 0 when
 * no fit is worse than published, none stopped on a limit and none is worse
 * than the stored run.
 *
 *   bench_fidelity [--fits FILE] [--baseline FILE] [--write FILE] [--materials all|quick|A,B,...]
 *                  [--models A,B,...] [--backend auto|opencl|host]
 *                  [--starts N] [--refine N] [--max-evals N] [--ftol X] [--xtol X]
 *                  (brdffit_fit_options)
 *
 * --fits       published parameters (default ../shared/data/ngan2005-fits.tsv)
 * --baseline   a stored run: TSV of material, model, Error (bench/baseline-errors.tsv)
 * --write      also store this run's Errors in the --baseline format
 * --materials  the fits file's materials (default), `all` (the 100 of
 *              merl-table --list), `quick` (the ten of QUICK_MATERIALS, a few
 *              minutes) or a comma-separated list
 * Tables come from ../shared/tools/merl-table (or $BRDFFIT_SHARED/tools). */
#define _POSIX_C_SOURCE 200809L
#include "brdffit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* A fit is worse than the stored run's when its Error exceeds it by more than
 * WORSE_TOL (relative); the summary also counts the fits beyond the wider
 * band WIDE_TOL, within which two runs' LM stopping inside their convergence
 * tolerance can differ, and those better by more than it. */
#define WORSE_TOL 1e-9
#define WIDE_TOL 1e-7

/* --materials quick: the materials where fits were hardest to get right
 * (F0 on its bound on metals, sharp Lafortune lobes, fabrics on alpha's
 * bound, d = 0 in two channels), and alum-bronze. */
#define QUICK_MATERIALS                                                                          \
    "alum-bronze,aluminium,black-obsidian,blue-fabric,chrome,dark-blue-paint,delrin,"            \
    "grease-covered-steel,violet-acrylic,white-fabric"

enum { MAX_ROWS = 2048, MAX_MATERIALS = 256, NAME_MAX_LEN = 64, LINE_MAX_LEN = 4096 };

/* A stored row: a material, a model, parameters (published) or an Error (baseline). */
typedef struct row {
    char material[NAME_MAX_LEN];
    brdffit_model model;
    brdffit_params params;
    double error;
} row;

typedef struct rowset {
    row *rows;
    int n;
} rowset;

typedef struct tally {
    FILE *write;            /* --write: this run's Errors, in the stored-run format */
    int fits, failed, scored, worse_published, limit, at_lobe_bound;
    int compared, worse_baseline, better_baseline, above_wide;
    double worst_ratio, worst_base_ratio;
    char worst[2 * NAME_MAX_LEN + 2], worst_base[2 * NAME_MAX_LEN + 2];
    double fit_seconds;
    double *seconds[BRDFFIT_MODEL_COUNT]; /* per model, for medians */
    int nseconds[BRDFFIT_MODEL_COUNT];
} tally;

typedef struct config {
    char fits[1024], baseline[1024], tools[1024], write[1024];
    const char *materials;   /* NULL: the fits file's */
    int use_model[BRDFFIT_MODEL_COUNT];
    brdffit_context_options ctx;
    brdffit_fit_options fit;
} config;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *shared_path(const char *rel, char *buf, size_t len)
{
    const char *root = getenv("BRDFFIT_SHARED");
    snprintf(buf, len, "%s/%s", root && *root ? root : "../shared", rel);
    return buf;
}

/* Split a tab-separated line in place; returns the number of fields. */
static int split_tabs(char *line, char **f, int max)
{
    line[strcspn(line, "\r\n")] = '\0';
    int n = 0;
    for (char *p = line; n < max;) {
        f[n++] = p;
        char *t = strchr(p, '\t');
        if (!t)
            break;
        *t = '\0';
        p = t + 1;
    }
    return n;
}

static double field_num(const char *s)
{
    return *s ? strtod(s, NULL) : 0.0;
}

/* Read published fits (material model d_r..s_b p0 p1 p2) or a baseline
 * (material model error ...) into rs.  Returns 0, or -1 with a message. */
static int read_rows(const char *path, int published, rowset *rs)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "bench_fidelity: cannot open %s\n", path);
        return -1;
    }
    rs->rows = calloc(MAX_ROWS, sizeof *rs->rows);
    rs->n = 0;
    char line[LINE_MAX_LEN], *fl[16];
    int lineno = 0, rc = 0;
    while (rs->rows && fgets(line, sizeof line, f)) {
        lineno++;
        if (line[0] == '#' || strncmp(line, "material\t", 9) == 0 || line[0] == '\n')
            continue;
        int n = split_tabs(line, fl, 16);
        row *r = &rs->rows[rs->n];
        if (n < (published ? 9 : 3) || rs->n >= MAX_ROWS ||
            brdffit_model_from_name(fl[1], &r->model, NULL) != BRDFFIT_OK) {
            fprintf(stderr, "bench_fidelity: %s:%d: not a row (material, model, ...)\n", path, lineno);
            rc = -1;
            break;
        }
        snprintf(r->material, sizeof r->material, "%s", fl[0]);
        memset(&r->params, 0, sizeof r->params);
        if (published) {
            double v[9] = { 0 };
            for (int k = 0; k < 9 && 2 + k < n; k++)
                v[k] = field_num(fl[2 + k]);
            memcpy(r->params.d, v, 3 * sizeof *v);
            memcpy(r->params.s, v + 3, 3 * sizeof *v);
            memcpy(r->params.p, v + 6, 3 * sizeof *v);
        } else {
            r->error = field_num(fl[2]);
        }
        rs->n++;
    }
    fclose(f);
    if (!rs->rows) {
        fprintf(stderr, "bench_fidelity: out of memory\n");
        return -1;
    }
    return rc;
}

static const row *find_row(const rowset *rs, const char *material, brdffit_model model)
{
    for (int i = 0; rs && i < rs->n; i++)
        if (rs->rows[i].model == model && strcmp(rs->rows[i].material, material) == 0)
            return &rs->rows[i];
    return NULL;
}

/* The materials to fit, in order: a list, all 100, or the fits file's. */
static int material_list(const config *c, const rowset *pub, char (*names)[NAME_MAX_LEN])
{
    int n = 0;
    if (c->materials && strcmp(c->materials, "all") == 0) {
        char cmd[1200], line[256];
        snprintf(cmd, sizeof cmd, "'%.1000s/merl-table' --list", c->tools);
        FILE *p = popen(cmd, "r");
        while (p && n < MAX_MATERIALS && fgets(line, sizeof line, p)) {
            line[strcspn(line, "\r\n")] = '\0';
            if (line[0])
                snprintf(names[n++], NAME_MAX_LEN, "%.*s", NAME_MAX_LEN - 1, line);
        }
        if (p)
            pclose(p);
        return n;
    }
    if (c->materials) {
        const char *s = c->materials;
        while (*s && n < MAX_MATERIALS) {
            size_t len = strcspn(s, ",");
            snprintf(names[n++], NAME_MAX_LEN, "%.*s", (int)len, s);
            s += len + (s[len] == ',');
        }
        return n;
    }
    for (int i = 0; i < pub->n; i++) {
        int seen = 0;
        for (int k = 0; k < n && !seen; k++)
            seen = strcmp(names[k], pub->rows[i].material) == 0;
        if (!seen && n < MAX_MATERIALS)
            snprintf(names[n++], NAME_MAX_LEN, "%s", pub->rows[i].material);
    }
    return n;
}

/* The flat-scale sample set of a merl-table material, or NULL with a message. */
static brdffit_samples *load_samples(const config *c, const char *material)
{
    char cmd[1200], path[1024];
    snprintf(cmd, sizeof cmd, "'%.1000s/merl-table' '%.63s'", c->tools, material);
    FILE *p = popen(cmd, "r");
    char *got = p ? fgets(path, sizeof path, p) : NULL;
    int rc = p ? pclose(p) : -1;
    if (!got || rc != 0) {
        fprintf(stderr, "bench_fidelity: merl-table %s failed\n", material);
        return NULL;
    }
    path[strcspn(path, "\r\n")] = '\0';
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.scale = BRDFFIT_SCALE_FLAT;
    if (brdffit_table_read(path, &t, &err) != BRDFFIT_OK ||
        brdffit_samples_create(t, &so, &s, &err) != BRDFFIT_OK)
        fprintf(stderr, "bench_fidelity: %s\n", err.message);
    brdffit_table_free(t);
    return s;
}

/* "limit", "bound: m, d_r", "ok": what the result says beyond its Error. */
static const char *result_note(const brdffit_fit_result *r, char *buf, size_t len)
{
    const brdffit_model_info *mi = brdffit_model_get(r->model);
    static const char *const ch[3] = { "r", "g", "b" };
    size_t o = 0;
    buf[0] = '\0';
    if (r->flags & BRDFFIT_FIT_LIMIT)
        o += (size_t)snprintf(buf + o, len - o, "limit ");
    if (r->at_bound & BRDFFIT_AT_BOUND_LOBE) {
        o += (size_t)snprintf(buf + o, len - o, "bound:");
        for (int k = 0; k < mi->nparams && o < len; k++)
            if (r->at_bound & (BRDFFIT_AT_BOUND_P0 << k))
                o += (size_t)snprintf(buf + o, len - o, " %s", mi->params[k].name);
        o += (size_t)snprintf(buf + o, len - o, " ");
    }
    for (int c = 0; c < 3 && o < len; c++)
        if (r->at_bound & (BRDFFIT_AT_BOUND_D_R << c))
            o += (size_t)snprintf(buf + o, len - o, "d_%s=0 ", ch[c]);
    if (o == 0)
        snprintf(buf, len, "ok");
    else if (o < len)
        buf[o - 1] = '\0';
    return buf;
}

static void note_ratio(double ratio, double *worst, char *where, size_t len, const char *material,
                       const char *model)
{
    if (ratio > *worst) {
        *worst = ratio;
        snprintf(where, len, "%.63s/%.63s", material, model);
    }
}

/* Fit one model to one material, score the published row, print one line. */
static void one_fit(brdffit_context *ctx, const brdffit_samples *s, const char *material,
                    brdffit_model m, const brdffit_fit_options *fo, const rowset *pub,
                    const rowset *base, tally *T)
{
    const brdffit_model_info *mi = brdffit_model_get(m);
    brdffit_error err;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    T->fits++;
    if (brdffit_fit(ctx, s, m, fo, &r, &err) != BRDFFIT_OK) {
        T->failed++;
        printf("%-26s %-17s FAILED: %s\n", material, mi->name, err.message);
        return;
    }
    T->fit_seconds += r.seconds;
    if (T->write)
        fprintf(T->write, "%s\t%s\t%.17g\t%d\t%d\t%d\t%.3f\n", material, mi->name, r.error,
                r.cminpack_info, r.iterations, r.passes, r.seconds);
    T->seconds[m][T->nseconds[m]++] = r.seconds;
    char pubtxt[64] = "-", basetxt[64] = "-", note[128];
    const row *pr = find_row(pub, material, m);
    if (pr) {
        double e_pub;
        if (brdffit_error_of(ctx, s, m, &pr->params, &e_pub, &err) != BRDFFIT_OK) {
            T->failed++;
            snprintf(pubtxt, sizeof pubtxt, "NOT SCORED");
            fprintf(stderr, "bench_fidelity: %s/%s published: %s\n", material, mi->name, err.message);
        } else {
            double ratio = r.error / e_pub;
            T->scored++;
            T->worse_published += ratio > 1.0;
            note_ratio(ratio, &T->worst_ratio, T->worst, sizeof T->worst, material, mi->name);
            snprintf(pubtxt, sizeof pubtxt, "%.6g ratio %.4f", e_pub, ratio);
        }
    }
    const row *br = find_row(base, material, m);
    if (br && br->error > 0) {
        double ratio = r.error / br->error;
        T->compared++;
        T->worse_baseline += ratio > 1.0 + WORSE_TOL;
        T->above_wide += ratio > 1.0 + WIDE_TOL;
        T->better_baseline += ratio < 1.0 - WIDE_TOL;
        note_ratio(ratio, &T->worst_base_ratio, T->worst_base, sizeof T->worst_base, material, mi->name);
        snprintf(basetxt, sizeof basetxt, "%.6g (%+.2e)", br->error, ratio - 1.0);
    }
    T->limit += (r.flags & BRDFFIT_FIT_LIMIT) != 0;
    T->at_lobe_bound += (r.at_bound & BRDFFIT_AT_BOUND_LOBE) != 0;
    printf("%-26s %-17s fit %-11.6g published %-24s baseline %-22s %5.2f s  %s\n", material, mi->name,
           r.error, pubtxt, basetxt, r.seconds, result_note(&r, note, sizeof note));
    fflush(stdout);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int summary(const tally *T, int nmat, double wall, int have_base)
{
    printf("\nsummary: %d materials, %d fits (%d failed), %d scored against published\n", nmat, T->fits,
           T->failed, T->scored);
    printf("  fits worse than published:  %d (target 0); worst ratio %.4f (%s)\n", T->worse_published,
           T->worst_ratio, T->worst[0] ? T->worst : "-");
    printf("  fits stopped on a limit:    %d (target 0)\n", T->limit);
    printf("  fits with a lobe parameter on a bound: %d\n", T->at_lobe_bound);
    if (have_base)
        printf("  against the stored run:     %d compared, %d worse by > %.0e relative (target 0; "
               "%d of them by > %.0e), %d better by > %.0e; worst ratio %.11f (%s)\n",
               T->compared, T->worse_baseline, WORSE_TOL, T->above_wide, WIDE_TOL, T->better_baseline,
               WIDE_TOL, T->worst_base_ratio, T->worst_base[0] ? T->worst_base : "-");
    printf("  time: %.0f s wall, %.0f s in fits; median fit seconds:", wall, T->fit_seconds);
    for (int m = 0; m < brdffit_model_count(); m++) {
        if (!T->nseconds[m])
            continue;
        qsort(T->seconds[m], (size_t)T->nseconds[m], sizeof(double), cmp_double);
        int n = T->nseconds[m];
        double med = n % 2 ? T->seconds[m][n / 2] : 0.5 * (T->seconds[m][n / 2 - 1] + T->seconds[m][n / 2]);
        printf(" %s %.2f", brdffit_model_get((brdffit_model)m)->name, med);
    }
    printf("\n");
    int ok = T->failed == 0 && T->worse_published == 0 && T->limit == 0 &&
             (!have_base || T->worse_baseline == 0);
    printf("  result: %s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}

static int parse_args(int argc, char **argv, config *c)
{
    memset(c, 0, sizeof *c);
    shared_path("data/ngan2005-fits.tsv", c->fits, sizeof c->fits);
    shared_path("tools", c->tools, sizeof c->tools);
    brdffit_context_options_default(&c->ctx);
    brdffit_fit_options_default(&c->fit);
    for (int m = 0; m < brdffit_model_count(); m++)
        c->use_model[m] = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v)
            goto usage;
        i++;
        if (strcmp(a, "--fits") == 0) {
            snprintf(c->fits, sizeof c->fits, "%s", v);
        } else if (strcmp(a, "--baseline") == 0) {
            snprintf(c->baseline, sizeof c->baseline, "%s", v);
        } else if (strcmp(a, "--write") == 0) {
            snprintf(c->write, sizeof c->write, "%s", v);
        } else if (strcmp(a, "--materials") == 0) {
            c->materials = strcmp(v, "quick") == 0 ? QUICK_MATERIALS : v;
        } else if (strcmp(a, "--starts") == 0) {
            c->fit.starts = atoi(v);
        } else if (strcmp(a, "--refine") == 0) {
            c->fit.refine = atoi(v);
        } else if (strcmp(a, "--ftol") == 0) {
            c->fit.ftol = atof(v);
        } else if (strcmp(a, "--xtol") == 0) {
            c->fit.xtol = atof(v);
        } else if (strcmp(a, "--max-evals") == 0) {
            c->fit.max_evals = atoi(v);
        } else if (strcmp(a, "--backend") == 0) {
            c->ctx.backend = strcmp(v, "host") == 0     ? BRDFFIT_BACKEND_HOST
                             : strcmp(v, "opencl") == 0 ? BRDFFIT_BACKEND_OPENCL
                                                        : BRDFFIT_BACKEND_AUTO;
        } else if (strcmp(a, "--models") == 0) {
            memset(c->use_model, 0, sizeof c->use_model);
            char buf[512];
            snprintf(buf, sizeof buf, "%s", v);
            for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
                brdffit_model m;
                if (brdffit_model_from_name(t, &m, NULL) != BRDFFIT_OK) {
                    fprintf(stderr, "bench_fidelity: unknown model %s\n", t);
                    return -1;
                }
                c->use_model[m] = 1;
            }
        } else {
            goto usage;
        }
    }
    return 0;
usage:
    fprintf(stderr, "usage: bench_fidelity [--fits FILE] [--baseline FILE] [--write FILE]\n"
                    "                      [--materials all|quick|A,B,...]\n"
                    "                      [--models A,B,...] [--backend auto|opencl|host]\n"
                    "                      [--starts N] [--refine N] [--max-evals N] [--ftol X] [--xtol X]\n");
    return -1;
}

int main(int argc, char **argv)
{
    config c;
    if (parse_args(argc, argv, &c) != 0)
        return 2;
    double t0 = now();
    rowset pub = { 0 }, base = { 0 };
    static char names[MAX_MATERIALS][NAME_MAX_LEN];
    tally T;
    memset(&T, 0, sizeof T);
    brdffit_context *ctx = NULL;
    brdffit_error err;
    int rc = 2, nmat = 0;
    if (read_rows(c.fits, 1, &pub) != 0 || (c.baseline[0] && read_rows(c.baseline, 0, &base) != 0))
        goto done;
    nmat = material_list(&c, &pub, names);
    for (int m = 0; m < brdffit_model_count(); m++)
        if (!(T.seconds[m] = calloc(MAX_MATERIALS, sizeof(double))))
            goto done;
    if (c.write[0]) {
        if (!(T.write = fopen(c.write, "w"))) {
            fprintf(stderr, "bench_fidelity: cannot write %s\n", c.write);
            goto done;
        }
        fprintf(T.write, "# Errors of a bench_fidelity run (flat scale, cutoff 80 deg, fit options starts %d,"
                         " refine %d, max_evals %d)\n"
                         "material\tmodel\terror\tcminpack_info\titerations\tevaluations\tseconds\n",
                c.fit.starts, c.fit.refine, c.fit.max_evals);
    }
    if (brdffit_context_create(&c.ctx, &ctx, &err) != BRDFFIT_OK) {
        fprintf(stderr, "bench_fidelity: %s\n", err.message);
        goto done;
    }
    printf("fidelity: %d materials, flat scale, cutoff 80 deg, fit options starts %d (0: the model's),"
           " refine %d, max_evals %d; %s\n"
           "  published: %s%s%s\n\n",
           nmat, c.fit.starts, c.fit.refine, c.fit.max_evals, brdffit_context_describe(ctx), c.fits, c.baseline[0] ? "; stored run: " : "", c.baseline);
    for (int i = 0; i < nmat; i++) {
        brdffit_samples *s = load_samples(&c, names[i]);
        if (!s) {
            T.failed++;
            continue;
        }
        for (int m = 0; m < brdffit_model_count(); m++)
            if (c.use_model[m])
                one_fit(ctx, s, names[i], (brdffit_model)m, &c.fit, &pub, c.baseline[0] ? &base : NULL,
                        &T);
        brdffit_samples_free(s);
    }
    rc = summary(&T, nmat, now() - t0, c.baseline[0] != 0);
done:
    if (T.write && fclose(T.write) != 0) {
        fprintf(stderr, "bench_fidelity: writing %s failed\n", c.write);
        rc = 2;
    }
    brdffit_context_free(ctx);
    for (int m = 0; m < brdffit_model_count(); m++)
        free(T.seconds[m]);
    free(pub.rows);
    free(base.rows);
    return rc;
}
