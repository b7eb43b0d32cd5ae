/* SPDX-License-Identifier: MIT */
/* test_cli_faults.c -- the brdffit program under faults: no device under
 * --backend opencl (every file gets its failure record), a --device that
 * matches nothing (an error under opencl, a warning under auto), an unusable
 * POCL_CACHE_DIR named with why, sample sets too small for a model, a huge
 * stored value named, and file names with control characters or of 3 KB
 * printed harmlessly and with their reason. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define NB ((size_t)BRDFFIT_MERL_BINS)

#define expect_exit(r, want, what)                                                          \
    ck_assert_msg((r).status == (want), "%s: exit %d, expected %d\nstdout:\n%s\nstderr:\n%s", \
                  (what), (r).status, (want), (r).out, (r).err)

/* No OpenCL platform (the ICD loader pointed at an empty directory) under
 * --backend opencl: each of three files gets its own failure record and
 * message, none of them skipped silently. */
START_TEST(no_device_every_file_recorded)
{
    char icd[] = "/tmp/brdffit-noicd-XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(icd));
    const char *table = tu_table_fixture();
    char env[256], args[2048];
    snprintf(env, sizeof env, "OCL_ICD_VENDORS=%s", icd);
    snprintf(args, sizeof args, "fit --json --backend opencl --model ward '%s' '%s' '%s'", table,
             "/nonexistent-brdffit-dir/gone.binary", table);
    tu_run_out r = tu_run_cli(env, args);
    expect_exit(r, 1, args);
    ck_assert_msg(tu_count_lines(r.out) == 3, "%d records, expected 3:\n%s", tu_count_lines(r.out), r.out);
    char *second = strchr(r.out, '\n') + 1, *third = strchr(second, '\n') + 1;
    ck_assert_msg(strstr(r.out, "\"status\":\"no OpenCL device\"") < second, "%s", r.out);
    ck_assert_msg(strstr(second, "\"status\":\"cannot open file\"") < third, "%s", r.out);
    ck_assert_msg(strstr(third, "\"status\":\"no OpenCL device\""), "%s", r.out);
    ck_assert_msg(strstr(third, "not fitted: cannot set up the OpenCL backend"), "%s", third);
    /* stderr: one line per file, and the count */
    ck_assert_msg(strstr(r.err, "gone.binary: cannot open"), "%s", r.err);
    const char *first_msg = strstr(r.err, "not fitted: cannot set up the OpenCL backend");
    ck_assert_msg(first_msg && strstr(first_msg + 1, "not fitted: cannot set up the OpenCL backend"),
                  "not one message per file:\n%s", r.err);
    ck_assert_msg(strstr(r.err, "3 failures"), "%s", r.err);
    tu_run_free(&r);
    rmdir(icd);
}
END_TEST

/* --device that matches nothing: an error under --backend opencl; a warning
 * on stderr under auto (not silent), and the fit runs on the host. */
START_TEST(device_matching_nothing)
{
    const char *table = tu_table_fixture();
    char args[2048];
    snprintf(args, sizeof args, "fit --backend opencl --device no-such-device-xyz --model ward '%s'",
             table);
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, "no OpenCL device matches 'no-such-device-xyz'"), "%s", r.err);
    tu_run_free(&r);
    snprintf(args, sizeof args,
             "fit --device no-such-device-xyz --model ward-duer --cutoff 20 --starts 2 '%s'", table);
    r = tu_run_cli("", args);
    expect_exit(r, 0, args);
    ck_assert_msg(strstr(r.err, "brdffit: warning: fitting on the host (C, one thread), not OpenCL: "
                                "no OpenCL device matches 'no-such-device-xyz'"),
                  "no warning:\n%s", r.err);
    ck_assert_msg(strstr(r.out, "host: C"), "%s", r.out);
    tu_run_free(&r);
    /* BRDFFIT_DEVICE does the same */
    snprintf(args, sizeof args, "fit --backend opencl --model ward '%s'", table);
    r = tu_run_cli("BRDFFIT_DEVICE=nothing-like-this", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, "no OpenCL device matches 'nothing-like-this'"), "%s", r.err);
    tu_run_free(&r);
    /* an index past 2^32 is out of range, not device 0:0 */
    snprintf(args, sizeof args, "fit --backend opencl --device 4294967296:0 --model ward '%s'", table);
    r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, "platform index 4294967296:0 out of range"), "%s", r.err);
    tu_run_free(&r);
}
END_TEST

/* An existing but unwritable POCL_CACHE_DIR (/proc: no file can be made
 * there, even by root): named with why, not a bare kernel build error -11 on
 * every fit; under auto the host path, said so. */
