/* SPDX-License-Identifier: MIT */
/* material.c -- what a fit report is about: a material's name from its path. */
#include "cli.h"

#include <string.h>

const char *cli_material_name(const char *path, char *buf, size_t len)
{
    const char *base = strrchr(path, '/');
    base = base && base[1] ? base + 1 : path;
    size_t n = strlen(base);
    static const char ext[] = ".binary";
    const size_t ne = sizeof ext - 1;
    if (n > ne && strcmp(base + n - ne, ext) == 0)
        n -= ne;
    if (n >= len)
        n = len - 1;
    memcpy(buf, base, n);
    buf[n] = '\0';
    return buf;
}
