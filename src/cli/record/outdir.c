/* SPDX-License-Identifier: MIT */
/* outdir.c -- the output directory (outdir.h): opened once, directories made
 * inside it without following links, names checked, the lock of a batch
 * directory. */
#define _DEFAULT_SOURCE
#define _POSIX_C_SOURCE 200809L
#include "outdir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#define LOCK_NAME ".brdffit-lock"

static int fail(brdffit_error *err, const char *what, const char *path, const char *why)
{
    err->status = BRDFFIT_E_FILE_WRITE;
    snprintf(err->message, sizeof err->message, "cannot %s %.1500s: %.400s", what, path, why);
    return -1;
}

/* The reason of errno e for a name opened inside a directory: there ELOOP
 * means that the name is a symbolic link (O_NOFOLLOW). */
static const char *reason(int e)
{
    if (e == ELOOP)
        return "it is a symbolic link (not followed)";
    return strerror(e ? e : EIO);
}

const char *od_name_problem(const char *name)
{
    if (!name || !name[0])
        return "it is empty";
    if (strcmp(name, ".") == 0 || strcmp(name, "..") == 0)
        return "it is \".\" or \"..\"";
    if (strchr(name, '/'))
        return "it holds '/'";
    if (strlen(name) >= OD_NAME_MAX)
        return "it is too long";
    return NULL;
}

/* Why path, which exists but could not be opened as a directory (e), is not one. */
static int not_a_dir(const char *path, int e, brdffit_error *err)
{
    struct stat st;
    char target[300];
    if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode) && stat(path, &st) != 0) {
        ssize_t n = readlink(path, target, sizeof target - 1);
        target[n > 0 ? n : 0] = '\0';
        char why[400];
        snprintf(why, sizeof why, "it is a symbolic link to %s, which does not exist", target);
        return fail(err, "create the directory", path, why);
    }
    if (e == ENOTDIR)
        return fail(err, "create the directory", path, "it exists and is not a directory");
    return fail(err, "open the directory", path, reason(e));
}

int od_open(out_dir *d, const char *path, int make, brdffit_error *err)
{
    d->fd = -1;
    if (strlen(path) >= sizeof d->path)
        return fail(err, "open the directory", path, strerror(ENAMETOOLONG));
    strcpy(d->path, path);
    if (make && mkdir(path, 0777) != 0 && errno != EEXIST)
        return fail(err, "create the directory", path, strerror(errno));
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return not_a_dir(path, errno, err);
    if (make && access(path, W_OK | X_OK) != 0) {
        int e = errno;
        close(fd);
        return fail(err, "write into the directory", path, strerror(e));
    }
    d->fd = fd;
    return 0;
}

