/* SPDX-License-Identifier: MIT */
/* fc_shim.h -- the C side of the Ceres fitter (fit_ceres.cc): everything it
 * needs from the library and the kernel headers, behind plain C declarations
 * (the C++ file includes only this and brdffit.h).  fc_shim.c is compiled
 * as C with the project's flags; the lobe values and partials come from
 * kernels/bf_lobe.h (bf_lobe, bf_lobe_vdk), the samples and the start
 * screening from the library's internals.
 *
 * The fitter's unknowns are d[3], s[3] and the lobe coordinates theta[nc]
 * (fc_coords): per lobe coordinate j of the fit (bf_model_coord_param), a
 * LOG parameter is theta = ln p, a LINEAR one theta = p (both bounded by the
 * registry's bounds), a DIRECTION pair (Lafortune's Cxy, Cz) the angle phi
 * with (Cxy, Cz) = (cos phi / sqrt 2, sin phi) (unbounded). */
#ifndef FC_SHIM_H
#define FC_SHIM_H

#include "brdffit.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* 1 when the model's lobe has analytic partials in the kernel headers
 * (bf_lobe_vdk: BF_FD_GRAD or BF_FD_SCHLICK): the models this fitter takes. */
int fc_has_partials(brdffit_model model);

/* The lobe coordinates theta of a model: their number (returned), and per
 * coordinate its bounds lo[j] <= theta_j <= hi[j] when bounded[j]. */
int fc_coords(brdffit_model model, double lo[3], double hi[3], int bounded[3]);
/* theta -> the lobe parameters p in the paper's units, and back. */
void fc_params_of(brdffit_model model, const double *theta, double p[3]);
void fc_theta_of(brdffit_model model, const double p[3], double *theta);

/* The samples a fit's passes on all of s read: its mirror set (kept with s,
 * freed with it) when mirror, else s itself; NULL after printing why. */
const brdffit_samples *fc_fitted_set(const brdffit_samples *s, int mirror);
/* Its samples, and the part of the Error^2 no residual carries: the mirror
 * set's pairs' share (pair_see summed over the channels; 0 for a plain set). */
size_t fc_count(const brdffit_samples *set);
double fc_pair_see(const brdffit_samples *set);

/* The residuals of samples i0 .. i0 + n - 1 of set at (d, s, theta), three a
 * sample (row 3 i + c for channel c):
 *     r = sqrt(a2) (rho_c - d_c / pi - s_c K_c(p)),  a2 = w cos^2 ti / (3 sum w)
 * (the set's metric weight BF_F_A2), so that sum r^2 + fc_pair_see = Error^2.
 * With jd, js, jt (all or none NULL), their Jacobian, row-major as Ceres
 * takes it: jd and js 3n x 3 (d r / d d, d r / d s), jt 3n x nc (d r / d theta,
 * from bf_lobe_vdk's partials in p times d p / d theta). */
void fc_residuals(const brdffit_samples *set, size_t i0, size_t n, brdffit_model model,
                  const double d[3], const double s[3], const double *theta, double *r,
                  double *jd, double *js, double *jt);

/* The same for one channel c: n residuals (row i for sample i0 + i) at
 * (ds[0], ds[1]) = (d_c, s_c); with jds and jt (both or neither NULL) their
 * Jacobian, n x 2 (d r / d d_c, d r / d s_c) and n x nc. */
void fc_residuals_channel(const brdffit_samples *set, size_t i0, size_t n, brdffit_model model,
                          int c, const double ds[2], const double *theta, double *r, double *jds,
                          double *jt);

/* Error (the "ngan-l2" metric) of (d, s, p) from fc_residuals over the whole
 * set plus fc_pair_see. */
double fc_error(const brdffit_samples *set, brdffit_model model, const double d[3],
                const double s[3], const double p[3]);

/* The start a brdffit fit of `samples` refines (for the models here:
 * one round of default_starts starts from the registry's start grid, the
 * cheapest kept), screened as brdffit screens it: one value pass each, with
 * d, s solved exactly (bf_linear_best), on the model's screening subset
 * (bf_screen_subsets; all samples when it has none); the kept start is then
 * taken again on all samples (the mirror set).  Into theta its lobe
 * coordinates, into d, s the best d, s there.  0, or 1 after printing why. */
int fc_best_start(brdffit_context *ctx, const brdffit_samples *samples, brdffit_model model,
                  double *theta, double d[3], double s[3]);

#ifdef __cplusplus
}
#endif

#endif /* FC_SHIM_H */
