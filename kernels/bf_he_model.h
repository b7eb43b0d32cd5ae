/* SPDX-License-Identifier: MIT */
/*
 * bf_he_model.h -- the He et al. 1991 directional-diffuse lobe ("A
 * Comprehensive Physical Model for Light Reflection", SIGGRAPH 1991) as Ngan
 * et al. fitted it: p0 = tau (autocorrelation length, um), p1 = sigma0 (rms
 * roughness, um), p2 = n (real refractive index), K per channel at
 * wavelengths lam[0..2] (um).  One function a term, in the paper's order,
 * each citing its equation (docs/he-model.md lists them).  brdffit_eval and
 * the renders evaluate He here; a data pass computes the same K with the
 * machinery of bf_he_pass.h, tested against this file.
 *
 * With wi toward the light, wo toward the viewer, N = z, v = wi + wo:
 *
 *   K = F G S D / (pi cos ti cos to)                       rho_bd,dd
 *
 * Cosines are floored at BF_HE_COS_MIN = 1e-100, so that every term stays
 * finite for any direction strictly above the horizon.  erfc is Cody's
 * (bf_he_num.h), taken as 0 for u >= 6 with e^(-u^2) (bf_he_erfc2).
 */
#ifndef BF_HE_MODEL_H
#define BF_HE_MODEL_H

#ifndef __OPENCL_VERSION__
#include "bf_he_num.h"
#endif

/* The directions as the terms use them: cos and sin of ti and to and
 * v = wi + wo as |v_xy|^2 and v_z (with the floored cosines). */
typedef struct bf_he_angles {
    BF_REAL ci, si, co, so, vxy2, vz;
} bf_he_angles;

BF_FN void bf_he_angles_make(const bf_geom *g, bf_he_angles *d)
{
    BF_REAL vx = g->ix + g->ox, vy = g->iy + g->oy;
    d->ci = fmax(g->iz, BF_HE_COS_MIN);
    d->co = fmax(g->oz, BF_HE_COS_MIN);
    d->si = sqrt(g->ix * g->ix + g->iy * g->iy);
    d->so = sqrt(g->ox * g->ox + g->oy * g->oy);
    d->vxy2 = vx * vx + vy * vy;
    d->vz = d->ci + d->co;
}

/* ---- F: Fresnel reflectance (the paper's appendix), unpolarised, real
 * index n >= 1, at c = cos theta_b = |v| / 2 in [BF_HE_COS_MIN, 1]:
 *   F = (1/2) ((g' - c) / (g' + c))^2 (1 + ((c (g' + c) - 1) / (c (g' - c) + 1))^2),
 *   g'^2 = n^2 + c^2 - 1.
 * Written with e = n^2 - 1 and A = g' + c: g' - c = e / A (no cancellation
 * for n ~ 1), q = (g' - c) / A = e / A^2, r = (c A - 1) A / (c e + A); both
 * denominators come from one division (A^2 (c e + A) >= 8e-300: A >= 2c).
 * Not contracted to fused multiply-adds in the kernel, so that it rounds as
 * the host's C does: a full pass's neighbour in n takes F again at n + dn,
 * and its difference quotient multiplies F's rounding by 1 / h ~ 1e7. */
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

/* c = cos theta_b = |v| / 2, the angle F is taken at. */
BF_FN BF_REAL bf_he_cos_b(const bf_he_angles *d)
{
    return fmin(fmax(0.5 * sqrt(d->vxy2 + d->vz * d->vz), BF_HE_COS_MIN), 1.0);
}

/* ---- S: shadowing (Eqs. 24, 25).  u = tau cot(theta) / (2 sigma0) of one
 * direction from its cosine and sine, kept in [1e-300, 1e10] (1e10 at the
 * normal, where S = 1; the sine floored at 1e-150). */
BF_FN BF_REAL bf_he_u(BF_REAL c, BF_REAL s, double tau, double sigma0)
{
    BF_REAL u = (tau / (2.0 * sigma0)) * c / fmax(s, BF_R(1e-150));
    return fmin(fmax(u, BF_R(1e-300)), BF_R(1e10));
}

/* What S and sigma take of one direction: u, erfc(u) and e^(-u^2)
 * (bf_he_erfc2: both 0 for u >= 6). */
typedef struct bf_he_side {
    BF_REAL u, ec, ex;
} bf_he_side;

BF_FN bf_he_side bf_he_side_make(BF_REAL c, BF_REAL s, double tau, double sigma0)
{
    bf_he_side d;
    d.u = bf_he_u(c, s, tau, sigma0);
    bf_he_erfc2(d.u, &d.ec, &d.ex);
    return d;
}

/* Eq. 25: Lambda(u) = (e^(-u^2) / (sqrt(pi) u) - erfc(u)) / 2 >= 0 (the paper
 * prints it without e^(-u^2); its errata and independent implementations put
 * it back: docs/he-model.md). */
BF_FN BF_REAL bf_he_lambda(bf_he_side d)
{
    return 0.5 * (d.ex / (BF_SQRT_PI * d.u) - d.ec);
}

