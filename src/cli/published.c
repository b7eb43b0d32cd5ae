/* SPDX-License-Identifier: MIT */
/* published.c -- a table of published fits (the format of ngan2005-fits.tsv):
 * '#' comment lines, a header "material model d_r d_g d_b s_r s_g s_b p0 p1 p2",
 * then one row per material and model, tab-separated; an empty p is 0. */
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
    snprintf(err->message, sizeof err->message, "%.1500s: line %d: %.300s", path, line, why);
    return -1;
}

int pub_read(const char *path, pub_table *t, brdffit_error *err)
{
    memset(t, 0, sizeof *t);
    snprintf(t->path, sizeof t->path, "%s", path);
    FILE *f = fopen(path, "r");
    if (!f) {
        err->status = BRDFFIT_E_FILE_OPEN;
        snprintf(err->message, sizeof err->message, "%.1800s: cannot open: %s", path,
                 strerror(errno));
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t n;
    int lineno = 0, header = 0, rc = 0, cap_rows = 0;
    while ((n = getline(&line, &cap, f)) > 0) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '#' || line[0] == '\0')
            continue;
        char *fld[PUB_FIELDS + 1];
        int nf = split_tabs(line, fld, PUB_FIELDS);
        if (!header) {
            if (nf != PUB_FIELDS || strcmp(fld[0], "material") != 0 || strcmp(fld[1], "model") != 0) {
                rc = bad(err, path, lineno,
                         "expected the header 'material<TAB>model<TAB>d_r ... p2' (11 columns)");
                break;
            }
            header = 1;
            continue;
        }
        if (nf != PUB_FIELDS) {
            rc = bad(err, path, lineno, "expected 11 tab-separated columns");
            break;
        }
        pub_row row;
        memset(&row, 0, sizeof row);
        if (strlen(fld[0]) == 0 || strlen(fld[0]) >= sizeof row.material) {
            rc = bad(err, path, lineno, "empty or too long material name");
            break;
        }
        strcpy(row.material, fld[0]);
        if (brdffit_model_from_name(fld[1], &row.model) != BRDFFIT_OK) {
            char why[256];
            snprintf(why, sizeof why, "unknown model '%.100s'", fld[1]);
            rc = bad(err, path, lineno, why);
            break;
        }
        double v[9];
        int okv = 1;
        for (int k = 0; k < 9; k++) {
            const char *s = fld[2 + k];
            if (k >= 6 && s[0] == '\0')
                v[k] = 0;
            else if (cli_parse_double(s, &v[k]) != 0)
                okv = 0;
        }
        if (!okv) {
            rc = bad(err, path, lineno, "a value is not a finite number");
            break;
        }
        memcpy(row.params.d, v, sizeof row.params.d);
        memcpy(row.params.s, v + 3, sizeof row.params.s);
        memcpy(row.params.p, v + 6, sizeof row.params.p);
        if (t->n == cap_rows) {
            cap_rows = cap_rows ? cap_rows * 2 : 128;
            pub_row *g = realloc(t->rows, (size_t)cap_rows * sizeof *g);
            if (!g) {
                rc = bad(err, path, lineno, "out of memory");
                break;
            }
            t->rows = g;
        }
        t->rows[t->n++] = row;
    }
    if (rc == 0 && !header)
        rc = bad(err, path, lineno, "no header line 'material<TAB>model<TAB>...'");
    free(line);
    fclose(f);
    if (rc != 0)
        pub_free(t);
    return rc;
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
