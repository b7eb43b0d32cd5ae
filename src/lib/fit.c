/* SPDX-License-Identifier: MIT */
/* fit.c -- brdffit_fit: start screening and Levenberg-Marquardt (cminpack).
 *
 * The linear unknowns d, s >= 0 are solved exactly at every lobe point from
 * the pass's moments (variable projection, linear.h): LM moves only the lobe
 * coordinates u (nx = nl of them), as the model registry maps its parameters
 * (brdffit_param_map): a bounded parameter is v = lo + (hi-lo)(1+sin u)/2
 * (lo, hi and v in log units for LOG); a DIRECTION pair (Lafortune's Cxy, Cz)
 * is one angle phi, (a, b) = (cos phi / sqrt 2, sin phi).
 *
 * cminpack's own QR would cost far more than a data pass on ~1M rows, so lmder
 * is given an exactly equivalent problem whose size does not grow with the
 * data: from the reduced normal equations H = J^T J, g = J^T r and r^T r form
 * the Cholesky factor R of H, z = R^-T g, t = sqrt(r^T r - |z|^2), and hand
 * lmder the nx+1 residuals [z; t] with Jacobian [R; 0].  Then
 * |[z;t]|^2 = r^T r and |[z;t] + [R;0] p|^2 = |r + J p|^2 for every step p,
 * so lmder's steps, scaling and convergence tests are those of the full
 * problem.  Each evaluated point caches both (lmder pairs a trial's residual
 * with the Jacobian it asks for next).  H may carry a secant estimate of the
 * residuals' curvature (secant_correct), which Gauss-Newton leaves out.
 *
 * The passes on all samples read the set's mirror set (samples_mirror.c:
 * the same sums from about half the samples); the screening's subsets are
 * made from the set itself.
 */
#define _DEFAULT_SOURCE /* M_PI, M_SQRT2, M_SQRT1_2 */
#include "linear.h"
#include "pass.h"
#include "refine_select.h"
#include "registry.h"
#include "round_search.h"
#include "samples.h"
#include "subsets.h"

#include <cminpack.h>
#include <math.h>
#include <string.h>

#define NX_MAX BF_MAX_NP
#define NM_MAX (NX_MAX + 1)
#define FD_STEP 1e-7
/* A direction angle's step: a sharp Lafortune lobe (n ~ 5e4) varies with the
 * angle on a scale ~1/n, so 1e-7 made its derivative ~1% wrong and LM stop
 * short of the minimum (measured: violet-acrylic 1.2e-7, black-obsidian
 * 1e-8 relative above what 1e-9 reaches; 1e-10 and 1e-11 gave the same). */
#define FD_STEP_DIRECTION 1e-9

/* How lobe coordinate j maps to the model's parameters (registry.c). */
typedef struct fitmap {
    brdffit_model model;
    int nl;                     /* lobe coordinates */
    brdffit_param_map kind[BF_MAX_NP];
    int param[BF_MAX_NP];       /* the (first) lobe parameter of coordinate j */
    double lo[BF_MAX_NP], hi[BF_MAX_NP]; /* bounds, in log units for BRDFFIT_MAP_LOG */
} fitmap;

static void fitmap_init(fitmap *fm, brdffit_model model)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    memset(fm, 0, sizeof *fm);
    fm->model = model;
    fm->nl = bf_model_ncoords(model);
    for (int j = 0; j < fm->nl; j++) {
        int k = bf_model_coord_param(model, j);
        const brdffit_param_info *pi = &mi->params[k];
        fm->param[j] = k;
        fm->kind[j] = pi->map;
        fm->lo[j] = pi->map == BRDFFIT_MAP_LOG ? log(pi->lower) : pi->lower;
        fm->hi[j] = pi->map == BRDFFIT_MAP_LOG ? log(pi->upper) : pi->upper;
    }
}

static double map_fwd(const fitmap *fm, int j, double u)
{
    double v = fm->lo[j] + (fm->hi[j] - fm->lo[j]) * 0.5 * (1.0 + sin(u));
    return fm->kind[j] == BRDFFIT_MAP_LOG ? exp(v) : v;
}

static double map_inv(const fitmap *fm, int j, double v)
{
    if (fm->kind[j] == BRDFFIT_MAP_LOG)
        v = log(v);
    double t = 2.0 * (v - fm->lo[j]) / (fm->hi[j] - fm->lo[j]) - 1.0;
    return asin(fmin(fmax(t, -1.0), 1.0));
}

/* Lobe coordinates u -> lobe parameters p in the paper's units. */
static void coords_to_params(const fitmap *fm, const double *u, double p[3])
{
    p[0] = p[1] = p[2] = 0.0;
    for (int j = 0; j < fm->nl; j++) {
        int k = fm->param[j];
        if (fm->kind[j] == BRDFFIT_MAP_DIRECTION) {
            p[k] = cos(u[j]) * M_SQRT1_2;
            p[k + 1] = sin(u[j]);
        } else {
            p[k] = map_fwd(fm, j, u[j]);
        }
    }
}

static void params_to_coords(const fitmap *fm, const double p[3], double *u)
{
    for (int j = 0; j < fm->nl; j++) {
        int k = fm->param[j];
        if (fm->kind[j] == BRDFFIT_MAP_DIRECTION)
            u[j] = atan2(p[k + 1], p[k] * M_SQRT2);
        else
            u[j] = map_inv(fm, j, p[k]);
    }
}

/* ---------------------------------------------------------------- one point */

typedef struct start {
    double p[3];        /* lobe parameters */
    double x[NX_MAX];   /* lobe coordinates */
    bf_linear lin;      /* the best d, s there */
    double cost;        /* r^T r there */
    int index, round;   /* its number in the start grid, its round */
    const bf_pass_driver *seeded; /* not NULL: mom is the full pass at x on
                                   * this driver's samples (seed_start)     */
    bf_linear mom_ref;  /* the d, s mom was taken at */
    double mom[BF_NMOM_MAX];
} start;

