/* SPDX-License-Identifier: MIT */
/* fits_read.c -- the files of fits `brdffit export` reads, record by record:
 * the JSON Lines of `brdffit fit --json` (the fit record's own reader,
 * fit_record_json.c), or a TSV whose header names its columns: a batch's
 * fits.tsv or params.tsv, or a table of the ngan2005-fits.tsv format.  The
 * TSV's columns are found by name, so that a file with more or fewer lobe
 * parameter columns (p0..p3) is read as well. */
#define _POSIX_C_SOURCE 200809L
#include "export.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TSV_MAX_FIELDS 64

/* The columns of a TSV by what they hold: -1 absent. */
typedef struct tsv_cols {
    int material, model, d[3], s[3], p[BRDFFIT_MAX_LOBE_PARAMS], status, status_code, message;
} tsv_cols;

static int split_tabs(char *line, char **fields, int max)
{
    int n = 0;
    for (char *p = line; n < max;) {
        fields[n++] = p;
        char *t = strchr(p, '\t');
        if (!t)
            break;
        *t = '\0';
        p = t + 1;
    }
    return n;
}

static int column(char **names, int n, const char *want)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], want) == 0)
            return i;
    return -1;
}

/* The header's columns: 0, or -1 when it lacks material, model or a colour. */
static int header_cols(char **names, int n, tsv_cols *c)
{
    static const char *const dn[3] = { "d_r", "d_g", "d_b" }, *const sn[3] = { "s_r", "s_g", "s_b" };
    c->material = column(names, n, "material");
    c->model = column(names, n, "model");
    c->status = column(names, n, "status");
    c->status_code = column(names, n, "status_code");
    c->message = column(names, n, "message");
    int ok = c->material >= 0 && c->model >= 0;
    for (int k = 0; k < 3; k++) {
        c->d[k] = column(names, n, dn[k]);
        c->s[k] = column(names, n, sn[k]);
        ok = ok && c->d[k] >= 0 && c->s[k] >= 0;
    }
    for (int k = 0; k < BRDFFIT_MAX_LOBE_PARAMS; k++) {
        char name[8];
        snprintf(name, sizeof name, "p%d", k);
        c->p[k] = column(names, n, name);
    }
    return ok ? 0 : -1;
}

static const char *field(char **f, int n, int col)
{
    return col >= 0 && col < n ? f[col] : "";
}

/* A number of the TSV: 1 a value (which may be nan or inf: the check
 * names it), 0 none ("-" or empty), -1 not a number. */
static int tsv_number(const char *s, double *x)
{
    if (s[0] == '\0' || strcmp(s, "-") == 0)
        return 0;
    char *end;
    errno = 0;
    *x = strtod(s, &end);
    return end != s && *end == '\0' ? 1 : -1;
}

/* The status columns into r: "ok", "limit", another text (the fit failed),
 * or none (a table of parameters: they are fits). */
static void tsv_status(char **f, int n, const tsv_cols *c, fit_record *r)
{
    const char *st = field(f, n, c->status);
    if (c->status < 0 || strcmp(st, "ok") == 0)
        return;
    if (strcmp(st, "limit") == 0) {
        r->flags |= BRDFFIT_FIT_LIMIT;
        return;
    }
    int code;
    if (cli_parse_int(field(f, n, c->status_code), 1, BRDFFIT_STATUS_COUNT - 1, &code) != 0)
        code = BRDFFIT_E_FIT_FAILED;
    r->status = (brdffit_status)code;
    const char *msg = field(f, n, c->message);
    snprintf(r->message, sizeof r->message, "%s", msg[0] && strcmp(msg, "-") ? msg : st);
}

