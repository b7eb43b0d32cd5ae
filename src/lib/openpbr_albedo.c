/* SPDX-License-Identifier: MIT */
/* openpbr_albedo.c -- the GGX lobe's directional albedo that the openpbr
 * model's layering and multiple-scattering compensation take
 * (kernels/bf_openpbr.h): with a Schlick Fresnel F0 + (1 - F0) (1 - V.H)^5
 * the albedo is F0 A(mu, alpha) + B(mu, alpha), where
 *
 *   A = int (G2 / G1(V)) (1 - (1 - V.H)^5) dD_V(H),  B = int (G2 / G1(V)) (1 - V.H)^5 dD_V(H)
 *
 * over the distribution of visible normals D_V (height-correlated Smith G2,
 * reflected directions below the horizon giving 0).  A and B are tabulated
 * once per process on a grid over mu = cos theta_V and the roughness r
 * (alpha = r^2), each entry by a product quadrature over the visible
 * normals' spherical-cap parametrisation (Dupuy and Benyoub 2023):
 * Gauss-Legendre in the cap's height, the midpoint rule in its azimuth.  A
 * lookup interpolates bicubically (Catmull-Rom).  Its error against a direct
 * integration over the hemisphere is measured by the tests (docs/openpbr.md). */
#define _DEFAULT_SOURCE /* M_PI */
#include "bf_openpbr.h"

#include <math.h>
#include <pthread.h>

#define AL_NMU 33 /* table nodes in mu: 0, 1/32, ..., 1 */
#define AL_NR 33  /* and in the roughness */
#define AL_NH 24  /* Gauss-Legendre nodes in the cap's height */
#define AL_NPHI 48 /* midpoint nodes in the azimuth, over [0, pi] */

static double table_a[AL_NR][AL_NMU], table_b[AL_NR][AL_NMU];
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

/* A and B at mu (> 0) and alpha by the quadrature. */
static void albedo_integrate(double mu, double alpha, const double *gx, const double *gw,
                             double *A, double *B)
{
    const double a2 = alpha * alpha, vx = sqrt(fmax(1.0 - mu * mu, 0.0)), vz = mu;
    const double lv = smith_lambda(mu, a2);
    double sx = alpha * vx, sz = vz, sl = sqrt(sx * sx + sz * sz);
    sx /= sl;
    sz /= sl;
    double sa = 0.0, sb = 0.0;
    for (int i = 0; i < AL_NH; i++) {
        double z = (1.0 - gx[i]) * (1.0 + sz) - sz, st = sqrt(fmax(1.0 - z * z, 0.0));
        double ra = 0.0, rb = 0.0;
        for (int j = 0; j < AL_NPHI; j++) {
            double phi = M_PI * (j + 0.5) / AL_NPHI;
            double hx = alpha * (st * cos(phi) + sx), hy = alpha * st * sin(phi);
            double hz = fmax(z + sz, 0.0), hl = sqrt(hx * hx + hy * hy + hz * hz);
            if (!(hl > 0.0))
                continue;
            hx /= hl;
            hz /= hl;
            double vh = vx * hx + vz * hz, lz = 2.0 * vh * hz - vz;
            if (!(lz > 0.0) || !(vh > 0.0))
                continue;
            double g = (1.0 + lv) / (1.0 + lv + smith_lambda(lz, a2));
            double u = 1.0 - fmin(vh, 1.0), fw = u * u * u * u * u;
            ra += g * (1.0 - fw);
            rb += g * fw;
        }
        sa += gw[i] * ra;
        sb += gw[i] * rb;
    }
    *A = sa / AL_NPHI;
    *B = sb / AL_NPHI;
}

/* The grid's nodes: mu and r at i / 32, floored at BF_COS_FLOOR and
 * BF_GLTF_ROUGHNESS_MIN (the least values the model evaluates). */
static double node_mu(int i)
{
    return fmax((double)i / (AL_NMU - 1), BF_COS_FLOOR);
}

static double node_r(int j)
{
    return fmax((double)j / (AL_NR - 1), BF_GLTF_ROUGHNESS_MIN);
}

static void table_make(void)
{
    double gx[AL_NH], gw[AL_NH];
    gauss_legendre01(AL_NH, gx, gw);
    for (int j = 0; j < AL_NR; j++) {
        double r = node_r(j);
        for (int i = 0; i < AL_NMU; i++)
            albedo_integrate(node_mu(i), r * r, gx, gw, &table_a[j][i], &table_b[j][i]);
    }
}

/* Catmull-Rom weights at t in [0, 1] for the nodes -1, 0, 1, 2. */
static void cr_weights(double t, double *w)
{
    double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
}

/* The cell of x in [0, 1] on n nodes, and the offset t in it. */
static int cell(double x, int n, double *t)
{
    double s = fmin(fmax(x, 0.0), 1.0) * (n - 1);
    int i = (int)s;
    if (i > n - 2)
        i = n - 2;
    *t = s - i;
    return i;
}

/* Table value at node (j, i), a node beyond an end extrapolated linearly. */
static double at(double tab[AL_NR][AL_NMU], int j, int i)
{
    if (i < 0)
        return 2.0 * at(tab, j, 0) - at(tab, j, 1);
    if (i >= AL_NMU)
        return 2.0 * at(tab, j, AL_NMU - 1) - at(tab, j, AL_NMU - 2);
    if (j < 0)
        return 2.0 * tab[0][i] - tab[1][i];
    if (j >= AL_NR)
        return 2.0 * tab[AL_NR - 1][i] - tab[AL_NR - 2][i];
    return tab[j][i];
}

void bf_openpbr_albedo_ab(double mu, double r, double *A, double *B)
{
    pthread_once(&table_once, table_make);
    double tm, tr, wm[4], wr[4];
    int i = cell(mu, AL_NMU, &tm), j = cell(r, AL_NR, &tr);
    cr_weights(tm, wm);
    cr_weights(tr, wr);
    double a = 0.0, b = 0.0;
    for (int q = 0; q < 4; q++)
        for (int k = 0; k < 4; k++) {
            double w = wr[q] * wm[k];
            a += w * at(table_a, j - 1 + q, i - 1 + k);
            b += w * at(table_b, j - 1 + q, i - 1 + k);
        }
    *A = a;
    *B = b;
}
