/* SPDX-License-Identifier: MIT */
/* bf_he_stages.h -- a data pass's He K in stages (the direction pair, then
 * tau and sigma0, then n, then each channel) and its forward-difference
 * neighbours carried from the value point's stages to first order: the
 * terms of bf_he_model.h (F, G as ln G, S, sigma, g, a, D) shared between
 * the points of a pass. */
#ifndef BF_HE_STAGES_H
#define BF_HE_STAGES_H

#ifndef __OPENCL_VERSION__
#include "bf_he_memo.h"
#endif

/* ---- K in stages: the direction pair, then (tau, sigma0), then n, then the
 * per-channel arguments of D.  bf_he_pass_value runs them in order; bf_he_fd (a value
 * and its forward-difference neighbours) reuses what a parameter step leaves
 * unchanged. */

/* What depends on the directions only. */
typedef struct bf_he_dir {
    BF_REAL ci, si, co, so; /* cosines (floored) and sines of ti, to   */
    BF_REAL c;              /* cos theta_b = |v| / 2 (bf_he_dir_half)   */
    BF_REAL vz, vxy2;       /* v_z, |v_xy|^2                            */
    BF_REAL lg2;            /* 2 ln(v.v / v_z) = ln G                   */
    BF_REAL lvxy2;          /* ln |v_xy|^2 (floored)                    */
} bf_he_dir;

/* The sines of ti and to and their u = tau cot t / (2 sigma0) (bf_he_u2):
 * made once where a vector's flatness is tested (bf_he_flat_make) and
 * taken from there by its shadowing (bf_he_fd_surface), the same to the bit. */
typedef struct bf_he_su {
    BF_REAL si, so, ui, uo;
} bf_he_su;

BF_FN void bf_he_su_make(const bf_geom *g, double tau, double sigma0, bf_he_su *su)
{
    su->si = sqrt(g->ix * g->ix + g->iy * g->iy);
    su->so = sqrt(g->ox * g->ox + g->oy * g->oy);
    bf_he_u2(fmax(g->iz, BF_HE_COS_MIN), su->si, fmax(g->oz, BF_HE_COS_MIN), su->so, tau, sigma0,
             &su->ui, &su->uo);
}

/* What bf_he_dir_make computes but the two logarithms (lg2, lvxy2 left
 * unset) and c (bf_he_dir_half), with the sines si, so: all that a lane's
 * shadowing and sigma need (bf_he_fd_surface). */
BF_FN void bf_he_dir_cos(const bf_geom *g, BF_REAL si, BF_REAL so, bf_he_dir *d)
{
    BF_REAL ci = fmax(g->iz, BF_HE_COS_MIN), co = fmax(g->oz, BF_HE_COS_MIN);
    BF_REAL vx = g->ix + g->ox, vy = g->iy + g->oy, vz = ci + co;
    BF_REAL vxy2 = vx * vx + vy * vy;
    d->ci = ci;
    d->si = si;
    d->co = co;
    d->so = so;
    d->vz = vz;
    d->vxy2 = vxy2;
}

/* d's c = cos theta_b = |v| / 2 (d made by bf_he_dir_cos): what Fresnel
 * needs (bf_he_fd_fresnel). */
BF_FN void bf_he_dir_half(bf_he_dir *d)
{
    BF_REAL vv = d->vxy2 + d->vz * d->vz;
    d->c = fmin(fmax(0.5 * sqrt(vv), BF_HE_COS_MIN), 1.0);
}

/* The logarithms of d (made by bf_he_dir_cos): ln G and ln |v_xy|^2. */
BF_FN void bf_he_dir_logs(bf_he_dir *d)
{
    BF_REAL vv = d->vxy2 + d->vz * d->vz;
    d->lg2 = 2.0 * log(vv / d->vz);
    d->lvxy2 = log(fmax(d->vxy2, BF_R(1e-300)));
}

BF_FN void bf_he_dir_make(const bf_geom *g, bf_he_dir *d)
{
    bf_he_dir_cos(g, sqrt(g->ix * g->ix + g->iy * g->iy), sqrt(g->ox * g->ox + g->oy * g->oy), d);
    bf_he_dir_logs(d);
}

/* What depends on (tau, sigma0) too: S(ti), S(to), S(ti) / cos ti, S(to) / cos to
 * (within [1e-3, 1e3]-ish) and the effective roughness sigma; with deriv, also what
 * bf_he_rough_step needs to carry them to a nearby (tau, sigma0).  With flat,
 * every lane takes the flat values (S = 1, sigma = sigma0) whatever its u:
 * what a bin's row of a pass is made with (bf_he_bin_rows). */
