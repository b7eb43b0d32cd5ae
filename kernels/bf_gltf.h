/* SPDX-License-Identifier: MIT */
/*
 * bf_gltf.h -- the BRDF of the glTF 2.0 metallic-roughness material, as the
 * specification defines it (glTF 2.0, Appendix B "BRDF Implementation"),
 * with the ratified extensions KHR_materials_ior and KHR_materials_specular
 * (their "Implementation" sections and "Interaction with other extensions":
 * f0 from the IOR, scaled by the specular colour, clamped to 1, times the
 * specular factor; f90 = the specular factor; the diffuse weighted by
 * 1 - max over the channels of the dielectric Fresnel):
 *
 *   fw          = (1 - |V.H|)^5
 *   specular    = D(a) Vis(a),  a = roughness^2
 *   D           = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2)          Trowbridge-Reitz
 *   Vis         = 1 / (2 (|N.V| sqrt(a^2 + (1 - a^2)(N.L)^2)
 *                        + |N.L| sqrt(a^2 + (1 - a^2)(N.V)^2)))  height-correlated Smith
 *   f0_c        = min(((ior - 1) / (ior + 1))^2 specularColor_c, 1) specularFactor
 *   F_c         = f0_c + (specularFactor - f0_c) fw             dielectric Fresnel
 *   dielectric  = F_c specular + (1 - max_c F_c) baseColor_c / pi
 *   metal       = specular (baseColor_c + (1 - baseColor_c) fw)  conductor Fresnel
 *   f_c         = (1 - metallic) dielectric + metallic metal
 *
 * Without the extensions (ior 1.5, specularFactor 1, specularColor white,
 * their defaults) F = 0.04 + 0.96 fw and dielectric = mix(baseColor / pi,
 * specular, F): the core material of Appendix B exactly.  No cosine factor;
 * directions above the horizon (the library gives 0 below it, as for every
 * model; cosines floored at BF_COS_FLOOR as bf_geom_derive does).  The
 * Heaviside factors of D and Vis are 1 there (N.H, V.H > 0).
 *
 * The base colour enters affinely, f_c = A_c + baseColor_c B_c with
 *   A_c = (1 - metallic) F_c specular + metallic fw specular,
 *   B_c = (1 - metallic) (1 - max F) / pi + metallic (1 - fw) specular,
 * which is what a fit solves exactly (bf_gltf_affine).
 *
 * Parameters: p = [metallic, roughness, ior, specularFactor], col =
 * specularColorFactor (per channel).  Roughness is floored at
 * BF_GLTF_ROUGHNESS_MIN: the specification's note on a = 0 ("Implementations
 * should therefore never use a = 0 ... a should be clamped to a small
 * positive value").
 */
#ifndef BF_GLTF_H
#define BF_GLTF_H

#ifndef __OPENCL_VERSION__
#include "bf_models.h"
#endif

/* The least roughness evaluated: a = 1e-6, where the lobe is already far
 * sharper than a MERL bin. */
#define BF_GLTF_ROUGHNESS_MIN 1e-3

/* The BRDF's functions are always inlined on the host: a loop over samples
 * that calls them (affine_pass.c) then becomes vectors. */
#if !defined(__OPENCL_VERSION__) && defined(__GNUC__)
#define BF_GLTF_FN static inline __attribute__((always_inline))
#else
#define BF_GLTF_FN BF_FN
#endif

/* Trowbridge-Reitz D(a) at N.H = nh. */
BF_GLTF_FN double bf_gltf_d(double a2, double nh)
{
    double t = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (BF_PI * t * t);
}

/* The height-correlated Smith visibility G / (4 |N.L| |N.V|). */
BF_GLTF_FN double bf_gltf_vis(double a2, double nl, double nv)
{
    double gv = nl * sqrt(a2 + (1.0 - a2) * nv * nv);
    double gl = nv * sqrt(a2 + (1.0 - a2) * nl * nl);
    return 0.5 / (gv + gl);
}

