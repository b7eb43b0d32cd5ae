/* SPDX-License-Identifier: MIT */
/* bf_he_rows.h -- the bin rows of a He data pass: K cos ti cos to per
 * (theta_h, theta_d) bin and point where the shadowing is flat, made once per
 * pass from the sample set's bin table (BF_B_*) and served to the vectors
 * whose lanes are flat. */
#ifndef BF_HE_ROWS_H
#define BF_HE_ROWS_H

#ifndef __OPENCL_VERSION__
#include "bf_he_stages.h"
#endif

/* The (theta_h, theta_d) bins of a sample set, for a lobe whose value factors
 * on a bin (He where the shadowing is flat: bf_he_bin_rows).  Bin hd = the
 * MERL bin index / 180 (0 .. BF_NHD - 1); field f of bin hd at
 * bins[f * BF_NHD_PAD + hd]: the geometry of the set's first sample in the
 * bin, BF_B_COT, the largest over the bin's samples of
 * min(cot ti, cot to) (bf_he_cot_of_cos; 0 for a bin with no sample), and
 * BF_B_COTLO, the smallest (0 for a bin with no sample).  Then the bin's
 * samples as one run of the set, for a pass that sums a bin whose every
 * sample is flat from these sums instead of its samples (bf_he_bin_whole,
 * bf_pass_whole_bins in bf_pass.h), with q = 1 / (cos ti cos to) of each sample
 * (bf_he_bin_q) and a^2 its weight: BF_B_START1, 1 + the index of its first
 * sample (0: no sample, or a set not in table order: never summed so);
 * BF_B_COTW, BF_B_COTLO where START1 > 0 and -1 elsewhere (one load tells
 * whether a bin is summed whole: bf_he_bin_whole);
 * BF_B_COUNT, its samples; BF_B_SA, BF_B_SAQ, BF_B_SAQQ, the sums of a^2,
 * a^2 q and a^2 q^2; BF_B_QBAR = SAQ / SA; BF_B_SQ1 and BF_B_SQC, the sums
 * of a^2 (q - qbar) (0 but for rounding) and a^2 (q - qbar)^2; and per
 * channel c, at BF_B_LINE + c BF_BL_FIELDS + BF_BL_*, the weighted least
 * squares line rho ~ RBAR + BETA (q - qbar) of the bin's values and the sums
 * of its residuals r: BF_BL_R = sum a^2 r (0 but for rounding),
 * BF_BL_RQC = sum a^2 r (q - qbar), BF_BL_RR = sum a^2 r^2.  A pass's bin
 * rows hold BF_BK_FIELDS fields per bin (bf_he_bin_rows). */
enum { BF_BL_RBAR, BF_BL_BETA, BF_BL_R, BF_BL_RQC, BF_BL_RR, BF_BL_FIELDS };
enum {
    BF_B_IX, BF_B_IY, BF_B_IZ, BF_B_OX, BF_B_OY, BF_B_OZ, BF_B_NH, BF_B_VH,
    BF_B_COT, BF_B_COTLO,
    BF_B_START1, BF_B_COTW, BF_B_COUNT, BF_B_SA, BF_B_SAQ, BF_B_SAQQ, BF_B_QBAR, BF_B_SQ1, BF_B_SQC,
    BF_B_LINE,
    BF_BFIELDS = BF_B_LINE + 3 * BF_BL_FIELDS
};
#define BF_NHD (90 * 90)
#define BF_NHD_PAD (BF_NHD + 8) /* a vector from the last bin stays inside */
/* A pass's rows: fields 3 j + c, K cos ti cos to at p[j] in channel c, then
 * per channel c the carry of the lanes a little rougher than flat at p[0]
 * (bf_he_near_serve): BF_HE_ROW_G + c, G = d ln K / d ln g, and
 * BF_HE_ROW_H + c, H = d^2 ln K / d (ln g)^2 (bf_he_row_carry). */
#define BF_HE_ROW_G (3 * (1 + BF_HE_NP))
#define BF_HE_ROW_H (BF_HE_ROW_G + 3)
#define BF_BK_FIELDS (BF_HE_ROW_H + 3)

