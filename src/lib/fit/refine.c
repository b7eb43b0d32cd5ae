/* SPDX-License-Identifier: MIT */
/* refine.c -- the refinement policy: what LM runs a fit makes from the kept
 * starts, on which samples and in which order (the bin subset, the stride
 * subset, all samples), with which secant correction, what it does with a
 * run that ends on a bound or at an earlier run's end, which runs go on,
 * and the polish of the best.  The stages, not the numerics of a run
 * (problem.c) nor the choice of starts (screen.c); docs/fitting.md,
 * "Refinement" and "What ends a fit". */
#define _DEFAULT_SOURCE /* M_PI_2 */
#include "fit_internal.h"

#include "refine_select.h"

#include <math.h>
#include <string.h>

enum { LM_RESTARTS = 2 };
_Static_assert(MAX_KEEP <= BF_REFINE_MAX, "bf_refine_select takes every kept start");

/* The secant estimate of the residuals' curvature that a run ends with is
 * where the next run on the same minimum starts (bf_lm_once): the run on all
 * samples from the subset's end (scaled by the ratio of their sums of a2,
 * as the subset's sums are a sample of the full ones), the polish, and a
 * restart after max_evals: started at 0, LM would spend its first
 * iterations relearning it (docs/performance.md).  A run from another point
 * (bound_restart) or with pinned coordinates (pinned_run) starts afresh. */
static void sc_forget(lmrun *run)
{
    memset(run->sc, 0, sizeof run->sc);
    run->sc_a2 = 0.0;
}

/* lmder from run->x (updated in place).  A run that stops on max_evals
 * (info 5) is restarted from where it stopped, with a fresh trust region,
 * up to LM_RESTARTS times; run->info is the last run's. */
static brdffit_status lm_converge(lmstate *S, const brdffit_fit_options *o, lmrun *run,
                                  double *solver_s)
{
    for (int k = 0; k <= LM_RESTARTS; k++) {
        brdffit_status st = bf_lm_once(S, o, run, solver_s);
        if (st != BRDFFIT_OK || run->info != 5)
            return st;
    }
    return BRDFFIT_OK;
}

/* After refining on the subset, a start whose subset r^T r is more than
 * this above the lowest is not refined on all samples: over the 100 MERL
 * tables no He fit differs by more than 5e-10 relative from refining them
 * all, and the fits are shorter (docs/fitting.md). */
#define SUBSET_MARGIN 0.02

/* On the subset, plain Gauss-Newton LM for the first evaluations of a run,
 * then with the secant correction.  With it from the first (He),
 * blue-metallic-paint slides into another minimum, 0.37% worse; without it,
 * LM crawls along the flat valleys of tau and sigma0 (silver-metallic-paint2:
 * two of its starts stop 1e-2 apart in the valley).  From the 8th He takes
 * the fewest subset passes with no fit above the stored run (docs/fitting.md). */
#define SUBSET_SECANT_FROM 8

/* lm_converge on the passes of dr (the points cached for the other driver's
 * samples are not this one's). */
static brdffit_status lm_on(lmstate *S, bf_pass_driver *dr, const brdffit_fit_options *o,
                            lmrun *run, double *solver_s)
{
    bf_pass_driver *was = S->ps;
    S->ps = dr;
    bf_cache_clear(S);
    brdffit_status st = lm_converge(S, o, run, solver_s);
    S->ps = was;
    bf_cache_clear(S);
    return st;
}

/* LM on a subset (dr: the screening's, sub, or its bin subset) from run
 * (its d, s the reference), with the secant correction from the
 * SUBSET_SECANT_FROM-th evaluation on (from the first if the model uses it
 * always). */
static brdffit_status lm_subset(lmstate *S, bf_pass_driver *dr, const brdffit_fit_options *o,
                                lmrun *run, double *solver_s)
{
    S->ref = run->lin;
    S->secant = S->secant_use == BF_SECANT_ALWAYS;
    S->secant_from = SUBSET_SECANT_FROM;
    brdffit_status st = lm_on(S, dr, o, run, solver_s);
    S->secant_from = 0;
    return st;
}

/* Keep cand in *run when it ended lower; its LM iterations count either way
 * (cand started as a copy of *run, so its njev includes run's). */
static void keep_lower(lmrun *run, const lmrun *cand)
{
    if (cand->rr < run->rr)
        *run = *cand;
    else
        run->njev = cand->njev;
}

/* A run that has not moved from start sp. */
static void run_at(lmrun *run, const start *sp)
{
    memset(run, 0, sizeof *run);
    memcpy(run->x, sp->x, sizeof run->x);
    run->lin = sp->lin;
    run->rr = sp->cost;
}

