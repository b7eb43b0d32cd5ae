/* SPDX-License-Identifier: MIT */
/*
 * bf_lobe.h -- the lobe of the model a data pass is for, for the C library and
 * the OpenCL kernel alike.  Which function that is comes from the model
 * registry (src/lib/registry.c):
 *   kernel  built for one model with -DBF_LOBE=bf_lobe_<model> and, for a lobe
 *           with forward differences of its own, -DBF_LOBE_FD=<function>;
 *   host    bf_lobe and bf_lobe_fd look the model up in the registry.
 * A renderer does not need this file: it calls bf_lobe_<model> (bf_models.h,
 * bf_he.h) directly.
 */
#ifndef BF_LOBE_H
#define BF_LOBE_H

#ifndef __OPENCL_VERSION__
#include "bf_models.h"
#include "bf_he.h"
#endif

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

/* He's forward differences with its member of the state (NULL: no memo). */
BF_FN void bf_lobe_fd_he(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                         BF_REAL *K0, BF_REAL (*Kj)[3], bf_lobe_state *st)
{
    bf_he_fd(g, p, np, lam, K0, Kj, st ? &st->he : (bf_he_memo *)0);
}

/* bf_lobe_fd: K at p[0] and at the np forward-difference neighbours p[1..np]
 * of a data pass (see bf_pass.h): K0[c] = K(p[0]) as the model's
 * bf_lobe_<model> gives it, Kj[j][c] ~ K(p[1 + j]).  A lobe without forward
 * differences of its own is evaluated at each point; He sums its series once
 * and carries it to the neighbours to first order in its log, and with a
 * state (NULL: none) reuses the previous vector's series where g and a are
 * unchanged (bf_he_fd; K0 is then bf_he's to ~1e-13). */
#ifdef __OPENCL_VERSION__

#ifndef BF_LOBE
#error "build with -DBF_LOBE=bf_lobe_<model>"
#endif

BF_FN void bf_lobe_fd(int model, const bf_geom *g, const double (*p)[3], int np,
                      const double *lam, BF_REAL *K0, BF_REAL (*Kj)[3], bf_lobe_state *st)
{
    (void)model;
#ifdef BF_LOBE_FD
    BF_LOBE_FD(g, p, np, lam, K0, Kj, st);
#else
    (void)st;
    BF_LOBE(g, p[0], lam, K0);
    for (int j = 0; j < np; j++)
        BF_LOBE(g, p[1 + j], lam, Kj[j]);
#endif
}

#else /* host: src/lib/registry.c */

/* K per channel into K[0..2] of model `model` (an id the caller checked) for
 * lobe parameters p (paper units) and wavelengths lam (um). */
void bf_lobe(int model, const bf_geom *g, const double *p, const double *lam, double *K);
void bf_lobe_fd(int model, const bf_geom *g, const double (*p)[3], int np, const double *lam,
                double *K0, double (*Kj)[3], bf_lobe_state *st);

#endif

#endif /* BF_LOBE_H */
