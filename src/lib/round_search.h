/* SPDX-License-Identifier: MIT */
/* round_search.h -- which starts of a round of the start grid a screening
 * takes (round_search.c; the fit's screening: fit/screen.c). */
#ifndef BRDFFIT_ROUND_SEARCH_H
#define BRDFFIT_ROUND_SEARCH_H

/* The longest round searched (a round's screened starts are held on the
 * stack, ~0.7 kB each); a longer one is screened whole. */
#define BF_ROUND_MAX 16

/* The next start (0 .. n - 1) of a round of n to screen, given the costs of
 * those screened so far (cost[k] is NaN where start k is not screened yet),
 * or -1 when the round is done: first every other start (1, 3, 5, ...;
 * start 0 of a round of one), then, while the cheapest start screened has
 * a neighbour not screened, that neighbour (the lower first).  The round's
 * cheapest start is then the cheapest screened wherever the costs fall and
 * rise once along the round; a round of 7 takes 4 or 5 of them.  n outside
 * [1, BF_ROUND_MAX]: -1. */
int bf_round_next(int n, const double *cost);

#endif /* BRDFFIT_ROUND_SEARCH_H */
