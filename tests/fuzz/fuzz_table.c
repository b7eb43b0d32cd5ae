/* SPDX-License-Identifier: MIT */
/* fuzz_table.c -- libFuzzer target: the MERL table reader (brdffit_table_read)
 * and, for a table it accepts, the sample set made from it.
 *
 * The first input byte picks the mode:
 *   bit 0 clear  the rest of the input is the whole file;
 *   bit 0 set    the second byte is a signed change of the file length, and
 *                the rest overwrites the start (the 12-byte header and the
 *                first samples) of a valid table of 34,992,012 bytes, so that
 *                inputs reach the checks only a full-size file gets to
 *                (values, trailing bytes);
 *   bit 1 set    with bit 0: the valid table patched is one whose R plane is
 *                -1 (masked) and G, B planes 0.5, so that the patch decides
 *                which bins are samples; a table that is read is then made
 *                into a sample set (cheap: masked bins cost nothing).
 * Files are memfds read back through /proc/self/fd; the two valid tables are
 * made once and what an input changed of one is restored after the input.
 * `make fuzz` builds this with clang and runs it; tests/fuzz/make_seeds.c
 * writes its seed corpus. */
#define _GNU_SOURCE
#include "brdffit.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

/* How much of the start of the valid table an input may overwrite. */
#define PATCH_MAX 4096

/* the valid tables: [0] a Ward-Duer material, [1] R masked, G and B 0.5 */
static int raw_fd = -1, valid_fd[2] = { -1, -1 };
static char raw_path[64], valid_path[2][64];
static unsigned char *valid[2]; /* their bytes */
static size_t valid_len;

static int write_all(int fd, const unsigned char *p, size_t n, off_t at)
{
    while (n > 0) {
        ssize_t w = pwrite(fd, p, n, at);
        if (w <= 0)
            return -1;
        p += w;
        n -= (size_t)w;
        at += w;
    }
    return 0;
}

/* A valid table, written by the library's own writer and read back. */
static void make_valid(int which)
{
    brdffit_table *t = NULL;
    brdffit_error err;
    brdffit_params p = { { 0.06, 0.05, 0.04 }, { 0.05, 0.04, 0.03 }, { 0.12, 0, 0 }, { 0 } };
    if (brdffit_table_create(&t, &err) != BRDFFIT_OK)
        abort();
    if (which == 0) {
        if (brdffit_table_fill_model(t, BRDFFIT_WARD_DUER, &p, BRDFFIT_SCALE_STANDARD, &err) != BRDFFIT_OK)
            abort();
    } else {
        double *v = brdffit_table_values(t);
        for (size_t n = 0; n < 3 * (size_t)BRDFFIT_MERL_BINS; n++)
            v[n] = n < (size_t)BRDFFIT_MERL_BINS ? -1.0 : 0.5;
    }
    if (brdffit_table_write(t, valid_path[which], &err) != BRDFFIT_OK) {
        fprintf(stderr, "fuzz_table: cannot make a valid table: %s\n", err.message);
        abort();
    }
    brdffit_table_free(t);
    valid_len = (size_t)lseek(valid_fd[which], 0, SEEK_END);
    valid[which] = malloc(valid_len);
    if (!valid[which] || pread(valid_fd[which], valid[which], valid_len, 0) != (ssize_t)valid_len)
        abort();
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    raw_fd = memfd_create("brdffit-fuzz-raw", 0);
    if (raw_fd < 0)
        abort();
    snprintf(raw_path, sizeof raw_path, "/proc/self/fd/%d", raw_fd);
    for (int w = 0; w < 2; w++) {
        valid_fd[w] = memfd_create("brdffit-fuzz-valid", 0);
        if (valid_fd[w] < 0)
            abort();
        snprintf(valid_path[w], sizeof valid_path[w], "/proc/self/fd/%d", valid_fd[w]);
        make_valid(w);
    }
    return 0;
}

static void read_and_sample(const char *path, int sample)
{
    brdffit_table *t = NULL;
    brdffit_error err;
    brdffit_status st = brdffit_table_read(path, &t, &err);
    if (st != BRDFFIT_OK) {
        /* a refusal names the file and carries a message */
        if (t || err.status != st || !strstr(err.message, path))
            abort();
        return;
    }
    if (!sample) {
        brdffit_table_free(t);
        return;
    }
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    brdffit_samples *s = NULL;
    if (brdffit_samples_create(t, &so, &s, &err) == BRDFFIT_OK)
        brdffit_samples_free(s);
    brdffit_table_free(t);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    if (!(data[0] & 1)) { /* the whole file */
        if (ftruncate(raw_fd, 0) != 0 || write_all(raw_fd, data + 1, size - 1, 0) != 0)
            abort();
        read_and_sample(raw_path, 0);
        return 0;
    }
    if (size < 2)
        return 0;
    int w = (data[0] & 2) ? 1 : 0, fd = valid_fd[w];
    int delta = (int8_t)data[1];
    size_t n = size - 2 > PATCH_MAX ? PATCH_MAX : size - 2;
    if (write_all(fd, data + 2, n, 0) != 0 || ftruncate(fd, (off_t)valid_len + delta) != 0)
        abort();
    read_and_sample(valid_path[w], w);
    /* back to the valid table */
    size_t tail = delta < 0 ? (size_t)-delta : 0;
    if (write_all(fd, valid[w], n, 0) != 0 || ftruncate(fd, (off_t)valid_len) != 0 ||
        write_all(fd, valid[w] + valid_len - tail, tail, (off_t)(valid_len - tail)) != 0)
        abort();
    return 0;
}
