/* SPDX-License-Identifier: MIT */
/* refine_select.h -- which kept starts' subset runs a fit refines on all
 * samples (refine_select.c; the fit's stages: fit/refine.c, bf_refine_kept). */
#ifndef BRDFFIT_REFINE_SELECT_H
#define BRDFFIT_REFINE_SELECT_H

/* Numbers that place a run's end: two per lobe coordinate (a bounded one:
 * its place in its range, 0 at the lower bound and 1 at the upper, then 0;
 * a direction: its cosine and sine). */
#define BF_END_PLACES 6

/* Two subset ends lie in one valley when their r^T r are within
 * BF_VALLEY_RR of each other (relative) and every place within
 * BF_VALLEY_PLACE (bf_same_valley; refine_select.c says why these). */
#define BF_VALLEY_RR 1e-4
#define BF_VALLEY_PLACE 1e-2

/* How a subset run ended. */
typedef struct bf_run_end {
    double rr;                    /* its r^T r on the subset              */
    double place[BF_END_PLACES];  /* where (see BF_END_PLACES), nplaces of them */
    int joined;                   /* 1: it stopped at an earlier run's end */
} bf_run_end;

/* 1 when every a[k] lies within tol of b[k], k < n (a NaN: 0). */
int bf_places_within(const double *a, const double *b, int n, double tol);

/* 1 when a and b (nplaces places each) lie in one valley. */
int bf_same_valley(const bf_run_end *a, const bf_run_end *b, int nplaces);

/* The most runs bf_refine_select takes (a fit's kept starts at most). */
#define BF_REFINE_MAX 16

/* Which of the n runs ends[0 .. n-1] go on to all samples, into refine[r]
 * (1: refine it).  The candidates are the runs whose r^T r is within margin
 * (relative) of the lowest of the n (any, margin INFINITY) and that did not
 * stop at an earlier run's end (joined); taken from the lowest r^T r up (a
 * tie: the earlier run first), each is refined unless it lies in one valley
 * with one refined before it: of the ends in one valley, only the lowest.
 * n at most BF_REFINE_MAX; nplaces at most BF_END_PLACES. */
void bf_refine_select(const bf_run_end *ends, int n, int nplaces, double margin, int *refine);

#endif /* BRDFFIT_REFINE_SELECT_H */