/* Eq. 24: S(theta) = (1 - erfc(u) / 2) / (1 + Lambda(u)) of one direction. */
BF_FN BF_REAL bf_he_shadow(bf_he_side d)
{
    return (1.0 - 0.5 * d.ec) / (1.0 + bf_he_lambda(d));
}

/* Eq. 24: S = S(theta_i) S(theta_o) of a direction pair. */
BF_FN BF_REAL bf_he_shadowing(const bf_geom *g, double tau, double sigma0)
{
    bf_he_angles d;
    bf_he_angles_make(g, &d);
    return bf_he_shadow(bf_he_side_make(d.ci, d.si, tau, sigma0))
         * bf_he_shadow(bf_he_side_make(d.co, d.so, tau, sigma0));
}

/* ---- G: the geometrical factor (Eq. 76), (v.v / v_z)^2.  He's vector form
 * (v.v / v_z)^2 [(s_r.k_i)^2 + (p_r.k_i)^2] [(s_i.k_r)^2 + (p_i.k_r)^2] / |k_r x k_i|^4
 * is exactly this: (s_r, p_r, k_r) is an orthonormal basis, so each bracket is
 * |k_r x k_i|^2.  No 0/0 at wi = wo (G = 4 / cos^2 theta) nor at the normal. */
BF_FN BF_REAL bf_he_geometry_v(BF_REAL vxy2, BF_REAL vz)
{
    BF_REAL q = (vxy2 + vz * vz) / vz;
    return q * q;
}

BF_FN BF_REAL bf_he_geometry(const bf_geom *g)
{
    bf_he_angles d;
    bf_he_angles_make(g, &d);
    return bf_he_geometry_v(d.vxy2, d.vz);
}

/* ---- D: the distribution (Eq. 78),
 *   D = (pi tau / (2 lam))^2 sum_{m>=1} g^m e^-g / (m! m) e^(-a/m),
 * the series for g <= 18, Beckmann's rough-surface limit
 * (pi tau / (2 lam))^2 e^(-a/g) / g for g >= 19 (as He et al. use it), and
 * linear in g between (the blend is part of the model as fitted). */

/* The sum of Eq. 78 for g < 19 (0 in lanes with g >= 19), term by term from
 * m = 1 (ln(m m!) from bf_he_lkk, at most BF_HE_MMAX = 400 terms: for g < 19
 * every later term is below e^-840 of the sum).  The terms are log-concave in
 * m, so once one is smaller than the one before, all after it are smaller
 * still; the sum stops there at the first term below 1e-12 of the sum. */
BF_FN BF_REAL bf_he_D_series(BF_REAL g, BF_REAL a)
{
    BF_REAL lng = log(fmax(g, BF_TINY)), sum = BF_R(0.0), eprev = BF_R(-1e308);
    BF_REAL act = BF_SEL(BF_R(0.0), BF_R(1.0), g < BF_HE_G_HI);
    for (int m = 1; m <= BF_HE_MMAX && BF_ANY(act > 0.0); m++) {
        const double dm = (double)m;
        BF_REAL e = dm * lng - g - bf_he_lkk[m] - a / dm; /* ln of term m */
        BF_REAL t = bf_exp_wide(e);
        sum = BF_SEL(sum, sum + t, act > 0.0);
        act = BF_SEL(act, BF_R(0.0), (e < eprev) && (t <= 1e-12 * sum));
        eprev = e;
    }
    return sum;
}

/* The rough-surface limit e^(-a/g) / g of the sum (g >= 18 where used). */
BF_FN BF_REAL bf_he_D_limit(BF_REAL g, BF_REAL a)
{
    return exp(-a / g) / g;
}

/* The blend's weight t of the limit: 0 for g <= 18, 1 for g >= 19, linear
 * between; and (1 - t) series + t limit, each side alone at its end (so that
 * a side's value is never read where it is not needed). */
BF_FN BF_REAL bf_he_blend_t(BF_REAL g)
{
    return fmin(fmax(g - BF_HE_G_LO, 0.0), 1.0);
}

BF_FN BF_REAL bf_he_blend(BF_REAL t, BF_REAL ser, BF_REAL lim)
{
    return BF_SEL(BF_SEL((1.0 - t) * ser + t * lim, ser, t <= 0.0), lim, t >= 1.0);
}

/* Eq. 78: D(g, a) of one wavelength lam (um) for tau (um), g > 0, a >= 0. */
BF_FN BF_REAL bf_he_D(BF_REAL g, BF_REAL a, double tau, double lam)
{
    const double k = BF_PI * tau / (2.0 * lam);
    BF_REAL gs = fmax(g, BF_TINY), as = fmax(a, 0.0);
    BF_REAL t = bf_he_blend_t(gs), ser = BF_R(0.0), lim = BF_R(0.0);
    if (BF_ANY(t < 1.0))
        ser = bf_he_D_series(gs, as);
    if (BF_ANY(t > 0.0))
        lim = bf_he_D_limit(fmax(gs, BF_R(BF_HE_G_LO)), as);
    return (k * k) * bf_he_blend(t, ser, lim);
}