START_TEST(unwritable_cache_named)
{
    const char *table = tu_table_fixture();
    char args[2048];
    snprintf(args, sizeof args, "fit --backend opencl --model ward '%s'", table);
    tu_run_out r = tu_run_cli("POCL_CACHE_DIR=/proc", args);
    expect_exit(r, 1, args);
    /* root owns /proc, so only root gets as far as trying to write there */
    const char *why = geteuid() == 0 ? "is not writable" : "is owned by uid 0";
    char want[200];
    snprintf(want, sizeof want, "POCL_CACHE_DIR=/proc %s", why);
    ck_assert_msg(strstr(r.err, want), "%s", r.err);
    tu_run_free(&r);
    snprintf(args, sizeof args, "fit --model ward-duer --cutoff 20 --starts 2 '%s'", table);
    r = tu_run_cli("POCL_CACHE_DIR=/proc", args);
    expect_exit(r, 0, args);
    ck_assert_msg(strstr(r.err, "warning: fitting on the host (C, one thread), not OpenCL: PoCL "
                                "kernel cache: POCL_CACHE_DIR=/proc ") && strstr(r.err, want),
                  "%s", r.err);
    tu_run_free(&r);
    /* no usable directory at all, POCL_CACHE_DIR unset: said as such */
    snprintf(args, sizeof args, "fit --backend opencl --model ward '%s'", table);
    r = tu_run_cli("env -u POCL_CACHE_DIR HOME=/dev/null XDG_CACHE_HOME=/dev/null TMPDIR=/dev/null",
                   args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, "no private directory could be used") && !strstr(r.err, "double precision"),
                  "%s", r.err);
    tu_run_free(&r);
}
END_TEST

/* --cutoff 1e-300 leaves only the normal: every fit refused with a clear
 * status (not ok with s up to 3.6e35). */
START_TEST(tiny_cutoff_refused)
{
    const char *table = tu_table_fixture();
    char args[2048];
    snprintf(args, sizeof args, "fit --json --cutoff 1e-300 --model ward,he '%s'", table);
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_int_eq(tu_count_lines(r.out), 2);
    char want[64];
    snprintf(want, sizeof want, "\"status\":\"%s\"", brdffit_strerror(BRDFFIT_E_TOO_FEW_SAMPLES));
    const char *first = strstr(r.out, want);
    ck_assert_msg(first && strstr(first + 1, want), "%s", r.out);
    ck_assert_msg(strstr(r.err, "fitting ward failed: 180 samples at 1 distinct geometry"), "%s", r.err);
    tu_run_free(&r);
}
END_TEST

/* A table with one huge finite value: refused at read time, the bin named. */
START_TEST(huge_value_file_named)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_int_eq(brdffit_table_read(tu_table_fixture(), &t, &err), BRDFFIT_OK);
    brdffit_table_values(t)[5 + 180 * (6 + 90 * 7)] = 2.5e150;
    char path[512], args[1024];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    ck_assert_int_eq(brdffit_table_write(t, path, &err), BRDFFIT_OK);
    brdffit_table_free(t);
    snprintf(args, sizeof args, "fit --model ward '%s'", path);
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(strstr(r.err, "value 2.5e+150 at byte ") && strstr(r.err, "channel R, bin 7,6,5"),
                  "%s", r.err);
    tu_run_free(&r);
    unlink(path);
}
END_TEST

/* A material with no specular part: the JSON record names s_r, s_g, s_b as
 * ended on their bound. */
START_TEST(no_specular_bound_in_json)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_params p = { { 0.3, 0.2, 0.1 }, { 0, 0, 0 }, { 0.15, 0, 0 }, { 0 } };
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_WARD_DUER, &p, BRDFFIT_SCALE_STANDARD, &err),
                     BRDFFIT_OK);
    char path[512], args[1024];
    ck_assert_ptr_nonnull(tu_tmpfile(path, sizeof path));
    ck_assert_int_eq(brdffit_table_write(t, path, &err), BRDFFIT_OK);
    brdffit_table_free(t);
    snprintf(args, sizeof args, "fit --json --model ward-duer --cutoff 30 --starts 2 '%s'", path);
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 0, args);
    const char *ab = strstr(r.out, "\"at_bound\":[");
    ck_assert_msg(ab, "%s", r.out);
    const char *end = strchr(ab, ']');
    ck_assert_msg(end && strstr(ab, "\"s_r\"") < end && strstr(ab, "\"s_g\"") < end &&
                      strstr(ab, "\"s_b\"") < end && strstr(ab, "\"s_r\""),
                  "%s", r.out);
    tu_run_free(&r);
    unlink(path);
}
END_TEST

