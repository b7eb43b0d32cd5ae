/* SPDX-License-Identifier: MIT */
/* test_cache.c -- PoCL's kernel cache directory: a directory the library
 * chooses is private (made 0700, or existing and owned by the user, not a
 * symbolic link, not group- or world-writable, in a parent nobody else can
 * replace it in) or is not used; so is a directory POCL_CACHE_DIR names,
 * and an unusable one is named with why; nothing is made in or under a
 * directory refused; under AUTO the context falls back to the host and says so.  The
 * choice is made once per process, so every case runs in a fresh child. */
#define _XOPEN_SOURCE 700
#include "testutil.h"
#include "context.h"

#include <check.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* What a child saw: the OPENCL and AUTO contexts, and POCL_CACHE_DIR after. */
typedef struct cache_seen {
    int st_opencl;               /* brdffit_context_create, backend OPENCL   */
    char msg_opencl[BRDFFIT_MESSAGE_MAX];
    int st_auto, backend_auto;   /* backend AUTO: status and backend in use   */
    int st_fallback;             /* brdffit_context_fallback of the AUTO one   */
    char msg_fallback[BRDFFIT_MESSAGE_MAX];
    int st_build;                /* a kernel build on the OPENCL context (-1: none) */
    char pocl_cache_dir[1024];   /* "" when unset */
} cache_seen;

/* The environment of a case: TMPDIR, HOME, XDG_CACHE_HOME, POCL_CACHE_DIR
 * (NULL: unset). */
typedef struct cache_env {
    const char *tmpdir, *home, *xdg, *pocl;
} cache_env;

static void set_or_unset(const char *name, const char *value)
{
    if (value)
        setenv(name, value, 1);
    else
        unsetenv(name);
}

static void try_contexts(void *arg, void *out, size_t len)
{
    const cache_env *e = arg;
    cache_seen *r = out;
    (void)len;
    set_or_unset("TMPDIR", e->tmpdir);
    set_or_unset("HOME", e->home);
    set_or_unset("XDG_CACHE_HOME", e->xdg);
    set_or_unset("POCL_CACHE_DIR", e->pocl);
    brdffit_error err;
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    brdffit_context *ctx = NULL;
    co.backend = BRDFFIT_BACKEND_OPENCL;
    r->st_opencl = brdffit_context_create(&co, &ctx, &err);
    snprintf(r->msg_opencl, sizeof r->msg_opencl, "%s", r->st_opencl ? err.message : "");
    r->st_build = -1;
    if (ctx) {
        cl_kernel kf, kv;
        r->st_build = bf_context_kernels(ctx, BRDFFIT_WARD, &kf, &kv, &err);
        brdffit_context_free(ctx);
    }
    co.backend = BRDFFIT_BACKEND_AUTO;
    ctx = NULL;
    r->st_auto = brdffit_context_create(&co, &ctx, &err);
    r->backend_auto = brdffit_context_backend(ctx);
    r->st_fallback = brdffit_context_fallback(ctx, &err);
    snprintf(r->msg_fallback, sizeof r->msg_fallback, "%s", err.message);
    brdffit_context_free(ctx);
    const char *cache = getenv("POCL_CACHE_DIR");
    snprintf(r->pocl_cache_dir, sizeof r->pocl_cache_dir, "%s", cache ? cache : "");
}

static cache_seen run_case(const cache_env *e)
{
    static cache_seen r; /* large: not on the stack */
    int rc = tu_in_child(try_contexts, (void *)e, &r, sizeof r);
    ck_assert_msg(rc == 0, "the child failed (%d)", rc);
    return r;
}

