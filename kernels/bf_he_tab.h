/* SPDX-License-Identifier: MIT */
/* bf_he_tab.h -- the series of one (theta_h, theta_d) bin as a polynomial
 * in g (bf_he_tab), made once per bin and channel in a data pass, and the
 * series at one point (bf_he_series_point) for lanes that share it. */
#ifndef BF_HE_TAB_H
#define BF_HE_TAB_H

#ifndef __OPENCL_VERSION__
#include "bf_he_series.h"
#endif

/* The series table of a bin (bf_he_tab_make, bf_he_tab_eval): a data pass
 * walks a (theta_h, theta_d) bin's samples one after another, and within a
 * bin a = pi^2 (tau/lam)^2 |v_xy|^2 is fixed (|v_xy| = 2 cos theta_d
 * sin theta_h) while g varies with sigma alone, never above the bin's g at
 * sigma = sigma0 (g_ref).  So
 *     V(g) = sum_m T_m(g) = e^(L - g) sum_{m=k}^{k+n-1} b_m y^m,  y = g / g_ref,
 * b_m = e^(ln T_m(g_ref) + g_ref - L) is a polynomial in y whose
 * coefficients are made once per bin and channel (n exps, a vector of them
 * at a time), and each
 * lane then costs n multiply-adds instead of a search for its peak and an
 * exp per term.  The table keeps c_j = b_{k+j} / (k+j), and a Horner pass
 * (bf_he_horner) gives Q = sum c_j y^j with Q' and Q''/2, from which (D = y d/dy)
 *     sum (t_m / m) = y^k Q,  sum t_m = y^k (k Q + y Q'),
 *     sum m t_m = y^k (k^2 Q + (2k+1) y Q' + y^2 Q''):
 * the value and both partials of ln V (bf_he_series_x's).  All coefficients
 * are positive and y <= 1, so Horner loses nothing to cancellation (~n ulp).
 * The window: the terms at g_ref from the first within e^-BF_HE_TAB_HEAD of
 * its largest (the ones below put less than e^-680 of g_ref's largest term
 * into any lane's sum: y >= 0 and e^(g_ref - g) <= e^19) to the last within
 * e^-BF_HE_TAB_TAIL past it (for g <= g_ref the tail falls off faster still).
 * So a lane's V agrees with bf_he_series_x's, which stops at 1e-12 of the sum,
 * to that truncation (~3e-13 measured).
 * A pass opens a bin's table (bf_he_tab_open: the window and L, a few dozen
 * scalar terms) and fills its coefficients (bf_he_tab_fill: the exps) only
 * when a lane it serves is not dead: a lane's ln V is at most
 * lpk + ln n with lpk = k ln y + L - g (y <= 1, every b_m <= 1), and a lane
 * with lpk + lk < BF_HE_LN_DEAD is 0 (bf_he_tab_serve), as bf_he_series_x
 * leaves a lane whose peak term is that small.  At a sharp lobe most bins
 * far from the specular direction are dead (alum-bronze at its fit: 38% of
 * the table terms of a pass). */
#define BF_HE_TAB_HEAD 700.0
#define BF_HE_TAB_TAIL 45.0
/* A lane is in a table's bin when its a is the table's within this (relative;
 * the lanes of one bin differ by the rounding of their directions, and the
 * first-order carry in a covers that) and its g at most g_ref within
 * BF_HE_TAB_GTOL (g_ref is the bin's g at sigma0, to rounding). */
#define BF_HE_TAB_ATOL 1e-12
#define BF_HE_TAB_GTOL 1e-9

typedef struct bf_he_tab {
    double a, gref;       /* what it was made for (n = 0: nothing yet)        */
    double lngref, igref; /* ln g_ref, 1 / g_ref                              */
    double L;             /* ln of the largest T_m(g_ref) e^g_ref             */
    double k, n;          /* the window: m = k .. k + n - 1                   */
    double filled;        /* 1: c holds the window's coefficients             */
    double c[BF_HE_MMAX + 8]; /* c[j] = b_{k+j} / (k + j); the 8 past MMAX take
                               * the last vector's overreach in the kernel    */
} bf_he_tab;

