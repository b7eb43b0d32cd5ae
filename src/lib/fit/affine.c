/* SPDX-License-Identifier: MIT */
/* affine.c -- the fit of the glTF models (affine.h): the base colour solved
 * exactly at every lobe point, cminpack's lmder on the lobe coordinates
 * (metallic, roughness; gltf-ext also ior and specular), handed the reduced
 * problem as problem.c hands its own: from H = J^T J, g = J^T r and r^T r,
 * the residuals [z; t] = [R^-T g; sqrt(r^T r - |z|^2)] with Jacobian [R; 0],
 * R the Cholesky factor of H, whose steps and tests are the full problem's.
 *
 * The stages: the starts (roughness over the registry's grid, metallic near
 * 0 and near 1 in turn, every other coordinate at its registry start, all
 * kept off their bounds, where the sine map has no slope) are screened by
 * their Error on every screen_stride-th sample of the mirror set; the best
 * (at least two, brdffit_fit_options.refine if more) are refined by LM on
 * that subset; the lowest end is refined on all samples (Gauss-Newton steps
 * with a secant along each when at most AF_GN_MAX_NX coordinates are free,
 * then LM if they have not converged; coordinates near an end of their
 * range pinned there, af_pinned); its Error is then summed directly
 * (bf_model_rr), as brdffit_error_of does. */
#define _DEFAULT_SOURCE /* M_PI */
#include "affine.h"

#include "samples.h"

#include <cminpack.h>
#include <math.h>
#include <string.h>

#define AF_FD_STEP 1e-7
/* A start's coordinates keep this far inside their ranges (in the range's
 * fraction, 0 .. 1). */
#define AF_START_INSIDE 0.02
#define AF_MAX_STARTS 64
/* The LM runs on the subset stop at this relative change (ftol, xtol). */
#define AF_SUBSET_TOL 1e-4
/* A coordinate this close to an end of its range (in the range's fraction)
 * after the subset's run is pinned there for the run on all samples; it is
 * freed again when the Error is lower AF_PIN_PROBE inside the end. */
#define AF_PIN_NEAR 0.05
#define AF_PIN_PROBE 1e-4
/* The Gauss-Newton steps on all samples before LM (af_newton): at most this
 * many, each at most this long in every coordinate (radians of the sine map). */
#define AF_GN_STEPS 4
#define AF_GN_MAX_STEP 0.1
/* ... with at most this many free coordinates (gltf's two: with more, as
 * gltf-ext's, the steps fall short in more than one direction and the
 * secant along one does not save LM's passes). */
#define AF_GN_MAX_NX 2
/* The secant's point along a step at most this many steps from its start. */
#define AF_GN_MAX_T 4.0

/* An LM run's point: every lobe coordinate u (the pinned ones too). */
typedef struct afrun {
    double u[AF_NP];
    double rr;          /* r^T r there */
    int info;           /* lmder's info of the last run */
    int njev;           /* Jacobian evaluations, all runs */
} afrun;

typedef struct afstate {
    const brdffit_samples *samples;
    fitmap fm;
    int nx;                     /* the coordinates LM moves: act[0 .. nx-1] */
    int act[AF_NP];
    double ufix[AF_NP];         /* u of every coordinate; the pinned ones
                                 * (not in act) stay at this value       */
    int valid;                  /* the cache below holds the point x */
    double x[AF_NP];
    double fvec[AF_NP + 1];
    double fjac[(AF_NP + 1) * AF_NP]; /* column-major, leading dimension nx + 1 */
    double rr;
    double base[3];             /* the best base colour at x */
    int passes;
    double seconds_passes;
    brdffit_status st;
    brdffit_error *err;
} afstate;

/* Every coordinate u from the active ones x (the rest: S->ufix). */
static void expand(const afstate *S, const double *x, double *u)
{
    memcpy(u, S->ufix, sizeof S->ufix);
    for (int j = 0; j < S->nx; j++)
        u[S->act[j]] = x[j];
}

/* The points of a pass at active coordinates x: pts[0] the parameters,
 * pts[1 + j] at x + h_j e_j (np = 0: the value only). */
