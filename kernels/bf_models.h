/* SPDX-License-Identifier: MIT */
/*
 * bf_models.h -- the closed-form BRDF lobes K(wi, wo; p), written once for the
 * C library and the OpenCL kernel (see bf_common.h).
 *
 * Frame: z is the normal; wi (i*) points toward the light, wo (o*) toward the
 * viewer; both unit vectors strictly above the horizon (cos t taken at least
 * BF_COS_FLOOR = 1e-6 by bf_geom_derive).  H = normalize(wi+wo),
 * delta = angle(N, H).  f_c = d_c/pi + s_c K_c, no cosine factor.
 *
 * Each model has one entry point of the same shape,
 *     bf_lobe_<model>(g, p, lam, K):  K[0..2] per channel for lobe parameters
 *     p[0..] (paper units) and wavelengths lam[0..2] (um, chromatic lobes only),
 * bound to its id by BF_MODEL_LOBES at the end of this file.  A renderer may
 * include bf_lobe.h and call bf_geom_derive + bf_lobe(id, ...) or a model's
 * bf_lobe_<model> directly: nothing here allocates or has state.
 */
#ifndef BF_MODELS_H
#define BF_MODELS_H

#ifndef __OPENCL_VERSION__
#include "bf_exp.h"
#endif

/* The geometry of a (wi, wo) pair: computed once per sample of a table. */
typedef struct bf_geom {
    BF_REAL ix, iy, iz;  /* wi, toward the light  */
    BF_REAL ox, oy, oz;  /* wo, toward the viewer */
    BF_REAL nh;          /* N.H = cos delta       */
    BF_REAL vh;          /* V.H = L.H = cos theta_d */
} bf_geom;

/* The floor of cos ti and cos to: a direction closer to the horizon is
 * evaluated with cos t = BF_COS_FLOOR (5.7e-5 deg above it; the direction's
 * length then differs from 1 by less than 1e-12), so that every lobe's
 * quotients stay finite (below it Ward, Ward-Duer, Cook-Torrance,
 * Ashikhmin-Shirley and GGX would take 0/0 or x/0 at cosines of 1e-100 and less).
 * No sample of a MERL table comes near it (the bins' centres lie within
 * 89.5 deg). */
#define BF_COS_FLOOR 1e-6

/* Fill the derived fields of g from its two unit directions (their z
 * floored at BF_COS_FLOOR). */
BF_FN void bf_geom_derive(bf_geom *g)
{
    g->iz = fmax(g->iz, BF_COS_FLOOR);
    g->oz = fmax(g->oz, BF_COS_FLOOR);
    BF_REAL c = g->ix * g->ox + g->iy * g->oy + g->iz * g->oz;   /* wi.wo */
    /* |wi + wo| = sqrt(2 + 2 wi.wo); wi = -wo cannot happen above the horizon */
    BF_REAL len = sqrt(fmax(2.0 + 2.0 * c, BF_TINY));
    g->nh = fmin(fmax((g->iz + g->oz) / len, BF_TINY), 1.0);
    g->vh = fmin(sqrt(fmax(0.5 + 0.5 * c, 0.0)), 1.0);
}

/* tan^2(delta) from cos(delta), finite for cos delta in (0, 1]. */
BF_FN BF_REAL bf_tan2(BF_REAL c)
{
    return fmax(1.0 - c * c, 0.0) / (c * c);
}

/* Schlick's Fresnel term F0 + (1 - F0)(1 - c)^5, without pow. */
BF_FN BF_REAL bf_schlick(double f0, BF_REAL c)
{
    BF_REAL u = 1.0 - c, u2 = u * u;
    return f0 + (1.0 - f0) * (u2 * u2 * u);
}

/* ln x as bf_powu takes it (x floored at BF_TINY): also d ln x^n / d n. */
BF_FN BF_REAL bf_powu_log(BF_REAL x)
{
    return log(fmax(x, BF_TINY));
}

/* bf_powu from lx = bf_powu_log(x), for a lobe that needs lx again. */
BF_FN BF_REAL bf_powu_l(BF_REAL x, BF_REAL lx, double n)
{
    return BF_SEL(bf_exp_wide(n * lx), BF_R(0.0), x <= 0.0);
}