int od_sub(out_dir *sub, const out_dir *parent, const char *name, brdffit_error *err)
{
    sub->fd = -1;
    const char *bad = od_name_problem(name);
    if (out_join(sub->path, sizeof sub->path, parent->path, name ? name : "") != 0)
        return fail(err, "create the directory", parent->path, strerror(ENAMETOOLONG));
    if (bad)
        return fail(err, "create the directory", sub->path, bad);
    if (mkdirat(parent->fd, name, 0777) != 0 && errno != EEXIST)
        return fail(err, "create the directory", sub->path, strerror(errno));
    int fd = openat(parent->fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        struct stat st;
        if (fstatat(parent->fd, name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(st.st_mode))
            e = ELOOP;
        return fail(err, "open the directory", sub->path, reason(e));
    }
    sub->fd = fd;
    return 0;
}

void od_close(out_dir *d)
{
    if (d->fd >= 0)
        close(d->fd);
    d->fd = -1;
}

int od_sync(const out_dir *d, brdffit_error *err)
{
    /* some file systems cannot sync a directory (EINVAL): nothing to make durable there */
    if (fsync(d->fd) != 0 && errno != EINVAL)
        return fail(err, "sync the directory", d->path, strerror(errno));
    return 0;
}

int od_open_append(const out_dir *d, const char *name, brdffit_error *err)
{
    char path[OD_PATH_MAX + OD_NAME_MAX];
    out_join(path, sizeof path, d->path, name);
    int fd = openat(d->fd, name, O_RDWR | O_CREAT | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC,
                    0666);
    if (fd < 0)
        return fail(err, "open", path, reason(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return fail(err, "open", path, "not a regular file");
    }
    int fl = fcntl(fd, F_GETFL);
    if (fl != -1)
        (void)fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    return fd;
}

/* ------------------------------------------------------------------ temporaries */

/* ".NAME.XXXXXXXXXXXX.tmp" (outfile.c): a dot, a name, a dot, 12 letters or
 * digits, ".tmp". */
static int is_temporary(const char *s)
{
    size_t n = strlen(s);
    if (n < 1 + 1 + 1 + 12 + 4 || s[0] != '.' || strcmp(s + n - 4, ".tmp") != 0 ||
        s[n - 4 - 12 - 1] != '.')
        return 0;
    for (size_t i = n - 4 - 12; i < n - 4; i++) {
        char c = s[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')))
            return 0;
    }
    return 1;
}

void od_sweep(const out_dir *d)
{
    int fd = openat(d->fd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    DIR *dir = fd >= 0 ? fdopendir(fd) : NULL;
    if (!dir) {
        if (fd >= 0)
            close(fd);
        return;
    }
    struct dirent *e;
    struct stat st;
    while ((e = readdir(dir)) != NULL)
        if (is_temporary(e->d_name) &&
            fstatat(d->fd, e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode))
            unlinkat(d->fd, e->d_name, 0);
    closedir(dir);
}

/* ------------------------------------------------------------------ the lock */

/* "another brdffit batch (pid N) is writing DIR", or that a report reads it. */
static int busy(int fd, const out_dir *d, brdffit_error *err)
{
    char *why = err->message, text[64] = "", who[16] = "batch";
    size_t len = sizeof err->message;
    long pid = 0;
    if (flock(fd, LOCK_SH | LOCK_NB) == 0) { /* only readers hold it */
        flock(fd, LOCK_UN);
        snprintf(why, len, "a brdffit report is reading %.1800s; try again when it is done",
                 d->path);
    } else {
        ssize_t n = pread(fd, text, sizeof text - 1, 0);
        text[n > 0 ? n : 0] = '\0';
        if (sscanf(text, "%15s %ld", who, &pid) == 2 && pid > 0)
            snprintf(why, len, "another brdffit %s (pid %ld) is writing %.1800s", who, pid,
                     d->path);
        else
            snprintf(why, len, "another brdffit batch is writing %.1800s", d->path);
    }
    close(fd);
    err->status = BRDFFIT_E_FILE_WRITE;
    return -1;
}

/* Open the lock file of d: made when missing (0666 less the umask). */
static int lock_file(const out_dir *d, int shared, int *e)
{
    int fd = openat(d->fd, LOCK_NAME, O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
    if (fd < 0 && shared && (errno == EACCES || errno == EROFS || errno == EPERM))
        fd = openat(d->fd, LOCK_NAME, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    *e = errno;
    struct stat st;
    if (fd >= 0 && (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))) {
        close(fd);
        *e = EINVAL;
        return -1;
    }
    return fd;
}

int od_lock_take(od_lock *l, const out_dir *d, int shared, const char *who, brdffit_error *err)
{
    l->fd = -1;
    char path[OD_PATH_MAX + 32];
    out_join(path, sizeof path, d->path, LOCK_NAME);
    int e = 0, fd = lock_file(d, shared, &e);
    if (fd < 0) {
        if (shared && (e == ENOENT || e == EACCES || e == EROFS || e == EPERM))
            return 0; /* nothing can write there: nothing to lock against */
        return fail(err, "lock", path, e == EINVAL ? "not a regular file" : reason(e));
    }
    if (flock(fd, (shared ? LOCK_SH : LOCK_EX) | LOCK_NB) != 0) {
        if (errno == EWOULDBLOCK)
            return busy(fd, d, err);
        e = errno;
        close(fd);
        return fail(err, "lock", path, strerror(e));
    }
    if (!shared) {
        char text[64];
        int n = snprintf(text, sizeof text, "%s %ld\n", who, (long)getpid());
        if (ftruncate(fd, 0) != 0 || pwrite(fd, text, (size_t)n, 0) != n) {
            e = errno;
            close(fd);
            return fail(err, "write", path, strerror(e));
        }
    }
    l->fd = fd;
    return 0;
}

void od_lock_release(od_lock *l)
{
    if (l->fd >= 0)
        close(l->fd);
    l->fd = -1;
}
