/* SPDX-License-Identifier: MIT */
/* bf_he_surface.h -- the He lobe's terms of one direction (pair) at the
 * surface: Fresnel's F, u = tau cot(theta) / (2 sigma0), erfc(u) (Cody's
 * approximation), the shadowing S(u) and its derivative, and the root x of
 * the effective roughness sigma (bf_he.h: the model). */
#ifndef BF_HE_SURFACE_H
#define BF_HE_SURFACE_H

#ifndef __OPENCL_VERSION__
#include "bf_he_const.h"
#endif

/* Fresnel reflectance, unpolarised, real index n >= 1, at c = cos theta_b in
 * [BF_HE_COS_MIN, 1]: F = q^2 (1 + r^2) / 2 with A = g' + c, q = (g' - c) / A
 * = e / A^2 (g' - c = e / A, e = n^2 - 1: no cancellation for n ~ 1) and
 * r = (c A - 1) / (c (g' - c) + 1) = (c A - 1) A / (c e + A).  Both
 * denominators come from one division: A^2 (c e + A) >= 8e-300 (A >= 2c).
 * Not contracted to fused multiply-adds in the kernel, so that it rounds as
 * the host's C does: a full pass's neighbour in n takes F again at n + dn,
 * and its difference quotient multiplies F's rounding by 1 / h ~ 1e7 (with
 * c e + A and c A - 1 fused in the kernel alone, its sums and the C loop's
 * parted by 1.1e-9 relative: tests/test_pass.c). */
BF_FN BF_REAL bf_he_fresnel(BF_REAL c, double n)
{
#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#endif
    double e = (n - 1.0) * (n + 1.0);
    BF_REAL A = sqrt(e + c * c) + c, A2 = A * A;
    BF_REAL B = c * e + A;
    BF_REAL inv = 1.0 / (A2 * B);
    BF_REAL q = (e * B) * inv;
    BF_REAL r = ((c * A - 1.0) * A) * (A2 * inv);
    return 0.5 * (q * q) * (1.0 + r * r);
}

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

/* erfc(u) for u in [0, BF_HE_U_FLAT], given ex = e^(-u^2): W. J. Cody's
 * rational Chebyshev approximations (Math. Comp. 23, 631-637, 1969; the
 * coefficients of netlib's specfun CALERF): 1 - u A(u^2) / B(u^2) on
 * [0, 0.46875], ex C(u) / D(u) on (0.46875, 4], ex (1/sqrt(pi) - z P(z) / Q(z)) / u,
 * z = 1/u^2, above; each piece only when some lane needs it.  Against glibc's
 * erfc over [0, 6] in steps of 1e-6 (tests/test_he.c, erfc_cody): within
 * 2.3e-15 relative up to u = 5 and 4e-15 up to 6 (where erfc < 2e-12: the
 * rounding of u^2 in ex).  It replaced the OpenCL library's erfc, which cost
 * as much as the rest of a rough sample's shadowing. */
BF_HE_CONSTANT double bf_he_cody_a[5] = {
    3.16112374387056560e00, 1.13864154151050156e02, 3.77485237685302021e02,
    3.20937758913846947e03, 1.85777706184603153e-1
};
BF_HE_CONSTANT double bf_he_cody_b[4] = {
    2.36012909523441209e01, 2.44024637934444173e02, 1.28261652607737228e03,
    2.84423683343917062e03
};
BF_HE_CONSTANT double bf_he_cody_c[9] = {
    5.64188496988670089e-1, 8.88314979438837594e00, 6.61191906371416295e01,
    2.98635138197400131e02, 8.81952221241769090e02, 1.71204761263407058e03,
    2.05107837782607147e03, 1.23033935479799725e03, 2.15311535474403846e-8
};
BF_HE_CONSTANT double bf_he_cody_d[8] = {
    1.57449261107098347e01, 1.17693950891312499e02, 5.37181101862009858e02,
    1.62138957456669019e03, 3.29079923573345963e03, 4.36261909014324716e03,
    3.43936767414372164e03, 1.23033935480374942e03
};
BF_HE_CONSTANT double bf_he_cody_p[6] = {
    3.05326634961232344e-1, 3.60344899949804439e-1, 1.25781726111229246e-1,
    1.60837851487422766e-2, 6.58749161529837803e-4, 1.63153871373020978e-2
};
BF_HE_CONSTANT double bf_he_cody_q[5] = {
    2.56852019228982242e00, 1.87295284992346725e00, 5.27905102951428412e-1,
    6.05183413124413191e-2, 2.33520497626869185e-3
};