static void make_points(const afstate *S, const double *x, int np, double (*pts)[AF_NP],
                        double *inv_h)
{
    double u[AF_NP];
    expand(S, x, u);
    bf_coords_to_params(&S->fm, u, pts[0]);
    for (int j = 0; j < np; j++) {
        double v[AF_NP];
        const int k = S->act[j];
        memcpy(v, u, sizeof v);
        double h = AF_FD_STEP * fmax(1.0, fabs(remainder(u[k], 2.0 * M_PI)));
        v[k] += h;
        inv_h[j] = 1.0 / (v[k] - u[k]);
        bf_coords_to_params(&S->fm, v, pts[1 + j]);
    }
}

/* One pass at active coordinates x (with its differences when np > 0) into m. */
static brdffit_status af_pass(afstate *S, const double *x, int np, af_mom *m)
{
    double pts[1 + AF_NP][AF_NP], inv_h[AF_NP];
    memset(pts, 0, sizeof pts);
    make_points(S, x, np, pts, inv_h);
    double t0 = bf_now();
    brdffit_status st = bf_affine_pass(S->samples, S->fm.model, (const double (*)[AF_NP])pts, np,
                                       inv_h, m, S->err);
    S->seconds_passes += bf_now() - t0;
    S->passes++;
    return st;
}

/* Evaluate the reduced problem at x into the cache. */
static brdffit_status evaluate(afstate *S, const double *x)
{
    if (S->valid && memcmp(S->x, x, (size_t)S->nx * sizeof *x) == 0)
        return BRDFFIT_OK;
    af_mom m;
    brdffit_status st = af_pass(S, x, S->nx, &m);
    if (st != BRDFFIT_OK)
        return st;
    double H[AF_NP][AF_NP], g[AF_NP], hdiag[AF_NP], R[AF_NP][AF_NP], z[AF_NP];
    bf_affine_reduce(&m, S->nx, &S->rr, H, g, hdiag, S->base);
    bf_affine_chol(S->nx, H, g, hdiag, R, z);
    const int nx = S->nx, mres = nx + 1;
    double zz = 0.0;
    for (int j = 0; j < nx; j++) {
        S->fvec[j] = z[j];
        zz += z[j] * z[j];
        for (int i = 0; i < mres; i++)
            S->fjac[i + mres * j] = i < nx ? R[i][j] : 0.0;
    }
    S->fvec[nx] = sqrt(fmax(S->rr - zz, 0.0));
    memcpy(S->x, x, (size_t)nx * sizeof *x);
    S->valid = 1;
    return BRDFFIT_OK;
}

static int af_callback(void *user, int m, int n, const double *x, double *fvec, double *fjac,
                       int ldfjac, int iflag)
{
    afstate *S = user;
    if (iflag == 0)
        return 0;
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i])) {
            S->st = bf_fail(S->err, BRDFFIT_E_FIT_FAILED, "the optimiser produced a non-finite step");
            return -1;
        }
    S->st = evaluate(S, x);
    if (S->st != BRDFFIT_OK)
        return -1;
    if (iflag == 1)
        memcpy(fvec, S->fvec, (size_t)m * sizeof *fvec);
    else
        for (int j = 0; j < n; j++)
            for (int i = 0; i < m; i++)
                fjac[i + ldfjac * j] = S->fjac[i + m * j];
    return 0;
}

/* An LM run on S's samples and active coordinates from run->u (updated in
 * place): its end's r^T r, colours, lmder's info and Jacobian count into
 * run. */
