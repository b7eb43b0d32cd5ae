/* SPDX-License-Identifier: MIT */
/* utf8.h -- the one UTF-8 decoder of the program's text writers (json.c,
 * svg.c, text.c): what counts as well-formed is decided here only. */
#ifndef BRDFFIT_CLI_UTF8_H
#define BRDFFIT_CLI_UTF8_H

/* Length (1..4) of the well-formed UTF-8 sequence at s, with its code point
 * in *cp, or 0 when the bytes there are not one: a stray continuation byte,
 * a truncated sequence (a NUL ends it), an overlong form, a surrogate
 * (U+D800..U+DFFF) or a code point above U+10FFFF. */
int utf8_seq(const unsigned char *s, unsigned *cp);

#endif
