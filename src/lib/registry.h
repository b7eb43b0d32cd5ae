/* SPDX-License-Identifier: MIT */
/* registry.h -- the model registry: every fact about a model, written once in
 * registry.c (its lobe, by id, in BF_MODEL_LOBES of kernels/bf_models.h, the
 * one part the kernel sees).  The public part (brdffit_model_info,
 * brdffit_param_info) is what brdffit_model_get and brdffit_model_param
 * return; the rest is the fit's (its start grid). */
#ifndef BRDFFIT_REGISTRY_H
#define BRDFFIT_REGISTRY_H

#include "internal.h"

/* The starting points a fit screens.  Start i of n has every lobe parameter at
 * its `start` value except:
 *   param        set to the i-th point of lo..hi, evenly spaced (LINEAR) or
 *                geometrically (LOG): over all n starts when period is 0,
 *                else over `period` points repeated (i % period);
 *   round_param  (unless -1) in round k = i / period (of `period` starts)
 *                multiplied by round_factor^e, e = 0, 1, -1, 2, -2, ... for
 *                k = 0, 1, 2, 3, 4, ..., kept within its bounds. */
typedef struct bf_start_grid {
    int param;
    brdffit_param_map spacing;
    double lo, hi;
    int period;
    int round_param;
    double round_factor;
} bf_start_grid;

/* When the fit corrects Gauss-Newton's H by a secant estimate of the
 * residuals' curvature (fit/problem.c, secant_correct). */
typedef enum bf_secant_use {
    BF_SECANT_ALWAYS = 0, /* in every LM run                                   */
    BF_SECANT_ON_ALL = 1  /* in the LM runs on all samples, not in those on the
                           * screening's subset (refine_on_subset)             */
} bf_secant_use;

typedef struct bf_model_def {
    brdffit_model_info info;     /* the public descriptor                       */
    bf_start_grid grid;          /* the starts the fit screens                  */
    int screen_stride;           /* > 1: the starts are screened on every
                                  * screen_stride-th sample, and the kept ones
                                  * then taken on all, or refined on the subset
                                  * first (refine_on_subset); 0: all samples  */
    int screen_bins[3];          /* all > 0: the starts are screened on the
                                  * samples of every screen_bins[0]-th theta_h,
                                  * [1]-th theta_d and [2]-th phi_d bin index
                                  * (fewer bins than the screen_stride subset,
                                  * for a lobe whose per-bin work is most of a
                                  * pass), and the kept ones taken again on the
                                  * screen_stride subset; zeros: not used     */
    bf_secant_use secant;        /* when LM's H gets the secant correction (fit/) */
    int refine_on_subset;        /* 1: each kept start is refined by LM on the
                                  * screening's subset first, then on all
                                  * samples from where that stopped (fit/refine.c,
                                  * bf_refine_kept); 0: on all samples only   */
    int refine_on_bins;          /* 1 (with refine_on_subset and screen_bins):
                                  * each kept start is refined by LM on the
                                  * bin subset before the screen_stride
                                  * subset, and only the bin ends within
                                  * BINS_MARGIN of the lowest go on there, from
                                  * that end (fit/refine.c, bins_runs)       */
    int rough_param;             /* with refine_on_bins: a bin end whose lobe
                                  * parameter rough_param is at or above
                                  * rough_from goes on from its start instead */
    double rough_from;
    unsigned held;               /* bit k: the fit holds parameter k at its
                                  * start (a parameter that trades off
                                  * exactly with others), though the model
                                  * takes any value in its bounds          */
    int nonreciprocal;           /* 1: f(wi, wo) != f(wo, wi), so a fit and
                                  * brdffit_error_of take every sample, not
                                  * the mirror set's merged pairs           */
} bf_model_def;

/* The registry entry of a model, or NULL for an id out of range. */
const bf_model_def *bf_model_def_get(brdffit_model model);

/* 1 when the model is of the form f = d/pi + s K with a lobe K in
 * BF_MODEL_LOBES (the data pass and its kernel fit it), 0 for the others
 * (the glTF models: fit/affine.c) and unknown ids. */
int bf_model_has_lobe(brdffit_model model);
/* The lobe coordinates a fit uses for a model: one per parameter, one per
 * DIRECTION pair (Lafortune: direction + n = 2), none for a parameter whose
 * bounds are equal (held at that value); 0 for an unknown model. */
int bf_model_ncoords(brdffit_model model);
/* The first parameter of lobe coordinate j (-1 when out of range). */
int bf_model_coord_param(brdffit_model model, int j);
/* p[0 .. n-1]: every lobe parameter at its `start` value, 0 beyond the
 * model's parameters (n: the room the caller has). */
void bf_model_start_params(brdffit_model model, double *p, int n);

#endif
