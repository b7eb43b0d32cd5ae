/* SPDX-License-Identifier: MIT */
/* bf_he_memo.h -- what a data pass keeps from one sample vector to the
 * next for the He lobe (bf_he_memo: the point's constants, the last lane's
 * series, the bin tables and rows), and the series of a lane through it
 * (bf_he_series_memo, bf_he_dblend). */
#ifndef BF_HE_MEMO_H
#define BF_HE_MEMO_H

#ifndef __OPENCL_VERSION__
#include "bf_he_tab.h"
#endif

/* The memo of a data pass (bf_he_series_memo, through bf_he_fd).  A data pass
 * walks the samples in table order, so consecutive vectors mostly share
 * theta_h and theta_d and differ in phi_d alone; g and a depend on phi_d
 * only through sigma, which is sigma0 exactly wherever r <= 1e-9 (a smooth
 * surface away from grazing).  There every lane of a vector has the (g, a) of
 * the previous vector's last lane to rounding.  With memo != NULL (a pass
 * keeps one per work-item, zeroed at its start, and gives it vector after
 * vector), the lanes of a channel whose g and a are within BF_HE_MEMO_TOL
 * (relative) of the memo's do not sum the series (only the other lanes do,
 * if any): they take the memo's lpk, sum and partials and carry them to
 * their own g, a to first order in ln V, as bf_he_fd carries its neighbours
 * (the remainder is below (m* 1e-12)^2 ~ 1e-19 relative; the carry itself is
 * ~1e-13).  Values then agree with bf_he_pass_value to ~1e-13 relative, and depend on
 * where a work-item's run of samples starts only at that level.  A channel
 * whose last lane sums its series leaves that lane in the memo; a memo whose
 * lane was dead (too small to sum) serves only lanes dead as well.  (A vector
 * that straddles two bins thus sums one bin's window, not the union of
 * both.) */
#define BF_HE_FD_MARGIN 1.001
#define BF_HE_MEMO_TOL 1e-12

/* The memo's hit counters (hits, thits, bhits, nhits, bsure) say which
 * machinery served a pass's lanes; only tests read them, so they count only
 * where BF_HE_COUNT_HITS is defined before this file is included (the
 * fields are there either way). */
#ifdef BF_HE_COUNT_HITS
#define BF_HE_HIT(counter) ((counter) += 1.0)
#else
#define BF_HE_HIT(counter) ((void)0)
#endif

/* The logs of the constants of a pass's point that bf_he_fd_base and
 * bf_he_fd_channel use (scalar logs cost as much as the vector work of a
 * sample vector): made for (tau, lam[0..2]) = key, once per run of a pass
 * through the memo (key[0] = 0: not made yet; tau >= 1). */
typedef struct bf_he_pconst {
    double key[4];
    double lkl2[3], lkt2[3], l4kt2[3]; /* ln (2 pi / lam)^2, ln kt^2, ln 4 kt^2, kt = pi tau / (2 lam) */
    double ltau16;                     /* ln (tau^2 / 16)                     */
    double ldead[3];                   /* bf_he_series_x's ldead per channel: BF_HE_LN_DEAD,
                                        * raised in the bin rows (bf_he_row_floor) */
} bf_he_pconst;

BF_FN void bf_he_pconst_make(double tau, const double *lam, bf_he_pconst *pc)
{
    pc->key[0] = tau;
    for (int ch = 0; ch < 3; ch++) {
        double kl = 2.0 * BF_PI / lam[ch];
        double kt = BF_PI * tau / (2.0 * lam[ch]);
        pc->key[1 + ch] = lam[ch];
        pc->lkl2[ch] = log(kl * kl);
        pc->lkt2[ch] = log(kt * kt);
        pc->l4kt2[ch] = log(4.0 * (kt * kt));
    }
    pc->ltau16 = log(tau * tau / 16.0);
    for (int ch = 0; ch < 3; ch++)
        pc->ldead[ch] = BF_HE_LN_DEAD;
}

BF_FN int bf_he_pconst_for(const bf_he_pconst *pc, double tau, const double *lam)
{
    return pc->key[0] == tau && pc->key[1] == lam[0] && pc->key[2] == lam[1] && pc->key[3] == lam[2];
}

/* He's lobe parameters: the forward-difference neighbours of a pass, at most. */
#define BF_HE_NP 3

