/* table.c -- MERL tables: reading, writing, the bin <-> direction mapping,
 * solid-angle weights, channel scales, filling from a model and lookup.
 *
 * File format (MERL .binary): three int32 (90, 90, 180), then 3 x 1,458,000
 * float64, R plane, G plane, B plane, value index k + 180*(j + 90*i).  The
 * file is little-endian (as MERL's files and readers are); the reader and the
 * writer convert on a big-endian host, though only little-endian hosts are
 * tested. */
#define _POSIX_C_SOURCE 200809L
#include "internal.h"

#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define NTH BRDFFIT_MERL_NTH
#define NTD BRDFFIT_MERL_NTD
#define NPD BRDFFIT_MERL_NPD
#define NBINS ((size_t)BRDFFIT_MERL_BINS)
#define NVALUES (3 * NBINS)
#define HEADER_BYTES ((size_t)12)
#define DATA_BYTES (NVALUES * sizeof(double))
#define FILE_BYTES (HEADER_BYTES + DATA_BYTES) /* 34,992,012 */

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Lookup snaps grid coordinates this close to an integer onto it, so that
 * the directions of a bin map back to exactly that bin despite rounding. */
#define GRID_EPS 1e-9

struct brdffit_table {
    double v[NVALUES]; /* R plane, G plane, B plane */
};

static const char channel_name[3] = { 'R', 'G', 'B' };

/* ------------------------------------------------------------------ scales */

static int scale_known(brdffit_scale scale)
{
    return scale == BRDFFIT_SCALE_STANDARD || scale == BRDFFIT_SCALE_FLAT;
}

void bf_scale_factors(brdffit_scale scale, double factors[3])
{
    /* Anything but FLAT gives the standard factors; public callers validate. */
    if (scale == BRDFFIT_SCALE_FLAT) {
        factors[0] = factors[1] = factors[2] = 1.0 / 1500.0;
    } else {
        factors[0] = 1.0 / 1500.0;
        factors[1] = 1.15 / 1500.0;
        factors[2] = 1.66 / 1500.0;
    }
}

brdffit_status brdffit_scale_factors(brdffit_scale scale, double factors[3])
{
    if (!factors || !scale_known(scale))
        return BRDFFIT_E_INVALID_ARGUMENT;
    bf_scale_factors(scale, factors);
    return BRDFFIT_OK;
}

const char *brdffit_scale_name(brdffit_scale scale)
{
    switch (scale) {
    case BRDFFIT_SCALE_STANDARD: return "standard";
    case BRDFFIT_SCALE_FLAT: return "flat";
    }
    return "unknown";
}

brdffit_status brdffit_scale_from_name(const char *name, brdffit_scale *out)
{
    if (!name || !out)
        return BRDFFIT_E_INVALID_ARGUMENT;
    if (strcmp(name, "standard") == 0) {
        *out = BRDFFIT_SCALE_STANDARD;
        return BRDFFIT_OK;
    }
    if (strcmp(name, "flat") == 0) {
        *out = BRDFFIT_SCALE_FLAT;
        return BRDFFIT_OK;
    }
    return BRDFFIT_E_INVALID_ARGUMENT;
}

/* ------------------------------------------------------------------ create / free */

brdffit_status brdffit_table_create(brdffit_table **out, brdffit_error *err)
{
    if (!out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_create: out is NULL");
    *out = NULL;
    brdffit_table *t = calloc(1, sizeof *t);
    if (!t)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "brdffit_table_create: cannot allocate %zu bytes",
                       sizeof *t);
    *out = t;
    bf_ok(err);
    return BRDFFIT_OK;
}

void brdffit_table_free(brdffit_table *table)
{
    free(table);
}

double *brdffit_table_values(brdffit_table *table)
{
    return table ? table->v : NULL;
}

