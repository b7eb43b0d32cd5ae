/* SPDX-License-Identifier: MIT */
/* outfile.c -- files of the batch report: written whole (a temporary renamed
 * over the name), directories made and synced, every failure turned into
 * "cannot write PATH: reason". */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"
#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int fail(brdffit_error *err, const char *what, const char *path, int e)
{
    err->status = BRDFFIT_E_FILE_WRITE;
    snprintf(err->message, sizeof err->message, "cannot %s %.1800s: %s", what, path,
             strerror(e ? e : EIO));
    return -1;
}

int out_join(char *buf, size_t len, const char *dir, const char *name)
{
    int w = snprintf(buf, len, "%s/%s", dir, name);
    return w < 0 || (size_t)w >= len ? -1 : 0;
}

int out_open(out_file *o, const char *path, brdffit_error *err)
{
    memset(o, 0, sizeof *o);
    if (strlen(path) >= sizeof o->path)
        return fail(err, "write", path, ENAMETOOLONG);
    strcpy(o->path, path);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp", path);
    o->f = fopen(o->tmp, "wb");
    if (!o->f)
        return fail(err, "write", o->tmp, errno);
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
    if (!e && lstat(o->path, &st) == 0 && !S_ISREG(st.st_mode))
        e = EEXIST; /* never rename over a directory, device or link: report it */
    if (e) {
        unlink(o->tmp);
        return fail(err, "write", o->path, e);
    }
    if (rename(o->tmp, o->path) != 0) {
        e = errno;
        unlink(o->tmp);
        return fail(err, "write", o->path, e);
    }
    return 0;
}

void out_abandon(out_file *o)
{
    if (o->f) {
        fclose(o->f);
        o->f = NULL;
        unlink(o->tmp);
    }
}

int out_mkdir(const char *path, brdffit_error *err)
{
    if (mkdir(path, 0755) == 0)
        return 0;
    int e = errno;
    struct stat st;
    if (e == EEXIST && stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return 0;
    if (e == EEXIST)
        e = ENOTDIR;
    return fail(err, "create the directory", path, e);
}

int out_sync_dir(const char *path, brdffit_error *err)
{
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return fail(err, "open the directory", path, errno);
    int rc = fsync(fd);
    int e = errno;
    close(fd);
    /* some file systems cannot sync a directory (EINVAL): nothing to make durable there */
    if (rc != 0 && e != EINVAL)
        return fail(err, "sync the directory", path, e);
    return 0;
}

int out_copy(const char *from, const char *to, brdffit_error *err)
{
    FILE *in = cli_fopen_regular(from, err);
    if (!in)
        return -1;
    out_file o;
    if (out_open(&o, to, err) != 0) {
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
