/* SPDX-License-Identifier: MIT */
/* merl_file.c -- reading and writing MERL .binary files.
 *
 * Format: three int32 (90, 90, 180), then 3 x 1,458,000 float64, R plane,
 * G plane, B plane, value index k + 180*(j + 90*i).  The file is
 * little-endian (as MERL's files and readers are); the reader and the writer
 * convert on a big-endian host, though only little-endian hosts are tested. */
#define _POSIX_C_SOURCE 200809L
#include "internal.h"
#include "grid.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define HEADER_BYTES ((size_t)12)
#define DATA_BYTES (BF_NVALUES * sizeof(double))
#define FILE_BYTES (HEADER_BYTES + DATA_BYTES) /* 34,992,012 */

/* ------------------------------------------------------------------ byte order */

static int host_little_endian(void)
{
    const uint16_t one = 1;
    unsigned char b;
    memcpy(&b, &one, 1);
    return b == 1;
}

static void swap8(void *p, size_t n)
{
    unsigned char *b = p;
    for (size_t i = 0; i < n; i++, b += 8) {
        for (int k = 0; k < 4; k++) {
            unsigned char t = b[k];
            b[k] = b[7 - k];
            b[7 - k] = t;
        }
    }
}

static int32_t get_le32(const unsigned char *b)
{
    uint32_t u = (uint32_t)b[0] | ((uint32_t)b[1] << 8) | ((uint32_t)b[2] << 16) |
                 ((uint32_t)b[3] << 24);
    int32_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static void put_le32(unsigned char *b, int32_t v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    b[0] = (unsigned char)(u & 0xff);
    b[1] = (unsigned char)((u >> 8) & 0xff);
    b[2] = (unsigned char)((u >> 16) & 0xff);
    b[3] = (unsigned char)((u >> 24) & 0xff);
}

/* ------------------------------------------------------------------ read */

/* Read up to len bytes; returns the count read (< len only at end of file)
 * or -1 with errno set. */
static long long read_full(int fd, void *buf, size_t len)
{
    unsigned char *p = buf;
    size_t got = 0;
    while (got < len) {
        size_t chunk = len - got;
        if (chunk > ((size_t)1 << 30))
            chunk = (size_t)1 << 30;
        ssize_t r = read(fd, p + got, chunk);
        if (r < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        if (r == 0)
            break;
        got += (size_t)r;
    }
    return (long long)got;
}

/* 1 when three int32 could be a table's dimensions, if not MERL's (a damaged
 * or other-resolution table); text, images and other files begin with bytes
 * that read as far larger numbers. */
static int header_like(const int32_t dims[3])
{
    for (int k = 0; k < 3; k++)
        if (dims[k] < -65536 || dims[k] > 65536)
            return 0;
    return 1;
}

static int is_text_byte(unsigned char c)
{
    return (c >= 0x20 && c < 0x7f) || c == '\t' || c == '\n' || c == '\r';
}

/* The letter of C's escape of c: t, n, r, or c itself (a quote, a backslash). */
static char c_escape(unsigned char c)
{
    return c == '\t' ? 't' : c == '\n' ? 'n' : c == '\r' ? 'r' : (char)c;
}

/* The first n (<= 12) bytes of a file for a message, into out (64 bytes):
 * "\"text\"" when they are text (printable ASCII, tabs, line ends; escaped
 * as in C), else "bytes 89 50 4e ..." in hex. */
static const char *show_bytes(const unsigned char *b, size_t n, char *out, size_t len)
{
    int text = 1;
    for (size_t i = 0; i < n; i++)
        text &= is_text_byte(b[i]);
    size_t used = (size_t)snprintf(out, len, text ? "\"" : "bytes");
    for (size_t i = 0; i < n && used < len; i++) {
        if (!text)
            used += (size_t)snprintf(out + used, len - used, " %02x", b[i]);
        else if (strchr("\t\n\r\"\\", b[i]))
            used += (size_t)snprintf(out + used, len - used, "\\%c", c_escape(b[i]));
        else
            used += (size_t)snprintf(out + used, len - used, "%c", b[i]);
    }
    if (text && used < len)
        snprintf(out + used, len - used, "\"");
    return out;
}

/* The file's size and header: a regular file of exactly FILE_BYTES whose
 * header names the MERL dimensions (the fd is left after the header). */
static brdffit_status read_header(int fd, const char *path, brdffit_error *err)
{
    struct stat sb;
    if (fstat(fd, &sb) != 0)
        return bf_fail(err, BRDFFIT_E_FILE_READ, "%s: cannot stat: %s", path, strerror(errno));
    if (S_ISDIR(sb.st_mode))
        return bf_fail(err, BRDFFIT_E_FILE_NOT_REGULAR, "%s: is a directory, not a MERL table",
                       path);
    if (!S_ISREG(sb.st_mode))
        return bf_fail(err, BRDFFIT_E_FILE_NOT_REGULAR, "%s: not a regular file", path);
    unsigned long long size = (unsigned long long)sb.st_size;
    if (size == 0)
        return bf_fail(err, BRDFFIT_E_FILE_EMPTY, "%s: empty file (0 bytes, %zu expected)", path,
                       FILE_BYTES);
    if (size < HEADER_BYTES)
        return bf_fail(err, BRDFFIT_E_FILE_TRUNCATED,
                       "%s: truncated at byte %llu of %zu expected (shorter than the 12-byte header)",
                       path, size, FILE_BYTES);

    unsigned char hdr[HEADER_BYTES];
    long long r = read_full(fd, hdr, sizeof hdr);
    if (r < 0)
        return bf_fail(err, BRDFFIT_E_FILE_READ, "%s: read error: %s", path, strerror(errno));
    if ((size_t)r < sizeof hdr)
        return bf_fail(err, BRDFFIT_E_FILE_TRUNCATED, "%s: truncated at byte %lld of %zu expected",
                       path, r, FILE_BYTES);
    int32_t dims[3] = { get_le32(hdr), get_le32(hdr + 4), get_le32(hdr + 8) };
    if (!header_like(dims)) {
        char shown[64];
        return bf_fail(err, BRDFFIT_E_FILE_DIMS,
                       "%s: not a MERL table: it begins with %s, where a MERL .binary begins with "
                       "the int32 dimensions %d %d %d",
                       path, show_bytes(hdr, sizeof hdr, shown, sizeof shown), BF_NTH, BF_NTD,
                       BF_NPD);
    }
    if (dims[0] != BF_NTH || dims[1] != BF_NTD || dims[2] != BF_NPD)
        return bf_fail(err, BRDFFIT_E_FILE_DIMS, "%s: dims %ldx%ldx%ld, expected %dx%dx%d", path,
                       (long)dims[0], (long)dims[1], (long)dims[2], BF_NTH, BF_NTD, BF_NPD);
    if (size < FILE_BYTES)
        return bf_fail(err, BRDFFIT_E_FILE_TRUNCATED, "%s: truncated at byte %llu of %zu expected",
                       path, size, FILE_BYTES);
    if (size > FILE_BYTES)
        return bf_fail(err, BRDFFIT_E_FILE_TRAILING,
                       "%s: %llu trailing bytes after the table (%llu bytes, %zu expected)", path,
                       size - FILE_BYTES, size, FILE_BYTES);
    return BRDFFIT_OK;
}

/* The values after the header into v, and nothing after them (the file may
 * have changed size since fstat). */
static brdffit_status read_values(int fd, const char *path, double *v, brdffit_error *err)
{
    long long r = read_full(fd, v, DATA_BYTES);
    if (r < 0)
        return bf_fail(err, BRDFFIT_E_FILE_READ, "%s: read error: %s", path, strerror(errno));
    if ((size_t)r < DATA_BYTES) /* the file shrank since fstat */
        return bf_fail(err, BRDFFIT_E_FILE_TRUNCATED, "%s: truncated at byte %llu of %zu expected",
                       path, (unsigned long long)HEADER_BYTES + (unsigned long long)r, FILE_BYTES);
    unsigned char extra;
    r = read_full(fd, &extra, 1);
    if (r < 0)
        return bf_fail(err, BRDFFIT_E_FILE_READ, "%s: read error: %s", path, strerror(errno));
    if (r > 0) /* grew since fstat */
        return bf_fail(err, BRDFFIT_E_FILE_TRAILING, "%s: trailing bytes after byte %zu", path,
                       FILE_BYTES);
    if (!host_little_endian())
        swap8(v, BF_NVALUES);
    return BRDFFIT_OK;
}

/* Every value finite and at most BRDFFIT_VALUE_MAX; the first that is not is
 * named by byte, index, channel and bin. */
static brdffit_status check_values(const double *v, const char *path, brdffit_error *err)
{
    for (size_t n = 0; n < BF_NVALUES; n++) {
        double x = v[n];
        if (isfinite(x) && x <= BRDFFIT_VALUE_MAX)
            continue;
        size_t c = n / BF_NBINS;
        int i, j, k;
        bf_bin_ijk(n % BF_NBINS, &i, &j, &k);
        if (isfinite(x))
            return bf_fail(err, BRDFFIT_E_VALUE_RANGE,
                           "%s: value %.17g at byte %zu (index %zu, channel %c, bin %d,%d,%d) is above "
                           "%g, the largest a table may hold",
                           path, x, HEADER_BYTES + n * sizeof(double), n, bf_channel_name[c], i, j, k,
                           BRDFFIT_VALUE_MAX);
        return bf_fail(err, BRDFFIT_E_FILE_NONFINITE, "%s: %s at index %zu (channel %c, bin %d,%d,%d)",
                       path, isnan(x) ? "NaN" : (x > 0 ? "+inf" : "-inf"), n, bf_channel_name[c], i,
                       j, k);
    }
    return BRDFFIT_OK;
}

static brdffit_status read_fd(int fd, const char *path, brdffit_table **out, brdffit_error *err)
{
    brdffit_status st = read_header(fd, path, err);
    if (st != BRDFFIT_OK)
        return st;
    /* huge pages, as brdffit_table_create's: read() into 4 KB pages faulted
     * ~8,600 times a table, half the page faults of `brdffit fit` */
    brdffit_table *t = bf_alloc_aligned(sizeof *t);
    if (!t)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "%s: cannot allocate %zu bytes for the table",
                       path, sizeof *t);
    st = read_values(fd, path, t->v, err);
    if (st == BRDFFIT_OK)
        st = check_values(t->v, path, err);
    if (st != BRDFFIT_OK) {
        bf_free_aligned(t);
        return st;
    }
    *out = t;
    bf_ok(err);
    return BRDFFIT_OK;
}

brdffit_status brdffit_table_read(const char *path, brdffit_table **out, brdffit_error *err)
{
    if (out)
        *out = NULL;
    if (!path || !out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_read: %s is NULL",
                       !path ? "path" : "out");
    /* O_NONBLOCK: opening a FIFO must not hang before fstat rejects it. */
    int fd;
    do
        fd = open(path, O_RDONLY | O_NONBLOCK);
    while (fd < 0 && errno == EINTR);
    /* messages name the path shortened, so that the reason after it fits */
    char shown[BRDFFIT_MESSAGE_MAX / 2];
    bf_path_brief(path, shown, sizeof shown);
    if (fd < 0)
        return bf_fail(err, BRDFFIT_E_FILE_OPEN, "%s: cannot open: %s", shown, strerror(errno));
    brdffit_status st = read_fd(fd, shown, out, err);
    close(fd);
    return st;
}

/* ------------------------------------------------------------------ write */

brdffit_status brdffit_table_write(const brdffit_table *table, const char *path,
                                   brdffit_error *err)
{
    if (!table || !path)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_write: %s is NULL",
                       !table ? "table" : "path");
    char shown[BRDFFIT_MESSAGE_MAX / 2];
    bf_path_brief(path, shown, sizeof shown);
    FILE *f = fopen(path, "wb");
    if (!f)
        return bf_fail(err, BRDFFIT_E_FILE_WRITE, "%s: cannot open for writing: %s", shown,
                       strerror(errno));
    unsigned char hdr[HEADER_BYTES];
    put_le32(hdr, BF_NTH);
    put_le32(hdr + 4, BF_NTD);
    put_le32(hdr + 8, BF_NPD);
    int ok = fwrite(hdr, 1, sizeof hdr, f) == sizeof hdr;
    int e = ok ? 0 : errno;
    if (ok && host_little_endian()) {
        ok = fwrite(table->v, sizeof(double), BF_NVALUES, f) == BF_NVALUES;
    } else if (ok) {
        double buf[1024];
        for (size_t n = 0; ok && n < BF_NVALUES; n += 1024) {
            size_t m = BF_NVALUES - n < 1024 ? BF_NVALUES - n : 1024;
            memcpy(buf, table->v + n, m * sizeof(double));
            swap8(buf, m);
            ok = fwrite(buf, sizeof(double), m, f) == m;
        }
    }
    if (!ok && !e)
        e = errno;
    if (fclose(f) != 0 && ok) {
        ok = 0;
        e = errno;
    }
    if (!ok)
        return bf_fail(err, BRDFFIT_E_FILE_WRITE, "%s: write failed: %s", shown,
                       e ? strerror(e) : "short write");
    bf_ok(err);
    return BRDFFIT_OK;
}

