/* SPDX-License-Identifier: MIT */
/* bf_he_surface.h -- a data pass's terms of one direction pair at the
 * surface (the first of the pass machinery, bf_he_pass.h): both directions'
 * u = tau cot(theta) / (2 sigma0) from one division, the shadowing S(u)
 * (Eq. 24) as h u / lu and its derivative, and the root x of the effective
 * roughness sigma (Eq. 80) with one Newton step from a rational start.  The
 * same terms as bf_he_model.h's, to rounding (tests/test_he.c). */
#ifndef BF_HE_SURFACE_H
#define BF_HE_SURFACE_H

#ifndef __OPENCL_VERSION__
#include "bf_he_model.h"
#endif

/* u = tau cot(theta) / (2 sigma0) of both directions from their cosines and
 * sines, each kept in [1e-300, 1e10] (u = 1e10 is the normal: every use
 * below is exactly its u -> inf value there), with one division for the
 * two: a sine is floored at 1e-150 (where cos = 1 and u is 1e10 for any
 * tau / sigma0 above 1e-140), so that their product does not underflow. */
BF_FN void bf_he_u2(BF_REAL ci, BF_REAL si, BF_REAL co, BF_REAL so, double tau, double sigma0,
                    BF_REAL *ui, BF_REAL *uo)
{
    const double k = tau / (2.0 * sigma0);
    BF_REAL rsi, rso;
    bf_rcp2(fmax(si, BF_R(1e-150)), fmax(so, BF_R(1e-150)), &rsi, &rso);
    *ui = fmin(fmax((k * ci) * rsi, BF_R(1e-300)), BF_R(1e10));
    *uo = fmin(fmax((k * co) * rso, BF_R(1e-300)), BF_R(1e10));
}

/* One direction's shadowing is S(theta) = (1 - erfc(u) / 2) / (1 + L(u)),
 * L(u) = (e^(-u^2) / (sqrt(pi) u) - erfc(u)) / 2; bf_he_rough_make_u takes it
 * as h u / lu, h = 1 - erfc(u) / 2, from lu = (1 + L(u)) u =
 * h u + e^(-u^2) / (2 sqrt(pi)), given u, erfc(u) and exp(-u^2): in
 * [0.28, 1e10] for u in [1e-300, 1e10], with no cancellation (both terms
 * non-negative). */
BF_FN BF_REAL bf_he_shadow_lu(BF_REAL u, BF_REAL ec, BF_REAL ex)
{
    return (1.0 - 0.5 * ec) * u + ex * (0.5 / BF_SQRT_PI);
}

/* dS/du times lu^2 (h and lu as above), finite for u in [1e-300, 1e10]:
 * with L' = -e^(-u^2) / (2 sqrt(pi) u^2),
 * dS/du = e^(-u^2) / sqrt(pi) (u lu + h / 2) / lu^2. */
BF_FN BF_REAL bf_he_dshadow_lu(BF_REAL u, BF_REAL h, BF_REAL lu, BF_REAL ex)
{
    return (ex * (1.0 / BF_SQRT_PI)) * (u * lu + 0.5 * h);
}

/* The effective roughness sigma = sigma0 / sqrt(1 + x^2), x e^(x^2/2) = r, from
 * r = (K(ti) + K(to)) / sqrt(8 pi) >= 0.  For r <= BF_HE_R_SER = 0.01 the
 * series x = r (1 - t/2 + 5 t^2/8 - 49 t^3/48), t = r^2 (of y = e^(-t y^2 / 2),
 * y = x / r; the next term is below 2 t^4 < 2e-16), within 3.2e-16 of the
 * root (against a long double Newton; tests/test_he.c, newton_x).  Above,
 * Newton on ln x + x^2/2 - ln r (no overflow for any r): for r up to
 * BF_HE_R_FIT = 2 from r P / Q (bf_he_x_start_pq), within 5.7e-11 of the root, so that
 * one step ends it (the rough samples' r are mostly below 1, and from x = r
 * a vector would take the four steps of its slowest lane: a rough full pass
 * 5% faster this way), above from max(sqrt(2 ln r), 0.75) (monotone on either side of
 * x = 1).  A lane stops after a step |dx| <= 1e-8 x: with
 * F = ln x + x^2/2 - ln r the relative error after a step is
 * (x F'' / 2F') (dx / x)^2 and |x F'' / 2F'| = |x^2 - 1| / (2 (1 + x^2))
 * < 1/2, so x is then within 5e-17 of the root (and rounding: 1.3e-15
 * measured).  A vector whose every r is at most 0.01 takes no logarithm; one
 * whose every r is at most BF_HE_R_FIT takes that one step with one
 * logarithm and one division (bf_he_newton_y1: a rough full pass 3-4% faster
 * than with the step's two logarithms and three divisions). */