/* ln(T_m(g_ref) e^g_ref) of one term, lng = ln g_ref: what bf_he_tab_make
 * searches (concave in m, as its log ratios bf_he_dlog decrease). */
BF_FN double bf_he_tab_l(int m, double lng, double a)
{
    double dm = (double)m;
    return dm * lng - a / dm - bf_he_lkk[m];
}

/* bf_he_tab_l of the BF_NLANES terms from m0 (m0 = 1 mod BF_NLANES, so the
 * load of bf_he_lkk stays inside it: BF_HE_MMAX is a multiple of 4 and 8). */
BF_FN BF_REAL bf_he_tab_lv(int m0, double lng, double a)
{
    BF_REAL mv = (double)m0 + BF_IOTA;
    return mv * lng - a / mv - BF_LOADC(bf_he_lkk + m0);
}

/* The first m in [lo, hi) whose l_m < thr is `below` (hi if none), on a
 * side of the peak where l_m is monotone (a bisection). */
BF_FN int bf_he_tab_cross(int lo, int hi, double lng, double a, double thr, int below)
{
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if ((bf_he_tab_l(mid, lng, a) < thr) == below)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* The window of the terms l_m at a and g_ref (lng = ln g_ref): the largest
 * term l_m* = *lmax, the first term k within `head` of it and the last
 * term *mend before the first past the peak that is more than `tail`
 * below it (BF_HE_MMAX if none); a table's (see bf_he_tab) with
 * BF_HE_TAB_HEAD and BF_HE_TAB_TAIL (bf_he_tab_window).  l_m is concave in m, so each is a bisection
 * on a monotone side: about 27 scalar terms instead of every term up to the
 * tail's end (a scan of m = 1 .. ~200 at a sharp lobe's bins, which cost as
 * much as the table's exps). */
BF_FN int bf_he_window(double a, double lng, double head, double tail, double *lmax, int *mend)
{
    int lo = 1, hi = BF_HE_MMAX; /* the peak: the first m with l_(m+1) <= l_m */
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (bf_he_tab_l(mid + 1, lng, a) > bf_he_tab_l(mid, lng, a))
            lo = mid + 1;
        else
            hi = mid;
    }
    const int peak = lo;
    const double top = bf_he_tab_l(peak, lng, a);
    /* the tail: the first m past the peak below top - TAIL; the head: the
     * first m before it within HEAD of top (the peak itself if none) */
    *mend = bf_he_tab_cross(peak + 1, BF_HE_MMAX + 1, lng, a, top - tail, 1) - 1;
    *lmax = top;
    return bf_he_tab_cross(1, peak, lng, a, top - head, 0);
}

BF_FN int bf_he_tab_window(double a, double lng, double *lmax, int *mend)
{
    return bf_he_window(a, lng, BF_HE_TAB_HEAD, BF_HE_TAB_TAIL, lmax, mend);
}

/* The table for a and g_ref opened: its window (bf_he_tab_window), its
 * coefficients not made yet (bf_he_tab_fill). */
BF_FN void bf_he_tab_open(bf_he_tab *t, double a, double gref)
{
    double lng = log(gref), lmax;
    int mend;
    const int k = bf_he_tab_window(a, lng, &lmax, &mend);
    t->a = a;
    t->gref = gref;
    t->lngref = lng;
    t->igref = 1.0 / gref;
    t->L = lmax;
    t->k = (double)k;
    t->n = (double)(mend - k + 1);
    t->filled = 0.0;
}

/* The coefficients of an open table: the terms of its window BF_NLANES at a
 * time (bf_he_tab_lv). */