/* x^n for x >= 0 (at most 1 + rounding) and real n > 0: e^(n log x) by
 * bf_exp_wide (kernels/bf_exp.h: Lafortune's full pass 14% faster at a sharp
 * lobe than with the OpenCL exp), 0 where x <= 0.  Not clamped at 1: the
 * reference values are not either. */
BF_FN BF_REAL bf_powu(BF_REAL x, double n)
{
    return bf_powu_l(x, bf_powu_log(x), n);
}

/* The partials of the lobes, for a data pass's derivatives (BF_FD_GRAD and
 * BF_FD_SCHLICK in bf_lobe.h): K = bf_<model>_vdk(g, p, dK) is the lobe's
 * value at p, bit for bit what bf_<model> gives (the same operations), and
 * sets dK[i] = dK / dp_i for its parameters p[i]; r = bf_<model>_rest_vdk(g,
 * p1, &dr) the same for a Schlick lobe's rest (below) and its partial in p1.
 * Where K = 0 (underflowed, or cut off) the partials are 0.  The helpers: */

/* d ln K / d alpha of a lobe exp(-tan^2 delta / alpha^2) / alpha^2 times
 * what does not depend on alpha (Ward, Ward-Duer, Cook-Torrance's m), from
 * t = tan^2 delta (bf_beckmann_dlog_t) or from g. */
BF_FN BF_REAL bf_beckmann_dlog_t(BF_REAL t, double alpha)
{
    return (2.0 * t / (alpha * alpha) - 2.0) / alpha;
}

BF_FN BF_REAL bf_beckmann_dlog(const bf_geom *g, double alpha)
{
    return bf_beckmann_dlog_t(bf_tan2(g->nh), alpha);
}

/* K dlog where K > 0, else 0: a lobe that has underflowed (or is cut off)
 * has partials 0, and its dlog may be infinite there. */
BF_FN BF_REAL bf_dk_where(BF_REAL K, BF_REAL dlog)
{
    return BF_SEL(K * dlog, BF_R(0.0), K <= 0.0);
}

/* Ward [alpha] */
BF_FN BF_REAL bf_ward(const bf_geom *g, double alpha)
{
    double a2 = alpha * alpha;
    return exp(-bf_tan2(g->nh) / a2) / ((4.0 * BF_PI * a2) * sqrt(g->iz * g->oz));
}

/* Ward-Duer [alpha] */
BF_FN BF_REAL bf_ward_duer(const bf_geom *g, double alpha)
{
    double a2 = alpha * alpha;
    return exp(-bf_tan2(g->nh) / a2) / ((4.0 * BF_PI * a2) * (g->iz * g->oz));
}

BF_FN BF_REAL bf_ward_vdk(const bf_geom *g, const double *p, BF_REAL *dK)
{
    BF_REAL K = bf_ward(g, p[0]);
    dK[0] = bf_dk_where(K, bf_beckmann_dlog(g, p[0]));
    return K;
}

BF_FN BF_REAL bf_ward_duer_vdk(const bf_geom *g, const double *p, BF_REAL *dK)
{
    BF_REAL K = bf_ward_duer(g, p[0]);
    dK[0] = bf_dk_where(K, bf_beckmann_dlog(g, p[0]));
    return K;
}

/* Blinn-Phong [n] */
BF_FN BF_REAL bf_blinn_phong_l(const bf_geom *g, double n, BF_REAL lx)
{
    return ((n + 2.0) / (2.0 * BF_PI)) * bf_powu_l(g->nh, lx, n);
}

BF_FN BF_REAL bf_blinn_phong(const bf_geom *g, double n)
{
    return bf_blinn_phong_l(g, n, bf_powu_log(g->nh));
}

BF_FN BF_REAL bf_blinn_phong_vdk(const bf_geom *g, const double *p, BF_REAL *dK)
{
    BF_REAL lx = bf_powu_log(g->nh);
    BF_REAL K = bf_blinn_phong_l(g, p[0], lx);
    dK[0] = bf_dk_where(K, 1.0 / (p[0] + 2.0) + lx);
    return K;
}

