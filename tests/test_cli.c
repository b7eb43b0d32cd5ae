/* SPDX-License-Identifier: MIT */
/* test_cli.c -- the brdffit program ($BRDFFIT_CLI, default ./build/brdffit):
 * exit statuses, usage errors, failed files beside fitted ones, the JSON
 * Lines records (checked by a small JSON parser), demo, models, eval. */
#define _DEFAULT_SOURCE
#include "testutil.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* ------------------------------------------------------------------ running the program */

typedef tu_run_out run_out;

/* Run `brdffit ARGS` (args are already shell-quoted where needed). */
static run_out run(const char *args)
{
    return tu_run_cli("", args);
}

static void run_free(run_out *r)
{
    tu_run_free(r);
}

#define expect_status TU_EXPECT_STATUS

/* The blue-rubber table from ../shared (NULL, with a note, when unavailable). */
static const char *blue_rubber(char *buf, size_t len)
{
    const char *p = tu_merl_table("blue-rubber", buf, len);
    ck_assert_msg(p != NULL, "../shared/tools/merl-table blue-rubber failed");
    return p;
}

/* Split the output into lines (in place); returns the count. */
static int split_lines(char *text, char **lines, int max)
{
    int n = 0;
    char *save = NULL;
    for (char *l = strtok_r(text, "\n", &save); l && n < max; l = strtok_r(NULL, "\n", &save))
        lines[n++] = l;
    return n;
}

/* Checks every key a successful fit record must have. */
static void check_fit_record(const char *line, const char *want_material, const char *want_model)
{
    static const char *const keys[] = { "kind", "material", "model", "d", "s", "p", "error",
                                        "settings", "status", "status_code", "message",
                                        "iterations", "passes", "seconds", "seconds_build",
                                        "backend", "samples", "cminpack_info", "at_bound", "flags" };
    ck_assert_msg(tu_json_object_line(line), "not one JSON object: %s", line);
    ck_assert_msg(line[0] == '{' && line[strlen(line) - 1] == '}', "line: %s", line);
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        ck_assert_msg(tu_json_member(line, keys[k]) != NULL, "no \"%s\" in %s", keys[k], line);
    char s[256];
    ck_assert(tu_json_get_string(line, "status", s, sizeof s));
    ck_assert_msg(strcmp(s, "ok") == 0, "status %s in %s", s, line);
    double code;
    ck_assert(tu_json_get_number(line, "status_code", &code) && code == BRDFFIT_OK);
    ck_assert(tu_json_get_string(line, "kind", s, sizeof s));
    ck_assert_str_eq(s, "fit");
    ck_assert(tu_json_get_string(line, "material", s, sizeof s));
    ck_assert_str_eq(s, want_material);
    ck_assert(tu_json_get_string(line, "model", s, sizeof s));
    if (want_model)
        ck_assert_str_eq(s, want_model);
    brdffit_model m;
    ck_assert_int_eq(brdffit_model_from_name(s, &m, NULL), BRDFFIT_OK);
    double e;
    ck_assert_msg(tu_json_get_number(line, "error", &e) && isfinite(e) && e >= 0, "error in %s", line);
    ck_assert_int_eq(tu_json_array_len(line, "d"), 3);
    ck_assert_int_eq(tu_json_array_len(line, "s"), 3);
    ck_assert_int_eq(tu_json_array_len(line, "p"), brdffit_model_get(m)->nparams);
    const char *metric = tu_json_member(line, "settings");
    ck_assert_ptr_nonnull(metric);
    ck_assert(tu_json_get_string(metric, "metric", s, sizeof s));
    ck_assert_str_eq(s, brdffit_metric_name());
    double cut;
    ck_assert(tu_json_get_number(metric, "cutoff_deg", &cut));
    ck_assert(tu_json_get_string(metric, "scale", s, sizeof s));
    double n;
    ck_assert(tu_json_get_number(line, "samples", &n) && n > 0);
    ck_assert(tu_json_get_number(line, "iterations", &n) && n >= 0);
    ck_assert(tu_json_get_number(line, "passes", &n) && n >= 1);
    ck_assert(tu_json_get_number(line, "seconds", &n) && n >= 0);
    double b;
    ck_assert(tu_json_get_number(line, "seconds_build", &b) && b >= 0 && b <= n);
}

