/* SPDX-License-Identifier: MIT */
/* test_journal.c -- the fit record's JSON reader and writer (src/cli/record/fit_record_json.c
 * over src/cli/record/jsonread.c), as the batch journal uses them: what the writer
 * writes reads back the same, a journal line of the earlier form (before
 * fit_record.h: "ok", a "status" text, "on_bound", "file" {path, size, hash})
 * still reads, resume decides by the status code, and a line a damaged or
 * hostile journal may hold is refused (the batch then skips and counts it),
 * never read as a record with impossible values. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "batch.h"
#include "cli.h"

#include <check.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A fit line of the earlier journal form. */
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
    fit_record r, back;
    ck_assert_int_eq(fr_read_json(line, &r, FR_NEED_KEY), 0);
    ck_assert_int_eq(r.kind, FR_FIT);
    ck_assert_int_eq(r.status, BRDFFIT_OK);
    ck_assert_int_eq(r.id.size, 34992012);
    ck_assert_int_eq(r.iterations, 3);
    ck_assert_int_eq(r.samples, 923870);
    ck_assert_str_eq(r.message, "caf\xC3\xA9 \xC3\xA9 \xF0\x9F\x98\x80");
    char *text = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&text, &n);
    ck_assert_ptr_nonnull(f);
    fr_write_json(f, &r);
    ck_assert_int_eq(fclose(f), 0);
    ck_assert_int_eq(fr_read_json(text, &back, FR_NEED_KEY), 0);
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
    fit_record r;
    if (_i < 2) {
        ck_assert_msg(fr_read_json(edited, &r, FR_NEED_KEY) == -1, "read as a record:\n%s", edited);
    } else { /* underflow is 0, a number JSON can say back */
        ck_assert_int_eq(fr_read_json(edited, &r, FR_NEED_KEY), 0);
        ck_assert(r.error == 0.0);
    }
}
END_TEST

START_TEST(journal_refuses_impossible_lines)
{
    const bad_line *b = &bad_lines[_i];
    char line[2048];
    fit_line(line, sizeof line, b->size, b->message, b->iterations);
    fit_record r;
    ck_assert_msg(fr_read_json(line, &r, FR_NEED_KEY) == -1, "case %d read as a record:\n%s", _i, line);
}
END_TEST

/* Write r, read it back (journal form) into back; the line into line. */
static void round_trip(const fit_record *r, fit_record *back, char *line, size_t len)
{
    char *text = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&text, &n);
    ck_assert_ptr_nonnull(f);
    fr_write_json(f, r);
    ck_assert_int_eq(fclose(f), 0);
    ck_assert_msg(tu_json_object_line(text), "not one JSON object: %s", text);
    ck_assert_msg(fr_read_json(text, back, FR_NEED_KEY) == 0, "not read back: %s", text);
    snprintf(line, len, "%s", text);
    free(text);
}

static void key_of(fit_record *r, fr_kind kind)
{
    fr_init(r, kind);
    snprintf(r->material, sizeof r->material, "alum-bronze");
    snprintf(r->id.path, sizeof r->id.path, "/d/alum-bronze.binary");
    r->id.size = 34992012;
    snprintf(r->id.hash, sizeof r->id.hash, "8143736677fba4d1");
    snprintf(r->settings.version, sizeof r->settings.version, "0.1.0");
    snprintf(r->settings.scale, sizeof r->settings.scale, "flat");
    r->settings.cutoff_deg = 75;
    r->settings.starts = 4;
    snprintf(r->settings.metric, sizeof r->settings.metric, "log");
}

