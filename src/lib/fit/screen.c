/* SPDX-License-Identifier: MIT */
/* screen.c -- start screening: which starts of the model's start grid LM
 * refines.  Each start is screened with one value pass (its exact best d, s
 * and cost), on the model's screening subsets when it has them, and the
 * best are kept, in the order the refinement takes them.  Which samples
 * and which starts, not how LM moves: apart from the reduced problem
 * (problem.c) and from what is done with the kept starts (refine.c).  The
 * screening's subsets are made from the sample set itself (subsets.c);
 * docs/fitting.md, "Starts". */
#include "fit_internal.h"

#include "round_search.h"
#include "subsets.h"

#include <math.h>
#include <string.h>

/* The lobe parameters of start number i of n: the model's start grid (see
 * bf_start_grid in registry.h). */
static void start_params(brdffit_model model, int i, int n, double p[BRDFFIT_MAX_LOBE_PARAMS])
{
    const bf_start_grid *gr = &bf_model_def_get(model)->grid;
    const brdffit_model_info *mi = brdffit_model_get(model);
    bf_model_start_params(model, p, BRDFFIT_MAX_LOBE_PARAMS);
    int k = gr->period > 0 ? i % gr->period : i, m = gr->period > 0 ? gr->period : n;
    double v = gr->lo;
    if (m > 1) {
        if (gr->spacing == BRDFFIT_MAP_LOG)
            v = gr->lo * pow(gr->hi / gr->lo, (double)k / (m - 1));
        else
            v = gr->lo + (gr->hi - gr->lo) * k / (m - 1);
    } else if (gr->period == 0) { /* one start: the middle of the grid */
        v = gr->spacing == BRDFFIT_MAP_LOG ? gr->lo * pow(gr->hi / gr->lo, 0.5)
                                           : 0.5 * (gr->lo + gr->hi);
    }
    p[gr->param] = v;
    if (gr->round_param >= 0 && gr->period > 0) {
        /* rounds 0, 1, 2, 3, 4, ...: factor^0, ^1, ^-1, ^2, ^-2, ... */
        int r = gr->round_param, k = i / gr->period;
        int e = k % 2 ? (k + 1) / 2 : -(k / 2);
        p[r] *= pow(gr->round_factor, (double)e);
        p[r] = fmin(fmax(p[r], mi->params[r].lower), mi->params[r].upper);
    }
}

/* One value pass at the start's lobe with d = s = 0 gives the exact best
 * linear part there. */
static brdffit_status screen_start(lmstate *S, const double p[BRDFFIT_MAX_LOBE_PARAMS], start *sp)
{
    bf_pass_par pp;
    memset(&pp, 0, sizeof pp);
    memcpy(pp.lam, S->lam, sizeof pp.lam);
    memcpy(pp.p[0], p, 3 * sizeof *p);
    double mom[BF_NMOM_MAX];
    brdffit_status st = bf_driver_run(S->ps, 0, &pp, mom, S->err);
    if (st != BRDFFIT_OK)
        return st;
    const bf_linear zero = { { 0, 0, 0 }, { 0, 0, 0 } };
    sp->cost = bf_linear_best(mom, S->ps->nk, 0, &zero, &sp->lin);
    memmove(sp->p, p, sizeof sp->p); /* p may be sp->p: a kept start taken again */
    bf_params_to_coords(&S->fm, p, sp->x);
    return BRDFFIT_OK;
}

/* A kept start taken again on S->ps's samples with a full pass at its
 * coordinates (d, s at the screening's as the reference): its cost and best
 * d, s there, and the pass kept in it for the first evaluation of the LM run
 * that starts from it (problem.c, seed_serves), which would take that same pass: one
 * value pass less per kept start.  No fit ends above the stored run
 * (bench/baseline-errors.tsv); the time saved: docs/performance.md. */
static brdffit_status seed_start(lmstate *S, start *sp)
{
    S->ref = sp->lin;
    brdffit_status st = bf_take_pass(S, sp->x, sp->mom, &sp->cost, &sp->lin);
    sp->mom_ref = S->ref;
    sp->seeded = st == BRDFFIT_OK ? S->ps : NULL;
    return st;
}

/* Starts come in rounds of the start grid's period when a round changes a
 * parameter (He: 7 values of tau at one sigma0, then 7 at the next); the
 * other models' starts are one round. */