typedef struct point {
    int valid;
    double x[NX_MAX];              /* lobe coordinates u */
    bf_linear lin;                 /* the best d, s at u */
    double fvec[NM_MAX];
    double fjac[NM_MAX * NX_MAX];  /* column-major, leading dimension nx+1 */
    double rr;                     /* r^T r = E^2 */
} point;

typedef struct lmstate {
    bf_pass_driver *ps;
    bf_pass_driver *sub;           /* the screening's subset, or NULL */
    bf_pass_driver *bins;          /* its bin subset (open when bins_open) */
    int bins_open;
    fitmap fm;
    int nx;
    double lam[3];
    bf_linear ref;                 /* d, s the next pass is taken at */
    point cache[2];
    int next;
    double seconds_cb;             /* time inside the callback */
    bf_secant_use secant_use;      /* the registry's: when secant is set   */
    int secant;                    /* correct H by the secant estimate Sc */
    int secant_from;               /* > 0: correct it from this evaluation of an
                                    * lmder run on (secant unset)           */
    int nev;                       /* evaluations assembled in this lmder run */
    unsigned pinned;               /* lobe coordinates held on their bounds
                                    * (bits; see pinned_run)               */
    int have_prev;                 /* prev_x, prev_g: the point evaluated before in this lmder run */
    double prev_x[NX_MAX], prev_g[NX_MAX];
    double Sc[NX_MAX][NX_MAX];     /* estimate of the Hessian's residual-curvature part */
    const struct lmrun *ends;      /* the subset runs refined before this one */
    int nends;                     /* (0: it joins none; see join_end)     */
    int joined;                    /* the one of ends it came to (-1: none) */
    point join;                    /* the point where it did               */
    const struct start *seed;      /* a kept start whose full pass the run's
                                    * first evaluation takes (see seed_start) */
    brdffit_status st;
    brdffit_error *err;
} lmstate;

/* The pass at lobe coordinates u, d and s at the reference (S->ref). */
static void make_pass_par(const lmstate *S, const double *u0, int with_fd, bf_pass_par *pp)
{
    memset(pp, 0, sizeof *pp);
    memcpy(pp->d, S->ref.d, sizeof pp->d);
    memcpy(pp->s, S->ref.s, sizeof pp->s);
    memcpy(pp->lam, S->lam, sizeof pp->lam);
    coords_to_params(&S->fm, u0, pp->p[0]);
    if (!with_fd)
        return;
    for (int j = 0; j < S->fm.nl; j++) {
        double u[BF_MAX_NP];
        memcpy(u, u0, sizeof u);
        /* relative to u's place in its period: lmder may carry u far out
         * (u = 1e8 seen), where a step relative to |u| is no longer small */
        double h = (S->fm.kind[j] == BRDFFIT_MAP_DIRECTION ? FD_STEP_DIRECTION : FD_STEP)
                 * fmax(1.0, fabs(remainder(u[j], 2.0 * M_PI)));
        u[j] += h;
        h = u[j] - u0[j]; /* the step actually representable */
        coords_to_params(&S->fm, u, pp->p[1 + j]);
        pp->inv_h[j] = 1.0 / h;
    }
}

/* Cholesky H = R^T R (upper R) and z = R^-T g.  A pivot that vanishes (a
 * direction the data does not see, e.g. s = 0) gives a zero row. */
static void cholesky_solve(int nx, double H[][BF_MAX_NP], const double *g, const double *hdiag,
                           double R[][BF_MAX_NP], double *z)
{
    memset(R, 0, sizeof(double) * BF_MAX_NP * BF_MAX_NP);
    for (int k = 0; k < nx; k++) {
        double piv = H[k][k];
        for (int i = 0; i < k; i++)
            piv -= R[i][k] * R[i][k];
        if (!(piv > 1e-13 * hdiag[k]) || !(piv > 0)) {
            z[k] = 0.0;
            continue;
        }
        double rkk = sqrt(piv);
        R[k][k] = rkk;
        for (int j = k + 1; j < nx; j++) {
            double v = H[k][j];
            for (int i = 0; i < k; i++)
                v -= R[i][k] * R[i][j];
            R[k][j] = v / rkk;
        }
        double v = g[k];
        for (int i = 0; i < k; i++)
            v -= R[i][k] * z[i];
        z[k] = v / rkk;
    }
}

/* 1 when A is positive definite (nx x nx, Cholesky succeeds). */
static int pos_def(int nx, double A[][BF_MAX_NP])
{
    double L[BF_MAX_NP][BF_MAX_NP];
    for (int k = 0; k < nx; k++) {
        double piv = A[k][k];
        for (int i = 0; i < k; i++)
            piv -= L[i][k] * L[i][k];
        if (!(piv > 0))
            return 0;
        L[k][k] = sqrt(piv);
        for (int j = k + 1; j < nx; j++) {
            double v = A[k][j];
            for (int i = 0; i < k; i++)
                v -= L[i][k] * L[i][j];
            L[k][j] = v / L[k][k];
        }
    }
    return 1;
}

#define SECANT_LO 0.1

/* Gauss-Newton's H = J^T J leaves out the residuals' curvature, sum r_i
 * d2 r_i, which on these large-residual problems is a fixed fraction of H
 * (measured: the distance to the minimum halved per iteration), and at a
 * bound, where the sin map folds and J vanishes, is all of the curvature
 * (LM crawled there for ~30 iterations).  A symmetric rank-one secant update
 * from consecutive evaluated points (x, g = J^T r, exact under variable
 * projection) estimates that part (Sc); H + Sc is used when H + Sc -
 * SECANT_LO H is positive definite, else H alone.  lmder is then handed the
 * Cholesky factor of the corrected H: its quadratic model is Newton's. */
