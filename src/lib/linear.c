/* SPDX-License-Identifier: MIT */
/* linear.c -- the linear unknowns d, s of a fit, solved exactly from a pass's
 * moments, and the normal equations of the lobe coordinates with d, s
 * projected out (see linear.h). */
#define _DEFAULT_SOURCE /* M_PI */
#include "linear.h"

#include <math.h>
#include <string.h>

/* One channel's normal equations in the offsets (dd, ds) = (d - d_ref, s - s_ref):
 * cost(dd, ds) = see - 2 (g1 dd + g2 ds) + a11 dd^2 + 2 a12 dd ds + a22 ds^2. */
typedef struct chan_eq {
    double a11, a12, a22, g1, g2, see;
} chan_eq;

static chan_eq channel_equations(const double *mom, int nk, int np, int c)
{
    const double *mk = mom + bf_mom_lobe(nk > 1 ? c : 0, np);
    const double *mc = mom + bf_mom_chan(c, nk, np);
    chan_eq q;
    q.a11 = mom[BF_MOM_A] / (M_PI * M_PI);
    q.a12 = mk[BF_MK_SK] / M_PI;
    q.a22 = mk[BF_MK_SKK];
    q.g1 = mc[BF_MC_SE] / M_PI;
    q.g2 = mc[BF_MC_SKE];
    q.see = mc[BF_MC_SEE];
    return q;
}

static double eq_cost(const chan_eq *q, double dd, double ds)
{
    return q->see - 2.0 * (q->g1 * dd + q->g2 * ds) + q->a11 * dd * dd + 2.0 * q->a12 * dd * ds +
           q->a22 * ds * ds;
}

/* Keep candidate (d, s) when it is feasible and cheaper than the best so far. */
static void consider(const chan_eq *q, double dref, double sref, double d, double s, double *bd,
                     double *bs, double *best)
{
    if (!(d >= 0.0) || !(s >= 0.0) || !isfinite(d) || !isfinite(s))
        return;
    double c = eq_cost(q, d - dref, s - sref);
    if (c < *best) {
        *best = c;
        *bd = d;
        *bs = s;
    }
}

/* The convex 2-unknown problem over d, s >= 0: its minimum is the cheapest
 * feasible one of the corner, the two faces' minima and the interior minimum. */
static double channel_best(const chan_eq *q, double dref, double sref, double *d, double *s)
{
    double best = INFINITY, bd = 0.0, bs = 0.0;
    consider(q, dref, sref, 0.0, 0.0, &bd, &bs, &best);
    if (q->a11 > 0) /* s = 0 face */
        consider(q, dref, sref, fmax(dref + (q->g1 + q->a12 * sref) / q->a11, 0.0), 0.0, &bd, &bs, &best);
    if (q->a22 > 0) /* d = 0 face */
        consider(q, dref, sref, 0.0, fmax(sref + (q->g2 + q->a12 * dref) / q->a22, 0.0), &bd, &bs, &best);
    double det = q->a11 * q->a22 - q->a12 * q->a12;
    if (det > 1e-14 * q->a11 * q->a22) {
        double dd = (q->g1 * q->a22 - q->g2 * q->a12) / det;
        double ds = (q->a11 * q->g2 - q->a12 * q->g1) / det;
        consider(q, dref, sref, dref + dd, sref + ds, &bd, &bs, &best);
    }
    *d = bd;
    *s = bs;
    return fmax(best, 0.0);
}

double bf_linear_best(const double *mom, int nk, int np, const bf_linear *ref, bf_linear *best)
{
    double rr = 0.0;
    for (int c = 0; c < 3; c++) {
        chan_eq q = channel_equations(mom, nk, np, c);
        rr += channel_best(&q, ref->d[c], ref->s[c], &best->d[c], &best->s[c]);
    }
    return rr;
}

/* Subtract from H the part of the lobe columns that the free linear columns
 * of one channel explain: H -= B M^-1 B^T over the free ones (M = their Gram
 * matrix, B their products with the lobe columns). */
static void project_out(const chan_eq *q, int dfree, int sfree, const double *bd, const double *bs,
                        int np, double H[][BF_MAX_NP])
{
    double det = q->a11 * q->a22 - q->a12 * q->a12;
    for (int j = 0; j < np; j++)
        for (int l = 0; l < np; l++) {
            double v = 0.0;
            if (dfree && sfree && det > 0)
                v = (q->a22 * bd[j] * bd[l] - q->a12 * (bd[j] * bs[l] + bs[j] * bd[l]) +
                     q->a11 * bs[j] * bs[l]) / det;
            else if (dfree && q->a11 > 0)
                v = bd[j] * bd[l] / q->a11;
            else if (sfree && q->a22 > 0)
                v = bs[j] * bs[l] / q->a22;
            H[j][l] -= v;
        }
}

void bf_linear_reduce(const double *mom, int nk, int np, const bf_linear *ref, const bf_linear *best,
                      double H[][BF_MAX_NP], double *g, double *hdiag)
{
    for (int j = 0; j < np; j++) {
        g[j] = hdiag[j] = 0.0;
        for (int l = 0; l < np; l++)
            H[j][l] = 0.0;
    }
    for (int c = 0; c < 3; c++) {
        const double *mk = mom + bf_mom_lobe(nk > 1 ? c : 0, np);
        const double *mc = mom + bf_mom_chan(c, nk, np);
        chan_eq q = channel_equations(mom, nk, np, c);
        double s = best->s[c], dd = best->d[c] - ref->d[c], ds = best->s[c] - ref->s[c];
        double bd[BF_MAX_NP], bs[BF_MAX_NP], C[BF_MAX_NP][BF_MAX_NP];
        memset(C, 0, sizeof C);
        for (int j = 0; j < np; j++) {
            double sg = mk[bf_mk_sg(j)], skg = mk[bf_mk_skg(np, j)];
            bd[j] = s * sg / M_PI;
            bs[j] = s * skg;
            /* J_u^T r* with r = -a e*, e* = e_ref - dd/pi - ds K */
            g[j] -= s * (mc[bf_mc_sge(j)] - dd * sg / M_PI - ds * skg);
            for (int l = j; l < np; l++)
                C[j][l] = C[l][j] = s * s * mk[bf_mk_sgg(np, j, l)];
        }
        project_out(&q, best->d[c] > 0, best->s[c] > 0, bd, bs, np, C);
        for (int j = 0; j < np; j++) {
            hdiag[j] += s * s * mk[bf_mk_sgg(np, j, j)];
            for (int l = 0; l < np; l++)
                H[j][l] += C[j][l];
        }
    }
}

int bf_linear_ref_far(const double *mom, int nk, int np, double rr)
{
    double see = 0.0;
    for (int c = 0; c < 3; c++)
        see += mom[bf_mom_chan(c, nk, np) + BF_MC_SEE];
    return see > BF_LINEAR_REF_FAR * rr;
}