START_TEST(json_checker_self_test)
{
    ck_assert(tu_json_object_line("{\"a\":[1,2.5e-3,-0],\"b\":{\"c\":null},\"d\":\"x\\\"y\\u0001\"}"));
    ck_assert(!tu_json_object_line("{\"a\":nan}"));
    ck_assert(!tu_json_object_line("{\"a\":1,}"));
    ck_assert(!tu_json_object_line("{\"a\":\"tab\there\"}"));
    ck_assert(!tu_json_object_line("{\"a\":1} x"));
    ck_assert_int_eq(tu_json_array_len("{\"p\":[1,2,3]}", "p"), 3);
    ck_assert_int_eq(tu_json_array_len("{\"p\":[]}", "p"), 0);
    double x;
    ck_assert(tu_json_get_element("{\"p\":[1,2,3]}", "p", 2, &x) && x == 3);
}
END_TEST

/* ------------------------------------------------------------------ usage */

START_TEST(models_lists_all)
{
    run_out r = run("models");
    expect_status(r, 0, "models");
    for (int m = 0; m < brdffit_model_count(); m++) {
        const brdffit_model_info *mi = brdffit_model_get((brdffit_model)m);
        /* "name  title  p0 [lower, upper] unit (start), ...; N starts" */
        char line[256];
        snprintf(line, sizeof line, "\n%-18s %-18s %s [%g, %g]", mi->name, mi->title,
                 mi->params[0].name, mi->params[0].lower, mi->params[0].upper);
        ck_assert_msg(strstr(r.out, line) != NULL, "models does not list %s as '%s'", mi->name,
                      line + 1);
        const char *row = strstr(r.out, line) + 1, *end = strchr(row, '\n');
        char want[64];
        snprintf(want, sizeof want, "; %d starts", mi->default_starts);
        ck_assert_msg(strstr(row, want) && strstr(row, want) < end, "%s: no '%s'", mi->name, want);
        for (int k = 0; k < mi->nparams; k++) {
            const brdffit_param_info *pi = &mi->params[k];
            char one[128];
            snprintf(one, sizeof one, "%s [%g, %g]%s%s (%g)", pi->name, pi->lower, pi->upper,
                     *pi->unit ? " " : "", pi->unit, pi->start);
            ck_assert_msg(strstr(row, one) && strstr(row, one) < end, "%s: no '%s'", mi->name, one);
            ck_assert_msg(strstr(r.out, pi->description) != NULL, "no '%s'", pi->description);
        }
    }
    run_free(&r);
    r = run("models extra");
    expect_status(r, 2, "models extra");
    run_free(&r);
}
END_TEST

START_TEST(help_and_version)
{
    run_out r = run("--help");
    expect_status(r, 0, "--help");
    ck_assert(strstr(r.out, "Usage") != NULL);
    ck_assert(strstr(r.out, "fit") && strstr(r.out, "demo") && strstr(r.out, "brdffit help COMMAND"));
    run_free(&r);
    r = run("fit --help");
    expect_status(r, 0, "fit --help");
    ck_assert(strstr(r.out, "--json") != NULL);
    run_free(&r);
    r = run("--version");
    expect_status(r, 0, "--version");
    ck_assert_msg(strstr(r.out, brdffit_version()) != NULL, "version: %s", r.out);
    run_free(&r);
}
END_TEST

START_TEST(unknown_command)
{
    run_out r = run("frobnicate");
    expect_status(r, 2, "frobnicate");
    ck_assert(strstr(r.err, "frobnicate") != NULL);
    ck_assert(strstr(r.err, "Usage") != NULL);
    ck_assert_str_eq(r.out, "");
    run_free(&r);
    r = run("");
    expect_status(r, 2, "(nothing)");
    run_free(&r);
}
END_TEST

START_TEST(fit_without_files)
{
    run_out r = run("fit");
    expect_status(r, 2, "fit");
    ck_assert(strstr(r.err, "file") != NULL);
    run_free(&r);
    r = run("fit --model ward --json");
    expect_status(r, 2, "fit --model ward --json");
    run_free(&r);
}
END_TEST

