/* SPDX-License-Identifier: MIT */
/* status.c -- status texts, error reports, and the small utilities every file uses. */
#include "internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define BF_STR_(x) #x
#define BF_STR(x) BF_STR_(x)

/* The header's version macros are the one place the version is written. */
const char *brdffit_version(void)
{
    return BF_STR(BRDFFIT_VERSION_MAJOR) "." BF_STR(BRDFFIT_VERSION_MINOR) "." BF_STR(
        BRDFFIT_VERSION_PATCH);
}

static const char *const status_text[BRDFFIT_STATUS_COUNT] = {
    [BRDFFIT_OK] = "success",
    [BRDFFIT_E_INVALID_ARGUMENT] = "invalid argument",
    [BRDFFIT_E_NO_MEMORY] = "out of memory",
    [BRDFFIT_E_FILE_OPEN] = "cannot open file",
    [BRDFFIT_E_FILE_NOT_REGULAR] = "not a regular file",
    [BRDFFIT_E_FILE_READ] = "read error",
    [BRDFFIT_E_FILE_EMPTY] = "empty file",
    [BRDFFIT_E_FILE_TRUNCATED] = "truncated file",
    [BRDFFIT_E_FILE_DIMS] = "unexpected table dimensions",
    [BRDFFIT_E_FILE_TRAILING] = "trailing bytes after the table",
    [BRDFFIT_E_FILE_NONFINITE] = "non-finite value in the table",
    [BRDFFIT_E_FILE_WRITE] = "write error",
    [BRDFFIT_E_UNKNOWN_MODEL] = "unknown model",
    [BRDFFIT_E_PARAM_RANGE] = "parameter out of range",
    [BRDFFIT_E_NO_SAMPLES] = "no valid samples",
    [BRDFFIT_E_NO_DEVICE] = "no OpenCL device",
    [BRDFFIT_E_OPENCL] = "OpenCL error",
    [BRDFFIT_E_KERNEL_BUILD] = "OpenCL kernel build failed",
    [BRDFFIT_E_FIT_FAILED] = "fit failed",
    [BRDFFIT_E_CACHE_DIR] = "PoCL kernel cache directory unusable",
    [BRDFFIT_E_TOO_FEW_SAMPLES] = "too few samples for the model",
    [BRDFFIT_E_VALUE_RANGE] = "value too large",
    [BRDFFIT_E_OPTIONS_SIZE] = "invalid options struct size",
};

const char *brdffit_strerror(brdffit_status status)
{
    if ((int)status < 0 || status >= BRDFFIT_STATUS_COUNT)
        return "unknown status";
    return status_text[status];
}

brdffit_status bf_fail(brdffit_error *err, brdffit_status status, const char *fmt, ...)
{
    if (err) {
        err->status = status;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return status;
}

int bf_direction_ok(const double v[3])
{
    double l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    return isfinite(l2) && l2 > 0;
}

brdffit_status bf_fail_pair(brdffit_error *err, const char *what, const double wi[3],
                            const double wo[3])
{
    int i_ok = bf_direction_ok(wi);
    if (!i_ok || !bf_direction_ok(wo)) {
        const double *v = i_ok ? wo : wi;
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s: %s = (%.9g, %.9g, %.9g) is not a finite, non-zero direction", what,
                       i_ok ? "wo" : "wi", v[0], v[1], v[2]);
    }
    return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                   "%s: wo = (%.9g, %.9g, %.9g) is opposite to wi: no half vector", what, wo[0],
                   wo[1], wo[2]);
}

brdffit_status bf_fail_pairs(brdffit_error *err, const char *fn, size_t first, size_t n,
                             size_t bad, const char *fill, const double *wi, const double *wo)
{
    char what[160];
    snprintf(what, sizeof what, "%s: pair %zu of %zu (%zu bad pair%s, rgb %s there)", fn, first, n,
             bad, bad == 1 ? "" : "s", fill);
    return bf_fail_pair(err, what, wi + 3 * first, wo + 3 * first);
}

const char *bf_path_brief(const char *path, char *buf, size_t len)
{
    size_t n = strlen(path);
    if (len < 8 || n < len) {
        snprintf(buf, len, "%s", path);
        return buf;
    }
    /* head ... tail: the start says where, the end names the file */
    size_t keep = len - 4, head = keep / 3, tail = keep - head;
    memcpy(buf, path, head);
    memcpy(buf + head, "...", 3);
    memcpy(buf + head + 3, path + n - tail, tail);
    buf[head + 3 + tail] = '\0';
    return buf;
}

void bf_ok(brdffit_error *err)
{
    if (err) {
        err->status = BRDFFIT_OK;
        err->message[0] = '\0';
    }
}

double bf_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double brdffit_seconds(void)
{
    return bf_now();
}