static brdffit_status af_lm(afstate *S, const brdffit_fit_options *o, afrun *run, double *base,
                            double *solver_s)
{
    double x[AF_NP] = { 0 };
    memcpy(S->ufix, run->u, sizeof S->ufix);
    for (int j = 0; j < S->nx; j++)
        x[j] = run->u[S->act[j]];
    S->valid = 0;
    const int nx = S->nx, m = nx + 1;
    if (nx == 0) { /* every coordinate pinned: the point itself */
        brdffit_status st = evaluate(S, x);
        run->rr = S->rr;
        memcpy(base, S->base, 3 * sizeof *base);
        return st;
    }
    double fvec[AF_NP + 1], fjac[(AF_NP + 1) * AF_NP], diag[AF_NP], qtf[AF_NP];
    double wa1[AF_NP], wa2[AF_NP], wa3[AF_NP], wa4[AF_NP + 1];
    int ipvt[AF_NP], nfev = 0, njev = 0;
    S->st = BRDFFIT_OK;
    double p0 = S->seconds_passes, t0 = bf_now();
    run->info = lmder(af_callback, S, m, nx, x, fvec, fjac, m, o->ftol, o->xtol, o->gtol,
                      o->max_evals, diag, 1, 100.0, 0, &nfev, &njev, ipvt, qtf, wa1, wa2, wa3, wa4);
    *solver_s += (bf_now() - t0) - (S->seconds_passes - p0);
    run->njev += njev;
    if (S->st != BRDFFIT_OK)
        return S->st;
    brdffit_status st = evaluate(S, x);
    if (st != BRDFFIT_OK)
        return st;
    expand(S, x, run->u);
    run->rr = S->rr;
    memcpy(base, S->base, 3 * sizeof *base);
    return BRDFFIT_OK;
}

/* At evaluate's point: the Gauss-Newton step d (R d = -z, R upper, in
 * S->fjac) into d, its longest coordinate returned. */
static double gn_step(const afstate *S, double *d)
{
    const int nx = S->nx, m = nx + 1;
    double big = 0.0;
    for (int i = nx - 1; i >= 0; i--) {
        double rii = S->fjac[i + m * i], v = -S->fvec[i];
        for (int j = i + 1; j < nx; j++)
            v -= S->fjac[i + m * j] * d[j];
        d[i] = rii != 0.0 ? v / rii : 0.0;
        big = fmax(big, fabs(d[i]));
    }
    return big;
}

/* At evaluate's point: g . d, g = J^T r = R^T z the gradient of r^T r / 2. */
static double slope(const afstate *S, const double *d)
{
    const int nx = S->nx, m = nx + 1;
    double v = 0.0;
    for (int j = 0; j < nx; j++)
        for (int i = 0; i <= j; i++)
            v += S->fjac[i + m * j] * S->fvec[i] * d[j];
    return v;
}

/* At evaluate's point: the reduction of r^T r a Gauss-Newton step predicts
 * (|z|^2), relative to r^T r. */
static double predicted(const afstate *S)
{
    double zz = 0.0;
    for (int j = 0; j < S->nx; j++)
        zz += S->fvec[j] * S->fvec[j];
    return S->rr > 0.0 ? zz / S->rr : 0.0;
}

/* Take the point x (evaluated last) as the run's. */
static void take(afstate *S, const double *x, afrun *run, double *base)
{
    expand(S, x, run->u);
    run->rr = S->rr;
    memcpy(base, S->base, 3 * sizeof *base);
}

/* Steps on S's samples from run->u (its active coordinates) before LM: from
 * a subset's end the minimum on all samples is near.  Each step is a
 * Gauss-Newton step d, then a secant along it: with large residuals the
 * Gauss-Newton model's curvature is below the Error's, its steps fall short
 * by a steady fraction (LM's would too, one pass each), and the slopes g . d
 * at both ends of d place the minimum along d.  The steps end, converged
 * (*done = 1), where the reduction a Gauss-Newton step predicts is at most
 * o->ftol of r^T r.  A step that does not lower r^T r, is not finite or is
 * longer than AF_GN_MAX_STEP, or AF_GN_STEPS steps that do not converge,
 * leave *done = 0 and run->u at the lowest point, for lmder. */