static const char *const bad_cutoffs[] = { "abc", "0", "95", "nan", "inf", "-5", "80x", "''",
                                           "' 80'", "1e999", "90.0001" };

START_TEST(bad_cutoff)
{
    char args[256];
    snprintf(args, sizeof args, "fit --cutoff %s /nonexistent/x.binary", bad_cutoffs[_i]);
    run_out r = run(args);
    expect_status(r, 2, args);
    ck_assert_msg(strstr(r.err, "--cutoff") != NULL, "%s: stderr %s", args, r.err);
    ck_assert_msg(strstr(r.err, "x.binary") == NULL, "%s: the file was read: %s", args, r.err);
    run_free(&r);
}
END_TEST

START_TEST(unknown_model)
{
    run_out r = run("fit --model phong /nonexistent/x.binary");
    expect_status(r, 2, "fit --model phong");
    ck_assert(strstr(r.err, "phong") != NULL);
    for (int m = 0; m < brdffit_model_count(); m++) {
        const char *name = brdffit_model_get((brdffit_model)m)->name;
        ck_assert_msg(strstr(r.err, name) != NULL, "stderr does not name %s: %s", name, r.err);
    }
    run_free(&r);
    r = run("fit --model ward,,he /nonexistent/x.binary");
    expect_status(r, 2, "fit --model ward,,he");
    run_free(&r);
    r = run("fit --model /nonexistent/x.binary");
    expect_status(r, 2, "fit --model FILE");
    run_free(&r);
}
END_TEST

static const char *const bad_option_args[] = {
    "fit --frobnicate x.binary", "fit --scale linear x.binary", "fit --starts 0 x.binary",
    "fit --starts 2x x.binary",  "fit --backend cuda x.binary", "fit --device '' x.binary",
    "fit x.binary --cutoff",     "demo --starts -1",            "demo extra.binary",
    "fit -x x.binary",
};

START_TEST(bad_options)
{
    run_out r = run(bad_option_args[_i]);
    expect_status(r, 2, bad_option_args[_i]);
    ck_assert_msg(strstr(r.err, "--help") != NULL, "%s: %s", bad_option_args[_i], r.err);
    run_free(&r);
}
END_TEST

/* ------------------------------------------------------------------ files that cannot be read */

START_TEST(fit_missing_file)
{
    const char *path = "/nonexistent-brdffit-dir/missing.binary";
    run_out r = run("fit /nonexistent-brdffit-dir/missing.binary");
    expect_status(r, 1, "fit missing.binary");
    ck_assert_msg(strstr(r.err, path) != NULL, "stderr does not name %s: %s", path, r.err);
    run_free(&r);
}
END_TEST

/* A truncated table and a missing file: both reported on stderr and as JSON
 * records with "status", "status_code" and "message"; names with quotes, backslashes
 * and tabs come out escaped. */
START_TEST(json_failure_records)
{
    char dir[512], bad[1024];
    ck_assert_ptr_nonnull(tu_tmpfile(dir, sizeof dir));
    unlink(dir);
    ck_assert_int_eq(mkdir(dir, 0700), 0);
    const char *name = "we\"ird\\na\tme";
    snprintf(bad, sizeof bad, "%s/%s.binary", dir, name);
    unsigned char head[100];
    memset(head, 0, sizeof head);
    int32_t dims[3] = { 90, 90, 180 };
    memcpy(head, dims, sizeof dims);
    ck_assert_int_eq(tu_write_bytes(bad, head, sizeof head), 0);

    char args[4096];
    snprintf(args, sizeof args, "fit --json --model ward '%s' /nonexistent-brdffit-dir/gone.binary",
             bad);
    run_out r = run(args);
    expect_status(r, 1, args);
    /* stderr is for a terminal: the tab comes out as \x09 */
    char shown[1024];
    snprintf(shown, sizeof shown, "%s/we\"ird\\na\\x09me.binary", dir);
    ck_assert_msg(strstr(r.err, shown) != NULL, "stderr does not name %s: %s", shown, r.err);
    ck_assert(strstr(r.err, "/nonexistent-brdffit-dir/gone.binary") != NULL);
    char *lines[16];
    int n = split_lines(r.out, lines, 16);
    ck_assert_msg(n == 2, "%d JSON lines, expected 2", n);
    for (int i = 0; i < n; i++) {
        ck_assert_msg(tu_json_object_line(lines[i]), "not a JSON object: %s", lines[i]);
        char s[2048];
        ck_assert(tu_json_get_string(lines[i], "status", s, sizeof s));
        ck_assert_str_ne(s, "ok");
        double code;
        ck_assert(tu_json_get_number(lines[i], "status_code", &code));
        ck_assert_int_eq((int)code, i == 0 ? BRDFFIT_E_FILE_TRUNCATED : BRDFFIT_E_FILE_OPEN);
        ck_assert(tu_json_get_string(lines[i], "kind", s, sizeof s));
        ck_assert_str_eq(s, "failure");
        ck_assert(tu_json_get_string(lines[i], "message", s, sizeof s));
        ck_assert_msg(strstr(s, i == 0 ? bad : "gone.binary") != NULL, "message %s", s);
        ck_assert(tu_json_get_string(lines[i], "material", s, sizeof s));
        ck_assert_str_eq(s, i == 0 ? name : "gone");
        ck_assert_ptr_nonnull(tu_json_member(lines[i], "settings"));
    }
    run_free(&r);
    unlink(bad);
    rmdir(dir);
}
END_TEST

