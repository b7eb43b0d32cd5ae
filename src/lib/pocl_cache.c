/* SPDX-License-Identifier: MIT */
/* pocl_cache.c -- PoCL's kernel cache directory.  PoCL loads the compiled
 * kernels it finds there as shared objects, so a directory the library
 * chooses must be one no other user can write to or replace; and PoCL reads
 * POCL_CACHE_DIR once, at its first set-up, so the choice is made once per
 * process, before the library's first OpenCL call. */
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

/* mkdir -p with mode 0700 for what it makes; 0, or -1 with why. */
static int make_dirs(const char *dir, char *why, size_t len)
{
    char tmp[PATH_MAX], shown[SHOWN_PATH];
    if (snprintf(tmp, sizeof tmp, "%s", dir) >= (int)sizeof tmp) {
        snprintf(why, len, "cannot be created (the path is longer than %d bytes)", PATH_MAX - 1);
        return -1;
    }
    for (char *p = tmp + 1;; p++) {
        if (*p != '/' && *p != '\0')
            continue;
        char c = *p;
        *p = '\0';
        if (mkdir(tmp, 0700) != 0 && errno != EEXIST) {
            int e = errno;
            snprintf(why, len, "cannot be created (mkdir %s: %s)", bf_path_brief(tmp, shown, sizeof shown),
                     strerror(e));
            return -1;
        }
        *p = c;
        if (c == '\0')
            return 0;
    }
}

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

/* Every directory above real (a resolved path) is owned by root or by this
 * user and, when others may write to it, sticky: nobody else can rename the
 * cache directory away and put their own in its place. */
static int parents_safe(const char *real, char *why, size_t len)
{
    char up[PATH_MAX], shown[SHOWN_PATH];
    snprintf(up, sizeof up, "%s", real);
    uid_t me = geteuid();
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
        if (st.st_uid != 0 && st.st_uid != me) {
            snprintf(why, len, "is inside %s, owned by uid %lu (another user could replace it)",
                     bf_path_brief(up, shown, sizeof shown), (unsigned long)st.st_uid);
            return -1;
        }
        if ((st.st_mode & (S_IWGRP | S_IWOTH)) && !(st.st_mode & S_ISVTX)) {
            snprintf(why, len,
                     "is inside %s, which others can write to (mode %04o, not sticky: they could "
                     "replace it)",
                     bf_path_brief(up, shown, sizeof shown), (unsigned)(st.st_mode & 07777));
            return -1;
        }
        if (slash == up)
            return 0;
    }
}

int bf_private_dir(const char *dir, char *why, size_t len)
{
    if (make_dirs(dir, why, len) != 0)
        return -1;
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

/* The directory named by POCL_CACHE_DIR: the user's choice, so only usable
 * (made when missing, a directory, writable), not necessarily private. */
static brdffit_status check_given(const char *dir, brdffit_error *err)
{
    char why[600], shown[SHOWN_PATH];
    struct stat st;
    if (stat(dir, &st) != 0) {
        if (make_dirs(dir, why, sizeof why) != 0) /* says which part failed */
            return bf_fail(err, BRDFFIT_E_CACHE_DIR, "PoCL kernel cache: POCL_CACHE_DIR=%s %s",
                           bf_path_brief(dir, shown, sizeof shown), why);
    } else if (!S_ISDIR(st.st_mode)) {
        return bf_fail(err, BRDFFIT_E_CACHE_DIR, "PoCL kernel cache: POCL_CACHE_DIR=%s is not a directory",
                       bf_path_brief(dir, shown, sizeof shown));
    }
    if (can_write(dir, why, sizeof why) != 0)
        return bf_fail(err, BRDFFIT_E_CACHE_DIR, "PoCL kernel cache: POCL_CACHE_DIR=%s %s",
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
                   "(%s); set POCL_CACHE_DIR to a writable directory",
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
