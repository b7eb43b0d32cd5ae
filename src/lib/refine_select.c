/* SPDX-License-Identifier: MIT */
/* refine_select.c -- bf_refine_select: which subset runs a fit refines on
 * all samples.
 *
 * He refines each kept start by LM on the stride subset first, then only
 * some of those runs on all samples, each pass of which costs up to ~7
 * subset passes at a rough point (fit/refine.c, bf_refine_kept).  A run whose subset
 * r^T r ends more than SUBSET_MARGIN above the lowest is not refined, nor
 * one that stopped at an earlier run's end (join_end).  Of the others, two
 * whose ends lie in one valley (r^T r within BF_VALLEY_RR and every lobe
 * coordinate within BF_VALLEY_PLACE of its range) are one minimum seen
 * through the subset: only the lower end is refined (in the three MERL fits
 * with such a pair, its run on all samples ended as low as the other's, to
 * 5e-10, or lower).  Refining both ends of such a valley spends passes on
 * one minimum (hematite, nickel, black-obsidian over the 100 MERL tables;
 * docs/fitting.md), and where the two ends differ on all samples the lower
 * comes from the lower subset end. */
#include "refine_select.h"

#include <math.h>

int bf_places_within(const double *a, const double *b, int n, double tol)
{
    for (int k = 0; k < n; k++)
        if (!(fabs(a[k] - b[k]) <= tol))
            return 0;
    return 1;
}

int bf_same_valley(const bf_run_end *a, const bf_run_end *b, int nplaces)
{
    return fabs(a->rr - b->rr) <= BF_VALLEY_RR * fmax(a->rr, b->rr)
           && bf_places_within(a->place, b->place, nplaces, BF_VALLEY_PLACE);
}

/* A run within margin of the lowest (any, margin infinite) and not joined. */
static int candidate(const bf_run_end *e, double lowest, double margin)
{
    return !e->joined && (isinf(margin) || e->rr <= lowest * (1.0 + margin));
}

void bf_refine_select(const bf_run_end *ends, int n, int nplaces, double margin, int *refine)
{
    double lowest = INFINITY;
    for (int r = 0; r < n; r++) {
        lowest = fmin(lowest, ends[r].rr);
        refine[r] = 0;
    }
    if (n > BF_REFINE_MAX) /* past the documented bound: the first ones only */
        n = BF_REFINE_MAX;
    /* the candidates from the lowest r^T r up (ties: the earlier first),
     * each refined unless it lies in one valley with one refined before */
    int seen[BF_REFINE_MAX] = { 0 };
    for (int k = 0; k < n; k++) {
        int r = -1;
        for (int q = 0; q < n; q++)
            if (!seen[q] && candidate(&ends[q], lowest, margin) && (r < 0 || ends[q].rr < ends[r].rr))
                r = q;
        if (r < 0)
            return;
        seen[r] = 1;
        refine[r] = 1;
        for (int q = 0; q < n && refine[r]; q++)
            if (q != r && refine[q] && bf_same_valley(&ends[q], &ends[r], nplaces))
                refine[r] = 0;
    }
}