/* Refining a start is two stages (three with refine_on_bins: bins_runs
 * first).  refine_subset: LM on the screening's subset when the model's
 * registry entry says so (sub; else the start as screened on all
 * samples), with the secant correction from its SUBSET_SECANT_FROM-th
 * evaluation on (from the first if the model uses it always).  refine_all:
 * LM on all samples from there, with it.  A lobe
 * coordinate that ends on its bound is stuck there whether or not the data's
 * optimum is inside (v = lo + (hi-lo)(1+sin u)/2 has no gradient at the
 * bounds), so such a run is repeated from a point a quarter of the range
 * inside on those coordinates (bound_restart), and the better kept; one that
 * still ends there is taken once more with them held on the bound
 * (pinned_run). */
static brdffit_status refine_subset(lmstate *S, bf_pass_driver *sub, const brdffit_fit_options *o,
                                    const start *sp, lmrun *run, double *solver_s)
{
    run_at(run, sp);
    if (!sub)
        return BRDFFIT_OK;
    S->seed = sp;
    brdffit_status st = lm_subset(S, sub, o, run, solver_s);
    S->seed = NULL;
    return st;
}

/* A run that ended with lobe coordinates on their bounds (mask), from a
 * quarter of the range inside on those: on the subset first when there is
 * one (sub), and on all samples only if it did not come back to the same bounds
 * and point there; the lower run into *run. */
static brdffit_status bound_restart(lmstate *S, bf_pass_driver *sub, const brdffit_fit_options *o,
                                    lmrun *run, unsigned mask, double *solver_s)
{
    lmrun again = *run;
    sc_forget(&again);
    for (int j = 0; j < S->fm.nl; j++)
        if (mask & (1u << j))
            again.x[j] = asin(bf_coord_position(&S->fm, j, run->x[j]) < 0.5 ? -0.5 : 0.5);
    brdffit_status st;
    if (sub) {
        st = lm_subset(S, sub, o, &again, solver_s);
        if (st != BRDFFIT_OK)
            return st;
        if (bf_on_bounds(&S->fm, again.x) == mask && bf_same_coords(&S->fm, again.x, run->x)) {
            run->njev = again.njev;
            return BRDFFIT_OK;
        }
    }
    S->ref = again.lin;
    S->secant = 1;
    st = lm_converge(S, o, &again, solver_s);
    if (st == BRDFFIT_OK)
        keep_lower(run, &again);
    return st;
}

/* lm_converge with the lobe coordinates of mask held where they are
 * (S->pinned; none when mask is 0).  The cached points were assembled
 * without the pins, and the run's with them: the cache is cleared on both
 * sides of a pinned run. */
static brdffit_status lm_converge_pinned(lmstate *S, const brdffit_fit_options *o, lmrun *run,
                                         unsigned mask, double *solver_s)
{
    S->pinned = mask;
    if (mask)
        bf_cache_clear(S);
    brdffit_status st = lm_converge(S, o, run, solver_s);
    if (mask)
        bf_cache_clear(S);
    S->pinned = 0;
    return st;
}

/* LM on all samples with the coordinates of mask held exactly on their
 * bounds (S->pinned: their rows of J^T J and J^T r are 0, so every step
 * leaves them), from *run, kept when lower.  LM that ends on a bound with
 * the coordinate free stops early: the sin map's fold leaves a column that
 * vanishes only at the bound itself, and the rest converge slowly beside it
 * (measured, He, black-soft-plastic: 1.2e-5 above where a second run from
 * inside went). */
static brdffit_status pinned_run(lmstate *S, const brdffit_fit_options *o, lmrun *run,
                                 unsigned mask, double *solver_s)
{
    lmrun pin = *run;
    sc_forget(&pin);
    for (int j = 0; j < S->fm.nl; j++)
        if (mask & (1u << j))
            pin.x[j] = bf_coord_position(&S->fm, j, run->x[j]) < 0.5 ? -M_PI_2 : M_PI_2;
    S->ref = pin.lin;
    S->secant = 1;
    brdffit_status st = lm_converge_pinned(S, o, &pin, mask, solver_s);
    if (st == BRDFFIT_OK)
        keep_lower(run, &pin);
    return st;
}