/* A fit that succeeded: every field written reads back the same. */
START_TEST(record_round_trips_a_fit)
{
    fit_record r, back;
    char line[16384];
    key_of(&r, FR_FIT);
    snprintf(r.model, sizeof r.model, "he");
    r.nparams = 3;
    r.has_params = 1;
    r.params = (brdffit_params){ { 0.08, 0.05, 0.02 }, { 0.04, 0.02, 0.01 }, { 0.25, 0.3, 1.6 },
                                 { 0.645, 0.526, 0.444 } };
    r.error = 0.0568;
    r.errors[0] = 0.0712;
    r.errors[1] = 0.0568;
    r.errors[2] = 0.1234;
    r.has_counts = 1;
    r.iterations = 3;
    r.passes = 13;
    r.cminpack_info = 5;
    r.flags = BRDFFIT_FIT_LIMIT;
    r.at_bound = BRDFFIT_AT_BOUND_P2 | BRDFFIT_AT_BOUND_D_B | BRDFFIT_AT_BOUND_S_R;
    r.seconds = 0.204;
    r.seconds_solver = 0.01;
    r.seconds_passes = 0.15;
    r.seconds_build = 0;
    r.samples = 923870;
    snprintf(r.backend, sizeof r.backend, "opencl");
    snprintf(r.backend_description, sizeof r.backend_description, "OpenCL: pthread-x (PoCL)");
    round_trip(&r, &back, line, sizeof line);
    char s[256];
    ck_assert(tu_json_get_string(line, "status", s, sizeof s));
    ck_assert_str_eq(s, "limit");
    double code;
    ck_assert(tu_json_get_number(line, "status_code", &code) && code == 0);
    ck_assert_int_eq(back.kind, FR_FIT);
    ck_assert_int_eq(back.status, BRDFFIT_OK);
    ck_assert_str_eq(back.material, r.material);
    ck_assert_str_eq(back.model, "he");
    ck_assert_str_eq(back.id.path, r.id.path);
    ck_assert_int_eq(back.id.size, r.id.size);
    ck_assert_str_eq(back.id.hash, r.id.hash);
    ck_assert(bj_settings_equal(&back.settings, &r.settings));
    ck_assert_int_eq(back.has_params, 1);
    ck_assert_int_eq(back.nparams, 3);
    ck_assert(memcmp(&back.params, &r.params, sizeof r.params) == 0);
    ck_assert(back.error == r.error);
    ck_assert_str_eq(back.settings.metric, "log");
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++)
        ck_assert(back.errors[m] == r.errors[m]);
    ck_assert_msg(strstr(line, "\"errors\":{\"ngan-l2\":0.0711999999999"), "%s", line);
    char why[320];
    back.params.p[0] = 3.0; /* tau in He's range: the check gets to the Errors */
    const char *bad = fr_check(&back, why, sizeof why);
    ck_assert_msg(bad == NULL, "%s", bad);
    back.errors[1] = 0.05; /* its Error under log is not its Error */
    bad = fr_check(&back, why, sizeof why);
    ck_assert_msg(bad && strstr(bad, "not its Error under its metric log"), "%s", bad ? bad : "ok");
    back.errors[1] = r.errors[1];
    back.params.p[0] = r.params.p[0];
    ck_assert_int_eq(back.iterations, 3);
    ck_assert_int_eq(back.passes, 13);
    ck_assert_int_eq(back.cminpack_info, 5);
    ck_assert_uint_eq(back.flags, BRDFFIT_FIT_LIMIT);
    ck_assert_uint_eq(back.at_bound, r.at_bound);
    ck_assert(back.seconds == r.seconds && back.seconds_solver == r.seconds_solver &&
              back.seconds_passes == r.seconds_passes && back.seconds_build == 0);
    ck_assert_int_eq(back.samples, 923870);
    ck_assert_str_eq(back.backend, "opencl");
    ck_assert_str_eq(back.backend_description, r.backend_description);
    /* at_bound by name: he's third parameter, then d_b, s_r */
    const char *ab = tu_json_member(line, "at_bound");
    ck_assert_msg(ab && strncmp(ab, "[\"n\",\"d_b\",\"s_r\"]", 17) == 0, "%s", line);
}
END_TEST

/* A fit that failed and a material that could not be read: status code and
 * message read back; no parameters, no counts. */
/* An ngan-l2 fit without its Errors under log and cube-root (not asked
 * for): null in the record, read back as NaN, and the record passes the
 * check; its Error under ngan-l2, when given, must be its Error. */