BF_FN void bf_he_tab_fill(bf_he_tab *t)
{
    const double a = t->a, lng = t->lngref, lmax = t->L;
    const int k = (int)t->k, mend = k + (int)t->n - 1;
    /* ln(T_m(g_ref) e^g_ref) into c[m - 1] for the window's vectors */
    for (int m0 = k - (k - 1) % BF_NLANES; m0 <= mend; m0 += BF_NLANES)
        BF_STORE(bf_he_tab_lv(m0, lng, a), t->c + (m0 - 1));
    /* c[j] from c[k - 1 + j]: a vector is loaded before it is stored over,
     * and k >= 1, so no later load reads a stored value */
    for (int j0 = 0; j0 <= mend - k; j0 += BF_NLANES) {
        BF_REAL mv = (double)(k + j0) + BF_IOTA;
        BF_STORE(bf_exp(BF_LOADP(t->c + (k - 1 + j0)) - lmax) / mv, t->c + j0);
    }
    t->filled = 1.0;
}

/* The table for a and g_ref, opened and filled. */
BF_FN void bf_he_tab_make(bf_he_tab *t, double a, double gref)
{
    bf_he_tab_open(t, a, gref);
    bf_he_tab_fill(t);
}

/* lpk of bf_he_tab_eval: ln V - ln sum at gs <= g_ref (lngs = ln gs). */
BF_FN BF_REAL bf_he_tab_lpk(const bf_he_tab *t, BF_REAL gs, BF_REAL lngs)
{
    return t->k * (lngs - t->lngref) + (t->L - gs);
}

/* Q = sum c_j y^j over j < n, Q' and Q''/2 into *q0, *q1, *q2.  A Horner
 * pass's three chains each wait for the multiply-add before, so from n = 8
 * the pass takes the halves L of c[0 .. h-1] and H of c[h .. n-1] side by
 * side (six chains) and joins them, Q = L + y^h H with
 *     Q' = L' + h y^(h-1) H + y^h H',
 *     Q''/2 = L''/2 + h(h-1)/2 y^(h-2) H + h y^(h-1) H' + y^h H''/2
 * (every term positive: no cancellation): a rough full pass 3% faster. */
BF_FN void bf_he_horner(const double *c, int n, BF_REAL y, BF_REAL *q0, BF_REAL *q1, BF_REAL *q2)
{
    BF_REAL l0 = BF_R(0.0), l1 = BF_R(0.0), l2 = BF_R(0.0);
    if (n < 8) {
        for (int j = n - 1; j >= 0; j--) {
            l2 = l2 * y + l1;
            l1 = l1 * y + l0;
            l0 = l0 * y + c[j];
        }
        *q0 = l0;
        *q1 = l1;
        *q2 = l2;
        return;
    }
    const int h = n - n / 2; /* H has h or h - 1 terms */
    BF_REAL h0 = BF_R(0.0), h1 = BF_R(0.0), h2 = BF_R(0.0), pw = BF_R(1.0);
    for (int i = h - 1; i >= 0; i--) {
        const double ch = h + i < n ? c[h + i] : 0.0;
        l2 = l2 * y + l1;
        l1 = l1 * y + l0;
        l0 = l0 * y + c[i];
        h2 = h2 * y + h1;
        h1 = h1 * y + h0;
        h0 = h0 * y + ch;
        if (i >= 2)
            pw = pw * y; /* y^(h-2) at the end */
    }
    const double dh = (double)h;
    BF_REAL p1 = pw * y, p0 = p1 * y; /* y^(h-1), y^h */
    *q0 = l0 + p0 * h0;
    *q1 = l1 + dh * p1 * h0 + p0 * h1;
    *q2 = l2 + (0.5 * dh * (dh - 1.0)) * pw * h0 + dh * p1 * h1 + p0 * h2;
}

/* V = e^lpk sum at gs <= g_ref (lngs = ln gs) from filled table t, and the
 * partials of ln V in g and a (see bf_he_tab; the caller carries ln V from
 * t's a to the lane's). */
