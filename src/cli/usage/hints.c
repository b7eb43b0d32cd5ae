/* SPDX-License-Identifier: MIT */
/* hints.c -- what an input a command cannot take was probably meant to be:
 * a directory given to `fit` (batch fits every table in one), a text file
 * given to `batch` without its '@' (a list of tables, one a line). */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

int cli_is_directory(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

int cli_is_text_file(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISREG(st.st_mode))
        return 0;
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0)
        return 0;
    unsigned char b[512];
    ssize_t n = read(fd, b, sizeof b);
    close(fd);
    if (n <= 0)
        return 0;
    for (ssize_t i = 0; i < n; i++) /* bytes >= 0x80: UTF-8 names */
        if (b[i] < 0x20 && b[i] != '\t' && b[i] != '\n' && b[i] != '\r')
            return 0;
    return 1;
}

void cli_hint_unreadable_table(const char *path)
{
    if (cli_is_directory(path))
        cli_error("note: %s is a directory; to fit every *.binary in it: "
                  "brdffit batch %s --out DIR", path, path);
    else if (cli_is_text_file(path))
        cli_error("note: %s is text; if it lists tables, one a line: brdffit batch @%s --out DIR",
                  path, path);
}
