/* SPDX-License-Identifier: MIT */
/* metric_fit.c -- what a fit does under "log" and "cube-root" after its
 * "ngan-l2" fit (docs/metrics.md): LM on all parameters (colours and lobe
 * coordinates) from the "ngan-l2" fit's, with the residuals
 * sqrt(w_s / (3 sum w)) (g(rho) - g(f)) summed by host passes (metric.c)
 * into J^T J, J^T r and r^T r; first on every 8th mirror pair, then on all.
 * Also every fit's Error under each metric, and the metrics' names. */
#include "fit_internal.h"
#include "metric.h"
#include "samples.h"
#include "subsets.h"

#include <ctype.h>
#include <math.h>
#include <string.h>

static const char *const metric_names[BRDFFIT_METRIC_COUNT] = { "ngan-l2", "log", "cube-root" };

const char *brdffit_metric_get_name(brdffit_metric metric)
{
    return (unsigned)metric < BRDFFIT_METRIC_COUNT ? metric_names[metric] : NULL;
}

brdffit_status brdffit_metric_from_name(const char *name, brdffit_metric *out, brdffit_error *err)
{
    if (!name || !out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_metric_from_name: NULL argument");
    for (int m = 0; m < BRDFFIT_METRIC_COUNT; m++) {
        const char *a = name, *b = metric_names[m];
        while (*a && *b && (tolower((unsigned char)*a) == *b || (*a == '_' && *b == '-'))) {
            a++;
            b++;
        }
        if (!*a && !*b) {
            *out = (brdffit_metric)m;
            return BRDFFIT_OK;
        }
    }
    return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                   "unknown metric \"%.60s\": the metrics are ngan-l2, log, cube-root", name);
}

/* The point of a metric pass at theta (colours, then lobe coordinates u). */
static void point_at(bf_metric_point *pt, const fitmap *fm, const double *theta)
{
    const int nlin = pt->gltf ? 3 : 6;
    for (int c = 0; c < 3; c++) {
        pt->params.d[c] = theta[c];
        if (!pt->gltf)
            pt->params.s[c] = theta[3 + c];
    }
    const double *u = theta + nlin;
    memset(pt->pts, 0, sizeof pt->pts);
    bf_coords_to_params(fm, u, pt->pts[0]);
    for (int j = 0; j < fm->nl; j++) {
        double uj[BRDFFIT_MAX_LOBE_PARAMS];
        memcpy(uj, u, sizeof(double) * (size_t)fm->nl);
        double h = 1e-7 * fmax(1.0, fabs(fmod(u[j], 2.0 * BF_PI)));
        uj[j] += h;
        bf_coords_to_params(fm, uj, pt->pts[1 + j]);
        pt->inv_h[j] = 1.0 / h;
    }
    memcpy(pt->params.p, pt->pts[0], sizeof pt->params.p);
}

static void point_init(bf_metric_point *pt, brdffit_model model, brdffit_metric metric,
                       const brdffit_params *params)
{
    memset(pt, 0, sizeof *pt);
    pt->model = model;
    pt->metric = metric;
    pt->gltf = !bf_model_has_lobe(model);
    pt->nl = bf_model_ncoords(model);
    pt->params = *params;
    bf_lambdas(params, pt->lam);
    memcpy(pt->pts[0], params->p, sizeof pt->pts[0]);
}

/* Solves (H + lambda diag H) x = -g over the free entries (Cholesky);
 * 0 when the matrix is not positive definite. */
static int damped_step(const double *H, const double *g, int n, const int *free_, double lambda,
                       double *x)
{
    double L[BF_MT_MAX][BF_MT_MAX], y[BF_MT_MAX];
    int idx[BF_MT_MAX], m = 0;
    for (int t = 0; t < n; t++)
        if (free_[t])
            idx[m++] = t;
    for (int a = 0; a < m; a++)
        for (int b = 0; b <= a; b++) {
            double v = H[idx[a] * BF_MT_MAX + idx[b]];
            if (a == b)
                v += lambda * fmax(v, 1e-300);
            for (int k = 0; k < b; k++)
                v -= L[a][k] * L[b][k];
            if (a == b) {
                if (!(v > 0))
                    return 0;
                L[a][a] = sqrt(v);
            } else {
                L[a][b] = v / L[b][b];
            }
        }
    for (int a = 0; a < m; a++) {
        double v = -g[idx[a]];
        for (int k = 0; k < a; k++)
            v -= L[a][k] * y[k];
        y[a] = v / L[a][a];
    }
    for (int t = 0; t < n; t++)
        x[t] = 0.0;
    for (int a = m - 1; a >= 0; a--) {
        double v = y[a];
        for (int k = a + 1; k < m; k++)
            v -= L[k][a] * x[idx[k]];
        x[idx[a]] = v / L[a][a];
    }
    return 1;
}