/* The bin rows of a data pass (bf_he_memo.rows).  Where the shadowing is flat
 * (u >= BF_HE_U_FLAT for both directions: S = 1, sigma = sigma0), K depends
 * on the sample through its (theta_h, theta_d) bin alone (F at cos theta_d,
 * G, g and a, the rough limit) and through the factor 1 / (cos ti cos to) of
 * S(ti) S(to) / (cos ti cos to); so do the neighbours (bf_he_rough_step keeps
 * S and sigma0's place there).  A pass therefore makes, once per bin of its
 * samples and point p[0..np], the row K cos ti cos to at each point and
 * channel (bf_he_bin_rows: the bin's geometry from the sample set's bin table,
 * BF_NLANES bins at a time, so the series of distinct bins fill a vector's
 * lanes), and a vector whose lanes are all flat takes K = row / (cos ti cos to):
 * no logarithm, exponential or series.  The lanes of a bin differ from the
 * table's sample by the rounding of their directions, so a served K differs
 * from its own evaluation by that rounding's effect (tests/test_he.c,
 * pass_memo: at most ~1e-12 relative, at K ~ 1e-148 where a large a
 * amplifies it), or is 0 below the rows' floor (bf_he_row_floor). */
typedef struct bf_he_flat {
    BF_REAL ci, co;   /* cos ti, cos to, floored as bf_he_dir_make floors them */
    BF_REAL lanes;    /* 1 in a lane whose shadowing is flat at p[0]            */
    bf_he_su su;      /* the sines and u at p[0] (bf_he_flat_make only)        */
} bf_he_flat;

/* f's cosines, floored as bf_he_dir_make floors them. */
BF_FN void bf_he_flat_cos(const bf_geom *g, bf_he_flat *f)
{
    f->ci = fmax(g->iz, BF_HE_COS_MIN);
    f->co = fmax(g->oz, BF_HE_COS_MIN);
}

BF_FN void bf_he_flat_make(const bf_geom *g, double tau, double sigma0, bf_he_flat *f)
{
    bf_he_flat_cos(g, f);
    bf_he_su_make(g, tau, sigma0, &f->su);
    f->lanes = BF_SEL(BF_R(0.0), BF_R(1.0), (f->su.ui >= BF_HE_U_FLAT) && (f->su.uo >= BF_HE_U_FLAT));
}

/* bf_he_flat_make's flags for a vector whose lanes all lie in one bin hd
 * whose every sample is flat at p0 = (tau, sigma0) for certain (its
 * smallest min(cot ti, cot to), BF_B_COTLO, at least BF_HE_SURE_MARGIN above
 * the threshold 2 BF_HE_U_FLAT sigma0 / tau: the samples' own u, computed
 * from other roundings of the same cotangent, are then >= BF_HE_U_FLAT): the
 * cosines alone, with no square root or division.  0 when it cannot say (f
 * left); the lanes are then bf_he_flat_make's. */
#define BF_HE_SURE_MARGIN 1e-6

BF_FN double bf_he_cot_sure(double tau, double sigma0)
{
    return (2.0 * BF_HE_U_FLAT) * sigma0 / tau * (1.0 + BF_HE_SURE_MARGIN);
}

BF_FN int bf_he_flat_sure(const bf_geom *g, BF_GLOBAL const double *bins, BF_REAL vhd,
                          double cot_sure, bf_he_flat *f)
{
    const double hd = BF_LAST(vhd);
    if (!bins || BF_ANY(vhd != hd) || !(bins[BF_B_COTLO * BF_NHD_PAD + (int)hd] >= cot_sure))
        return 0;
    bf_he_flat_cos(g, f);
    f->lanes = BF_R(1.0);
    return 1;
}

/* 1 in the lanes whose bin hd (vhd) a pass sums whole from the bin table's
 * sums (bf_pass_whole_bins in bf_pass.h): every sample of the bin flat at
 * p0 for certain (BF_B_COTLO, as bf_he_flat_sure) and its samples one run
 * of a set in table order (BF_B_START1), so BF_B_COTW at least cot_sure.  Every such
 * sample would be served by the rows (bf_he_fd_factored: the bin's row
 * times its own q), so the bin's moments follow from its row and the sums
 * of a^2 q^k and of its values' line.  0 everywhere when the pass has no
 * rows. */
