/* SPDX-License-Identifier: MIT */
/* openpbr_albedo.c -- the directional albedo of the openpbr model's GGX
 * lobe with the exact dielectric Fresnel (kernels/bf_openpbr.h): at view
 * cosine mu, roughness r (alpha = r^2) and normal-incidence reflectance F0
 * (IOR (1 + sqrt F0) / (1 - sqrt F0)),
 *
 *   E = int D(H) G2(L, V) F(V.H) (V.H) / mu dH,
 *
 * over the half vectors H whose reflected L is above the horizon (dL = 4
 * (V.H) dH), D Trowbridge-Reitz and G2 the height-correlated Smith function;
 * at F0 = 1 (F = 1) it is the lobe's own albedo Ess.  E is tabulated once
 * per process on 33 x 33 x 17 nodes over s = sqrt(mu), r and q = sqrt(F0).
 * Each (s, r) column is a product Gauss-Legendre quadrature, its nodes
 * shared by the 17 F0: in t = atan(tan(theta_H) / alpha), where D's mass is
 * spread evenly, split where the reflected directions start to fall below
 * the horizon (theta_H = pi/4 -+ theta_V / 2, from 2 (N.H) (V.H) = N.V), and
 * in the azimuth over the range that stays above it (cos phi > (mu / (2 cos
 * theta_H) - mu cos theta_H) / (sin theta_V sin theta_H)).  Every integrand
 * is then smooth: 32 x 16 nodes a piece give E to 1e-4.  A lookup
 * interpolates tricubically (Catmull-Rom); its error against a direct
 * integration over the hemisphere is measured by the tests (docs/openpbr.md,
 * The albedo table). */
#define _DEFAULT_SOURCE /* M_PI */
#include "bf_openpbr.h"

#include <math.h>
#include <pthread.h>

#define AL_NS BF_OPENPBR_ALBEDO_NS /* table nodes in s = sqrt(mu): 0, 1/32, ..., 1 */
#define AL_NR 33 /* in the roughness */
#define AL_NQ 17 /* in q = sqrt(F0): 0, 1/16, ..., 1 */
#define AL_NT 32 /* Gauss-Legendre nodes a piece in t */
#define AL_NPHI 16 /* and in the azimuth */

static double table_e[AL_NR][AL_NS][AL_NQ];
static pthread_once_t table_once = PTHREAD_ONCE_INIT;

/* Gauss-Legendre nodes x[i] in (0, 1) and weights w[i] summing to 1. */
static void gauss_legendre01(int n, double *x, double *w)
{
    for (int i = 0; i < n; i++) {
        double z = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-15)
                break;
        }
        x[i] = 0.5 * (1.0 - z);
        w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
    }
}

/* Smith's Lambda for GGX at cos theta = mu. */
static double smith_lambda(double mu, double a2)
{
    return 0.5 * (sqrt(mu * mu + a2 * (1.0 - mu * mu)) / mu - 1.0);
}

typedef struct al_quad {
    double tx[AL_NT], tw[AL_NT], px[AL_NPHI], pw[AL_NPHI];
} al_quad;

/* The azimuth range [0, phi_max] (of H about N, from V's) whose L is above
 * the horizon, at theta_H with sine st and cosine ct. */
static double phi_max(double vx, double vz, double st, double ct)
{
    double num = vz / (2.0 * ct) - vz * ct, den = vx * st;
    if (!(den > 0.0))
        return num > 0.0 ? 0.0 : M_PI;
    return acos(fmin(fmax(num / den, -1.0), 1.0));
}

/* The IOR of each q node (0: q = 1, F = 1). */
static void node_etas(double *eta)
{
    for (int k = 0; k < AL_NQ; k++) {
        double q = (double)k / (AL_NQ - 1);
        eta[k] = k == AL_NQ - 1 ? 0.0 : (1.0 + q) / (1.0 - q);
    }
}

/* E at every q node, over t in [t0, t1], at mu (> 0) and alpha, added to e. */
static void albedo_piece(const al_quad *q, double mu, double alpha, double t0, double t1,
                         const double *eta, double *e)
{
    const double a2 = alpha * alpha, vx = sqrt(fmax(1.0 - mu * mu, 0.0)), vz = mu;
    const double lv = smith_lambda(mu, a2);
    for (int i = 0; i < AL_NT; i++) {
        double t = t0 + (t1 - t0) * q->tx[i], tt = tan(t), at = alpha * tt;
        double th = atan(at), st = sin(th), ct = cos(th);
        double dth = alpha / (cos(t) * cos(t) * (1.0 + at * at));
        double d = a2 / (M_PI * (ct * ct * (a2 - 1.0) + 1.0) * (ct * ct * (a2 - 1.0) + 1.0));
        double pm = phi_max(vx, vz, st, ct);
        double w = q->tw[i] * (t1 - t0) * dth * st * d * 2.0 * pm / mu;
        for (int j = 0; j < AL_NPHI && pm > 0.0; j++) {
            double vh = fmin(vx * st * cos(pm * q->px[j]) + vz * ct, 1.0), lz = 2.0 * vh * ct - vz;
            if (!(lz > 0.0) || !(vh > 0.0))
                continue;
            double g = w * q->pw[j] * vh / (1.0 + lv + smith_lambda(lz, a2));
            for (int k = 0; k < AL_NQ; k++)
                e[k] += g * (eta[k] > 0.0 ? bf_openpbr_fresnel_dielectric(vh, eta[k]) : 1.0);
        }
    }
}

