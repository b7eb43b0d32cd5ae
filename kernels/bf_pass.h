/*
 * bf_pass.h -- the work of one data pass on one sample (or one vector of
 * samples), shared by the host C loop (src/lib/pass_host.c) and the OpenCL
 * kernel (bf_pass.cl).
 *
 * A fit needs, at a point (d, s, p), the normal-equation sums of the
 * weighted residuals r_sc = a_s (f_c(s) - rho_c(s)), a_s^2 = w_s cos^2 ti / (3 sum w):
 * J^T J, J^T r and r^T r.  f_c = d_c/pi + s_c K_c is linear in d and s, so
 * those sums follow from a few per-lobe "moments" (A = sum a^2, sums of a^2 K,
 * a^2 K^2, a^2 G_j, a^2 K G_j, a^2 G_j G_l with G_j = dK/du_j) and per-channel
 * residual moments (a^2 e, a^2 K e, a^2 e^2, a^2 G_j e with e = rho - f).  The
 * host assembles J^T J from them (src/lib/fit.c).  G_j is a forward
 * difference in the fit's internal lobe coordinate u_j:
 *     G_j = (K(p_j) - K(p_0)) / h_j,  p_j = the lobe parameters at u + h_j e_j,
 * so the pass needs no knowledge of how the fit maps u to p.  (bf_lobe_fd
 * gives K(p_0) and the K(p_j); for He the K(p_j) carry the series summed at
 * p_0 to first order in its log: see bf_he_fd.)
 *
 * Layout of the moments (nk = 1 lobe, or 3 for a chromatic model; np lobe
 * coordinates, 0 for a value-only pass):
 *   [0]                         A
 *   per lobe k, at 1 + k*KB:    SK, SKK, SG[np], SKG[np], SGG[j<=l] (np(np+1)/2)
 *   per channel c, at 1 + nk*KB + c*(3+np):  SE, SKE, SEE, SGE[np]
 * with KB = bf_kblk(np).
 */
#ifndef BF_PASS_H
#define BF_PASS_H

#ifndef __OPENCL_VERSION__
#include "bf_lobe.h"
#endif

/* Fields of a prepared sample set: field f of sample i is data[f * npad + i]. */
enum {
    BF_F_IX, BF_F_IY, BF_F_IZ, /* wi (toward the light), unit */
    BF_F_OX, BF_F_OY, BF_F_OZ, /* wo (toward the viewer), unit */
    BF_F_NH, BF_F_VH,          /* N.H and V.H, as bf_geom_derive gives them */
    BF_F_R, BF_F_G, BF_F_B,    /* measured value x channel scale */
    BF_F_A2,                   /* w cos^2(theta_i) / (3 sum w): the metric's weight */
    BF_NFIELDS
};

#define BF_MAX_NP 3
#define BF_NMOM_MAX 61 /* bf_nmom(3, 3) */

/* The point of a pass.  Only doubles: the same bytes in C and OpenCL C. */
typedef struct bf_pass_par {
    double d[3], s[3];            /* diffuse albedo and rho_s per channel     */
    double lam[3];                /* wavelengths (He)                         */
    double inv_h[BF_MAX_NP];      /* 1 / h_j                                  */
    double p[1 + BF_MAX_NP][3];   /* p[0]: lobe params; p[1+j]: at u + h_j e_j */
} bf_pass_par;
#define BF_PASS_PAR_DOUBLES 24

BF_FN int bf_kblk(int np)
{
    return 2 + 2 * np + np * (np + 1) / 2;
}

BF_FN int bf_nmom(int nk, int np)
{
    return 1 + nk * bf_kblk(np) + 3 * (3 + np);
}

/* Offset of lobe k's moments (SK, SKK, SG, SKG, SGG). */
BF_FN int bf_mom_lobe(int k, int np)
{
    return 1 + k * bf_kblk(np);
}

/* Offset of channel c's residual moments (SE, SKE, SEE, SGE). */
BF_FN int bf_mom_chan(int c, int nk, int np)
{
    return 1 + nk * bf_kblk(np) + c * (3 + np);
}

/* Add one sample's (or one vector's) contributions to acc[bf_nmom(nk, np)].
 * memo: the He memo of the run of samples being walked in table order
 * (zeroed at its start; see bf_he_fd), or NULL. */
BF_FN void bf_accumulate(int model, int nk, int np, const bf_pass_par *pp, const bf_geom *g,
                         const BF_REAL *rho, BF_REAL a2, BF_REAL *acc, bf_he_memo *memo)
{
    BF_REAL K0[3], K[BF_MAX_NP][3], G[3][BF_MAX_NP];
    bf_lobe_fd(model, g, pp->p, np, pp->lam, K0, K, memo);
    for (int j = 0; j < np; j++)
        for (int k = 0; k < nk; k++)
            G[k][j] = (K[j][k] - K0[k]) * pp->inv_h[j];
    acc[0] += a2;
    for (int k = 0; k < nk; k++) {
        BF_REAL *m = acc + bf_mom_lobe(k, np);
        BF_REAL aK = a2 * K0[k];
        m[0] += aK;
        m[1] += aK * K0[k];
        int t = 2 + 2 * np;
        for (int j = 0; j < np; j++) {
            BF_REAL aG = a2 * G[k][j];
            m[2 + j] += aG;
            m[2 + np + j] += aK * G[k][j];
            for (int l = j; l < np; l++)
                m[t++] += aG * G[k][l];
        }
    }
    for (int c = 0; c < 3; c++) {
        int k = nk > 1 ? c : 0;
        BF_REAL e = rho[c] - (pp->d[c] * (1.0 / BF_PI) + pp->s[c] * K0[k]);
        BF_REAL ae = a2 * e;
        BF_REAL *m = acc + bf_mom_chan(c, nk, np);
        m[0] += ae;
        m[1] += ae * K0[k];
        m[2] += ae * e;
        for (int j = 0; j < np; j++)
            m[3 + j] += ae * G[k][j];
    }
}

#endif /* BF_PASS_H */
