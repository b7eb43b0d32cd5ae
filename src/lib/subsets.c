/* SPDX-License-Identifier: MIT */
/* subsets.c -- the subsets of a sample set that a model's fit screens its
 * starts on (registry: screen_stride, screen_bins), kept with the set so
 * that every fit of it shares them, and brdffit_samples_prepare, which
 * makes them (and He's bin tables) before any fit asks. */
#include "internal.h"
#include "pass.h"
#include "registry.h"
#include "samples.h"
#include "subsets.h"
#include "fit/affine.h"

#include "bf_lobe_pass.h"

brdffit_status bf_screen_subsets(const brdffit_samples *s, brdffit_model model,
                                 const brdffit_samples **every, const brdffit_samples **bins,
                                 brdffit_error *err)
{
    const bf_model_def *def = bf_model_def_get(model);
    *every = NULL;
    if (bins)
        *bins = NULL;
    size_t stride = (size_t)def->screen_stride;
    if (stride <= 1 || s->n / stride < BF_SCREEN_MIN_SAMPLES)
        return BRDFFIT_OK;
    brdffit_status st = bf_samples_every_kept(s, stride, every, err);
    if (st != BRDFFIT_OK || !bins)
        return st;
    if (!(def->screen_bins[0] > 0 && def->screen_bins[1] > 0 && def->screen_bins[2] > 0))
        return BRDFFIT_OK;
    const brdffit_samples *b = NULL;
    st = bf_samples_bins_kept(s, def->screen_bins, &b, err);
    if (st == BRDFFIT_OK && b->n >= BF_SCREEN_MIN_SAMPLES)
        *bins = b;
    return st;
}

brdffit_status brdffit_samples_prepare(const brdffit_samples *samples, brdffit_model model,
                                       brdffit_error *err)
{
    if (!samples)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_samples_prepare: NULL samples");
    if (!brdffit_model_get(model))
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    const brdffit_samples *sets[3] = { NULL, NULL, NULL }; /* all samples' mirror set, subsets */
    brdffit_status st = bf_samples_mirror_kept(samples, &sets[0], err);
    if (st == BRDFFIT_OK && !bf_model_has_lobe(model)) /* the glTF models (fit/affine.c) */
        st = bf_affine_subset(sets[0], model, &sets[1], err);
    else if (st == BRDFFIT_OK)
        st = bf_screen_subsets(samples, model, &sets[1], &sets[2], err);
    for (int i = 0; i < 3 && st == BRDFFIT_OK; i++)
        if (sets[i] && sets[i]->n > 0 && bf_lobe_has_own_fd((int)model))
            st = bf_pass_bins_prepare(sets[i], err);
    if (st == BRDFFIT_OK)
        bf_ok(err);
    return st;
}
