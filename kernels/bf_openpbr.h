/* SPDX-License-Identifier: MIT */
/*
 * bf_openpbr.h -- the BRDF of OpenPBR Surface 1.1's base and specular layers
 * (no coat, fuzz, transmission, subsurface, thin film, emission: their
 * weights 0; base_weight 1; base_diffuse_roughness 0, a Lambertian diffuse),
 * as the specification defines it and, where it leaves a choice, as
 * MaterialX's open_pbr_surface implementation does (docs/openpbr.md):
 *
 *   alpha       = specular_roughness^2
 *   D, Vis      = Trowbridge-Reitz D and the height-correlated Smith
 *                 G2 / (4 |N.L| |N.V|), as glTF's (bf_gltf_d, bf_gltf_vis)
 *   F_s         = ((ior - 1) / (ior + 1))^2
 *   F0'         = min(specular_weight F_s, 0.99999)       modulated IOR's F0
 *   eta'        = (1 + sqrt F0') / (1 - sqrt F0')          modulated IOR
 *   F_d(c)      = the exact unpolarised dielectric Fresnel at eta'
 *   F_m(c)      = clamp(F82-tint(base_color, specular_color, c), 0, 1)
 *   comp        = 1 + Fss (1 - Ess) / Ess,  Fss = F0 + (1 - F0) / 21
 *                 multiple-scattering compensation (Turquin), Ess the
 *                 lobe's albedo with F = 1
 *   E_d         = min(comp_d E(N.V; F0'), 1): the dielectric lobe's albedo,
 *                 E with the exact Fresnel F_d (bf_openpbr_albedo)
 *   dielectric  = specular_color D Vis F_d(V.H) comp_d
 *                 + (1 - E_d) base_color / pi              albedo scaling
 *   metal       = specular_weight D Vis F_m(V.H) comp_m
 *   f_c         = (1 - base_metalness) dielectric + base_metalness metal
 *
 * V is wo (toward the viewer), L wi.  The albedo scaling is the
 * specification's non-reciprocal form (1 - E at the view direction only),
 * MaterialX's layer node: f(wi, wo) != f(wo, wi) in general.
 *
 * Parameters: p = [base_metalness, specular_roughness, specular_ior,
 * specular_weight], base = base_color, col = specular_color (per channel).
 *
 * The base colour C enters per channel as f_c = A_c + C B_c + C^2 Q_c: the
 * metal's compensation comp_m is affine in C, as is F_m for a fixed
 * specular_color (where the clamp is not reached); bf_openpbr_form gives
 * A, B, Q with a white specular colour.
 */
#ifndef BF_OPENPBR_H
#define BF_OPENPBR_H

#include "bf_gltf.h"

/* The largest F0' of the modulated IOR (MaterialX's clamp of
 * specular_weight F_s): eta' stays finite. */
#define BF_OPENPBR_F0_MAX 0.99999
/* F82-tint's angle: cos = 1/7. */
#define BF_OPENPBR_MU_BAR (1.0 / 7.0)

/* The GGX lobe's directional albedo with the exact dielectric Fresnel of
 * reflectance f0 at normal incidence, E, and with F = 1, Ess, at cos theta_V
 * = mu and roughness r (alpha = r^2): interpolated in a table made once per
 * process (src/lib/openpbr_albedo.c). */
void bf_openpbr_albedo(double mu, double r, double f0, double *E, double *Ess);

/* The table's nodes in sqrt(mu). */
#define BF_OPENPBR_ALBEDO_NS 33

/* The table interpolated at one roughness r and f0, over its nodes in
 * sqrt(mu): what a pass at one point looks up per sample (the tricubic
 * interpolation is separable, so bf_openpbr_slice_at gives
 * bf_openpbr_albedo's E and Ess up to rounding). */
typedef struct bf_openpbr_slice {
    double e[BF_OPENPBR_ALBEDO_NS], ess[BF_OPENPBR_ALBEDO_NS];
} bf_openpbr_slice;
void bf_openpbr_albedo_slice(double r, double f0, bf_openpbr_slice *sl);
void bf_openpbr_slice_at(const bf_openpbr_slice *sl, double mu, double *E, double *Ess);

/* F0' = specular_weight F_s, clamped to [0, BF_OPENPBR_F0_MAX]. */
BF_FN double bf_openpbr_f0(double ior, double weight)
{
    double q = (ior - 1.0) / (ior + 1.0);
    return fmin(fmax(weight * q * q, 0.0), BF_OPENPBR_F0_MAX);
}

/* The modulated IOR eta' with F0' = f0 (ior >= 1: sgn(eta - 1) >= 0). */
BF_FN double bf_openpbr_eta(double f0)
{
    double e = sqrt(f0);
    return (1.0 + e) / (1.0 - e);
}

/* The unpolarised Fresnel reflectance of a dielectric of relative IOR eta
 * at cos c (MaterialX's mx_fresnel_dielectric). */