BF_FN BF_REAL bf_he_bin_whole(const bf_he_memo *m, BF_REAL vhd)
{
    if (!m->rows)
        return BF_R(0.0);
    BF_REAL cotw = BF_GATHERG(m->bins + BF_B_COTW * BF_NHD_PAD, vhd);
    return BF_SEL(BF_R(0.0), BF_R(1.0), cotw >= m->cot_sure);
}

/* The factor q = 1 / (cos ti cos to) of a vector the rows serve: its K at
 * p[j] in channel c is row[j][c] q. */
BF_FN BF_REAL bf_he_bin_q(const bf_he_flat *f)
{
    return 1.0 / (f->ci * f->co);
}

/* The cotangent of the angle whose cosine is c, with bf_he_u2's floors: a
 * lane is flat at (tau, sigma0) where min(cot ti, cot to) is at least
 * 2 BF_HE_U_FLAT sigma0 / tau (to rounding), and min(cot ti, cot to) is this
 * of min(cos ti, cos to) (to rounding: sin t = sqrt(1 - cos^2 t) for unit
 * directions).  The sample set's bin table keeps it of the largest
 * min(cos ti, cos to) over a bin (BF_B_COT). */
BF_FN BF_REAL bf_he_cot_of_cos(BF_REAL c)
{
    BF_REAL cf = fmax(c, BF_HE_COS_MIN);
    return cf / fmax(sqrt(fmax(1.0 - c * c, 0.0)), 1e-150);
}

/* K0 and Kj of a vector the rows serve whole (every lane in the bin of bk),
 * from its factor q. */
BF_FN void bf_he_bin_serve(const bf_he_memo *m, BF_REAL q, int np, BF_REAL *K0,
                           BF_REAL (*Kj)[3])
{
    for (int c = 0; c < 3; c++)
        K0[c] = m->bk[0][c] * q;
    for (int j = 0; j < np; j++)
        for (int c = 0; c < 3; c++)
            Kj[j][c] = m->bk[1 + j][c] * q;
}

/* bk from bin hd's row, for np neighbours. */
BF_FN void bf_he_bin_load(bf_he_memo *m, int hd, int np)
{
    for (int j = 0; j <= np; j++)
        for (int c = 0; c < 3; c++)
            m->bk[j][c] = m->rows[(3 * j + c) * m->nrows + hd];
    m->bgen = 1.0 + (double)hd;
}

/* 1 when the lanes' bins (m->vhd) are at most two, its first lane's and
 * its last's (a vector of the stride subset mostly spans two). */
BF_FN int bf_he_rows_two(const bf_he_memo *m)
{
    const double h0 = BF_FIRST(m->vhd), h1 = BF_LAST(m->vhd);
    return !BF_ANY((m->vhd != h0) && (m->vhd != h1));
}

/* Field f of the rows of the lanes' bins, two = bf_he_rows_two(m): where
 * they lie in two, a select between the two rows (4% faster than gathering
 * them at blue-acrylic's and brass's fits). */
BF_FN BF_REAL bf_he_row_field(const bf_he_memo *m, int f, int two)
{
    BF_GLOBAL const double *r = m->rows + f * m->nrows;
    if (two)
        return BF_SEL(BF_R(r[(int)BF_FIRST(m->vhd)]), BF_R(r[(int)BF_LAST(m->vhd)]),
                      m->vhd == BF_LAST(m->vhd));
    return BF_GATHERG(r, m->vhd);
}

/* K0 and Kj of a flat vector whose lanes lie in several bins: each lane's
 * row, times its q. */
BF_FN void bf_he_bin_gather(const bf_he_memo *m, BF_REAL q, int np, BF_REAL *K0,
                            BF_REAL (*Kj)[3])
{
    const int two = bf_he_rows_two(m);
    for (int c = 0; c < 3; c++)
        K0[c] = bf_he_row_field(m, c, two) * q;
    for (int j = 0; j < np; j++)
        for (int c = 0; c < 3; c++)
            Kj[j][c] = bf_he_row_field(m, 3 * (1 + j) + c, two) * q;
}