BF_FN void bf_he_tab_eval(const bf_he_tab *t, BF_REAL gs, BF_REAL lngs, BF_REAL *lpk,
                          BF_REAL *sum, BF_REAL *vg, BF_REAL *va)
{
    BF_REAL y = gs * t->igref;
    BF_REAL q0 = BF_R(0.0), q1 = BF_R(0.0), q2 = BF_R(0.0); /* Q, Q', Q''/2 */
    bf_he_horner(t->c, (int)t->n, y, &q0, &q1, &q2);
    const double k = t->k;
    BF_REAL yq1 = y * q1;
    BF_REAL s0 = k * q0 + yq1;
    BF_REAL s1 = (k * k) * q0 + (2.0 * k + 1.0) * yq1 + 2.0 * (y * y) * q2;
    BF_REAL is0 = 1.0 / s0;
    *lpk = bf_he_tab_lpk(t, gs, lngs);
    *sum = s0;
    *vg = (s1 * is0) / gs - 1.0;
    *va = -(q0 * is0);
}

/* The lanes of need whose series table t serves (see bf_he_tab): 1 or 0. */
BF_FN BF_REAL bf_he_tab_lanes(const bf_he_tab *t, BF_REAL gs, BF_REAL aa, BF_REAL need)
{
    if (!(t->n > 0.0))
        return BF_R(0.0);
    return BF_SEL(BF_R(0.0), BF_R(1.0),
                  (need > 0.0) && (fabs(aa - t->a) <= BF_HE_TAB_ATOL * t->a)
                      && (gs <= t->gref * (1.0 + BF_HE_TAB_GTOL)));
}

/* The series of the lanes of tl > 0 from table t into *lpk, *sum, *vg, *va
 * and *ser = e^(lpk + lk) sum (bf_he_series_x's outputs), the others left;
 * lanes with lpk + lk < ldead are dead, as in bf_he_series_x (sum,
 * partials and value 0), and t is filled when another lane needs it. */
BF_FN void bf_he_tab_serve(bf_he_tab *t, BF_REAL tl, BF_REAL gs, BF_REAL lngs, BF_REAL aa,
                           BF_REAL lk, double ldead, BF_REAL *lpk, BF_REAL *sum, BF_REAL *vg,
                           BF_REAL *va,
                           BF_REAL *ser)
{
    BF_REAL dlpk = bf_he_tab_lpk(t, gs, lngs);
    BF_REAL live = BF_SEL(BF_R(0.0), BF_R(1.0), (tl > 0.0) && (dlpk + lk >= ldead));
    BF_REAL dead = BF_SEL(BF_R(0.0), BF_R(1.0), (tl > 0.0) && !(live > 0.0));
    if (BF_ANY(dead > 0.0)) {
        *lpk = BF_SEL(*lpk, dlpk, dead > 0.0);
        *sum = BF_SEL(*sum, BF_R(0.0), dead > 0.0);
        *vg = BF_SEL(*vg, BF_R(0.0), dead > 0.0);
        *va = BF_SEL(*va, BF_R(0.0), dead > 0.0);
        *ser = BF_SEL(*ser, BF_R(0.0), dead > 0.0);
    }
    if (!BF_ANY(live > 0.0))
        return;
    if (!(t->filled > 0.0))
        bf_he_tab_fill(t);
    BF_REAL tlpk, tsum, tvg, tva;
    bf_he_tab_eval(t, gs, lngs, &tlpk, &tsum, &tvg, &tva);
    tlpk = tlpk + tva * (aa - t->a); /* to the lane's own a, to first order */
    *lpk = BF_SEL(*lpk, tlpk, live > 0.0);
    *sum = BF_SEL(*sum, tsum, live > 0.0);
    *vg = BF_SEL(*vg, tvg, live > 0.0);
    *va = BF_SEL(*va, tva, live > 0.0);
    *ser = BF_SEL(*ser, tsum * exp(fmin(tlpk + lk, BF_R(700.0))), live > 0.0);
}