typedef struct bf_he_rough {
    int flat;                       /* 1: u >= BF_HE_U_FLAT in every lane and
                                     * both directions (see bf_he_rough_make) */
    BF_REAL Si, So;                 /* S(ti), S(to)                        */
    BF_REAL shi, sho, sigma;
    BF_REAL ui, uo, ei, eo, xi, xo; /* u, erfc(u), exp(-u^2) of ti and to  */
    BF_REAL dshi, dsho;             /* d(S(t) / cos t) / du                */
    BF_REAL r, x;                   /* sigma's r and x                     */
    BF_REAL tani, tano;             /* tan ti, tan to (r's weights)        */
    BF_REAL xk, xr;                 /* xk = x / (1 + x^2): dx per d ln r at the
                                     * root, and -d ln sigma per dx; xr = xk / r:
                                     * dx per dr                           */
    BF_REAL w;                      /* x^2 / (1 + x^2) = 1 - (sigma / sigma0)^2:
                                     * g's relative shortfall from its value at
                                     * sigma0 (bf_he_near_serve)           */
} bf_he_rough;

/* bf_he_rough_make with the directions' u given (bf_he_u2 of d's cosines and
 * sines at (tau, sigma0)). */
BF_FN void bf_he_rough_make_u(const bf_he_dir *d, BF_REAL ui, BF_REAL uo, double sigma0,
                              int deriv, int flat, bf_he_rough *r)
{
    r->flat = flat || !BF_ANY((ui < BF_HE_U_FLAT) || (uo < BF_HE_U_FLAT));
    if (r->flat) {
        /* erfc and e^(-u^2) are 0 (bf_he_erfc2): S = 1, r = 0, x = BF_TINY
         * (bf_he_newton_xq), sigma = sigma0, the partials in u 0: the values
         * of the general path below for such a lane, bit for bit (1 / cos t
         * as u / (cos t u), its lu being u: a lane's values do not depend on
         * the vector it is in), without its erfc; u taken at least
         * BF_HE_U_FLAT where flat makes a rougher lane flat (so the product
         * bf_rcp2 divides by is at least 3.6e-199) */
        BF_REAL uci = fmax(ui, BF_R(BF_HE_U_FLAT)), uco = fmax(uo, BF_R(BF_HE_U_FLAT));
        BF_REAL wi, wo;
        bf_rcp2(d->ci * uci, d->co * uco, &wi, &wo);
        r->Si = r->So = BF_R(1.0);
        r->shi = uci * wi;
        r->sho = uco * wo;
        r->sigma = BF_R(sigma0);
        if (deriv) {
            r->ui = ui;
            r->uo = uo;
            r->ei = r->eo = r->xi = r->xo = BF_R(0.0);
            r->dshi = r->dsho = BF_R(0.0);
            r->r = BF_R(0.0);
            r->x = BF_R(BF_TINY);
            r->tani = r->tano = r->xk = r->xr = r->w = BF_R(0.0);
        }
        return;
    }
    BF_REAL ei, eo, xi, xo;
    bf_he_erfc2(ui, &ei, &xi);
    bf_he_erfc2(uo, &eo, &xo);
    /* S(t) = h u / lu with h = 1 - erfc(u) / 2 and lu = (1 + L(u)) u
     * (bf_he_shadow_lu); S / cos t, tan t = sin t / cos t and the partial
     * d(S / cos t) / du all divide by cos t lu, whose reciprocals in both
     * directions come from one division (ci lui co luo lies in
     * [1e-202, 1e22]: cos >= BF_HE_COS_MIN, lu in [0.28, 1e10]) */
    BF_REAL hi = 1.0 - 0.5 * ei, ho = 1.0 - 0.5 * eo;
    BF_REAL lui = bf_he_shadow_lu(ui, ei, xi), luo = bf_he_shadow_lu(uo, eo, xo);
    BF_REAL wi, wo; /* 1 / (cos t lu) */
    bf_rcp2(d->ci * lui, d->co * luo, &wi, &wo);
    r->shi = (hi * ui) * wi;
    r->sho = (ho * uo) * wo;
    r->Si = r->shi * d->ci;
    r->So = r->sho * d->co;
    BF_REAL tani = (d->si * lui) * wi, tano = (d->so * luo) * wo;
    BF_REAL rr = (tani * ei + tano * eo) * (1.0 / sqrt(8.0 * BF_PI));
    BF_REAL xq, x = bf_he_newton_xq(rr, &xq);
    /* sigma = sigma0 / sqrt(1 + x^2); with deriv xk = x / (1 + x^2) and
     * xr = xk / r (r floored at BF_TINY), from one division, or none where
     * x^2 rounds away in every lane (sigma0 to the bit, as the rows' near
     * lanes need: bf_he_near_serve) */
    BF_REAL x1 = 1.0 + x * x, sq = BF_R(1.0), ix = BF_R(1.0);
    if (BF_ANY(x1 != 1.0)) {
        sq = sqrt(x1);
        ix = 1.0 / (sq * x1);
    }
    r->sigma = sigma0 * (x1 * ix);
    if (deriv) {
        r->tani = tani;
        r->tano = tano;
        r->xk = x * (sq * ix);
        r->xr = xq * (sq * ix);
        r->w = (x * x) * (sq * ix);
        r->ui = ui;
        r->uo = uo;
        r->ei = ei;
        r->eo = eo;
        r->xi = xi;
        r->xo = xo;
        r->dshi = bf_he_dshadow_lu(ui, hi, lui, xi) * ((wi * wi) * d->ci);
        r->dsho = bf_he_dshadow_lu(uo, ho, luo, xo) * ((wo * wo) * d->co);
        r->r = rr;
        r->x = x;
    }
}

