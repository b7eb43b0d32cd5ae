/* SPDX-License-Identifier: MIT */
/* subsets.h -- the screening subsets of a sample set (subsets.c). */
#ifndef BRDFFIT_SUBSETS_H
#define BRDFFIT_SUBSETS_H

#include "brdffit.h"

/* Below this many samples in a subset, a model's screen_stride (or
 * screen_bins) is not used. */
#define BF_SCREEN_MIN_SAMPLES 4096

/* The subsets of s that fits of model screen on, kept with s (made the
 * first time one is asked for): every screen_stride-th sample (*every) and,
 * when bins is not NULL, the bin subset of screen_bins (*bins); NULL where
 * the model has none or it would hold fewer than BF_SCREEN_MIN_SAMPLES
 * samples (*bins is NULL whenever *every is). */
brdffit_status bf_screen_subsets(const brdffit_samples *s, brdffit_model model,
                                 const brdffit_samples **every, const brdffit_samples **bins,
                                 brdffit_error *err);

#endif /* BRDFFIT_SUBSETS_H */
