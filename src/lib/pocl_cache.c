/* SPDX-License-Identifier: MIT */
/* pocl_cache.c -- PoCL's kernel cache directory.  PoCL loads the compiled
 * kernels it finds there as shared objects, so the directory, whether the
 * library chooses it or POCL_CACHE_DIR names it, must be one no other user
 * can write to or replace; nothing is created in or under a directory that
 * fails the checks.  PoCL reads POCL_CACHE_DIR once, at its first set-up, so
 * the decision is made once per process, before the library's first OpenCL
 * call. */
#define _XOPEN_SOURCE 700 /* realpath, S_ISVTX */
#include "pocl_cache.h"

#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

/* Longest path shown in a message (head ... tail beyond it). */
#define SHOWN_PATH 300

/* What a user-set directory that is refused is told to do. */
#define GIVEN_HINT                                                                              \
    "; PoCL runs the kernels it finds there, so POCL_CACHE_DIR must name a directory of yours " \
    "that only you can write to, inside directories only root or you can change: fix it "      \
    "(e.g. chmod go-w), name another, or unset POCL_CACHE_DIR to let brdffit choose one"

/* A file can be made in dir (access() says yes to root on a read-only
 * file system, and PoCL needs to create files, so try). */
static int can_write(const char *dir, char *why, size_t len)
{
    char probe[PATH_MAX];
    if (snprintf(probe, sizeof probe, "%s/.brdffit-probe-XXXXXX", dir) >= (int)sizeof probe) {
        snprintf(why, len, "is unusable (the path is longer than %d bytes)", PATH_MAX - 40);
        return -1;
    }
    int fd = mkstemp(probe);
    if (fd < 0) {
        snprintf(why, len, "is not writable (creating a file in it: %s)", strerror(errno));
        return -1;
    }
    close(fd);
    unlink(probe);
    return 0;
}

/* A directory at or above the cache (path, its lstat st): owned by root or
 * by this user and, when others may write to it, sticky, so that nobody else
 * can rename what is inside away and put their own in its place.  (A
 * symbolic link's own mode means nothing; its owner does.) */
static int holder_safe(const char *path, const struct stat *st, char *why, size_t len)
{
    char shown[SHOWN_PATH];
    if (st->st_uid != 0 && st->st_uid != geteuid()) {
        snprintf(why, len, "is inside %s, owned by uid %lu (another user could replace it)",
                 bf_path_brief(path, shown, sizeof shown), (unsigned long)st->st_uid);
        return -1;
    }
    if (!S_ISLNK(st->st_mode) && (st->st_mode & (S_IWGRP | S_IWOTH)) && !(st->st_mode & S_ISVTX)) {
        snprintf(why, len,
                 "is inside %s, which others can write to (mode %04o, not sticky: they could "
                 "replace it)",
                 bf_path_brief(path, shown, sizeof shown), (unsigned)(st->st_mode & 07777));
        return -1;
    }
    return 0;
}

/* Every directory above real (a resolved path) passes holder_safe. */
static int parents_safe(const char *real, char *why, size_t len)
{
    char up[PATH_MAX], shown[SHOWN_PATH];
    snprintf(up, sizeof up, "%s", real);
    for (;;) {
        char *slash = strrchr(up, '/');
        if (!slash)
            return 0;
        if (slash == up)
            slash[1] = '\0'; /* "/" itself */
        else
            *slash = '\0';
        struct stat st;
        if (lstat(up, &st) != 0) {
            snprintf(why, len, "cannot be checked (lstat %s: %s)", bf_path_brief(up, shown, sizeof shown),
                     strerror(errno));
            return -1;
        }
        if (holder_safe(up, &st, why, len) != 0)
            return -1;
        if (slash == up)
            return 0;
    }
}

/* An existing directory above the cache, path (lstat st): safe to hold it,
 * and, when a symbolic link, so are where it leads and all above that. */
