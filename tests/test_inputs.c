/* SPDX-License-Identifier: MIT */
/* test_inputs.c -- what the program reads ($BRDFFIT_CLI): a FIFO given
 * wherever a path is read is refused at once (never waited on), a journal's
 * records are judged by their values (a tampered one is ignored with its
 * line number and its fit done again), the program's own records round-trip
 * (a failure to read, a name that is not UTF-8), and the messages of eval and
 * score about numbers they cannot use.  The table is made here (a Ward
 * lobe), so nothing needs ../shared. */
#define _DEFAULT_SOURCE
#include "testutil.h"
#include "batch.h"
#include "cli.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Fast batches: one model, one start, no pictures. */
#define QUICK "--model ward --starts 1 --no-render --no-plot"

static void tmpdir(char *buf, size_t len)
{
    const char *t = getenv("TMPDIR");
    snprintf(buf, len, "%s/brdffit-inputs-XXXXXX", t && *t ? t : "/tmp");
    ck_assert_ptr_nonnull(mkdtemp(buf));
}

/* DIR/NAME: a MERL table of a Ward material. */
static void make_table(const char *dir, const char *name)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    brdffit_table *t = NULL;
    brdffit_error err;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    brdffit_params p;
    memset(&p, 0, sizeof p);
    for (int c = 0; c < 3; c++) {
        p.d[c] = 0.1 + 0.05 * c;
        p.s[c] = 0.05;
    }
    p.p[0] = 0.2;
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_WARD, &p, BRDFFIT_SCALE_STANDARD, &err),
                     BRDFFIT_OK);
    ck_assert_msg(brdffit_table_write(t, path, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
}

static tu_run_out run(const char *args)
{
    return tu_run_cli("", args);
}

/* The lines of DIR/journal.jsonl whose kind is kind. */
static int journal_count(const char *dir, const char *kind)
{
    char path[1200], want[64];
    snprintf(path, sizeof path, "%s/journal.jsonl", dir);
    snprintf(want, sizeof want, "{\"kind\":\"%s\"", kind);
    char *j = tu_slurp(path);
    if (!j)
        return 0;
    int n = 0;
    for (char *p = j; (p = strstr(p, want)) != NULL; p++)
        n++;
    free(j);
    return n;
}

/* ------------------------------------------------------------------ FIFOs */

/* Each command line reads a FIFO (%1$s is the test's directory): DIR/fifo,
 * or DIR/jd whose journal.jsonl is one. */
static const char *const fifo_cases[] = {
    "fit '%1$s/fifo'",
    "batch '%1$s/fifo' --out '%1$s/o' " QUICK,
    "batch '@%1$s/fifo' --out '%1$s/o' " QUICK,
    "batch '%1$s/t.binary' --published '%1$s/fifo' --out '%1$s/o' " QUICK,
    "batch '%1$s/t.binary' --out '%1$s/jd' " QUICK,
    "score '%1$s/t.binary' --fits '%1$s/fifo'",
    "render '%1$s/t.binary' --fits '%1$s/fifo' --out '%1$s/r'",
    "render '%1$s/t.binary' --model ward --env '%1$s/fifo' --out '%1$s/r'",
    "report '%1$s/jd' --out '%1$s/rep'",
};
enum { NFIFO = (int)(sizeof fifo_cases / sizeof fifo_cases[0]) };

/* Refused with a message within the timeout: `timeout` exits 124 when the
 * program is still waiting on the FIFO's open. */
START_TEST(fifo_inputs_are_refused_at_once)
{
    char dir[512], path[1200], args[4096], jd[1024];
    tmpdir(dir, sizeof dir);
    make_table(dir, "t.binary");
    snprintf(path, sizeof path, "%s/fifo", dir);
    ck_assert_int_eq(mkfifo(path, 0600), 0);
    snprintf(jd, sizeof jd, "%s/jd", dir);
    ck_assert_int_eq(mkdir(jd, 0755), 0);
    snprintf(path, sizeof path, "%s/journal.jsonl", jd);
    ck_assert_int_eq(mkfifo(path, 0600), 0);
    snprintf(args, sizeof args, fifo_cases[_i], dir);
    tu_run_out r = tu_run_cli("timeout 60", args);
    ck_assert_msg(r.status != 124, "brdffit %s: still waiting after 60 s", args);
    ck_assert_msg(r.status != 0, "brdffit %s: exit 0\n%s", args, r.err);
    ck_assert_msg(strstr(r.err, "fifo: not a regular file") ||
                      strstr(r.err, "journal.jsonl: not a regular file"),
                  "brdffit %s: no message naming the FIFO:\n%s", args, r.err);
    tu_run_free(&r);
    ck_assert_int_eq(tu_remove_tree(dir), 0);
}
END_TEST

/* ------------------------------------------------------------------ the program's own records */

/* A table that cannot be read is journaled once: the failure record reads
 * back as written, so the second run neither ignores a line nor adds one. */
START_TEST(unreadable_input_is_journaled_once)
{
    char dir[512], args[2048], out[1024];
    tmpdir(dir, sizeof dir);
    snprintf(out, sizeof out, "%s/o", dir);
    snprintf(args, sizeof args, "batch /dev/null --out '%s' " QUICK, out);
    for (int run_no = 0; run_no < 2; run_no++) {
        tu_run_out r = run(args);
        ck_assert_msg(r.status != 0, "a failure exits 0:\n%s", r.err);
        ck_assert_msg(strstr(r.err, "/dev/null: not a regular file"), "%s", r.err);
        ck_assert_msg(!strstr(r.err, "ignored"), "run %d ignored a line:\n%s", run_no, r.err);
        tu_run_free(&r);
        ck_assert_int_eq(journal_count(out, "failure"), 1);
    }
    ck_assert_int_eq(tu_remove_tree(dir), 0);
}
END_TEST

/* A file name that is not UTF-8 is journaled losslessly (\udcXX) and so
 * matched on the next run: fitted once. */
START_TEST(name_not_utf8_is_fitted_once)
{
    char dir[512], args[2048], out[1024];
    tmpdir(dir, sizeof dir);
    make_table(dir, "na\xef" "me.binary");
    snprintf(out, sizeof out, "%s/o", dir);
    snprintf(args, sizeof args, "batch '%s/na\xef" "me.binary' --out '%s' " QUICK, dir, out);
    for (int run_no = 0; run_no < 2; run_no++) {
        tu_run_out r = run(args);
        TU_EXPECT_STATUS(r, 0, args);
        if (run_no == 1)
            ck_assert_msg(strstr(r.err, "done (journaled)"), "fitted again:\n%s", r.err);
        tu_run_free(&r);
        ck_assert_int_eq(journal_count(out, "fit"), 1);
    }
    char path[1200];
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *j = tu_slurp(path);
    ck_assert_ptr_nonnull(j);
    ck_assert_msg(strstr(j, "\"material\":\"na\\udcefme\""), "%s", j);
    free(j);
    snprintf(args, sizeof args, "report '%s' --out '%s/rep'", out, dir);
    tu_run_out r = run(args);
    TU_EXPECT_STATUS(r, 0, args);
    tu_run_free(&r);
    ck_assert_int_eq(tu_remove_tree(dir), 0);
}
END_TEST

/* The same through the reader: a string with bytes that are not UTF-8
 * written by json_string reads back byte for byte. */
START_TEST(json_strings_keep_their_bytes)
{
    fit_record r, back;
    fr_init(&r, FR_FAILURE);
    snprintf(r.material, sizeof r.material, "a\xff\xc3(\xe2\x82 \xc3\xa9");
    snprintf(r.id.path, sizeof r.id.path, "/x/\x80\xbf.binary");
    snprintf(r.settings.version, sizeof r.settings.version, "1");
    snprintf(r.settings.scale, sizeof r.settings.scale, "standard");
    r.settings.cutoff_deg = 80;
    fr_set_failure(&r, BRDFFIT_E_FILE_OPEN, NULL);
    char *line = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&line, &len);
    fr_write_json(f, &r);
    ck_assert_int_eq(fclose(f), 0);
    ck_assert_int_eq(fr_read_json(line, &back, FR_NEED_KEY), 0);
    ck_assert_str_eq(back.material, r.material);
    ck_assert_str_eq(back.id.path, r.id.path);
    ck_assert_int_eq(back.id.size, -1);
    char why[320];
    const char *bad = fr_check(&back, why, sizeof why);
    ck_assert_msg(bad == NULL, "%s", bad);
    free(line);
}
END_TEST

