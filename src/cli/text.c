/* text.c -- text for the terminal: names and messages that come from files
 * or the command line printed with their control characters made harmless. */
#include "cli.h"

void plain_string(FILE *f, const char *s)
{
    for (const unsigned char *p = (const unsigned char *)s; *p; p++)
        putc(*p < 0x20 || *p == 0x7F ? '?' : *p, f);
}
