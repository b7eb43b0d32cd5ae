/* SPDX-License-Identifier: MIT */
/* openpbr_albedo.c -- the GGX lobe's directional albedo that the openpbr
 * model's layering and multiple-scattering compensation take
 * (kernels/bf_openpbr.h): with a Schlick Fresnel F0 + (1 - F0) (1 - V.H)^5
 * the albedo is F0 A(mu, alpha) + B(mu, alpha), where
 *
 *   A = int D(H) G2(L, V) (1 - (1 - V.H)^5) (V.H) / mu dH,   B the same with (1 - V.H)^5,
 *
 * over the half vectors H whose reflected L is above the horizon (dL = 4 (V.H)
 * dH), D Trowbridge-Reitz and G2 the height-correlated Smith function.
 * A and B are tabulated once per process on 33 x 33 nodes over s = sqrt(mu)
 * and the roughness r (alpha = r^2).  Each entry is a product
 * Gauss-Legendre quadrature: in t = atan(tan(theta_H) / alpha), where D's
 * mass is spread evenly, split where the reflected directions start to
 * fall below the horizon (theta_H = pi/4 -+ theta_V / 2, from 2 (N.H) (V.H)
 * = N.V), and in the azimuth over the range that stays above it
 * (cos phi > (mu / (2 cos theta_H) - mu cos theta_H) / (sin theta_V sin
 * theta_H)).  Every integrand is then smooth: 32 x 16 nodes a piece give A
 * and B to 1e-4.  A lookup interpolates bicubically (Catmull-Rom); its
 * error against a direct integration over the hemisphere is measured by the
 * tests (docs/openpbr.md, The albedo table). */
#define _DEFAULT_SOURCE /* M_PI */
#include "bf_openpbr.h"

#include <math.h>
#include <pthread.h>

#define AL_NS 33 /* table nodes in s = sqrt(mu): 0, 1/32, ..., 1 */
#define AL_NR 33 /* and in the roughness */
#define AL_NT 32 /* Gauss-Legendre nodes a piece in t */
#define AL_NPHI 16 /* and in the azimuth */

static double table_a[AL_NR][AL_NS], table_b[AL_NR][AL_NS];
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

/* A and B over t in [t0, t1] at mu (> 0) and alpha. */
static void albedo_piece(const al_quad *q, double mu, double alpha, double t0, double t1,
                         double *A, double *B)
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
            double vh = vx * st * cos(pm * q->px[j]) + vz * ct, lz = 2.0 * vh * ct - vz;
            if (!(lz > 0.0))
                continue;
            double g = 1.0 / (1.0 + lv + smith_lambda(lz, a2));
            double u = 1.0 - fmin(vh, 1.0), fw = u * u * u * u * u;
            *A += w * q->pw[j] * g * vh * (1.0 - fw);
            *B += w * q->pw[j] * g * vh * fw;
        }
    }
}

/* The angle t of theta_H: tan theta_H = alpha tan t. */
static double t_of(double th, double alpha)
{
    return th >= 0.5 * M_PI ? 0.5 * M_PI : atan(tan(th) / alpha);
}

static void albedo_integrate(const al_quad *q, double mu, double alpha, double *A, double *B)
{
    double tv = acos(mu), t1 = t_of(0.25 * M_PI - 0.5 * tv, alpha);
    double t2 = t_of(0.25 * M_PI + 0.5 * tv, alpha);
    *A = *B = 0.0;
    albedo_piece(q, mu, alpha, 0.0, t1, A, B);
    albedo_piece(q, mu, alpha, t1, t2, A, B);
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
    gauss_legendre01(AL_NT, q.tx, q.tw);
    gauss_legendre01(AL_NPHI, q.px, q.pw);
    for (int j = 0; j < AL_NR; j++) {
        double r = node_r(j);
        for (int i = 0; i < AL_NS; i++)
            albedo_integrate(&q, node_mu(i), r * r, &table_a[j][i], &table_b[j][i]);
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
static double at(double tab[AL_NR][AL_NS], int j, int i)
{
    if (i < 0)
        return 2.0 * at(tab, j, 0) - at(tab, j, 1);
    if (i >= AL_NS)
        return 2.0 * at(tab, j, AL_NS - 1) - at(tab, j, AL_NS - 2);
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
    int i = cell(sqrt(fmax(mu, 0.0)), AL_NS, &tm), j = cell(r, AL_NR, &tr);
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