/* bf_he_rough_make_u with each direction's u from d. */
BF_FN void bf_he_rough_make(const bf_he_dir *d, double tau, double sigma0, int deriv,
                            int flat, bf_he_rough *r)
{
    BF_REAL ui, uo;
    bf_he_u2(d->ci, d->si, d->co, d->so, tau, sigma0, &ui, &uo);
    bf_he_rough_make_u(d, ui, uo, sigma0, deriv, flat, r);
}

/* r0 (made with deriv at (tau0, sigma00)) carried to (tau, sigma0) nearby,
 * to first order in the steps: u scales with tau / sigma0 (so du = u0 times
 * the ratio's step, exactly but for rounding), S(t) / cos t by dS/du, erfc by
 * -2 e^(-u^2) / sqrt(pi), r by its weights tan t, x by one Newton step on
 * ln x + x^2/2 = ln r from r0's root (dx = x dr / (r (1 + x^2))), sigma by
 * d ln sigma = d ln sigma0 - x dx / (1 + x^2), w by dw = 2 x dx / (1 + x^2)^2.
 * No exp, erfc, log, square root or division per lane.  (It sets shi, sho,
 * sigma and w: all that a neighbour uses.) */
BF_FN void bf_he_rough_step(const bf_he_rough *r0, double tau0, double sigma00, double tau,
                            double sigma0, bf_he_rough *r)
{
    r->flat = r0->flat;
    if (r0->flat) { /* every partial is 0 and x = BF_TINY: the general path's values */
        r->shi = r0->shi;
        r->sho = r0->sho;
        r->sigma = BF_R(sigma0);
        r->w = BF_R(0.0);
        return;
    }
    /* u'/u - 1; u = 1e10 is the normal's clamp (bf_he_u2), where u stays */
    const double du = (tau * sigma00 - tau0 * sigma0) / (tau0 * sigma0);
    BF_REAL dui = BF_SEL(r0->ui * du, BF_R(0.0), r0->ui >= 1e10);
    BF_REAL duo = BF_SEL(r0->uo * du, BF_R(0.0), r0->uo >= 1e10);
    r->shi = r0->shi + r0->dshi * dui;
    r->sho = r0->sho + r0->dsho * duo;
    BF_REAL dr = (r0->tani * r0->xi * dui + r0->tano * r0->xo * duo)
               * (-2.0 / (BF_SQRT_PI * sqrt(8.0 * BF_PI)));
    BF_REAL dx = r0->xr * dr;
    r->sigma = (r0->sigma * (sigma0 / sigma00)) * (1.0 - r0->xk * dx);
    r->w = r0->w + (2.0 * r0->xk) * (1.0 - r0->w) * dx; /* dw/dx = 2 x / (1 + x^2)^2 */
}

