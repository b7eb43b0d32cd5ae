/* SPDX-License-Identifier: MIT */
/* fit_internal.h -- what the fit's files share: the coordinate map (map.c),
 * the points, starts and runs of LM, the reduced problem's state (problem.c),
 * the screening's subsets (screen.c opens them, refine.c runs on them), and
 * the functions one of these files calls in another.  The fit as a whole:
 * docs/fitting.md. */
#ifndef BRDFFIT_FIT_INTERNAL_H
#define BRDFFIT_FIT_INTERNAL_H

#include "linear.h"
#include "pass.h"
#include "registry.h"

#define NX_MAX BF_MAX_NP
#define NM_MAX (NX_MAX + 1)

/* The most kept starts (screen_starts) and so the most runs a fit refines. */
enum { MAX_KEEP = 16 };

/* How lobe coordinate j maps to the model's parameters (registry.c). */
typedef struct fitmap {
    brdffit_model model;
    int nl;                     /* lobe coordinates (at most BF_MAX_NP for a
                                 * model with a lobe, BRDFFIT_MAX_LOBE_PARAMS
                                 * for the affine engine's) */
    brdffit_param_map kind[BRDFFIT_MAX_LOBE_PARAMS];
    int param[BRDFFIT_MAX_LOBE_PARAMS]; /* the (first) lobe parameter of coordinate j */
    double lo[BRDFFIT_MAX_LOBE_PARAMS], hi[BRDFFIT_MAX_LOBE_PARAMS]; /* bounds, in log
                                 * units for BRDFFIT_MAP_LOG */
} fitmap;

/* A screened start. */
typedef struct start {
    double p[BRDFFIT_MAX_LOBE_PARAMS]; /* lobe parameters */
    double x[NX_MAX];   /* lobe coordinates */
    bf_linear lin;      /* the best d, s there */
    double cost;        /* r^T r there */
    int index, round;   /* its number in the start grid, its round */
    const bf_pass_driver *seeded; /* not NULL: mom is the full pass at x on
                                   * this driver's samples (seed_start)     */
    bf_linear mom_ref;  /* the d, s mom was taken at */
    double mom[BF_NMOM_MAX];
} start;

/* An evaluated point of the reduced problem: what lmder is handed there. */
typedef struct point {
    int valid;
    double x[NX_MAX];              /* lobe coordinates u */
    bf_linear lin;                 /* the best d, s at u */
    double fvec[NM_MAX];
    double fjac[NM_MAX * NX_MAX];  /* column-major, leading dimension nx+1 */
    double rr;                     /* r^T r = E^2 */
} point;

/* The outcome of refining one start. */
typedef struct lmrun {
    double x[NX_MAX];
    bf_linear lin;
    double rr;
    int info;           /* lmder's info of the last run */
    int njev;           /* Jacobian evaluations, all runs */
    double sc[NX_MAX][NX_MAX]; /* the secant estimate Sc its last run ended with */
    double sc_a2;       /* the sum of a2 of the samples that made sc (0: none) */
} lmrun;

/* The reduced problem on one driver's samples and the state of its LM run.
 * The fields down to `seed` are set by its callers before a run; the rest
 * are problem.c's own. */
typedef struct lmstate {
    bf_pass_driver *ps;            /* the samples the passes are taken on */
    fitmap fm;
    int nx;
    double lam[3];
    bf_linear ref;                 /* d, s the next pass is taken at */
    bf_secant_use secant_use;      /* the registry's: when secant is set   */
    int secant;                    /* correct H by the secant estimate Sc */
    int secant_from;               /* > 0: correct it from this evaluation of an
                                    * lmder run on (secant unset)           */
    unsigned pinned;               /* lobe coordinates held on their bounds
                                    * (bits; see pinned_run)               */
    const lmrun *ends;             /* the subset runs refined before this one */
    int nends;                     /* (0: it joins none; see join_end)     */
    int joined;                    /* the one of ends it came to (-1: none) */
    const start *seed;             /* a kept start whose full pass the run's
                                    * first evaluation takes (see seed_start) */
    point join;                    /* the point where it joined one of ends */
    point cache[2];
    int next;
    double seconds_cb;             /* time inside the callback */
    int nev;                       /* evaluations assembled in this lmder run */
    int have_prev;                 /* prev_x, prev_g: the point evaluated before in this lmder run */
    double prev_x[NX_MAX], prev_g[NX_MAX];
    double Sc[NX_MAX][NX_MAX];     /* estimate of the Hessian's residual-curvature part */
    brdffit_status st;
    brdffit_error *err;
} lmstate;

