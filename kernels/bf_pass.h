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
 * host assembles J^T J from them (src/lib/fit/problem.c).  G_j is a forward
 * difference in the fit's internal lobe coordinate u_j:
 *     G_j = (K(p_j) - K(p_0)) / h_j,  p_j = the lobe parameters at u + h_j e_j,
 * so the pass needs no knowledge of how the fit maps u to p.  (bf_lobe_fd
 * gives K(p_0) and the K(p_j); a lobe with partials dK / dp gives G_j to
 * first order, dK . (p_j - p_0) / h_j: bf_pass_partials.)
 */
#ifndef BF_PASS_H
#define BF_PASS_H

#ifndef __OPENCL_VERSION__
#include "bf_layout.h"
#include "bf_lobe_pass.h"
#endif

/* The sums of a run of factored vectors (bf_lobe_fd_factored: K_c(p_j) =
 * F[j][c] q per lane, F fixed over the run).  With G_j = gam_j q,
 * gam_j = (F[j+1] - F[0]) / h_j, every lobe moment of the run is F[0] or
 * gam times sum a^2 q or sum a^2 q^2, and every channel moment follows from
 * sum a^2 e, sum a^2 e q and sum a^2 e^2 (e = rho - d / pi - s F[0] q): 11
 * sums a vector instead of the ~70 products of bf_accumulate's general
 * path, folded into the moments once per run (bf_fold_flush).  The moments
 * agree with the general path's to rounding (a product taken as F (a^2 q)
 * instead of (F q) a^2). */
typedef struct bf_fold {
    double gen;                     /* bf_lobe_factor_gen of F (-1: no run)   */
    double F[1 + BF_MAX_NP][3];     /* the run's factors                     */
    BF_REAL sq, sqq;                /* sum a^2 q, sum a^2 q^2                 */
    BF_REAL se[3], seq[3], see[3];  /* per channel: sum a^2 e, a^2 e q, a^2 e^2 */
} bf_fold;

/* BF_PAIRS: 1 where bf_accumulate may hold a vector back (bf_pair): the
 * host's loop, and the kernel of a model with bin rows (He).  The other
 * kernels have no such state: with it, though never used, their full
 * passes take 2-4% longer (docs/performance.md). */
#if defined(__OPENCL_VERSION__) && !BF_ROWS
#define BF_PAIRS 0
#else
#define BF_PAIRS 1
#endif

/* A vector held back by bf_accumulate (a model with its own forward
 * differences: He), to be summed with the next one: its weights, K at p0,
 * G and values. */
typedef struct bf_pair {
    double held;                    /* 1: a vector is held                   */
    BF_REAL a2, K0[3], G[3][BF_MAX_NP], rho[3];
} bf_pair;

/* What a pass carries from one vector to the next of a work-item's run of
 * samples (table order): the lobe's memos, the fold of factored vectors
 * and a vector held for the next. */
typedef struct bf_pass_state {
    bf_lobe_state lobe;
    bf_fold fold;
#if BF_PAIRS
    bf_pair pair;
#endif
} bf_pass_state;

BF_FN void bf_fold_zero(bf_fold *f)
{
    f->gen = -1.0;
    f->sq = f->sqq = BF_R(0.0);
    for (int c = 0; c < 3; c++)
        f->se[c] = f->seq[c] = f->see[c] = BF_R(0.0);
}

BF_FN void bf_pass_state_clear(bf_pass_state *ps)
{
    bf_lobe_state_clear(&ps->lobe);
    bf_fold_zero(&ps->fold);
#if BF_PAIRS
    ps->pair.held = 0.0;
#endif
    for (int j = 0; j <= BF_MAX_NP; j++)
        for (int c = 0; c < 3; c++)
            ps->fold.F[j][c] = 0.0;
}

/* Add to acc the moments of samples whose K at p[j] is F[j][c] q (q per
 * sample): f0 = F[0] and gam[k][j] = (F[1 + j][k] - F[0][k]) / h_j per
 * lobe k, sq = sum a^2 q, sqq = sum a^2 q^2, and per channel se = sum a^2 e,
 * seq = sum a^2 e q, see = sum a^2 e^2.  A = sum a^2 is the caller's.  The
 * fold's flush (a run of factored vectors) and the whole bins (from the bin
 * table's sums) both end here. */