BF_FN BF_REAL bf_he_erfc_cody(BF_REAL u, BF_REAL ex)
{
    /* each piece's quotient num / den, then one division for the pieces
     * the lanes need (at He's typical start most vectors of grazing lanes
     * take the two upper ones): each lane's value that of its piece alone,
     * to the bit */
    BF_REAL num = BF_R(0.0), den = BF_R(1.0);
    if (BF_ANY(u <= 0.46875)) {
        BF_REAL z = u * u, n = bf_he_cody_a[4] * z, d = z;
        for (int i = 0; i < 3; i++) {
            n = (n + bf_he_cody_a[i]) * z;
            d = (d + bf_he_cody_b[i]) * z;
        }
        num = BF_SEL(num, u * (n + bf_he_cody_a[3]), u <= 0.46875);
        den = BF_SEL(den, d + bf_he_cody_b[3], u <= 0.46875);
    }
    if (BF_ANY((u > 0.46875) && (u <= 4.0))) {
        BF_REAL n = bf_he_cody_c[8] * u, d = u;
        for (int i = 0; i < 7; i++) {
            n = (n + bf_he_cody_c[i]) * u;
            d = (d + bf_he_cody_d[i]) * u;
        }
        num = BF_SEL(num, ex * (n + bf_he_cody_c[7]), (u > 0.46875) && (u <= 4.0));
        den = BF_SEL(den, d + bf_he_cody_d[7], (u > 0.46875) && (u <= 4.0));
    }
    if (BF_ANY(u > 4.0)) {
        /* z P(z) / Q(z) with z = 1 / w, w = u^2, is P~(w) / (w Q~(w)) with
         * the coefficients reversed (P~(w) = w^5 P(1 / w), w <= 36 here):
         * one quotient for the piece instead of three */
        BF_REAL uc = fmax(u, BF_R(4.0)), w = uc * uc;
        BF_REAL n = bf_he_cody_p[4] * w, d = bf_he_cody_q[4] * w;
        for (int i = 3; i >= 0; i--) {
            n = (n + bf_he_cody_p[i]) * w;
            d = (d + bf_he_cody_q[i]) * w;
        }
        n += bf_he_cody_p[5];
        d += 1.0;
        BF_REAL wd = w * d;
        num = BF_SEL(num, ex * (0.56418958354775628695 * wd - n), u > 4.0);
        den = BF_SEL(den, wd * uc, u > 4.0);
    }
    BF_REAL r = num / den;
    return BF_SEL(r, 1.0 - r, u <= 0.46875);
}

/* erfc(u) and e^(-u^2) of the shadowing, for u in [1e-300, 1e10], as 0 for
 * u >= BF_HE_U_FLAT = 6 (erfc(6) = 2.2e-17, e^-36 = 2.3e-16): there S(t)
 * rounds to 1 and sigma's r gains less than 1e-14 (sigma: relative 1e-14),
 * so the rule changes no value measurably, and a vector with every u >= 6 (a
 * smooth surface away from grazing) skips both. */
BF_FN void bf_he_erfc2(BF_REAL u, BF_REAL *ec, BF_REAL *ex)
{
    *ec = BF_R(0.0);
    *ex = BF_R(0.0);
    if (BF_ANY(u < BF_HE_U_FLAT)) {
        BF_REAL flat = BF_SEL(BF_R(0.0), BF_R(1.0), u >= BF_HE_U_FLAT);
        BF_REAL us = fmin(u, BF_R(BF_HE_U_FLAT));
        BF_REAL e = exp(-us * us);
        *ec = BF_SEL(bf_he_erfc_cody(us, e), BF_R(0.0), flat > 0.0);
        *ex = BF_SEL(e, BF_R(0.0), flat > 0.0);
    }
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
