/* SPDX-License-Identifier: MIT */
/* albedo_quad.c -- the points and weights of the directional albedo's
 * quadrature (albedo.h). */
#include "albedo.h"

#include <math.h>

#define PI 3.14159265358979323846
/* Intervals graded toward the pole: at most this many halvings. */
#define MAX_POLE_LEVELS 48
/* Intervals graded toward the horizon end: halvings of the radial range. */
#define END_LEVELS 4
#define MAX_ORDER 128
/* Intervals of [1/2, 3/4] of the radial range (where kinks of a lobe's
 * shadowing term lie for broad lobes). */
#define MID_STEPS 2
/* The most kinks a line of phi has (albedo.h). */
#define MAX_KINKS 16
/* Intervals of the radial range on which level crossings are sought. */
#define LEVEL_SAMPLES 8
/* Phis where kinks meet (kink_phis) and the most phi panels. */
#define AQ_MAX_PHI_KINKS 3
#define AQ_MAX_PANELS (3 + AQ_MAX_PHI_KINKS)
/* The fewest phi points a panel split at a kink's phi takes; the panels'
 * sum is then at most nphi + (AQ_MIN_PANEL + 1) AQ_MAX_PANELS. */
#define AQ_MIN_PANEL 4

void aq_gauss_legendre(int n, double *x, double *w)
{
    for (int i = 0; i < (n + 1) / 2; i++) {
        double z = cos(PI * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = 0;
            for (int k = 1; k <= n; k++) {
                double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p2) / k;
            }
            dp = n * (z * p0 - p1) / (z * z - 1);
            double dz = p0 / dp;
            z -= dz;
            if (fabs(dz) < 1e-16)
                break;
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = w[n - 1 - i] = 2.0 / ((1 - z * z) * dp * dp);
    }
}

static int pole_levels(double len, double width)
{
    int k = 1;
    while (k < MAX_POLE_LEVELS && len * ldexp(1.0, -k) > width)
        k++;
    return k;
}

#define TABLE_BINS 90

size_t aq_max_points(const aq_rule *rule)
{
    size_t per = rule->kind == AQ_TABLE ? TABLE_BINS + 1 : MAX_POLE_LEVELS + END_LEVELS + MID_STEPS + MAX_KINKS + 2;
    return ((size_t)rule->nphi + (AQ_MIN_PANEL + 1) * AQ_MAX_PANELS) * (size_t)rule->order * per;
}

/* The table's theta_h bin edges below hi, then hi. */
static int table_breakpoints(double hi, double *t)
{
    int n = 0;
    for (int k = 0; k < TABLE_BINS; k++) {
        double e = (double)k * k / (TABLE_BINS * TABLE_BINS) * (0.5 * PI);
        if (e >= hi)
            break;
        t[n++] = e;
    }
    t[n++] = hi;
    return n;
}

/* The breakpoints of [a, b] graded toward a (down to width) and toward b;
 * returns their number (intervals + 1). */
static int breakpoints(double a, double b, double width, double *t)
{
    double len = b - a;
    int k = pole_levels(len, width), n = 0;
    t[n++] = a;
    for (int j = k; j >= 2; j--)
        t[n++] = a + len * ldexp(1.0, -j);
    for (int j = 0; j < MID_STEPS; j++)
        t[n++] = a + len * (0.5 + 0.25 * j / MID_STEPS);
    for (int j = 2; j <= END_LEVELS; j++)
        t[n++] = b - len * ldexp(1.0, -j);
    t[n++] = b;
    return n;
}

/* Inserts r into the sorted breakpoints t[0..n-1] when strictly inside
 * (t[0], t[n-1]) and not already one; returns the new count. */
static int insert_breakpoint(double *t, int n, double r)
{
    if (!(r > t[0] && r < t[n - 1]))
        return n;
    int k = n - 1;
    while (t[k - 1] > r)
        k--;
    if (t[k - 1] == r)
        return n;
    for (int j = n; j > k; j--)
        t[j] = t[j - 1];
    t[k] = r;
    return n + 1;
}

static double direction(const aq_rule *rule, const double wo[3], double r, double cphi,
                        double sphi, aq_point *pt);

/* kink_q at radius r of the line of phi, less level. */
static double level_gap(const aq_rule *rule, const double wo[3], double r, double cphi,
                        double sphi, double level)
{
    aq_point pt;
    direction(rule, wo, r, cphi, sphi, &pt);
    return rule->kink_q(rule->kink_ctx, pt.wi, wo) - level;
}

/* The crossing of level in [a, b], where the gap changes sign (fa, fb): the
 * Illinois variant of regula falsi. */
