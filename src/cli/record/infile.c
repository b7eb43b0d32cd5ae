/* SPDX-License-Identifier: MIT */
/* infile.c -- every path the program reads (tables' identities, lists of
 * tables, journals, --fits, --env, --published) is opened here: without
 * blocking (O_NONBLOCK: the open of a FIFO with no writer, or of some devices,
 * would wait for ever), kept only when fstat says it is a regular file, then
 * made blocking again.  So a FIFO, a directory or a device given as an input
 * is refused at once with a message, before a byte is read. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int refuse(brdffit_error *err, brdffit_status st, const char *path, const char *why,
                  const char *detail)
{
    char shown[BRDFFIT_MESSAGE_MAX / 2];
    cli_brief(path, shown, sizeof shown);
    err->status = st;
    snprintf(err->message, sizeof err->message, "%s: %s%s%s", shown, why, detail ? ": " : "",
             detail ? detail : "");
    return -1;
}

int cli_open_regular(const char *path, brdffit_error *err)
{
    int fd;
    do
        fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        int e = errno;
        refuse(err, BRDFFIT_E_FILE_OPEN, path, "cannot open", strerror(e));
        errno = e; /* ENOENT: the caller may take a missing file as an empty one */
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        close(fd);
        return refuse(err, BRDFFIT_E_FILE_READ, path, "cannot stat", strerror(e));
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        return refuse(err, BRDFFIT_E_FILE_NOT_REGULAR, path,
                      S_ISDIR(st.st_mode) ? "is a directory, not a file" : "not a regular file",
                      NULL);
    }
    int fl = fcntl(fd, F_GETFL);
    if (fl < 0 || fcntl(fd, F_SETFL, fl & ~O_NONBLOCK) != 0) {
        int e = errno;
        close(fd);
        return refuse(err, BRDFFIT_E_FILE_READ, path, "cannot read", strerror(e));
    }
    return fd;
}

FILE *cli_fopen_regular(const char *path, brdffit_error *err)
{
    int fd = cli_open_regular(path, err);
    if (fd < 0)
        return NULL;
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        refuse(err, BRDFFIT_E_NO_MEMORY, path, "cannot read", strerror(errno));
    }
    return f;
}