/* specular_brdf(a = roughness^2): D Vis. */
BF_GLTF_FN double bf_gltf_specular(const bf_geom *g, double roughness)
{
    double r = fmax(roughness, BF_GLTF_ROUGHNESS_MIN);
    double a2 = (r * r) * (r * r);
    return bf_gltf_d(a2, g->nh) * bf_gltf_vis(a2, g->iz, g->oz);
}

/* The dielectric Fresnel F_c per channel (KHR_materials_ior and
 * KHR_materials_specular) at fw = (1 - |V.H|)^5. */
BF_GLTF_FN void bf_gltf_dielectric_fresnel(double ior, double weight, const double *col, double fw,
                                      double *F)
{
    double q = (ior - 1.0) / (ior + 1.0);
    BF_UNROLL3(c, double f0 = fmin(q * q * col[c], 1.0) * weight; F[c] = f0 + (weight - f0) * fw;)
}

/* The affine form f_c = A[c] + baseColor_c B[c] at p = [metallic,
 * roughness, ior, specularFactor] and specular colour col. */
BF_GLTF_FN void bf_gltf_affine(const bf_geom *g, const double *p, const double *col, double *A,
                          double *B)
{
    const double metallic = p[0];
    double u = 1.0 - g->vh, u2 = u * u;
    double fw = u2 * u2 * u;
    double spec = bf_gltf_specular(g, p[1]);
    double F[3];
    bf_gltf_dielectric_fresnel(p[2], p[3], col, fw, F);
    double fmax3 = F[0] > F[1] ? F[0] : F[1]; /* fmax, without its call */
    fmax3 = fmax3 > F[2] ? fmax3 : F[2];
    double bdiel = (1.0 - fmax3) * (1.0 / BF_PI), bmetal = (1.0 - fw) * spec;
    BF_UNROLL3(c, A[c] = (1.0 - metallic) * (F[c] * spec) + metallic * (fw * spec);
                  B[c] = (1.0 - metallic) * bdiel + metallic * bmetal;)
}

/* The numbers of the affine form's partials that depend on the point p =
 * [metallic, roughness, ior, specularFactor] alone, taken once a point
 * (bf_gltf_point) rather than once a sample. */
typedef struct bf_gltf_pt {
    double m, w;  /* metallic, specularFactor                                 */
    double a2;    /* a^2 = roughness^4 (the roughness floored)                */
    double da2;   /* d a^2 / d roughness, 0 below BF_GLTF_ROUGHNESS_MIN        */
    double q2;    /* ((ior - 1) / (ior + 1))^2, at most 1                      */
    double dq2;   /* d q^2 / d ior                                             */
} bf_gltf_pt;

BF_GLTF_FN bf_gltf_pt bf_gltf_point(const double *p)
{
    bf_gltf_pt t;
    double r = fmax(p[1], BF_GLTF_ROUGHNESS_MIN), q = (p[2] - 1.0) / (p[2] + 1.0);
    t.m = p[0];
    t.w = p[3];
    t.a2 = (r * r) * (r * r);
    t.da2 = p[1] > BF_GLTF_ROUGHNESS_MIN ? 4.0 * (r * r * r) : 0.0;
    t.q2 = fmin(q * q, 1.0);
    t.dq2 = 4.0 * q / ((p[2] + 1.0) * (p[2] + 1.0));
    return t;
}

/* A sample's terms of the affine form with a white specular colour (the
 * same in every channel: what a fit takes) at the point's numbers t
 * (bf_gltf_point): fw, D Vis and its parts, the Fresnel F = w F1 with
 * F1 = q^2 + (1 - q^2) fw (q = (ior - 1) / (ior + 1), w = specularFactor). */
typedef struct bf_gltf_terms {
    double fw, tt, sv, sl, gv, gl, spec, F1, F;
} bf_gltf_terms;

/* A and B with a white specular colour at the point's numbers t, and the
 * terms their partials take (bf_gltf_affine_grad_at).  No branch and no
 * call but sqrt: a loop over samples becomes vectors. */