/* Lafortune [Cxy, Cz, n]: the base is normalised by max(|Cxy|, |Cz|) before
 * the power, so that large n cannot underflow the normalisation.  The
 * weights are divided by it once a call, not each sample's base and
 * partials (three vector divisions less a sample: a full pass ~7% shorter,
 * docs/performance.md). */
BF_FN BF_REAL bf_lafortune_x(const bf_geom *g, double cxy, double cz)
{
    const double rm = 1.0 / fmax(fabs(cxy), fabs(cz));
    return (cxy * rm) * (g->ix * g->ox + g->iy * g->oy) + (cz * rm) * (g->iz * g->oz);
}

BF_FN BF_REAL bf_lafortune(const bf_geom *g, double cxy, double cz, double n)
{
    BF_REAL x = bf_lafortune_x(g, cxy, cz);
    return ((n + 2.0) / (2.0 * BF_PI)) * bf_powu(x, n);
}

/* Lafortune's partials.  With m = max(|Cxy|, |Cz|) (taken from Cxy on a tie,
 * as one-sided as a forward difference is) and w = wi.wo's tangential or
 * normal part, d x / d C = (w - [m is |C|] x sgn C) / m and
 * d K / d C = K n (d x / d C) / x, x floored at BF_LAF_X_MIN: below it the
 * lobe is at most (n + 2) / (2 pi) 1e-12^n, and for n < 1 its partial would
 * grow without bound (K = 0 where x <= 0: its partials 0).  Always inlined,
 * as PoCL inlines the other lobes' partials of itself (bf_accumulate). */
#define BF_LAF_X_MIN 1e-12
BF_FN_INLINE BF_REAL bf_lafortune_vdk(const bf_geom *g, const double *p, BF_REAL *dK)
{
    const double cxy = p[0], cz = p[1], n = p[2];
    const double rm = 1.0 / fmax(fabs(cxy), fabs(cz));
    const double sxy = fabs(cxy) >= fabs(cz) ? copysign(1.0, cxy) : 0.0;
    const double sz = fabs(cxy) >= fabs(cz) ? 0.0 : copysign(1.0, cz);
    BF_REAL x = bf_lafortune_x(g, cxy, cz), lx = bf_powu_log(x);
    BF_REAL K = ((n + 2.0) / (2.0 * BF_PI)) * bf_powu_l(x, lx, n);
    BF_REAL kx = K * ((n * rm) / fmax(x, BF_LAF_X_MIN));
    dK[0] = kx * (g->ix * g->ox + g->iy * g->oy - x * sxy);
    dK[1] = kx * (g->iz * g->oz - x * sz);
    dK[2] = bf_dk_where(K, 1.0 / (n + 2.0) + lx);
    return K;
}

/* The lobes whose F0 enters only through Schlick's factor at V.H are
 * written K = F(F0, V.H) R(g, p1), R their _rest: a full data pass takes
 * F0's partial from R and p1's from bf_<model>_rest_vdk (BF_FD_SCHLICK in
 * bf_lobe.h). */

/* Cook-Torrance [F0, m], with the constant 1/(4 pi m^2) of the published fits:
 * R = G D / (cos ti cos to), G = min(1, 2 N.H min(cos ti, cos to) / V.H),
 * D = e^(-tan^2 delta / m^2) / (4 pi m^2 cos^4 delta).  Written with one
 * division a sample: 1 / cos^2 delta (for tan^2 delta) and the rest's
 * denominator both from 1 / (cos^2 delta V.H cos ti cos to) (written with
 * five, a full pass takes ~30% longer: docs/performance.md).
 * *t gets tan^2 delta, for the partial. */
BF_FN BF_REAL bf_cook_torrance_rest_t(const bf_geom *g, double m, BF_REAL *t)
{
    const double m2 = m * m;
    BF_REAL nh = g->nh, vh = g->vh, nh2 = nh * nh;
    BF_REAL den = vh * (g->iz * g->oz);
    BF_REAL inv = 1.0 / (nh2 * den);
    BF_REAL inh2 = den * inv; /* 1 / cos^2 delta */
    *t = fmax(1.0 - nh2, 0.0) * inh2;
    BF_REAL ggv = fmin(2.0 * nh * fmin(g->oz, g->iz), vh); /* G V.H */
    return (ggv * exp(-*t / m2)) * ((inv * inh2) * (1.0 / (4.0 * BF_PI * m2)));
}