/* K at p[0] and at p[1..np] of the lanes of b (bf_he_fd_base's at p[0]):
 * each channel's value, then the neighbours carried from it. */
BF_FN void bf_he_fd_rest(bf_he_base *b, const double (*p)[3], int np, const double *lam,
                         const bf_he_pconst *pc, BF_REAL *K0, BF_REAL (*Kj)[3], bf_he_memo *memo)
{
    for (int ch = 0; ch < 3; ch++)
        K0[ch] = bf_he_fd_channel(b, p[0][0], lam[ch], ch, pc, memo);
    for (int j = 0; j < np; j++)
        bf_he_fd_neighbour(b, p[0], p[1 + j], lam, Kj[j]);
}

/* K at p[0] and at p[1..np] of the lanes of g, every step of bf_he_fd
 * (bf_he_pass.h) but the rows; with flat, every lane flat (bf_he_rough_make). */
BF_FN void bf_he_fd_lanes(const bf_geom *g, const double (*p)[3], int np, const double *lam,
                          const bf_he_pconst *pc, int flat, BF_REAL *K0, BF_REAL (*Kj)[3],
                          bf_he_memo *memo)
{
    bf_he_base b;
    bf_he_fd_base(g, p[0], lam, pc, flat, &b);
    bf_he_fd_rest(&b, p, np, lam, pc, K0, Kj, memo);
}

/* The lanes near the flat ones, from the rows.  Where u >= BF_HE_U_ROW in
 * both directions the shadowing S(t) = 1 - O(erfc u) is not 1 (erfc(2) =
 * 4.7e-3), but sigma's root x is often small: at He's typical start
 * (tau = 16, sigma0 = 0.5) every sample of alum-bronze's that is not flat has
 * 1 - sigma / sigma0 below 1e-7.  Such a lane's g, a, F and G are its bin's
 * at sigma0 (to the rounding of its directions, as for a flat lane) but for
 * g's relative shortfall w = x^2 / (1 + x^2) = 1 - (sigma / sigma0)^2.  With
 * w <= BF_HE_W_CARRY its K is its bin's row times
 * (S(ti) / cos ti) (S(to) / cos to), times ln K carried from the row's g to
 * g (1 - w) by the row's G and H (bf_he_row_carry): e^(G s + H s^2 / 2),
 * s = ln(1 - w) = -w (1 + w / 2) to 3e-22.  What that leaves out is the
 * next term, d^3 ln K / d(ln g)^3 s^3 / 6: in the rough limit a/g s^3 / 6;
 * in the series, where the rows keep no H, H s^2 / 2 itself, H = Var(m) - g
 * of the series' weights (|H| < 30 over the (g, a) of the MERL bins:
 * 1.5e-13 at w = 1e-7).  At p[j]: the row at p[j], the shadowing and w
 * carried there (bf_he_rough_step), G and H those at p[0] (what that leaves
 * out is ~h w dG/dp ~ 1e-13 of K, h ~ 1e-7 the step).  tests/test_he.c
 * (pass_memo) holds every served K within 2e-12 and every neighbour within
 * 1e-11 of its own evaluation.  Where sigma is sigma0 to the bit (the only
 * lanes served so before the carry), w is taken as 0 at every point.  The
 * rows are made for every bin with a sample at u >= BF_HE_U_ROW
 * (bf_he_bin_rows), so every lane served has its bin's row; below u = 2,
 * w <= 1e-7 needs tan t < 0.34 (r >= tan t erfc(u) / sqrt(8 pi), at most 3.2e-4).
 * A vector is served when all its lanes are (else 0, nothing set).
 * b needs no Fresnel (bf_he_fd_fresnel): F enters K through the rows, and
 * its zero flag (F S(ti) S(to) / (pi cos ti cos to) below BF_TINY) is never
 * set in such a lane but where F is 0 in every lane and row: with S/cos t
 * >= 0.99 (u >= 2), it needs F < 1e-307, and F >= ((n - 1) / (n + 1))^2 /
 * 2 >= 1e-37 for n in (1, 30] (n - 1 >= 2.2e-16), 0 at n = 1, where the
 * rows are 0 (bf_he_fd_channel's zero flag) and so is K.
 * At the typical start on alum-bronze's mirror set this serves all but ~0.3%
 * of the samples from the rows (docs/he-model.md). */