START_TEST(record_round_trips_errors_not_computed)
{
    fit_record r, back;
    char line[16384];
    key_of(&r, FR_FIT);
    snprintf(r.settings.metric, sizeof r.settings.metric, "ngan-l2");
    snprintf(r.model, sizeof r.model, "ward");
    r.nparams = 1;
    r.has_params = 1;
    r.params = (brdffit_params){ { 0.08, 0.05, 0.02 }, { 0.04, 0.02, 0.01 }, { 0.1 }, { 0 } };
    r.error = 0.0712;
    r.errors[0] = 0.0712;
    r.has_counts = 1;
    r.iterations = 3;
    r.passes = 13;
    r.cminpack_info = 1;
    round_trip(&r, &back, line, sizeof line);
    ck_assert_msg(strstr(line, "\"errors\":{\"ngan-l2\":0.0711999999999"), "%s", line);
    ck_assert_msg(strstr(line, "\"log\":null,\"cube-root\":null}"), "%s", line);
    ck_assert(back.errors[0] == r.error && isnan(back.errors[1]) && isnan(back.errors[2]));
    char why[320];
    const char *bad = fr_check(&back, why, sizeof why);
    ck_assert_msg(bad == NULL, "%s", bad);
    back.errors[0] = 0.07;
    bad = fr_check(&back, why, sizeof why);
    ck_assert_msg(bad && strstr(bad, "not its Error under its metric ngan-l2"), "%s",
                  bad ? bad : "ok");
}
END_TEST

START_TEST(record_round_trips_failures)
{
    fit_record r, back;
    char line[16384];
    key_of(&r, FR_FIT);
    snprintf(r.model, sizeof r.model, "ward");
    r.nparams = 1;
    r.samples = 100;
    brdffit_error err = { BRDFFIT_E_KERNEL_BUILD, "build log:\n\terror: \"x\"" };
    fr_set_failure(&r, BRDFFIT_E_KERNEL_BUILD, &err);
    round_trip(&r, &back, line, sizeof line);
    ck_assert_int_eq(back.kind, FR_FIT);
    ck_assert_int_eq(back.status, BRDFFIT_E_KERNEL_BUILD);
    ck_assert_str_eq(back.message, err.message);
    ck_assert_int_eq(back.has_params, 0);
    ck_assert_int_eq(back.has_counts, 0);
    ck_assert(back.error != back.error);
    ck_assert_int_eq(back.samples, 100);
    char s[256];
    ck_assert(tu_json_get_string(line, "status", s, sizeof s));
    ck_assert_str_eq(s, brdffit_strerror(BRDFFIT_E_KERNEL_BUILD));
    ck_assert_ptr_nonnull(tu_json_member(line, "d"));
    ck_assert(strncmp(tu_json_member(line, "d"), "null", 4) == 0);

    /* a table that could not be opened: no size, no hash, no model */
    key_of(&r, FR_FAILURE);
    r.id.size = -1;
    r.id.hash[0] = '\0';
    err = (brdffit_error){ BRDFFIT_E_FILE_OPEN, "/d/alum-bronze.binary: cannot open" };
    fr_set_failure(&r, BRDFFIT_E_FILE_OPEN, &err);
    round_trip(&r, &back, line, sizeof line);
    ck_assert_int_eq(back.kind, FR_FAILURE);
    ck_assert_int_eq(back.status, BRDFFIT_E_FILE_OPEN);
    ck_assert_str_eq(back.message, err.message);
    ck_assert_int_eq(back.id.size, -1);
    ck_assert_str_eq(back.id.hash, "");
    ck_assert_str_eq(back.model, "");
    ck_assert(strncmp(tu_json_member(line, "size"), "null", 4) == 0);
    ck_assert(strncmp(tu_json_member(line, "model"), "null", 4) == 0);
}
END_TEST

/* Every kind of record has the same keys: one schema. */
/* A failed fit of a model this version does not know, its line carrying
 * parameters: read, it keeps none, and it writes back as it reads. */
