/* SPDX-License-Identifier: MIT */
/*
 * bf_models.h -- the closed-form BRDF lobes K(wi, wo; p), written once for the
 * C library and the OpenCL kernel (see bf_common.h).
 *
 * Frame: z is the normal; wi (i*) points toward the light, wo (o*) toward the
 * viewer; both unit vectors strictly above the horizon.  H = normalize(wi+wo),
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
#include "bf_common.h"
#endif

/* The geometry of a (wi, wo) pair: computed once per sample of a table. */
typedef struct bf_geom {
    BF_REAL ix, iy, iz;  /* wi, toward the light  */
    BF_REAL ox, oy, oz;  /* wo, toward the viewer */
    BF_REAL nh;          /* N.H = cos delta       */
    BF_REAL vh;          /* V.H = L.H = cos theta_d */
} bf_geom;

/* Fill the derived fields of g from its two unit directions. */
BF_FN void bf_geom_derive(bf_geom *g)
{
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

/* x^n for x >= 0 (at most 1 + rounding) and real n > 0: exp(n log x), 0 where
 * x <= 0.  Not clamped at 1: the reference values are not either. */
BF_FN BF_REAL bf_powu(BF_REAL x, double n)
{
    BF_REAL xs = fmax(x, BF_TINY);
    return BF_SEL(exp(n * log(xs)), BF_R(0.0), x <= 0.0);
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

/* Blinn-Phong [n] */
BF_FN BF_REAL bf_blinn_phong(const bf_geom *g, double n)
{
    return ((n + 2.0) / (2.0 * BF_PI)) * bf_powu(g->nh, n);
}

/* Lafortune [Cxy, Cz, n]: the base is normalised by max(|Cxy|, |Cz|) before
 * the power, so that large n cannot underflow the normalisation. */
BF_FN BF_REAL bf_lafortune(const bf_geom *g, double cxy, double cz, double n)
{
    double m = fmax(fabs(cxy), fabs(cz));
    BF_REAL x = (cxy * (g->ix * g->ox + g->iy * g->oy) + cz * (g->iz * g->oz)) / m;
    return ((n + 2.0) / (2.0 * BF_PI)) * bf_powu(x, n);
}

/* The lobes whose F0 enters only through Schlick's factor at V.H are
 * written K = F(F0, V.H) R(g, p1), R their _rest: a data pass reuses R for
 * F0's forward difference (BF_FD_SCHLICK in bf_lobe.h), bit for bit. */

/* Cook-Torrance [F0, m], with the constant 1/(4 pi m^2) of the published fits */
BF_FN BF_REAL bf_cook_torrance_rest(const bf_geom *g, double m)
{
    double m2 = m * m;
    BF_REAL nh = g->nh, vh = g->vh;
    BF_REAL gg = fmin(fmin(2.0 * nh * g->oz / vh, 2.0 * nh * g->iz / vh), 1.0);
    BF_REAL nh2 = nh * nh;
    BF_REAL d = exp(-bf_tan2(nh) / m2) / ((4.0 * BF_PI * m2) * (nh2 * nh2));
    return gg * d / (g->iz * g->oz);
}

BF_FN BF_REAL bf_cook_torrance(const bf_geom *g, double f0, double m)
{
    return bf_schlick(f0, g->vh) * bf_cook_torrance_rest(g, m);
}

/* Ashikhmin-Shirley [F0, n] */
BF_FN BF_REAL bf_ashikhmin_shirley_rest(const bf_geom *g, double n)
{
    return ((n + 1.0) / (8.0 * BF_PI)) * bf_powu(g->nh, n) / (g->vh * fmax(g->iz, g->oz));
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
 * G2 / (4 cos ti cos to) = 1 / (2 (q(wi) oz + q(wo) iz)). */
BF_FN BF_REAL bf_ggx_rest(const bf_geom *g, double alpha)
{
    double a2 = alpha * alpha;
    BF_REAL hx = g->ix + g->ox, hy = g->iy + g->oy, hz = g->iz + g->oz;
    BF_REAL s2 = hx * hx + hy * hy, h2 = s2 + hz * hz;
    BF_REAL den = a2 * (hz * hz) + s2;
    BF_REAL d = (a2 * (h2 * h2)) / (BF_PI * (den * den));
    BF_REAL qi = sqrt(g->iz * g->iz + a2 * (g->ix * g->ix + g->iy * g->iy));
    BF_REAL qo = sqrt(g->oz * g->oz + a2 * (g->ox * g->ox + g->oy * g->oy));
    return d / (2.0 * (qi * g->oz + qo * g->iz));
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
 * with bf_lobe_<model> its entry point and fd how a data pass takes its
 * forward differences, BF_FD_POINTWISE (the lobe at each point), BF_FD_SCHLICK
 * (K = F(p[0], V.H) bf_<model>_rest(g, p[1]): the rest once per distinct p[1])
 * or BF_FD_OWN (its own bf_lobe_fd_<model>).  bf_lobe and bf_lobe_fd (bf_lobe.h) switch
 * over this list; the rest of a model's facts are its registry entry. */
#define BF_MODEL_LOBES(X)                                                                 \
    X(0, ward, BF_FD_POINTWISE)                                                           \
    X(1, ward_duer, BF_FD_POINTWISE)                                                      \
    X(2, blinn_phong, BF_FD_POINTWISE)                                                    \
    X(3, lafortune, BF_FD_POINTWISE)                                                      \
    X(4, cook_torrance, BF_FD_SCHLICK)                                                    \
    X(5, ashikhmin_shirley, BF_FD_SCHLICK)                                                \
    X(6, he, BF_FD_OWN)                                                                   \
    X(7, ggx, BF_FD_SCHLICK)

#endif /* BF_MODELS_H */
