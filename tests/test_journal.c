/* SPDX-License-Identifier: MIT */
/* test_journal.c -- the batch journal's line reader (src/cli/journal.c over
 * src/cli/jsonread.c): what the writer writes reads back the same, and a
 * line a damaged or hostile journal may hold is refused (the batch then
 * skips and counts it), never read as a record with impossible values. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "batch.h"
#include "cli.h"

#include <check.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FIT_HEAD "{\"kind\":\"fit\",\"material\":\"alum-bronze\",\"file\":{\"path\":\"/d/a.binary\",\"size\":"
#define FIT_MID  ",\"hash\":\"8143736677fba4d1\"},\"settings\":{\"version\":\"0.1.0\",\"scale\":\"standard\"," \
                 "\"cutoff_deg\":80,\"starts\":0},\"model\":\"ward\",\"ok\":true,\"status\":\"ok\",\"message\":\""
#define FIT_TAIL "\",\"d\":[0.08,0.05,0.02],\"s\":[0.04,0.02,0.01],\"p\":[0.03],\"lambda_um\":[0,0,0]," \
                 "\"error\":0.0568,\"iterations\":"
#define FIT_END  ",\"passes\":13,\"cminpack_info\":1,\"seconds\":0.2,\"samples\":923870,\"on_bound\":\"\"," \
                 "\"backend\":\"opencl\"}"

/* A fit line with the given size, message and iterations fields. */
static void fit_line(char *buf, size_t len, const char *size, const char *message, const char *it)
{
    snprintf(buf, len, "%s%s%s%s%s%s%s", FIT_HEAD, size, FIT_MID, message, FIT_TAIL, it, FIT_END);
}

START_TEST(journal_line_round_trips)
{
    char line[2048];
    fit_line(line, sizeof line, "34992012", "caf\xC3\xA9 \\u00e9 \\ud83d\\ude00", "3");
    bj_record r, back;
    ck_assert_int_eq(bj_record_parse(line, &r), 0);
    ck_assert_int_eq(r.kind, BJ_FIT);
    ck_assert_int_eq(r.id.size, 34992012);
    ck_assert_int_eq(r.iterations, 3);
    ck_assert_int_eq(r.samples, 923870);
    ck_assert_str_eq(r.message, "caf\xC3\xA9 \xC3\xA9 \xF0\x9F\x98\x80");
    char *text = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&text, &n);
    ck_assert_ptr_nonnull(f);
    bj_record_json(f, &r);
    ck_assert_int_eq(fclose(f), 0);
    ck_assert_int_eq(bj_record_parse(text, &back), 0);
    ck_assert_str_eq(back.message, r.message);
    ck_assert_int_eq(back.id.size, r.id.size);
    ck_assert_double_eq(back.error, r.error);
    free(text);
}
END_TEST

typedef struct bad_line {
    const char *size, *message, *iterations;
} bad_line;

static const bad_line bad_lines[] = {
    { "1e999", "", "3" },           /* +inf: not a size                 */
    { "-1", "", "3" },              /* negative                          */
    { "1.5", "", "3" },             /* not whole                         */
    { "34992012", "", "1e10" },     /* beyond an int                     */
    { "34992012", "", "-2" },
    { "34992012", "\xC3(", "3" },   /* malformed UTF-8 in a string       */
    { "34992012", "\xED\xA0\x80", "3" }, /* a raw surrogate              */
    { "34992012", "\xC0\xAF", "3" },     /* overlong                     */
};
enum { NBAD = (int)(sizeof bad_lines / sizeof bad_lines[0]) };

/* A number beyond the double range anywhere in a line (here the Error, as
 * the journal fuzzer found: "error":0.05E568 read as inf, written back as
 * null, read again as NaN) is refused, not read as inf. */