static int above_safe(const char *path, const struct stat *st, char *why, size_t len)
{
    char shown[SHOWN_PATH], real[PATH_MAX];
    struct stat dst;
    if (stat(path, &dst) != 0) {
        snprintf(why, len, "cannot be checked (stat %s: %s)", bf_path_brief(path, shown, sizeof shown),
                 strerror(errno));
        return -1;
    }
    if (!S_ISDIR(dst.st_mode)) {
        snprintf(why, len, "cannot be created (%s: %s)", bf_path_brief(path, shown, sizeof shown),
                 strerror(ENOTDIR));
        return -1;
    }
    if (holder_safe(path, st, why, len) != 0)
        return -1;
    if (!S_ISLNK(st->st_mode))
        return 0;
    if (!realpath(path, real) || lstat(real, &dst) != 0) {
        snprintf(why, len, "cannot be checked (resolving %s: %s)", bf_path_brief(path, shown, sizeof shown),
                 strerror(errno));
        return -1;
    }
    if (holder_safe(real, &dst, why, len) != 0)
        return -1;
    return parents_safe(real, why, len);
}

/* The cache directory itself, existing: this user's, a directory, not a
 * link, not writable by others, above it only safe holders, writable. */
static int own_dir(const char *dir, char *why, size_t len)
{
    struct stat st;
    if (lstat(dir, &st) != 0) {
        snprintf(why, len, "cannot be checked (lstat: %s)", strerror(errno));
        return -1;
    }
    if (S_ISLNK(st.st_mode)) {
        snprintf(why, len, "is a symbolic link");
        return -1;
    }
    if (!S_ISDIR(st.st_mode)) {
        snprintf(why, len, "is not a directory");
        return -1;
    }
    if (st.st_uid != geteuid()) {
        snprintf(why, len, "is owned by uid %lu, not by this user (uid %lu)", (unsigned long)st.st_uid,
                 (unsigned long)geteuid());
        return -1;
    }
    if (st.st_mode & (S_IWGRP | S_IWOTH)) {
        snprintf(why, len, "is %s-writable (mode %04o)", st.st_mode & S_IWOTH ? "world" : "group",
                 (unsigned)(st.st_mode & 07777));
        return -1;
    }
    char real[PATH_MAX];
    if (!realpath(dir, real)) {
        snprintf(why, len, "cannot be resolved (%s)", strerror(errno));
        return -1;
    }
    if (parents_safe(real, why, len) != 0)
        return -1;
    return can_write(dir, why, len);
}

/* dir made absolute (under the working directory when relative) into abs. */
static int absolute(const char *dir, char *abs, size_t len, char *why, size_t wlen)
{
    char cwd[PATH_MAX];
    int n;
    if (dir[0] == '/') {
        n = snprintf(abs, len, "%s", dir);
    } else {
        if (!getcwd(cwd, sizeof cwd)) {
            snprintf(why, wlen, "cannot be checked (the working directory: %s)", strerror(errno));
            return -1;
        }
        n = snprintf(abs, len, "%s/%s", cwd, dir);
    }
    if (n < 0 || (size_t)n >= len) {
        snprintf(why, wlen, "is unusable (the path is longer than %d bytes)", (int)len - 1);
        return -1;
    }
    return 0;
}

/* One directory on the way down to the cache, pre (the cache itself when
 * last): checked when it exists, made with mode 0700 when not (and then so
 * is everything below it, inside a directory that is now this user's). */
static int step(const char *pre, int last, int *making, char *why, size_t len)
{
    char shown[SHOWN_PATH];
    struct stat st;
    if (!*making) {
        if (lstat(pre, &st) == 0)
            return last ? 0 : above_safe(pre, &st, why, len);
        if (errno != ENOENT) {
            snprintf(why, len, "cannot be checked (lstat %s: %s)", bf_path_brief(pre, shown, sizeof shown),
                     strerror(errno));
            return -1;
        }
        *making = 1;
    }
    if (mkdir(pre, 0700) != 0) {
        snprintf(why, len, "cannot be created (mkdir %s: %s)", bf_path_brief(pre, shown, sizeof shown),
                 strerror(errno));
        return -1;
    }
    return 0;
}

