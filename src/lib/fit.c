/* fit.c -- brdffit_fit: start screening and Levenberg-Marquardt (cminpack).
 *
 * Unknowns x (internal coordinates, nx = X_LOBE + nl), offsets named X_*:
 *   x[X_D + c] = sqrt(d_c), x[X_S + c] = sqrt(s_c)      (d, s >= 0)
 *   x[X_LOBE + j] = lobe coordinates u: bounded parameters v = lo + (hi-lo)(1+sin u)/2,
 *             on a log scale for widths and exponents; Lafortune's direction is
 *             an angle phi with (Cxy, Cz) = (cos phi / sqrt 2, sin phi).
 *
 * cminpack's own QR would cost far more than a data pass on ~1M rows, so lmder
 * is given an exactly equivalent problem whose size does not grow with the
 * data: from a pass's sums J^T J, J^T r, r^T r form the Cholesky factor R of
 * J^T J, z = R^-T J^T r, t = sqrt(r^T r - |z|^2), and hand lmder the nx+1
 * residuals [z; t] with Jacobian [R; 0].  Then |[z;t]|^2 = r^T r and
 * |[z;t] + [R;0] p|^2 = |r + J p|^2 for every step p, so lmder's steps,
 * scaling and convergence tests are those of the full problem.  Each
 * evaluated point caches both (lmder pairs a trial's residual with the
 * Jacobian it asks for next).
 */
#define _DEFAULT_SOURCE /* M_PI, M_SQRT2, M_SQRT1_2 */
#include "pass.h"
#include "samples.h"

#include <cminpack.h>
#include <math.h>
#include <string.h>

enum { X_D = 0, X_S = 3, X_LOBE = 6 }; /* offsets of the unknowns */
#define NX_MAX (X_LOBE + BF_MAX_NP)
#define NM_MAX (NX_MAX + 1)
#define FD_STEP 1e-7

enum { MAP_LOG, MAP_LIN, MAP_ANGLE };

typedef struct fitmap {
    brdffit_model model;
    int nl;                     /* lobe coordinates */
    int kind[BF_MAX_NP];
    double lo[BF_MAX_NP], hi[BF_MAX_NP]; /* in log units for MAP_LOG */
} fitmap;

static void fitmap_init(fitmap *fm, brdffit_model model)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    fm->model = model;
    fm->nl = bf_model_ncoords(model);
    int src = 0;
    for (int j = 0; j < fm->nl; j++, src++) {
        if (model == BRDFFIT_LAFORTUNE && j == 0) {
            fm->kind[0] = MAP_ANGLE;
            fm->lo[0] = fm->hi[0] = 0;
            src = 1; /* Cxy, Cz -> one angle; the next coordinate is n (param 2) */
            continue;
        }
        int is_f0 = (model == BRDFFIT_COOK_TORRANCE || model == BRDFFIT_ASHIKHMIN_SHIRLEY) && j == 0;
        fm->kind[j] = is_f0 ? MAP_LIN : MAP_LOG;
        fm->lo[j] = is_f0 ? mi->lower[src] : log(mi->lower[src]);
        fm->hi[j] = is_f0 ? mi->upper[src] : log(mi->upper[src]);
    }
}

static double map_fwd(const fitmap *fm, int j, double u)
{
    double v = fm->lo[j] + (fm->hi[j] - fm->lo[j]) * 0.5 * (1.0 + sin(u));
    return fm->kind[j] == MAP_LOG ? exp(v) : v;
}

static double map_inv(const fitmap *fm, int j, double v)
{
    if (fm->kind[j] == MAP_LOG)
        v = log(v);
    double t = 2.0 * (v - fm->lo[j]) / (fm->hi[j] - fm->lo[j]) - 1.0;
    return asin(fmin(fmax(t, -1.0), 1.0));
}

/* Lobe coordinates u -> lobe parameters p in the paper's units. */
static void coords_to_params(const fitmap *fm, const double *u, double p[3])
{
    p[0] = p[1] = p[2] = 0.0;
    if (fm->model == BRDFFIT_LAFORTUNE) {
        p[0] = cos(u[0]) * M_SQRT1_2;
        p[1] = sin(u[0]);
        p[2] = map_fwd(fm, 1, u[1]);
        return;
    }
    for (int j = 0; j < fm->nl; j++)
        p[j] = map_fwd(fm, j, u[j]);
}