static brdffit_status af_newton(afstate *S, const brdffit_fit_options *o, afrun *run, double *base,
                                int *done)
{
    const int nx = S->nx;
    double x[AF_NP] = { 0 };
    *done = 0;
    memcpy(S->ufix, run->u, sizeof S->ufix);
    for (int j = 0; j < nx; j++)
        x[j] = run->u[S->act[j]];
    S->valid = 0;
    brdffit_status st = evaluate(S, x);
    for (int it = 0; st == BRDFFIT_OK && it < AF_GN_STEPS; it++) {
        if (predicted(S) <= o->ftol) {
            take(S, x, run, base);
            run->info = 1;
            *done = 1;
            return BRDFFIT_OK;
        }
        double d[AF_NP] = { 0 }, x1[AF_NP] = { 0 }, x2[AF_NP] = { 0 };
        if (!(gn_step(S, d) <= AF_GN_MAX_STEP))
            return BRDFFIT_OK;
        const double rr0 = S->rr, s0 = slope(S, d);
        for (int j = 0; j < nx; j++)
            x1[j] = x[j] + d[j];
        if ((st = evaluate(S, x1)) != BRDFFIT_OK || !(S->rr < rr0))
            return st;
        memcpy(x, x1, sizeof x);
        take(S, x, run, base);
        run->njev++;
        const double rr1 = S->rr, s1 = slope(S, d);
        if (!(s0 < s1 && s1 < 0.0))
            continue; /* no minimum beyond x1 along d */
        double t = s0 / (s0 - s1); /* the minimum along d at x0 + t d */
        if (!(t < AF_GN_MAX_T))
            continue;
        for (int j = 0; j < nx; j++)
            x2[j] = x1[j] - d[j] + t * d[j];
        if ((st = evaluate(S, x2)) != BRDFFIT_OK || !(S->rr < rr1))
            return st; /* lmder from x1 */
        memcpy(x, x2, sizeof x);
        take(S, x, run, base);
        run->njev++;
    }
    return st;
}

/* Start i's coordinates: the registry's starts, roughness (the grid's
 * parameter) over its grid, metallic near 0 and near 1 in turn, all kept
 * AF_START_INSIDE inside their ranges. */
static void start_coords(const fitmap *fm, const bf_model_def *def, int i, double *u)
{
    double p[AF_NP];
    bf_model_start_params(fm->model, p, AF_NP);
    const bf_start_grid *gr = &def->grid;
    int period = gr->period > 1 ? gr->period : 1, k = i % period;
    double t = period > 1 ? (double)k / (period - 1) : 0.0;
    p[gr->param] = gr->spacing == BRDFFIT_MAP_LOG ? exp(log(gr->lo) + t * (log(gr->hi) - log(gr->lo)))
                                                  : gr->lo + t * (gr->hi - gr->lo);
    p[0] = (i / period) % 2 == 0 ? 0.0 : 1.0; /* metallic */
    bf_params_to_coords(fm, p, u);
    for (int j = 0; j < fm->nl; j++) {
        double lo = asin(2.0 * AF_START_INSIDE - 1.0), hi = -lo;
        u[j] = fmin(fmax(u[j], lo), hi);
    }
}

/* Make every coordinate active (act = 0 .. nl-1) but those in `pinned`. */
static void set_active(afstate *S, unsigned pinned)
{
    S->nx = 0;
    for (int j = 0; j < S->fm.nl; j++)
        if (!(pinned & (1u << j)))
            S->act[S->nx++] = j;
    S->valid = 0;
}

/* The Error^2 and best colours at coordinates u on S's samples (a value
 * pass; every coordinate taken from u). */
static brdffit_status value_at(afstate *S, const double *u, double *rr, double *base)
{
    memcpy(S->ufix, u, sizeof S->ufix);
    const int nx = S->nx;
    S->nx = 0;
    af_mom m;
    brdffit_status st = af_pass(S, u, 0, &m);
    S->nx = nx;
    if (st != BRDFFIT_OK)
        return st;
    double H[AF_NP][AF_NP], g[AF_NP], hdiag[AF_NP];
    bf_affine_reduce(&m, 0, rr, H, g, hdiag, base);
    return BRDFFIT_OK;
}

/* Screen the starts on S's samples; the best *nkeep (at most) into keep,
 * lowest r^T r first. */