static void secant_correct(lmstate *S, const double *x, double H[][BF_MAX_NP], const double *g)
{
    const int nx = S->nx;
    if (S->have_prev) {
        double s[NX_MAX], v[NX_MAX], ss = 0.0, vs = 0.0, vv = 0.0;
        for (int j = 0; j < nx; j++) {
            s[j] = x[j] - S->prev_x[j];
            ss += s[j] * s[j];
        }
        for (int j = 0; j < nx; j++) {
            v[j] = g[j] - S->prev_g[j];
            for (int l = 0; l < nx; l++)
                v[j] -= (H[j][l] + S->Sc[j][l]) * s[l];
            vs += v[j] * s[j];
            vv += v[j] * v[j];
        }
        if (ss > 0 && fabs(vs) > 1e-8 * sqrt(vv * ss))
            for (int j = 0; j < nx; j++)
                for (int l = 0; l < nx; l++)
                    S->Sc[j][l] += v[j] * v[l] / vs;
    }
    memcpy(S->prev_x, x, nx * sizeof *x);
    memcpy(S->prev_g, g, nx * sizeof *g);
    S->have_prev = 1;
    double lo[BF_MAX_NP][BF_MAX_NP];
    for (int j = 0; j < nx; j++)
        for (int l = 0; l < nx; l++)
            lo[j][l] = H[j][l] + S->Sc[j][l] - SECANT_LO * H[j][l];
    if (!pos_def(nx, lo))
        return;
    for (int j = 0; j < nx; j++)
        for (int l = 0; l < nx; l++)
            H[j][l] += S->Sc[j][l];
}

/* From the moments at u (taken at S->ref) and their best d, s (lin) and
 * r^T r (rr, bf_linear_best's): [z; t] and [R; 0] of the reduced problem. */
static void assemble(lmstate *S, const double *x, const double *mom, double rr,
                     const bf_linear *lin, point *pt)
{
    const int nx = S->nx, m = nx + 1, nk = S->ps->nk;
    double H[BF_MAX_NP][BF_MAX_NP], g[BF_MAX_NP], hdiag[BF_MAX_NP];
    pt->lin = *lin;
    bf_linear_reduce(mom, nk, nx, &S->ref, &pt->lin, H, g, hdiag);
    S->nev++;
    if (S->secant || (S->secant_from > 0 && S->nev >= S->secant_from))
        secant_correct(S, x, H, g);
    for (int j = 0; j < nx; j++)
        if (S->pinned & (1u << j)) {
            for (int l = 0; l < nx; l++)
                H[j][l] = H[l][j] = 0.0;
            g[j] = 0.0;
        }
    double R[BF_MAX_NP][BF_MAX_NP], z[BF_MAX_NP];
    cholesky_solve(nx, H, g, hdiag, R, z);
    double zz = 0.0;
    for (int k = 0; k < nx; k++)
        zz += z[k] * z[k];
    double t = sqrt(fmax(rr - zz, 0.0));
    if (zz > rr) { /* rounding: keep |[z;t]|^2 = r^T r exactly */
        double f = zz > 0 ? sqrt(rr / zz) : 0.0;
        for (int k = 0; k < nx; k++)
            z[k] *= f;
        t = 0.0;
    }
    pt->valid = 1;
    memcpy(pt->x, x, nx * sizeof *x);
    for (int k = 0; k < nx; k++)
        pt->fvec[k] = z[k];
    pt->fvec[nx] = t;
    for (int j = 0; j < nx; j++) {
        for (int i = 0; i < nx; i++)
            pt->fjac[i + m * j] = R[i][j];
        pt->fjac[nx + m * j] = 0.0;
    }
    pt->rr = rr;
}

/* A pass whose reference is far from its best d, s (bf_linear_ref_far) is
 * taken again at the best, up to REF_RETAKES times. */
#define REF_RETAKES 2

/* The evaluated point at x if it is still in the cache (no pass), or NULL. */
static const point *cached(const lmstate *S, const double *x)
{
    for (int i = 0; i < 2; i++)
        if (S->cache[i].valid && memcmp(S->cache[i].x, x, S->nx * sizeof *x) == 0)
            return &S->cache[i];
    return NULL;
}

/* A full pass at x, taken at S->ref and again at its best d, s while the
 * reference is far (bf_linear_ref_far; S->ref then moves there): its
 * moments, r^T r and best d, s. */
static brdffit_status take_pass(lmstate *S, const double *x, double *mom, double *rr,
                                bf_linear *lin)
{
    for (int take = 0;; take++) {
        bf_pass_par pp;
        make_pass_par(S, x, 1, &pp);
        brdffit_status st = bf_driver_run(S->ps, 1, &pp, mom, S->err);
        if (st != BRDFFIT_OK)
            return st;
        *rr = bf_linear_best(mom, S->ps->nk, S->nx, &S->ref, lin);
        if (take >= REF_RETAKES || !bf_linear_ref_far(mom, S->ps->nk, S->nx, *rr))
            return BRDFFIT_OK;
        S->ref = *lin;
    }
}

static int seed_serves(const lmstate *S, const double *x);

static const point *evaluate(lmstate *S, const double *x)
{
    const point *hit = cached(S, x);
    if (hit)
        return hit;
    double mom[BF_NMOM_MAX], rr;
    bf_linear lin;
    if (seed_serves(S, x)) { /* the kept start's pass, taken when it was screened */
        memcpy(mom, S->seed->mom, sizeof mom);
        S->ref = S->seed->mom_ref;
        rr = S->seed->cost;
        lin = S->seed->lin;
    } else if ((S->st = take_pass(S, x, mom, &rr, &lin)) != BRDFFIT_OK) {
        return NULL;
    }
    S->seed = NULL;
    point *pt = &S->cache[S->next];
    S->next ^= 1;
    assemble(S, x, mom, rr, &lin, pt);
    S->ref = pt->lin; /* the next pass is taken near the answer */
    return pt;
}

static int join_end(const lmstate *S, const point *pt);

