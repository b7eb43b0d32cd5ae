/* SPDX-License-Identifier: MIT */
/* test_published.c -- the program's reader of published-fit tables
 * (src/cli/pipeline/published.c, the format of ngan2005-fits.tsv): a good table reads
 * back value for value, with the scale its "# scale:" comment states; each
 * kind of malformed table is refused with the line and the reason, and
 * leaves no rows behind; a scale other than the tables' is found and named. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "batch.h"
#include "cli.h"

#include <check.h>
#include <string.h>
#include <unistd.h>

#define HEADER "material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\n"

/* pub_read of a file holding text; the path is removed again. */
static int read_text(const char *text, pub_table *t, brdffit_error *err)
{
    char path[512];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    ck_assert_int_eq(tu_write_bytes(path, text, strlen(text)), 0);
    int rc = pub_read(path, t, err);
    unlink(path);
    return rc;
}

START_TEST(published_reads_rows)
{
    pub_table t;
    brdffit_error err;
    const char *text = "# a comment\n" HEADER
                       "alum-bronze\tcook-torrance\t0.1\t0.2\t0.3\t0.4\t0.5\t0.6\t0.7\t0.08\t\n"
                       "\n"
                       "chrome\the\t0\t0\t0\t1\t1\t1\t20\t0.5\t1.6\r\n";
    ck_assert_int_eq(read_text(text, &t, &err), 0);
    ck_assert_int_eq(t.n, 2);
    const pub_row *r = pub_find(&t, "alum-bronze", BRDFFIT_COOK_TORRANCE);
    ck_assert_ptr_nonnull(r);
    ck_assert_double_eq(r->params.d[2], 0.3);
    ck_assert_double_eq(r->params.s[0], 0.4);
    ck_assert_double_eq(r->params.p[1], 0.08);
    ck_assert_double_eq(r->params.p[2], 0.0); /* an empty p is 0 */
    r = pub_find(&t, "chrome", BRDFFIT_HE);
    ck_assert_ptr_nonnull(r);
    ck_assert_double_eq(r->params.p[2], 1.6);
    ck_assert_ptr_null(pub_find(&t, "chrome", BRDFFIT_WARD));
    ck_assert_int_eq(t.scale_line, 0); /* no scale stated: no mismatch with either */
    char msg[512];
    ck_assert_int_eq(pub_scale_mismatch(&t, BRDFFIT_SCALE_STANDARD, msg, sizeof msg), 0);
    ck_assert_int_eq(pub_scale_mismatch(&t, BRDFFIT_SCALE_FLAT, msg, sizeof msg), 0);
    pub_free(&t);
}
END_TEST

START_TEST(published_reads_its_scale)
{
    pub_table t;
    brdffit_error err;
    const char *text = "# fitted to flat tables\n#  scale:  flat \n" HEADER
                       "a\tward\t0\t0\t0\t0\t0\t0\t0.1\t\t\n# scale: flat\n";
    ck_assert_int_eq(read_text(text, &t, &err), 0);
    ck_assert_int_eq(t.scale_line, 2);
    ck_assert_int_eq(t.scale, BRDFFIT_SCALE_FLAT);
    char msg[2048];
    ck_assert_int_eq(pub_scale_mismatch(&t, BRDFFIT_SCALE_FLAT, msg, sizeof msg), 0);
    ck_assert_int_eq(pub_scale_mismatch(&t, BRDFFIT_SCALE_STANDARD, msg, sizeof msg), 1);
    ck_assert_msg(strstr(msg, "states '# scale: flat' (line 2)") &&
                      strstr(msg, "read with --scale standard"), "%s", msg);
    ck_assert_ptr_nonnull(strstr(pub_scale_advice(&t), "pass --scale flat"));
    ck_assert_ptr_nonnull(strstr(pub_scale_advice(&t), "--allow-scale-mismatch"));
    pub_free(&t);
}
END_TEST

typedef struct bad_case {
    const char *text;
    const char *message; /* a part of the message */
} bad_case;

static const bad_case bad_cases[] = {
    { "", "the file is empty" },
    { HEADER "a\tward\t0\t0\t0\t0\t0\t0\t0.1\t\t\n" "b\tward\t0\t0\t0\t0\t0\t0\t0.1\t\t\n"
             "a\tWard\t0\t0\t0\t0\t0\t0\t0.2\t\t\n",
      "line 4: a second row of a ward (the first is line 2)" },
    { HEADER "a\tward\t0\t0\t0\t0\t0\t0\t0.1\t0.5\t\n",
      "line 2: p1 is '0.5', but ward has 1 parameter (p1 and after empty)" },
    { HEADER "a\tcook-torrance\t0\t0\t0\t0\t0\t0\t0.1\t0.2\t0\n",
      "line 2: p2 is '0', but cook-torrance has 2 parameters" },
    { "# only a comment\n", "no header line" },
    { "material\tmodel\n", "line 1: expected the header" },
    { HEADER "a\tward\t1\t2\t3\n", "line 2: expected 11 tab-separated columns" },
    { HEADER "a\tnot-a-model\t0\t0\t0\t0\t0\t0\t0\t0\t0\n", "line 2: unknown model 'not-a-model'" },
    { HEADER "a\tward\t0\t0\tnan\t0\t0\t0\t0.1\t\t\n", "line 2: a value is not a finite number" },
    { HEADER "a\tward\t0\t0\t0\t0\t0\t0\t\t\t\n" "b\tward\t0\t0\t0\t0\t0\t0\t0.1\t\t\t\n",
      "line 3: expected 11 tab-separated columns" },
    { HEADER "\tward\t0\t0\t0\t0\t0\t0\t0.1\t\t\n", "line 2: empty or too long material name" },
    { "# scale: linear\n" HEADER, "line 1: '# scale: linear': expected '# scale: standard' or" },
    { "# scale: flat please\n" HEADER, "line 1: '# scale: flat please': expected" },
    { "# scale: flat\n# scale: standard\n" HEADER,
      "line 2: '# scale: standard', but line 1 states '# scale: flat'" },
};
enum { NBAD = (int)(sizeof bad_cases / sizeof bad_cases[0]) };

START_TEST(published_refuses_malformed)
{
    pub_table t;
    brdffit_error err;
    memset(&err, 0, sizeof err);
    ck_assert_int_eq(read_text(bad_cases[_i].text, &t, &err), -1);
    ck_assert_int_eq(err.status, BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_msg(strstr(err.message, bad_cases[_i].message) != NULL, "case %d: \"%s\"", _i,
                  err.message);
    ck_assert_int_eq(t.n, 0);
    ck_assert_ptr_null(t.rows);
}
END_TEST

START_TEST(published_missing_file)
{
    pub_table t;
    brdffit_error err;
    ck_assert_int_eq(pub_read("/nonexistent/fits.tsv", &t, &err), -1);
    ck_assert_int_eq(err.status, BRDFFIT_E_FILE_OPEN);
    ck_assert_ptr_nonnull(strstr(err.message, "/nonexistent/fits.tsv: cannot open"));
}
END_TEST

Suite *published_suite(void)
{
    Suite *s = suite_create("published");
    TCase *tc = tcase_create("read");
    tcase_add_test(tc, published_reads_rows);
    tcase_add_test(tc, published_reads_its_scale);
    tcase_add_loop_test(tc, published_refuses_malformed, 0, NBAD);
    tcase_add_test(tc, published_missing_file);
    suite_add_tcase(s, tc);
    return s;
}