/* ------------------------------------------------------------------ fitting */

/* One good table and one missing file: exit 1, the good one still fitted. */
START_TEST(fit_good_and_missing)
{
    char table[1024], args[2048];
    blue_rubber(table, sizeof table);
    snprintf(args, sizeof args,
             "fit --model ward '%s' /nonexistent-brdffit-dir/missing.binary", table);
    run_out r = run(args);
    expect_status(r, 1, args);
    ck_assert_msg(strstr(r.err, "/nonexistent-brdffit-dir/missing.binary") != NULL, "%s", r.err);
    ck_assert_msg(strstr(r.out, "blue-rubber") != NULL, "no blue-rubber header:\n%s", r.out);
    ck_assert_msg(strstr(r.out, "ngan-l2") && strstr(r.out, "cutoff 80 deg") &&
                      strstr(r.out, "scale standard"),
                  "no metric line:\n%s", r.out);
    ck_assert_msg(strstr(r.out, "backend ") != NULL, "no backend line:\n%s", r.out);
    /* the ward row: name, 3 + 3 + 1 numbers, '-' for p1 p2 p3, the Error */
    const char *row = strstr(r.out, "\nward ");
    ck_assert_msg(row != NULL, "no ward row:\n%s", r.out);
    double v[7], e;
    char d1[8], d2[8], d3[8];
    int got = sscanf(row, " ward %lf %lf %lf %lf %lf %lf %lf %7s %7s %7s %lf", &v[0], &v[1], &v[2],
                     &v[3], &v[4], &v[5], &v[6], d1, d2, d3, &e);
    ck_assert_msg(got == 11, "ward row not parsed (%d fields): %.200s", got, row);
    ck_assert_str_eq(d1, "-");
    ck_assert_str_eq(d2, "-");
    ck_assert_str_eq(d3, "-");
    ck_assert(isfinite(e) && e > 0 && e < 1);
    for (int k = 0; k < 6; k++)
        ck_assert(v[k] >= 0);
    ck_assert(v[6] > 0 && v[6] <= 0.5);
    run_free(&r);
}
END_TEST

START_TEST(fit_json_good_and_missing)
{
    char table[1024], args[2048];
    blue_rubber(table, sizeof table);
    snprintf(args, sizeof args,
             "fit --json --model ward --cutoff 75 --scale flat '%s' /nonexistent-brdffit-dir/missing.binary",
             table);
    run_out r = run(args);
    expect_status(r, 1, args);
    char *lines[16];
    int n = split_lines(r.out, lines, 16);
    ck_assert_msg(n == 2, "%d lines, expected 2:\n%s", n, r.out);
    check_fit_record(lines[0], "blue-rubber", "ward");
    const char *metric = tu_json_member(lines[0], "settings");
    double cut;
    char scale[32];
    ck_assert(tu_json_get_number(metric, "cutoff_deg", &cut));
    ck_assert(cut == 75);
    ck_assert(tu_json_get_string(metric, "scale", scale, sizeof scale));
    ck_assert_str_eq(scale, "flat");
    ck_assert_msg(tu_json_object_line(lines[1]), "%s", lines[1]);
    char s[1024];
    ck_assert(tu_json_get_string(lines[1], "status", s, sizeof s));
    ck_assert_str_eq(s, brdffit_strerror(BRDFFIT_E_FILE_OPEN));
    ck_assert(tu_json_get_string(lines[1], "message", s, sizeof s));
    ck_assert(strstr(s, "/nonexistent-brdffit-dir/missing.binary") != NULL);
    run_free(&r);
}
END_TEST