#define BF_HE_W_CARRY 1e-7
/* G of a bin whose rows carry no lane (bf_he_row_carry). */
#define BF_HE_ROW_NONE 1e300

/* G and H of the lanes' bins (rows fields BF_HE_ROW_G, BF_HE_ROW_H) into
 * G[3], H[3]: 0 when a lane with w > 0 lies in a bin that has none
 * (BF_HE_ROW_NONE: bf_he_row_carry), else 1. */
BF_FN int bf_he_row_carry_load(const bf_he_memo *m, BF_REAL w, BF_REAL *G, BF_REAL *H)
{
    const int two = bf_he_rows_two(m);
    for (int c = 0; c < 3; c++) {
        G[c] = bf_he_row_field(m, BF_HE_ROW_G + c, two);
        if (BF_ANY((w > 0.0) && (G[c] >= BF_HE_ROW_NONE)))
            return 0;
        H[c] = bf_he_row_field(m, BF_HE_ROW_H + c, two);
    }
    return 1;
}

/* s = ln(1 - w) of a lane's w (to 3e-22 for w <= BF_HE_W_CARRY), once a
 * point for the three channels' bf_he_row_carry_exp. */
BF_FN BF_REAL bf_he_row_carry_s(BF_REAL w)
{
    return -w * (1.0 + 0.5 * w);
}

/* e^(G s + H s^2 / 2) of channel c (see above). */
BF_FN BF_REAL bf_he_row_carry_exp(const BF_REAL *G, const BF_REAL *H, int c, BF_REAL s)
{
    return bf_he_exp_small(s * (G[c] + (0.5 * s) * H[c]));
}

BF_FN int bf_he_near_serve(bf_he_memo *m, const bf_he_base *b, const double (*p)[3], int np,
                           BF_REAL *K0, BF_REAL (*Kj)[3])
{
    const double tau = p[0][0], sigma0 = p[0][1];
    if (BF_ANY((b->r.ui < BF_HE_U_ROW) || (b->r.uo < BF_HE_U_ROW) || (b->r.w > BF_HE_W_CARRY)))
        return 0;
    BF_REAL w = BF_SEL(b->r.w, BF_R(0.0), b->r.sigma == sigma0), G[3], H[3];
    const int carry = BF_ANY(w > 0.0);
    if (carry && !bf_he_row_carry_load(m, w, G, H))
        return 0;
    bf_he_bin_gather(m, BF_R(1.0), np, K0, Kj);
    BF_REAL s = b->r.shi * b->r.sho;
    BF_REAL ls = carry ? bf_he_row_carry_s(w) : BF_R(0.0);
    for (int c = 0; c < 3; c++)
        K0[c] *= carry ? s * bf_he_row_carry_exp(G, H, c, ls) : s;
    for (int j = 0; j < np; j++) {
        bf_he_rough rj;
        bf_he_rough_step(&b->r, tau, sigma0, p[1 + j][0], p[1 + j][1], &rj);
        BF_REAL sj = rj.shi * rj.sho;
        BF_REAL lsj = carry ? bf_he_row_carry_s(BF_SEL(rj.w, BF_R(0.0), w <= 0.0)) : BF_R(0.0);
        for (int c = 0; c < 3; c++)
            Kj[j][c] *= carry ? sj * bf_he_row_carry_exp(G, H, c, lsj) : sj;
    }
    BF_HE_HIT(m->nhits);
    return 1;
}

