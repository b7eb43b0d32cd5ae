/* SPDX-License-Identifier: MIT */
/* affine_reduce.c -- the affine engine's reduced problem (affine.h): from a
 * pass's sums, the best base colours and the Error, gradient and Gauss-Newton
 * matrix of the lobe coordinates with the colours solved, and its Cholesky
 * factor, which affine.c hands to cminpack; glTF's colour enters affinely,
 * OpenPBR's as a quadratic (bf_affine_reduce_q). */
#include "affine.h"

#include <math.h>
#include <string.h>

/* The best base colour of channel c at a pass's sums (x = argmin over [0, 1]
 * of the channel's r^T r, a parabola in x), and whether it is inside. */
static double best_colour(const af_mom *m, int c, int *free)
{
    *free = 0;
    if (!(m->bb > 0.0))
        return 0.0;
    double x = (m->rb[c] - m->ab) / m->bb;
    if (!(x > 0.0))
        return 0.0;
    if (!(x < 1.0))
        return 1.0;
    *free = 1;
    return x;
}

/* r^T r, H = J_red^T J_red and g = J^T r (nx x nx, nx) at the best colours
 * into *rr, H, g and base; hdiag: H's diagonal before the colours are
 * projected out.  With f = A + x B: r = A + x B - rho, J_j = dA_j + x dB_j,
 * and for a colour inside (0, 1) its column B projected out (Kaufman's
 * approximation, as linear.h). */
void bf_affine_reduce(const af_mom *m, int nx, double *rr, double H[][AF_NP], double *g,
                      double *hdiag, double *base)
{
    *rr = 0.0;
    memset(H, 0, sizeof(double) * AF_NP * AF_NP);
    memset(g, 0, sizeof(double) * AF_NP);
    memset(hdiag, 0, sizeof(double) * AF_NP);
    for (int c = 0; c < 3; c++) {
        int free;
        double x = best_colour(m, c, &free);
        base[c] = x;
        *rr += m->rr[c] - 2.0 * (m->ra[c] + x * m->rb[c]) + m->aa + x * (2.0 * m->ab + x * m->bb);
        double v[AF_NP];
        for (int j = 0; j < nx; j++) {
            g[j] += m->daa[j] + x * (m->dab[j] + m->dba[j] + x * m->dbb[j]) - m->rda[c][j]
                    - x * m->rdb[c][j];
            v[j] = m->dab[j] + x * m->dbb[j];
        }
        for (int j = 0; j < nx; j++)
            for (int l = j; l < nx; l++) {
                double h = m->dada[j][l] + x * (m->dadb[j][l] + m->dadb[l][j]) + x * x * m->dbdb[j][l];
                if (l == j)
                    hdiag[j] += h;
                if (free)
                    h -= v[j] * v[l] / m->bb;
                H[j][l] += h;
            }
    }
    for (int j = 0; j < nx; j++)
        for (int l = 0; l < j; l++)
            H[j][l] = H[l][j];
    *rr = fmax(*rr, 0.0);
}

/* OpenPBR: f_c = A + x_c B + x_c^2 Q. */

/* The Gram matrix of the bases, both triangles. */
static void gram(const af_qmom *m, double G[AF_NB][AF_NB])
{
    for (int x = 0; x < m->nb; x++)
        for (int y = 0; y < m->nb; y++)
            G[x][y] = x <= y ? m->gg[x][y] : m->gg[y][x];
}

/* Channel c's r^T r at colour x, less rho rho: c(x)^T G c(x) - 2 c(x) . rg,
 * c(x) = (1, x, x^2). */
static double colour_rr(const af_qmom *m, const double G[AF_NB][AF_NB], int c, double x)
{
    const double cv[AF_NB] = { 1.0, x, x * x };
    double v = 0.0;
    for (int i = 0; i < m->nb; i++) {
        v -= 2.0 * cv[i] * m->rg[c][i];
        for (int j = 0; j < m->nb; j++)
            v += cv[i] * G[i][j] * cv[j];
    }
    return v;
}

/* Half its derivative in x: c'(x)^T (G c(x) - rg), c'(x) = (0, 1, 2 x). */
static double colour_slope(const af_qmom *m, const double G[AF_NB][AF_NB], int c, double x)
{
    const double cv[AF_NB] = { 1.0, x, x * x }, cd[AF_NB] = { 0.0, 1.0, 2.0 * x };
    double v = 0.0;
    for (int i = 1; i < m->nb; i++) {
        double gi = -m->rg[c][i];
        for (int j = 0; j < m->nb; j++)
            gi += G[i][j] * cv[j];
        v += cd[i] * gi;
    }
    return v;
}

#define AF_COLOUR_CELLS 32

/* The best base colour of channel c at a pass's sums (x = argmin over [0, 1]
 * of the channel's r^T r: a parabola in x for glTF, solved directly; a
 * quartic for OpenPBR, whose stationary points are bracketed on
 * AF_COLOUR_CELLS cells and bisected), and whether it is inside. */