static brdffit_status screen(afstate *S, const bf_model_def *def, int nstarts, afrun *keep,
                             int *nkeep)
{
    afrun cand[AF_MAX_STARTS];
    int n = 0;
    for (int i = 0; i < nstarts; i++) {
        afrun *c = &cand[n];
        memset(c, 0, sizeof *c);
        double base[3];
        start_coords(&S->fm, def, i, c->u);
        brdffit_status st = value_at(S, c->u, &c->rr, base);
        if (st != BRDFFIT_OK)
            return st;
        if (isfinite(c->rr))
            n++;
    }
    int k = 0;
    for (; k < *nkeep && k < n; k++) {
        int lo = k;
        for (int i = k + 1; i < n; i++)
            if (cand[i].rr < cand[lo].rr)
                lo = i;
        afrun t = cand[k];
        cand[k] = cand[lo];
        cand[lo] = t;
        keep[k] = cand[k];
    }
    *nkeep = k;
    return BRDFFIT_OK;
}

/* Which parameters of the fit ended on a bound. */
static unsigned af_bounds(const fitmap *fm, const double *u, const double *base)
{
    unsigned mask = 0;
    for (int c = 0; c < 3; c++)
        if (base[c] <= 0.0 || base[c] >= 1.0)
            mask |= (unsigned)BRDFFIT_AT_BOUND_D_R << c;
    unsigned on = bf_on_bounds(fm, u);
    for (int j = 0; j < fm->nl; j++)
        if (on & (1u << j))
            mask |= (unsigned)BRDFFIT_AT_BOUND_P0 << fm->param[j];
    return mask;
}

static void fill(const afstate *S, const afrun *best, const double *base,
                 brdffit_fit_result *r)
{
    memset(r, 0, sizeof *r);
    r->size = sizeof *r;
    r->model = S->fm.model;
    for (int c = 0; c < 3; c++) {
        r->params.d[c] = base[c];
        r->params.s[c] = 1.0; /* the specular colour the fit holds */
    }
    bf_coords_to_params(&S->fm, best->u, r->params.p);
    r->cminpack_info = best->info;
    r->iterations = best->njev;
    r->flags = best->info == 5 ? BRDFFIT_FIT_LIMIT : 0u;
    r->at_bound = af_bounds(&S->fm, best->u, base);
}

/* The coordinates of u within AF_PIN_NEAR of an end of their ranges (bits),
 * and u with them put on it (u = -pi/2 or pi/2: the bound exactly). */
static unsigned pin_ends(const fitmap *fm, double *u)
{
    unsigned pins = 0;
    for (int j = 0; j < fm->nl; j++) {
        double t = bf_coord_position(fm, j, u[j]);
        if (t >= 0.0 && (t < AF_PIN_NEAR || t > 1.0 - AF_PIN_NEAR)) {
            pins |= 1u << j;
            u[j] = t < 0.5 ? -M_PI_2 : M_PI_2;
        }
    }
    return pins;
}

/* LM on all samples from *best with the coordinates near an end of their
 * range pinned there (where the sine map's slope vanishes, LM would crawl
 * towards the end, halving the distance each step): then each pinned one is
 * tried AF_PIN_PROBE inside, on the subset (the test is the Error's slope
 * along it at the end, which the subset's samples show as well as all of
 * them, at an eighth of the cost), and where that is lower (the end is not
 * the minimum along it) the run is taken again with it free, from where the
 * subset's run left it. */