/* One LM on the groups of a set (every stride-th). */
typedef struct mlm {
    const bf_metric_set *set;
    const fitmap *fm;
    bf_metric_point pt;
    double lo[BF_MT_MAX], hi[BF_MT_MAX];
    int n;              /* entries of theta */
    int passes, iterations;
    double seconds;
    brdffit_error *err;
} mlm;

static brdffit_status run_pass(mlm *L, size_t stride, const double *theta, int full,
                               bf_metric_sums *sums)
{
    double t0 = bf_now();
    point_at(&L->pt, L->fm, theta);
    brdffit_status st = bf_metric_pass(L->set, stride, &L->pt, full, sums, L->err);
    L->passes++;
    L->seconds += bf_now() - t0;
    if (st == BRDFFIT_OK && !isfinite(sums->rr[L->pt.metric]))
        st = bf_fail(L->err, BRDFFIT_E_FIT_FAILED, "a %s pass gave a non-finite sum",
                     metric_names[L->pt.metric]);
    return st;
}

/* The damped step from theta with the entries it would take past a bound
 * put on that bound and the step solved again without them (so that one
 * coefficient going to 0 does not shorten the step of all the others). */
static int bounded_step(const mlm *L, const bf_metric_sums *S, const double *theta,
                        const int *free_in, double lambda, double *dx)
{
    int free_[BF_MT_MAX], clamped[BF_MT_MAX];
    double to[BF_MT_MAX]; /* a clamped entry's step: to its bound */
    memcpy(free_, free_in, sizeof(int) * (size_t)L->n);
    memset(clamped, 0, sizeof clamped);
    for (int round = 0; round <= L->n; round++) {
        double g[BF_MT_MAX];
        memcpy(g, S->jtr, sizeof(double) * (size_t)L->n);
        for (int t = 0; t < L->n; t++)
            if (clamped[t])
                for (int u = 0; u < L->n; u++)
                    g[u] += S->jtj[u * BF_MT_MAX + t] * to[t];
        if (!damped_step(S->jtj, g, L->n, free_, lambda, dx))
            return 0;
        int more = 0;
        for (int t = 0; t < L->n; t++) {
            if (clamped[t]) {
                dx[t] = to[t];
            } else if (free_[t] && (theta[t] + dx[t] < L->lo[t] || theta[t] + dx[t] > L->hi[t])) {
                to[t] = (theta[t] + dx[t] < L->lo[t] ? L->lo[t] : L->hi[t]) - theta[t];
                clamped[t] = 1;
                free_[t] = 0;
                more = 1;
            }
        }
        if (!more)
            break;
    }
    for (int t = 0; t < L->n; t++)
        if (clamped[t])
            dx[t] = to[t];
    return 1;
}

/* The residuals' own curvature sum w r grad^2 r, which J^T J leaves out and
 * which on these fits is a large negative share of the Hessian in the lobe
 * coordinates (a tenth of J^T J's, on alum-bronze): estimated by symmetric
 * rank-one secant updates from consecutive points' gradients J^T r, as the
 * "ngan-l2" fit does (docs/fitting.md, "Newton's curvature"). */
static void secant_update(const mlm *L, double *sc, const bf_metric_sums *old,
                          const bf_metric_sums *now, const double *step)
{
    const int n = L->n;
    double v[BF_MT_MAX], vs = 0.0, vv = 0.0, ss = 0.0;
    for (int t = 0; t < n; t++) {
        double bs = 0.0;
        for (int u = 0; u < n; u++)
            bs += (now->jtj[t * BF_MT_MAX + u] + sc[t * BF_MT_MAX + u]) * step[u];
        v[t] = (now->jtr[t] - old->jtr[t]) - bs;
        vs += v[t] * step[t];
        vv += v[t] * v[t];
        ss += step[t] * step[t];
    }
    if (!(fabs(vs) > 1e-8 * sqrt(vv * ss)))
        return;
    for (int t = 0; t < n; t++)
        for (int u = 0; u < n; u++)
            sc[t * BF_MT_MAX + u] += v[t] * v[u] / vs;
}

/* The sums with J^T J + sc in place of J^T J when that, less a tenth of
 * J^T J, is positive definite; else as they are. */
static bf_metric_sums with_secant(const mlm *L, const bf_metric_sums *S, const double *sc)
{
    bf_metric_sums H = *S;
    int all[BF_MT_MAX];
    double x[BF_MT_MAX];
    for (int t = 0; t < L->n; t++)
        all[t] = 1;
    for (int t = 0; t < L->n; t++)
        for (int u = 0; u < L->n; u++)
            H.jtj[t * BF_MT_MAX + u] = 0.9 * S->jtj[t * BF_MT_MAX + u] + sc[t * BF_MT_MAX + u];
    if (!damped_step(H.jtj, S->jtr, L->n, all, 0.0, x))
        return *S;
    for (int t = 0; t < L->n; t++)
        for (int u = 0; u < L->n; u++)
            H.jtj[t * BF_MT_MAX + u] = S->jtj[t * BF_MT_MAX + u] + sc[t * BF_MT_MAX + u];
    return H;
}

