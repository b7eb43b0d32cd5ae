/* SPDX-License-Identifier: MIT */
/* published.c -- a table of published fits (the format of ngan2005-fits.tsv):
 * '#' comment lines (one may be "# scale: flat" or "# scale: standard", the
 * scale of the tables the parameters were fitted to), a header "material
 * model d_r d_g d_b s_r s_g s_b p0 p1 p2", then one row per material and
 * model, tab-separated; an empty p is 0. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#define PUB_FIELDS 11

static int split_tabs(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    for (;;) {
        if (n == max)
            return max + 1;
        fields[n++] = p;
        char *t = strchr(p, '\t');
        if (!t)
            return n;
        *t = '\0';
        p = t + 1;
    }
}

static int bad(brdffit_error *err, const char *path, int line, const char *why)
{
    err->status = BRDFFIT_E_INVALID_ARGUMENT;
    if (line > 0)
        snprintf(err->message, sizeof err->message, "%.1500s: line %d: %.300s", path, line, why);
    else /* an empty file has no line to name */
        snprintf(err->message, sizeof err->message, "%.1500s: %.300s", path, why);
    return -1;
}

/* One data row's fields into *row: NULL, or why they are not one. */
static const char *parse_row(char **fld, pub_row *row, char *why, size_t len)
{
    memset(row, 0, sizeof *row);
    if (strlen(fld[0]) == 0 || strlen(fld[0]) >= sizeof row->material)
        return "empty or too long material name";
    strcpy(row->material, fld[0]);
    if (brdffit_model_from_name(fld[1], &row->model, NULL) != BRDFFIT_OK) {
        snprintf(why, len, "unknown model '%.100s'", fld[1]);
        return why;
    }
    const brdffit_model_info *mi = brdffit_model_get(row->model);
    double v[9];
    for (int k = 0; k < 9; k++) {
        const char *s = fld[2 + k];
        if (k >= 6 + mi->nparams && s[0] != '\0') {
            snprintf(why, len, "p%d is '%.40s', but %s has %d parameter%s (p%d and after empty)",
                     k - 6, s, mi->name, mi->nparams, mi->nparams == 1 ? "" : "s", mi->nparams);
            return why;
        }
        if (k >= 6 && s[0] == '\0')
            v[k] = 0;
        else if (cli_parse_double(s, &v[k]) != 0)
            return "a value is not a finite number";
    }
    memcpy(row->params.d, v, sizeof row->params.d);
    memcpy(row->params.s, v + 3, sizeof row->params.s);
    memset(row->params.p, 0, sizeof row->params.p);
    memcpy(row->params.p, v + 6, 3 * sizeof *v); /* the file's p0, p1, p2 */
    return NULL;
}

/* A comment line: its "# scale: NAME" into t.  NULL, or why it is not one. */
static const char *read_comment(const char *line, int lineno, pub_table *t, char *why, size_t len)
{
    const char *p = line + 1;
    p += strspn(p, " \t");
    if (strncmp(p, "scale:", 6) != 0)
        return NULL; /* any other comment */
    p += 6;
    p += strspn(p, " \t");
    char name[32];
    size_t n = strcspn(p, " \t");
    snprintf(name, sizeof name, "%.*s", (int)(n < sizeof name ? n : sizeof name - 1), p);
    brdffit_scale s;
    if (n >= sizeof name || p[n + strspn(p + n, " \t")] != '\0' ||
        brdffit_scale_from_name(name, &s, NULL) != BRDFFIT_OK) {
        snprintf(why, len, "'%.60s': expected '# scale: standard' or '# scale: flat'", line);
        return why;
    }
    if (t->scale_line > 0 && s != t->scale) {
        snprintf(why, len, "'# scale: %s', but line %d states '# scale: %s'", brdffit_scale_name(s),
                 t->scale_line, brdffit_scale_name(t->scale));
        return why;
    }
    if (t->scale_line == 0) {
        t->scale = s;
        t->scale_line = lineno;
    }
    return NULL;
}

int pub_scale_mismatch(const pub_table *t, brdffit_scale scale, char *msg, size_t len)
{
    if (t->scale_line <= 0 || t->scale == scale)
        return 0;
    snprintf(msg, len, "%.1200s states '# scale: %s' (line %d), but the tables are read with "
             "--scale %s", t->path, brdffit_scale_name(t->scale), t->scale_line,
             brdffit_scale_name(scale));
    return 1;
}

const char *pub_scale_advice(const pub_table *t)
{
    return t->scale == BRDFFIT_SCALE_FLAT
               ? "pass --scale flat to compare on the data its parameters were fitted to, or "
                 "--allow-scale-mismatch to compare anyway"
               : "pass --scale standard to compare on the data its parameters were fitted to, "
                 "or --allow-scale-mismatch to compare anyway";
}

/* row appended to t's rows: NULL, or why not. */
static const char *append_row(pub_table *t, const pub_row *row, int *cap_rows)
{
    if (t->n == *cap_rows) {
        int cap = *cap_rows ? *cap_rows * 2 : 128;
        pub_row *g = realloc(t->rows, (size_t)cap * sizeof *g);
        if (!g)
            return "out of memory";
        t->rows = g;
        *cap_rows = cap;
    }
    t->rows[t->n++] = *row;
    return NULL;
}

int pub_read(const char *path, pub_table *t, brdffit_error *err)
{
    memset(t, 0, sizeof *t);
    snprintf(t->path, sizeof t->path, "%s", path);
    FILE *f = cli_fopen_regular(path, err);
    if (!f)
        return -1;
    char *line = NULL, why[256];
    size_t cap = 0;
    int lineno = 0, header = 0, cap_rows = 0;
    const char *fault = NULL;
    while (!fault && getline(&line, &cap, f) > 0) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '#')
            fault = read_comment(line, lineno, t, why, sizeof why);
        if (line[0] == '#' || line[0] == '\0')
            continue;
        char *fld[PUB_FIELDS + 1];
        int nf = split_tabs(line, fld, PUB_FIELDS);
        if (!header) {
            if (nf != PUB_FIELDS || strcmp(fld[0], "material") != 0 || strcmp(fld[1], "model") != 0)
                fault = "expected the header 'material<TAB>model<TAB>d_r ... p2' (11 columns)";
            header = 1;
            continue;
        }
        pub_row row;
        const pub_row *first;
        if (nf != PUB_FIELDS)
            fault = "expected 11 tab-separated columns";
        else if ((fault = parse_row(fld, &row, why, sizeof why)) != NULL)
            continue; /* the loop ends on it */
        else if ((first = pub_find(t, row.material, row.model)) != NULL) {
            snprintf(why, sizeof why, "a second row of %.100s %s (the first is line %d)",
                     row.material, brdffit_model_get(row.model)->name, first->line);
            fault = why;
        } else {
            row.line = lineno;
            fault = append_row(t, &row, &cap_rows);
        }
    }
    if (!fault && lineno == 0)
        fault = "the file is empty (a header line 'material<TAB>model<TAB>...' expected)";
    else if (!fault && !header)
        fault = "no header line 'material<TAB>model<TAB>...'";
    free(line);
    fclose(f);
    if (!fault)
        return 0;
    pub_free(t);
    return bad(err, path, lineno, fault);
}

void pub_free(pub_table *t)
{
    free(t->rows);
    t->rows = NULL;
    t->n = 0;
}

const pub_row *pub_find(const pub_table *t, const char *material, brdffit_model model)
{
    for (int i = 0; t && i < t->n; i++)
        if (t->rows[i].model == model && strcmp(t->rows[i].material, material) == 0)
            return &t->rows[i];
    return NULL;
}