BF_FN BF_REAL bf_cook_torrance_rest(const bf_geom *g, double m)
{
    BF_REAL t;
    return bf_cook_torrance_rest_t(g, m, &t);
}

BF_FN BF_REAL bf_cook_torrance_rest_vdk(const bf_geom *g, double m, BF_REAL *dr)
{
    BF_REAL t;
    BF_REAL r = bf_cook_torrance_rest_t(g, m, &t);
    *dr = bf_dk_where(r, bf_beckmann_dlog_t(t, m));
    return r;
}

BF_FN BF_REAL bf_cook_torrance(const bf_geom *g, double f0, double m)
{
    return bf_schlick(f0, g->vh) * bf_cook_torrance_rest(g, m);
}

/* Ashikhmin-Shirley [F0, n] */
BF_FN BF_REAL bf_ashikhmin_shirley_rest_l(const bf_geom *g, double n, BF_REAL lx)
{
    return ((n + 1.0) / (8.0 * BF_PI)) * bf_powu_l(g->nh, lx, n) / (g->vh * fmax(g->iz, g->oz));
}

BF_FN BF_REAL bf_ashikhmin_shirley_rest(const bf_geom *g, double n)
{
    return bf_ashikhmin_shirley_rest_l(g, n, bf_powu_log(g->nh));
}

BF_FN BF_REAL bf_ashikhmin_shirley_rest_vdk(const bf_geom *g, double n, BF_REAL *dr)
{
    BF_REAL lx = bf_powu_log(g->nh);
    BF_REAL r = bf_ashikhmin_shirley_rest_l(g, n, lx);
    *dr = bf_dk_where(r, 1.0 / (n + 1.0) + lx);
    return r;
}

BF_FN BF_REAL bf_ashikhmin_shirley(const bf_geom *g, double f0, double n)
{
    return bf_schlick(f0, g->vh) * bf_ashikhmin_shirley_rest(g, n);
}

/* GGX [F0, alpha], as pbrt-v4 evaluates it: K = D G2 F / (4 cos ti cos to),
 * D the Trowbridge-Reitz distribution 1 / (pi a^2 cos^4 th (1 + tan^2 th / a^2)^2),
 * G2 the height-correlated Smith term 1 / (1 + L(wi) + L(wo)) with
 * L(w) = (sqrt(1 + a^2 tan^2 theta) - 1) / 2, F Schlick's at wo.h.  Written
 * without 1 - cos^2 and without dividing by the cosines: with H = wi + wo
 * (not normalised) D = a^2 |H|^4 / (pi (a^2 Hz^2 + Hx^2 + Hy^2)^2), and with
 * q(w) = sqrt(z^2 + a^2 (x^2 + y^2)) = z (1 + 2 L(w)),
 * G2 / (4 cos ti cos to) = 1 / (2 (q(wi) oz + q(wo) iz)).  With deriv, also
 * *dr = d R / d alpha = R 2 alpha d ln R / d a^2, where
 * d ln R / d a^2 = 1 / a^2 - 2 Hz^2 / den - (oz dqi + iz dqo) / (qi oz + qo iz),
 * dq(w) = d q(w) / d a^2 = (x^2 + y^2) / (2 q(w)). */
