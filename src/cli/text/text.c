/* SPDX-License-Identifier: MIT */
/* text.c -- text for the terminal: names and messages that come from files
 * or the command line printed with their control characters made harmless,
 * and long paths shortened so that what follows them is not cut off. */
#include "cli.h"
#include "utf8.h"

#include <stdarg.h>
#include <string.h>


/* s with every control character, C1 control and byte outside well-formed
 * UTF-8 written as \xHH; newlines too unless lines, then as a newline and
 * an indent (so that no line of it can pass for a line of the program's). */
static void plain(FILE *f, const char *s, int lines)
{
    for (const unsigned char *p = (const unsigned char *)s; *p;) {
        if (*p >= 0x20 && *p < 0x7F) {
            putc(*p++, f);
            continue;
        }
        if (lines && *p == '\n') {
            fputs("\n    ", f);
            p++;
            continue;
        }
        unsigned cp;
        int n = *p >= 0x80 ? utf8_seq(p, &cp) : 0;
        /* C1 controls (U+0080..U+009F) act on terminals as ESC sequences do */
        if (n > 0 && cp < 0xA0)
            n = 0;
        if (n > 0) {
            fwrite(p, 1, (size_t)n, f);
            p += n;
        } else {
            fprintf(f, "\\x%02x", *p++);
        }
    }
}

void plain_string(FILE *f, const char *s)
{
    plain(f, s, 0);
}

void plain_lines(FILE *f, const char *s)
{
    plain(f, s, 1);
}

void cli_error(const char *fmt, ...)
{
    char msg[3 * BRDFFIT_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fputs("brdffit: ", stderr);
    plain_string(stderr, msg);
    putc('\n', stderr);
}

const char *cli_brief(const char *s, char *buf, size_t len)
{
    size_t n = strlen(s);
    if (len < 8 || n < len) {
        snprintf(buf, len, "%s", s);
        return buf;
    }
    size_t keep = len - 4, head = keep / 3, tail = keep - head;
    memcpy(buf, s, head);
    memcpy(buf + head, "...", 3);
    memcpy(buf + head + 3, s + n - tail, tail);
    buf[head + 3 + tail] = '\0';
    return buf;
}