/* The series at one (a, g): where every lane of a vector that needs a series
 * is flat (sigma = sigma0, so g is its bin's g_ref) with the (g, a) of its
 * last lane (to BF_HE_MEMO_TOL; at a smooth point every table a pass made
 * was for such lanes alone: alum-bronze at its fit), the pass sums that one series
 * as a scalar, BF_NLANES terms at a time, instead of making the bin's table
 * (whose head reaches e^-BF_HE_TAB_HEAD below the largest term for lanes
 * at g far below g_ref) and a Horner pass per lane.  Its terms: those
 * within e^-BF_HE_PT_EDGE of the largest on either side (what it leaves out
 * is below 400 e^-45 ~ 1e-17 of the sum).  It gives *lpk (ln of the
 * largest term T_m*), *sum (of T_m / T_m*) and the partials of ln V as
 * bf_he_series_x gives them for a lane at (g, a); a series whose
 * lpk + lkmax < ldead is dead (sum and partials 0, no exps), as
 * bf_he_series_x leaves such a lane. */
#define BF_HE_PT_EDGE 45.0

BF_FN void bf_he_series_point(double a, double g, double lkmax, double ldead, double *lpk,
                              double *sum, double *vg, double *va)
{
    double lng = log(g), top;
    int mend;
    const int k = bf_he_window(a, lng, BF_HE_PT_EDGE, BF_HE_PT_EDGE, &top, &mend);
    *lpk = top - g;
    *sum = *vg = *va = 0.0;
    if (*lpk + lkmax < ldead)
        return;
    BF_REAL s0 = BF_R(0.0), s1 = BF_R(0.0), si = BF_R(0.0);
    for (int m0 = k - (k - 1) % BF_NLANES; m0 <= mend; m0 += BF_NLANES) {
        BF_REAL mv = (double)m0 + BF_IOTA;
        BF_REAL l = bf_he_tab_lv(m0, lng, a);
        BF_REAL t = BF_SEL(BF_R(0.0), bf_exp(fmin(l - top, BF_R(0.0))), (mv >= (double)k) && (mv <= (double)mend));
        s0 += t;
        s1 += t * mv;
        si += t / mv;
    }
    const double S0 = BF_HSUM(s0);
    *sum = S0;
    *vg = BF_HSUM(s1) / (g * S0) - 1.0;
    *va = -(BF_HSUM(si) / S0);
}

/* The lanes of `one` (every one at (gl, al) to BF_HE_MEMO_TOL) from the
 * series at (gl, al) (bf_he_series_point), carried to their own g and a to
 * first order in ln V as the memo carries its lanes, into *lpk, *sum, *vg,
 * *va and *ser (bf_he_series_x's outputs); the other lanes left. */
BF_FN void bf_he_point_serve(BF_REAL one, double gl, double al, BF_REAL gs, BF_REAL aa,
                             BF_REAL lk, double ldead, BF_REAL *lpk, BF_REAL *sum, BF_REAL *vg,
                             BF_REAL *va,
                             BF_REAL *ser)
{
    double plpk, psum, pvg, pva;
    bf_he_series_point(al, gl, bf_max_where(lk, one, -INFINITY), ldead, &plpk, &psum, &pvg,
                       &pva);
    BF_REAL l = plpk + (pvg * (gs - gl) + pva * (aa - al));
    *lpk = BF_SEL(*lpk, l, one > 0.0);
    *sum = BF_SEL(*sum, BF_R(psum), one > 0.0);
    *vg = BF_SEL(*vg, BF_R(pvg), one > 0.0);
    *va = BF_SEL(*va, BF_R(pva), one > 0.0);
    *ser = BF_SEL(*ser, psum * exp(fmin(l + lk, BF_R(700.0))), one > 0.0);
}

#endif /* BF_HE_TAB_H */