static int lm_callback(void *user, int m, int n, const double *x, double *fvec, double *fjac,
                       int ldfjac, int iflag)
{
    lmstate *S = user;
    if (iflag == 0)
        return 0;
    double t0 = bf_now();
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i])) {
            S->st = bf_fail(S->err, BRDFFIT_E_FIT_FAILED, "the optimiser produced a non-finite step");
            return -1;
        }
    const point *pt = evaluate(S, x);
    if (!pt) {
        S->seconds_cb += bf_now() - t0;
        return -1;
    }
    if (S->nends > 0 && S->joined < 0 && (S->joined = join_end(S, pt)) >= 0) {
        S->join = *pt;
        S->seconds_cb += bf_now() - t0;
        return -1; /* lmder stops (info -1); lm_once takes the point */
    }
    if (iflag == 1) {
        memcpy(fvec, pt->fvec, m * sizeof *fvec);
    } else {
        for (int j = 0; j < n; j++)
            for (int i = 0; i < m; i++)
                fjac[i + ldfjac * j] = pt->fjac[i + m * j];
    }
    S->seconds_cb += bf_now() - t0;
    return 0;
}

/* ---------------------------------------------------------------- starts */

/* The lobe parameters of start number i of n: the model's start grid (see
 * bf_start_grid in registry.h). */
static void start_params(brdffit_model model, int i, int n, double p[3])
{
    const bf_start_grid *gr = &bf_model_def_get(model)->grid;
    const brdffit_model_info *mi = brdffit_model_get(model);
    bf_model_start_params(model, p);
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
static brdffit_status screen_start(lmstate *S, const double p[3], start *sp)
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
    params_to_coords(&S->fm, p, sp->x);
    return BRDFFIT_OK;
}

/* A kept start taken again on S->ps's samples with a full pass at its
 * coordinates (d, s at the screening's as the reference): its cost and best
 * d, s there, and the pass kept in it for the first evaluation of the LM run
 * that starts from it (seed_serves), which would take that same pass: one
 * value pass less per kept start.  No fit ends above the stored run
 * (bench/baseline-errors.tsv); the time saved: docs/performance.md. */
static brdffit_status seed_start(lmstate *S, start *sp)
{
    S->ref = sp->lin;
    brdffit_status st = take_pass(S, sp->x, sp->mom, &sp->cost, &sp->lin);
    sp->mom_ref = S->ref;
    sp->seeded = st == BRDFFIT_OK ? S->ps : NULL;
    return st;
}

/* 1 when the evaluation at x is the seeded start's (S->seed, seed_start):
 * the same point, samples and no pinned coordinates. */
static int seed_serves(const lmstate *S, const double *x)
{
    return S->seed && S->seed->seeded == S->ps && !S->pinned &&
           memcmp(S->seed->x, x, S->nx * sizeof *x) == 0;
}

void brdffit_fit_options_init(brdffit_fit_options *opt, size_t size)
{
    brdffit_fit_options d;
    memset(&d, 0, sizeof d);
    d.size = sizeof d;
    d.starts = 0; /* the model's default_starts */
    d.refine = 1;
    d.ftol = 1e-8;
    d.xtol = 1e-8;
    d.gtol = 0.0;
    d.max_evals = 200;
    bf_options_init(BRDFFIT_STRUCT_FIT_OPTIONS, &d, opt, size);
}

const char *brdffit_metric_name(void)
{
    return "ngan-l2";
}

static brdffit_status check_fit_options(const brdffit_fit_options *o, brdffit_error *err)
{
    if (o->starts < 0 || o->starts > 1000)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "starts = %d must be in [1, 1000] (or 0: the model's default)", o->starts);
    if (o->refine < 1)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "refine = %d must be >= 1", o->refine);
    if (!(o->ftol >= 0) || !(o->xtol >= 0) || !(o->gtol >= 0) || !isfinite(o->ftol) ||
        !isfinite(o->xtol) || !isfinite(o->gtol))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "tolerances must be finite and >= 0");
    if (o->max_evals < 1)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "max_evals = %d must be >= 1", o->max_evals);
    for (int c = 0; c < 3; c++)
        if (o->lambda_um[c] != 0.0 && !(o->lambda_um[c] >= 0.1 && o->lambda_um[c] <= 10.0))
            return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                           "lambda_um[%d] = %g must be 0 (default) or in [0.1, 10]", c, o->lambda_um[c]);
    return BRDFFIT_OK;
}

enum { MAX_KEEP = 16, LM_RESTARTS = 2 };
_Static_assert(MAX_KEEP <= BF_REFINE_MAX, "bf_refine_select takes every kept start");
_Static_assert(2 * NX_MAX <= BF_END_PLACES, "coord_places fits a bf_run_end");

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
        double p[3];
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
 * S->bins, opened here (bins_open) and closed by the caller; then, unless
 * the model refines on the bin subset first (refine_on_bins: its runs start
 * there, in the screening's order), the kept starts taken again on S->ps's
 * samples and ordered as a screening there orders them. */
static brdffit_status screen_on_bins(lmstate *S, brdffit_context *ctx, const brdffit_samples *bins,
                                     int nstarts, int refine, start *keep, int *nkeep)
{
    bf_pass_driver *on = S->ps;
    brdffit_status st = bf_driver_open(S->bins, ctx, bins, S->fm.model, S->err);
    S->bins_open = st == BRDFFIT_OK;
    if (st != BRDFFIT_OK)
        return st;
    S->ps = S->bins;
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
 * caller; first on the bin subset when it has one, through S->bins, which
 * the caller closes too), or on all samples when it has none.  A model that
 * refines on the subset (registry:
 * refine_on_subset) keeps S->sub = sd and its kept starts as the subset
 * left them; otherwise the kept starts' cost and d, s are taken again on
 * all samples, so that each is refined from exactly where a screening on
 * all samples would have left it. */
static brdffit_status screen_kept(lmstate *S, brdffit_context *ctx, const brdffit_samples *samples,
                                  int nstarts, int refine, start *keep, int *nkeep,
                                  bf_pass_driver *sd)
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
        st = screen_on_bins(S, ctx, bins, nstarts, refine, keep, nkeep);
    else
        st = screen_starts(S, nstarts, refine, keep, nkeep);
    S->ps = all;
    if (bf_model_def_get(S->fm.model)->refine_on_subset) {
        S->sub = sd;
        return st;
    }
    for (int k = 0; k < *nkeep && st == BRDFFIT_OK; k++)
        st = seed_start(S, &keep[k]);
    return st;
}

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