static brdffit_status refine_all(lmstate *S, bf_pass_driver *sub, const brdffit_fit_options *o,
                                 lmrun *run, double *solver_s)
{
    S->ref = run->lin;
    S->secant = 1; /* on all samples: ALWAYS and ON_ALL alike */
    brdffit_status st = lm_converge(S, o, run, solver_s);
    unsigned mask = st == BRDFFIT_OK ? bf_on_bounds(&S->fm, run->x) : 0u;
    if (!mask)
        return st;
    st = bound_restart(S, sub, o, run, mask, solver_s);
    mask = st == BRDFFIT_OK ? bf_on_bounds(&S->fm, run->x) : 0u;
    if (!mask)
        return st;
    return pinned_run(S, o, run, mask, solver_s);
}

/* Where a run ended, as bf_refine_select sees it (bf_coord_places). */
static void run_end(const fitmap *fm, const lmrun *run, int joined, bf_run_end *e)
{
    e->rr = run->rr;
    e->joined = joined;
    bf_coord_places(fm, run->x, e->place);
}

/* Before run r of runs: a point it comes to at the end of runs 0 .. r-1
 * stops it there (join_end). */
static void join_before(lmstate *S, const lmrun *runs, int r)
{
    S->ends = runs;
    S->nends = r;
    S->joined = -1;
}

/* After it: where it ended (and whether it joined one) into *e, and no
 * joining for the runs that follow elsewhere. */
static void join_after(lmstate *S, const lmrun *run, bf_run_end *e)
{
    run_end(&S->fm, run, S->joined >= 0, e);
    S->nends = 0;
    S->joined = -1;
}

/* A run on the bin subset goes on to the stride subset when it ended
 * within BINS_MARGIN of the lowest bin end (and neither at an earlier run's
 * end nor the higher of two ends in one valley: bf_refine_select).
 * Over the 100 MERL tables, 0.05, 0.1 and 0.2 give the same He fits and
 * passes within ~2%, none above the stored run (docs/fitting.md).
 * 0.1 is five times SUBSET_MARGIN: the bin subset's r^T r
 * ranks ends as the stride subset's does only roughly (silicon-nitrade:
 * 1.36x on the bins, 1.013x on the stride subset, not the lowest on all
 * samples). */
#define BINS_MARGIN 0.1

/* Each kept start by LM on the bin subset (bins), each stopping where it
 * comes to an earlier one's end (problem.c, join_end), into bruns;
 * take[r] = 1 for those that go on to the stride subset (BINS_MARGIN). */
static brdffit_status bins_runs(lmstate *S, bf_pass_driver *bins, const brdffit_fit_options *o,
                                const start *keep, int nkeep, lmrun *bruns, int *take,
                                double *solver_s)
{
    bf_run_end ends[MAX_KEEP];
    for (int r = 0; r < nkeep; r++) {
        run_at(&bruns[r], &keep[r]);
        join_before(S, bruns, r);
        brdffit_status st = lm_subset(S, bins, o, &bruns[r], solver_s);
        join_after(S, &bruns[r], &ends[r]);
        if (st != BRDFFIT_OK)
            return st;
    }
    bf_refine_select(ends, nkeep, 2 * S->fm.nl, BINS_MARGIN, take);
    return BRDFFIT_OK;
}

/* Where kept start k's run on the stride subset starts after its run on the
 * bin subset ended at bin: there, or at k itself when the end is rough
 * (registry: rough_param, rough_from).  Neither has a seeded pass. */
static void start_after_bins(const lmstate *S, const start *k, const lmrun *bin, start *sp)
{
    const bf_model_def *def = bf_model_def_get(S->fm.model);
    double p[BRDFFIT_MAX_LOBE_PARAMS];
    bf_coords_to_params(&S->fm, bin->x, p);
    *sp = *k;
    if (p[def->rough_param] >= def->rough_from)
        return;
    memcpy(sp->p, p, sizeof sp->p);
    memcpy(sp->x, bin->x, sizeof sp->x);
    sp->lin = bin->lin;
    sp->cost = bin->rr;
}

/* Every kept start on the subset (each stopping where it comes to an
 * earlier one's end: join_end; when the model refines on the bin subset
 * first, those bins_runs takes, from start_after_bins' point, the others
 * not run: r^T r infinite), then on all samples those bf_refine_select
 * takes: within SUBSET_MARGIN of the lowest subset Error, not joined, and of
 * the ends that lie in one valley the lowest (without a subset: every kept
 * start); the lowest run into *best. */