static int start_round(brdffit_model model, int i)
{
    const bf_start_grid *gr = &bf_model_def_get(model)->grid;
    return gr->period > 0 && gr->round_param >= 0 ? i / gr->period : 0;
}

/* The screening's choice so far: the best `refine` starts, cheapest first
 * (keep, *nkeep of them), and the best of each round (round_best). */
typedef struct screening {
    start *keep;
    int *nkeep, refine;
    start round_best[MAX_KEEP];
    int nrounds;
} screening;

/* Take a screened start into the choice. */
static void consider(screening *sc, const start *cand)
{
    int r = cand->round;
    if (r < MAX_KEEP) {
        if (r >= sc->nrounds || cand->cost < sc->round_best[r].cost)
            sc->round_best[r] = *cand;
        if (r >= sc->nrounds)
            sc->nrounds = r + 1;
    }
    int pos = *sc->nkeep;
    while (pos > 0 && cand->cost < sc->keep[pos - 1].cost)
        pos--;
    if (pos >= sc->refine)
        return;
    if (*sc->nkeep < sc->refine)
        (*sc->nkeep)++;
    memmove(sc->keep + pos + 1, sc->keep + pos, (size_t)(*sc->nkeep - 1 - pos) * sizeof *sc->keep);
    sc->keep[pos] = *cand;
}

/* Screen the round of starts first .. first + n - 1 into sc: every start,
 * or with search the ones bf_round_next asks for (round_search.c); the
 * screened ones are then considered in their order in the grid. */
static brdffit_status screen_round(lmstate *S, int first, int n, int nstarts, int search,
                                   screening *sc)
{
    start cand[BF_ROUND_MAX];
    double cost[BF_ROUND_MAX];
    for (int k = 0; k < n; k++)
        cost[k] = NAN;
    for (int k = 0; k < n; k++) {
        int next = search ? bf_round_next(n, cost) : k;
        if (next < 0)
            break;
        double p[BRDFFIT_MAX_LOBE_PARAMS];
        start *c = &cand[next];
        memset(c, 0, sizeof *c);
        start_params(S->fm.model, first + next, nstarts, p);
        brdffit_status st = screen_start(S, p, c);
        if (st != BRDFFIT_OK)
            return st;
        c->index = first + next;
        c->round = start_round(S->fm.model, first + next);
        cost[next] = c->cost;
    }
    for (int k = 0; k < n; k++)
        if (!isnan(cost[k]))
            consider(sc, &cand[k]);
    return BRDFFIT_OK;
}

/* Screen nstarts starts; keep the best `refine` of them, cheapest first, and
 * then the best start of every other round (the cheapest start of the
 * screening is not always in the best basin: measured on He, where each
 * round's best finds a minimum the other misses).  With refine = 1 and a
 * grid in rounds (He), each round is searched for its cheapest start
 * (bf_round_next) instead of screened whole: that start is all the round
 * gives the choice. */
static brdffit_status screen_starts(lmstate *S, int nstarts, int refine, start *keep, int *nkeep)
{
    screening sc;
    memset(&sc, 0, sizeof sc);
    sc.keep = keep;
    sc.nkeep = nkeep;
    sc.refine = refine;
    *nkeep = 0;
    const bf_start_grid *gr = &bf_model_def_get(S->fm.model)->grid;
    const int rounds = gr->period > 0 && gr->round_param >= 0;
    const int period = rounds ? gr->period : nstarts;
    const int search = refine == 1 && rounds && period <= BF_ROUND_MAX;
    /* each round in pieces of at most BF_ROUND_MAX starts (a searched one
     * whole), considered in grid order as the whole round would be */
    for (int first = 0; first < nstarts;) {
        int end = first - first % period + period; /* the end of first's round */
        end = end < nstarts ? end : nstarts;
        int n = end - first < BF_ROUND_MAX ? end - first : BF_ROUND_MAX;
        brdffit_status st = screen_round(S, first, n, nstarts, search, &sc);
        if (st != BRDFFIT_OK)
            return st;
        first += n;
    }
    for (int r = 0; r < sc.nrounds && *nkeep < MAX_KEEP; r++) {
        int kept = 0;
        for (int k = 0; k < *nkeep && !kept; k++)
            kept = memcmp(keep[k].x, sc.round_best[r].x, sizeof keep[k].x) == 0;
        if (!kept)
            keep[(*nkeep)++] = sc.round_best[r];
    }
    return BRDFFIT_OK;
}