/* What bf_he_fd computes at p[0] and its neighbours are carried from. */
typedef struct bf_he_base {
    bf_he_dir d;
    bf_he_rough r;                /* made with deriv                          */
    BF_REAL F;                    /* Fresnel at n                             */
    BF_REAL fs, ifs;              /* F S(ti) S(to) / (pi cos ti cos to), 1 / fs */
    BF_REAL lc;                   /* ln fs + ln G                             */
    BF_REAL zero;                 /* 1 where fs underflows: K = 0             */
    BF_REAL sv, lsv2;             /* sigma v_z and 2 ln(sigma v_z)            */
    BF_REAL s0v;                  /* sigma0 v_z                               */
    double klmax2;                /* the largest (2 pi / lam)^2 of the channels */
    BF_REAL q0, lim0;             /* a / g and e^lk / g of the rough limit (see bf_he_fd_scale) */
    /* per channel: the value before the zero flag, the series V (summed at
     * min(g, 19)) and its partials, the limit L, min(g, 19), a, max(g, 18),
     * a / max(g, 18) */
    BF_REAL Kr[3], V[3], Vg[3], Va[3], L[3], g0[3], a0[3], gl[3], agl[3];
} bf_he_base;

/* Of b's directions (b->d, their logarithms and c not needed), the
 * shadowing and sigma (with their partials) from the directions' u at
 * p0 = (tau, sigma0, n) (flat: see bf_he_rough_make). */
BF_FN void bf_he_fd_shade(const double *p0, int flat, BF_REAL ui, BF_REAL uo, bf_he_base *b)
{
    bf_he_rough_make_u(&b->d, ui, uo, p0[1], 1, flat, &b->r);
}

/* After bf_he_fd_shade: b's c (bf_he_dir_half), F, fs, 1 / fs and the zero
 * flag at p0.  A vector the rows serve near the flat ones needs none of
 * them (bf_he_near_serve), and so takes no Fresnel, square root or
 * division for them (at He's typical start, tau = 16, sigma0 = 0.5, 19% of
 * alum-bronze's samples are served so; the same values to the bit). */
BF_FN void bf_he_fd_fresnel(const double *p0, bf_he_base *b)
{
    bf_he_dir_half(&b->d);
    b->F = bf_he_fresnel(b->d.c, p0[2]);
    b->fs = b->F * b->r.shi * b->r.sho * (1.0 / BF_PI);
    b->ifs = 1.0 / fmax(b->fs, BF_TINY);
    b->zero = BF_SEL(BF_R(0.0), BF_R(1.0), b->fs < BF_TINY);
}

/* The first stage of bf_he_fd_base: the direction pair without its
 * logarithms and c (bf_he_dir_cos) and bf_he_fd_shade, with the sines and u
 * of su (bf_he_su_make at p0).  All that a lane served from the bin rows
 * near the flat ones needs (bf_he_near_serve); bf_he_fd_fresnel,
 * bf_he_dir_logs of b->d and bf_he_fd_scale complete b. */
BF_FN void bf_he_fd_surface(const bf_geom *g, const double *p0, int flat, const bf_he_su *su,
                            bf_he_base *b)
{
    bf_he_dir_cos(g, su->si, su->so, &b->d);
    bf_he_fd_shade(p0, flat, su->ui, su->uo, b);
}

/* The last stage, once b->d has its logarithms (bf_he_dir_logs): ln fs +
 * ln G, sigma v_z and the rough limit shared by the channels. */
BF_FN void bf_he_fd_scale(const double *p0, const double *lam, const bf_he_pconst *pc,
                          bf_he_base *b)
{
    const double tau = p0[0], sigma0 = p0[1];
    b->lc = log(fmax(b->fs, BF_TINY)) + b->d.lg2;
    b->sv = b->r.sigma * b->d.vz;             /* > 1e-106: g never underflows */
    b->lsv2 = 2.0 * log(b->sv);
    b->s0v = sigma0 * b->d.vz;

    /* The rough limit e^(lk - a/g) / g is the same in every channel where
     * g >= 18: a/g = q0 = tau^2 |v_xy|^2 / (4 sv^2) and e^lk / g =
     * e^lc (tau / 4)^2 / sv^2 do not depend on lam (one exp for the three). */
    b->klmax2 = 0.0;
    for (int ch = 0; ch < 3; ch++)
        b->klmax2 = fmax(b->klmax2, (2.0 * BF_PI / lam[ch]) * (2.0 * BF_PI / lam[ch]));
    b->q0 = BF_R(0.0);
    b->lim0 = BF_R(0.0);
    if (BF_ANY(b->klmax2 * (b->sv * b->sv) > BF_HE_G_LO / BF_HE_FD_MARGIN)) {
        b->q0 = (0.25 * tau * tau) * b->d.vxy2 / (b->sv * b->sv);
        b->lim0 = exp(fmin(b->lc - b->q0 - b->lsv2 + pc->ltau16, BF_R(700.0)));
    }
}

