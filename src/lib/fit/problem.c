/* SPDX-License-Identifier: MIT */
/* problem.c -- the reduced least-squares problem LM solves at the lobe
 * coordinates, and the lmder run on it.
 *
 * The linear unknowns d, s >= 0 are solved exactly at every lobe point from
 * the pass's moments (variable projection, linear.h): LM moves only the lobe
 * coordinates u (nx = nl of them; the map: map.c).
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
 * This file is the numerics of one run on one driver's samples; which
 * starts and runs, on which samples, is the screening's and the stages'
 * (screen.c, refine.c; docs/fitting.md, "Unknowns").
 */
#define _DEFAULT_SOURCE /* M_PI */
#include "fit_internal.h"

#include "samples.h"

#include <cminpack.h>
#include <math.h>
#include <string.h>

#define FD_STEP 1e-7
/* A direction angle's step: a sharp Lafortune lobe (n ~ 5e4) varies with the
 * angle on a scale ~1/n, so 1e-7 made its derivative ~1% wrong and LM stop
 * short of the minimum (measured: violet-acrylic 1.2e-7, black-obsidian
 * 1e-8 relative above what 1e-9 reaches; 1e-10 and 1e-11 gave the same). */
#define FD_STEP_DIRECTION 1e-9

/* The pass at lobe coordinates u, d and s at the reference (S->ref). */
static void make_pass_par(const lmstate *S, const double *u0, int with_fd, bf_pass_par *pp)
{
    memset(pp, 0, sizeof *pp);
    memcpy(pp->d, S->ref.d, sizeof pp->d);
    memcpy(pp->s, S->ref.s, sizeof pp->s);
    memcpy(pp->lam, S->lam, sizeof pp->lam);
    bf_coords_to_params(&S->fm, u0, pp->p[0]);
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
        bf_coords_to_params(&S->fm, u, pp->p[1 + j]);
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
const point *bf_cached(const lmstate *S, const double *x)
{
    for (int i = 0; i < 2; i++)
        if (S->cache[i].valid && memcmp(S->cache[i].x, x, S->nx * sizeof *x) == 0)
            return &S->cache[i];
    return NULL;
}

/* A full pass at x, taken at S->ref and again at its best d, s while the
 * reference is far (bf_linear_ref_far; S->ref then moves there): its
 * moments, r^T r and best d, s. */
brdffit_status bf_take_pass(lmstate *S, const double *x, double *mom, double *rr, bf_linear *lin)
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

/* 1 when the evaluation at x is the seeded start's (S->seed; screen.c,
 * seed_start): the same point, samples and no pinned coordinates. */
static int seed_serves(const lmstate *S, const double *x)
{
    return S->seed && S->seed->seeded == S->ps && !S->pinned &&
           memcmp(S->seed->x, x, S->nx * sizeof *x) == 0;
}

/* Two ends with r^T r within SAME_RR (relative) and their lobe coordinates
 * one point (bf_same_coords) are one minimum (same_end: where a later
 * subset run joins an earlier one's end, join_end; which ends go on to all
 * samples is bf_refine_select's, refine_select.c). */
#define SAME_RR 1e-6

/* Two ends, each its r^T r and lobe coordinates, at one minimum (an end
 * with r^T r not finite, such as a run not taken, refine.c's bins_runs, is
 * none: two infinities would be within SAME_RR of each other). */
static int same_end(const fitmap *fm, double ra, const double *xa, double rb, const double *xb)
{
    return isfinite(ra) && isfinite(rb) && fabs(ra - rb) <= SAME_RR * fmax(ra, rb) &&
           bf_same_coords(fm, xa, xb);
}

/* A subset run that comes to the point where an earlier one ended (a point
 * it evaluates is at that run's end as same_end has it) stops there: it
 * would go on to end at that minimum and then not be refined on all
 * samples (refine.c, bf_refine_kept), its further passes spent for nothing.
 * Over the 100 MERL tables about a third of He's kept starts' subset runs
 * come to an earlier one's end, and stopping them changes no fit
 * (docs/fitting.md).
 * The index of the run of S->ends it came to, or -1. */
static int join_end(const lmstate *S, const point *pt)
{
    for (int q = 0; q < S->nends; q++) {
        if (same_end(&S->fm, pt->rr, pt->x, S->ends[q].rr, S->ends[q].x))
            return q;
    }
    return -1;
}

static const point *evaluate(lmstate *S, const double *x)
{
    const point *hit = bf_cached(S, x);
    if (hit)
        return hit;
    double mom[BF_NMOM_MAX], rr;
    bf_linear lin;
    if (seed_serves(S, x)) { /* the kept start's pass, taken when it was screened */
        memcpy(mom, S->seed->mom, sizeof mom);
        S->ref = S->seed->mom_ref;
        rr = S->seed->cost;
        lin = S->seed->lin;
    } else if ((S->st = bf_take_pass(S, x, mom, &rr, &lin)) != BRDFFIT_OK) {
        return NULL;
    }
    S->seed = NULL;
    point *pt = &S->cache[S->next];
    S->next ^= 1;
    assemble(S, x, mom, rr, &lin, pt);
    S->ref = pt->lin; /* the next pass is taken near the answer */
    return pt;
}

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
        return -1; /* lmder stops (info -1); bf_lm_once takes the point */
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

/* One lmder run from run->x (updated in place), the secant estimate from
 * run's (see refine.c, sc_forget). */
brdffit_status bf_lm_once(lmstate *S, const brdffit_fit_options *o, lmrun *run, double *solver_s)
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

/* Forget the evaluated points (assembled for other samples or pins). */
void bf_cache_clear(lmstate *S)
{
    S->cache[0].valid = S->cache[1].valid = 0;
}