/* The screening's subset drivers: opened by the screening, refined on by
 * the stages after it. */
typedef struct fitsubsets {
    bf_pass_driver *sub;           /* the screening's subset, or NULL */
    bf_pass_driver *bins;          /* its bin subset (open when bins_open) */
    int bins_open;
} fitsubsets;

/* ---- map.c ---- */
/* fm for model: its lobe coordinates, their parameters, maps and bounds. */
void bf_fitmap_init(fitmap *fm, brdffit_model model);
/* Lobe coordinates u -> lobe parameters p in the paper's units. */
void bf_coords_to_params(const fitmap *fm, const double *u, double *p);
/* Lobe parameters p -> lobe coordinates u (the inverse map, clamped to the bounds). */
void bf_params_to_coords(const fitmap *fm, const double *p, double *u);
/* Where coordinate j at u stands in its range: 0 lower bound, 1 upper, -1 a direction. */
double bf_coord_position(const fitmap *fm, int j, double u);
/* The places of lobe coordinates x, two a coordinate (see BF_END_PLACES). */
void bf_coord_places(const fitmap *fm, const double *x, double *place);
/* 1 when lobe coordinates xa and xb are one point (SAME_POINT in their places). */
int bf_same_coords(const fitmap *fm, const double *xa, const double *xb);
/* The lobe coordinates of x on a bound (bit j: coordinate j). */
unsigned bf_on_bounds(const fitmap *fm, const double *x);

/* ---- problem.c ---- */
/* A full pass at x taken at S->ref (again at its best d, s while far): moments, r^T r, d, s. */
brdffit_status bf_take_pass(lmstate *S, const double *x, double *mom, double *rr, bf_linear *lin);
/* One lmder run from run->x (updated in place), the secant estimate from run's. */
brdffit_status bf_lm_once(lmstate *S, const brdffit_fit_options *o, lmrun *run, double *solver_s);
/* The evaluated point at x if it is still in the cache (no pass), or NULL. */
const point *bf_cached(const lmstate *S, const double *x);
/* Forget the evaluated points (assembled for other samples or pins). */
void bf_cache_clear(lmstate *S);

/* ---- screen.c ---- */
/* Screen nstarts starts (on the model's subsets: sd, D->bins) and keep the best into keep. */
brdffit_status bf_screen_kept(lmstate *S, fitsubsets *D, brdffit_context *ctx,
                              const brdffit_samples *samples, int nstarts, int refine, start *keep,
                              int *nkeep, bf_pass_driver *sd);

/* ---- refine.c ---- */
/* Refine the kept starts on D's subsets, then on all samples; the lowest run into *best. */
brdffit_status bf_refine_kept(lmstate *S, const fitsubsets *D, const brdffit_fit_options *o,
                              const start *keep, int nkeep, lmrun *best, double *solver_s);
/* The model's polish of the best run: one more LM run on all samples, kept when lower. */
brdffit_status bf_polish(lmstate *S, const brdffit_fit_options *o, lmrun *best, double *solver_s);

/* ---- metric_fit.c: the fit under "log" and "cube-root" (docs/metrics.md) */

/* r holds the "ngan-l2" fit: refits all its parameters under metric (LM,
 * host passes) and sets params, errors[1..], metric, metric_iterations,
 * at_bound and adds its passes, iterations and seconds; error and
 * errors[0] are the caller's. */
brdffit_status bf_metric_refit(const brdffit_samples *samples, brdffit_model model,
                               brdffit_metric metric, brdffit_fit_result *r, brdffit_error *err);
/* errors[1..] (log, cube-root) of params: one host value pass. */
brdffit_status bf_metric_errors(const brdffit_samples *samples, brdffit_model model,
                                const brdffit_params *params, double *errors, brdffit_error *err);

#endif /* BRDFFIT_FIT_INTERNAL_H */