/* ------------------------------------------------------------------ tampered records */

/* line with the value of "key" replaced by value (a new string). */
static char *with_member(const char *line, const char *key, const char *value)
{
    char k[64];
    snprintf(k, sizeof k, "\"%s\":", key);
    const char *at = strstr(line, k);
    ck_assert_msg(at != NULL, "no %s in %s", key, line);
    const char *v = at + strlen(k), *end;
    if (*v == '[')
        end = strchr(v, ']') + 1;
    else if (*v == '{')
        end = strchr(v, '}') + 1;
    else if (*v == '"')
        end = strchr(v + 1, '"') + 1;
    else
        end = v + strcspn(v, ",}");
    size_t n = strlen(line) + strlen(value) + 1;
    char *out = malloc(n);
    ck_assert_ptr_nonnull(out);
    snprintf(out, n, "%.*s%s%s", (int)(v - line), line, value, end);
    return out;
}

typedef struct tamper {
    const char *key, *value;
    const char *why; /* a part of the message */
} tamper;

static const tamper tampers[] = {
    { "error", "-1", "the Error is not a finite number >= 0" },
    { "error", "null", "the Error is not a finite number >= 0" },
    { "d", "[1,2]", "not a journal record" },
    { "p", "[]", "p holds 0 numbers, ward has 1 parameters" },
    { "p", "[5]", "parameters out of range" },
    { "s", "[0.1,-1,0.1]", "parameters out of range" },
    { "model", "\"nope\"", "no model of this version" },
    { "material", "\"\"", "the material name is empty" },
    { "hash", "\"xyz\"", "size or hash" },
    { "iterations", "null", "a fit without its iterations" },
    { "errors", "{\"ngan-l2\":1,\"log\":2,\"cube-root\":3}", "is not its Error under its metric ngan-l2" },
    { "errors", "{\"ngan-l2\":1,\"log\":-2,\"cube-root\":3}", "the Error under log is not a finite number" },
    { "errors", "{\"ngan-l2\":1,\"log\":null,\"cube-root\":null}", "is not its Error under its metric ngan-l2" },
    { "metric", "\"l3\"", "metric \"l3\" is not a metric" },
};
enum { NTAMPER = (int)(sizeof tampers / sizeof tampers[0]) };

