/* SPDX-License-Identifier: MIT */
/*
 * bf_he_pass.h -- He's lobe in a data pass: K at a pass's point and its
 * forward-difference neighbours (bf_he_fd), the same K as the model's
 * bf_he (bf_he_model.h: the equations) computed with the pass machinery.
 * Only the data pass includes it (through bf_lobe_pass.h); brdffit_eval and
 * the renders do not.
 *
 * Numerics.  The terms T_m of the series D (Eq. 78) are log-concave in m
 * (their log ratios decrease), so per lane the peak m* is found exactly (a
 * Newton estimate, then a step or two on the sign of the log ratio, from a
 * table of ln(m m!): bf_he_dlog).  K is computed as
 * e^(ln T_m* + ln(pref F G S / (pi cos cos))) sum_m T_m / T_m*, so nothing
 * underflows unless K does: a lane whose peak term puts less than e^-760 into
 * K is 0 without summing (in a pass's bin rows, a higher floor:
 * bf_he_row_floor); the sum starts where the terms are within e^-40
 * (BF_HE_HEAD) of the peak and stops, past the peak, once a term is below
 * 1e-12 of the sum (relative error ~1e-12; 3e-13 measured against 40-digit
 * sums), in the bin rows also where the terms fall below their floor.  The cap
 * m <= BF_HE_MMAX = 400 is exact: for g < 19, T_m < Poisson(m; 19) < e^-840
 * beyond it, and the scale factor is below e^45 for directions up to 89.9 deg
 * (and far beyond), so no later term reaches the double range.  The peak can
 * lie far beyond the ~80 terms a = 0 needs (m* = 166 at g = 16.3, a = 6.4e4,
 * K = 2e-269: a row of he-reference.tsv).  A data pass takes the series of
 * most lanes from a table of its terms made once per (theta_h, theta_d) bin
 * (bf_he_tab), to the same accuracy.
 *
 * The machinery, each file including the one before (the kernel
 * concatenates them in this order, after bf_he_model.h and bf_lobe.h: the
 * Makefile's KERNEL_SOURCES):
 *   bf_he_surface.h  both directions' u, the shadowing S and sigma's root
 *   bf_he_series.h   the series D around its peak, and the rough limit
 *   bf_he_tab.h      a bin's series as a polynomial in g, a point's series
 *   bf_he_memo.h     what a pass keeps from vector to vector; a lane's series
 *   bf_he_stages.h   K in stages, and the neighbours of a forward difference
 *   bf_he_rows.h     the bin rows of a pass where the shadowing is flat
 *   bf_he_pass.h     (this file) K and its neighbours for a pass: rows or
 *                    stages (bf_he_fd)
 */
#ifndef BF_HE_PASS_H
#define BF_HE_PASS_H

#ifndef __OPENCL_VERSION__
#include "bf_he_rows.h"
#endif