const double *brdffit_table_values_const(const brdffit_table *table)
{
    return table ? table->v : NULL;
}

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
    for (size_t s = 0; s < n; s++, b += 8) {
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

static brdffit_status read_fd(int fd, const char *path, brdffit_table **out, brdffit_error *err)
{
    struct stat st;
    if (fstat(fd, &st) != 0)
        return bf_fail(err, BRDFFIT_E_FILE_READ, "%s: cannot stat: %s", path, strerror(errno));
    if (S_ISDIR(st.st_mode))
        return bf_fail(err, BRDFFIT_E_FILE_NOT_REGULAR, "%s: is a directory, not a MERL table",
                       path);
    if (!S_ISREG(st.st_mode))
        return bf_fail(err, BRDFFIT_E_FILE_NOT_REGULAR, "%s: not a regular file", path);
    unsigned long long size = (unsigned long long)st.st_size;
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
    if (dims[0] != NTH || dims[1] != NTD || dims[2] != NPD)
        return bf_fail(err, BRDFFIT_E_FILE_DIMS, "%s: dims %ldx%ldx%ld, expected %dx%dx%d", path,
                       (long)dims[0], (long)dims[1], (long)dims[2], NTH, NTD, NPD);
    if (size < FILE_BYTES)
        return bf_fail(err, BRDFFIT_E_FILE_TRUNCATED, "%s: truncated at byte %llu of %zu expected",
                       path, size, FILE_BYTES);
    if (size > FILE_BYTES)
        return bf_fail(err, BRDFFIT_E_FILE_TRAILING,
                       "%s: %llu trailing bytes after the table (%llu bytes, %zu expected)", path,
                       size - FILE_BYTES, size, FILE_BYTES);

    brdffit_table *t = malloc(sizeof *t);
    if (!t)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "%s: cannot allocate %zu bytes for the table",
                       path, sizeof *t);
    r = read_full(fd, t->v, DATA_BYTES);
    if (r < 0) {
        int e = errno;
        free(t);
        return bf_fail(err, BRDFFIT_E_FILE_READ, "%s: read error: %s", path, strerror(e));
    }
    if ((size_t)r < DATA_BYTES) { /* the file shrank since fstat */
        free(t);
        return bf_fail(err, BRDFFIT_E_FILE_TRUNCATED, "%s: truncated at byte %llu of %zu expected",
                       path, (unsigned long long)HEADER_BYTES + (unsigned long long)r, FILE_BYTES);
    }
    unsigned char extra;
    r = read_full(fd, &extra, 1);
    if (r != 0) { /* grew since fstat, or failed */
        int e = errno;
        free(t);
        if (r < 0)
            return bf_fail(err, BRDFFIT_E_FILE_READ, "%s: read error: %s", path, strerror(e));
        return bf_fail(err, BRDFFIT_E_FILE_TRAILING, "%s: trailing bytes after byte %zu", path,
                       FILE_BYTES);
    }
    if (!host_little_endian())
        swap8(t->v, NVALUES);

    for (size_t n = 0; n < NVALUES; n++) {
        double x = t->v[n];
        if (!isfinite(x)) {
            size_t c = n / NBINS, b = n % NBINS;
            int k = (int)(b % NPD), j = (int)((b / NPD) % NTD), i = (int)(b / ((size_t)NPD * NTD));
            free(t);
            return bf_fail(err, BRDFFIT_E_FILE_NONFINITE,
                           "%s: %s at index %zu (channel %c, bin %d,%d,%d)", path,
                           isnan(x) ? "NaN" : (x > 0 ? "+inf" : "-inf"), n, channel_name[c], i, j,
                           k);
        }
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
    if (fd < 0)
        return bf_fail(err, BRDFFIT_E_FILE_OPEN, "%s: cannot open: %s", path, strerror(errno));
    brdffit_status s = read_fd(fd, path, out, err);
    close(fd);
    return s;
}

/* ------------------------------------------------------------------ write */

brdffit_status brdffit_table_write(const brdffit_table *table, const char *path,
                                   brdffit_error *err)
{
    if (!table || !path)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_write: %s is NULL",
                       !table ? "table" : "path");
    FILE *f = fopen(path, "wb");
    if (!f)
        return bf_fail(err, BRDFFIT_E_FILE_WRITE, "%s: cannot open for writing: %s", path,
                       strerror(errno));
    unsigned char hdr[HEADER_BYTES];
    put_le32(hdr, NTH);
    put_le32(hdr + 4, NTD);
    put_le32(hdr + 8, NPD);
    int ok = fwrite(hdr, 1, sizeof hdr, f) == sizeof hdr;
    int e = ok ? 0 : errno;
    if (ok && host_little_endian()) {
        ok = fwrite(table->v, sizeof(double), NVALUES, f) == NVALUES;
    } else if (ok) {
        double buf[1024];
        for (size_t n = 0; ok && n < NVALUES; n += 1024) {
            size_t m = NVALUES - n < 1024 ? NVALUES - n : 1024;
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
        return bf_fail(err, BRDFFIT_E_FILE_WRITE, "%s: write failed: %s", path,
                       e ? strerror(e) : "short write");
    bf_ok(err);
    return BRDFFIT_OK;
}

/* ------------------------------------------------------------------ bins */

size_t brdffit_bin_index(int i, int j, int k)
{
    return (size_t)k + (size_t)NPD * ((size_t)j + (size_t)NTD * (size_t)i);
}

static int bin_ok(int i, int j, int k)
{
    return i >= 0 && i < NTH && j >= 0 && j < NTD && k >= 0 && k < NPD;
}

/* The same arithmetic, in the same order, as ../shared/tools/merl-from-nbrdf.c,
 * so that directions (and the horizon test) agree bit for bit. */
static void bin_dirs(int i, int j, int k, double wi[3], double wo[3])
{
    double u = (double)i / NTH, th = u * u * M_PI / 2;
    double td = (double)j / NTD * M_PI / 2;
    double pd = (double)k / NPD * M_PI;
    double d[3] = { sin(td) * cos(pd), sin(td) * sin(pd), cos(td) };
    double h[3] = { sin(th), 0.0, cos(th) };
    wi[0] = d[0] * cos(th) + d[2] * sin(th);
    wi[1] = d[1];
    wi[2] = -d[0] * sin(th) + d[2] * cos(th);
    double hd = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
    for (int c = 0; c < 3; c++)
        wo[c] = 2 * hd * h[c] - wi[c];
}

brdffit_status brdffit_bin_directions(int i, int j, int k, double wi[3], double wo[3])
{
    if (!wi || !wo || !bin_ok(i, j, k))
        return BRDFFIT_E_INVALID_ARGUMENT;
    bin_dirs(i, j, k, wi, wo);
    return BRDFFIT_OK;
}

double brdffit_bin_weight(int i, int j)
{
    if (i < 0 || i >= NTH || j < 0 || j >= NTD)
        return 0.0;
    double ul = (double)i / NTH, uh = (double)(i + 1) / NTH;
    double thl = ul * ul * M_PI / 2, thh = uh * uh * M_PI / 2;
    double tdl = (double)j * M_PI / 180, tdh = (double)(j + 1) * M_PI / 180;
    double sl = sin(tdl), sh = sin(tdh);
    return (cos(thl) - cos(thh)) * (sh * sh - sl * sl) / 2;
}

/* ------------------------------------------------------------------ fill from a model */

brdffit_status brdffit_table_fill_model(brdffit_table *table, brdffit_model model,
                                        const brdffit_params *params, brdffit_scale scale,
                                        brdffit_error *err)
{
    if (!table || !params)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_table_fill_model: %s is NULL",
                       !table ? "table" : "params");
    if (!scale_known(scale))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "brdffit_table_fill_model: unknown scale %d", (int)scale);
    brdffit_status s = brdffit_params_check(model, params, err);
    if (s != BRDFFIT_OK)
        return s;
    double f[3];
    bf_scale_factors(scale, f);
    double wi[3 * NPD], wo[3 * NPD], rgb[3 * NPD];
    for (int i = 0; i < NTH; i++) {
        for (int j = 0; j < NTD; j++) {
            for (int k = 0; k < NPD; k++)
                bin_dirs(i, j, k, wi + 3 * k, wo + 3 * k);
            s = brdffit_eval_batch(model, params, NPD, wi, wo, rgb);
            if (s != BRDFFIT_OK)
                return bf_fail(err, s, "brdffit_table_fill_model: evaluating bin row %d,%d: %s",
                               i, j, brdffit_strerror(s));
            size_t base = brdffit_bin_index(i, j, 0);
            for (int k = 0; k < NPD; k++) {
                int above = wi[3 * k + 2] > 0 && wo[3 * k + 2] > 0;
                for (int c = 0; c < 3; c++)
                    table->v[c * NBINS + base + (size_t)k] = above ? rgb[3 * k + c] / f[c] : -1.0;
            }
        }
    }
    bf_ok(err);
    return BRDFFIT_OK;
}