START_TEST(unknown_model_failure_round_trips)
{
    static const char line[] =
        "{\"kind\":\"fit\",\"material\":\"alum-bronze\",\"file\":\"/d/alum-bronze.binary\","
        "\"size\":34992012,\"hash\":\"8143736677fba4d1\",\"settings\":{\"version\":\"0.1.0\","
        "\"metric\":\"ngan-l2\",\"scale\":\"standard\",\"cutoff_deg\":80,\"starts\":0},"
        "\"model\":\"hh\",\"param_names\":[\"tau\",\"sigma0\",\"n\"],\"status\":\"ok\","
        "\"status_code\":1,\"message\":\"\",\"d\":[1.08,0.05,0.02],\"s\":[0.04,0.02,0.01],"
        "\"p\":[12.5,0.3,1.6],\"lambda_um\":[0.645,0.526,0.444],\"error\":0.0568,"
        "\"iterations\":3,\"passes\":13,\"cminpack_info\":1,\"flags\":[],\"at_bound\":[],"
        "\"assets_key\":null,\"assets\":null}";
    static fit_record r, back;
    char text[8192];
    ck_assert_int_eq(fr_read_json(line, &r, FR_NEED_KEY), 0);
    ck_assert_int_eq(r.has_params, 0);
    ck_assert_int_eq(r.nparams, 0);
    round_trip(&r, &back, text, sizeof text);
    ck_assert_int_eq(back.nparams, r.nparams);
    ck_assert_int_eq(back.has_params, r.has_params);
    ck_assert_str_eq(back.model, "hh");
    ck_assert_int_eq(back.status, r.status);
}
END_TEST

START_TEST(record_keys_are_the_same_for_every_kind)
{
    char first[2048] = "", keys[2048], line[16384];
    for (int k = FR_FIT; k <= FR_ASSETS; k++) {
        fit_record r, back;
        key_of(&r, (fr_kind)k);
        if (k == FR_ASSETS)
            snprintf(r.assets_key, sizeof r.assets_key, "rf1:render=1,plot=1:ward");
        round_trip(&r, &back, line, sizeof line);
        ck_assert_int_gt(tu_json_keys(line, keys, sizeof keys), 20);
        if (k == FR_FIT)
            snprintf(first, sizeof first, "%s", keys);
        ck_assert_str_eq(keys, first);
    }
}
END_TEST

/* A journal of the earlier form: its fit, its failed fit and its failure are
 * read, the status text mapped to the code, "on_bound" to the at_bound bits. */
START_TEST(old_journal_lines_are_read)
{
    static const char *const fit =
        "{\"kind\":\"fit\",\"material\":\"a\",\"file\":{\"path\":\"/d/a.binary\",\"size\":34992012,"
        "\"hash\":\"8143736677fba4d1\"},\"settings\":{\"version\":\"0.1.0\",\"scale\":\"standard\","
        "\"cutoff_deg\":80,\"starts\":0},\"model\":\"he\",\"ok\":true,\"status\":\"limit\","
        "\"message\":\"\",\"d\":[0.08,0.05,0.02],\"s\":[0.04,0.02,0.01],\"p\":[12.5,0.3,1.6],"
        "\"lambda_um\":[0.645,0.526,0.444],\"error\":0.0568,\"iterations\":3,\"passes\":13,"
        "\"cminpack_info\":5,\"seconds\":0.204,\"samples\":923870,\"on_bound\":\"n=upper,d_b=0\","
        "\"backend\":\"opencl\"}";
    static const char *const failed =
        "{\"kind\":\"fit\",\"material\":\"a\",\"file\":{\"path\":\"/d/a.binary\",\"size\":34992012,"
        "\"hash\":\"8143736677fba4d1\"},\"settings\":{\"version\":\"0.1.0\",\"scale\":\"standard\","
        "\"cutoff_deg\":80,\"starts\":0},\"model\":\"ward\",\"ok\":false,\"status\":\"OpenCL error\","
        "\"message\":\"clEnqueueNDRangeKernel: -5\",\"d\":[0,0,0],\"s\":[0,0,0],\"p\":[0],"
        "\"lambda_um\":[0,0,0],\"error\":null,\"iterations\":0,\"passes\":0,\"cminpack_info\":0,"
        "\"seconds\":null,\"samples\":923870,\"on_bound\":\"\",\"backend\":\"opencl\"}";
    static const char *const failure =
        "{\"kind\":\"failure\",\"material\":\"b\",\"file\":{\"path\":\"/d/b.binary\",\"size\":12,"
        "\"hash\":\"0123456789abcdef\"},\"settings\":{\"version\":\"0.1.0\",\"scale\":\"flat\","
        "\"cutoff_deg\":80,\"starts\":0},\"model\":\"\",\"ok\":false,\"status\":\"truncated file\","
        "\"message\":\"/d/b.binary: 12 bytes\"}";
    fit_record r;
    ck_assert_int_eq(fr_read_json(fit, &r, FR_NEED_KEY), 0);
    ck_assert_int_eq(r.status, BRDFFIT_OK);
    ck_assert_uint_eq(r.flags, BRDFFIT_FIT_LIMIT);
    ck_assert_uint_eq(r.at_bound, BRDFFIT_AT_BOUND_P2 | BRDFFIT_AT_BOUND_D_B);
    ck_assert_int_eq(r.has_params, 1);
    ck_assert(r.params.p[0] == 12.5 && r.params.lambda_um[2] == 0.444);
    ck_assert_int_eq(fr_retry(&r), 0);
    ck_assert_int_eq(fr_read_json(failed, &r, FR_NEED_KEY), 0);
    ck_assert_int_eq(r.status, BRDFFIT_E_OPENCL);
    ck_assert_str_eq(r.message, "clEnqueueNDRangeKernel: -5");
    ck_assert_int_eq(r.has_params, 0);
    ck_assert_int_eq(fr_retry(&r), 1);
    ck_assert_int_eq(fr_read_json(failure, &r, FR_NEED_KEY), 0);
    ck_assert_int_eq(r.kind, FR_FAILURE);
    ck_assert_int_eq(r.status, BRDFFIT_E_FILE_TRUNCATED);
    ck_assert_int_eq(fr_retry(&r), 0);
}
END_TEST