BF_FN_INLINE void bf_fold_moments(int nk, int np, const BF_REAL *f0, BF_REAL (*gam)[BF_MAX_NP],
                                  BF_REAL sq, BF_REAL sqq, const BF_REAL *se, const BF_REAL *seq,
                                  const BF_REAL *see, BF_REAL *acc)
{
    for (int k = 0; k < nk; k++) {
        BF_REAL *m = acc + bf_mom_lobe(k, np);
        m[BF_MK_SK] += f0[k] * sq;
        m[BF_MK_SKK] += (f0[k] * f0[k]) * sqq;
        for (int j = 0; j < np; j++) {
            m[bf_mk_sg(j)] += gam[k][j] * sq;
            m[bf_mk_skg(np, j)] += (f0[k] * gam[k][j]) * sqq;
            for (int l = j; l < np; l++)
                m[bf_mk_sgg(np, j, l)] += (gam[k][j] * gam[k][l]) * sqq;
        }
    }
    for (int c = 0; c < 3; c++) {
        const int k = nk > 1 ? c : 0;
        BF_REAL *m = acc + bf_mom_chan(c, nk, np);
        m[BF_MC_SE] += se[c];
        m[BF_MC_SKE] += f0[k] * seq[c];
        m[BF_MC_SEE] += see[c];
        for (int j = 0; j < np; j++)
            m[bf_mc_sge(j)] += gam[k][j] * seq[c];
    }
}

/* Add the fold's run to acc and empty it. */
BF_FN_INLINE void bf_fold_flush(bf_fold *f, int nk, int np, const bf_pass_par *pp, BF_REAL *acc)
{
    if (f->gen < 0.0)
        return;
    BF_REAL f0[3], gam[3][BF_MAX_NP];
    for (int k = 0; k < nk; k++) {
        f0[k] = BF_R(f->F[0][k]);
        for (int j = 0; j < np; j++)
            gam[k][j] = BF_R((f->F[1 + j][k] - f->F[0][k]) * pp->inv_h[j]);
    }
    bf_fold_moments(nk, np, f0, gam, f->sq, f->sqq, f->se, f->seq, f->see, acc);
    bf_fold_zero(f);
}

/* Add a factored vector (factor q per lane) to the fold, after flushing a
 * run of other factors. */
BF_FN_INLINE void bf_fold_add(bf_pass_state *ps, int nk, int np, const bf_pass_par *pp,
                              const BF_REAL *rho, BF_REAL a2, BF_REAL q, BF_REAL *acc)
{
    bf_fold *f = &ps->fold;
    double gen = bf_lobe_factor_gen(&ps->lobe);
    if (f->gen != gen) {
        bf_fold_flush(f, nk, np, pp, acc);
        f->gen = gen;
        for (int j = 0; j <= np; j++)
            for (int c = 0; c < 3; c++)
                f->F[j][c] = bf_lobe_factor(&ps->lobe, j, c);
    }
    BF_REAL aq = a2 * q;
    acc[BF_MOM_A] += a2;
    f->sq += aq;
    f->sqq += aq * q;
    for (int c = 0; c < 3; c++) {
        int k = nk > 1 ? c : 0;
        BF_REAL e = rho[c] - (pp->d[c] * (1.0 / BF_PI) + pp->s[c] * (f->F[0][k] * q));
        BF_REAL ae = a2 * e;
        f->se[c] += ae;
        f->seq[c] += ae * q;
        f->see[c] += ae * e;
    }
}

