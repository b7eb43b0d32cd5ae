/* SPDX-License-Identifier: MIT */
/* linear.h -- the linear unknowns of a fit (d, s per channel), solved exactly
 * at every lobe point from one data pass's moments (variable projection).
 *
 * f_c = d_c/pi + s_c K_c(p) is linear in d and s, so for given lobe
 * parameters p the best non-negative d, s of each channel are a 2-unknown
 * non-negative least-squares problem whose normal equations are moments of
 * the pass.  The pass is taken at a reference (d_ref, s_ref) (its residual
 * moments are those of e = rho - d_ref/pi - s_ref K), and every quantity
 * here is written in the offsets d - d_ref, s - s_ref, so it loses no digits
 * when the reference is near the answer (the previous point's solution).
 *
 * The fit's least-squares problem in the lobe coordinates u alone is then
 *   F(u) = min over d, s >= 0 of |r(d, s, u)|^2,
 * with gradient J_u^T r* at the solution (r* is orthogonal to the free
 * linear columns) and Gauss-Newton matrix J_red^T J_red, J_red = (I - P) J_u,
 * P the projection on the free linear columns (Kaufman's approximation). */
#ifndef BRDFFIT_LINEAR_H
#define BRDFFIT_LINEAR_H

#include "internal.h"
#include "bf_layout.h"

typedef struct bf_linear {
    double d[3], s[3];
} bf_linear;

/* The best non-negative d, s per channel at the pass's lobe point into best,
 * from moments mom[bf_nmom(nk, np)] taken at ref; returns the Error^2 (r^T r)
 * there.  np may be 0 (a value pass). */
double bf_linear_best(const double *mom, int nk, int np, const bf_linear *ref, bf_linear *best);

/* 1 when r^T r = rr (bf_linear_best's, from the same moments) has lost
 * digits to cancellation: it is the residual energy at the reference minus
 * what the offsets to the best d, s explain, and that energy exceeds
 * BF_LINEAR_REF_FAR times rr (a reference s ~ 1e5 times the best, after a
 * start whose lobe is nearly zero, can leave a spurious rr = 0).  Then take
 * the pass again at the best d, s. */
#define BF_LINEAR_REF_FAR 1e4
int bf_linear_ref_far(const double *mom, int nk, int np, double rr);

/* The reduced normal equations in the np lobe coordinates at best (from
 * bf_linear_best on the same moments): H = J_red^T J_red (np x np, rows of
 * BF_MAX_NP), g = J_red^T r, and hdiag = the diagonal of J_u^T J_u before the
 * linear unknowns are projected out (a scale for rank decisions). */
void bf_linear_reduce(const double *mom, int nk, int np, const bf_linear *ref, const bf_linear *best,
                      double H[][BF_MAX_NP], double *g, double *hdiag);

#endif