/* `fit` reads the next file while it fits one (prefetch.c), or not
 * (--no-read-ahead: flag): with a missing and a truncated file between two
 * copies of one table, the records and the messages come in file order, each
 * failure as a read in order reports it, and the fourth file's fit (from the
 * sample set made ahead) equals the first's to the bit.  The first's Error
 * into *e0. */
static void read_ahead_case(const char *flag, double *e0)
{
    char table[1024], dir[] = "/tmp/brdffit-readahead-XXXXXX", cut[1100], args[4096];
    blue_rubber(table, sizeof table);
    ck_assert(mkdtemp(dir) != NULL);
    snprintf(cut, sizeof cut, "%s/cut.binary", dir);
    char *whole = tu_slurp(table);
    ck_assert(whole != NULL);
    FILE *f = fopen(cut, "wb");
    ck_assert(f != NULL && fwrite(whole, 1, 5000, f) == 5000 && fclose(f) == 0);
    free(whole);
    snprintf(args, sizeof args, "fit --json %s --model ward '%s' %s/missing.binary '%s' '%s'", flag,
             table, dir, cut, table);
    run_out r = run(args);
    expect_status(r, 1, args);
    char *lines[16];
    int n = split_lines(r.out, lines, 16);
    ck_assert_msg(n == 4, "%d lines, expected 4:\n%s", n, r.out);
    check_fit_record(lines[0], "blue-rubber", "ward");
    check_fit_record(lines[3], "blue-rubber", "ward");
    char s[1024];
    ck_assert(tu_json_get_string(lines[1], "status", s, sizeof s));
    ck_assert_str_eq(s, brdffit_strerror(BRDFFIT_E_FILE_OPEN));
    ck_assert(tu_json_get_string(lines[2], "status", s, sizeof s));
    ck_assert_str_eq(s, brdffit_strerror(BRDFFIT_E_FILE_TRUNCATED));
    double e3;
    ck_assert(tu_json_get_number(lines[0], "error", e0));
    ck_assert(tu_json_get_number(lines[3], "error", &e3));
    ck_assert_msg(memcmp(e0, &e3, sizeof e3) == 0, "%s: %.17g vs %.17g", flag, *e0, e3);
    const char *m1 = strstr(r.err, "missing.binary"), *m2 = strstr(r.err, "cut.binary");
    ck_assert_msg(m1 && m2 && m1 < m2, "stderr out of order:\n%s", r.err);
    run_free(&r);
    unlink(cut);
    rmdir(dir);
}

/* The same with and without reading ahead, and the same fits to the bit. */
START_TEST(fit_read_ahead_keeps_order)
{
    double ahead, not_ahead;
    read_ahead_case("", &ahead);
    read_ahead_case("--no-read-ahead", &not_ahead);
    ck_assert_msg(memcmp(&ahead, &not_ahead, sizeof ahead) == 0, "%.17g vs %.17g", ahead, not_ahead);
}
END_TEST

/* A device that does not exist with --backend opencl: a failure (1), not a usage error. */
START_TEST(fit_no_such_device)
{
    char table[1024], args[2048];
    blue_rubber(table, sizeof table);
    snprintf(args, sizeof args,
             "fit --json --backend opencl --device no-such-device-xyz --model ward '%s'", table);
    run_out r = run(args);
    expect_status(r, 1, args);
    ck_assert_msg(strstr(r.err, "no-such-device-xyz") != NULL, "%s", r.err);
    char *lines[4];
    ck_assert_int_eq(split_lines(r.out, lines, 4), 1);
    ck_assert(tu_json_object_line(lines[0]));
    char s[256];
    ck_assert(tu_json_get_string(lines[0], "status", s, sizeof s));
    ck_assert_str_eq(s, brdffit_strerror(BRDFFIT_E_NO_DEVICE));
    run_free(&r);
}
END_TEST