/* The secant estimate of the residuals' curvature that a run ends with is
 * where the next run on the same minimum starts (lm_once): the run on all
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

/* One lmder run from run->x (updated in place), the secant estimate from
 * run's (see sc_forget). */
static brdffit_status lm_once(lmstate *S, const brdffit_fit_options *o, lmrun *run, double *solver_s)
{
    const int nx = S->nx, m = nx + 1;
    double fvec[NM_MAX], fjac[NM_MAX * NX_MAX], diag[NX_MAX], qtf[NX_MAX];
    double wa1[NX_MAX], wa2[NX_MAX], wa3[NX_MAX], wa4[NM_MAX];
    int ipvt[NX_MAX], nfev = 0, njev = 0;
    const double a2 = S->ps->samples->sum_a2;
    S->st = BRDFFIT_OK;
    S->have_prev = 0;
    S->nev = 0;
    memset(S->Sc, 0, sizeof S->Sc);
    if (run->sc_a2 > 0.0 && a2 > 0.0)
        for (int j = 0; j < nx; j++)
            for (int l = 0; l < nx; l++)
                S->Sc[j][l] = run->sc[j][l] * (a2 / run->sc_a2);
    double cb0 = S->seconds_cb, t0 = bf_now();
    run->info = lmder(lm_callback, S, m, nx, run->x, fvec, fjac, m, o->ftol, o->xtol, o->gtol,
                      o->max_evals, diag, 1, 100.0, 0, &nfev, &njev, ipvt, qtf, wa1, wa2, wa3, wa4);
    *solver_s += (bf_now() - t0) - (S->seconds_cb - cb0);
    run->njev += njev;
    memcpy(run->sc, S->Sc, sizeof run->sc);
    run->sc_a2 = a2;
    if (S->st != BRDFFIT_OK) /* a pass failed: lmder was stopped (info < 0) */
        return S->st;
    if (S->joined >= 0) { /* stopped where an earlier run ended */
        memcpy(run->x, S->join.x, sizeof run->x);
        run->lin = S->join.lin;
        run->rr = S->join.rr;
        return BRDFFIT_OK;
    }
    const point *pt = evaluate(S, run->x); /* cached: the point lmder returned */
    if (!pt)
        return S->st;
    run->rr = pt->rr;
    run->lin = pt->lin;
    return BRDFFIT_OK;
}

/* Where lobe coordinate j stands in its range: 0 at the lower bound, 1 at
 * the upper; -1 for a direction (no bounds). */
static double coord_position(const fitmap *fm, int j, double u)
{
    return fm->kind[j] == BRDFFIT_MAP_DIRECTION ? -1.0 : 0.5 * (1.0 + sin(u));
}

/* A coordinate within this of an end of its range is on its bound. */
#define ON_BOUND 1e-6

/* lmder from run->x (updated in place).  A run that stops on max_evals
 * (info 5) is restarted from where it stopped, with a fresh trust region,
 * up to LM_RESTARTS times; run->info is the last run's. */