#define BF_HE_R_SER 0.01
#define BF_HE_R_FIT 2.0

/* x's start for r in [0, BF_HE_R_FIT]: r P(t) / Q(t), t = r^2, a rational
 * function of degree (6, 6) fitted to x / r over t in [0, 4] (x^2 = W(r^2),
 * Lambert's W), its relative error below 5.7e-11 there (tests/test_he.c,
 * newton_x); every coefficient positive, so P and Q take no cancellation. */
BF_FN void bf_he_x_start_pq(BF_REAL t, BF_REAL *p, BF_REAL *q)
{
    *p = 0.99999999994255218 + t * (4.9252967663259284 + t * (8.0826456807894687
         + t * (5.239735759256245 + t * (1.2652491419240943 + t * (0.089074894653451975
         + t * 0.00082898072995929439)))));
    *q = 1.0 + t * (5.4252967485420305 + t * (10.170294935704433 + t * (7.9548888863217604
         + t * (2.5263287435881709 + t * (0.2745068180691122 + t * 0.0064419946217939561)))));
}

/* The one Newton step from that start that ends the root for every r in
 * [0, BF_HE_R_FIT] (below), with one division and one logarithm: with
 * y0 = P / Q = x0 / r, F = ln y0 + x0^2 / 2 (= ln x0 + x0^2 / 2 - ln r) and
 * x0 / (1 + x0^2) = r P Q^2 / (Q m), m = Q^2 + t P^2, both quotients come
 * from 1 / (Q m).  Returns x / r, floored at y0 / 2 as the loop's step is. */
BF_FN BF_REAL bf_he_newton_y1(BF_REAL r, BF_REAL t)
{
    BF_REAL p, q;
    bf_he_x_start_pq(t, &p, &q);
    BF_REAL q2 = q * q, m = q2 + t * (p * p);
    BF_REAL inv = 1.0 / (q * m);
    BF_REAL y0 = (p * m) * inv, x0 = r * y0;
    BF_REAL f = log(y0) + 0.5 * (x0 * x0);
    return fmax(y0 - f * ((p * q2) * inv), 0.5 * y0);
}

/* x, and x / max(r, BF_TINY) into *q: the series' y where r <= BF_HE_R_SER
 * (no division for a vector that takes no Newton step). */
BF_FN BF_REAL bf_he_newton_xq(BF_REAL r, BF_REAL *q)
{
    BF_REAL rs = fmax(r, BF_TINY), t = rs * rs;
    BF_REAL ys = 1.0 + t * (-0.5 + t * (0.625 + t * (-49.0 / 48.0)));
    BF_REAL xs = rs * ys;
    *q = ys;
    if (!BF_ANY(rs > BF_HE_R_SER))
        return xs;
    /* each lane's x whatever lanes share its vector: the one step up to
     * BF_HE_R_FIT, the loop above it */
    BF_REAL rf = fmin(rs, BF_R(BF_HE_R_FIT));
    BF_REAL y = bf_he_newton_y1(rf, rf * rf);
    *q = BF_SEL(ys, y, rs > BF_HE_R_SER);
    BF_REAL x = BF_SEL(xs, rs * y, rs > BF_HE_R_SER);
    if (!BF_ANY(rs > BF_HE_R_FIT))
        return x;
    BF_REAL lr = log(rs);
    BF_REAL xn = fmax(sqrt(2.0 * fmax(lr, 0.0)), BF_R(0.75));
    BF_REAL act = BF_SEL(BF_R(0.0), BF_R(1.0), rs > BF_HE_R_FIT);
    for (int it = 0; it < 60 && BF_ANY(act > 0.0); it++) {
        BF_REAL dx = (log(xn) + 0.5 * xn * xn - lr) * xn / (1.0 + xn * xn);
        xn = BF_SEL(xn, fmax(xn - dx, 0.5 * xn), act > 0.0);
        act = BF_SEL(act, BF_R(0.0), fabs(dx) <= 1e-8 * xn);
    }
    *q = BF_SEL(*q, xn / rs, rs > BF_HE_R_FIT);
    return BF_SEL(x, xn, rs > BF_HE_R_FIT);
}

#endif /* BF_HE_SURFACE_H */
