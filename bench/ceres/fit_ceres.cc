// SPDX-License-Identifier: MIT
// fit_ceres.cc -- `make bench-ceres`: brdffit's fit against a tuned Ceres
// Solver fit of the same problem, on the same tables, in one run.
//
// WHAT IT SOLVES.  The objective of every brdffit fit, the "ngan-l2" Error
// (include/brdffit.h):
//     E^2 = sum_s sum_c a2_s (rho_c(s) - d_c / pi - s_c K(s; p))^2 (+ pair_see)
// with a2_s = w_s cos^2 ti / (3 sum w) the library's metric weight, as
// nonlinear least squares: one residual sqrt(a2_s) (rho_c - f_c) per sample
// and channel (bench/ceres/fc_shim.c), over the samples brdffit's passes on
// all samples read: the sample set's mirror set (each pair of samples at
// phi_d and pi - phi_d, which every model gives one value, merged into one;
// pair_see is their constant share of E^2 that no residual carries: the same
// sums as the whole set up to rounding, about half the samples).  With
// --all-samples the set itself instead (twice the residuals, same minimum).
// The run checks the residuals against the library: E from them at brdffit's
// fitted parameters against brdffit's reported Error (printed, "Error check").
//
// UNKNOWNS.  Per channel c a parameter block (d_c, s_c), free within
// d, s >= 0, and one block theta of the lobe coordinates in the registry's
// maps: ln p for a LOG parameter, p for a LINEAR one (F0), each within the
// registry's bounds through Ceres's bounds, Lafortune's (Cxy, Cz) direction
// as one angle.  Ceres has no variable projection, so d and s are unknowns
// of its LM: 6 + np of them, where brdffit's LM moves only the np lobe
// coordinates and solves d, s exactly at each lobe point (linear.c).  (A
// projection inside Ceres would need the library's moments and its
// non-negative solve per evaluation -- brdffit's own algorithm with Ceres in
// cminpack's place, not a general-purpose fit.)
//
// JACOBIAN.  Analytic: K and dK/dp from the kernel headers' own maths
// (bf_lobe_vdk; bf_lobe when Ceres asks for values only) through the C shim
// fc_shim.c, compiled with the project's flags; d r / d d, d r / d s and the
// chain rule through the parameter map are the only derivatives written
// there.  No numeric differentiation, no second copy of a model formula.
//
// TUNING.  Levenberg-Marquardt trust region (as cminpack's lmder, which
// brdffit drives), num_threads = 2 (the machine's cores; Ceres evaluates
// residual blocks in parallel).  Residual blocks of --chunk 16384 samples of
// one channel, each over (d_c, s_c) and theta (--layout channel): a
// block-sparse Jacobian of 2 + np columns a row instead of 6 + np, solved
// by SPARSE_NORMAL_CHOLESKY.  Measured on alum-bronze (ggx, cook-torrance;
// --report gives Ceres's time split): with one block of all three channels
// over d[3], s[3], theta (--layout joint) DENSE_NORMAL_CHOLESKY took 1.4-1.7x
// and DENSE_QR 2.5x the time; per channel DENSE_SCHUR was as fast, dense
// normal Cholesky 1.3-1.9x; blocks of 1024-65536 samples varied within the
// machine's noise, 16384 the fastest.  Ceres's projected line search after a
// bounded step (max_num_line_search_step_size_iterations) is off
// (--bound-search N turns it on): it took a second Jacobian evaluation every
// iteration, 1.5-2x the time, to the same minimum.  The initial trust
// region radius (--radius, 1e2 .. 1e8) changed nothing: LM's steps are not
// held by the region (gain ratio ~1.8 every step) but short, Gauss-Newton's
// linear convergence on a problem whose residuals stay large (Ward on
// gold-metallic-paint2: 22 iterations, each removing ~40% of what is left;
// brdffit's LM corrects Gauss-Newton's H by a secant estimate of the
// residuals' curvature, fit/problem.c secant_correct, and takes 5).  Ceres's
// line-search BFGS (--minimizer bfgs; without bounds, which Ceres's line
// search does not take) converged faster there but took 50-80 iterations on
// blue-rubber and pickled-oak-260: the median over these 35 fits the same
// within the machine's noise, so LM, which keeps the bounds.  Jacobi scaling on
// (lmder's diag scaling).  Tolerances those of brdffit's LM
// (brdffit_fit_options defaults): function_tolerance = ftol = 1e-8,
// parameter_tolerance = xtol = 1e-8, gradient_tolerance 1e-10 (Ceres's
// default; brdffit's gtol is 0), max_num_iterations 200 (brdffit's
// max_evals).
//
// FAIRNESS.  Same data (the library's sample set, and the mirror set brdffit
// reads), same objective (checked against the library's Error), same start:
// Ceres starts at the start brdffit's screening keeps and refines (the
// registry's start grid, screened by value passes as brdffit screens it,
// fc_best_start), with the exact best d, s there -- that screening is NOT in
// Ceres's time, while brdffit's time includes its own screening of all its
// starts.  Both timed with kernels and derived sample sets made beforehand
// (brdffit_context_prepare, brdffit_samples_prepare; Ceres's Problem built
// beforehand), each the fastest of --reps runs, in alternation (a burst of
// load on the shared machine hits both).  Ceres's time is that of
// ceres::Solve; a second figure, "Ceres to 1%", is the time at the end of
// the first Ceres iteration whose Error is within 1% of brdffit's final
// Error (what a Ceres user would need were they to know when to stop).  A
// Ceres fit "matches" when its final Error is within 1% of brdffit's.
//
// Usage: bench_ceres [--models a,b,...] [--materials a,b,...] [--reps N]
//                    [--chunk N] [--solver NAME] [--layout channel|joint] [--bound-search N]
//                    [--radius R] [--minimizer lm|bfgs] [--all-samples] [--report]
//                    [--record SCRIPT]
//   --report: Ceres's progress and full report of each model and table's solves.
//   --record SCRIPT: each figure also appended through SCRIPT (bench/record)
//   as BENCHMARK METRIC VALUE.