START_TEST(journal_refuses_out_of_range_numbers)
{
    static const char *const fields[] = { "\"error\":0.05E568", "\"error\":-1e999",
                                          "\"error\":1e-999" };
    char line[2048];
    fit_line(line, sizeof line, "34992012", "", "3");
    char *at = strstr(line, "\"error\":0.0568");
    ck_assert_ptr_nonnull(at);
    size_t head = (size_t)(at - line), old = strlen("\"error\":0.0568");
    char edited[2100];
    snprintf(edited, sizeof edited, "%.*s%s%s", (int)head, line, fields[_i], at + old);
    bj_record r;
    if (_i < 2) {
        ck_assert_msg(bj_record_parse(edited, &r) == -1, "read as a record:\n%s", edited);
    } else { /* underflow is 0, a number JSON can say back */
        ck_assert_int_eq(bj_record_parse(edited, &r), 0);
        ck_assert(r.error == 0.0);
    }
}
END_TEST

START_TEST(journal_refuses_impossible_lines)
{
    const bad_line *b = &bad_lines[_i];
    char line[2048];
    fit_line(line, sizeof line, b->size, b->message, b->iterations);
    bj_record r;
    ck_assert_msg(bj_record_parse(line, &r) == -1, "case %d read as a record:\n%s", _i, line);
}
END_TEST

/* A file of n bytes, byte i = i * mul + add, into path. */
static void pattern_file(char *path, size_t len, size_t n, unsigned mul, unsigned add)
{
    ck_assert_ptr_nonnull(tu_tmpfile(path, len));
    unsigned char *data = malloc(n);
    ck_assert_ptr_nonnull(data);
    for (size_t i = 0; i < n; i++)
        data[i] = (unsigned char)(i * mul + add);
    ck_assert_int_eq(tu_write_bytes(path, data, n), 0);
    free(data);
}

typedef struct identify_job {
    const char *path;
    bj_identity want;
    int wrong; /* identities that differed from want */
} identify_job;

static void *identify_again(void *arg)
{
    identify_job *j = arg;
    for (int round = 0; round < 40; round++) {
        bj_identity id;
        brdffit_error err;
        if (bj_identify(j->path, &id, &err) != 0 || !bj_identity_equal(&id, &j->want))
            j->wrong++;
    }
    return NULL;
}

/* bj_identify from two threads at once (the batch's prefetch thread and its
 * main thread do): each file's identity is the one it has alone. */
START_TEST(identify_from_two_threads)
{
    char pa[512], pb[512];
    pattern_file(pa, sizeof pa, 3 << 16, 7, 1);
    pattern_file(pb, sizeof pb, 3 << 16, 13, 5);
    identify_job ja = { .path = pa }, jb = { .path = pb };
    brdffit_error err;
    ck_assert_msg(bj_identify(pa, &ja.want, &err) == 0, "%s", err.message);
    ck_assert_msg(bj_identify(pb, &jb.want, &err) == 0, "%s", err.message);
    ck_assert_str_ne(ja.want.hash, jb.want.hash);
    pthread_t ta, tb;
    ck_assert_int_eq(pthread_create(&ta, NULL, identify_again, &ja), 0);
    ck_assert_int_eq(pthread_create(&tb, NULL, identify_again, &jb), 0);
    pthread_join(ta, NULL);
    pthread_join(tb, NULL);
    ck_assert_int_eq(ja.wrong, 0);
    ck_assert_int_eq(jb.wrong, 0);
    unlink(pa);
    unlink(pb);
}
END_TEST

Suite *journal_suite(void)
{
    Suite *s = suite_create("journal");
    TCase *tc = tcase_create("lines");
    tcase_add_test(tc, journal_line_round_trips);
    tcase_add_test(tc, identify_from_two_threads);
    tcase_add_loop_test(tc, journal_refuses_impossible_lines, 0, NBAD);
    tcase_add_loop_test(tc, journal_refuses_out_of_range_numbers, 0, 3);
    suite_add_tcase(s, tc);
    return s;
}