/* Eq. 79: g = ((2 pi sigma / lam)(cos ti + cos to))^2. */
BF_FN BF_REAL bf_he_g(BF_REAL sigma, double lam, BF_REAL vz)
{
    BF_REAL x = (2.0 * BF_PI / lam) * (sigma * vz);
    return x * x;
}

/* ---- sigma: the effective roughness (Eq. 80), sigma0 / sqrt(1 + x^2)
 * with x e^(x^2/2) = (K(ti) + K(to)) / sqrt(8 pi). */

/* Eqs. 82-83: K(theta) = tan theta erfc(u) of one direction. */
BF_FN BF_REAL bf_he_K_theta(BF_REAL c, BF_REAL s, bf_he_side d)
{
    return (s / c) * d.ec;
}

/* The root x >= 0 of x e^(x^2/2) = r >= 0 (r floored at BF_TINY: x = r
 * where r is that small): Newton on ln x + x^2/2 - ln r, from
 * min(r, max(sqrt(2 ln r), 0.75)), a step floored at half of x, until a
 * step is below 1e-8 x (x is then within 5e-17 of the root: the step's
 * relative error is |x^2 - 1| / (2 (1 + x^2)) (dx/x)^2). */
BF_FN BF_REAL bf_he_root_x(BF_REAL r)
{
    BF_REAL rs = fmax(r, BF_R(BF_TINY)), lr = log(rs);
    BF_REAL x = fmin(rs, fmax(sqrt(2.0 * fmax(lr, 0.0)), BF_R(0.75)));
    BF_REAL act = BF_R(1.0);
    for (int it = 0; it < 100 && BF_ANY(act > 0.0); it++) {
        BF_REAL dx = (log(x) + 0.5 * (x * x) - lr) * x / (1.0 + x * x);
        x = BF_SEL(x, fmax(x - dx, 0.5 * x), act > 0.0);
        act = BF_SEL(act, BF_R(0.0), fabs(dx) <= 1e-8 * x);
    }
    return x;
}

/* Eq. 80 from the two directions' K(theta) (Eqs. 82-83). */
BF_FN BF_REAL bf_he_sigma_of(BF_REAL Ki, BF_REAL Ko, double sigma0)
{
    BF_REAL x = bf_he_root_x((Ki + Ko) / sqrt(8.0 * BF_PI));
    return sigma0 / sqrt(1.0 + x * x);
}

BF_FN BF_REAL bf_he_sigma(const bf_geom *g, double tau, double sigma0)
{
    bf_he_angles d;
    bf_he_angles_make(g, &d);
    return bf_he_sigma_of(bf_he_K_theta(d.ci, d.si, bf_he_side_make(d.ci, d.si, tau, sigma0)),
                          bf_he_K_theta(d.co, d.so, bf_he_side_make(d.co, d.so, tau, sigma0)),
                          sigma0);
}

/* Eq. 84: a = pi^2 (tau / lam)^2 |v_xy|^2, v_xy the tangential part of v. */
BF_FN BF_REAL bf_he_a(double tau, double lam, BF_REAL vxy2)
{
    const double k = BF_PI * tau / lam;
    return (k * k) * vxy2;
}

/* ---- K = F G S D / (pi cos ti cos to) (rho_bd,dd) per channel into
 * K[0..2] at wavelengths lam[0..2], S / cos taken per direction (both stay
 * finite at grazing, where S(theta) ~ sqrt(pi) u). */
BF_FN void bf_he(const bf_geom *g, double tau, double sigma0, double n, const double *lam,
                 BF_REAL *K)
{
    bf_he_angles d;
    bf_he_angles_make(g, &d);
    bf_he_side side_i = bf_he_side_make(d.ci, d.si, tau, sigma0);
    bf_he_side side_o = bf_he_side_make(d.co, d.so, tau, sigma0);
    BF_REAL F = bf_he_fresnel(bf_he_cos_b(&d), n);
    BF_REAL FS = F * (bf_he_shadow(side_i) / d.ci) * (bf_he_shadow(side_o) / d.co);
    BF_REAL G = bf_he_geometry_v(d.vxy2, d.vz);
    BF_REAL sigma = bf_he_sigma_of(bf_he_K_theta(d.ci, d.si, side_i),
                                   bf_he_K_theta(d.co, d.so, side_o), sigma0);
    for (int ch = 0; ch < 3; ch++) {
        BF_REAL D = bf_he_D(bf_he_g(sigma, lam[ch], d.vz), bf_he_a(tau, lam[ch], d.vxy2), tau,
                            lam[ch]);
        K[ch] = FS * (G * D) * (1.0 / BF_PI);
    }
}

/* The He model's entry point (the shape of bf_models.h's bf_lobe_<model>). */
BF_FN void bf_lobe_he(const bf_geom *g, const double *p, const double *lam, BF_REAL *K)
{
    bf_he(g, p[0], p[1], p[2], lam, K);
}

#endif /* BF_HE_MODEL_H */