/* A fresh temporary directory (mode 0700) into buf. */
static const char *tmp_dir(char *buf, size_t len)
{
    snprintf(buf, len, "/tmp/brdffit-cache-test-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(buf));
    return buf;
}

static const char *planted(const char *tmpdir, char *buf, size_t len)
{
    snprintf(buf, len, "%s/brdffit-pocl-%lu", tmpdir, (unsigned long)geteuid());
    return buf;
}

/* Refused: OPENCL fails with BRDFFIT_E_CACHE_DIR naming dir and why; AUTO
 * fits on the host and says the same; PoCL was not pointed at anything. */
static void expect_refused(const cache_seen *r, const char *dir, const char *why)
{
    ck_assert_msg(r->st_opencl == BRDFFIT_E_CACHE_DIR, "OPENCL: status %d (%s)", r->st_opencl,
                  r->msg_opencl);
    ck_assert_msg(strstr(r->msg_opencl, dir), "message does not name %s: %s", dir, r->msg_opencl);
    ck_assert_msg(strstr(r->msg_opencl, why), "message does not say '%s': %s", why, r->msg_opencl);
    ck_assert_int_eq(r->st_auto, BRDFFIT_OK);
    ck_assert_int_eq(r->backend_auto, BRDFFIT_BACKEND_HOST);
    ck_assert_int_eq(r->st_fallback, BRDFFIT_E_CACHE_DIR);
    ck_assert_msg(strstr(r->msg_fallback, why), "fallback does not say '%s': %s", why,
                  r->msg_fallback);
}

/* The hostile-user case: another user (or anyone) made the predictable
 * $TMPDIR/brdffit-pocl-UID first, world-writable, while HOME and
 * XDG_CACHE_HOME are unusable.  It must not be used. */
START_TEST(planted_world_writable_refused)
{
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    planted(tmp, dir, sizeof dir);
    ck_assert_int_eq(mkdir(dir, 0700), 0);
    ck_assert_int_eq(chmod(dir, 0777), 0);
    cache_env e = { tmp, "/dev/null", "/dev/null", NULL };
    cache_seen r = run_case(&e);
    expect_refused(&r, dir, "world-writable (mode 0777)");
    ck_assert_str_eq(r.pocl_cache_dir, "");
    /* every candidate tried is listed with its reason */
    ck_assert_ptr_nonnull(strstr(r.msg_opencl, "/dev/null/brdffit/pocl cannot be created"));
    ck_assert_ptr_nonnull(strstr(r.msg_opencl, "/dev/null/.cache/brdffit/pocl cannot be created"));
    rmdir(dir);
    rmdir(tmp);
}
END_TEST

START_TEST(planted_group_writable_refused)
{
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    planted(tmp, dir, sizeof dir);
    ck_assert_int_eq(mkdir(dir, 0700), 0);
    ck_assert_int_eq(chmod(dir, 0770), 0);
    cache_env e = { tmp, "/dev/null", "/dev/null", NULL };
    cache_seen r = run_case(&e);
    expect_refused(&r, dir, "group-writable (mode 0770)");
    rmdir(dir);
    rmdir(tmp);
}
END_TEST

/* A symbolic link in its place (to a directory the attacker controls; here
 * one of ours, private, so that only the link itself is at fault). */
START_TEST(planted_symlink_refused)
{
    char tmp[256], dir[512], target[512];
    tmp_dir(tmp, sizeof tmp);
    planted(tmp, dir, sizeof dir);
    snprintf(target, sizeof target, "%s/elsewhere", tmp);
    ck_assert_int_eq(mkdir(target, 0700), 0);
    ck_assert_int_eq(symlink(target, dir), 0);
    cache_env e = { tmp, "/dev/null", "/dev/null", NULL };
    cache_seen r = run_case(&e);
    expect_refused(&r, dir, "is a symbolic link");
    ck_assert_str_eq(r.pocl_cache_dir, "");
    unlink(dir);
    rmdir(target);
    rmdir(tmp);
}
END_TEST

/* Owned by another user, private mode: refused.  Making a directory owned by
 * someone else needs root; as another user this case checks nothing and says
 * so on stderr. */
START_TEST(planted_other_owner_refused)
{
    if (geteuid() != 0) {
        fprintf(stderr, "test_cache: planted_other_owner_refused not run: needs root to chown\n");
        return;
    }
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    planted(tmp, dir, sizeof dir);
    ck_assert_int_eq(mkdir(dir, 0700), 0);
    ck_assert_int_eq(chown(dir, 65534, 65534), 0);
    cache_env e = { tmp, "/dev/null", "/dev/null", NULL };
    cache_seen r = run_case(&e);
    expect_refused(&r, dir, "is owned by uid 65534");
    rmdir(dir);
    rmdir(tmp);
}
END_TEST

/* Private itself, but in a directory anyone may write to without the sticky
 * bit: another user could rename it away and put theirs in its place. */
START_TEST(replaceable_parent_refused)
{
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    ck_assert_int_eq(chmod(tmp, 0777), 0);
    planted(tmp, dir, sizeof dir);
    cache_env e = { tmp, "/dev/null", "/dev/null", NULL };
    cache_seen r = run_case(&e);
    expect_refused(&r, dir, "which others can write to (mode 0777, not sticky");
    rmdir(dir);
    rmdir(tmp);
}
END_TEST

/* Nothing planted: the library makes $TMPDIR/brdffit-pocl-UID itself, mode
 * 0700, points PoCL at it, and kernels build there. */
START_TEST(made_private_and_used)
{
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    planted(tmp, dir, sizeof dir);
    cache_env e = { tmp, "/dev/null", "/dev/null", NULL };
    cache_seen r = run_case(&e);
    ck_assert_msg(r.st_opencl == BRDFFIT_OK, "%s", r.msg_opencl);
    ck_assert_int_eq(r.st_build, BRDFFIT_OK);
    ck_assert_str_eq(r.pocl_cache_dir, dir);
    ck_assert_int_eq(r.backend_auto, BRDFFIT_BACKEND_OPENCL);
    ck_assert_int_eq(r.st_fallback, BRDFFIT_OK);
    struct stat st;
    ck_assert_int_eq(lstat(dir, &st), 0);
    ck_assert(S_ISDIR(st.st_mode));
    ck_assert_int_eq(st.st_mode & 0777, 0700);
    ck_assert_int_eq(st.st_uid, geteuid());
    /* an existing private one (this one, the second time) is used again */
    r = run_case(&e);
    ck_assert_msg(r.st_opencl == BRDFFIT_OK, "%s", r.msg_opencl);
    ck_assert_str_eq(r.pocl_cache_dir, dir);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* No candidate can be created: said as such, not as "no OpenCL device". */
START_TEST(none_creatable_said_so)
{
    cache_env e = { "/dev/null", "/dev/null", "/dev/null", NULL };
    cache_seen r = run_case(&e);
    ck_assert_int_eq(r.st_opencl, BRDFFIT_E_CACHE_DIR);
    ck_assert_ptr_null(strstr(r.msg_opencl, "no OpenCL device"));
    ck_assert_ptr_nonnull(strstr(r.msg_opencl, "POCL_CACHE_DIR is unset"));
    char want[64];
    snprintf(want, sizeof want, "/dev/null/brdffit-pocl-%lu cannot be created", (unsigned long)geteuid());
    ck_assert_msg(strstr(r.msg_opencl, want), "%s", r.msg_opencl);
    ck_assert_ptr_nonnull(strstr(r.msg_opencl, "Not a directory"));
    ck_assert_int_eq(r.backend_auto, BRDFFIT_BACKEND_HOST);
    ck_assert_int_eq(r.st_fallback, BRDFFIT_E_CACHE_DIR);
}
END_TEST

/* POCL_CACHE_DIR set to a directory no file can be made in (/proc refuses
 * even root): named with why, instead of every build failing with -11. */
START_TEST(given_unwritable_named)
{
    cache_env e = { "/tmp", "/dev/null", "/dev/null", "/proc" };
    cache_seen r = run_case(&e);
    ck_assert_int_eq(r.st_opencl, BRDFFIT_E_CACHE_DIR);
    /* root owns /proc, so only root gets as far as trying to write there */
    ck_assert_msg(strstr(r.msg_opencl, geteuid() == 0 ? "POCL_CACHE_DIR=/proc is not writable (creating a "
                                                        "file in it: "
                                                      : "POCL_CACHE_DIR=/proc is owned by uid 0"),
                  "%s", r.msg_opencl);
    ck_assert_int_eq(r.backend_auto, BRDFFIT_BACKEND_HOST);
    ck_assert_int_eq(r.st_fallback, BRDFFIT_E_CACHE_DIR);
    ck_assert_ptr_nonnull(strstr(r.msg_fallback, "POCL_CACHE_DIR=/proc"));
    ck_assert_str_eq(r.pocl_cache_dir, "/proc"); /* the user's setting is left alone */
}
END_TEST

/* POCL_CACHE_DIR that cannot be created; and one that is a file. */
START_TEST(given_uncreatable_named)
{
    cache_env e = { "/tmp", "/dev/null", "/dev/null", "/dev/null/kcache" };
    cache_seen r = run_case(&e);
    ck_assert_int_eq(r.st_opencl, BRDFFIT_E_CACHE_DIR);
    ck_assert_msg(strstr(r.msg_opencl, "POCL_CACHE_DIR=/dev/null/kcache cannot be created (/dev/null: "
                                       "Not a directory)"),
                  "%s", r.msg_opencl);
    cache_env f = { "/tmp", "/dev/null", "/dev/null", "/dev/null" };
    r = run_case(&f);
    ck_assert_int_eq(r.st_opencl, BRDFFIT_E_CACHE_DIR);
    ck_assert_msg(strstr(r.msg_opencl, "POCL_CACHE_DIR=/dev/null is not a directory"), "%s",
                  r.msg_opencl);
}
END_TEST

/* POCL_CACHE_DIR naming a missing directory: made (PoCL itself would quietly
 * use a directory of its own instead). */
START_TEST(given_missing_made)
{
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    snprintf(dir, sizeof dir, "%s/a/b/kcache", tmp);
    cache_env e = { "/tmp", "/dev/null", "/dev/null", dir };
    cache_seen r = run_case(&e);
    ck_assert_msg(r.st_opencl == BRDFFIT_OK, "%s", r.msg_opencl);
    ck_assert_int_eq(r.st_build, BRDFFIT_OK);
    struct stat st;
    ck_assert_int_eq(stat(dir, &st), 0);
    ck_assert(S_ISDIR(st.st_mode));
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* A POCL_CACHE_DIR others could plant kernels in is refused as the
 * library's own choice would be: why, and what to do; PoCL is not touched
 * (under AUTO: the host) and the variable is left as set. */
static void expect_given_refused(const char *dir, const char *why)
{
    cache_env e = { "/tmp", "/dev/null", "/dev/null", dir };
    cache_seen r = run_case(&e);
    char want[700];
    snprintf(want, sizeof want, "POCL_CACHE_DIR=%s %s", dir, why);
    expect_refused(&r, dir, want);
    ck_assert_ptr_nonnull(strstr(r.msg_opencl, "only you can write to"));
    ck_assert_ptr_nonnull(strstr(r.msg_opencl, "unset POCL_CACHE_DIR"));
    ck_assert_int_eq(r.st_build, -1);
    ck_assert_str_eq(r.pocl_cache_dir, dir);
}

START_TEST(given_world_writable_refused)
{
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    snprintf(dir, sizeof dir, "%s/kcache", tmp);
    ck_assert_int_eq(mkdir(dir, 0700), 0);
    ck_assert_int_eq(chmod(dir, 0777), 0);
    expect_given_refused(dir, "is world-writable (mode 0777)");
    chmod(dir, 0770);
    expect_given_refused(dir, "is group-writable (mode 0770)");
    /* nothing was made in it: no probe file, no kernels */
    char cmd[700];
    snprintf(cmd, sizeof cmd, "test -z \"$(ls -A '%s')\"", dir);
    ck_assert_int_eq(system(cmd), 0);
    rmdir(dir);
    rmdir(tmp);
}
END_TEST

START_TEST(given_symlink_refused)
{
    char tmp[256], dir[512], target[512];
    tmp_dir(tmp, sizeof tmp);
    snprintf(target, sizeof target, "%s/elsewhere", tmp);
    snprintf(dir, sizeof dir, "%s/kcache", tmp);
    ck_assert_int_eq(mkdir(target, 0700), 0);
    ck_assert_int_eq(symlink(target, dir), 0);
    expect_given_refused(dir, "is a symbolic link");
    unlink(dir);
    rmdir(target);
    rmdir(tmp);
}
END_TEST

/* Owned by another user (needs root to chown to nobody, 65534: as another
 * user this case checks nothing and says so on stderr). */
START_TEST(given_other_owner_refused)
{
    if (geteuid() != 0) {
        fprintf(stderr, "test_cache: given_other_owner_refused not run: needs root to chown\n");
        return;
    }
    char tmp[256], dir[512];
    tmp_dir(tmp, sizeof tmp);
    snprintf(dir, sizeof dir, "%s/kcache", tmp);
    ck_assert_int_eq(mkdir(dir, 0700), 0);
    ck_assert_int_eq(chown(dir, 65534, 65534), 0);
    expect_given_refused(dir, "is owned by uid 65534, not by this user");
    /* a missing directory under another user's: refused, and not made */
    char under[600];
    snprintf(under, sizeof under, "%s/a/kcache", dir);
    expect_given_refused(under, "is inside");
    struct stat st;
    snprintf(under, sizeof under, "%s/a", dir);
    ck_assert_int_ne(lstat(under, &st), 0);
    rmdir(dir);
    rmdir(tmp);
}
END_TEST

/* Private itself, but under a directory anyone may write to without the
 * sticky bit (another user could rename it away and put theirs in its
 * place); nothing is made under such a directory either. */
START_TEST(given_replaceable_parent_refused)
{
    char tmp[256], open_dir[512], dir[600], missing[600];
    tmp_dir(tmp, sizeof tmp);
    snprintf(open_dir, sizeof open_dir, "%s/shared", tmp);
    ck_assert_int_eq(mkdir(open_dir, 0700), 0);
    ck_assert_int_eq(chmod(open_dir, 0777), 0);
    snprintf(dir, sizeof dir, "%s/kcache", open_dir);
    ck_assert_int_eq(mkdir(dir, 0700), 0);
    expect_given_refused(dir, "is inside");
    cache_env e = { "/tmp", "/dev/null", "/dev/null", dir };
    cache_seen r = run_case(&e);
    ck_assert_ptr_nonnull(strstr(r.msg_opencl, "which others can write to (mode 0777, not sticky"));
    snprintf(missing, sizeof missing, "%s/new/kcache", open_dir);
    expect_given_refused(missing, "is inside");
    snprintf(missing, sizeof missing, "%s/new", open_dir);
    struct stat st;
    ck_assert_int_ne(lstat(missing, &st), 0);
    rmdir(dir);
    rmdir(open_dir);
    rmdir(tmp);
}
END_TEST

/* XDG_CACHE_HOME another user owns: refused without brdffit/pocl being
 * made in it; the next candidate (TMPDIR's) is taken. */
START_TEST(other_users_xdg_left_alone)
{
    if (geteuid() != 0) {
        fprintf(stderr, "test_cache: other_users_xdg_left_alone not run: needs root to chown\n");
        return;
    }
    char tmp[256], xdg[512], made[600];
    tmp_dir(tmp, sizeof tmp);
    snprintf(xdg, sizeof xdg, "%s/xdg", tmp);
    ck_assert_int_eq(mkdir(xdg, 0755), 0);
    ck_assert_int_eq(chown(xdg, 65534, 65534), 0);
    cache_env e = { tmp, "/dev/null", xdg, NULL };
    cache_seen r = run_case(&e);
    ck_assert_msg(r.st_opencl == BRDFFIT_OK, "%s", r.msg_opencl);
    planted(tmp, made, sizeof made);
    ck_assert_str_eq(r.pocl_cache_dir, made);
    snprintf(made, sizeof made, "%s/brdffit", xdg);
    struct stat st;
    ck_assert_int_ne(lstat(made, &st), 0);
    /* and with no other candidate, the refusal names it with why */
    cache_env f = { "/dev/null", "/dev/null", xdg, NULL };
    r = run_case(&f);
    ck_assert_int_eq(r.st_opencl, BRDFFIT_E_CACHE_DIR);
    ck_assert_msg(strstr(r.msg_opencl, "owned by uid 65534"), "%s", r.msg_opencl);
    ck_assert_int_ne(lstat(made, &st), 0);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
    ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* bf_path_brief keeps a long path's head and tail so the reason after it
 * fits in a message. */
START_TEST(path_brief_keeps_ends)
{
    char path[5000], buf[64];
    memset(path, 'a', sizeof path);
    memcpy(path, "/start", 6);
    memcpy(path + sizeof path - 10, "/end.file", 10);
    ck_assert_uint_eq(strlen(bf_path_brief(path, buf, sizeof buf)), sizeof buf - 1);
    ck_assert(strncmp(buf, "/start", 6) == 0);
    ck_assert_ptr_nonnull(strstr(buf, "..."));
    ck_assert_str_eq(buf + strlen(buf) - 9, "/end.file");
    ck_assert_str_eq(bf_path_brief("/short", buf, sizeof buf), "/short");
}
END_TEST

Suite *cache_suite(void)
{
    Suite *s = suite_create("cache");
    TCase *tc = tcase_create("cache");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, planted_world_writable_refused);
    tcase_add_test(tc, planted_group_writable_refused);
    tcase_add_test(tc, planted_symlink_refused);
    tcase_add_test(tc, planted_other_owner_refused);
    tcase_add_test(tc, replaceable_parent_refused);
    tcase_add_test(tc, made_private_and_used);
    tcase_add_test(tc, none_creatable_said_so);
    tcase_add_test(tc, given_unwritable_named);
    tcase_add_test(tc, given_uncreatable_named);
    tcase_add_test(tc, given_missing_made);
    tcase_add_test(tc, given_world_writable_refused);
    tcase_add_test(tc, given_symlink_refused);
    tcase_add_test(tc, given_other_owner_refused);
    tcase_add_test(tc, given_replaceable_parent_refused);
    tcase_add_test(tc, other_users_xdg_left_alone);
    tcase_add_test(tc, path_brief_keeps_ends);
    suite_add_tcase(s, tc);
    return s;
}
