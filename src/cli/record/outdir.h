/* SPDX-License-Identifier: MIT */
/* outdir.h -- the output directory: every file the program writes goes in
 * through a directory opened once, never through a path that a link planted
 * inside it could redirect.
 *
 *   outdir.c   the directory the user named (--out: made when missing, a link
 *              the user gave followed), directories inside it (made with
 *              mkdirat, opened without following a link), material names
 *              checked as one path component, the lock of a batch directory
 *   outfile.c  files written whole: a temporary of an unpredictable name made
 *              with O_EXCL | O_NOFOLLOW in the directory, renamed over the name
 *
 * Files are made 0666 and directories 0777, less the umask, as Unix programs
 * do.  Failures fill a brdffit_error (BRDFFIT_E_FILE_WRITE, "cannot ... PATH:
 * reason") and return -1; nothing is printed. */
#ifndef BRDFFIT_OUTDIR_H
#define BRDFFIT_OUTDIR_H

#include "brdffit.h"

#include <stdio.h>

#define OD_PATH_MAX 4096
#define OD_NAME_MAX 256

/* A directory open for writing into. */
typedef struct out_dir {
    int fd;                      /* O_DIRECTORY; -1 when closed          */
    char path[OD_PATH_MAX];      /* as given or joined: for messages     */
} out_dir;

/* Open the directory path (the user's --out: a symbolic link there is
 * followed, the user named it).  make: made when missing (its parent must
 * exist) and it must be writable.  A dangling link is said to be one.
 * 0, or -1 with err. */
int od_open(out_dir *d, const char *path, int make, brdffit_error *err);
/* The directory name inside parent: the name checked (od_name_problem), made
 * when missing, opened without following a link.  0, or -1 with err. */
int od_sub(out_dir *sub, const out_dir *parent, const char *name, brdffit_error *err);
void od_close(out_dir *d);
/* fsync the directory (new entries made durable): 0, or -1 with err. */
int od_sync(const out_dir *d, brdffit_error *err);
/* NULL when name can be one path component (a material's directory), else
 * why not: empty, "." or "..", holds '/'.  Other bytes, control characters
 * included, are allowed: every file that shows a name escapes them. */
const char *od_name_problem(const char *name);
/* Remove the temporaries of files written whole that a killed run left in d
 * (under the lock of the directory only: another run's would go too). */
void od_sweep(const out_dir *d);
/* Open name in d for appending (made when missing; a link or anything but a
 * regular file refused): the descriptor, or -1 with err. */
int od_open_append(const out_dir *d, const char *name, brdffit_error *err);

/* The lock of a batch directory: DIR/.brdffit-lock, held with flock while a
 * batch writes the directory (exclusive; the file names the holder, "batch
 * PID") or a report reads it (shared).  Not waited for. */
typedef struct od_lock {
    int fd;                      /* -1: not held */
} od_lock;

/* Take d's lock; who ("batch", "report") is written into it when exclusive.
 * 0; -1 with err when another run holds it ("another brdffit batch (pid N)
 * is writing DIR", "a brdffit report is reading DIR").  shared: when the
 * file cannot be made (a directory the user may not write), no lock is
 * needed (no batch can write there either) and 0 is returned. */
int od_lock_take(od_lock *l, const out_dir *d, int shared, const char *who, brdffit_error *err);
void od_lock_release(od_lock *l);

/* ---- outfile.c ---- */

/* A file written whole: a temporary in the directory, renamed over the name
 * by out_commit, so that a file is never seen half-written. */
typedef struct out_file {
    FILE *f;
    int dirfd;                   /* the directory's (borrowed)            */
    char name[OD_NAME_MAX];
    char tmp[OD_NAME_MAX + 32];
    char path[OD_PATH_MAX];      /* the directory's path / name: messages */
} out_file;

/* Start name in d: 0, or -1 with err ("cannot write PATH: reason"). */
int out_open(out_file *o, const out_dir *d, const char *name, brdffit_error *err);
/* Flush, close and rename over the name (never over anything but a regular
 * file: a link, directory or device there is reported).  0, or -1 with err. */
int out_commit(out_file *o, brdffit_error *err);
/* Close and remove the temporary (after a failure). */
void out_abandon(out_file *o);
/* Copy the regular file from (not a link) to name in d: 0, or -1 with err. */
int out_copy(const char *from, const out_dir *d, const char *name, brdffit_error *err);
/* Join dir and name into buf ("dir/name"); -1 when it does not fit. */
int out_join(char *buf, size_t len, const char *dir, const char *name);

#endif
