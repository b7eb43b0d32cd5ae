/* SPDX-License-Identifier: MIT */
/* affine_reduce.c -- the affine engine's reduced problem (affine.h): from a
 * pass's sums, the best base colours and the Error, gradient and Gauss-Newton
 * matrix of the lobe coordinates with the colours solved, and its Cholesky
 * factor, which affine.c hands to cminpack. */
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