/* One data row into r: NULL, or why it is not a record. */
static const char *tsv_row(char **f, int n, const tsv_cols *c, fit_record *r)
{
    fr_init(r, FR_FIT);
    const char *mat = field(f, n, c->material), *model = field(f, n, c->model);
    if (!mat[0] || strlen(mat) >= sizeof r->material || !model[0] ||
        strlen(model) >= sizeof r->model)
        return "no material or model, or one too long";
    strcpy(r->material, mat);
    strcpy(r->model, model);
    tsv_status(f, n, c, r);
    int have = 0, want = 6;
    for (int k = 0; k < 3; k++) {
        int hd = tsv_number(field(f, n, c->d[k]), &r->params.d[k]);
        int hs = tsv_number(field(f, n, c->s[k]), &r->params.s[k]);
        if (hd < 0 || hs < 0)
            return "a colour value is not a number";
        have += hd + hs;
    }
    r->nparams = 0;
    for (int k = 0; k < BRDFFIT_MAX_LOBE_PARAMS; k++) {
        int hp = tsv_number(field(f, n, c->p[k]), &r->params.p[k]);
        if (hp < 0)
            return "a lobe parameter is not a number";
        if (hp > 0)
            r->nparams = k + 1;
    }
    r->has_params = fr_ok(r) && have == want;
    return NULL;
}

static int read_tsv(FILE *in, fits_visit visit, void *user)
{
    char *line = NULL, *head = NULL;
    char *names[TSV_MAX_FIELDS], *f[TSV_MAX_FIELDS];
    size_t cap = 0;
    long lineno = 0;
    int nnames = 0, stop = 0;
    tsv_cols c = { 0 };
    fit_record *r = malloc(sizeof *r);
    while (r && !stop && getline(&line, &cap, in) > 0) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '#' || line[0] == '\0')
            continue;
        if (!head) {
            head = strdup(line);
            nnames = head ? split_tabs(head, names, TSV_MAX_FIELDS) : 0;
            if (!head || header_cols(names, nnames, &c) != 0) {
                visit(user, NULL, lineno,
                      "not a header naming material, model, d_r..s_b (a TSV of fits)");
                break;
            }
            continue;
        }
        const char *why = tsv_row(f, split_tabs(line, f, TSV_MAX_FIELDS), &c, r);
        stop = visit(user, why ? NULL : r, lineno, why);
    }
    int rc = r ? 0 : -1;
    free(r);
    free(head);
    free(line);
    return rc;
}

static int read_jsonl(FILE *in, fits_visit visit, void *user)
{
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0;
    int stop = 0;
    fit_record *r = malloc(sizeof *r);
    while (r && !stop && getline(&line, &cap, in) > 0) {
        lineno++;
        if (strspn(line, " \t\r\n") == strlen(line))
            continue;
        if (fr_read_json(line, r, FR_NEED_FIT) == 0)
            stop = visit(user, r, lineno, NULL);
        else
            stop = visit(user, NULL, lineno,
                         "not a record of brdffit fit --json (material, model, status)");
    }
    int rc = r ? 0 : -1;
    free(r);
    free(line);
    return rc;
}

/* 1 when the first character of in that is not white space is '{'. */
static int looks_like_json(FILE *in)
{
    int ch;
    while ((ch = getc(in)) != EOF && (ch == ' ' || ch == '\t' || ch == '\r' || ch == '\n'))
        ;
    rewind(in);
    return ch == '{';
}

int fits_read(const char *path, fits_visit visit, void *user, brdffit_error *err)
{
    if (cli_is_directory(path)) {
        err->status = BRDFFIT_E_FILE_NOT_REGULAR;
        snprintf(err->message, sizeof err->message,
                 "%.1800s: a directory (a batch's fits are DIR/fits.tsv)", path);
        return -1;
    }
    FILE *in = cli_fopen_regular(path, err); /* a FIFO or device refused before it is read */
    if (!in)
        return -1;
    int rc = looks_like_json(in) ? read_jsonl(in, visit, user) : read_tsv(in, visit, user);
    if (rc != 0) {
        err->status = BRDFFIT_E_NO_MEMORY;
        snprintf(err->message, sizeof err->message, "%.1800s: out of memory", path);
    } else if (ferror(in)) {
        err->status = BRDFFIT_E_FILE_READ;
        snprintf(err->message, sizeof err->message, "%.1800s: read error", path);
        rc = -1;
    }
    fclose(in);
    return rc;
}
