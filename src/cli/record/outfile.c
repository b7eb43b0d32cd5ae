/* SPDX-License-Identifier: MIT */
/* outfile.c -- files written whole (outdir.h): a temporary ".NAME.XXXXXXXXXXXX.tmp"
 * made in the open directory with O_CREAT | O_EXCL | O_NOFOLLOW (no link
 * planted under any name is followed, and an unpredictable name cannot be
 * taken beforehand), renamed over NAME with renameat; every failure turned
 * into "cannot write PATH: reason". */
#define _DEFAULT_SOURCE
#define _POSIX_C_SOURCE 200809L
#include "outdir.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static int fail(brdffit_error *err, const char *what, const char *path, int e)
{
    err->status = BRDFFIT_E_FILE_WRITE;
    snprintf(err->message, sizeof err->message, "cannot %s %.1800s: %s", what, path,
             e == ELOOP ? "it is a symbolic link (not followed)" : strerror(e ? e : EIO));
    return -1;
}

int out_join(char *buf, size_t len, const char *dir, const char *name)
{
    int w = snprintf(buf, len, "%s/%s", dir, name);
    return w < 0 || (size_t)w >= len ? -1 : 0;
}

/* 64 bits no one can guess: the system's entropy, else the clock, the
 * process and a counter mixed (O_EXCL keeps even a guessed name safe). */
static uint64_t random64(void)
{
    static _Atomic uint64_t counter;
    uint64_t x;
    if (getentropy(&x, sizeof x) == 0)
        return x;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    x = (uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 30) ^ ((uint64_t)getpid() << 16) ^
        atomic_fetch_add(&counter, 0x9e3779b97f4a7c15ULL);
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL; /* splitmix64's finaliser */
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/* Make the temporary of o: its descriptor, or -1 (errno). */
static int make_temporary(out_file *o)
{
    static const char digits[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    for (int attempt = 0; attempt < 100; attempt++) {
        uint64_t r = random64();
        char sfx[13];
        for (int i = 0; i < 12; i++, r /= 62)
            sfx[i] = digits[r % 62];
        sfx[12] = '\0';
        snprintf(o->tmp, sizeof o->tmp, ".%s.%s.tmp", o->name, sfx);
        int fd = openat(o->dirfd, o->tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                        0666);
        if (fd >= 0 || errno != EEXIST)
            return fd;
    }
    errno = EEXIST;
    return -1;
}

int out_open(out_file *o, const out_dir *d, const char *name, brdffit_error *err)
{
    memset(o, 0, sizeof *o);
    o->dirfd = d->fd;
    if (out_join(o->path, sizeof o->path, d->path, name) != 0 || strlen(name) >= sizeof o->name)
        return fail(err, "write", name, ENAMETOOLONG);
    strcpy(o->name, name);
    int fd = make_temporary(o);
    if (fd < 0)
        return fail(err, "write", o->path, errno);
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        int e = errno;
        close(fd);
        unlinkat(o->dirfd, o->tmp, 0);
        return fail(err, "write", o->path, e);
    }
    return 0;
}

int out_commit(out_file *o, brdffit_error *err)
{
    int e = 0;
    if (fflush(o->f) != 0 || ferror(o->f))
        e = errno ? errno : EIO;
    if (fclose(o->f) != 0 && !e)
        e = errno ? errno : EIO;
    o->f = NULL;
    struct stat st;
    if (!e && fstatat(o->dirfd, o->name, &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
        e = S_ISLNK(st.st_mode) ? ELOOP : EEXIST; /* never renamed over a link, directory or device */
    if (!e && renameat(o->dirfd, o->tmp, o->dirfd, o->name) != 0)
        e = errno;
    if (e) {
        unlinkat(o->dirfd, o->tmp, 0);
        return fail(err, "write", o->path, e);
    }
    return 0;
}

void out_abandon(out_file *o)
{
    if (o->f) {
        fclose(o->f);
        o->f = NULL;
        unlinkat(o->dirfd, o->tmp, 0);
    }
}

int out_copy(const char *from, const out_dir *d, const char *name, brdffit_error *err)
{
    int fd = open(from, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    struct stat st;
    int e = fd < 0 ? errno : fstat(fd, &st) != 0 ? errno : !S_ISREG(st.st_mode) ? EINVAL : 0;
    FILE *in = e ? NULL : fdopen(fd, "rb");
    if (!in) {
        if (fd >= 0)
            close(fd);
        err->status = BRDFFIT_E_FILE_OPEN;
        snprintf(err->message, sizeof err->message, "cannot read %.1800s: %s", from,
                 e == ELOOP ? "it is a symbolic link (not followed)"
                 : e == EINVAL ? "not a regular file" : strerror(e ? e : errno));
        return -1;
    }
    out_file o;
    if (out_open(&o, d, name, err) != 0) {
        fclose(in);
        return -1;
    }
    char buf[1 << 16];
    size_t got;
    while ((got = fread(buf, 1, sizeof buf, in)) > 0)
        if (fwrite(buf, 1, got, o.f) != got)
            break;
    int bad_in = ferror(in);
    fclose(in);
    if (bad_in) {
        out_abandon(&o);
        err->status = BRDFFIT_E_FILE_READ;
        snprintf(err->message, sizeof err->message, "cannot read %.1800s", from);
        return -1;
    }
    return out_commit(&o, err);
}