/* The floor of a pass's rows.  At a smooth point most bins lie far from the
 * specular direction, where K is far below its value at normal incidence,
 * and summing their series was most of the rows' work (blue-acrylic at its
 * fit: half the bins, 60% of the terms).  So the rows take a lane as dead
 * (0) where its series' peak term puts less into K than e^-BF_HE_ROW_FLOOR of
 * K at normal incidence (wi = wo = N) at p0, per channel: pc->ldead =
 * max(BF_HE_LN_DEAD, ln K_normal - BF_HE_ROW_FLOOR) (BF_HE_LN_DEAD where
 * K_normal is 0), and a live lane's sum leaves out its terms below e^ldead
 * (bf_he_series_x).  A served K then differs from bf_he_pass_value's by less than
 * BF_HE_MMAX e^-BF_HE_ROW_FLOOR K_normal ~ 2.8e-10 K_normal (at most
 * BF_HE_MMAX terms left out, each below e^ldead; tests/test_he.c,
 * pass_memo), in practice by a few e^-28 K_normal ~ 1e-12 K_normal, where
 * the measured values are the diffuse part's; a pass's value moments then
 * differ from those of the samples evaluated one by one by ~1e-13 and its
 * Jacobian moments by ~2e-11 (relative; tests/test_pass.c, fold_equals_plain
 * and subset_every_8th), far below the forward differences' own error.
 * Over the 100 MERL tables (He, --scale flat) each fit's Error at its
 * parameters is within 3e-12 (relative) of the same with the floor at
 * e^-60, no fit above the stored run (bench/baseline-errors.tsv), and
 * stride-subset passes take 5-22% less; lower floors (e^-25, e^-20) move
 * the Errors by up to 1.6e-11 and 2.7e-9 (docs/he-model.md). */
#define BF_HE_ROW_FLOOR 28.0

BF_FN void bf_he_row_floor(const double *p0, const double *lam, bf_he_pconst *pc)
{
    const double p[1][3] = { { p0[0], p0[1], p0[2] } };
    bf_geom n;
    n.ix = n.iy = n.ox = n.oy = BF_R(0.0);
    n.iz = n.oz = n.nh = n.vh = BF_R(1.0);
    BF_REAL K[3];
    bf_he_fd_lanes(&n, p, 0, lam, pc, 0, K, (BF_REAL(*)[3])0, (bf_he_memo *)0);
    for (int ch = 0; ch < 3; ch++) {
        const double kn = BF_LAST(K[ch]);
        pc->ldead[ch] = kn > 0.0 ? fmax(BF_HE_LN_DEAD, log(kn) - BF_HE_ROW_FLOOR) : BF_HE_LN_DEAD;
    }
}

/* 1 when no lane of d (BF_NLANES bins' directions, bf_he_dir_make: the
 * rows then make theirs from the same d) needs its row made at p0:
 * each is either not read (live 0: no sample of its bin has u >= BF_HE_U_ROW) or dead in
 * every channel at every point for certain (0 in the rows, as
 * bf_he_fd_lanes would make it), from a bound that takes a few logarithms
 * instead of the series' search for its peak.  With F <= 1 and S = 1 (flat),
 * K's scale e^lk is at most kt^2 G / (pi cos ti cos to), and with P the
 * Poisson weights of g, V = sum_m P(m) e^(-a/m) / m is at most
 * e^(-a/M) + P(m >= M) <= e^(-a/M) + e^(M (1 + ln(g/M)) - g) for any M > g
 * (Chernoff).  With M = a / w, w = 2 + ln(kt^2 G / (pi ci co)) - ldead,
 * both are at most e^-w, so lpk + lk <= ln V + lk <= ln 2 - 2 + ldead < ldead:
 * bf_he_series_x leaves the lane dead.  Only where g < 18 / BF_HE_FD_MARGIN,
 * so that no rough limit enters the value or a neighbour. */