static void params_to_coords(const fitmap *fm, const double p[3], double *u)
{
    if (fm->model == BRDFFIT_LAFORTUNE) {
        u[0] = atan2(p[1], p[0] * M_SQRT2);
        u[1] = map_inv(fm, 1, p[2]);
        return;
    }
    for (int j = 0; j < fm->nl; j++)
        u[j] = map_inv(fm, j, p[j]);
}

/* ---------------------------------------------------------------- one point */

typedef struct point {
    int valid;
    double x[NX_MAX];
    double fvec[NM_MAX];
    double fjac[NM_MAX * NX_MAX];  /* column-major, leading dimension nx+1 */
    double rr;                     /* r^T r = E^2 */
} point;

typedef struct lmstate {
    bf_pass_driver *ps;
    fitmap fm;
    int nx;
    double lam[3];
    point cache[2];
    int next;
    double seconds_cb;             /* time inside the callback */
    brdffit_status st;
    brdffit_error *err;
} lmstate;

static void make_pass_par(const lmstate *S, const double *x, int with_fd, bf_pass_par *pp)
{
    memset(pp, 0, sizeof *pp);
    for (int c = 0; c < 3; c++) {
        pp->d[c] = x[X_D + c] * x[X_D + c];
        pp->s[c] = x[X_S + c] * x[X_S + c];
        pp->lam[c] = S->lam[c];
    }
    coords_to_params(&S->fm, x + X_LOBE, pp->p[0]);
    if (!with_fd)
        return;
    for (int j = 0; j < S->fm.nl; j++) {
        double u[BF_MAX_NP];
        memcpy(u, x + X_LOBE, sizeof u);
        double h = FD_STEP * fmax(1.0, fabs(u[j]));
        u[j] += h;
        h = u[j] - x[X_LOBE + j]; /* the step actually representable */
        coords_to_params(&S->fm, u, pp->p[1 + j]);
        pp->inv_h[j] = 1.0 / h;
    }
}