int bf_private_dir(const char *dir, char *why, size_t len)
{
    char path[PATH_MAX];
    struct stat root;
    if (absolute(dir, path, sizeof path, why, len) != 0)
        return -1;
    if (lstat("/", &root) != 0) {
        snprintf(why, len, "cannot be checked (lstat /: %s)", strerror(errno));
        return -1;
    }
    if (holder_safe("/", &root, why, len) != 0)
        return -1;
    int making = 0;
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        path[--n] = '\0';
    for (size_t i = 1; i <= n; i++) {
        if ((path[i] != '/' && path[i] != '\0') || path[i - 1] == '/')
            continue;
        char c = path[i];
        path[i] = '\0';
        int rc = step(path, i == n, &making, why, len);
        path[i] = c;
        if (rc != 0)
            return -1;
    }
    return own_dir(path, why, len);
}

/* The directory named by POCL_CACHE_DIR: the user's choice, held to the same
 * rules as the library's own (made when missing). */
static brdffit_status check_given(const char *dir, brdffit_error *err)
{
    char why[600], shown[SHOWN_PATH];
    if (bf_private_dir(dir, why, sizeof why) != 0)
        return bf_fail(err, BRDFFIT_E_CACHE_DIR, "PoCL kernel cache: POCL_CACHE_DIR=%s %s" GIVEN_HINT,
                       bf_path_brief(dir, shown, sizeof shown), why);
    return BRDFFIT_OK;
}

/* POCL_CACHE_DIR unset: the first private candidate, exported for PoCL. */
static brdffit_status choose(brdffit_error *err)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME"), *tmp = getenv("TMPDIR");
    char uid[32];
    snprintf(uid, sizeof uid, "%lu", (unsigned long)geteuid());
    const struct { const char *base, *tail, *suffix; } cand[] = {
        { xdg, "/brdffit/pocl", "" },
        { home, "/.cache/brdffit/pocl", "" },
        { tmp && *tmp ? tmp : "/tmp", "/brdffit-pocl-", uid },
    };
    char tried[BRDFFIT_MESSAGE_MAX] = "";
    size_t used = 0;
    for (size_t i = 0; i < sizeof cand / sizeof cand[0]; i++) {
        char dir[PATH_MAX], why[600], shown[SHOWN_PATH];
        if (!cand[i].base || !*cand[i].base)
            continue;
        if (snprintf(dir, sizeof dir, "%s%s%s", cand[i].base, cand[i].tail, cand[i].suffix) >=
            (int)sizeof dir) {
            snprintf(why, sizeof why, "is longer than %d bytes", PATH_MAX - 1);
        } else if (bf_private_dir(dir, why, sizeof why) == 0) {
            if (setenv("POCL_CACHE_DIR", dir, 1) != 0)
                return bf_fail(err, BRDFFIT_E_CACHE_DIR, "PoCL kernel cache: cannot set POCL_CACHE_DIR: %s",
                               strerror(errno));
            return BRDFFIT_OK;
        }
        int w = snprintf(tried + used, sizeof tried - used, "%s%s %s", used ? "; " : "",
                         bf_path_brief(dir, shown, sizeof shown), why);
        if (w > 0)
            used = used + (size_t)w < sizeof tried ? used + (size_t)w : sizeof tried - 1;
    }
    return bf_fail(err, BRDFFIT_E_CACHE_DIR,
                   "PoCL kernel cache: POCL_CACHE_DIR is unset and no private directory could be used "
                   "(%s); set POCL_CACHE_DIR to a directory of yours that only you can write to",
                   used ? tried : "no HOME, XDG_CACHE_HOME or TMPDIR");
}

static pthread_once_t decide_once = PTHREAD_ONCE_INIT;
static brdffit_error decision;

static void decide(void)
{
    const char *given = getenv("POCL_CACHE_DIR");
    bf_ok(&decision);
    if (given && *given)
        check_given(given, &decision);
    else
        choose(&decision);
}

brdffit_status bf_pocl_cache_ready(brdffit_error *err)
{
    pthread_once(&decide_once, decide);
    if (decision.status == BRDFFIT_OK) {
        bf_ok(err);
        return BRDFFIT_OK;
    }
    if (err)
        *err = decision;
    return decision.status;
}
