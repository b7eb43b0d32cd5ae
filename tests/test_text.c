/* SPDX-License-Identifier: MIT */
/* test_text.c -- the program's one UTF-8 decoder (src/cli/utf8.c) and the
 * three text writers that rely on it (JSON strings, terminal text, XML):
 * each keeps a well-formed sequence as it is and replaces a malformed one,
 * for the same byte strings. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "cli.h"
#include "svg.h"
#include "utf8.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct utf8_case {
    const char *bytes;
    int len;     /* utf8_seq's length, 0: malformed */
    unsigned cp; /* its code point where len > 0   */
} utf8_case;

static const utf8_case cases[] = {
    { "A", 1, 0x41 },
    { "\xC3\xA9", 2, 0xE9 },              /* e acute             */
    { "\xE2\x82\xAC", 3, 0x20AC },        /* euro sign           */
    { "\xF0\x9F\x98\x80", 4, 0x1F600 },   /* an emoji            */
    { "\xF4\x8F\xBF\xBF", 4, 0x10FFFF },  /* the last code point */
    { "\xC0\xAF", 0, 0 },                 /* overlong '/'        */
    { "\xE0\x80\xAF", 0, 0 },             /* overlong, 3 bytes   */
    { "\xF0\x80\x80\xAF", 0, 0 },         /* overlong, 4 bytes   */
    { "\xED\xA0\x80", 0, 0 },             /* a surrogate         */
    { "\xF4\x90\x80\x80", 0, 0 },         /* above U+10FFFF      */
    { "\x80", 0, 0 },                     /* stray continuation  */
    { "\xE2\x82", 0, 0 },                 /* truncated by the NUL */
    { "\xF5\x80\x80\x80", 0, 0 },         /* no such lead byte   */
};
enum { NCASES = (int)(sizeof cases / sizeof cases[0]) };

START_TEST(utf8_decodes_and_refuses)
{
    const utf8_case *c = &cases[_i];
    unsigned cp = 0xDEAD;
    int n = utf8_seq((const unsigned char *)c->bytes, &cp);
    ck_assert_msg(n == c->len, "case %d: length %d, expected %d", _i, n, c->len);
    if (n > 0)
        ck_assert_uint_eq(cp, c->cp);
}
END_TEST

/* What a writer made of s, as a string the test frees. */
static char *written(void (*writer)(FILE *, const char *), const char *s)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    ck_assert_ptr_nonnull(f);
    writer(f, s);
    ck_assert_int_eq(fclose(f), 0);
    return buf;
}

/* A well-formed non-ASCII sequence passes every writer as it is; a malformed
 * one never does (JSON writes \udcXX, XML U+FFFD, the terminal text \xHH). */
START_TEST(writers_agree_with_the_decoder)
{
    const utf8_case *c = &cases[_i];
    if (c->len == 1)
        return; /* ASCII: each writer has its own escapes */
    void (*writers[3])(FILE *, const char *) = { json_string, plain_string, xml_escape };
    for (int w = 0; w < 3; w++) {
        char *out = written(writers[w], c->bytes);
        int kept = strstr(out, c->bytes) != NULL;
        ck_assert_msg(kept == (c->len > 0), "case %d writer %d: wrote \"%s\"", _i, w, out);
        free(out);
    }
}
END_TEST

/* The terminal writer also refuses C1 controls (U+0080..U+009F), which are
 * well-formed UTF-8 but act like escape sequences on terminals. */
START_TEST(plain_refuses_c1_controls)
{
    char *out = written(plain_string, "a\xC2\x9B" "b");
    ck_assert_str_eq(out, "a\\xc2\\x9bb");
    free(out);
}
END_TEST

Suite *text_suite(void)
{
    Suite *s = suite_create("text");
    TCase *tc = tcase_create("utf8");
    tcase_add_loop_test(tc, utf8_decodes_and_refuses, 0, NCASES);
    tcase_add_loop_test(tc, writers_agree_with_the_decoder, 0, NCASES);
    tcase_add_test(tc, plain_refuses_c1_controls);
    suite_add_tcase(s, tc);
    return s;
}