/* The angle t of theta_H: tan theta_H = alpha tan t. */
static double t_of(double th, double alpha)
{
    return th >= 0.5 * M_PI ? 0.5 * M_PI : atan(tan(th) / alpha);
}

static void albedo_integrate(const al_quad *q, double mu, double alpha, const double *eta,
                             double *e)
{
    double tv = acos(mu), t1 = t_of(0.25 * M_PI - 0.5 * tv, alpha);
    double t2 = t_of(0.25 * M_PI + 0.5 * tv, alpha);
    for (int k = 0; k < AL_NQ; k++)
        e[k] = 0.0;
    albedo_piece(q, mu, alpha, 0.0, t1, eta, e);
    albedo_piece(q, mu, alpha, t1, t2, eta, e);
}

/* The grid's nodes: s and r at i / 32; mu = s^2 and r floored at
 * BF_COS_FLOOR and BF_GLTF_ROUGHNESS_MIN (the least values the model
 * evaluates). */
static double node_mu(int i)
{
    double s = (double)i / (AL_NS - 1);
    return fmax(s * s, BF_COS_FLOOR);
}

static double node_r(int j)
{
    return fmax((double)j / (AL_NR - 1), BF_GLTF_ROUGHNESS_MIN);
}

static void table_make(void)
{
    al_quad q;
    double eta[AL_NQ];
    gauss_legendre01(AL_NT, q.tx, q.tw);
    gauss_legendre01(AL_NPHI, q.px, q.pw);
    node_etas(eta);
    for (int j = 0; j < AL_NR; j++) {
        double r = node_r(j);
        for (int i = 0; i < AL_NS; i++)
            albedo_integrate(&q, node_mu(i), r * r, eta, table_e[j][i]);
    }
}

/* An interpolated albedo kept where albedos lie, 0 <= E <= Ess <= 1 (the
 * cubic overshoots by ~1e-3 near grazing, where the table is coarse). */
static void clamp_albedo(double e, double ess, double *E, double *Ess)
{
    *Ess = fmin(fmax(ess, 1e-6), 1.0);
    *E = fmin(fmax(e, 0.0), *Ess);
}

/* Catmull-Rom weights w[0..3] on the nodes i - 1 .. i + 2 around x in [0,
 * 1] on n nodes (*i0 = i - 1); a node beyond an end is the linear
 * extrapolation of the two inside, its weight moved onto them. */
static void axis(double x, int n, int *i0, double *w)
{
    double s = fmin(fmax(x, 0.0), 1.0) * (n - 1);
    int i = (int)s;
    if (i > n - 2)
        i = n - 2;
    double t = s - i, t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
    if (i == 0) { /* node -1 = 2 v0 - v1 */
        w[1] += 2.0 * w[0];
        w[2] -= w[0];
        w[0] = 0.0;
    }
    if (i + 2 > n - 1) { /* node n = 2 v(n-1) - v(n-2) */
        w[2] += 2.0 * w[3];
        w[1] -= w[3];
        w[3] = 0.0;
    }
    *i0 = i - 1;
}

void bf_openpbr_albedo(double mu, double r, double f0, double *E, double *Ess)
{
    pthread_once(&table_once, table_make);
    int j0, i0, k0;
    double wr[4], ws[4], wq[4];
    axis(r, AL_NR, &j0, wr);
    axis(sqrt(fmax(mu, 0.0)), AL_NS, &i0, ws);
    axis(sqrt(fmax(f0, 0.0)), AL_NQ, &k0, wq);
    double e = 0.0, ess = 0.0;
    for (int a = 0; a < 4; a++) {
        if (wr[a] == 0.0)
            continue;
        for (int b = 0; b < 4; b++) {
            double w = wr[a] * ws[b];
            if (w == 0.0)
                continue;
            const double *col = table_e[j0 + a][i0 + b];
            ess += w * col[AL_NQ - 1];
            for (int c = 0; c < 4; c++)
                e += w * wq[c] * (wq[c] != 0.0 ? col[k0 + c] : 0.0);
        }
    }
    clamp_albedo(e, ess, E, Ess);
}

void bf_openpbr_albedo_slice(double r, double f0, bf_openpbr_slice *sl)
{
    pthread_once(&table_once, table_make);
    int j0, k0;
    double wr[4], wq[4];
    axis(r, AL_NR, &j0, wr);
    axis(sqrt(fmax(f0, 0.0)), AL_NQ, &k0, wq);
    for (int i = 0; i < AL_NS; i++) {
        double e = 0.0, ess = 0.0;
        for (int a = 0; a < 4; a++) {
            if (wr[a] == 0.0)
                continue;
            const double *col = table_e[j0 + a][i];
            ess += wr[a] * col[AL_NQ - 1];
            for (int c = 0; c < 4; c++)
                e += wr[a] * wq[c] * (wq[c] != 0.0 ? col[k0 + c] : 0.0);
        }
        sl->e[i] = e;
        sl->ess[i] = ess;
    }
}

void bf_openpbr_slice_at(const bf_openpbr_slice *sl, double mu, double *E, double *Ess)
{
    int i0;
    double ws[4], e = 0.0, ess = 0.0;
    axis(sqrt(fmax(mu, 0.0)), AL_NS, &i0, ws);
    for (int b = 0; b < 4; b++)
        if (ws[b] != 0.0) {
            e += ws[b] * sl->e[i0 + b];
            ess += ws[b] * sl->ess[i0 + b];
        }
    clamp_albedo(e, ess, E, Ess);
}