/* Whether kept start a comes before b in screen_starts' order: the `refine`
 * cheapest first (head: by cost, then by number), then the others by round. */
static int kept_before(const start *a, int a_head, const start *b, int b_head)
{
    if (a_head != b_head)
        return a_head;
    if (a_head)
        return a->cost < b->cost || (a->cost == b->cost && a->index < b->index);
    return a->round < b->round;
}

/* Kept starts taken again on other samples put in the order screen_starts
 * gives them there (so that the same kept starts lead to the same runs). */
static void keep_order(start *keep, int nkeep, int refine)
{
    int head[MAX_KEEP] = { 0 };
    for (int h = 0; h < refine && h < nkeep; h++) { /* the cheapest not yet in the head */
        int best = -1;
        for (int k = 0; k < nkeep; k++)
            if (!head[k] && (best < 0 || kept_before(&keep[k], 1, &keep[best], 1)))
                best = k;
        head[best] = 1;
    }
    for (int i = 1; i < nkeep; i++) { /* insertion sort: a few starts */
        start t = keep[i];
        int th = head[i], j = i;
        for (; j > 0 && kept_before(&t, th, &keep[j - 1], head[j - 1]); j--) {
            keep[j] = keep[j - 1];
            head[j] = head[j - 1];
        }
        keep[j] = t;
        head[j] = th;
    }
}

/* screen_starts on the model's bin subset (bins: bf_screen_subsets), through
 * D->bins, opened here (bins_open) and closed by the caller; then, unless
 * the model refines on the bin subset first (refine_on_bins: its runs start
 * there, in the screening's order), the kept starts taken again on S->ps's
 * samples and ordered as a screening there orders them. */
static brdffit_status screen_on_bins(lmstate *S, fitsubsets *D, brdffit_context *ctx,
                                     const brdffit_samples *bins, int nstarts, int refine,
                                     start *keep, int *nkeep)
{
    bf_pass_driver *on = S->ps;
    brdffit_status st = bf_driver_open(D->bins, ctx, bins, S->fm.model, S->err);
    D->bins_open = st == BRDFFIT_OK;
    if (st != BRDFFIT_OK)
        return st;
    S->ps = D->bins;
    st = screen_starts(S, nstarts, refine, keep, nkeep);
    S->ps = on;
    if (bf_model_def_get(S->fm.model)->refine_on_bins)
        return st;
    for (int k = 0; k < *nkeep && st == BRDFFIT_OK; k++)
        st = seed_start(S, &keep[k]); /* its index and round stay */
    if (st == BRDFFIT_OK)
        keep_order(keep, *nkeep, refine);
    return st;
}

/* screen_starts on the model's screening subsets (bf_screen_subsets: every
 * screen_stride-th sample through *sd, opened here and closed by the
 * caller; first on the bin subset when it has one, through D->bins, which
 * the caller closes too), or on all samples when it has none.  A model that
 * refines on the subset (registry:
 * refine_on_subset) keeps D->sub = sd and its kept starts as the subset
 * left them; otherwise the kept starts' cost and d, s are taken again on
 * all samples, so that each is refined from exactly where a screening on
 * all samples would have left it. */
brdffit_status bf_screen_kept(lmstate *S, fitsubsets *D, brdffit_context *ctx,
                              const brdffit_samples *samples, int nstarts, int refine, start *keep,
                              int *nkeep, bf_pass_driver *sd)
{
    const brdffit_samples *sub = NULL, *bins = NULL;
    brdffit_status st = bf_screen_subsets(samples, S->fm.model, &sub, &bins, S->err);
    if (st != BRDFFIT_OK)
        return st;
    if (!sub)
        return screen_starts(S, nstarts, refine, keep, nkeep);
    bf_pass_driver *all = S->ps;
    st = bf_driver_open(sd, ctx, sub, S->fm.model, S->err);
    if (st != BRDFFIT_OK)
        return st;
    S->ps = sd;
    if (bins)
        st = screen_on_bins(S, D, ctx, bins, nstarts, refine, keep, nkeep);
    else
        st = screen_starts(S, nstarts, refine, keep, nkeep);
    S->ps = all;
    if (bf_model_def_get(S->fm.model)->refine_on_subset) {
        D->sub = sd;
        return st;
    }
    for (int k = 0; k < *nkeep && st == BRDFFIT_OK; k++)
        st = seed_start(S, &keep[k]);
    return st;
}
