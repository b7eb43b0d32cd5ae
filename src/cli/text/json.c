/* SPDX-License-Identifier: MIT */
/* json.c -- JSON text for the --json records: escaped strings, numbers that round-trip.
 * A string is bytes (a file name need not be UTF-8): each byte that is not
 * part of well-formed UTF-8 is written as the escape of a lone low surrogate,
 * \udc80..\udcff for bytes 0x80..0xff (Python's "surrogateescape"), which no
 * UTF-8 text holds; jsonread.c turns them back into those bytes. */
#include "cli.h"
#include "utf8.h"

#include <math.h>

void json_string(FILE *f, const char *s)
{
    if (!s) {
        fputs("null", f);
        return;
    }
    const unsigned char *p = (const unsigned char *)s;
    putc('"', f);
    while (*p) {
        unsigned c = *p;
        switch (c) {
        case '"': fputs("\\\"", f); p++; continue;
        case '\\': fputs("\\\\", f); p++; continue;
        case '\b': fputs("\\b", f); p++; continue;
        case '\f': fputs("\\f", f); p++; continue;
        case '\n': fputs("\\n", f); p++; continue;
        case '\r': fputs("\\r", f); p++; continue;
        case '\t': fputs("\\t", f); p++; continue;
        default: break;
        }
        if (c < 0x20 || c == 0x7F) {
            fprintf(f, "\\u%04x", c);
            p++;
            continue;
        }
        unsigned cp;
        int n = utf8_seq(p, &cp);
        if (n == 0) { /* a byte that is not UTF-8: a lone low surrogate, U+DC80..U+DCFF */
            fprintf(f, "\\udc%02x", c);
            p++;
            continue;
        }
        fwrite(p, 1, (size_t)n, f);
        p += n;
    }
    putc('"', f);
}

void json_number(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.17g", x);
    else
        fputs("null", f);
}

void json_numbers(FILE *f, const double *x, int n)
{
    putc('[', f);
    for (int i = 0; i < n; i++) {
        if (i)
            putc(',', f);
        json_number(f, x[i]);
    }
    putc(']', f);
}
