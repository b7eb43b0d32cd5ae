/* SPDX-License-Identifier: MIT */
/*
 * bf_pass.h -- the work of one data pass on one sample (or one vector of
 * samples), shared by the host C loop (src/lib/pass_host.c) and the OpenCL
 * kernel (bf_pass.cl).  The exchanged layout is bf_layout.h.
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
 * gives K(p_0) and the K(p_j).)
 */
#ifndef BF_PASS_H
#define BF_PASS_H

#ifndef __OPENCL_VERSION__
#include "bf_layout.h"
#include "bf_lobe.h"
#endif

/* Add one sample's (or one vector's) contributions to acc[bf_nmom(nk, np)].
 * st: the lobe state of the run of samples being walked in table order
 * (bf_lobe_state_clear at its start), or NULL. */
BF_FN void bf_accumulate(int model, int nk, int np, const bf_pass_par *pp, const bf_geom *g,
                         const BF_REAL *rho, BF_REAL a2, BF_REAL *acc, bf_lobe_state *st)
{
    BF_REAL K0[3], K[BF_MAX_NP][3], G[3][BF_MAX_NP];
    bf_lobe_fd(model, g, pp->p, np, pp->lam, K0, K, st);
    for (int j = 0; j < np; j++)
        for (int k = 0; k < nk; k++)
            G[k][j] = (K[j][k] - K0[k]) * pp->inv_h[j];
    acc[BF_MOM_A] += a2;
    for (int k = 0; k < nk; k++) {
        BF_REAL *m = acc + bf_mom_lobe(k, np);
        BF_REAL aK = a2 * K0[k];
        m[BF_MK_SK] += aK;
        m[BF_MK_SKK] += aK * K0[k];
        for (int j = 0; j < np; j++) {
            BF_REAL aG = a2 * G[k][j];
            m[bf_mk_sg(j)] += aG;
            m[bf_mk_skg(np, j)] += aK * G[k][j];
            for (int l = j; l < np; l++)
                m[bf_mk_sgg(np, j, l)] += aG * G[k][l];
        }
    }
    for (int c = 0; c < 3; c++) {
        int k = nk > 1 ? c : 0;
        BF_REAL e = rho[c] - (pp->d[c] * (1.0 / BF_PI) + pp->s[c] * K0[k]);
        BF_REAL ae = a2 * e;
        BF_REAL *m = acc + bf_mom_chan(c, nk, np);
        m[BF_MC_SE] += ae;
        m[BF_MC_SKE] += ae * K0[k];
        m[BF_MC_SEE] += ae * e;
        for (int j = 0; j < np; j++)
            m[bf_mc_sge(j)] += ae * G[k][j];
    }
}

#endif /* BF_PASS_H */