/* Each tampered fit record is ignored, its line said, and the fit done again;
 * the next run takes the new record. */
START_TEST(tampered_records_are_ignored_and_refitted)
{
    const tamper *tp = &tampers[_i];
    char dir[512], args[2048], out[1024], path[1200];
    tmpdir(dir, sizeof dir);
    make_table(dir, "t.binary");
    snprintf(out, sizeof out, "%s/o", dir);
    snprintf(args, sizeof args, "batch '%s/t.binary' --out '%s' " QUICK, dir, out);
    tu_run_out r = run(args);
    TU_EXPECT_STATUS(r, 0, args);
    tu_run_free(&r);
    snprintf(path, sizeof path, "%s/journal.jsonl", out);
    char *j = tu_slurp(path);
    ck_assert_ptr_nonnull(j);
    char *fit = strstr(j, "{\"kind\":\"fit\"");
    ck_assert_ptr_nonnull(fit);
    fit[strcspn(fit, "\n")] = '\0';
    char *bad = with_member(fit, tp->key, tp->value);
    FILE *f = fopen(path, "w"); /* the tampered record alone, on line 1 */
    ck_assert_ptr_nonnull(f);
    fprintf(f, "%s\n", bad);
    ck_assert_int_eq(fclose(f), 0);
    free(bad);
    free(j);

    r = run(args);
    TU_EXPECT_STATUS(r, 0, args);
    ck_assert_msg(strstr(r.err, "journal.jsonl: line 1: ") && strstr(r.err, tp->why) &&
                      strstr(r.err, "ignored"),
                  "%s=%s: not said:\n%s", tp->key, tp->value, r.err);
    ck_assert_msg(!strstr(r.err, "(journaled)"), "%s=%s: kept:\n%s", tp->key, tp->value, r.err);
    tu_run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 2);

    r = run(args);
    TU_EXPECT_STATUS(r, 0, args);
    ck_assert_msg(strstr(r.err, "done (journaled)"), "%s", r.err);
    int said = 0; /* the ignored line said once a run */
    for (const char *p = r.err; (p = strstr(p, "journal.jsonl: line ")) != NULL; p++)
        said++;
    ck_assert_msg(said == 1, "said %d times:\n%s", said, r.err);
    tu_run_free(&r);
    ck_assert_int_eq(journal_count(out, "fit"), 2);
    ck_assert_int_eq(tu_remove_tree(dir), 0);
}
END_TEST