/* The demo material is Cook-Torrance at the published alum-bronze fit: the
 * Cook-Torrance fit gives those parameters back; three models keep it short. */
START_TEST(demo_json)
{
    const char *args = "demo --json --model ward,blinn-phong,cook-torrance";
    run_out r = run(args);
    expect_status(r, 0, args);
    char *lines[16];
    int n = split_lines(r.out, lines, 16);
    ck_assert_msg(n == 3, "%d lines, expected 3:\n%s", n, r.out);
    static const char *const want[3] = { "ward", "blinn-phong", "cook-torrance" };
    char material[256];
    ck_assert(tu_json_get_string(lines[0], "material", material, sizeof material));
    for (int i = 0; i < n; i++)
        check_fit_record(lines[i], material, want[i]);
    double e, f0, m, d0;
    ck_assert(tu_json_get_number(lines[2], "error", &e));
    ck_assert_msg(e < 1e-6, "cook-torrance Error %g on its own data", e);
    ck_assert(tu_json_get_element(lines[2], "p", 0, &f0) && tu_json_get_element(lines[2], "p", 1, &m));
    ck_assert(tu_json_get_element(lines[2], "d", 0, &d0));
    ck_assert_msg(tu_reldiff(f0, 0.203) < 1e-4 && tu_reldiff(m, 0.0367) < 1e-4 &&
                      tu_reldiff(d0, 0.0886) < 1e-4,
                  "recovered F0 %g m %g d_r %g", f0, m, d0);
    run_free(&r);
}
END_TEST

START_TEST(demo_table)
{
    const char *args = "demo --model cook-torrance --starts 2";
    run_out r = run(args);
    expect_status(r, 0, args);
    ck_assert_msg(strstr(r.out, "synthetic") && strstr(r.out, "alum-bronze"), "%s", r.out);
    ck_assert_msg(strstr(r.out, "ngan-l2") && strstr(r.out, "backend "), "%s", r.out);
    ck_assert_msg(strstr(r.out, "\ntruth ") && strstr(r.out, "\ncook-torrance "), "%s", r.out);
    ck_assert_msg(strstr(r.out, "summary:") && strstr(r.out, "best cook-torrance"), "%s", r.out);
    run_free(&r);
}
END_TEST

/* ------------------------------------------------------------------ eval */

START_TEST(eval_matches_library)
{
    static const struct {
        brdffit_model model;
        const char *args;
        brdffit_params p;
    } cases[] = {
        { BRDFFIT_WARD, "ward 0.1 0.2 0.3 0.05 0.04 0.03 0.1",
          { { 0.1, 0.2, 0.3 }, { 0.05, 0.04, 0.03 }, { 0.1 }, { 0 } } },
        { BRDFFIT_LAFORTUNE, "lafortune 0.1 0.2 0.3 0.05 0.04 0.03 -0.57 0.57 100",
          { { 0.1, 0.2, 0.3 }, { 0.05, 0.04, 0.03 }, { -0.57, 0.57, 100 }, { 0 } } },
        { BRDFFIT_HE, "he 0.1 0.2 0.3 0.05 0.04 0.03 24 0.514 2.33",
          { { 0.1, 0.2, 0.3 }, { 0.05, 0.04, 0.03 }, { 24, 0.514, 2.33 }, { 0 } } },
    };
    const double wi[3] = { 0.3, -0.1, 0.9 }, wo[3] = { -0.25, 0.05, 0.8 };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char args[512];
        snprintf(args, sizeof args, "eval %s --wi 0.3 -0.1 0.9 --wo -0.25 0.05 0.8", cases[c].args);
        run_out r = run(args);
        expect_status(r, 0, args);
        double got[3], want[3];
        ck_assert_msg(sscanf(r.out, "%lf %lf %lf", &got[0], &got[1], &got[2]) == 3, "%s", r.out);
        ck_assert_int_eq(brdffit_eval(cases[c].model, &cases[c].p, wi, wo, want, NULL), BRDFFIT_OK);
        for (int k = 0; k < 3; k++)
            ck_assert_msg(got[k] == want[k], "%s: channel %d %.17g != %.17g", args, k, got[k],
                          want[k]);
        run_free(&r);
    }
}
END_TEST