/* K at p[0] and at the np <= 3 forward-difference neighbours p[1..np] (each
 * p[j] = (tau, sigma0, n), a small step from p[0]) for one data pass:
 * K0[c] = bf_he_pass_value(p[0]) bit for bit without a memo (to ~1e-12 with one), and
 * bf_he(p[0]) (the model) to ~1e-12 (tests/test_he.c, model_equals_pass),
 * Kj[j-1][c] = bf_he_pass_value(p[j]) to second order in the step.
 *
 * All the transcendental work is done once, at p[0]: the series (most of
 * it) with the partials of its log in g and a, the shadowing and sigma with
 * theirs in u.  A neighbour is then a few dozen flops: u' exactly, S, erfc
 * and x (hence sigma, g') to first order (bf_he_rough_step), F and a'
 * exactly, the scale e^(lk' - lk) = (fs' / fs)(kt' / kt)^2 exactly, and
 *     series  V' = e^(lk' - lk) V e^x,  x = dlnV/dg (g' - g) + dlnV/da (a' - a)
 *             (e^x by its cubic: |x| is ~1e-4 at most where it matters),
 *     limit   L' = L e^(lk' - lk) e^(a/g - a'/g') g / g'   (the exp by its
 *             Taylor polynomial of degree 5 where every lane's exponent is
 *             within 1e-3 of 0, to 1.4e-21: bf_he_exp_small; else exp),
 * blended by the weight t(g') as bf_he_dblend blends the value; a step in
 * n alone scales K by F' / F.  The series is carried in its log because ln V is
 * close to linear in g and a where V itself is not (d lnV / d ln tau reaches
 * ~1e3 on smooth materials).  The remainder is O(h^2) in the relative step
 * h ~ 1e-7: of the order of the forward difference's own truncation error
 * (tests/test_he.c measures it: the difference quotients agree with those
 * of exact evaluations to 1.4e-5 of their size).  A lane whose series is
 * dead (0) at p[0] stays 0, and one with F S = 0 (n = 1) stays 0.  The
 * series is also summed for g in [19, 19 m) and the limit made for g in
 * (18 / m, 18], m = BF_HE_FD_MARGIN, where the value does not use them, so
 * that a step across 19 or 18 is covered; a step of 1e-3 relative in g
 * would not be.  np = 0 with no memo is bf_he_pass_value.  The memos: see bf_he_memo
 * (the series) and bf_he_flat (the bin rows).
 *
 * In steps: with a memo that has rows, a vector whose lanes are all flat
 * takes them (bf_he_bin_serve when its lanes share a bin, else
 * bf_he_bin_gather); else bf_he_fd_surface (the directions but their
 * logarithms and c, S, sigma: the sines and u from the test for flat
 * lanes), and a vector whose lanes are all flat or near them (sigma =
 * sigma0, or w = 1 - (sigma / sigma0)^2 <= 1e-7) takes the rows times its
 * own shadowing (and the carry of ln K to its g: bf_he_near_serve; no
 * logarithm or Fresnel taken); else F (bf_he_fd_fresnel), the directions'
 * logarithms and the rough limit (bf_he_dir_logs, bf_he_fd_scale), then
 * bf_he_fd_rest: bf_he_fd_channel per channel (the value, through
 * bf_he_dblend), bf_he_fd_neighbour per neighbour (with no rows:
 * bf_he_fd_lanes, the same: bf_he_fd_base, then bf_he_fd_rest).
 *
 * bf_he_fd_factored is bf_he_fd, and with q != NULL it returns a vector
 * whose lanes share a bin's row in factored form: 1, and *q (bf_he_bin_q),
 * K0 and Kj left unset, its K at p[j] in channel c being memo->bk[j][c] * q
 * (bk changes only with memo->bgen; bf_fold in bf_pass.h sums such vectors
 * per bin).  Otherwise (0) K0 and Kj are set as bf_he_fd sets them. */
BF_FN int bf_he_fd_factored(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                            BF_REAL *K0, BF_REAL (*Kj)[3], bf_he_memo *memo, BF_REAL *q)
{
    bf_he_pconst own, *pc = memo ? &memo->pc : &own;
    if (!memo || !bf_he_pconst_for(pc, p[0][0], lam))
        bf_he_pconst_make(p[0][0], lam, pc);
    if (memo && memo->rows) {
        bf_he_flat fl;
        if (bf_he_flat_sure(g, memo->bins, memo->vhd, memo->cot_sure, &fl))
            BF_HE_HIT(memo->bsure);
        else
            bf_he_flat_make(g, p[0][0], p[0][1], &fl);
        if (!BF_ANY(fl.lanes <= 0.0)) {
            BF_REAL qv = bf_he_bin_q(&fl);
            const double hd = BF_LAST(memo->vhd);
            BF_HE_HIT(memo->bhits);
            if (BF_ANY(memo->vhd != hd)) {
                bf_he_bin_gather(memo, qv, np, K0, Kj);
                return 0;
            }
            if (memo->bgen != 1.0 + hd)
                bf_he_bin_load(memo, (int)hd, np);
            if (q)
                *q = qv;
            else
                bf_he_bin_serve(memo, qv, np, K0, Kj);
            return 1;
        }
        bf_he_base b;
        bf_he_fd_surface(g, p[0], 0, &fl.su, &b); /* fl made by bf_he_flat_make */
        if (!bf_he_near_serve(memo, &b, p, np, K0, Kj)) {
            bf_he_fd_fresnel(p[0], &b);
            bf_he_dir_logs(&b.d);
            bf_he_fd_scale(p[0], lam, pc, &b);
            bf_he_fd_rest(&b, p, np, lam, pc, K0, Kj, memo);
        }
        return 0;
    }
    bf_he_fd_lanes(g, p, np, lam, pc, 0, K0, Kj, memo);
    return 0;
}

/* K0 and Kj always set (the factored vectors' too). */
BF_FN void bf_he_fd(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                    BF_REAL *K0, BF_REAL (*Kj)[3], bf_he_memo *memo)
{
    bf_he_fd_factored(g, p, np, lam, K0, Kj, memo, (BF_REAL *)0);
}

/* K per channel into K[0..2] at wavelengths lam[0..2] as a pass without
 * neighbours or memo computes it: bf_he_fd's value (bf_he is the model's). */
BF_FN void bf_he_pass_value(const bf_geom *g, double tau, double sigma0, double n,
                            const double *lam, BF_REAL *K)
{
    const double p[1][3] = { { tau, sigma0, n } };
    bf_he_fd(g, p, 0, lam, K, (BF_REAL(*)[3])0, (bf_he_memo *)0);
}

#endif /* BF_HE_PASS_H */