/* From the moments at x: J^T J (H), J^T r (g), r^T r; then [z; t] and [R; 0]. */
static void assemble(const lmstate *S, const double *x, const bf_pass_par *pp, const double *mom,
                     point *pt)
{
    const int nx = S->nx, np = S->fm.nl, nk = S->ps->nk, m = nx + 1;
    double H[NX_MAX][NX_MAX], g[NX_MAX], rr = 0.0;
    memset(H, 0, sizeof H);
    memset(g, 0, sizeof g);
    const double A = mom[BF_MOM_A], ipi = 1.0 / M_PI;
    for (int c = 0; c < 3; c++) {
        int k = nk > 1 ? c : 0;
        const double *mk = mom + bf_mom_lobe(k, np);
        const double *mc = mom + bf_mom_chan(c, nk, np);
        const int xd = X_D + c, xs = X_S + c;
        double jd = 2.0 * x[xd], js = 2.0 * x[xs], s = pp->s[c];
        H[xd][xd] = jd * jd * A * ipi * ipi;
        H[xd][xs] = jd * js * mk[BF_MK_SK] * ipi;
        H[xs][xs] = js * js * mk[BF_MK_SKK];
        g[xd] = -jd * ipi * mc[BF_MC_SE];
        g[xs] = -js * mc[BF_MC_SKE];
        rr += mc[BF_MC_SEE];
        for (int j = 0; j < np; j++) {
            H[xd][X_LOBE + j] = jd * ipi * s * mk[bf_mk_sg(j)];
            H[xs][X_LOBE + j] = js * s * mk[bf_mk_skg(np, j)];
            g[X_LOBE + j] -= s * mc[bf_mc_sge(j)];
            for (int l = j; l < np; l++)
                H[X_LOBE + j][X_LOBE + l] += s * s * mk[bf_mk_sgg(np, j, l)];
        }
    }
    /* Cholesky H = R^T R (upper R); a pivot that vanishes (a direction the
     * data does not see, e.g. d = 0) gives a zero row, consistent with J. */
    double R[NX_MAX][NX_MAX], z[NX_MAX];
    memset(R, 0, sizeof R);
    for (int k = 0; k < nx; k++) {
        double piv = H[k][k];
        for (int i = 0; i < k; i++)
            piv -= R[i][k] * R[i][k];
        if (!(piv > 1e-13 * H[k][k]) || !(piv > 0)) {
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
    double zz = 0.0;
    for (int k = 0; k < nx; k++)
        zz += z[k] * z[k];
    rr = fmax(rr, 0.0);
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

static const point *evaluate(lmstate *S, const double *x)
{
    for (int i = 0; i < 2; i++)
        if (S->cache[i].valid && memcmp(S->cache[i].x, x, S->nx * sizeof *x) == 0)
            return &S->cache[i];
    bf_pass_par pp;
    make_pass_par(S, x, 1, &pp);
    double mom[BF_NMOM_MAX];
    S->st = bf_driver_run(S->ps, 1, &pp, mom, S->err);
    if (S->st != BRDFFIT_OK)
        return NULL;
    point *pt = &S->cache[S->next];
    S->next ^= 1;
    assemble(S, x, &pp, mom, pt);
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

typedef struct start {
    double x[NX_MAX];
    double cost;
} start;

/* The lobe parameters of start number i of n (a log grid of the lobe width). */
static void start_params(brdffit_model model, int i, int n, double p[3])
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    double t = n > 1 ? (double)i / (n - 1) : 0.5;
    double lo = 0, hi = 0;
    p[0] = mi->start[0];
    p[1] = mi->start[1];
    p[2] = mi->start[2];
    switch (model) {
    case BRDFFIT_WARD:
    case BRDFFIT_WARD_DUER:
        lo = 0.005, hi = 0.5;
        p[0] = lo * pow(hi / lo, t);
        break;
    case BRDFFIT_BLINN_PHONG:
        lo = 2, hi = 5e4;
        p[0] = lo * pow(hi / lo, t);
        break;
    case BRDFFIT_LAFORTUNE:
        lo = 2, hi = 5e4;
        p[2] = lo * pow(hi / lo, t);
        break;
    case BRDFFIT_COOK_TORRANCE:
        lo = 0.005, hi = 0.5;
        p[1] = lo * pow(hi / lo, t);
        break;
    case BRDFFIT_ASHIKHMIN_SHIRLEY:
        lo = 2, hi = 5e4;
        p[1] = lo * pow(hi / lo, t);
        break;
    case BRDFFIT_HE:
        /* tau over 4, 8, ..., 28 as Ngan et al.; further rounds of 7 vary sigma0 */
        p[0] = 4.0 * (1 + (i % 7));
        p[1] = mi->start[1] * pow(4.0, (double)(i / 7));
        if (p[1] > mi->upper[1])
            p[1] = mi->upper[1];
        break;
    default:
        break;
    }
}

/* Best non-negative (d, s) for one channel from value moments taken at d = s = 0. */
static double best_linear(double A, double SK, double SKK, double SE, double SKE, double SEE,
                          double *d, double *s)
{
    const double a11 = A / (M_PI * M_PI), a12 = SK / M_PI, a22 = SKK, b1 = SE / M_PI, b2 = SKE;
#define COST(dd, ss) (SEE - 2.0 * (b1 * (dd) + b2 * (ss)) + a11 * (dd) * (dd) + \
                      2.0 * a12 * (dd) * (ss) + a22 * (ss) * (ss))
    double det = a11 * a22 - a12 * a12;
    double bd = 0, bs = 0, best = SEE;
    if (det > 1e-14 * a11 * a22) {
        double dd = (b1 * a22 - b2 * a12) / det, ss = (a11 * b2 - a12 * b1) / det;
        if (dd >= 0 && ss >= 0 && COST(dd, ss) < best)
            bd = dd, bs = ss, best = COST(dd, ss);
    }
    if (a11 > 0) {
        double dd = fmax(b1 / a11, 0.0);
        if (COST(dd, 0.0) < best)
            bd = dd, bs = 0, best = COST(dd, 0.0);
    }
    if (a22 > 0) {
        double ss = fmax(b2 / a22, 0.0);
        if (COST(0.0, ss) < best)
            bd = 0, bs = ss, best = COST(0.0, ss);
    }
#undef COST
    *d = bd;
    *s = bs;
    return best;
}

/* One value pass at the start's lobe with d = s = 0 gives the exact best
 * linear part; x gets it (kept off 0, where sqrt-coordinates stall). */
static brdffit_status screen_start(lmstate *S, const double p[3], start *st)
{
    bf_pass_par pp;
    memset(&pp, 0, sizeof pp);
    memcpy(pp.lam, S->lam, sizeof pp.lam);
    memcpy(pp.p[0], p, 3 * sizeof *p);
    double mom[BF_NMOM_MAX];
    brdffit_status rc = bf_driver_run(S->ps, 0, &pp, mom, S->err);
    if (rc != BRDFFIT_OK)
        return rc;
    const int nk = S->ps->nk;
    st->cost = 0.0;
    for (int c = 0; c < 3; c++) {
        const double *mk = mom + bf_mom_lobe(nk > 1 ? c : 0, 0);
        const double *mc = mom + bf_mom_chan(c, nk, 0);
        double d, s, A = mom[BF_MOM_A];
        st->cost += best_linear(A, mk[BF_MK_SK], mk[BF_MK_SKK], mc[BF_MC_SE], mc[BF_MC_SKE],
                                mc[BF_MC_SEE], &d, &s);
        double mean_rho = A > 0 ? fmax(mc[BF_MC_SE] / A, 0.0) : 0.0;
        double mean_k = A > 0 ? mk[BF_MK_SK] / A : 0.0;
        double dfloor = 1e-4 * M_PI * mean_rho + 1e-12;
        double sfloor = (mean_k > 0 ? 1e-4 * mean_rho / mean_k : 0.0) + 1e-12;
        st->x[X_D + c] = sqrt(fmax(d, dfloor));
        st->x[X_S + c] = sqrt(fmax(s, sfloor));
    }
    params_to_coords(&S->fm, p, st->x + X_LOBE);
    return BRDFFIT_OK;
}

void brdffit_fit_options_default(brdffit_fit_options *opt)
{
    if (!opt)
        return;
    memset(opt, 0, sizeof *opt);
    opt->starts = 0; /* the model's own: 8, He 7 */
    opt->refine = 1;
    opt->ftol = 1e-8;
    opt->xtol = 1e-8;
    opt->gtol = 0.0;
    opt->max_evals = 200;
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

brdffit_status brdffit_fit(brdffit_context *ctx, const brdffit_samples *samples, brdffit_model model,
                           const brdffit_fit_options *opt, brdffit_fit_result *result,
                           brdffit_error *err)
{
    double t_start = bf_now();
    if (!ctx || !samples || !result)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_fit: NULL context, samples or result");
    if (!brdffit_model_get(model))
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    brdffit_fit_options o;
    brdffit_fit_options_default(&o);
    if (opt)
        o = *opt;
    brdffit_status rc = check_fit_options(&o, err);
    if (rc != BRDFFIT_OK)
        return rc;
    rc = check_enough_samples(samples, model, err);
    if (rc != BRDFFIT_OK)
        return rc;

    bf_pass_driver ps;
    rc = bf_driver_open(&ps, ctx, samples, model, err);
    if (rc != BRDFFIT_OK) {
        bf_driver_close(&ps);
        return rc;
    }
    lmstate S;
    memset(&S, 0, sizeof S);
    S.ps = &ps;
    S.err = err;
    fitmap_init(&S.fm, model);
    S.nx = X_LOBE + S.fm.nl;
    brdffit_params lp;
    memset(&lp, 0, sizeof lp);
    memcpy(lp.lambda_um, o.lambda_um, sizeof lp.lambda_um);
    bf_lambdas(&lp, S.lam);

    /* screen the starts, keep the best `refine` */
    enum { MAX_KEEP = 16 };
    start keep[MAX_KEEP];
    int nkeep = 0, refine = o.refine < MAX_KEEP ? o.refine : MAX_KEEP;
    int nstarts = o.starts ? o.starts : model == BRDFFIT_HE ? 7 : 8;
    for (int i = 0; i < nstarts; i++) {
        double p[3];
        start st;
        start_params(model, i, nstarts, p);
        rc = screen_start(&S, p, &st);
        if (rc != BRDFFIT_OK) {
            bf_driver_close(&ps);
            return rc;
        }
        int pos = nkeep;
        while (pos > 0 && st.cost < keep[pos - 1].cost)
            pos--;
        if (pos >= refine)
            continue;
        if (nkeep < refine)
            nkeep++;
        memmove(keep + pos + 1, keep + pos, (nkeep - 1 - pos) * sizeof *keep);
        keep[pos] = st;
    }

    /* refine each kept start with lmder */
    const int nx = S.nx, m = nx + 1;
    double best_rr = INFINITY, best_x[NX_MAX];
    int best_info = 0, best_njev = 0;
    double solver_seconds = 0.0;
    for (int r = 0; r < nkeep; r++) {
        double x[NX_MAX], fvec[NM_MAX], fjac[NM_MAX * NX_MAX], diag[NX_MAX], qtf[NX_MAX];
        double wa1[NX_MAX], wa2[NX_MAX], wa3[NX_MAX], wa4[NM_MAX];
        int ipvt[NX_MAX], nfev = 0, njev = 0;
        memcpy(x, keep[r].x, sizeof x);
        S.cache[0].valid = S.cache[1].valid = 0;
        S.st = BRDFFIT_OK;
        double cb0 = S.seconds_cb, t0 = bf_now();
        int info = lmder(lm_callback, &S, m, nx, x, fvec, fjac, m, o.ftol, o.xtol, o.gtol,
                         o.max_evals, diag, 1, 100.0, 0, &nfev, &njev, ipvt, qtf, wa1, wa2, wa3, wa4);
        solver_seconds += (bf_now() - t0) - (S.seconds_cb - cb0);
        if (S.st != BRDFFIT_OK) { /* a pass failed: lmder was stopped (info < 0) */
            bf_driver_close(&ps);
            return S.st;
        }
        const point *pt = evaluate(&S, x); /* cached: the point lmder returned */
        if (!pt) {
            bf_driver_close(&ps);
            return S.st;
        }
        if (pt->rr < best_rr) {
            best_rr = pt->rr;
            memcpy(best_x, x, sizeof best_x);
            best_info = info;
            best_njev = njev;
        }
    }
    if (!isfinite(best_rr)) {
        bf_driver_close(&ps);
        return bf_fail(err, BRDFFIT_E_FIT_FAILED, "no start gave a finite Error");
    }

    memset(result, 0, sizeof *result);
    result->model = model;
    for (int c = 0; c < 3; c++) {
        result->params.d[c] = best_x[X_D + c] * best_x[X_D + c];
        result->params.s[c] = best_x[X_S + c] * best_x[X_S + c];
    }
    coords_to_params(&S.fm, best_x + X_LOBE, result->params.p);
    if (model == BRDFFIT_HE)
        memcpy(result->params.lambda_um, S.lam, sizeof S.lam);
    result->error = sqrt(best_rr);
    result->cminpack_info = best_info;
    result->iterations = best_njev;
    result->evaluations = ps.passes;
    result->samples = samples->n;
    result->backend = brdffit_context_backend(ctx);
    result->seconds_passes = ps.seconds;
    result->seconds_solver = solver_seconds;
    bf_driver_close(&ps);
    result->seconds = bf_now() - t_start;
    bf_ok(err);
    return BRDFFIT_OK;
}

brdffit_status brdffit_error_of(brdffit_context *ctx, const brdffit_samples *samples,
                                brdffit_model model, const brdffit_params *params, double *error,
                                brdffit_error *err)
{
    if (!ctx || !samples || !error)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_error_of: NULL argument");
    brdffit_status rc = brdffit_params_check(model, params, err);
    if (rc != BRDFFIT_OK)
        return rc;
    bf_pass_driver ps;
    rc = bf_driver_open(&ps, ctx, samples, model, err);
    if (rc == BRDFFIT_OK) {
        bf_pass_par pp;
        memset(&pp, 0, sizeof pp);
        memcpy(pp.d, params->d, sizeof pp.d);
        memcpy(pp.s, params->s, sizeof pp.s);
        bf_lambdas(params, pp.lam);
        memcpy(pp.p[0], params->p, sizeof pp.p[0]);
        double mom[BF_NMOM_MAX];
        rc = bf_driver_run(&ps, 0, &pp, mom, err);
        if (rc == BRDFFIT_OK) {
            double rr = 0.0;
            for (int c = 0; c < 3; c++)
                rr += mom[bf_mom_chan(c, ps.nk, 0) + BF_MC_SEE];
            *error = sqrt(fmax(rr, 0.0));
            bf_ok(err);
        }
    }
    bf_driver_close(&ps);
    return rc;
}