#include "brdffit.h"
#include "fc_shim.h"
extern "C" {
#include "testutil.h" /* tu_merl_samples: the tables as the benchmark reads them */
}

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

// One block of samples: 3 n residuals over the parameter blocks d[3], s[3],
// theta[nc].
class ChunkCost : public ceres::CostFunction {
  public:
    ChunkCost(const brdffit_samples *set, size_t i0, size_t n, brdffit_model model, int nc)
        : set_(set), i0_(i0), n_(n), model_(model)
    {
        set_num_residuals(static_cast<int>(3 * n));
        mutable_parameter_block_sizes()->push_back(3);
        mutable_parameter_block_sizes()->push_back(3);
        mutable_parameter_block_sizes()->push_back(nc);
    }

    bool Evaluate(double const *const *x, double *r, double **jac) const override
    {
        // Ceres asks for all three blocks' Jacobians or none (none is constant)
        fc_residuals(set_, i0_, n_, model_, x[0], x[1], x[2], r, jac ? jac[0] : nullptr,
                     jac ? jac[1] : nullptr, jac ? jac[2] : nullptr);
        return true;
    }

  private:
    const brdffit_samples *set_;
    size_t i0_, n_;
    brdffit_model model_;
};

// One block of samples of one channel c: n residuals over the parameter
// blocks (d_c, s_c) and theta[nc] (--layout channel).
class ChannelCost : public ceres::CostFunction {
  public:
    ChannelCost(const brdffit_samples *set, size_t i0, size_t n, brdffit_model model, int c, int nc)
        : set_(set), i0_(i0), n_(n), model_(model), c_(c)
    {
        set_num_residuals(static_cast<int>(n));
        mutable_parameter_block_sizes()->push_back(2);
        mutable_parameter_block_sizes()->push_back(nc);
    }

    bool Evaluate(double const *const *x, double *r, double **jac) const override
    {
        fc_residuals_channel(set_, i0_, n_, model_, c_, x[0], x[1], r, jac ? jac[0] : nullptr,
                             jac ? jac[1] : nullptr);
        return true;
    }

  private:
    const brdffit_samples *set_;
    size_t i0_, n_;
    brdffit_model model_;
    int c_;
};

