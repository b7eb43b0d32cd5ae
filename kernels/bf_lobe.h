/* SPDX-License-Identifier: MIT */
/*
 * bf_lobe.h -- one entry point to the lobes of every model, for the C library
 * and the OpenCL kernel alike.  In the kernel `model` is a compile-time
 * constant (-DBF_MODEL=...), so the switch folds away.
 */
#ifndef BF_LOBE_H
#define BF_LOBE_H

#ifndef __OPENCL_VERSION__
#include "bf_models.h"
#include "bf_he.h"
#endif

/* K per channel into K[0..2] for lobe parameters p[0..2] (paper units) and,
 * for He, wavelengths lam[0..2] in micrometres. */
BF_FN void bf_lobe(int model, const bf_geom *g, const double *p, const double *lam,
                   BF_REAL *K)
{
    BF_REAL k;
    switch (model) {
    case BF_WARD: k = bf_ward(g, p[0]); break;
    case BF_WARD_DUER: k = bf_ward_duer(g, p[0]); break;
    case BF_BLINN_PHONG: k = bf_blinn_phong(g, p[0]); break;
    case BF_LAFORTUNE: k = bf_lafortune(g, p[0], p[1], p[2]); break;
    case BF_COOK_TORRANCE: k = bf_cook_torrance(g, p[0], p[1]); break;
    case BF_ASHIKHMIN_SHIRLEY: k = bf_ashikhmin_shirley(g, p[0], p[1]); break;
    case BF_HE: bf_he(g, p[0], p[1], p[2], lam, K); return;
    default: k = BF_R(0.0); break;
    }
    K[0] = k;
    K[1] = k;
    K[2] = k;
}

/* What a lobe may carry from one vector of samples to the next within a
 * data pass, which walks the samples in table order: each lobe that keeps
 * something has its member (He: the memo of its series, bf_he_fd); the other
 * lobes keep nothing.  A pass zeroes it (bf_lobe_state_clear) at the start of
 * each run of samples and hands it to bf_lobe_fd vector after vector. */
typedef struct bf_lobe_state {
    bf_he_memo he;
} bf_lobe_state;

BF_FN void bf_lobe_state_clear(bf_lobe_state *st)
{
    bf_he_memo_clear(&st->he);
}

/* K at p[0] and at the np forward-difference neighbours p[1..np] of a data
 * pass (see bf_pass.h): K0[c] = K(p[0]) as bf_lobe gives it, Kj[j][c] ~
 * K(p[1 + j]).  The closed-form lobes evaluate each point; He sums its series
 * once and carries it to the neighbours to first order in its log, and with a
 * state (NULL: none) reuses the previous vector's series where g and a are
 * unchanged (bf_he_fd; K0 is then bf_he's to ~1e-13). */
BF_FN void bf_lobe_fd(int model, const bf_geom *g, const double (*p)[3], int np,
                      const double *lam, BF_REAL *K0, BF_REAL (*Kj)[3], bf_lobe_state *st)
{
    if (model == BF_HE) {
        bf_he_fd(g, p, np, lam, K0, Kj, st ? &st->he : (bf_he_memo *)0);
        return;
    }
    bf_lobe(model, g, p[0], lam, K0);
    for (int j = 0; j < np; j++)
        bf_lobe(model, g, p[1 + j], lam, Kj[j]);
}

#endif /* BF_LOBE_H */