BF_FN int bf_he_rows_dead(const bf_he_dir *d, BF_REAL live, const double *p0, const double *lam,
                          const bf_he_pconst *pc)
{
    BF_REAL lscale = d->lg2 - log(BF_PI * (d->ci * d->co)); /* ln G / (pi ci co) */
    BF_REAL vxy2 = d->vxy2, lnv2 = d->lvxy2;
    BF_REAL s0v = p0[1] * d->vz, lns0v2 = 2.0 * log(s0v);
    BF_REAL dead = BF_SEL(BF_R(1.0), BF_R(0.0), live > 0.0);
    BF_REAL all = BF_R(1.0);
    for (int ch = 0; ch < 3; ch++) {
        const double kl = 2.0 * BF_PI / lam[ch], kt = BF_PI * p0[0] / (2.0 * lam[ch]);
        BF_REAL gg = (kl * kl) * (s0v * s0v), lng = pc->lkl2[ch] + lns0v2;
        BF_REAL aa = (4.0 * (kt * kt)) * vxy2, la = pc->l4kt2[ch] + lnv2;
        BF_REAL w = 2.0 + (lscale + pc->lkt2[ch]) - pc->ldead[ch];
        BF_REAL lw = log(fmax(w, BF_R(1.0)));
        BF_REAL M = aa / fmax(w, BF_R(1.0)), lnM = la - lw;
        BF_REAL tail = M * (1.0 + lng - lnM) - gg;
        all = BF_SEL(BF_R(0.0), all,
                     (w >= 1.0) && (gg < BF_HE_G_LO / BF_HE_FD_MARGIN) && (M > gg) && (tail <= -w));
    }
    dead = BF_SEL(dead, BF_R(1.0), all > 0.0);
    return !BF_ANY(dead <= 0.0);
}

/* The floor of the rows at p0 (bf_he_row_floor's ldead) into floor[3]: the
 * pass driver makes it once a pass on the host (in every work-item of the
 * kernel it would cost ~4% of a smooth subset pass: K at normal incidence). */
BF_FN void bf_he_row_floors(const double *p0, const double *lam, double *floor)
{
    bf_he_pconst pc;
    bf_he_pconst_make(p0[0], lam, &pc);
    bf_he_row_floor(p0, lam, &pc);
    for (int ch = 0; ch < 3; ch++)
        floor[ch] = pc.ldead[ch];
}

/* G = d ln K / d ln g and H = d^2 ln K / d(ln g)^2 of a flat lane at p0
 * in channel ch (wavelength lam), b made by bf_he_fd_base_dir with flat and
 * K0 its value (bf_he_fd_rest), for bf_he_near_serve's carry: in the
 * series (g below 18) G = g dlnV/dg and H 0 (H itself is the carry's
 * remainder there: bf_he_near_serve), in the rough limit (g above 19,
 * ln K = lk - a/g - ln g) G = a/g - 1 and H = -a/g; 0 where K0 is 0 (no
 * carry changes a 0).  Within BF_HE_CARRY_EDGE (relative) of 18 and 19
 * and between them, where the blend's slope jumps, G = BF_HE_ROW_NONE: no
 * lane with w > 0 is carried from there, so that no carry (at p[0], or at
 * a neighbour's g_ref, which a step of ~1e-7 moves by ~2e-7) crosses a
 * jump. */
#define BF_HE_CARRY_EDGE 1e-6

BF_FN void bf_he_row_carry(const bf_he_base *b, BF_REAL K0, double lam, int ch, BF_REAL *G,
                           BF_REAL *H)
{
    const double kl = 2.0 * BF_PI / lam;
    BF_REAL gg = (kl * kl) * (b->sv * b->sv), ag = b->a0[ch] / gg;
    BF_REAL series = BF_SEL(BF_R(0.0), BF_R(1.0), gg < BF_HE_G_LO * (1.0 - BF_HE_CARRY_EDGE));
    BF_REAL limit = BF_SEL(BF_R(0.0), BF_R(1.0), gg > BF_HE_G_HI * (1.0 + BF_HE_CARRY_EDGE));
    *G = BF_SEL(BF_SEL(BF_R(BF_HE_ROW_NONE), ag - 1.0, limit > 0.0), gg * b->Vg[ch], series > 0.0);
    *H = BF_SEL(BF_R(0.0), -ag, limit > 0.0);
    *G = BF_SEL(*G, BF_R(0.0), K0 == 0.0);
    *H = BF_SEL(*H, BF_R(0.0), K0 == 0.0);
}