/* The direction pair, the shadowing and sigma (with their partials), F and
 * the rough limit shared by the channels, at p0 = (tau, sigma0, n) (flat: see
 * bf_he_rough_make): bf_he_fd_surface, then bf_he_fd_scale. */
BF_FN void bf_he_fd_base(const bf_geom *g, const double *p0, const double *lam,
                         const bf_he_pconst *pc, int flat, bf_he_base *b)
{
    bf_he_su su;
    bf_he_su_make(g, p0[0], p0[1], &su);
    bf_he_fd_surface(g, p0, flat, &su, b);
    bf_he_fd_fresnel(p0, b);
    bf_he_dir_logs(&b->d);
    bf_he_fd_scale(p0, lam, pc, b);
}

/* bf_he_fd_base from the direction pair d (bf_he_dir_make of the lanes'
 * geometry): the same b. */
BF_FN void bf_he_fd_base_dir(const bf_he_dir *d, const double *p0, const double *lam,
                             const bf_he_pconst *pc, int flat, bf_he_base *b)
{
    b->d = *d;
    BF_REAL ui, uo;
    bf_he_u2(d->ci, d->si, d->co, d->so, p0[0], p0[1], &ui, &uo);
    bf_he_fd_shade(p0, flat, ui, uo, b);
    bf_he_fd_fresnel(p0, b);
    bf_he_fd_scale(p0, lam, pc, b);
}

/* K(p0) of channel ch (wavelength lam um): bf_he_pass_value's operations, with the
 * partials of the series and what the neighbours need kept in b. */
BF_FN BF_REAL bf_he_fd_channel(bf_he_base *b, double tau, double lam, int ch,
                               const bf_he_pconst *pc, bf_he_memo *memo)
{
    double kl = 2.0 * BF_PI / lam;
    double kt = BF_PI * tau / (2.0 * lam);
    double kl2 = kl * kl, kt2 = kt * kt;
    BF_REAL gg = kl2 * (b->sv * b->sv), lng = pc->lkl2[ch] + b->lsv2, lk = b->lc + pc->lkt2[ch];
    BF_REAL aa = (4.0 * kt2) * b->d.vxy2, la = pc->l4kt2[ch] + b->d.lvxy2;
    BF_REAL lim = BF_R(0.0);
    b->gl[ch] = fmax(gg, BF_HE_G_LO);
    b->agl[ch] = BF_R(0.0);
    if (BF_ANY(gg > BF_HE_G_LO / BF_HE_FD_MARGIN)) {
        /* g in (18 / m, 18): the limit at the clamp g = 18 (for the neighbours) */
        BF_REAL below = BF_SEL(BF_R(0.0), BF_R(1.0), gg < BF_HE_G_LO);
        lim = b->lim0;
        if (BF_ANY((below > 0.0) && (gg > BF_HE_G_LO / BF_HE_FD_MARGIN))) {
            lim = BF_SEL(lim, bf_he_limit(gg, lng, aa, lk), below > 0.0);
            b->agl[ch] = aa / b->gl[ch];
        }
        lim = BF_SEL(lim, BF_R(0.0), gg <= BF_HE_G_LO / BF_HE_FD_MARGIN);
    }
    BF_REAL gtop = kl2 * (b->s0v * b->s0v); /* g at sigma = sigma0: the bin's largest */
    b->Kr[ch] = bf_he_dblend(gg, lng, aa, la, lk, pc->ldead[ch], lim, gtop, BF_HE_FD_MARGIN, 1,
                             memo, ch, &b->V[ch], &b->Vg[ch], &b->Va[ch]);
    b->L[ch] = lim;
    b->g0[ch] = fmin(gg, BF_HE_G_HI);
    b->a0[ch] = aa;
    return BF_SEL(b->Kr[ch], BF_R(0.0), b->zero > 0.0);
}

/* e^d for the exponent of a neighbour's rough limit relative to its value
 * point's, which a step of FD_STEP keeps small: the Taylor polynomial of
 * degree 5 when every lane has |d| <= BF_HE_EXP_SMALL (its remainder below
 * 1.4e-21 relative), else exp (tests/test_he.c, exp_small).  Two exps a
 * neighbour, most vectors of a rough pass: 2% of its time. */