/* The whole bins (bf_lobe_bin_whole) among bins h0 .. h1 whose first
 * sample is one of i_lo .. i_hi - 1 (a work-item's run: each whole bin is
 * summed once, by the run that holds its first sample) into acc, BF_NLANES
 * bins at a time, one bin a lane: each bin's moments as bf_fold_add would
 * have summed its samples, every one factored with the bin's row F (the
 * pass's rows, bf_lobe_bin_row) and its own q, from the bin table's sums
 * (BF_B_* in bf_he_rows.h).  With e = rho - b - m q (b = d / pi,
 * m = s F[0]) and the bin's line rho = RBAR + BETA (q - qbar) + r,
 * e = r + D0 + D1 (q - qbar), D0 = RBAR - b - m qbar, D1 = BETA - m, so
 *     sum a^2 e   = R + D0 SA + D1 SQ1,
 *     sum a^2 e q = RQC + D0 SQ1 + D1 SQC + qbar sum a^2 e,
 *     sum a^2 e^2 = RR + 2 (D0 R + D1 RQC) + D0^2 SA + 2 D0 D1 SQ1 + D1^2 SQC:
 * no term cancels more than the residuals themselves do (R, SQ1 are 0 but
 * for rounding), so a bin that the model fits closely keeps its small
 * sum of a^2 e^2 (tests/test_pass.c, whole_bins_*).  The moments are then
 * bf_fold_moments', with sum a^2 q = SAQ and sum a^2 q^2 = SAQQ.  The pass
 * then leaves these bins' samples out (bf_pass_bins_skip). */
BF_FN_INLINE void bf_pass_whole_bins(int nk, int np, const bf_pass_par *pp, const bf_pass_state *ps,
                                     int h0, int h1, long i_lo, long i_hi, BF_REAL *acc)
{
    BF_GLOBAL const double *t = bf_lobe_bin_table(&ps->lobe);
    if (!t)
        return;
#define BF_TB(f) BF_LOADG(t + (f) * BF_NHD_PAD + h)
    for (int h = h0; h <= h1; h += BF_NLANES) {
        const BF_REAL vh = BF_R((double)h) + BF_IOTA;
        const BF_REAL first = BF_TB(BF_B_START1) - 1.0;
        const BF_REAL take = BF_SEL(BF_R(0.0), BF_R(1.0),
                                    (bf_lobe_bin_whole(&ps->lobe, vh) > 0.0) && (first >= (double)i_lo)
                                        && (first < (double)i_hi) && (vh <= (double)h1));
        if (!BF_ANY(take > 0.0))
            continue;
        const BF_REAL sa = BF_SEL(BF_R(0.0), BF_TB(BF_B_SA), take > 0.0);
        const BF_REAL sq = BF_SEL(BF_R(0.0), BF_TB(BF_B_SAQ), take > 0.0);
        const BF_REAL sqq = BF_SEL(BF_R(0.0), BF_TB(BF_B_SAQQ), take > 0.0);
        const BF_REAL sq1 = BF_SEL(BF_R(0.0), BF_TB(BF_B_SQ1), take > 0.0);
        const BF_REAL sqc = BF_SEL(BF_R(0.0), BF_TB(BF_B_SQC), take > 0.0);
        const BF_REAL qbar = BF_SEL(BF_R(0.0), BF_TB(BF_B_QBAR), take > 0.0);
        BF_REAL f0[3], gam[3][BF_MAX_NP];
        for (int k = 0; k < nk; k++) {
            f0[k] = BF_SEL(BF_R(0.0), bf_lobe_bin_row(&ps->lobe, 0, k, h), take > 0.0);
            for (int j = 0; j < np; j++)
                gam[k][j] = (BF_SEL(BF_R(0.0), bf_lobe_bin_row(&ps->lobe, 1 + j, k, h), take > 0.0) - f0[k])
                            * pp->inv_h[j];
        }
        acc[BF_MOM_A] += sa;
        BF_REAL se[3], seq[3], see[3];
        for (int c = 0; c < 3; c++) {
            const int k = nk > 1 ? c : 0;
            const int line = BF_B_LINE + c * BF_BL_FIELDS;
            const BF_REAL r = BF_SEL(BF_R(0.0), BF_TB(line + BF_BL_R), take > 0.0);
            const BF_REAL rqc = BF_SEL(BF_R(0.0), BF_TB(line + BF_BL_RQC), take > 0.0);
            const BF_REAL rr = BF_SEL(BF_R(0.0), BF_TB(line + BF_BL_RR), take > 0.0);
            const BF_REAL mc = pp->s[c] * f0[k];
            const BF_REAL d0 = BF_SEL(BF_R(0.0), BF_TB(line + BF_BL_RBAR), take > 0.0)
                               - pp->d[c] * (1.0 / BF_PI) - mc * qbar;
            const BF_REAL d1 = BF_SEL(BF_R(0.0), BF_TB(line + BF_BL_BETA), take > 0.0) - mc;
            se[c] = r + d0 * sa + d1 * sq1;
            seq[c] = (rqc + d0 * sq1 + d1 * sqc) + qbar * se[c];
            see[c] = rr + 2.0 * (d0 * r + d1 * rqc) + (d0 * d0) * sa + 2.0 * (d0 * d1) * sq1
                     + (d1 * d1) * sqc;
        }
        bf_fold_moments(nk, np, f0, gam, sq, sqq, se, seq, see, acc);
    }
#undef BF_TB
}