BF_FN BF_REAL bf_ggx_rest_d(const bf_geom *g, double alpha, int deriv, BF_REAL *dr)
{
    double a2 = alpha * alpha;
    BF_REAL hx = g->ix + g->ox, hy = g->iy + g->oy, hz = g->iz + g->oz;
    BF_REAL s2 = hx * hx + hy * hy, h2 = s2 + hz * hz;
    BF_REAL den = a2 * (hz * hz) + s2;
    BF_REAL d = (a2 * (h2 * h2)) / (BF_PI * (den * den));
    BF_REAL ti2 = g->ix * g->ix + g->iy * g->iy, to2 = g->ox * g->ox + g->oy * g->oy;
    BF_REAL qi = sqrt(g->iz * g->iz + a2 * ti2);
    BF_REAL qo = sqrt(g->oz * g->oz + a2 * to2);
    BF_REAL qq = qi * g->oz + qo * g->iz;
    BF_REAL r = d / (2.0 * qq);
    if (deriv) {
        BF_REAL dq = (g->oz * (ti2 / qi) + g->iz * (to2 / qo)) / (2.0 * qq);
        *dr = bf_dk_where(r, (2.0 * alpha) * (1.0 / a2 - 2.0 * (hz * hz) / den - dq));
    }
    return r;
}

BF_FN BF_REAL bf_ggx_rest(const bf_geom *g, double alpha)
{
    return bf_ggx_rest_d(g, alpha, 0, (BF_REAL *)0);
}

BF_FN BF_REAL bf_ggx_rest_vdk(const bf_geom *g, double alpha, BF_REAL *dr)
{
    return bf_ggx_rest_d(g, alpha, 1, dr);
}

BF_FN BF_REAL bf_ggx(const bf_geom *g, double f0, double alpha)
{
    return bf_schlick(f0, g->vh) * bf_ggx_rest(g, alpha);
}

/* A lobe that is the same for the three channels, as a model entry point. */
#define BF_GREY_LOBE(model, expr)                                                        \
    BF_FN void bf_lobe_##model(const bf_geom *g, const double *p, const double *lam,    \
                               BF_REAL *K)                                               \
    {                                                                                    \
        (void)lam;                                                                       \
        BF_REAL k = (expr);                                                              \
        K[0] = k;                                                                        \
        K[1] = k;                                                                        \
        K[2] = k;                                                                        \
    }

BF_GREY_LOBE(ward, bf_ward(g, p[0]))
BF_GREY_LOBE(ward_duer, bf_ward_duer(g, p[0]))
BF_GREY_LOBE(blinn_phong, bf_blinn_phong(g, p[0]))
BF_GREY_LOBE(lafortune, bf_lafortune(g, p[0], p[1], p[2]))
BF_GREY_LOBE(cook_torrance, bf_cook_torrance(g, p[0], p[1]))
BF_GREY_LOBE(ashikhmin_shirley, bf_ashikhmin_shirley(g, p[0], p[1]))
BF_GREY_LOBE(ggx, bf_ggx(g, p[0], p[1]))

/* The lobe of each model, by id (the values of brdffit_model in brdffit.h;
 * src/lib/registry.c checks that it has an entry for each): X(id, model, fd)
 * with bf_lobe_<model> its entry point and fd how a full data pass takes its
 * derivatives: BF_FD_GRAD (the partials of bf_<model>_vdk), BF_FD_SCHLICK
 * (K = F(p[0], V.H) bf_<model>_rest(g, p[1]): Schlick's partial and
 * bf_<model>_rest_vdk's), BF_FD_POINTWISE (the lobe again at each forward-
 * difference neighbour: a new model's lobe needs no partials to be fitted)
 * or BF_FD_OWN (its own bf_lobe_fd_<model>).  bf_lobe and bf_lobe_fd (bf_lobe.h) switch
 * over this list; the rest of a model's facts are its registry entry. */
#define BF_LOBE_MODELS 8 /* the models of the form d/pi + s K: ids 0 .. 7 */
#define BF_MODEL_LOBES(X)                                                                 \
    X(0, ward, BF_FD_GRAD)                                                               \
    X(1, ward_duer, BF_FD_GRAD)                                                          \
    X(2, blinn_phong, BF_FD_GRAD)                                                        \
    X(3, lafortune, BF_FD_GRAD)                                                          \
    X(4, cook_torrance, BF_FD_SCHLICK)                                                    \
    X(5, ashikhmin_shirley, BF_FD_SCHLICK)                                                \
    X(6, he, BF_FD_OWN)                                                                   \
    X(7, ggx, BF_FD_SCHLICK)

#endif /* BF_MODELS_H */