/* LM from theta on every stride-th group, to a relative decrease below tol
 * or max_it steps (*limit set then); sums: the value sums at the end.  sc:
 * the secant estimate, carried in and out; made on other samples whose r^T r
 * at theta was sc_rr (> 0), it is scaled to these first. */
static brdffit_status lm_stage(mlm *L, size_t stride, double *theta, double tol, int max_it,
                               double *sc, double sc_rr, bf_metric_sums *at, int *limit)
{
    bf_metric_sums S, T;
    brdffit_status st = run_pass(L, stride, theta, 1, &S);
    if (st != BRDFFIT_OK)
        return st;
    const brdffit_metric m = L->pt.metric;
    if (sc_rr > 0)
        for (int k = 0; k < BF_MT_MAX * BF_MT_MAX; k++)
            sc[k] *= S.rr[m] / sc_rr;
    double lambda = 1e-3;
    *limit = 0;
    for (int it = 0;; it++) {
        if (it == max_it) {
            *limit = 1;
            break;
        }
        int free_[BF_MT_MAX], moved = 0;
        for (int t = 0; t < L->n; t++)
            free_[t] = !((theta[t] <= L->lo[t] && S.jtr[t] > 0) ||
                         (theta[t] >= L->hi[t] && S.jtr[t] < 0));
        double trial[BF_MT_MAX], rel = 0.0;
        for (int tries = 0; tries < 12 && !moved; tries++, lambda *= 4.0) {
            double dx[BF_MT_MAX];
            bf_metric_sums H = with_secant(L, &S, sc);
            if (!bounded_step(L, &H, theta, free_, lambda, dx))
                continue;
            for (int t = 0; t < L->n; t++)
                trial[t] = fmin(fmax(theta[t] + dx[t], L->lo[t]), L->hi[t]);
            st = run_pass(L, stride, trial, 0, &T);
            if (st != BRDFFIT_OK)
                return st;
            if (T.rr[m] < S.rr[m]) {
                rel = (S.rr[m] - T.rr[m]) / S.rr[m];
                moved = 1;
            }
        }
        if (!moved)
            break;
        lambda = fmax(lambda / 12.0, 1e-9); /* the loop's last *4, and /3 */
        double step[BF_MT_MAX];
        for (int t = 0; t < L->n; t++)
            step[t] = trial[t] - theta[t];
        memcpy(theta, trial, sizeof(double) * (size_t)L->n);
        L->iterations++;
        if (rel < tol) {
            S = T;
            break;
        }
        bf_metric_sums old = S;
        st = run_pass(L, stride, theta, 1, &S);
        if (st != BRDFFIT_OK)
            return st;
        secant_update(L, sc, &old, &S, step);
    }
    *at = S;
    return BRDFFIT_OK;
}

#define SUBSET_STRIDE 8
#define SUBSET_TOL 1e-6
#define SUBSET_MAX_IT 40
#define ALL_TOL 1e-6
#define ALL_MAX_IT 3

/* The bits of brdffit_at_bound of a metric fit's parameters. */
static unsigned metric_bounds(const mlm *L, const double *theta)
{
    unsigned mask = 0;
    const int nlin = L->pt.gltf ? 3 : 6;
    for (int t = 0; t < nlin; t++)
        if (theta[t] <= L->lo[t] || theta[t] >= L->hi[t])
            mask |= (unsigned)(t < 3 ? BRDFFIT_AT_BOUND_D_R << t : BRDFFIT_AT_BOUND_S_R << (t - 3));
    unsigned on = bf_on_bounds(L->fm, theta + nlin);
    for (int j = 0; j < L->fm->nl; j++)
        if (on & (1u << j))
            mask |= (unsigned)BRDFFIT_AT_BOUND_P0 << L->fm->param[j];
    return mask;
}

/* theta's length and bounds: the colours >= 0 (glTF: in [0, 1]), the lobe
 * coordinates free (their sine maps keep the parameters within bounds). */
static void theta_bounds(mlm *L)
{
    const int nlin = L->pt.gltf ? 3 : 6;
    L->n = nlin + L->fm->nl;
    for (int t = 0; t < nlin; t++) {
        L->lo[t] = 0.0;
        L->hi[t] = L->pt.gltf ? 1.0 : INFINITY;
    }
    for (int j = 0; j < L->fm->nl; j++) {
        L->lo[nlin + j] = -INFINITY;
        L->hi[nlin + j] = INFINITY;
    }
}