/* The lanes of the vector of samples at i0 (bins vhd) whose bin is summed
 * whole (bf_pass_whole_bins): 0 put into *keep in them (the caller then
 * gives them a^2 = 0: their terms are 0 in bf_accumulate).  Returns 1 when
 * every lane is such, with *skip the number of the next vectors that hold
 * only samples of the last lane's bin, which the caller then passes by; 0
 * otherwise. */
BF_FN_INLINE int bf_pass_bins_skip(const bf_pass_state *ps, BF_REAL vhd, long i0, BF_REAL *keep,
                                   long *skip)
{
    *skip = 0;
    const BF_REAL whole = bf_lobe_bin_whole(&ps->lobe, vhd);
    if (!BF_ANY(whole > 0.0))
        return 0;
    *keep = BF_SEL(*keep, BF_R(0.0), whole > 0.0);
    if (BF_ANY(whole <= 0.0))
        return 0;
    BF_GLOBAL const double *t = bf_lobe_bin_table(&ps->lobe);
    const int hl = (int)BF_LAST(vhd);
    const long end = (long)t[BF_B_START1 * BF_NHD_PAD + hl] - 1 + (long)t[BF_B_COUNT * BF_NHD_PAD + hl];
    const long next = end / BF_NLANES, v = i0 / BF_NLANES;
    *skip = next - v - 1 > 0 ? next - v - 1 : 0;
    return 1;
}

/* K0 and G (one lobe, nk = 1) of a lobe with partials (bf_lobe_vdk): G_j is
 * the partials' first-order step to p_j over h_j, dK . (p_j - p_0) / h_j,
 * each coefficient (p_j - p_0) / h_j a number of the pass.  It is the
 * difference quotient of the neighbours bf_lobe_fd gives, K(p_0) +
 * dK . (p_j - p_0), without their rounding: subtracting K(p_0) again lost
 * ~1e-16 K / h of each G_j (~1e-9 K at a fit's h = 1e-7).  The pass so
 * stores and reloads no neighbour (PoCL keeps stored neighbours in memory, a
 * store and a load each per vector), and a full pass of the models with
 * partials is shorter (docs/performance.md). */
BF_FN_INLINE void bf_pass_partials(int model, int np, const bf_pass_par *pp, const bf_geom *g,
                                   BF_REAL *K0, BF_REAL (*G)[BF_MAX_NP])
{
    BF_REAL dk[3];
    const BF_REAL k0 = bf_lobe_vdk(model, g, pp->p[0], dk);
    K0[0] = K0[1] = K0[2] = k0;
    BF_UNROLL3(j, if (j < np) {
        const double c0 = (pp->p[1 + j][0] - pp->p[0][0]) * pp->inv_h[j];
        const double c1 = (pp->p[1 + j][1] - pp->p[0][1]) * pp->inv_h[j];
        const double c2 = (pp->p[1 + j][2] - pp->p[0][2]) * pp->inv_h[j];
        G[0][j] = (dk[0] * c0 + dk[1] * c1) + dk[2] * c2;
    })
}