BF_GLTF_FN void bf_gltf_affine_at(const bf_geom *g, const bf_gltf_pt *t, double *A, double *B,
                                  bf_gltf_terms *k)
{
    const double m = t->m, a2 = t->a2;
    double u = 1.0 - g->vh, u2 = u * u;
    k->fw = u2 * u2 * u;
    k->tt = g->nh * g->nh * (a2 - 1.0) + 1.0;
    k->sv = sqrt(a2 + (1.0 - a2) * g->oz * g->oz);
    k->sl = sqrt(a2 + (1.0 - a2) * g->iz * g->iz);
    k->gv = g->iz * k->sv;
    k->gl = g->oz * k->sl;
    k->spec = (a2 / (BF_PI * k->tt * k->tt)) * (0.5 / (k->gv + k->gl));
    k->F1 = t->q2 + (1.0 - t->q2) * k->fw;
    k->F = t->w * k->F1;
    *A = (1.0 - m) * (k->F * k->spec) + m * (k->fw * k->spec);
    *B = (1.0 - m) * (1.0 - k->F) * (1.0 / BF_PI) + m * ((1.0 - k->fw) * k->spec);
}

/* bf_gltf_affine_at's A, B and their partials dA[k] = dA / dp_k, dB[k] =
 * dB / dp_k in p = [metallic, roughness, ior, specularFactor].  d specular /
 * d a^2 = specular (1 / a^2 - 2 (N.H)^2 / tt - (dgv + dgl) / (gv + gl)) (tt,
 * gv, gl as in bf_gltf_d and bf_gltf_vis); a roughness below
 * BF_GLTF_ROUGHNESS_MIN has no effect. */
BF_GLTF_FN void bf_gltf_affine_grad_at(const bf_geom *g, const bf_gltf_pt *t, double *A, double *B,
                                       double *dA, double *dB)
{
    bf_gltf_terms k;
    bf_gltf_affine_at(g, t, A, B, &k);
    const double m = t->m, w = t->w, a2 = t->a2, fw = k.fw, spec = k.spec, F = k.F;
    double dgv = g->iz * (1.0 - g->oz * g->oz) / (2.0 * k.sv);
    double dgl = g->oz * (1.0 - g->iz * g->iz) / (2.0 * k.sl);
    double dspec = spec * (1.0 / a2 - 2.0 * g->nh * g->nh / k.tt - (dgv + dgl) / (k.gv + k.gl))
                   * t->da2;
    double dF_ior = w * (1.0 - fw) * t->dq2;
    dA[0] = (fw - F) * spec;
    dB[0] = (1.0 - fw) * spec - (1.0 - F) * (1.0 / BF_PI);
    dA[1] = ((1.0 - m) * F + m * fw) * dspec;
    dB[1] = m * (1.0 - fw) * dspec;
    dA[2] = (1.0 - m) * spec * dF_ior;
    dB[2] = -(1.0 - m) * dF_ior * (1.0 / BF_PI);
    dA[3] = (1.0 - m) * spec * k.F1;
    dB[3] = -(1.0 - m) * k.F1 * (1.0 / BF_PI);
}

/* bf_gltf_affine_grad_at at p. */
BF_GLTF_FN void bf_gltf_affine_grad(const bf_geom *g, const double *p, double *A, double *B,
                               double *dA, double *dB)
{
    bf_gltf_pt t = bf_gltf_point(p);
    bf_gltf_affine_grad_at(g, &t, A, B, dA, dB);
}

/* f_c for base colour base[c], specular colour col[c] and p. */
BF_GLTF_FN void bf_gltf(const bf_geom *g, const double *p, const double *base, const double *col,
                   double *f)
{
    double A[3], B[3];
    bf_gltf_affine(g, p, col, A, B);
    BF_UNROLL3(c, f[c] = A[c] + base[c] * B[c];)
}

#endif /* BF_GLTF_H */