static brdffit_status af_pinned(afstate *all, afstate *sub, const brdffit_fit_options *o,
                                afrun *best, double *base, double *solver_s)
{
    const afrun from = *best;
    unsigned pins = pin_ends(&all->fm, best->u);
    for (;;) {
        set_active(all, pins);
        int done = all->nx == 0;
        brdffit_status st = BRDFFIT_OK;
        if (done) /* every coordinate pinned: the base colour at that point */
            st = value_at(all, best->u, &best->rr, base);
        else if (all->nx <= AF_GN_MAX_NX)
            st = af_newton(all, o, best, base, &done);
        if (st == BRDFFIT_OK && !done)
            st = af_lm(all, o, best, base, solver_s);
        if (st != BRDFFIT_OK || pins == 0)
            return st;
        double at_end, b[3];
        st = value_at(sub, best->u, &at_end, b);
        int freed = 0;
        for (int j = 0; j < all->fm.nl && !freed && st == BRDFFIT_OK; j++) {
            if (!(pins & (1u << j)))
                continue;
            afrun in = *best;
            double t = best->u[j] < 0.0 ? AF_PIN_PROBE : 1.0 - AF_PIN_PROBE;
            in.u[j] = asin(2.0 * t - 1.0);
            st = value_at(sub, in.u, &in.rr, b);
            if (st == BRDFFIT_OK && in.rr < at_end) { /* the minimum is inside: from the subset's end */
                best->u[j] = from.u[j];
                pins &= ~(1u << j);
                freed = 1;
            }
        }
        if (st != BRDFFIT_OK || !freed)
            return st;
    }
}

/* Refine the kept starts on the subset, the lowest end then on all. */
static brdffit_status af_stages(afstate *sub, afstate *all, const brdffit_fit_options *o,
                                afrun *keep, int nkeep, afrun *best, double *base,
                                double *solver_s)
{
    int lo = -1;
    double bsub[3];
    brdffit_fit_options os = *o; /* a subset end is only a start for all samples */
    os.ftol = fmax(o->ftol, AF_SUBSET_TOL);
    os.xtol = fmax(o->xtol, AF_SUBSET_TOL);
    set_active(sub, 0);
    for (int k = 0; k < nkeep; k++) {
        brdffit_status st = af_lm(sub, &os, &keep[k], bsub, solver_s);
        if (st != BRDFFIT_OK)
            return st;
        if (lo < 0 || keep[k].rr < keep[lo].rr)
            lo = k;
    }
    if (lo < 0)
        return bf_fail(all->err, BRDFFIT_E_FIT_FAILED, "no start gave a finite Error");
    *best = keep[lo];
    return af_pinned(all, sub, o, best, base, solver_s);
}

brdffit_status bf_affine_fit(brdffit_context *ctx, const brdffit_samples *samples,
                             brdffit_model model, const brdffit_fit_options *o,
                             brdffit_fit_result *r, brdffit_error *err)
{
    (void)ctx;
    const bf_model_def *def = bf_model_def_get(model);
    const brdffit_samples *mirror = NULL, *subset = NULL;
    brdffit_status st = bf_samples_mirror_kept(samples, &mirror, err);
    if (st == BRDFFIT_OK)
        st = bf_affine_subset(mirror, model, &subset, err);
    if (st != BRDFFIT_OK)
        return st;
    afstate all, sub;
    memset(&all, 0, sizeof all);
    all.samples = mirror;
    all.err = err;
    bf_fitmap_init(&all.fm, model);
    set_active(&all, 0);
    sub = all;
    sub.samples = subset;

    int nstarts = o->starts ? o->starts : def->info.default_starts;
    if (nstarts > AF_MAX_STARTS)
        nstarts = AF_MAX_STARTS;
    afrun keep[MAX_KEEP], best;
    int nkeep = o->refine < 2 ? 2 : o->refine < MAX_KEEP ? o->refine : MAX_KEEP;
    double solver_s = 0.0, base[3];
    st = screen(&sub, def, nstarts, keep, &nkeep);
    if (st == BRDFFIT_OK)
        st = af_stages(&sub, &all, o, keep, nkeep, &best, base, &solver_s);
    if (st != BRDFFIT_OK)
        return st;
    fill(&all, &best, base, r);
    r->error = sqrt(fmax(bf_model_rr(mirror, model, &r->params), 0.0));
    r->passes = all.passes + sub.passes + 1;
    r->seconds_passes = all.seconds_passes + sub.seconds_passes;
    r->seconds_solver = solver_s;
    r->samples = samples->n;
    r->backend = BRDFFIT_BACKEND_HOST;
    return BRDFFIT_OK;
}