BF_FN double bf_openpbr_fresnel_dielectric(double c, double eta)
{
    double g2 = eta * eta + c * c - 1.0;
    if (g2 < 0.0)
        return 1.0;
    double g = sqrt(g2), a = (g - c) / (g + c), b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

/* F82-tint (Kutz et al., as the specification): the Schlick curve from f0,
 * less the correction that makes it tint Schlick(mu_bar) at mu_bar;
 * clamped to [0, 1] (it goes below 0 for a dark tint and a low f0). */
BF_FN double bf_openpbr_f82(double f0, double tint, double c)
{
    const double mb = BF_OPENPBR_MU_BAR, ub = 1.0 - mb;
    double u = 1.0 - c, u5 = u * u * u * u * u;
    double ub5 = ub * ub * ub * ub * ub;
    double sbar = f0 + (1.0 - f0) * ub5;
    double w = c * u5 * u / (mb * ub5 * ub);
    return fmin(fmax(f0 + (1.0 - f0) * u5 - w * sbar * (1.0 - tint), 0.0), 1.0);
}

/* The multiple-scattering compensation 1 + Fss (1 - Ess) / Ess with Fss
 * the Fresnel average F0 + (1 - F0) / 21 (Turquin; mx_ggx_energy_compensation). */
BF_FN double bf_openpbr_comp(double f0, double ess)
{
    return 1.0 + (f0 + (1.0 - f0) * (1.0 / 21.0)) * (1.0 - ess) / ess;
}

/* The per-sample quantities every channel shares at p. */
typedef struct bf_openpbr_lobe {
    double spec;   /* D Vis                                  */
    double fw;     /* (1 - V.H)^5                            */
    double fd;     /* F_d(V.H) at eta'                       */
    double comp_d; /* the dielectric's compensation          */
    double ed;     /* E(N.V; F0'): the dielectric's albedo    */
    double ess;    /* Ess = A + B at N.V                     */
    double k;      /* (1 - Ess) / Ess                        */
} bf_openpbr_lobe;

/* The lobe at g and p, its albedos E(N.V; F0') and Ess(N.V) given. */
BF_FN void bf_openpbr_lobe_with(const bf_geom *g, const double *p, double e, double ess,
                                bf_openpbr_lobe *L)
{
    double u = 1.0 - g->vh, u2 = u * u, f0 = bf_openpbr_f0(p[2], p[3]);
    L->spec = bf_gltf_specular(g, p[1]);
    L->fw = u2 * u2 * u;
    L->fd = bf_openpbr_fresnel_dielectric(g->vh, bf_openpbr_eta(f0));
    L->comp_d = bf_openpbr_comp(f0, ess);
    L->ed = fmin(e * L->comp_d, 1.0);
    L->ess = ess;
    L->k = (1.0 - ess) / ess;
}

/* The lobe at p whose roughness is L0's (D Vis and (1 - V.H)^5 its), at
 * the albedos e, ess: what changes with specular_ior and specular_weight. */
BF_FN void bf_openpbr_lobe_f0(const bf_openpbr_lobe *L0, const bf_geom *g, const double *p,
                              double e, double ess, bf_openpbr_lobe *L)
{
    double f0 = bf_openpbr_f0(p[2], p[3]);
    *L = *L0;
    L->fd = bf_openpbr_fresnel_dielectric(g->vh, bf_openpbr_eta(f0));
    L->comp_d = bf_openpbr_comp(f0, ess);
    L->ed = fmin(e * L->comp_d, 1.0);
    L->ess = ess;
    L->k = (1.0 - ess) / ess;
}

BF_FN void bf_openpbr_lobe_at(const bf_geom *g, const double *p, bf_openpbr_lobe *L)
{
    double e, ess;
    bf_openpbr_albedo(g->oz, fmax(p[1], BF_GLTF_ROUGHNESS_MIN), bf_openpbr_f0(p[2], p[3]), &e, &ess);
    bf_openpbr_lobe_with(g, p, e, ess, L);
}

/* f_c for base colour base[c], specular colour col[c] and p. */
BF_FN void bf_openpbr(const bf_geom *g, const double *p, const double *base, const double *col,
                      double *f)
{
    bf_openpbr_lobe L;
    bf_openpbr_lobe_at(g, p, &L);
    const double m = p[0];
    for (int c = 0; c < 3; c++) {
        double diel = col[c] * L.spec * L.fd * L.comp_d + (1.0 - L.ed) * base[c] * (1.0 / BF_PI);
        double comp_m = bf_openpbr_comp(base[c], L.ess);
        double metal = p[3] * L.spec * bf_openpbr_f82(base[c], col[c], g->vh) * comp_m;
        f[c] = (1.0 - m) * diel + m * metal;
    }
}

/* With a white specular colour: f = A + C B + C^2 Q in the base colour C
 * (the same A, B, Q in every channel).  F_m = C (1 - fw) + fw (F82-tint
 * with tint 1 is Schlick's, inside [0, 1]) and comp_m = 1 + (C 20/21 +
 * 1/21) k. */
BF_FN void bf_openpbr_form_of(const bf_openpbr_lobe *L, const double *p, double *A, double *B,
                              double *Q)
{
    const double m = p[0], ms = m * p[3] * L->spec;
    const double k0 = 1.0 + L->k * (1.0 / 21.0), k1 = L->k * (20.0 / 21.0);
    *A = (1.0 - m) * L->spec * L->fd * L->comp_d + ms * L->fw * k0;
    *B = (1.0 - m) * (1.0 - L->ed) * (1.0 / BF_PI) + ms * ((1.0 - L->fw) * k0 + L->fw * k1);
    *Q = ms * (1.0 - L->fw) * k1;
}

BF_FN void bf_openpbr_form(const bf_geom *g, const double *p, double *A, double *B, double *Q)
{
    bf_openpbr_lobe L;
    bf_openpbr_lobe_at(g, p, &L);
    bf_openpbr_form_of(&L, p, A, B, Q);
}

#endif /* BF_OPENPBR_H */
