/* internal.h -- what the library's source files share and the API does not show. */
#ifndef BRDFFIT_INTERNAL_H
#define BRDFFIT_INTERNAL_H

#include "brdffit.h"

#include <stddef.h>

#include "bf_pass.h"

#if defined(__GNUC__)
#define BF_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define BF_PRINTF(a, b)
#endif

/* Record status and a formatted message in err (when err is not NULL) and
 * return status, so that callers can write `return bf_fail(err, ...)`. */
brdffit_status bf_fail(brdffit_error *err, brdffit_status status, const char *fmt, ...)
    BF_PRINTF(3, 4);
/* Mark err as a success (status OK, empty message). */
void bf_ok(brdffit_error *err);

/* Wall-clock seconds from a monotonic clock. */
double bf_now(void);

/* 64-byte-aligned allocation (for OpenCL CL_MEM_USE_HOST_PTR); free with bf_free_aligned. */
void *bf_alloc_aligned(size_t bytes);
void bf_free_aligned(void *p);

/* The channel factors of a scale mode; factors must hold 3. */
void bf_scale_factors(brdffit_scale scale, double factors[3]);

/* The default He wavelengths (um) where params->lambda_um[c] is 0. */
void bf_lambdas(const brdffit_params *params, double lam[3]);

/* ---- sample sets: the prepared geometry a data pass reads ----
 * One 64-byte-aligned block of BF_NFIELDS x npad doubles, field f at
 * data + f * npad (structure of arrays, so the kernel loads vectors); the
 * fields BF_F_* are listed in kernels/bf_pass.h.
 * Padding samples (index >= n) are harmless: wi = wo = (0, 0, 1), rgb = 0,
 * a2 = 0, so they add exactly 0 to every sum. */
#define BF_PAD 64  /* npad is a multiple of this */

struct brdffit_samples {
    size_t n;                    /* valid samples */
    size_t npad;                 /* n rounded up to a multiple of BF_PAD (>= BF_PAD) */
    size_t masked;               /* bins with a negative value in some channel */
    size_t beyond_cutoff;        /* valid bins outside the cutoff (or below the horizon) */
    brdffit_sample_options opt;
    double sum_w;                /* sum of the solid-angle weights of the n samples */
    double *data;                /* BF_NFIELDS * npad doubles, aligned */
    double *w;                   /* n solid-angle weights */
    int *bin;                    /* n bin indices k + 180*(j + 90*i) */
};

#endif /* BRDFFIT_INTERNAL_H */