// The time of the first iteration whose Error is within 1% of the target.
class WithinCallback : public ceres::IterationCallback {
  public:
    WithinCallback(double target_e, double pair_see) : target_(target_e), pair_see_(pair_see) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary &it) override
    {
        double e = std::sqrt(std::max(2.0 * it.cost + pair_see_, 0.0));
        if (seconds < 0 && e <= 1.01 * target_) {
            seconds = it.cumulative_time_in_seconds;
            iteration = it.iteration;
        }
        return ceres::SOLVER_CONTINUE;
    }
    double seconds = -1.0;
    int iteration = -1;

  private:
    double target_, pair_see_;
};

struct Args {
    std::vector<std::string> models{ "cook-torrance", "ggx", "ward", "blinn-phong", "ward-duer",
                                     "ashikhmin-shirley", "lafortune" };
    std::vector<std::string> materials{ "alum-bronze", "gold-metallic-paint2", "blue-rubber",
                                        "pickled-oak-260", "nickel" };
    int reps = 3;
    size_t chunk = 16384;
    ceres::LinearSolverType solver = ceres::SPARSE_NORMAL_CHOLESKY;
    bool all_samples = false;
    bool report = false;
    bool channel = true; // --layout channel: (d_c, s_c) blocks, residual blocks per channel
    int bound_search = 0;
    double radius = 1e4; // Ceres's initial_trust_region_radius (its default)
    bool bfgs = false;   // --minimizer bfgs: Ceres's line-search BFGS instead of LM
    const char *record = nullptr;
};

std::vector<std::string> split(const char *list)
{
    std::vector<std::string> out;
    std::stringstream ss(list);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty())
            out.push_back(item);
    return out;
}

int parse(int argc, char **argv, Args &a)
{
    for (int i = 1; i < argc; i++) {
        std::string o = argv[i];
        bool more = i + 1 < argc;
        if (o == "--models" && more)
            a.models = split(argv[++i]);
        else if (o == "--materials" && more)
            a.materials = split(argv[++i]);
        else if (o == "--reps" && more)
            a.reps = std::max(1, std::atoi(argv[++i]));
        else if (o == "--chunk" && more)
            a.chunk = static_cast<size_t>(std::max(64, std::atoi(argv[++i])));
        else if (o == "--solver" && more && ceres::StringToLinearSolverType(argv[i + 1], &a.solver))
            i++;
        else if (o == "--all-samples")
            a.all_samples = true;
        else if (o == "--bound-search" && more)
            a.bound_search = std::max(0, std::atoi(argv[++i]));
        else if (o == "--layout" && more && (!std::strcmp(argv[i + 1], "joint") ||
                                             !std::strcmp(argv[i + 1], "channel")))
            a.channel = !std::strcmp(argv[++i], "channel");
        else if (o == "--radius" && more)
            a.radius = std::atof(argv[++i]);
        else if (o == "--minimizer" && more && (!std::strcmp(argv[i + 1], "lm") ||
                                                !std::strcmp(argv[i + 1], "bfgs")))
            a.bfgs = !std::strcmp(argv[++i], "bfgs");
        else if (o == "--report")
            a.report = true;
        else if (o == "--record" && more)
            a.record = argv[++i];
        else {
            std::fprintf(stderr,
                         "usage: %s [--models a,b] [--materials a,b] [--reps N] [--chunk N]\n"
                         "          [--solver SPARSE_NORMAL_CHOLESKY|DENSE_NORMAL_CHOLESKY|DENSE_QR|DENSE_SCHUR]\n"
                         "          [--layout channel|joint] [--bound-search N] [--radius R]\n"
                         "          [--minimizer lm|bfgs] [--all-samples] [--report] [--record bench/record]\n",
                         argv[0]);
            return 2;
        }
    }
    return 0;
}

void record(const Args &a, const std::string &bench, const char *metric, double value)
{
    if (!a.record)
        return;
    char cmd[1024];
    std::snprintf(cmd, sizeof cmd, "sh '%s' '%s' '%s' %.9g", a.record, bench.c_str(), metric, value);
    if (std::system(cmd) != 0)
        std::fprintf(stderr, "bench-ceres: '%s' failed\n", cmd);
}

