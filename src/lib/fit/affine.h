/* SPDX-License-Identifier: MIT */
/* affine.h -- the fit of a model whose colour enters affinely (colour_form
 * BRDFFIT_COLOUR_GLTF): f_c = A(p) + x_c B(p), x_c the base colour of channel
 * c in [0, 1], A and B the same in every channel (the fit holds the specular
 * colour white: kernels/bf_gltf.h, docs/fitting.md "The glTF models").
 *
 * At every point p of the lobe parameters the best x_c is solved exactly
 * (a bounded one-unknown least-squares problem per channel) and LM moves only
 * the lobe coordinates u, as the d/pi + s K models' fit does with d and s
 * (linear.h).  A data pass (affine_pass.c) sums, over the samples, the
 * products of the weights a^2, the bases A, B and their derivatives dA_j,
 * dB_j in the coordinates u_j, and the measured values rho_c: every quantity the
 * reduced problem needs follows from them for any x (affine.c). */
#ifndef BRDFFIT_AFFINE_H
#define BRDFFIT_AFFINE_H

#include "fit_internal.h"

#define AF_NP BRDFFIT_MAX_LOBE_PARAMS

/* The sums of one pass at a point p_0 and its np neighbours p_j (all sums
 * weighted by a^2; dX_j = dX/dp . (p_j - p_0) / h_j, the partials' first-order
 * step to the neighbour, bf_gltf_affine_grad). */
typedef struct af_mom {
    int np;
    double aa, ab, bb;                 /* sum A A, A B, B B                   */
    double daa[AF_NP], dab[AF_NP];     /* sum dA_j A, dA_j B                  */
    double dba[AF_NP], dbb[AF_NP];     /* sum dB_j A, dB_j B                  */
    double dada[AF_NP][AF_NP];         /* sum dA_j dA_l                       */
    double dadb[AF_NP][AF_NP];         /* sum dA_j dB_l                       */
    double dbdb[AF_NP][AF_NP];         /* sum dB_j dB_l                       */
    double rr[3], ra[3], rb[3];        /* per channel: sum rho rho, rho A, rho B */
    double rda[3][AF_NP], rdb[3][AF_NP]; /* sum rho dA_j, rho dB_j           */
} af_mom;

/* The sums of a pass on samples at points pts[0..np] (pts[0] = p_0), with
 * 1 / h_j in inv_h, and the samples' pair_see added to rr.  Summed over the
 * samples in threads (at most the online CPUs), each its own run, added in
 * a fixed order: the same sums on every run. */
brdffit_status bf_affine_pass(const brdffit_samples *samples, brdffit_model model,
                              const double (*pts)[AF_NP], int np, const double *inv_h, af_mom *m,
                              brdffit_error *err);

/* fn on each of njobs jobs of size bytes from jobs, on the pass workers (at
 * most nworkers threads, made once a process) while the caller waits, or in
 * the calling thread when the workers are in use or cannot be made
 * (affine_pool.c). */
void bf_affine_run(void (*fn)(void *), void *jobs, size_t size, int njobs, int nworkers);

/* From a pass's sums m: r^T r, H = J^T J and g = J^T r in the first nx
 * coordinates (nx x nx, nx) at the best base colours (into base; each
 * solved in [0, 1], a colour inside projected out of H), and hdiag, H's
 * diagonal before that (affine_reduce.c). */
void bf_affine_reduce(const af_mom *m, int nx, double *rr, double H[][AF_NP], double *g,
                      double *hdiag, double *base);

/* H = R^T R (R upper) and z = R^-T g; a pivot that vanishes against hdiag
 * (a direction the data does not see) gives a zero row. */
void bf_affine_chol(int nx, double H[][AF_NP], const double *g, const double *hdiag,
                    double R[][AF_NP], double *z);

/* sum_s a^2 (rho_c - f_c)^2 over the three channels (with the samples'
 * pair_see) at params: the Error squared of a glTF model's parameters,
 * computed directly (the residuals, not the pass's sums). */
double bf_model_rr(const brdffit_samples *samples, brdffit_model model,
                   const brdffit_params *params);

/* The subset the affine fit screens its starts on: every screen_stride-th
 * sample of the mirror set (kept with it), or the mirror set itself when
 * that would hold fewer than BF_SCREEN_MIN_SAMPLES. */
brdffit_status bf_affine_subset(const brdffit_samples *mirror, brdffit_model model,
                                const brdffit_samples **out, brdffit_error *err);

/* brdffit_fit and brdffit_error_of for such a model (api.c routes to them). */
brdffit_status bf_affine_fit(brdffit_context *ctx, const brdffit_samples *samples,
                             brdffit_model model, const brdffit_fit_options *o,
                             brdffit_fit_result *r, brdffit_error *err);

#endif