/* Add to acc[bf_nmom(nk, np)] the moments of one vector (or sample): its
 * weights a2, K at p0 (K0) and G_j per lobe, and values rho. */
BF_FN_INLINE void bf_acc_one(int nk, int np, const bf_pass_par *pp, BF_REAL a2, const BF_REAL *K0,
                             BF_REAL (*G)[BF_MAX_NP], const BF_REAL *rho, BF_REAL *acc)
{
    acc[BF_MOM_A] += a2;
    BF_UNROLL3(k, if (k < nk) {
        BF_REAL *m = acc + bf_mom_lobe(k, np);
        BF_REAL aK = a2 * K0[k];
        m[BF_MK_SK] += aK;
        m[BF_MK_SKK] += aK * K0[k];
        BF_UNROLL3(j, if (j < np) {
            BF_REAL aG = a2 * G[k][j];
            m[bf_mk_sg(j)] += aG;
            m[bf_mk_skg(np, j)] += aK * G[k][j];
            BF_UNROLL3(l, if (l >= j && l < np) m[bf_mk_sgg(np, j, l)] += aG * G[k][l];)
        })
    })
    BF_UNROLL3(c, {
        const int k = nk > 1 ? c : 0;
        BF_REAL e = rho[c] - (pp->d[c] * (1.0 / BF_PI) + pp->s[c] * K0[k]);
        BF_REAL ae = a2 * e;
        BF_REAL *m = acc + bf_mom_chan(c, nk, np);
        m[BF_MC_SE] += ae;
        m[BF_MC_SKE] += ae * K0[k];
        m[BF_MC_SEE] += ae * e;
        BF_UNROLL3(j, if (j < np) m[bf_mc_sge(j)] += ae * G[k][j];)
    })
}

/* bf_acc_one of two vectors, (a2, K0, G, rho) and (b2, L0, H, sig), each
 * moment's two terms added before acc: one load and store of each moment
 * for the two.  He's 61 moments do not fit the registers (PoCL keeps them
 * in memory, a load and a store a moment and vector); summed in pairs, a
 * full pass at its typical start (tau = 16, sigma0 = 0.5, n = 2) ~6%
 * shorter (docs/performance.md). */
BF_FN_INLINE void bf_acc_two(int nk, int np, const bf_pass_par *pp, BF_REAL a2, const BF_REAL *K0,
                             BF_REAL (*G)[BF_MAX_NP], const BF_REAL *rho, BF_REAL b2,
                             const BF_REAL *L0, BF_REAL (*H)[BF_MAX_NP], const BF_REAL *sig,
                             BF_REAL *acc)
{
    acc[BF_MOM_A] += a2 + b2;
    BF_UNROLL3(k, if (k < nk) {
        BF_REAL *m = acc + bf_mom_lobe(k, np);
        BF_REAL aK = a2 * K0[k], bK = b2 * L0[k];
        m[BF_MK_SK] += aK + bK;
        m[BF_MK_SKK] += aK * K0[k] + bK * L0[k];
        BF_UNROLL3(j, if (j < np) {
            BF_REAL aG = a2 * G[k][j], bG = b2 * H[k][j];
            m[bf_mk_sg(j)] += aG + bG;
            m[bf_mk_skg(np, j)] += aK * G[k][j] + bK * H[k][j];
            BF_UNROLL3(l, if (l >= j && l < np) m[bf_mk_sgg(np, j, l)] += aG * G[k][l] + bG * H[k][l];)
        })
    })
    BF_UNROLL3(c, {
        const int k = nk > 1 ? c : 0;
        const BF_REAL dc = pp->d[c] * (1.0 / BF_PI);
        BF_REAL e = rho[c] - (dc + pp->s[c] * K0[k]), f = sig[c] - (dc + pp->s[c] * L0[k]);
        BF_REAL ae = a2 * e, bf = b2 * f;
        BF_REAL *m = acc + bf_mom_chan(c, nk, np);
        m[BF_MC_SE] += ae + bf;
        m[BF_MC_SKE] += ae * K0[k] + bf * L0[k];
        m[BF_MC_SEE] += ae * e + bf * f;
        BF_UNROLL3(j, if (j < np) m[bf_mc_sge(j)] += ae * G[k][j] + bf * H[k][j];)
    })
}