typedef struct bf_he_memo {
    bf_he_pconst pc;            /* the point's constants (see above)        */
    double g[3], a[3];          /* the (clamped) g and a of the stored lane */
    double ok[3];               /* 1: a lane is stored (active, peak found) */
    double lpk[3], sum[3];      /* its series e^lpk sum (sum 0: dead)       */
    double vg[3], va[3];        /* the partials of ln V there               */
    double hits;                /* channel-vectors served wholly by the memo */
    /* the bin rows (bf_he_bin_rows; rows NULL: none): a flat lane's
     * K cos ti cos to per bin, field f of bin hd at rows[f * nrows + hd] */
    BF_GLOBAL const double *rows;
    int nrows;
    /* the bin table the rows were made from, and the least BF_B_COTLO of a
     * bin whose samples are all flat at p0 for certain (bf_he_flat_sure) */
    BF_GLOBAL const double *bins;
    double cot_sure;
    BF_REAL vhd;                /* the bins hd of the vector's lanes         */
    double bk[1 + BF_HE_NP][3]; /* the row of the last bin served whole      */
    double bhits;               /* vectors served by the rows                */
    double nhits;               /* vectors served by the rows and their own
                                 * shadowing (bf_he_near_serve)             */
    double bsure;               /* of them, found flat by the bin table      */
    double bgen;                /* 1 + the bin of bk (0: none)               */
    /* the series tables (bf_he_tab), one per channel */
    bf_he_tab tab[3];
    double thits;               /* channel-vectors whose lanes that needed a
                                 * series all took it from a table          */
} bf_he_memo;

BF_FN void bf_he_memo_clear(bf_he_memo *m)
{
    for (int c = 0; c < 3; c++) {
        m->pc.key[1 + c] = m->pc.lkl2[c] = m->pc.lkt2[c] = m->pc.l4kt2[c] = 0.0;
    }
    m->pc.key[0] = m->pc.ltau16 = 0.0;
    for (int c = 0; c < 3; c++) {
        m->g[c] = m->a[c] = m->ok[c] = 0.0;
        m->lpk[c] = m->sum[c] = m->vg[c] = m->va[c] = 0.0;
    }
    m->hits = 0.0;
    m->rows = 0;
    m->nrows = 0;
    m->bins = 0;
    m->cot_sure = 0.0;
    m->vhd = BF_R(0.0);
    for (int j = 0; j <= BF_HE_NP; j++)
        for (int c = 0; c < 3; c++)
            m->bk[j][c] = 0.0;
    m->bhits = 0.0;
    m->nhits = 0.0;
    m->bsure = 0.0;
    m->bgen = 0.0;
    for (int c = 0; c < 3; c++) /* the coefficients are read only up to n */
        m->tab[c].a = m->tab[c].gref = m->tab[c].lngref = m->tab[c].igref = m->tab[c].L =
            m->tab[c].k = m->tab[c].n = m->tab[c].filled = 0.0;
    m->thits = 0.0;
}

/* The lanes of need that a pass's series tables serve, for
 * bf_he_series_memo (1 in those lanes, returned; their series into *lpk,
 * *sum, *vg, *va and *ser, bf_he_series_x's outputs): those that the
 * channel's table t covers (a vector that straddles two bins: those of the
 * bin before), then, when the last lane needs a series, the rest flat at
 * its (g, a) from that one series (bf_he_series_point), else those of its
 * bin from a table made for it. */