brdffit_status bf_refine_kept(lmstate *S, const fitsubsets *D, const brdffit_fit_options *o,
                              const start *keep, int nkeep, lmrun *best, double *solver_s)
{
    lmrun runs[MAX_KEEP], bruns[MAX_KEEP];
    bf_run_end ends[MAX_KEEP];
    int refine[MAX_KEEP], take[MAX_KEEP];
    const int on_bins = D->sub && D->bins_open && bf_model_def_get(S->fm.model)->refine_on_bins;
    brdffit_status st =
        on_bins ? bins_runs(S, D->bins, o, keep, nkeep, bruns, take, solver_s) : BRDFFIT_OK;
    for (int r = 0; r < nkeep && st == BRDFFIT_OK; r++) {
        const start *from = &keep[r];
        start after;
        if (on_bins) {
            start_after_bins(S, &keep[r], &bruns[r], &after);
            from = &after;
        }
        join_before(S, runs, r);
        if (on_bins && !take[r]) {
            run_at(&runs[r], from);
            runs[r].rr = INFINITY;
        } else {
            st = refine_subset(S, D->sub, o, from, &runs[r], solver_s);
        }
        join_after(S, &runs[r], &ends[r]);
    }
    if (st != BRDFFIT_OK)
        return st;
    if (D->sub)
        bf_refine_select(ends, nkeep, 2 * S->fm.nl, SUBSET_MARGIN, refine);
    else /* each start as screened on all samples: no run to compare */
        for (int r = 0; r < nkeep; r++)
            refine[r] = 1;
    for (int r = 0; r < nkeep; r++) {
        if (!refine[r])
            continue;
        lmrun run = runs[r];
        S->seed = &keep[r]; /* its pass on all samples, without a subset (seed_start) */
        st = refine_all(S, D->sub, o, &run, solver_s);
        S->seed = NULL;
        if (st != BRDFFIT_OK)
            return st;
        if (run.rr < best->rr)
            *best = run;
    }
    return BRDFFIT_OK;
}

/* A model whose registry entry says BF_SECANT_ON_ALL (He) then polishes the
 * best run: one more LM run on all samples from where it stopped, with a
 * fresh trust region and ftol, xtol times POLISH_TOL, kept when lower.  It
 * cannot end higher (LM only takes steps that lower the cost).  Without a
 * polish some He fits end higher by 1e-9 to 1.8e-8 relative
 * (silver-metallic-paint); with the caller's tolerances some stay up to
 * 2.6e-8 above where POLISH_TOL = 0.01 takes them (blue-metallic-paint;
 * docs/fitting.md).
 * The lobe coordinates the best run ended on their bounds are held there
 * (S->pinned, as pinned_run holds them): free, their column of J vanishes at
 * the fold, and LM's first steps would run out along them (tau to u = -9e5
 * on gold-metallic-paint), taking 8-10 rejected passes to come back to where
 * the run ended; held, such a polish takes 1-2 passes.
 * A best run whose last point is still evaluated (S->cache) and whose Newton
 * decrement there, |z|^2 / r^T r (z = R^-T g of the corrected H: what a
 * full step of LM's own model would lower r^T r by, relative), is below
 * POLISH_SKIP is not polished: the polish's first step would have predicted
 * less than its ftol.  A polish lowers r^T r by about the decrement, and a
 * skipped one saves 1-3 passes on all samples; over the 100 MERL tables the
 * lowest decrement of a polish that gains 1e-9 is 7.4e-11 (pearl-paint,
 * along a flat valley where LM's model is poor; docs/fitting.md). */
#define POLISH_TOL 0.01
#define POLISH_SKIP 1e-11

/* 1 when the best run's point is cached with a Newton decrement below
 * POLISH_SKIP (see bf_polish). */
static int polish_needless(const lmstate *S, const lmrun *best)
{
    const point *pt = bf_cached(S, best->x);
    if (!pt || !(pt->rr > 0.0))
        return 0;
    double zz = 0.0;
    for (int k = 0; k < S->nx; k++)
        zz += pt->fvec[k] * pt->fvec[k];
    return zz < POLISH_SKIP * pt->rr;
}

brdffit_status bf_polish(lmstate *S, const brdffit_fit_options *o, lmrun *best, double *solver_s)
{
    if (S->secant_use != BF_SECANT_ON_ALL || polish_needless(S, best))
        return BRDFFIT_OK;
    lmrun pol = *best;
    S->secant = 1;
    S->ref = best->lin;
    brdffit_fit_options tight = *o;
    tight.ftol *= POLISH_TOL;
    tight.xtol *= POLISH_TOL;
    brdffit_status st = lm_converge_pinned(S, &tight, &pol, bf_on_bounds(&S->fm, best->x), solver_s);
    if (st == BRDFFIT_OK)
        keep_lower(best, &pol);
    return st;
}