/* Add one sample's (or one vector's) contributions to acc[bf_nmom(nk, np)].
 * ps: the state of the run of samples being walked in table order
 * (bf_pass_state_clear at its start, bf_accumulate_end at its end), or NULL.
 *
 * Written so that PoCL keeps a closed-form model's moments in registers
 * through the kernel's loop: it is always inlined there (called, with nk
 * and np as run-time arguments, the closed-form full passes take 4-32%
 * longer), its loops are written out (BF_UNROLL3: each index into acc
 * a constant; the trip counts, 1-3, left as loops), acc never leaves
 * the kernel (bf_fold_add, bf_fold_flush and bf_accumulate_end inlined) and
 * the loop calls nothing (bf_lobe_fd inlined, and the lobes it calls: a call
 * clobbers every vector register, so the sums would be stored and loaded
 * around it).  Otherwise PoCL keeps acc in memory, a load and a store per
 * moment and vector; in registers a full pass takes 4-33% less time,
 * depending on the model (docs/performance.md).  He's 61 moments do not fit the registers:
 * with a run's state, its vectors that are not folded are summed in pairs
 * (bf_acc_two; the first of a pair held in ps->pair, a last one left
 * alone summed by bf_accumulate_end). */
BF_FN_INLINE void bf_accumulate(int model, int nk, int np, const bf_pass_par *pp,
                                const bf_geom *g, const BF_REAL *rho, BF_REAL a2, BF_REAL *acc,
                                bf_pass_state *ps)
{
    BF_REAL K0[3], G[3][BF_MAX_NP];
    if (bf_lobe_fd_kind(model) == BF_FD_KIND_PARTIALS && np > 0) {
        bf_pass_partials(model, np, pp, g, K0, G);
    } else {
        BF_REAL K[BF_MAX_NP][3], q;
        if (bf_lobe_fd_factored(model, g, pp->p, np, pp->lam, K0, K,
                                ps ? &ps->lobe : (bf_lobe_state *)0, &q)) {
            bf_fold_add(ps, nk, np, pp, rho, a2, q, acc);
            return;
        }
        BF_UNROLL3(j, if (j < np) {
            BF_UNROLL3(k, if (k < nk) G[k][j] = (K[j][k] - K0[k]) * pp->inv_h[j];)
        })
    }
#if BF_PAIRS
    if (bf_lobe_has_own_fd(model) && ps) {
        bf_pair *h = &ps->pair;
        if (h->held == 0.0) {
            h->held = 1.0;
            h->a2 = a2;
            BF_UNROLL3(k, if (k < nk) {
                h->K0[k] = K0[k];
                BF_UNROLL3(j, if (j < np) h->G[k][j] = G[k][j];)
            })
            BF_UNROLL3(c, h->rho[c] = rho[c];)
            return;
        }
        h->held = 0.0;
        bf_acc_two(nk, np, pp, h->a2, h->K0, h->G, h->rho, a2, K0, G, rho, acc);
        return;
    }
#endif
    bf_acc_one(nk, np, pp, a2, K0, G, rho, acc);
}

/* The end of a run of samples: what the fold and the pair hold into acc. */
BF_FN_INLINE void bf_accumulate_end(int nk, int np, const bf_pass_par *pp, BF_REAL *acc,
                                    bf_pass_state *ps)
{
    bf_fold_flush(&ps->fold, nk, np, pp, acc);
#if BF_PAIRS
    if (ps->pair.held != 0.0) {
        bf_pair *h = &ps->pair;
        bf_acc_one(nk, np, pp, h->a2, h->K0, h->G, h->rho, acc);
        h->held = 0.0;
    }
#endif
}

#endif /* BF_PASS_H */
