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
    size_t per = rule->kind == AQ_TABLE ? TABLE_BINS + 1 : MAX_POLE_LEVELS + END_LEVELS + MID_STEPS + 2;
    return (size_t)rule->nphi * (size_t)rule->order * per;
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
static int phi_panels(const aq_rule *rule, const double wo[3], double *edge, int *count)
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

size_t aq_points(const aq_rule *rule, const double wo[3], aq_point *pts)
{
    double xr[MAX_ORDER], wr[MAX_ORDER];
    double t[MAX_POLE_LEVELS + END_LEVELS + MID_STEPS + TABLE_BINS + 3], edge[4];
    int count[3];
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
