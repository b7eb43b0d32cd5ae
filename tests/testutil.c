/* testutil.c -- see testutil.h. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *tu_shared(const char *rel, char *buf, size_t len)
{
    const char *root = getenv("BRDFFIT_SHARED");
    snprintf(buf, len, "%s/%s", root && *root ? root : "../shared", rel);
    return buf;
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

double tu_reldiff(double a, double b)
{
    double m = fmax(fmax(fabs(a), fabs(b)), 1e-300);
    return fabs(a - b) / m;
}
