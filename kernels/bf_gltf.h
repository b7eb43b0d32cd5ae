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

/* Trowbridge-Reitz D(a) at N.H = nh. */
BF_FN double bf_gltf_d(double a2, double nh)
{
    double t = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (BF_PI * t * t);
}

/* The height-correlated Smith visibility G / (4 |N.L| |N.V|). */
BF_FN double bf_gltf_vis(double a2, double nl, double nv)
{
    double gv = nl * sqrt(a2 + (1.0 - a2) * nv * nv);
    double gl = nv * sqrt(a2 + (1.0 - a2) * nl * nl);
    return 0.5 / (gv + gl);
}

/* specular_brdf(a = roughness^2): D Vis. */
BF_FN double bf_gltf_specular(const bf_geom *g, double roughness)
{
    double r = fmax(roughness, BF_GLTF_ROUGHNESS_MIN);
    double a2 = (r * r) * (r * r);
    return bf_gltf_d(a2, g->nh) * bf_gltf_vis(a2, g->iz, g->oz);
}

/* The dielectric Fresnel F_c per channel (KHR_materials_ior and
 * KHR_materials_specular) at fw = (1 - |V.H|)^5. */
BF_FN void bf_gltf_dielectric_fresnel(double ior, double weight, const double *col, double fw,
                                      double *F)
{
    double q = (ior - 1.0) / (ior + 1.0);
    for (int c = 0; c < 3; c++) {
        double f0 = fmin(q * q * col[c], 1.0) * weight;
        F[c] = f0 + (weight - f0) * fw;
    }
}

/* The affine form f_c = A[c] + baseColor_c B[c] at p = [metallic,
 * roughness, ior, specularFactor] and specular colour col. */
BF_FN void bf_gltf_affine(const bf_geom *g, const double *p, const double *col, double *A,
                          double *B)
{
    const double metallic = p[0];
    double u = 1.0 - g->vh, u2 = u * u;
    double fw = u2 * u2 * u;
    double spec = bf_gltf_specular(g, p[1]);
    double F[3];
    bf_gltf_dielectric_fresnel(p[2], p[3], col, fw, F);
    double fmax3 = fmax(F[0], fmax(F[1], F[2]));
    double bdiel = (1.0 - fmax3) * (1.0 / BF_PI), bmetal = (1.0 - fw) * spec;
    for (int c = 0; c < 3; c++) {
        A[c] = (1.0 - metallic) * (F[c] * spec) + metallic * (fw * spec);
        B[c] = (1.0 - metallic) * bdiel + metallic * bmetal;
    }
}

/* The affine form's A, B with a white specular colour (the same in every
 * channel: what a fit takes), and their partials dA[k] = dA / dp_k,
 * dB[k] = dB / dp_k in p = [metallic, roughness, ior, specularFactor].
 * With q = (ior - 1) / (ior + 1) and w = specularFactor, F = w F1,
 * F1 = q^2 + (1 - q^2) fw, and d specular / d a^2 = specular (1 / a^2 -
 * 2 (N.H)^2 / t - (dgv + dgl) / (gv + gl)) (t, gv, gl as in bf_gltf_d and
 * bf_gltf_vis); a roughness below BF_GLTF_ROUGHNESS_MIN has no effect. */
BF_FN void bf_gltf_affine_grad(const bf_geom *g, const double *p, double *A, double *B,
                               double *dA, double *dB)
{
    const double m = p[0], w = p[3];
    double u = 1.0 - g->vh, u2 = u * u;
    double fw = u2 * u2 * u;
    double r = fmax(p[1], BF_GLTF_ROUGHNESS_MIN), a2 = (r * r) * (r * r);
    double t = g->nh * g->nh * (a2 - 1.0) + 1.0;
    double sv = sqrt(a2 + (1.0 - a2) * g->oz * g->oz), sl = sqrt(a2 + (1.0 - a2) * g->iz * g->iz);
    double gv = g->iz * sv, gl = g->oz * sl;
    double spec = (a2 / (BF_PI * t * t)) * (0.5 / (gv + gl));
    double dgv = g->iz * (1.0 - g->oz * g->oz) / (2.0 * sv);
    double dgl = g->oz * (1.0 - g->iz * g->iz) / (2.0 * sl);
    double dspec_da2 = spec * (1.0 / a2 - 2.0 * g->nh * g->nh / t - (dgv + dgl) / (gv + gl));
    double dspec = p[1] > BF_GLTF_ROUGHNESS_MIN ? dspec_da2 * 4.0 * (r * r * r) : 0.0;
    double q = (p[2] - 1.0) / (p[2] + 1.0), q2 = fmin(q * q, 1.0);
    double F1 = q2 + (1.0 - q2) * fw, F = w * F1;
    double dF_ior = w * (1.0 - fw) * 4.0 * q / ((p[2] + 1.0) * (p[2] + 1.0));
    *A = (1.0 - m) * (F * spec) + m * (fw * spec);
    *B = (1.0 - m) * (1.0 - F) * (1.0 / BF_PI) + m * ((1.0 - fw) * spec);
    dA[0] = (fw - F) * spec;
    dB[0] = (1.0 - fw) * spec - (1.0 - F) * (1.0 / BF_PI);
    dA[1] = ((1.0 - m) * F + m * fw) * dspec;
    dB[1] = m * (1.0 - fw) * dspec;
    dA[2] = (1.0 - m) * spec * dF_ior;
    dB[2] = -(1.0 - m) * dF_ior * (1.0 / BF_PI);
    dA[3] = (1.0 - m) * spec * F1;
    dB[3] = -(1.0 - m) * F1 * (1.0 / BF_PI);
}

/* f_c for base colour base[c], specular colour col[c] and p. */
BF_FN void bf_gltf(const bf_geom *g, const double *p, const double *base, const double *col,
                   double *f)
{
    double A[3], B[3];
    bf_gltf_affine(g, p, col, A, B);
    for (int c = 0; c < 3; c++)
        f[c] = A[c] + base[c] * B[c];
}

#endif /* BF_GLTF_H */