#define BF_HE_EXP_SMALL 1e-3

BF_FN BF_REAL bf_he_exp_small(BF_REAL d)
{
    if (BF_ANY(fabs(d) > BF_HE_EXP_SMALL))
        return exp(d);
    return 1.0 + d * (1.0 + d * (0.5 + d * (1.0 / 6.0 + d * (1.0 / 24.0 + d * (1.0 / 120.0)))));
}

/* K at pj = (tau', sigma0', n'), a small step from p0, carried from b: see bf_he_fd. */
BF_FN void bf_he_fd_neighbour(const bf_he_base *b, const double *p0, const double *pj,
                              const double *lam, BF_REAL *Kj)
{
    const double tau = p0[0], sigma0 = p0[1], n = p0[2];
    const double tj = pj[0], s0j = pj[1], nj = pj[2];
    BF_REAL Fj = b->F;
    if (nj != n)
        Fj = bf_he_fresnel(b->d.c, nj);
    if (tj == tau && s0j == sigma0) {
        /* n alone: S, sigma, g, a unchanged; K scales with F */
        BF_REAL fsj = Fj * b->r.shi * b->r.sho * (1.0 / BF_PI);
        BF_REAL zj = BF_SEL(b->zero, BF_R(1.0), fsj < BF_TINY);
        BF_REAL rat = fsj * b->ifs;
        for (int ch = 0; ch < 3; ch++)
            Kj[ch] = BF_SEL(rat * b->Kr[ch], BF_R(0.0), zj > 0.0);
        return;
    }
    bf_he_rough rj;
    bf_he_rough_step(&b->r, tau, sigma0, tj, s0j, &rj);
    BF_REAL fsj = Fj * rj.shi * rj.sho * (1.0 / BF_PI);
    BF_REAL zj = BF_SEL(b->zero, BF_R(1.0), fsj < BF_TINY);
    BF_REAL rat = fsj * b->ifs;
    BF_REAL svj = rj.sigma * b->d.vz;
    /* e^(a/g - a'/g') g / g' of the limit, shared by the channels where
     * g, g' >= 18 (see bf_he_fd_scale) */
    BF_REAL ej = BF_R(0.0);
    if (BF_ANY(b->klmax2 * (svj * svj) > BF_HE_G_LO)) {
        BF_REAL isv2 = 1.0 / (svj * svj);
        BF_REAL qj = (0.25 * tj * tj) * b->d.vxy2 * isv2;
        ej = bf_he_exp_small(fmin(b->q0 - qj, BF_R(700.0))) * ((b->sv * b->sv) * isv2);
    }
    for (int ch = 0; ch < 3; ch++) {
        double kl = 2.0 * BF_PI / lam[ch];
        double kt0 = BF_PI * tau / (2.0 * lam[ch]), kt = BF_PI * tj / (2.0 * lam[ch]);
        double kl2 = kl * kl, kt2 = kt * kt;
        BF_REAL gj = kl2 * (svj * svj), aj = (4.0 * kt2) * b->d.vxy2;
        BF_REAL rc = rat * (kt2 / (kt0 * kt0));     /* e^(lk' - lk) */
        BF_REAL x = b->Vg[ch] * (gj - b->g0[ch]) + b->Va[ch] * (aj - b->a0[ch]); /* ~ ln(V' / V) */
        BF_REAL ser = (rc * b->V[ch]) * (1.0 + x * (1.0 + x * (0.5 + x * (1.0 / 6.0))));
        BF_REAL t = bf_he_blend_t(gj);
        BF_REAL lim = BF_R(0.0);
        if (BF_ANY(t > 0.0)) {
            lim = (b->L[ch] * rc) * ej;
            BF_REAL up = BF_SEL(BF_R(0.0), BF_R(1.0), (t > 0.0) && (b->g0[ch] < BF_HE_G_LO));
            if (BF_ANY(up > 0.0)) { /* from below the clamp: the general form */
                BF_REAL iglj = 1.0 / fmax(gj, BF_HE_G_LO);
                lim = BF_SEL(lim, (b->L[ch] * rc) * (bf_he_exp_small(b->agl[ch] - aj * iglj) * (b->gl[ch] * iglj)),
                             up > 0.0);
            }
        }
        Kj[ch] = BF_SEL(bf_he_blend(t, ser, lim), BF_R(0.0), zj > 0.0);
    }
}

#endif /* BF_HE_STAGES_H */