static double crossing(const aq_rule *rule, const double wo[3], double cphi, double sphi,
                       double level, double a, double b, double fa, double fb)
{
    int side = 0;
    for (int it = 0; it < 40 && b - a > 1e-7; it++) {
        double c = (a * fb - b * fa) / (fb - fa);
        if (!(c > a && c < b))
            c = 0.5 * (a + b);
        double fc = level_gap(rule, wo, c, cphi, sphi, level);
        if (fc == 0)
            return c;
        if ((fc > 0) == (fb > 0)) {
            b = c, fb = fc;
            if (side == -1)
                fa *= 0.5;
            side = -1;
        } else {
            a = c, fa = fc;
            if (side == 1)
                fb *= 0.5;
            side = 1;
        }
    }
    return 0.5 * (a + b);
}

/* Adds the crossings of the rule's levels (albedo.h) between t[0] and t[n-1]
 * to the breakpoints, sought on LEVEL_SAMPLES equal intervals (a crossing
 * pair closer than that is missed: its kinks bound a thin sliver); returns
 * the new count. */
static int level_breakpoints(const aq_rule *rule, const double wo[3], double cphi, double sphi,
                             double *t, int n)
{
    double s[LEVEL_SAMPLES + 1], q[LEVEL_SAMPLES + 1];
    int ns = LEVEL_SAMPLES + 1, added = 0;
    for (int k = 0; k < ns; k++)
        s[k] = t[0] + (t[n - 1] - t[0]) * k / LEVEL_SAMPLES;
    for (int k = 0; k < ns; k++)
        q[k] = level_gap(rule, wo, s[k], cphi, sphi, 0.0);
    for (int l = 0; l < rule->nlevels; l++)
        for (int k = 0; k + 1 < ns && added < MAX_KINKS - 3; k++) {
            double fa = q[k] - rule->kink_level[l], fb = q[k + 1] - rule->kink_level[l];
            if ((fa > 0) == (fb > 0) || fa == 0)
                continue;
            double r = crossing(rule, wo, cphi, sphi, rule->kink_level[l], s[k], s[k + 1], fa, fb);
            int m = insert_breakpoint(t, n, r);
            added += m - n;
            n = m;
        }
    return n;
}

/* Adds the rule's kinks of the line of phi (albedo.h) to its breakpoints. */
static int kink_breakpoints(const aq_rule *rule, const double wo[3], double cphi, double sphi,
                            double *t, int n)
{
    double psi = atan2(wo[0] * cphi, wo[2]);
    if (rule->kinks & AQ_KINK_MIRROR)
        n = insert_breakpoint(t, n, psi);
    if (rule->kinks & AQ_KINK_SHADOW) {
        n = insert_breakpoint(t, n, 0.5 * PI - psi);
        n = insert_breakpoint(t, n, (psi + 0.5 * PI) / 3.0);
    }
    if (rule->kink_q && rule->nlevels > 0)
        n = level_breakpoints(rule, wo, cphi, sphi, t, n);
    return n;
}

/* The radial range [lo, hi] of direction phi where wi is above the horizon
 * (and, AQ_POLE, within pi/2 of the pole); 0 when empty. */
static int radial_range(const aq_rule *rule, const double wo[3], double cphi, double *lo,
                        double *hi)
{
    if (rule->kind != AQ_POLE) {
        double psi = atan2(wo[0] * cphi, wo[2]);
        *lo = 0;
        *hi = 0.5 * (psi + 0.5 * PI);
        return *hi > 0;
    }
    /* wi_z = Pz cos r - Px cos phi sin r = R cos(r - psi) */
    double psi = atan2(-rule->pole[0] * cphi, rule->pole[2]);
    *lo = fmax(0.0, psi - 0.5 * PI);
    *hi = fmin(0.5 * PI, psi + 0.5 * PI);
    return *hi > *lo;
}

/* The point at (r, phi) (wi, and N.H, V.H from h itself: AQ_HALF, AQ_TABLE)
 * and the Jacobian of d wi (without cos theta_i). */
static double direction(const aq_rule *rule, const double wo[3], double r, double cphi,
                        double sphi, aq_point *pt)
{
    double sr = sin(r), cr = cos(r), *wi = pt->wi;
    if (rule->kind != AQ_POLE) {
        double h[3] = { sr * cphi, sr * sphi, cr };
        double oh = wo[0] * h[0] + wo[2] * h[2];
        for (int c = 0; c < 3; c++)
            wi[c] = 2 * oh * h[c] - wo[c];
        pt->nh = cr;
        pt->vh = oh;
        return 4 * oh * sr;
    }
    const double *P = rule->pole;
    double e1[3] = { P[2], 0, -P[0] }; /* (0, 1, 0) x P */
    wi[0] = cr * P[0] + sr * cphi * e1[0];
    wi[1] = sr * sphi;
    wi[2] = cr * P[2] + sr * cphi * e1[2];
    pt->nh = pt->vh = -1;
    return sr;
}

