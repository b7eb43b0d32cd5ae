/* SPDX-License-Identifier: MIT */
/* albedo.h -- the quadrature of the directional albedo (albedo_quad.c) that
 * brdffit_albedo_model and brdffit_albedo_table (albedo.c) share.
 *
 * For one viewing direction wo = (sin to, 0, cos to) the hemisphere of wi is
 * covered in polar coordinates (r, phi) about a pole, phi in [0, pi] (every
 * integrand is symmetric in y: isotropic BRDFs, wo in the x-z plane) by
 * Gauss-Legendre, r over exactly the part of [0, r_end] where wi is above the
 * horizon, by composite Gauss-Legendre on intervals graded geometrically
 * (ratio 2) toward the pole down to the lobe's width and toward the horizon,
 * where an integrand may have a kink or a square root.  Two poles:
 *   AQ_HALF:  r = theta_h, the half vector h = (sin r cos phi, sin r sin phi,
 *             cos r), wi = 2 (wo.h) h - wo, d wi = 4 (wo.h) sin r dr dphi;
 *             wi is above the horizon for r < (psi + pi/2) / 2, psi =
 *             atan2(sin to cos phi, cos to).  Every lobe peaked at the mirror
 *             direction is round about h = N here.
 *   AQ_POLE:  r = the angle from a unit pole P in the x-z plane (Lafortune's
 *             lobe axis), r in [0, pi/2], d wi = sin r dr dphi.
 *   AQ_TABLE: AQ_HALF with the radial intervals a MERL table's theta_h bins
 *             (theta_h = (k / 90)^2 pi / 2, where its trilinear lookup has
 *             its kinks in theta_h), `order` points each.
 * Each point's weight includes cos theta_i and the factor 2 of the symmetry:
 * sum_points weight * f(wi, wo) is the albedo. */
#ifndef BRDFFIT_ALBEDO_H
#define BRDFFIT_ALBEDO_H

#include <stddef.h>

typedef enum aq_kind { AQ_HALF = 0, AQ_POLE = 1, AQ_TABLE = 2 } aq_kind;

typedef struct aq_rule {
    aq_kind kind;
    double pole[3];   /* AQ_POLE: unit, pole[1] = 0                          */
    double width;     /* the finest radial scale the lobe has (radians)      */
    int nphi;         /* Gauss-Legendre points in phi on [0, pi]             */
    int order;        /* Gauss-Legendre points per radial interval           */
} aq_rule;

/* A point: wi (unit, above the horizon), N.H and V.H of its half vector
 * (-1: not known, AQ_POLE) and its weight. */
typedef struct aq_point {
    double wi[3];
    double nh, vh;
    double w;
} aq_point;

/* The most points aq_points writes for a rule (an upper bound). */
size_t aq_max_points(const aq_rule *rule);

/* The quadrature's points for wo (unit, wo[1] = 0, wo[2] > 0) into pts
 * (aq_max_points of them at most); returns their number. */
size_t aq_points(const aq_rule *rule, const double wo[3], aq_point *pts);

/* Gauss-Legendre nodes x and weights w of order n (1..128) on [-1, 1]. */
void aq_gauss_legendre(int n, double *x, double *w);

/* brdffit_albedo_model with nphi points in phi (0: the public function's,
 * which depend on theta_o) and order points per radial interval (0: the
 * public function's, which depend on the model): for convergence checks. */
#include "brdffit.h"
brdffit_status bf_albedo_model_rule(brdffit_model model, const brdffit_params *params, size_t n,
                                    const double *theta_o_deg, double *rgb, int nphi, int order,
                                    brdffit_error *err);

#endif