/* A pass's rows (see above) of the bins h0 .. h1 of the bin table `bins`
 * (BF_B_* above) at p[0..np]: field f = 3 j + c (K cos ti cos to at p[j] in
 * channel c) of bin hd into rows[f * nrows + hd], BF_NLANES bins at a time
 * (so also bins up to h1 + BF_NLANES - 1), with the floor bf_he_row_floors
 * made (floor[3]).  A run of bins where no sample has u >= BF_HE_U_ROW at
 * p[0] (BF_B_COT, with a margin for rounding) is skipped: no lane of theirs
 * reads its row (neither a flat one nor one near them: bf_he_near_serve).
 * Rows made from u >= BF_HE_U_ROW instead of BF_HE_U_FLAT: at alum-bronze's
 * He fit a pass takes the same time either way. */
BF_FN void bf_he_bin_rows(BF_GLOBAL const double *bins, int h0, int h1, const double (*p)[3],
                          int np, const double *lam, const double *floor, BF_GLOBAL double *rows,
                          int nrows)
{
    const double cot_row = (2.0 * BF_HE_U_ROW) * p[0][1] / p[0][0] * (1.0 - 1e-9);
    bf_he_pconst pc;
    bf_he_pconst_make(p[0][0], lam, &pc);
    for (int ch = 0; ch < 3; ch++)
        pc.ldead[ch] = floor[ch];
    for (int h = h0; h <= h1; h += BF_NLANES) {
        BF_REAL cot = BF_LOADG(bins + BF_B_COT * BF_NHD_PAD + h);
        BF_REAL live = BF_SEL(BF_R(0.0), BF_R(1.0), cot >= cot_row);
        if (!BF_ANY(live > 0.0))
            continue;
        bf_geom g;
        g.ix = BF_LOADG(bins + BF_B_IX * BF_NHD_PAD + h);
        g.iy = BF_LOADG(bins + BF_B_IY * BF_NHD_PAD + h);
        g.iz = BF_LOADG(bins + BF_B_IZ * BF_NHD_PAD + h);
        g.ox = BF_LOADG(bins + BF_B_OX * BF_NHD_PAD + h);
        g.oy = BF_LOADG(bins + BF_B_OY * BF_NHD_PAD + h);
        g.oz = BF_LOADG(bins + BF_B_OZ * BF_NHD_PAD + h);
        g.nh = BF_LOADG(bins + BF_B_NH * BF_NHD_PAD + h);
        g.vh = BF_LOADG(bins + BF_B_VH * BF_NHD_PAD + h);
        BF_REAL K0[3], Kj[BF_HE_NP][3];
        bf_he_dir d;
        bf_he_dir_make(&g, &d);
        if (bf_he_rows_dead(&d, live, p[0], lam, &pc)) {
            for (int f = 0; f < 3 * (1 + np); f++)
                BF_STORE(BF_R(0.0), rows + f * nrows + h);
            for (int c = 0; c < 3; c++) {
                BF_STORE(BF_R(0.0), rows + (BF_HE_ROW_G + c) * nrows + h);
                BF_STORE(BF_R(0.0), rows + (BF_HE_ROW_H + c) * nrows + h);
            }
            continue;
        }
        bf_he_base b; /* bf_he_fd_lanes with flat, from d */
        bf_he_fd_base_dir(&d, p[0], lam, &pc, 1, &b);
        bf_he_fd_rest(&b, p, np, lam, &pc, K0, Kj, (bf_he_memo *)0);
        BF_REAL cc = fmax(g.iz, BF_HE_COS_MIN) * fmax(g.oz, BF_HE_COS_MIN);
        for (int c = 0; c < 3; c++) {
            BF_REAL G, H;
            bf_he_row_carry(&b, K0[c], lam[c], c, &G, &H);
            BF_STORE(K0[c] * cc, rows + c * nrows + h);
            BF_STORE(G, rows + (BF_HE_ROW_G + c) * nrows + h);
            BF_STORE(H, rows + (BF_HE_ROW_H + c) * nrows + h);
        }
        for (int j = 0; j < np; j++)
            for (int c = 0; c < 3; c++)
                BF_STORE(Kj[j][c] * cc, rows + (3 * (1 + j) + c) * nrows + h);
    }
}

#endif /* BF_HE_ROWS_H */