BF_FN BF_REAL bf_he_memo_tables(bf_he_tab *t, BF_REAL need, BF_REAL gs, BF_REAL lngs, BF_REAL aa,
                                BF_REAL lk, double ldead, BF_REAL gtop, BF_REAL *lpk,
                                BF_REAL *sum, BF_REAL *vg, BF_REAL *va, BF_REAL *ser)
{
    BF_REAL tl = bf_he_tab_lanes(t, gs, aa, need);
    if (BF_ANY(tl > 0.0))
        bf_he_tab_serve(t, tl, gs, lngs, aa, lk, ldead, lpk, sum, vg, va, ser);
    if (!(BF_LAST(need) > 0.0) || BF_LAST(tl) > 0.0)
        return tl;
    double gl = BF_LAST(gs), al = BF_LAST(aa);
    BF_REAL want = BF_SEL(need, BF_R(0.0), tl > 0.0);
    BF_REAL one = BF_SEL(BF_R(0.0), BF_R(1.0),
                         (want > 0.0) && (fabs(gs - gl) <= BF_HE_MEMO_TOL * gl)
                             && (fabs(aa - al) <= BF_HE_MEMO_TOL * al)
                             && (gs >= fmin(gtop, BF_R(BF_HE_G_HI)) * (1.0 - BF_HE_MEMO_TOL)));
    if (!BF_ANY((want > 0.0) && !(one > 0.0))) {
        bf_he_point_serve(one, gl, al, gs, aa, lk, ldead, lpk, sum, vg, va, ser);
        return BF_SEL(tl, BF_R(1.0), one > 0.0);
    }
    bf_he_tab_open(t, al, fmin(fmax(BF_LAST(gtop), gl), BF_HE_G_HI));
    BF_REAL tn = bf_he_tab_lanes(t, gs, aa, want);
    bf_he_tab_serve(t, tn, gs, lngs, aa, lk, ldead, lpk, sum, vg, va, ser);
    return BF_SEL(tl, BF_R(1.0), tn > 0.0);
}

/* The series of one channel ch for the lanes where act > 0, at gs = min(g, 19)
 * with lngs = ln gs (see bf_he_series_x for a, la, lk and deriv).  With a
 * memo (deriv must then be 1) the lanes it serves take its series carried to
 * their g and a; the others take it from the channel's series table when it
 * covers them (bf_he_tab: same a, g <= its g_ref), made anew for the last
 * lane when that lane needs a series the table does not cover (gtop: the
 * lane's g at sigma = sigma0, the largest its bin has), and sum it
 * (bf_he_series_x) only when neither serves them; the memo takes the last
 * lane if that one needed a series (see above).  With deriv, the partials of
 * ln V go to *vg_out and *va_out (0 where V is 0). */
BF_FN BF_REAL bf_he_series_memo(BF_REAL gs, BF_REAL lngs, BF_REAL aa, BF_REAL la, BF_REAL lk,
                                double ldead, BF_REAL gtop, BF_REAL act, int deriv,
                                bf_he_memo *memo, int ch, BF_REAL *vg_out, BF_REAL *va_out)
{
    /* hl: the lanes the memo serves; the others (that need it) sum */
    BF_REAL hl = BF_R(0.0), x = BF_R(0.0);
    if (memo && memo->ok[ch] > 0.0) {
        x = memo->vg[ch] * (gs - memo->g[ch]) + memo->va[ch] * (aa - memo->a[ch]);
        /* a memo that was not summed (dead) serves only lanes dead as well */
        hl = BF_SEL(BF_R(0.0), BF_R(1.0),
                    (fabs(gs - memo->g[ch]) <= BF_HE_MEMO_TOL * memo->g[ch])
                        && (fabs(aa - memo->a[ch]) <= BF_HE_MEMO_TOL * memo->a[ch])
                        && ((memo->sum[ch] > 0.0)
                            || (memo->lpk[ch] + lk < ldead)));
    }
    BF_REAL need = BF_SEL(act, BF_R(0.0), hl > 0.0);
    /* the served lanes' values, before the memo takes a new lane */
    BF_REAL hser = BF_R(0.0);
    double hvg = 0.0, hva = 0.0;
    if (BF_ANY(hl > 0.0)) {
        hser = memo->sum[ch] * exp(fmin(memo->lpk[ch] + lk + x, BF_R(700.0)));
        hser = BF_SEL(BF_R(0.0), hser, act > 0.0);
        hvg = memo->vg[ch];
        hva = memo->va[ch];
    }
    BF_REAL ser = BF_R(0.0), vg = BF_R(0.0), va = BF_R(0.0);
    if (BF_ANY(need > 0.0)) {
        BF_REAL lpk = BF_R(0.0), sum = BF_R(0.0), tl = BF_R(0.0);
        if (memo)
            tl = bf_he_memo_tables(&memo->tab[ch], need, gs, lngs, aa, lk, ldead, gtop, &lpk, &sum,
                                   &vg, &va, &ser);
        BF_REAL sx = BF_SEL(need, BF_R(0.0), tl > 0.0); /* the lanes that sum */
        if (BF_ANY(sx > 0.0)) {
            BF_REAL xlpk = BF_R(0.0), xsum = BF_R(0.0), xvg = BF_R(0.0), xva = BF_R(0.0);
            BF_REAL xser = bf_he_series_x(gs, lngs, aa, la, lk, ldead, sx, deriv, &xvg, &xva,
                                          &xlpk, &xsum);
            lpk = BF_SEL(lpk, xlpk, sx > 0.0);
            sum = BF_SEL(sum, xsum, sx > 0.0);
            vg = BF_SEL(vg, xvg, sx > 0.0);
            va = BF_SEL(va, xva, sx > 0.0);
            ser = BF_SEL(ser, xser, sx > 0.0);
        } else if (memo) {
            BF_HE_HIT(memo->thits);
        }
        if (memo && BF_LAST(need) > 0.0) {
            memo->ok[ch] = 1.0;
            memo->g[ch] = BF_LAST(gs);
            memo->a[ch] = BF_LAST(aa);
            memo->lpk[ch] = BF_LAST(lpk);
            memo->sum[ch] = BF_LAST(sum);
            memo->vg[ch] = BF_LAST(vg);
            memo->va[ch] = BF_LAST(va);
        }
    } else if (memo && BF_ANY(act > 0.0)) {
        BF_HE_HIT(memo->hits);
    }
    if (BF_ANY(hl > 0.0)) {
        ser = BF_SEL(ser, hser, hl > 0.0);
        vg = BF_SEL(vg, BF_R(hvg), hl > 0.0);
        va = BF_SEL(va, BF_R(hva), hl > 0.0);
    }
    *vg_out = vg;
    *va_out = va;
    return ser;
}