/* ------------------------------------------------------------------ messages */

typedef struct message_case {
    const char *args;  /* %1$s: the test's directory (DIR/t.binary is a table) */
    int status;
    const char *says;  /* a part of stderr */
} message_case;

static const message_case messages[] = {
    { "score '%1$s/t.binary' --model ward --params ''", 2, "brdffit: --params needs a value" },
    { "fit '%1$s/t.binary' --metric l3", 2, "brdffit: --metric 'l3': expected ngan-l2, log or cube-root" },
    { "batch '%1$s/t.binary' --out '%1$s/o' --metric", 2, "brdffit: --metric needs a value" },
    { "score '%1$s/t.binary' --model ward --params=", 2, "brdffit: --params needs a value" },
    { "batch '%1$s/t.binary' --out=", 2, "brdffit: --out needs a value" },
    { "score '%1$s/t.binary' --model ward --params 1e308,0,0,1e308,0,0,0.1", 1,
      "--params: ward: the Error of these parameters is not a finite number" },
    { "score '%1$s/t.binary' --model ward --params 0.1,0.1,0.1,0.1,0.1,0.1,5", 1,
      "--params: ward: alpha = 5 outside" },
    { "eval ward 1e308 0 0 1e308 0 0 0.1 --wi 0 0 1 --wo 0 0 1", 1,
      "eval: ward gives inf 0 0 at these directions: not finite" },
    { "eval ward 0.5 0 0 0.5 0 0 0.1 --wi 0 0 0 --wo 0 0 1", 2, "--wi 0 0 0 is not a direction" },
};
enum { NMESSAGES = (int)(sizeof messages / sizeof messages[0]) };

START_TEST(number_messages_name_their_option)
{
    const message_case *c = &messages[_i];
    char dir[512], args[2048];
    tmpdir(dir, sizeof dir);
    make_table(dir, "t.binary");
    snprintf(args, sizeof args, c->args, dir);
    tu_run_out r = run(args);
    TU_EXPECT_STATUS(r, c->status, args);
    ck_assert_msg(strstr(r.err, c->says), "brdffit %s:\n%s", args, r.err);
    ck_assert_msg(!strstr(r.err, "fit failed") && !strstr(r.out, "fit failed"), "%s", r.out);
    tu_run_free(&r);
    ck_assert_int_eq(tu_remove_tree(dir), 0);
}
END_TEST

/* A direction whose squared length overflows or underflows is still a
 * direction: the same value as its normalised form. */
START_TEST(eval_takes_directions_of_any_length)
{
    static const char *const wis[] = { "0 0 1", "1e308 1e308 1e308", "1e-200 1e-200 1e-200",
                                       "1 1 1" };
    char args[512], first[128] = "", second[128] = "";
    for (int k = 0; k < 4; k++) {
        snprintf(args, sizeof args, "eval ward 0.5 0.4 0.3 0.2 0.2 0.2 0.1 --wi %s --wo 0.1 0 1",
                 wis[k]);
        tu_run_out r = run(args);
        TU_EXPECT_STATUS(r, 0, args);
        char *keep = k == 1 ? first : k == 3 ? second : NULL;
        if (keep)
            snprintf(keep, 128, "%s", r.out);
        tu_run_free(&r);
    }
    ck_assert_str_eq(first, second);
}
END_TEST

Suite *inputs_suite(void)
{
    Suite *s = suite_create("inputs");
    TCase *tc = tcase_create("fifo");
    tcase_set_timeout(tc, 300);
    tcase_add_loop_test(tc, fifo_inputs_are_refused_at_once, 0, NFIFO);
    suite_add_tcase(s, tc);
    tc = tcase_create("records");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, unreadable_input_is_journaled_once);
    tcase_add_test(tc, name_not_utf8_is_fitted_once);
    tcase_add_test(tc, json_strings_keep_their_bytes);
    tcase_add_loop_test(tc, tampered_records_are_ignored_and_refitted, 0, NTAMPER);
    suite_add_tcase(s, tc);
    tc = tcase_create("messages");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, number_messages_name_their_option, 0, NMESSAGES);
    tcase_add_test(tc, eval_takes_directions_of_any_length);
    suite_add_tcase(s, tc);
    return s;
}