double median(std::vector<double> v)
{
    if (v.empty())
        return NAN;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A Ceres fit of one model on one set, built once and solved from the start
// as often as asked.
struct CeresFit {
    brdffit_model model;
    const brdffit_samples *set;
    int nc;
    double theta0[3] = { 0, 0, 0 }, d0[3], s0[3]; // the start
    double theta[3] = { 0, 0, 0 }, d[3], s[3];    // the parameter blocks
    double ds[3][2];                              // (d_c, s_c): --layout channel's
    bool channel = false;
    std::unique_ptr<ceres::Problem> problem;
    ceres::Solver::Options options;

    CeresFit(brdffit_model m, const brdffit_samples *fitted, const Args &a) : model(m), set(fitted)
    {
        double lo[3], hi[3];
        int bounded[3];
        nc = fc_coords(m, lo, hi, bounded);
        ceres::Problem::Options po;
        po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
        problem.reset(new ceres::Problem(po));
        size_t n = fc_count(fitted);
        channel = a.channel;
        for (size_t i0 = 0; i0 < n; i0 += a.chunk) {
            size_t k = std::min(a.chunk, n - i0);
            if (!channel)
                problem->AddResidualBlock(new ChunkCost(fitted, i0, k, m, nc), nullptr, d, s, theta);
            else
                for (int c = 0; c < 3; c++)
                    problem->AddResidualBlock(new ChannelCost(fitted, i0, k, m, c, nc), nullptr,
                                              ds[c], theta);
        }
        for (int c = 0; c < 3 && !a.bfgs; c++) {
            problem->SetParameterLowerBound(channel ? ds[c] : d, channel ? 0 : c, 0.0);
            problem->SetParameterLowerBound(channel ? ds[c] : s, channel ? 1 : c, 0.0);
        }
        for (int j = 0; j < nc; j++)
            if (bounded[j] && !a.bfgs) {
                problem->SetParameterLowerBound(theta, j, lo[j]);
                problem->SetParameterUpperBound(theta, j, hi[j]);
            }
        options.minimizer_type = ceres::TRUST_REGION;
        options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        options.linear_solver_type = a.solver;
        options.num_threads = 2;
        options.jacobi_scaling = true;
        options.function_tolerance = 1e-8;
        options.parameter_tolerance = 1e-8;
        options.gradient_tolerance = 1e-10;
        options.max_num_iterations = 200;
        options.max_num_line_search_step_size_iterations = a.bound_search;
        options.initial_trust_region_radius = a.radius;
        if (a.bfgs) { // no bounds: Ceres's line search takes none
            options.minimizer_type = ceres::LINE_SEARCH;
            options.line_search_direction_type = ceres::BFGS;
            options.max_num_line_search_step_size_iterations = 20;
        }
        options.logging_type = a.report ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
        options.minimizer_progress_to_stdout = a.report;
    }

    void set_start(const double *t, const double *dd, const double *ss)
    {
        std::memcpy(theta0, t, sizeof theta0);
        std::memcpy(d0, dd, sizeof d0);
        std::memcpy(s0, ss, sizeof s0);
    }

    // Solve from the start: wall seconds of ceres::Solve, the seconds to an
    // Error within 1% of target (-1: never), and the summary.
    double solve(double target, double *within, int *within_it, ceres::Solver::Summary *summary)
    {
        std::memcpy(theta, theta0, sizeof theta);
        std::memcpy(d, d0, sizeof d);
        std::memcpy(s, s0, sizeof s);
        for (int c = 0; c < 3; c++)
            ds[c][0] = d0[c], ds[c][1] = s0[c];
        WithinCallback cb(target, fc_pair_see(set));
        ceres::Solver::Options o = options;
        o.callbacks.push_back(&cb);
        double t0 = brdffit_seconds();
        ceres::Solve(o, problem.get(), summary);
        if (summary->termination_type == ceres::FAILURE)
            std::fprintf(stderr, "bench-ceres: Ceres failed: %s\n", summary->message.c_str());
        double t = brdffit_seconds() - t0;
        *within = cb.seconds;
        *within_it = cb.iteration;
        return t;
    }

    brdffit_params params() const
    {
        brdffit_params p;
        std::memset(&p, 0, sizeof p);
        for (int c = 0; c < 3; c++) {
            p.d[c] = channel ? ds[c][0] : d[c];
            p.s[c] = channel ? ds[c][1] : s[c];
        }
        fc_params_of(model, theta, p.p);
        return p;
    }
};

struct Row {
    double fit_s, ceres_s, within_s, fit_e, ceres_e;
    int within_it;
};

} // namespace

