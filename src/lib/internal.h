/* SPDX-License-Identifier: MIT */
/* internal.h -- what the library's source files share and the API does not show. */
#ifndef BRDFFIT_INTERNAL_H
#define BRDFFIT_INTERNAL_H

#include "brdffit.h"

#include <stddef.h>

#if defined(__GNUC__)
#define BF_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define BF_PRINTF(a, b)
#endif

/* Record status and a formatted message in err (when err is not NULL) and
 * return status, so that callers can write `return bf_fail(err, ...)`. */
brdffit_status bf_fail(brdffit_error *err, brdffit_status status, const char *fmt, ...)
    BF_PRINTF(3, 4);
/* path as it goes into a message: itself when shorter than len, else its
 * head, "...", and its tail (len - 1 bytes in all), so that what follows the
 * path in a message (the reason) still fits.  Returns buf. */
const char *bf_path_brief(const char *path, char *buf, size_t len);
/* The fault of a direction pair in err, prefixed by `what` ("brdffit_eval",
 * "brdffit_eval_batch: pair 3 of 10", ...): which of wi, wo is not a finite,
 * non-zero vector, with its value, else that wo = -wi (no half vector).
 * BRDFFIT_E_INVALID_ARGUMENT. */
brdffit_status bf_fail_pair(brdffit_error *err, const char *what, const double wi[3],
                            const double wo[3]);
/* bf_fail_pair for pair `first` of a batch of n, `bad` of them refused, whose
 * results were set to `fill` ("0", "-1"): the message says so. */
brdffit_status bf_fail_pairs(brdffit_error *err, const char *fn, size_t first, size_t n,
                             size_t bad, const char *fill, const double *wi, const double *wo);
/* The arguments every table lookup checks (fn names the caller in the message). */
brdffit_status bf_lookup_check(const char *fn, const brdffit_table *table, brdffit_scale scale,
                               brdffit_interp interp, brdffit_error *err);
/* 1 when v is finite and not zero (a direction once normalised). */
int bf_direction_ok(const double v[3]);
/* Mark err as a success (status OK, empty message). */
void bf_ok(brdffit_error *err);

/* Wall-clock seconds from a monotonic clock. */
double bf_now(void);

/* 64-byte-aligned allocation (for OpenCL CL_MEM_USE_HOST_PTR), on huge pages
 * from 4 MB on (a hint); free with bf_free_aligned, which keeps such an array
 * in a process-wide pool for the next one of about its size (alloc.c; not
 * zeroed: callers write what they read).  The library's large arrays take
 * it: a table's values, a sample set's fields, weights and bins, and the
 * index arrays its subsets and mirror set are made with. */
void *bf_alloc_aligned(size_t bytes);
void bf_free_aligned(void *p);
/* The bytes the pool holds now (brdffit_release_memory empties it); whether
 * this build pools at all (not under AddressSanitizer); and, for tests, every
 * pooled array filled with `byte` (so that a reader of what it did not write
 * sees that): the number of arrays filled. */
size_t bf_alloc_pooled(void);
int bf_alloc_pool_on(void);
size_t bf_alloc_pool_fill(unsigned char byte);

/* The channel factors of a scale mode; factors must hold 3. */
void bf_scale_factors(brdffit_scale scale, double factors[3]);
/* 1 for BRDFFIT_SCALE_STANDARD and _FLAT, 0 for anything else. */
int bf_scale_known(brdffit_scale scale);

/* The default He wavelengths (um) where params->lambda_um[c] is 0. */
void bf_lambdas(const brdffit_params *params, double lam[3]);
/* f per channel of a model at checked params for a derived geometry g
 * (bf_geom_derive), no cosine factor: d/pi + s K, or the glTF BRDF. */
struct bf_geom;
void bf_model_value(brdffit_model model, const struct bf_geom *g, const brdffit_params *params,
                    const double lam[3], double rgb[3]);

/* Sized options structs (include/brdffit.h: `size` first, set by _default()).
 * bf_options_read: out holds the defaults of struct `kind`; the members of
 * the caller's opt that lie wholly within opt->size replace them (opt NULL:
 * nothing to do).  bf_options_write: the members of src (a whole struct of
 * `kind`) that lie within out->size are copied into the caller's out.  Both
 * check the caller's size first: BRDFFIT_E_OPTIONS_SIZE naming the struct
 * for size 0, smaller than `size` itself, larger than the library's struct,
 * or ending inside a member. */
brdffit_status bf_options_read(brdffit_struct_kind kind, const void *opt, void *out,
                               brdffit_error *err);
brdffit_status bf_options_write(brdffit_struct_kind kind, const void *src, void *out,
                                brdffit_error *err);
/* The check alone, of a sized result the caller gives (brdffit_fit_result,
 * brdffit_sample): also refused is a size smaller than its first sized
 * layout.  bf_options_write then fills it. */
brdffit_status bf_sized_check(brdffit_struct_kind kind, const void *out, brdffit_error *err);
/* An options struct's defaults (dflt, a whole struct of `kind`) in the
 * caller's opt of `size` bytes (its sizeof as the caller was compiled):
 * `size` set, the members that lie wholly within it copied, the rest of its
 * bytes up to this library's struct cleared.  A size that a call then
 * refuses (larger than this library's struct, ending inside a member) is
 * written as given, so that the call names it.  Nothing for a NULL opt or a
 * size smaller than `size` itself. */
void bf_options_init(brdffit_struct_kind kind, const void *dflt, void *opt, size_t size);
/* The end of the last member of struct `kind` (its size without tail padding). */
size_t bf_struct_members_end(brdffit_struct_kind kind);

/* The model registry's internal side (bf_model_ncoords, ...): registry.h. */

#endif /* BRDFFIT_INTERNAL_H */