/* Resume decides by "status_code": a failed fit whose status text and
 * message say something else (reworded, or another version's words) is
 * retried, or kept, by its code alone. */
START_TEST(retry_is_decided_by_the_code)
{
    static const struct {
        int code;
        const char *status, *message;
        int retry;
    } cases[] = {
        { BRDFFIT_E_OPENCL, "a GPU problem", "reworded: the device went away", 1 },
        { BRDFFIT_E_NO_MEMORY, "fit failed", "fit failed", 1 },
        { BRDFFIT_E_KERNEL_BUILD, "ok", "", 1 },
        { BRDFFIT_E_CACHE_DIR, "no cache", "x", 1 },
        { BRDFFIT_E_NO_DEVICE, "no device", "x", 1 },
        { BRDFFIT_E_FIT_FAILED, "OpenCL error", "OpenCL error", 0 },
        { BRDFFIT_E_TOO_FEW_SAMPLES, "out of memory", "no OpenCL device", 0 },
        { BRDFFIT_OK, "OpenCL error", "", 0 },
    };
    fit_record ref, r;
    char line[16384];
    key_of(&ref, FR_FIT);
    snprintf(ref.model, sizeof ref.model, "ward");
    round_trip(&ref, &r, line, sizeof line);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char edited[17000], *at;
        /* the line with this status text, code and message */
        snprintf(edited, sizeof edited, "%s", line);
        at = strstr(edited, "\"status\":\"ok\",\"status_code\":0,\"message\":\"\"");
        ck_assert_ptr_nonnull(at);
        char tail[16384];
        snprintf(tail, sizeof tail, "%s", at + strlen("\"status\":\"ok\",\"status_code\":0,\"message\":\"\""));
        snprintf(at, sizeof edited - (size_t)(at - edited),
                 "\"status\":\"%s\",\"status_code\":%d,\"message\":\"%s\"%s", cases[i].status,
                 cases[i].code, cases[i].message, tail);
        ck_assert_msg(fr_read_json(edited, &r, FR_NEED_KEY) == 0, "%s", edited);
        ck_assert_int_eq(r.status, cases[i].code);
        ck_assert_msg(fr_retry(&r) == cases[i].retry, "code %d (status '%s'): retry %d", cases[i].code,
                      cases[i].status, fr_retry(&r));
    }
    /* a material that could not be read is kept whatever its code */
    key_of(&r, FR_FAILURE);
    r.status = BRDFFIT_E_NO_MEMORY;
    ck_assert_int_eq(fr_retry(&r), 0);
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
    tcase_add_test(tc, record_round_trips_a_fit);
    tcase_add_test(tc, record_round_trips_errors_not_computed);
    tcase_add_test(tc, record_round_trips_failures);
    tcase_add_test(tc, unknown_model_failure_round_trips);
    tcase_add_test(tc, record_keys_are_the_same_for_every_kind);
    tcase_add_test(tc, old_journal_lines_are_read);
    tcase_add_test(tc, retry_is_decided_by_the_code);
    suite_add_tcase(s, tc);
    return s;
}
