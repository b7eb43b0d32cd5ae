/* SPDX-License-Identifier: MIT */
/* samples.h -- the inside of a sample set: the prepared geometry and
 * values a data pass reads (samples.c makes it). */
#ifndef BRDFFIT_SAMPLES_H
#define BRDFFIT_SAMPLES_H

#include "brdffit.h"

#include <pthread.h>
#include <stddef.h>

#include "bf_layout.h"
#include "bf_models.h"

/* A sample set: one 64-byte-aligned block of BF_NFIELDS x npad doubles, field f at
 * data + f * npad (structure of arrays, so the kernel loads vectors); the
 * fields BF_F_* are listed in kernels/bf_layout.h.
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
    double sum_a2;               /* sum of the metric weights a2 of the n samples */
    double pair_see[3];          /* per channel, what a pass adds to its sum a2 e^2:
                                  * a mirror set's pairs' share of it beyond their
                                  * merged samples' (bf_samples_mirror); 0 else */
    double *data;                /* BF_NFIELDS * npad doubles, aligned */
    double *w;                   /* n solid-angle weights */
    int *bin;                    /* n bin indices k + 180*(j + 90*i) */
    /* What fits derive from the set and every fit of it can share (its
     * screening subsets, He's bin table: samples_derived.c), made by the
     * first fit that asks and kept until the set is freed.  The set is
     * otherwise read-only after it is made; derived_lock guards the list. */
    pthread_mutex_t derived_lock;
    struct bf_derived *derived;
};

/* The geometry of a padding sample: wi = wo = N, derived (bf_geom_derive).
 * Finite in every model; the bin table gives it to bins with no sample. */
void bf_samples_pad_geom(bf_geom *g);

/* How many distinct geometries the samples hold, counted up to need (at
 * most BF_GEOM_NEED_MAX): directions that differ only by a rotation about
 * the normal or by exchanging wi and wo are one geometry, as every model is
 * isotropic and reciprocal.  A fit with fewer than its unknowns per channel
 * is refused (brdffit_fit: BRDFFIT_E_TOO_FEW_SAMPLES). */
#define BF_GEOM_NEED_MAX 8
size_t bf_samples_geometries(const brdffit_samples *samples, size_t need);

/* Every stride-th sample of src (0, stride, 2 stride, ...: table order, so
 * runs of one (theta_h, theta_d) bin stay together) as a sample set of its
 * own, with src's metric weights a2 (its sums are about 1/stride of src's):
 * what a fit screens its starts on (bf_model_def.screen_stride). */
brdffit_status bf_samples_every(const brdffit_samples *src, size_t stride, brdffit_samples **out,
                                brdffit_error *err);

/* The samples of src whose bin is on every step[0]-th theta_h, step[1]-th
 * theta_d and step[2]-th phi_d index (steps >= 1), in table order, with
 * src's metric weights a2: what a fit screens its starts on when its model
 * has screen_bins (bf_model_def). */
brdffit_status bf_samples_bins(const brdffit_samples *src, const int step[3],
                               brdffit_samples **out, brdffit_error *err);

/* A sample set of src's samples idx[0..n-1] (increasing: table order), with
 * src's metric weights a2 (its sums are a sample of src's). */
brdffit_status bf_samples_take(const brdffit_samples *src, const size_t *idx, size_t n,
                               brdffit_samples **out, brdffit_error *err);

/* The mirror set of src (samples_mirror.c): each pair of samples in the MERL
 * bins (i, j, k) and (i, j, 180 - k) merged into one sample at bin k, with
 * the same sums in every data pass (pair_see): what a fit's passes on all
 * samples read, about half of src's samples. */
brdffit_status bf_samples_mirror(const brdffit_samples *src, brdffit_samples **out,
                                 brdffit_error *err);

/* ---- derived data kept with a set (samples_derived.c) */

/* The kinds of derived data (the key's meaning is the kind's). */
enum { BF_DERIVED_EVERY = 1, BF_DERIVED_BINS = 2, BF_DERIVED_BIN_TABLE = 3, BF_DERIVED_MIRROR = 4,
       BF_DERIVED_METRIC = 5 /* the pairs a metric pass reads (metric.c) */ };

/* Makes the data of (kind, key) from s into *out; frees it. */
typedef brdffit_status (*bf_derive_fn)(const brdffit_samples *s, const int key[3], void **out,
                                       brdffit_error *err);
typedef void (*bf_derived_free_fn)(void *data);

/* The lock and list of a set just made, and their end when it is freed
 * (freeing every derived datum). */
void bf_derived_init(brdffit_samples *s);
void bf_derived_free(brdffit_samples *s);

/* The datum of (kind, key) kept with s: made by make the first time (under
 * s's lock, so that two threads fitting s at once make it once), then the
 * same pointer until s is freed.  A failure of make is returned and nothing
 * is kept. */
brdffit_status bf_derived_get(const brdffit_samples *s, int kind, const int key[3],
                              bf_derive_fn make, bf_derived_free_fn free_fn, const void **out,
                              brdffit_error *err);

/* How many data s keeps (for the tests: that each is made once). */
size_t bf_derived_count(const brdffit_samples *s);

/* bf_samples_every, bf_samples_bins and bf_samples_mirror of src, kept with
 * src (the same samples to the bit; freed with src, not by the caller). */
brdffit_status bf_samples_every_kept(const brdffit_samples *src, size_t stride,
                                     const brdffit_samples **out, brdffit_error *err);
brdffit_status bf_samples_bins_kept(const brdffit_samples *src, const int step[3],
                                    const brdffit_samples **out, brdffit_error *err);
brdffit_status bf_samples_mirror_kept(const brdffit_samples *src, const brdffit_samples **out,
                                      brdffit_error *err);

#endif /* BRDFFIT_SAMPLES_H */