static double best_colour_q(const af_qmom *m, const double G[AF_NB][AF_NB], int c, int *free)
{
    *free = 0;
    if (!(G[1][1] > 0.0))
        return 0.0;
    if (m->nb == 2) {
        double x = (m->rg[c][1] - G[0][1]) / G[1][1];
        if (!(x > 0.0))
            return 0.0;
        if (!(x < 1.0))
            return 1.0;
        *free = 1;
        return x;
    }
    double best = 0.0, vbest = colour_rr(m, G, c, 0.0);
    if (colour_rr(m, G, c, 1.0) < vbest)
        best = 1.0, vbest = colour_rr(m, G, c, 1.0);
    double lo = 0.0, slo = colour_slope(m, G, c, 0.0);
    for (int k = 1; k <= AF_COLOUR_CELLS; k++) {
        double hi = (double)k / AF_COLOUR_CELLS, shi = colour_slope(m, G, c, hi);
        if (slo < 0.0 && shi >= 0.0) { /* a minimum inside [lo, hi] */
            double a = lo, b = hi;
            for (int it = 0; it < 60; it++) {
                double mid = 0.5 * (a + b);
                if (colour_slope(m, G, c, mid) < 0.0)
                    a = mid;
                else
                    b = mid;
            }
            double x = 0.5 * (a + b), v = colour_rr(m, G, c, x);
            if (v < vbest && x > 0.0 && x < 1.0)
                best = x, vbest = v, *free = 1;
            else if (v < vbest)
                best = x, vbest = v;
        }
        lo = hi;
        slo = shi;
    }
    if (*free && (best <= 0.0 || best >= 1.0))
        *free = 0;
    return best;
}

/* sum dX_j dY_l at rows f = j nb + X, h = l nb + Y (either order). */
static double dd_at(const af_qmom *m, int f, int h)
{
    return f <= h ? m->dd[f][h] : m->dd[h][f];
}

/* r^T r, H = J_red^T J_red and g = J^T r (nx x nx, nx) at the best colours
 * into *rr, H, g and base; hdiag: H's diagonal before the colours are
 * projected out.  With f = c(x) . (A, B, Q): r = f - rho, J_j = c(x) .
 * (dA_j, dB_j, dQ_j), and for a colour inside (0, 1) its column c'(x) .
 * (A, B, Q) projected out (Kaufman's approximation, as linear.h). */
void bf_affine_reduce_q(const af_qmom *m, int nx, double *rr, double H[][AF_NP], double *g,
                        double *hdiag, double *base)
{
    const int nb = m->nb;
    double G[AF_NB][AF_NB];
    gram(m, G);
    *rr = 0.0;
    memset(H, 0, sizeof(double) * AF_NP * AF_NP);
    memset(g, 0, sizeof(double) * AF_NP);
    memset(hdiag, 0, sizeof(double) * AF_NP);
    for (int c = 0; c < 3; c++) {
        int free;
        double x = best_colour_q(m, G, c, &free);
        const double cv[AF_NB] = { 1.0, x, x * x }, cd[AF_NB] = { 0.0, 1.0, 2.0 * x };
        base[c] = x;
        *rr += m->rr[c] + colour_rr(m, G, c, x);
        double v[AF_NP], bb = 0.0;
        for (int i = 0; i < nb; i++)
            for (int k = 0; k < nb; k++)
                bb += cd[i] * G[i][k] * cd[k];
        for (int j = 0; j < nx; j++) {
            v[j] = 0.0;
            for (int i = 0; i < nb; i++) {
                g[j] -= cv[i] * m->rd[c][j * nb + i];
                for (int k = 0; k < nb; k++) {
                    g[j] += cv[i] * cv[k] * m->dg[j * nb + i][k];
                    v[j] += cv[i] * cd[k] * m->dg[j * nb + i][k];
                }
            }
        }
        for (int j = 0; j < nx; j++)
            for (int l = j; l < nx; l++) {
                double h = 0.0;
                for (int i = 0; i < nb; i++)
                    for (int k = 0; k < nb; k++)
                        h += cv[i] * cv[k] * dd_at(m, j * nb + i, l * nb + k);
                if (l == j)
                    hdiag[j] += h;
                if (free && bb > 0.0)
                    h -= v[j] * v[l] / bb;
                H[j][l] += h;
            }
    }
    for (int j = 0; j < nx; j++)
        for (int l = 0; l < j; l++)
            H[j][l] = H[l][j];
    *rr = fmax(*rr, 0.0);
}

/* H = R^T R (upper R) and z = R^-T g; a pivot that vanishes against hdiag (a
 * direction the data does not see) gives a zero row. */
void bf_affine_chol(int nx, double H[][AF_NP], const double *g, const double *hdiag,
                    double R[][AF_NP], double *z)
{
    memset(R, 0, sizeof(double) * AF_NP * AF_NP);
    for (int k = 0; k < nx; k++) {
        double piv = H[k][k];
        for (int i = 0; i < k; i++)
            piv -= R[i][k] * R[i][k];
        z[k] = 0.0;
        if (!(piv > 1e-13 * hdiag[k]) || !(piv > 0))
            continue;
        R[k][k] = sqrt(piv);
        for (int j = k + 1; j < nx; j++) {
            double v = H[k][j];
            for (int i = 0; i < k; i++)
                v -= R[i][k] * R[i][j];
            R[k][j] = v / R[k][k];
        }
        double v = g[k];
        for (int i = 0; i < k; i++)
            v -= R[i][k] * z[i];
        z[k] = v / R[k][k];
    }
}