/* e^lk D / (pi tau / (2 lam))^2 of one channel from g > 0 with lng = ln g and
 * a >= 0 with la ~ ln a: the series below g = 18, the rough limit lim (the
 * caller's e^(lk - a/g) / g, used where g > 18) above 19, linear in g in
 * between: the one place the two are blended (bf_he_D_pass and bf_he_fd
 * both come here).  The series is summed, at min(g, 19), where g < 19 margin:
 * margin 1 for a value alone, BF_HE_FD_MARGIN when bf_he_fd will carry
 * neighbours from it.  *V gets the series; memo, ch, deriv, *vg, *va: see
 * bf_he_series_memo.  Finite wherever e^lk D is (lanes on one side never see
 * the other side's value). */
BF_FN BF_REAL bf_he_dblend(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL la, BF_REAL lk,
                           double ldead, BF_REAL lim, BF_REAL gtop, double margin, int deriv,
                           bf_he_memo *memo, int ch, BF_REAL *V, BF_REAL *vg, BF_REAL *va)
{
    BF_REAL t = bf_he_blend_t(g);
    BF_REAL act = BF_SEL(BF_R(0.0), BF_R(1.0), g < BF_HE_G_HI * margin);
    *V = bf_he_series_memo(fmin(g, BF_HE_G_HI), fmin(lng, BF_R(BF_HE_LN_G_HI)), a, la, lk, ldead,
                           gtop, act, deriv, memo, ch, vg, va);
    return bf_he_blend(t, *V, lim);
}

/* bf_he_dblend of one lane set with its own rough limit, no memo, no partials. */
BF_FN BF_REAL bf_he_dscaled(BF_REAL g, BF_REAL lng, BF_REAL a, BF_REAL la, BF_REAL lk)
{
    BF_REAL lim = BF_R(0.0);
    if (BF_ANY(bf_he_blend_t(g) > 0.0))
        lim = bf_he_limit(g, lng, a, lk);
    BF_REAL V, vg, va;
    return bf_he_dblend(g, lng, a, la, lk, BF_HE_LN_DEAD, lim, g, 1.0, 0, (bf_he_memo *)0, 0, &V,
                        &vg, &va);
}

/* The distribution D(g, a) of one wavelength lam (um) for tau (um), g > 0,
 * a >= 0, as a pass computes it (bf_he_D in bf_he_model.h: the model's). */
BF_FN BF_REAL bf_he_D_pass(BF_REAL g, BF_REAL a, double tau, double lam)
{
    double k = BF_PI * tau / (2.0 * lam);
    BF_REAL gs = fmax(g, BF_TINY), as = fmax(a, 0.0);
    return bf_he_dscaled(gs, log(gs), as, log(fmax(as, BF_TINY)), BF_R(log(k * k)));
}

#endif /* BF_HE_MEMO_H */