/* The points of one phi: returns their number. */
static size_t radial_points(const aq_rule *rule, const double wo[3], double phi, double wphi,
                            const double *xr, const double *wr, double *t, aq_point *pts)
{
    double cphi = cos(phi), sphi = sin(phi), lo, hi;
    if (!radial_range(rule, wo, cphi, &lo, &hi))
        return 0;
    int nt = rule->kind == AQ_TABLE ? table_breakpoints(hi, t) : breakpoints(lo, hi, rule->width, t);
    if (rule->kind == AQ_HALF && (rule->kinks || rule->kink_q))
        nt = kink_breakpoints(rule, wo, cphi, sphi, t, nt);
    size_t n = 0;
    for (int s = 0; s + 1 < nt; s++) {
        double a = t[s], half = 0.5 * (t[s + 1] - t[s]);
        for (int q = 0; q < rule->order; q++) {
            double r = a + half * (xr[q] + 1);
            double jac = direction(rule, wo, r, cphi, sphi, &pts[n]);
            if (!(pts[n].wi[2] > 0))
                continue;
            pts[n].w = wphi * half * wr[q] * jac * pts[n].wi[2];
            n++;
        }
    }
    return n;
}

/* The phi panels: one, or, when the radial range's end swings fast about
 * phi = pi/2 (wo or the pole tilted far from the normal: psi = atan2(t cos
 * phi, 1), t = tan of the tilt), three, the middle one pi/2 -+ 2/t wide with
 * half the points. */
static int base_panels(const aq_rule *rule, const double wo[3], double *edge, int *count)
{
    const double *P = rule->kind == AQ_POLE ? rule->pole : wo;
    double t = fabs(P[0]) / fmax(fabs(P[2]), 1e-300);
    if (t <= 2.0) {
        edge[0] = 0;
        edge[1] = PI;
        count[0] = rule->nphi;
        return 1;
    }
    double w = 2.0 / t;
    edge[0] = 0;
    edge[1] = 0.5 * PI - w;
    edge[2] = 0.5 * PI + w;
    edge[3] = PI;
    count[1] = rule->nphi / 3;
    count[0] = (rule->nphi - count[1]) / 2;
    count[2] = rule->nphi - count[0] - count[1];
    return 3;
}

/* The phis where the kinks (albedo.h) meet the ends of the radial range or
 * each other: psi = 0 (the mirror kink leaves at r = 0), pi/6 (pi/2 - psi
 * meets the horizon's end), pi/4 (the three meet); cos phi = tan psi /
 * tan theta_o.  Returns their number. */
static int kink_phis(const aq_rule *rule, const double wo[3], double *phi)
{
    if (rule->kind != AQ_HALF || !rule->kinks || !(wo[0] > 0))
        return 0;
    static const double psis[3] = { 0.0, PI / 6, PI / 4 };
    int n = 0;
    for (int k = 0; k < 3; k++) {
        double c = tan(psis[k]) * wo[2] / wo[0];
        if (c < 1.0)
            phi[n++] = acos(c);
    }
    return n;
}

/* The base panels split at the kinks' phis, each part taking its share of
 * its panel's points by width (at least 2). */
static int phi_panels(const aq_rule *rule, const double wo[3], double *edge, int *count)
{
    double be[4], kp[AQ_MAX_PHI_KINKS];
    int bc[3], nb = base_panels(rule, wo, be, bc), nk = kink_phis(rule, wo, kp), n = 0;
    edge[0] = 0;
    for (int b = 0; b < nb; b++) {
        double cut[AQ_MAX_PHI_KINKS + 2];
        int nc = 0;
        cut[nc++] = be[b];
        for (int k = nk - 1; k >= 0; k--) /* kp falls with k: ascending */
            if (kp[k] > be[b] + 1e-9 && kp[k] < be[b + 1] - 1e-9)
                cut[nc++] = kp[k];
        cut[nc++] = be[b + 1];
        for (int j = 0; j + 1 < nc; j++) {
            int c = (int)lround(bc[b] * (cut[j + 1] - cut[j]) / (be[b + 1] - be[b]));
            count[n] = nc == 2 ? bc[b] : c < AQ_MIN_PANEL ? AQ_MIN_PANEL : c;
            edge[++n] = cut[j + 1];
        }
    }
    return n;
}

size_t aq_points(const aq_rule *rule, const double wo[3], aq_point *pts)
{
    double xr[MAX_ORDER], wr[MAX_ORDER];
    double t[MAX_POLE_LEVELS + END_LEVELS + MID_STEPS + MAX_KINKS + TABLE_BINS + 3];
    double edge[AQ_MAX_PANELS + 1];
    int count[AQ_MAX_PANELS];
    aq_gauss_legendre(rule->order, xr, wr);
    int npanels = phi_panels(rule, wo, edge, count);
    size_t n = 0;
    for (int pa = 0; pa < npanels; pa++) {
        double xp[MAX_ORDER], wp[MAX_ORDER], half_phi = 0.5 * (edge[pa + 1] - edge[pa]);
        aq_gauss_legendre(count[pa], xp, wp);
        for (int i = 0; i < count[pa]; i++) {
            double phi = edge[pa] + half_phi * (xp[i] + 1);
            double wphi = 2.0 * half_phi * wp[i]; /* x2: the symmetry in y */
            n += radial_points(rule, wo, phi, wphi, xr, wr, t, pts + n);
        }
    }
    return n;
}