/* ------------------------------------------------------------------ lookup */

/* MERL's std_coords_to_half_diff_coords, written with the components of H
 * instead of acos and trigonometric round trips (better conditioned near
 * theta = 0), as continuous grid coordinates: uh = sqrt(theta_h/(pi/2))*90,
 * ud = theta_d/(pi/2)*90, up = phi_d/pi*180 with phi_d folded into [0, pi].
 * Returns 0 for a non-finite or zero direction or for wo = -wi. */
static int grid_coords(const double wi_in[3], const double wo_in[3], double u[3])
{
    double a[3], b[3];
    double la = sqrt(wi_in[0] * wi_in[0] + wi_in[1] * wi_in[1] + wi_in[2] * wi_in[2]);
    double lb = sqrt(wo_in[0] * wo_in[0] + wo_in[1] * wo_in[1] + wo_in[2] * wo_in[2]);
    if (!isfinite(la) || !isfinite(lb) || !(la > 0) || !(lb > 0))
        return 0;
    /* Vectors already unit up to rounding are used as given: dividing by a
     * length of 1 +- 1 ulp would perturb them, and at small theta_h phi_h
     * (hence phi_d) is sensitive to the slightest asymmetry of wi and wo. */
    if (fabs(la - 1) <= 4 * DBL_EPSILON)
        la = 1;
    if (fabs(lb - 1) <= 4 * DBL_EPSILON)
        lb = 1;
    for (int c = 0; c < 3; c++) {
        a[c] = wi_in[c] / la;
        b[c] = wo_in[c] / lb;
    }
    double h[3] = { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
    double hxy = hypot(h[0], h[1]);
    double hl = hypot(hxy, h[2]);
    if (!(hl > 1e-300))
        return 0;
    double theta_h = atan2(hxy, h[2]);
    double cp = 1.0, sp = 0.0; /* cos, sin phi_h */
    if (hxy > 0) {
        cp = h[0] / hxy;
        sp = h[1] / hxy;
    }
    double ct = h[2] / hl, st = hxy / hl; /* cos, sin theta_h */
    /* rotate wi by -phi_h about z, then by -theta_h about y */
    double t0 = a[0] * cp + a[1] * sp, t1 = -a[0] * sp + a[1] * cp, t2 = a[2];
    double d0 = t0 * ct - t2 * st, d1 = t1, d2 = t0 * st + t2 * ct;
    double theta_d = atan2(hypot(d0, d1), d2);
    double phi_d = atan2(d1, d0);
    if (phi_d < 0)
        phi_d += M_PI;
    u[0] = sqrt(theta_h / (M_PI / 2)) * NTH;
    u[1] = theta_d / (M_PI / 2) * NTD;
    u[2] = phi_d / M_PI * NPD;
    return 1;
}

static int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* floor for an index, robust to values that should be exact integers */
static int index_of(double u, int n)
{
    double f = floor(u + GRID_EPS);
    if (!(f >= 0))
        return 0;
    if (f > n - 1)
        return n - 1;
    return (int)f;
}

static double snap(double u)
{
    double r = nearbyint(u);
    return fabs(u - r) < GRID_EPS ? r : u;
}

brdffit_status brdffit_table_lookup(const brdffit_table *table, const double wi[3],
                                    const double wo[3], brdffit_scale scale,
                                    brdffit_interp interp, double rgb[3])
{
    if (!table || !wi || !wo || !rgb || !scale_known(scale) ||
        (interp != BRDFFIT_INTERP_NEAREST && interp != BRDFFIT_INTERP_TRILINEAR))
        return BRDFFIT_E_INVALID_ARGUMENT;
    double u[3];
    if (!grid_coords(wi, wo, u))
        return BRDFFIT_E_INVALID_ARGUMENT;
    double f[3];
    bf_scale_factors(scale, f);

    if (interp == BRDFFIT_INTERP_NEAREST) {
        size_t b = brdffit_bin_index(index_of(u[0], NTH), index_of(u[1], NTD),
                                     index_of(u[2], NPD));
        for (int c = 0; c < 3; c++) {
            double v = table->v[c * NBINS + b];
            rgb[c] = v < 0 ? -1.0 : v * f[c];
        }
        return BRDFFIT_OK;
    }

    /* trilinear: clamped in theta_h and theta_d, periodic in phi_d */
    double uh = fmin(fmax(snap(u[0]), 0.0), NTH - 1);
    double ud = fmin(fmax(snap(u[1]), 0.0), NTD - 1);
    double up = snap(u[2]);
    int ih = (int)floor(uh), id = (int)floor(ud), ip = (int)floor(up);
    double fh = uh - ih, fd = ud - id, fp = up - ip;
    int ih1 = clampi(ih + 1, 0, NTH - 1), id1 = clampi(id + 1, 0, NTD - 1);
    ip = ((ip % NPD) + NPD) % NPD;
    int ip1 = (ip + 1) % NPD;
    const int hh[2] = { ih, ih1 }, dd[2] = { id, id1 }, pp[2] = { ip, ip1 };
    const double wh[2] = { 1 - fh, fh }, wd[2] = { 1 - fd, fd }, wp[2] = { 1 - fp, fp };
    double sum[3] = { 0, 0, 0 };
    int masked[3] = { 0, 0, 0 };
    for (int a = 0; a < 2; a++) {
        for (int b = 0; b < 2; b++) {
            for (int c = 0; c < 2; c++) {
                double w = wh[a] * wd[b] * wp[c];
                if (w == 0)
                    continue;
                size_t bin = brdffit_bin_index(hh[a], dd[b], pp[c]);
                for (int ch = 0; ch < 3; ch++) {
                    double v = table->v[ch * NBINS + bin];
                    if (v < 0)
                        masked[ch] = 1;
                    else
                        sum[ch] += w * v;
                }
            }
        }
    }
    for (int c = 0; c < 3; c++)
        rgb[c] = masked[c] ? -1.0 : sum[c] * f[c];
    return BRDFFIT_OK;
}