brdffit_status bf_metric_refit(const brdffit_samples *samples, brdffit_model model,
                               brdffit_metric metric, brdffit_fit_result *r, brdffit_error *err)
{
    const bf_metric_set *set = NULL;
    brdffit_status st = bf_metric_set_kept(samples, &set, err);
    if (st != BRDFFIT_OK)
        return st;
    fitmap fm;
    bf_fitmap_init(&fm, model);
    mlm L;
    memset(&L, 0, sizeof L);
    L.set = set;
    L.fm = &fm;
    L.err = err;
    point_init(&L.pt, model, metric, &r->params);
    theta_bounds(&L);
    double theta[BF_MT_MAX];
    const int nlin = L.pt.gltf ? 3 : 6;
    for (int c = 0; c < 3; c++) {
        theta[c] = r->params.d[c];
        if (!L.pt.gltf)
            theta[3 + c] = r->params.s[c];
    }
    bf_params_to_coords(&fm, r->params.p, theta + nlin);
    bf_metric_sums at;
    int limit = 0;
    double sc[BF_MT_MAX * BF_MT_MAX];
    memset(sc, 0, sizeof sc);
    double sub_rr = 0.0;
    if (set->n / SUBSET_STRIDE >= BF_SCREEN_MIN_SAMPLES) {
        st = lm_stage(&L, SUBSET_STRIDE, theta, SUBSET_TOL, SUBSET_MAX_IT, sc, 0.0, &at, &limit);
        if (st != BRDFFIT_OK)
            return st;
        sub_rr = at.rr[metric];
    }
    /* on all samples every pass sums the other metrics too: the Errors at
     * the end come with the last one */
    L.pt.sum_bits = (1u << BRDFFIT_METRIC_LOG) | (1u << BRDFFIT_METRIC_CUBE_ROOT);
    st = lm_stage(&L, 1, theta, ALL_TOL, ALL_MAX_IT, sc, sub_rr, &at, &limit);
    if (st != BRDFFIT_OK)
        return st;
    point_at(&L.pt, &fm, theta);
    memcpy(r->params.d, L.pt.params.d, sizeof r->params.d);
    memcpy(r->params.s, L.pt.params.s, sizeof r->params.s);
    memcpy(r->params.p, L.pt.pts[0], sizeof r->params.p);
    for (int m = 1; m < BRDFFIT_METRIC_COUNT; m++)
        r->errors[m] = sqrt(fmax(at.rr[m], 0.0));
    r->metric = (int)metric;
    r->metric_iterations = L.iterations;
    r->iterations += L.iterations;
    r->passes += L.passes;
    r->seconds_passes += L.seconds;
    r->at_bound = metric_bounds(&L, theta);
    if (limit)
        r->flags |= BRDFFIT_FIT_LIMIT;
    return BRDFFIT_OK;
}

/* errors[m] of params for m = log, cube-root (one host value pass). */
brdffit_status bf_metric_errors(const brdffit_samples *samples, brdffit_model model,
                                const brdffit_params *params, double *errors, brdffit_error *err)
{
    const bf_metric_set *set = NULL;
    brdffit_status st = bf_metric_set_kept(samples, &set, err);
    if (st != BRDFFIT_OK)
        return st;
    bf_metric_point pt;
    point_init(&pt, model, BRDFFIT_METRIC_LOG, params);
    pt.sum_bits = (1u << BRDFFIT_METRIC_LOG) | (1u << BRDFFIT_METRIC_CUBE_ROOT);
    bf_metric_sums sums;
    st = bf_metric_pass(set, 1, &pt, 0, &sums, err);
    if (st != BRDFFIT_OK)
        return st;
    for (int m = 1; m < BRDFFIT_METRIC_COUNT; m++)
        errors[m] = sqrt(fmax(sums.rr[m], 0.0));
    return BRDFFIT_OK;
}

brdffit_status brdffit_error_metric(brdffit_context *ctx, const brdffit_samples *samples,
                                    brdffit_model model, const brdffit_params *params,
                                    brdffit_metric metric, double *error, brdffit_error *err)
{
    if ((unsigned)metric >= BRDFFIT_METRIC_COUNT)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "metric %d is not a metric (0 ngan-l2, 1 log, 2 cube-root)", (int)metric);
    if (metric == BRDFFIT_METRIC_NGAN_L2)
        return brdffit_error_of(ctx, samples, model, params, error, err);
    if (!ctx || !samples || !error)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_error_metric: NULL argument");
    if (!brdffit_model_get(model))
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    brdffit_status st = brdffit_params_check(model, params, err);
    if (st != BRDFFIT_OK)
        return st;
    double errors[BRDFFIT_METRIC_COUNT];
    st = bf_metric_errors(samples, model, params, errors, err);
    if (st == BRDFFIT_OK) {
        *error = errors[metric];
        bf_ok(err);
    }
    return st;
}