/* A file name with an escape sequence and a newline: on stderr as \xHH, one
 * line per message; the JSON record keeps the name exactly (escaped JSON).
 * batch and report name their inputs the same way. */
START_TEST(control_characters_escaped)
{
    const char *args = "fit --json --model ward '/nonexistent-brdffit-dir/evil\033[31m\nFAKE.binary'";
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 1, args);
    ck_assert_msg(!strchr(r.err, '\033'), "a raw ESC reached stderr:\n%s", r.err);
    ck_assert_msg(strstr(r.err, "evil\\x1b[31m\\x0aFAKE.binary: cannot open"), "%s", r.err);
    ck_assert_msg(tu_count_lines(r.err) == 2, "%d stderr lines:\n%s", tu_count_lines(r.err), r.err);
    ck_assert_msg(strstr(r.out, "evil\\u001b[31m\\nFAKE.binary"), "%s", r.out);
    tu_run_free(&r);
    /* a usage error quoting an argument */
    r = tu_run_cli("", "fit --model 'ward\033]0;title\007' x.binary");
    expect_exit(r, 2, "--model with escapes");
    ck_assert_msg(!strchr(r.err, '\033') && !strchr(r.err, '\007'), "%s", r.err);
    ck_assert_msg(strstr(r.err, "ward\\x1b]0;title\\x07"), "%s", r.err);
    tu_run_free(&r);
    /* batch and report name their inputs the same way */
    char tmp[512], out[600], cmd[1200];
    ck_assert_ptr_nonnull(tu_tmpfile(tmp, sizeof tmp));
    snprintf(out, sizeof out, "%s.d", tmp);
    snprintf(cmd, sizeof cmd, "batch '/nonexistent-brdffit-dir/evil\033[2J' --out '%s'", out);
    r = tu_run_cli("", cmd);
    ck_assert_msg(r.status == 1 && !strchr(r.err, '\033'), "exit %d:\n%s", r.status, r.err);
    ck_assert_msg(strstr(r.err, "evil\\x1b[2J: cannot open"), "%s", r.err);
    tu_run_free(&r);
    /* a path ending in '/' names no material: refused, not a page directory
     * made of the whole path */
    snprintf(cmd, sizeof cmd, "batch '/nonexistent-brdffit-dir/evil\033[2J/' --out '%s'", out);
    r = tu_run_cli("", cmd);
    ck_assert_msg(r.status == 2 && !strchr(r.err, '\033'), "exit %d:\n%s", r.status, r.err);
    ck_assert_msg(strstr(r.err, "evil\\x1b[2J/' cannot name a material"), "%s", r.err);
    tu_run_free(&r);
    r = tu_run_cli("", "report '/nonexistent-brdffit-dir/evil\033[2J' --out /nonexistent-brdffit-dir/r");
    ck_assert_msg(r.status != 0 && !strchr(r.err, '\033'), "exit %d:\n%s", r.status, r.err);
    ck_assert_msg(strstr(r.err, "evil\\x1b[2J"), "%s", r.err);
    tu_run_free(&r);
    tu_remove_tree(out);
    unlink(tmp);
}
END_TEST

/* A path of 3000 bytes: the message still ends with the reason. */
START_TEST(long_path_keeps_reason)
{
    char path[3100], args[3300];
    int n = snprintf(path, sizeof path, "/nonexistent-brdffit-dir/");
    while (n < 3000)
        n += snprintf(path + n, sizeof path - (size_t)n, "deep-directory-name/");
    snprintf(path + n, sizeof path - (size_t)n, "material.binary");
    snprintf(args, sizeof args, "fit --model ward '%s'", path);
    tu_run_out r = tu_run_cli("", args);
    expect_exit(r, 1, "a 3 KB path");
    ck_assert_msg(strstr(r.err, "material.binary: cannot open: No such file or directory"), "%s", r.err);
    tu_run_free(&r);
}
END_TEST

Suite *cli_faults_suite(void)
{
    Suite *s = suite_create("cli_faults");
    TCase *tc = tcase_create("cli_faults");
    tcase_set_timeout(tc, 600);
    tcase_add_unchecked_fixture(tc, tu_table_fixture_make, tu_table_fixture_remove);
    tcase_add_test(tc, no_device_every_file_recorded);
    tcase_add_test(tc, device_matching_nothing);
    tcase_add_test(tc, unwritable_cache_named);
    tcase_add_test(tc, tiny_cutoff_refused);
    tcase_add_test(tc, huge_value_file_named);
    tcase_add_test(tc, no_specular_bound_in_json);
    tcase_add_test(tc, control_characters_escaped);
    tcase_add_test(tc, long_path_keeps_reason);
    suite_add_tcase(s, tc);
    return s;
}