int main(int argc, char **argv)
{
    Args a;
    if (parse(argc, argv, a) != 0)
        return 2;
    brdffit_error err;
    brdffit_context *ctx = nullptr;
    if (brdffit_context_create(nullptr, &ctx, &err) != BRDFFIT_OK) {
        std::fprintf(stderr, "bench-ceres: %s\n", err.message);
        return 1;
    }
    std::vector<brdffit_model> models;
    for (const std::string &name : a.models) {
        brdffit_model m;
        if (brdffit_model_from_name(name.c_str(), &m, &err) != BRDFFIT_OK) {
            std::fprintf(stderr, "bench-ceres: %s\n", err.message);
            return 2;
        }
        if (!fc_has_partials(m)) {
            std::fprintf(stderr, "bench-ceres: %s has no analytic partials in kernels/ (not taken)\n",
                         name.c_str());
            return 2;
        }
        models.push_back(m);
    }
    std::printf("brdffit %s against Ceres Solver %s -- %s\n", brdffit_version(), CERES_VERSION_STRING,
                brdffit_context_describe(ctx));
    std::printf("Ceres: LM, %s, analytic Jacobian (kernels/ lobes and partials), %d threads,\n"
                "  ftol = xtol = 1e-8, gtol 1e-10, %zu samples a residual block; %s; the fastest of\n"
                "  %d runs each, alternating with brdffit_fit's (kernels built beforehand)\n\n",
                ceres::LinearSolverTypeToString(a.solver), 2, a.chunk,
                a.all_samples ? "all samples" : "the mirror set (as brdffit's passes)", a.reps);
    std::printf("%-17s %-22s %9s %9s %7s %9s %7s %11s %11s %8s %5s %5s %5s %5s %8s\n", "model",
                "material", "brdffit s", "Ceres s", "ratio", "C to 1% s", "ratio", "brdffit E",
                "Ceres E", "C/b E-1", "match", "LM it", "C it", "1% it", "E check");
    std::vector<std::vector<Row>> rows(models.size());
    int rc = 0;
    for (const std::string &mat : a.materials) {
        brdffit_samples *samples = nullptr;
        if (tu_merl_samples(mat.c_str(), nullptr, &samples, &err) != BRDFFIT_OK) {
            std::fprintf(stderr, "bench-ceres: %s: %s\n", mat.c_str(), err.message);
            rc = 1;
            continue;
        }
        const brdffit_samples *fitted = fc_fitted_set(samples, !a.all_samples);
        for (size_t mi = 0; mi < models.size() && fitted; mi++) {
            brdffit_model m = models[mi];
            const char *name = brdffit_model_get(m)->name;
            if (brdffit_context_prepare(ctx, m, &err) != BRDFFIT_OK ||
                brdffit_samples_prepare(samples, m, &err) != BRDFFIT_OK) {
                std::fprintf(stderr, "bench-ceres: %s\n", err.message);
                rc = 1;
                continue;
            }
            CeresFit cf(m, fitted, a);
            double theta[3] = { 0, 0, 0 }, d[3], s[3];
            if (fc_best_start(ctx, samples, m, theta, d, s) != 0) {
                rc = 1;
                continue;
            }
            cf.set_start(theta, d, s);
            Row row = { INFINITY, INFINITY, INFINITY, 0, 0, -1 };
            brdffit_fit_result best;
            std::memset(&best, 0, sizeof best);
            ceres::Solver::Summary cs;
            bool failed = false;
            for (int rep = 0; rep < a.reps && !failed; rep++) {
                brdffit_fit_result r;
                brdffit_fit_result_init(&r);
                if (brdffit_fit(ctx, samples, m, nullptr, &r, &err) != BRDFFIT_OK) {
                    std::fprintf(stderr, "bench-ceres: %s\n", err.message);
                    failed = true;
                    break;
                }
                if (r.seconds < row.fit_s) {
                    row.fit_s = r.seconds;
                    best = r;
                }
                double within;
                int within_it;
                double t = cf.solve(best.error, &within, &within_it, &cs);
                row.ceres_s = std::min(row.ceres_s, t);
                if (within >= 0 && within < row.within_s) {
                    row.within_s = within;
                    row.within_it = within_it;
                }
            }
            if (failed) {
                rc = 1;
                continue;
            }
            row.fit_e = best.error;
            brdffit_params cp = cf.params();
            if (brdffit_error_of(ctx, samples, m, &cp, &row.ceres_e, &err) != BRDFFIT_OK) {
                std::fprintf(stderr, "bench-ceres: %s (Ceres's parameters)\n", err.message);
                rc = 1;
                continue;
            }
            // the residuals against the library: E from them at brdffit's fit
            double e_res = fc_error(fitted, m, best.params.d, best.params.s, best.params.p);
            double check = std::fabs(e_res - best.error) / best.error;
            bool match = row.ceres_e <= 1.01 * row.fit_e;
            std::printf("%-17s %-22s %9.3f %9.3f %6.1fx %9.3f %6.1fx %11.5e %11.5e %8.1e %5s %5d %5d %5d %8.1e\n",
                        name, mat.c_str(), row.fit_s, row.ceres_s, row.ceres_s / row.fit_s,
                        std::isfinite(row.within_s) ? row.within_s : NAN,
                        row.within_s / row.fit_s, row.fit_e, row.ceres_e,
                        row.ceres_e / row.fit_e - 1.0, match ? "yes" : "NO",
                        best.iterations, static_cast<int>(cs.iterations.size()) - 1, row.within_it,
                        check);
            if (a.report)
                std::printf("%s\n", cs.FullReport().c_str());
            std::fflush(stdout);
            if (check > 1e-9) {
                std::fprintf(stderr, "bench-ceres: the residuals' Error at brdffit's fit differs by %.1e "
                                     "(relative) from the library's\n", check);
                rc = 1;
            }
            rows[mi].push_back(row);
            std::string b = std::string("ceres/") + name + "/" + mat;
            record(a, b, "brdffit-seconds", row.fit_s);
            record(a, b, "ceres-seconds", row.ceres_s);
            record(a, b, "ratio", row.ceres_s / row.fit_s);
            if (std::isfinite(row.within_s))
                record(a, b, "ceres-to-1pct-seconds", row.within_s);
            record(a, b, "brdffit-error", row.fit_e);
            record(a, b, "ceres-error", row.ceres_e);
        }
        brdffit_samples_free(samples);
    }
    std::printf("\nper model: median of (Ceres s / brdffit s) over the tables; Ceres fits matching\n"
                "(final Error within 1%% of brdffit's)\n");
    std::vector<double> all_r, all_w;
    int all_match = 0;
    for (size_t mi = 0; mi < models.size(); mi++) {
        const char *name = brdffit_model_get(models[mi])->name;
        std::vector<double> r, w;
        int match = 0;
        for (const Row &row : rows[mi]) {
            r.push_back(row.ceres_s / row.fit_s);
            if (std::isfinite(row.within_s))
                w.push_back(row.within_s / row.fit_s);
            match += row.ceres_e <= 1.01 * row.fit_e;
        }
        if (r.empty())
            continue;
        all_r.insert(all_r.end(), r.begin(), r.end());
        all_w.insert(all_w.end(), w.begin(), w.end());
        all_match += match;
        std::printf("%-18s Ceres / brdffit: median %.1fx (to 1%%: %.1fx over the %zu that got there), "
                    "%d of %zu matching\n",
                    name, median(r), median(w), w.size(), match, r.size());
        std::string b = std::string("ceres/") + name;
        record(a, b, "ratio-median", median(r));
        if (!w.empty())
            record(a, b, "ratio-to-1pct-median", median(w));
        record(a, b, "matching-count", match);
    }
    if (!all_r.empty()) {
        std::printf("%-18s Ceres / brdffit: median %.1fx (to 1%%: %.1fx over the %zu that got there), "
                    "%d of %zu matching\n",
                    "all fits", median(all_r), median(all_w), all_w.size(), all_match, all_r.size());
        record(a, "ceres/all", "ratio-median", median(all_r));
        if (!all_w.empty())
            record(a, "ceres/all", "ratio-to-1pct-median", median(all_w));
        record(a, "ceres/all", "matching-count", all_match);
    }
    brdffit_context_free(ctx);
    return rc;
}
