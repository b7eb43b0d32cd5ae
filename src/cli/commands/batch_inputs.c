/* SPDX-License-Identifier: MIT */
/* batch_inputs.c -- the materials of a batch's inputs (tables, directories
 * of *.binary, @LIST files): sorted, without repeats, this shard's share. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <dirent.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int add_material(material_list *L, const char *path, int embedded)
{
    if (L->n == L->cap) {
        int cap = L->cap ? L->cap * 2 : 64;
        batch_material *g = realloc(L->m, (size_t)cap * sizeof *g);
        if (!g)
            return -1;
        L->m = g;
        L->cap = cap;
    }
    batch_material *m = &L->m[L->n++];
    memset(m, 0, sizeof *m);
    m->embedded = embedded;
    if (embedded) {
        snprintf(m->name, sizeof m->name, "%s", cli_demo_name());
    } else {
        snprintf(m->path, sizeof m->path, "%s", path);
        cli_material_name(path, m->name, sizeof m->name);
    }
    return 0;
}

static int has_suffix(const char *s, const char *suf)
{
    size_t n = strlen(s), k = strlen(suf);
    return n > k && strcmp(s + n - k, suf) == 0;
}

static int add_directory(material_list *L, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        cli_error("cannot read the directory %s: %s", dir, strerror(errno));
        return -1;
    }
    struct dirent *e;
    int rc = 0, found = 0;
    while ((e = readdir(d)) != NULL && rc == 0) {
        if (e->d_name[0] == '.' || !has_suffix(e->d_name, ".binary"))
            continue;
        char path[BJ_PATH_MAX];
        if (out_join(path, sizeof path, dir, e->d_name) != 0 || add_material(L, path, 0) != 0)
            rc = -1;
        found++;
    }
    closedir(d);
    if (rc == 0 && found == 0)
        cli_error("note: no *.binary file in %s", dir);
    return rc;
}

static int add_list_file(material_list *L, const char *list)
{
    brdffit_error err;
    FILE *f = cli_fopen_regular(list, &err);
    if (!f) {
        cli_error("cannot read the list %s", err.message);
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    int rc = 0;
    while (rc == 0 && getline(&line, &cap, f) > 0) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '\0' || line[0] == '#')
            continue;
        rc = add_material(L, line, 0);
    }
    free(line);
    fclose(f);
    return rc;
}

static int by_name(const void *a, const void *b)
{
    const batch_material *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    return c ? c : strcmp(x->path, y->path);
}

/* The materials of the inputs, sorted by name, without repeats; then this shard's share. */
int batch_collect(const batch_options *b, material_list *L)
{
    for (int i = 0; i < b->common.nfiles; i++) {
        const char *in = b->common.files[i];
        struct stat st;
        int rc;
        if (in[0] == '@')
            rc = add_list_file(L, in + 1);
        else if (stat(in, &st) == 0 && S_ISDIR(st.st_mode))
            rc = add_directory(L, in);
        else if (cli_is_text_file(in))
            return cli_usage_error("%s is a text file, not a MERL table: did you mean @%s (a list "
                                   "of tables, one a line)?", in, in);
        else
            rc = add_material(L, in, 0); /* a missing file becomes a failure row */
        if (rc != 0)
            return CLI_USAGE;
    }
    if (b->demo && add_material(L, NULL, 1) != 0)
        return CLI_FAILED;
    qsort(L->m, (size_t)L->n, sizeof *L->m, by_name);
    int w = 0;
    for (int i = 0; i < L->n; i++) {
        if (w > 0 && strcmp(L->m[w - 1].name, L->m[i].name) == 0) {
            if (strcmp(L->m[w - 1].path, L->m[i].path) == 0)
                continue; /* the same file twice */
            return cli_usage_error("two inputs are named '%s' (%s and %s): the report has one "
                                   "page per name",
                                   L->m[i].name, L->m[w - 1].path, L->m[i].path);
        }
        if (strcmp(L->m[i].name, ".") == 0 || strcmp(L->m[i].name, "..") == 0 || !L->m[i].name[0]
            || strchr(L->m[i].name, '/'))
            return cli_usage_error("'%s' cannot name a material (its page directory)", L->m[i].path);
        L->m[w++] = L->m[i];
    }
    L->n = w;
    /* the shard: every N-th of the sorted list, from the K-th */
    w = 0;
    for (int i = 0; i < L->n; i++)
        if (i % b->shard_n == b->shard_k - 1)
            L->m[w++] = L->m[i];
    L->n = w;
    return CLI_OK;
}
