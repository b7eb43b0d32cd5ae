/* SPDX-License-Identifier: MIT */
/* partial.c -- removing what a failed write left behind. */
#define _POSIX_C_SOURCE 200809L
#include "image_io.h"

#include <stdio.h>
#include <sys/stat.h>

void io_remove_partial(const char *path)
{
    /* only a regular file: a failed write to /dev/full or a FIFO must not
     * delete the device node (the program may run as root) */
    struct stat st;
    if (lstat(path, &st) == 0 && S_ISREG(st.st_mode))
        remove(path);
}