static const char *const bad_evals[] = {
    "eval",
    "eval phong 0.1 0.1 0.1 0.1 0.1 0.1 10 --wi 0 0 1 --wo 0 0 1",
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 --wi 0 0 1 --wo 0 0 1",          /* alpha missing */
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.2 --wi 0 0 1 --wo 0 0 1",  /* one too many */
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 1.5 --wi 0 0 1 --wo 0 0 1",      /* alpha > 1 */
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 abc --wi 0 0 1 --wo 0 0 1",
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 0.1 --wi 0 0 1",
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 0.1 --wi 0 0 0 --wo 0 0 1",
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 0.1 --wi 0 0 1 --wo 0 nan 1",
    "eval ward 0.1 0.1 0.1 0.1 0.1 0.1 0.1 --wi 0 0 1 --wo 0 1",
};

START_TEST(eval_usage_errors)
{
    run_out r = run(bad_evals[_i]);
    expect_status(r, 2, bad_evals[_i]);
    ck_assert_str_eq(r.out, "");
    run_free(&r);
}
END_TEST

/* A glTF model's numbers are named by its colours and parameters in eval's
 * messages; a core-material value it refuses is named too. */
START_TEST(eval_gltf_names)
{
    run_out r = run("eval gltf 0.5 0.5 0.5 1 1 1 0.5 0.5 1.5 --wi 0 0 1 --wo 0 0 1");
    expect_status(r, 2, "eval gltf, 9 numbers");
    ck_assert_msg(strstr(r.err, "base_color_r base_color_g base_color_b specular_color_r "
                                "specular_color_g specular_color_b metallic roughness ior specular"),
                  "%s", r.err);
    run_free(&r);
    r = run("eval gltf 0.5 0.5 0.5 1 0.5 1 0.5 0.5 1.5 1 --wi 0 0 1 --wo 0 0 1");
    expect_status(r, 2, "eval gltf, a specular colour");
    ck_assert_msg(strstr(r.err, "specular_color_g"), "%s", r.err);
    run_free(&r);
    r = run("eval gltf-ext 0.5 0.5 0.5 1 0.5 1 0.5 0.5 2.2 0.8 --wi 0 0 1 --wo 0.6 0 0.8");
    expect_status(r, 0, "eval gltf-ext");
    run_free(&r);
}
END_TEST

Suite *cli_suite(void)
{
    Suite *s = suite_create("cli");
    TCase *tu = tcase_create("usage");
    tcase_set_timeout(tu, 30);
    tcase_add_test(tu, json_checker_self_test);
    tcase_add_test(tu, models_lists_all);
    tcase_add_test(tu, help_and_version);
    tcase_add_test(tu, unknown_command);
    tcase_add_test(tu, fit_without_files);
    tcase_add_loop_test(tu, bad_cutoff, 0, (int)(sizeof bad_cutoffs / sizeof bad_cutoffs[0]));
    tcase_add_test(tu, unknown_model);
    tcase_add_loop_test(tu, bad_options, 0, (int)(sizeof bad_option_args / sizeof bad_option_args[0]));
    tcase_add_test(tu, fit_missing_file);
    tcase_add_test(tu, json_failure_records);
    tcase_add_test(tu, eval_matches_library);
    tcase_add_loop_test(tu, eval_usage_errors, 0, (int)(sizeof bad_evals / sizeof bad_evals[0]));
    tcase_add_test(tu, eval_gltf_names);
    suite_add_tcase(s, tu);

    TCase *tf = tcase_create("fit");
    tcase_set_timeout(tf, 180);
    tcase_set_tags(tf, TU_NEEDS_SHARED);
    tcase_add_test(tf, fit_good_and_missing);
    tcase_add_test(tf, fit_json_good_and_missing);
    tcase_add_test(tf, fit_read_ahead_keeps_order);
    tcase_add_test(tf, fit_no_such_device);
    suite_add_tcase(s, tf);

    TCase *td = tcase_create("demo");
    tcase_set_timeout(td, 180);
    tcase_add_test(td, demo_json);
    tcase_add_test(td, demo_table);
    suite_add_tcase(s, td);
    return s;
}