static brdffit_status lm_converge(lmstate *S, const brdffit_fit_options *o, lmrun *run,
                                  double *solver_s)
{
    for (int k = 0; k <= LM_RESTARTS; k++) {
        brdffit_status st = lm_once(S, o, run, solver_s);
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

/* Forget the evaluated points (assembled for other samples or pins). */
static void cache_clear(lmstate *S)
{
    S->cache[0].valid = S->cache[1].valid = 0;
}

/* lm_converge on the passes of dr (the points cached for the other driver's
 * samples are not this one's). */
static brdffit_status lm_on(lmstate *S, bf_pass_driver *dr, const brdffit_fit_options *o,
                            lmrun *run, double *solver_s)
{
    bf_pass_driver *was = S->ps;
    S->ps = dr;
    cache_clear(S);
    brdffit_status st = lm_converge(S, o, run, solver_s);
    S->ps = was;
    cache_clear(S);
    return st;
}

/* LM on a subset (dr: the screening's, S->sub, or its bin subset) from run
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

/* Two points whose lobe coordinates lie within SAME_POINT of each other in
 * their place in the range (directions: in cos and sin) are one point
 * (same_coords); two ends there with r^T r within SAME_RR (relative) are
 * one minimum (same_end: where a later subset run joins an earlier one's
 * end, join_end; which ends go on to all samples is bf_refine_select's,
 * refine_select.c). */
#define SAME_POINT 1e-4
#define SAME_RR 1e-6

/* The places of lobe coordinates x, two a coordinate (see BF_END_PLACES):
 * its place in its range and 0, or a direction's cosine and sine. */
static void coord_places(const fitmap *fm, const double *x, double *place)
{
    for (int j = 0; j < fm->nl; j++) {
        double t = coord_position(fm, j, x[j]);
        place[2 * j] = t < 0.0 ? cos(x[j]) : t;
        place[2 * j + 1] = t < 0.0 ? sin(x[j]) : 0.0;
    }
}

static int same_coords(const fitmap *fm, const double *xa, const double *xb)
{
    double pa[BF_END_PLACES], pb[BF_END_PLACES];
    coord_places(fm, xa, pa);
    coord_places(fm, xb, pb);
    return bf_places_within(pa, pb, 2 * fm->nl, SAME_POINT);
}

/* Two ends, each its r^T r and lobe coordinates, at one minimum (an end
 * with r^T r not finite, such as a run not taken, bins_runs, is none: two
 * infinities would be within SAME_RR of each other). */
static int same_end(const fitmap *fm, double ra, const double *xa, double rb, const double *xb)
{
    return isfinite(ra) && isfinite(rb) && fabs(ra - rb) <= SAME_RR * fmax(ra, rb) &&
           same_coords(fm, xa, xb);
}

/* A subset run that comes to the point where an earlier one ended (a point
 * it evaluates is at that run's end as same_end has it) stops there: it
 * would go on to end at that minimum and then not be refined on all
 * samples (refine_kept), its further passes spent for nothing.  Over the
 * 100 MERL tables about a third of He's kept starts' subset runs come to an
 * earlier one's end, and stopping them changes no fit (docs/fitting.md).
 * The index of the run of S->ends it came to, or -1. */
static int join_end(const lmstate *S, const point *pt)
{
    for (int q = 0; q < S->nends; q++) {
        if (same_end(&S->fm, pt->rr, pt->x, S->ends[q].rr, S->ends[q].x))
            return q;
    }
    return -1;
}

/* The lobe coordinates of x on a bound (bit j: coordinate j). */
static unsigned on_bounds(const fitmap *fm, const double *x)
{
    unsigned mask = 0;
    for (int j = 0; j < fm->nl; j++) {
        double t = coord_position(fm, j, x[j]);
        if (t >= 0.0 && (t < ON_BOUND || t > 1.0 - ON_BOUND))
            mask |= 1u << j;
    }
    return mask;
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
 * registry entry says so (S->sub; else the start as screened on all
 * samples), with the secant correction from its SUBSET_SECANT_FROM-th
 * evaluation on (from the first if the model uses it always).  refine_all:
 * LM on all samples from there, with it.  A lobe
 * coordinate that ends on its bound is stuck there whether or not the data's
 * optimum is inside (v = lo + (hi-lo)(1+sin u)/2 has no gradient at the
 * bounds), so such a run is repeated from a point a quarter of the range
 * inside on those coordinates (bound_restart), and the better kept; one that
 * still ends there is taken once more with them held on the bound
 * (pinned_run). */
static brdffit_status refine_subset(lmstate *S, const brdffit_fit_options *o, const start *sp,
                                    lmrun *run, double *solver_s)
{
    run_at(run, sp);
    if (!S->sub)
        return BRDFFIT_OK;
    S->seed = sp;
    brdffit_status st = lm_subset(S, S->sub, o, run, solver_s);
    S->seed = NULL;
    return st;
}

/* A run that ended with lobe coordinates on their bounds (mask), from a
 * quarter of the range inside on those: on the subset first when there is
 * one, and on all samples only if it did not come back to the same bounds
 * and point there; the lower run into *run. */
static brdffit_status bound_restart(lmstate *S, const brdffit_fit_options *o, lmrun *run,
                                    unsigned mask, double *solver_s)
{
    lmrun again = *run;
    sc_forget(&again);
    for (int j = 0; j < S->fm.nl; j++)
        if (mask & (1u << j))
            again.x[j] = asin(coord_position(&S->fm, j, run->x[j]) < 0.5 ? -0.5 : 0.5);
    brdffit_status st;
    if (S->sub) {
        st = lm_subset(S, S->sub, o, &again, solver_s);
        if (st != BRDFFIT_OK)
            return st;
        if (on_bounds(&S->fm, again.x) == mask && same_coords(&S->fm, again.x, run->x)) {
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
        cache_clear(S);
    brdffit_status st = lm_converge(S, o, run, solver_s);
    if (mask)
        cache_clear(S);
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
            pin.x[j] = coord_position(&S->fm, j, run->x[j]) < 0.5 ? -M_PI_2 : M_PI_2;
    S->ref = pin.lin;
    S->secant = 1;
    brdffit_status st = lm_converge_pinned(S, o, &pin, mask, solver_s);
    if (st == BRDFFIT_OK)
        keep_lower(run, &pin);
    return st;
}

static brdffit_status refine_all(lmstate *S, const brdffit_fit_options *o, lmrun *run,
                                 double *solver_s)
{
    S->ref = run->lin;
    S->secant = 1; /* on all samples: ALWAYS and ON_ALL alike */
    brdffit_status st = lm_converge(S, o, run, solver_s);
    unsigned mask = st == BRDFFIT_OK ? on_bounds(&S->fm, run->x) : 0u;
    if (!mask)
        return st;
    st = bound_restart(S, o, run, mask, solver_s);
    mask = st == BRDFFIT_OK ? on_bounds(&S->fm, run->x) : 0u;
    if (!mask)
        return st;
    return pinned_run(S, o, run, mask, solver_s);
}

/* Where a run ended, as bf_refine_select sees it (coord_places). */
static void run_end(const fitmap *fm, const lmrun *run, int joined, bf_run_end *e)
{
    e->rr = run->rr;
    e->joined = joined;
    coord_places(fm, run->x, e->place);
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

/* Each kept start by LM on the bin subset (S->bins), each stopping where it
 * comes to an earlier one's end (join_end), into bruns; take[r] = 1 for
 * those that go on to the stride subset (BINS_MARGIN). */
static brdffit_status bins_runs(lmstate *S, const brdffit_fit_options *o, const start *keep,
                                int nkeep, lmrun *bruns, int *take, double *solver_s)
{
    bf_run_end ends[MAX_KEEP];
    for (int r = 0; r < nkeep; r++) {
        run_at(&bruns[r], &keep[r]);
        join_before(S, bruns, r);
        brdffit_status st = lm_subset(S, S->bins, o, &bruns[r], solver_s);
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
    double p[3];
    coords_to_params(&S->fm, bin->x, p);
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
static brdffit_status refine_kept(lmstate *S, const brdffit_fit_options *o, const start *keep,
                                  int nkeep, lmrun *best, double *solver_s)
{
    lmrun runs[MAX_KEEP], bruns[MAX_KEEP];
    bf_run_end ends[MAX_KEEP];
    int refine[MAX_KEEP], take[MAX_KEEP];
    const int on_bins = S->sub && S->bins_open && bf_model_def_get(S->fm.model)->refine_on_bins;
    brdffit_status st = on_bins ? bins_runs(S, o, keep, nkeep, bruns, take, solver_s) : BRDFFIT_OK;
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
            st = refine_subset(S, o, from, &runs[r], solver_s);
        }
        join_after(S, &runs[r], &ends[r]);
    }
    if (st != BRDFFIT_OK)
        return st;
    if (S->sub)
        bf_refine_select(ends, nkeep, 2 * S->fm.nl, SUBSET_MARGIN, refine);
    else /* each start as screened on all samples: no run to compare */
        for (int r = 0; r < nkeep; r++)
            refine[r] = 1;
    for (int r = 0; r < nkeep; r++) {
        if (!refine[r])
            continue;
        lmrun run = runs[r];
        S->seed = &keep[r]; /* its pass on all samples, without a subset (seed_start) */
        st = refine_all(S, o, &run, solver_s);
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
 * POLISH_SKIP (see polish). */
static int polish_needless(const lmstate *S, const lmrun *best)
{
    const point *pt = cached(S, best->x);
    if (!pt || !(pt->rr > 0.0))
        return 0;
    double zz = 0.0;
    for (int k = 0; k < S->nx; k++)
        zz += pt->fvec[k] * pt->fvec[k];
    return zz < POLISH_SKIP * pt->rr;
}

static brdffit_status polish(lmstate *S, const brdffit_fit_options *o, lmrun *best,
                             double *solver_s)
{
    if (S->secant_use != BF_SECANT_ON_ALL || polish_needless(S, best))
        return BRDFFIT_OK;
    lmrun pol = *best;
    S->secant = 1;
    S->ref = best->lin;
    brdffit_fit_options tight = *o;
    tight.ftol *= POLISH_TOL;
    tight.xtol *= POLISH_TOL;
    brdffit_status st = lm_converge_pinned(S, &tight, &pol, on_bounds(&S->fm, best->x), solver_s);
    if (st == BRDFFIT_OK)
        keep_lower(best, &pol);
    return st;
}

#define ROUNDED_AWAY 1e-12

/* Which parameters of the result are on a bound (brdffit_fit_result.at_bound). */
static unsigned bound_mask(const fitmap *fm, const double *u, const bf_linear *lin)
{
    unsigned mask = 0;
    /* a coefficient round-off left a hair above 0 (below 1e-12 of the
     * channel's other one: s = 6e-31 beside d = 0.2 on a material with no
     * specular part) is on its bound as well */
    for (int c = 0; c < 3; c++) {
        double d = lin->d[c], s = lin->s[c];
        if (d == 0.0 || d <= ROUNDED_AWAY * s)
            mask |= (unsigned)BRDFFIT_AT_BOUND_D_R << c;
        if (s == 0.0 || s <= ROUNDED_AWAY * d)
            mask |= (unsigned)BRDFFIT_AT_BOUND_S_R << c;
    }
    unsigned on = on_bounds(fm, u);
    for (int j = 0; j < fm->nl; j++)
        if (on & (1u << j))
            mask |= (unsigned)BRDFFIT_AT_BOUND_P0 << fm->param[j];
    return mask;
}

/* r^T r of the result from one value pass at its own d, s, p: the fit's
 * Error is then brdffit_error_of's of the returned parameters, to the bit
 * (the LM's r^T r comes from moments taken near, not at, the point). */
static brdffit_status exact_error(lmstate *S, lmrun *best)
{
    bf_pass_par pp;
    memset(&pp, 0, sizeof pp);
    memcpy(pp.d, best->lin.d, sizeof pp.d);
    memcpy(pp.s, best->lin.s, sizeof pp.s);
    memcpy(pp.lam, S->lam, sizeof pp.lam);
    coords_to_params(&S->fm, best->x, pp.p[0]);
    double mom[BF_NMOM_MAX], rr = 0.0;
    brdffit_status st = bf_driver_run(S->ps, 0, &pp, mom, S->err);
    if (st != BRDFFIT_OK)
        return st;
    for (int c = 0; c < 3; c++)
        rr += mom[bf_mom_chan(c, S->ps->nk, 0) + BF_MC_SEE];
    best->rr = fmax(rr, 0.0);
    return BRDFFIT_OK;
}

static void fill_result(const lmstate *S, const lmrun *best, brdffit_fit_result *result)
{
    memset(result, 0, sizeof *result);
    result->size = sizeof *result;
    result->model = S->fm.model;
    memcpy(result->params.d, best->lin.d, sizeof result->params.d);
    memcpy(result->params.s, best->lin.s, sizeof result->params.s);
    coords_to_params(&S->fm, best->x, result->params.p);
    if (brdffit_model_get(S->fm.model)->chromatic)
        memcpy(result->params.lambda_um, S->lam, sizeof S->lam);
    result->error = sqrt(best->rr);
    result->cminpack_info = best->info;
    result->iterations = best->njev;
    result->flags = best->info == 5 ? BRDFFIT_FIT_LIMIT : 0u;
    result->at_bound = bound_mask(&S->fm, best->x, &best->lin);
}

/* Each channel has d, s and the lobe's coordinates to determine: with fewer
 * distinct geometries than that the fit is underdetermined (one sample, or
 * a cutoff so small that only the normal is left), and LM would return any
 * of infinitely many answers. */
static brdffit_status check_enough_samples(const brdffit_samples *samples, brdffit_model model,
                                           brdffit_error *err)
{
    size_t unknowns = 2 + (size_t)bf_model_ncoords(model);
    size_t found = bf_samples_geometries(samples, unknowns);
    if (found >= unknowns)
        return BRDFFIT_OK;
    return bf_fail(err, BRDFFIT_E_TOO_FEW_SAMPLES,
                   "%zu sample%s at %zu distinct geometr%s (up to rotation about the normal and "
                   "exchange of wi and wo): too few for %s, which has %zu unknowns per channel "
                   "(d, s and %d lobe parameter%s)",
                   brdffit_samples_count(samples), brdffit_samples_count(samples) == 1 ? "" : "s",
                   found, found == 1 ? "y" : "ies", brdffit_model_get(model)->name, unknowns,
                   bf_model_ncoords(model), bf_model_ncoords(model) == 1 ? "" : "s");
}

/* The driver of a fit's (and brdffit_error_of's) passes on all samples: over
 * the set's mirror set (samples_mirror.c), so that a fit's Error is
 * brdffit_error_of's to the bit.  Close it whatever this returns. */
static brdffit_status open_all_samples(bf_pass_driver *ps, brdffit_context *ctx,
                                       const brdffit_samples *samples, brdffit_model model,
                                       brdffit_error *err)
{
    memset(ps, 0, sizeof *ps);
    const brdffit_samples *all = NULL;
    brdffit_status st = bf_samples_mirror_kept(samples, &all, err);
    return st == BRDFFIT_OK ? bf_driver_open(ps, ctx, all, model, err) : st;
}

brdffit_status brdffit_fit(brdffit_context *ctx, const brdffit_samples *samples, brdffit_model model,
                           const brdffit_fit_options *opt, brdffit_fit_result *result,
                           brdffit_error *err)
{
    double t_start = bf_now();
    if (!ctx || !samples || !result)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_fit: NULL context, samples or result");
    brdffit_status st = bf_sized_check(BRDFFIT_STRUCT_FIT_RESULT, result, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!brdffit_model_get(model))
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    brdffit_fit_options o;
    brdffit_fit_options_default(&o);
    st = bf_options_read(BRDFFIT_STRUCT_FIT_OPTIONS, opt, &o, err);
    if (st != BRDFFIT_OK)
        return st;
    st = check_fit_options(&o, err);
    if (st != BRDFFIT_OK)
        return st;
    st = check_enough_samples(samples, model, err);
    if (st != BRDFFIT_OK)
        return st;

    bf_pass_driver ps, sd, bd; /* all samples (their mirror set); the screening's
                                * subset and its bin subset */
    memset(&sd, 0, sizeof sd);
    memset(&bd, 0, sizeof bd);
    st = open_all_samples(&ps, ctx, samples, model, err);
    if (st != BRDFFIT_OK)
        goto done;
    lmstate S;
    memset(&S, 0, sizeof S);
    S.joined = -1;
    S.ps = &ps;
    S.err = err;
    S.bins = &bd;
    fitmap_init(&S.fm, model);
    S.nx = S.fm.nl;
    S.secant_use = bf_model_def_get(model)->secant;
    brdffit_params lp;
    memset(&lp, 0, sizeof lp);
    memcpy(lp.lambda_um, o.lambda_um, sizeof lp.lambda_um);
    bf_lambdas(&lp, S.lam);

    start keep[MAX_KEEP];
    int nkeep = 0, refine = o.refine < MAX_KEEP ? o.refine : MAX_KEEP;
    int nstarts = o.starts ? o.starts : brdffit_model_get(model)->default_starts;
    st = screen_kept(&S, ctx, samples, nstarts, refine, keep, &nkeep, &sd);
    if (st != BRDFFIT_OK)
        goto done;
    lmrun best = { .rr = INFINITY };
    double solver_seconds = 0.0;
    st = refine_kept(&S, &o, keep, nkeep, &best, &solver_seconds);
    if (st != BRDFFIT_OK)
        goto done;
    if (!isfinite(best.rr)) {
        st = bf_fail(err, BRDFFIT_E_FIT_FAILED, "no start gave a finite Error");
        goto done;
    }
    st = polish(&S, &o, &best, &solver_seconds);
    if (st == BRDFFIT_OK)
        st = exact_error(&S, &best);
    if (st != BRDFFIT_OK)
        goto done;
    brdffit_fit_result r; /* the library's whole struct; the caller gets its size of it */
    fill_result(&S, &best, &r);
    r.passes = ps.passes + sd.passes + bd.passes;
    r.seconds_build = ps.seconds_build;
    r.samples = samples->n;
    r.backend = brdffit_context_backend(ctx);
    r.seconds_passes = ps.seconds + sd.seconds + bd.seconds;
    r.seconds_solver = solver_seconds;
    r.seconds = bf_now() - t_start;
    st = bf_options_write(BRDFFIT_STRUCT_FIT_RESULT, &r, result, err);
    if (st == BRDFFIT_OK)
        bf_ok(err);
done:
    bf_driver_close(&bd);
    bf_driver_close(&sd);
    bf_driver_close(&ps);
    return st;
}

brdffit_status brdffit_error_of(brdffit_context *ctx, const brdffit_samples *samples,
                                brdffit_model model, const brdffit_params *params, double *error,
                                brdffit_error *err)
{
    if (!ctx || !samples || !error)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_error_of: NULL argument");
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st != BRDFFIT_OK)
        return st;
    bf_pass_driver ps;
    st = open_all_samples(&ps, ctx, samples, model, err);
    if (st == BRDFFIT_OK) {
        bf_pass_par pp;
        memset(&pp, 0, sizeof pp);
        memcpy(pp.d, params->d, sizeof pp.d);
        memcpy(pp.s, params->s, sizeof pp.s);
        bf_lambdas(params, pp.lam);
        memcpy(pp.p[0], params->p, sizeof pp.p[0]);
        double mom[BF_NMOM_MAX];
        st = bf_driver_run(&ps, 0, &pp, mom, err);
        if (st == BRDFFIT_OK) {
            double rr = 0.0;
            for (int c = 0; c < 3; c++)
                rr += mom[bf_mom_chan(c, ps.nk, 0) + BF_MC_SEE];
            *error = sqrt(fmax(rr, 0.0));
            bf_ok(err);
        }
    }
    bf_driver_close(&ps);
    return st;
}
