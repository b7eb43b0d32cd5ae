/* SPDX-License-Identifier: MIT */
/* test_pass.c -- the OpenCL data pass against the host C loop, device
 * selection, the host fallback, PoCL set-up and kernel build failures. */
#define _POSIX_C_SOURCE 200809L
/* He's pass hit counters (kernels/bf_he_memo.h) count in this file */
#define BF_HE_COUNT_HITS
#include "testutil.h"
#include "context.h"
#include "linear.h"
#include "pass.h"
#include "registry.h"
#include "grid.h"
#include "samples.h"

#include "bf_pass.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static brdffit_samples *load_samples(const char *material)
{
    brdffit_error err;
    brdffit_samples *s = NULL;
    ck_assert_msg(tu_merl_samples(material, NULL, &s, &err) == BRDFFIT_OK, "%s", err.message);
    return s;
}

/* A pass point away from any optimum (so that no sum cancels). */
static void some_point(brdffit_model m, bf_pass_par *pp)
{
    memset(pp, 0, sizeof *pp);
    for (int c = 0; c < 3; c++) {
        pp->d[c] = 0.02 + 0.01 * c;
        pp->s[c] = 0.05 + 0.02 * c;
    }
    pp->lam[0] = 0.645, pp->lam[1] = 0.526, pp->lam[2] = 0.444;
    int np = bf_model_ncoords(m);
    for (int j = 0; j <= np; j++) {
        bf_model_start_params(m, pp->p[j], BF_MAX_NP);
        if (j > 0) {
            int k = bf_model_coord_param(m, j - 1); /* a parameter coordinate j-1 moves */
            pp->p[j][k] *= 1 + 1e-6;
            pp->inv_h[j - 1] = 1e6;
        }
    }
}

/* He at p0 = (tau, sigma0, n), with forward-difference neighbours 1e-7 away. */
static void he_at(bf_pass_par *pp, const double *p0)
{
    some_point(BRDFFIT_HE, pp);
    for (int j = 0; j <= 3; j++) {
        memcpy(pp->p[j], p0, sizeof pp->p[j]);
        if (j > 0) {
            pp->p[j][j - 1] *= 1 + 1e-7;
            pp->inv_h[j - 1] = 1e7;
        }
    }
}

/* He at alum-bronze's own He fit, a smooth point where most samples are
 * flat. */
static void he_at_alum_bronze_fit(bf_pass_par *pp)
{
    const double p0[3] = { 38.97, 0.3836, 1.607 };
    he_at(pp, p0);
}

/* The kernel's sums of an open driver at pp equal the host C loop's to 1e-9
 * relative, both kernels (value only and value + Jacobian). */
static void assert_kernel_equals_host(bf_pass_driver *dr, const bf_pass_par *pp)
{
    brdffit_error err;
    for (int full = 0; full <= 1; full++) {
        int np = full ? dr->np : 0, nmom = bf_nmom(dr->nk, np);
        double k[BF_NMOM_MAX], h[BF_NMOM_MAX];
        ck_assert_msg(bf_driver_run(dr, full, pp, k, &err) == BRDFFIT_OK, "%s", err.message);
        bf_host_loop(dr->samples, &dr->bins, dr->model, dr->nk, np, pp, h);
        for (int i = 0; i < nmom; i++) {
            ck_assert_msg(isfinite(k[i]) && isfinite(h[i]), "moment %d not finite", i);
            ck_assert_msg(tu_reldiff(k[i], h[i]) <= 1e-9, "%s full=%d moment %d: kernel %.17g host %.17g",
                          brdffit_model_get(dr->model)->name, full, i, k[i], h[i]);
        }
        if (!full)
            ck_assert(h[BF_MOM_A] > 0); /* A = sum of the weights: the pass saw the data */
    }
}

/* The kernel's sums equal the host C loop's to 1e-9 relative, every model,
 * both kernels (value only and value + Jacobian). */
/* A model without a lobe K (bf_model_has_lobe: the glTF models) has no data
 * pass: bf_driver_open refuses it on either backend, with the model's name.
 * 1 when m is such a model (its test is then done). */
static int refused_without_lobe(brdffit_model m, const brdffit_samples *s)
{
    if (bf_model_has_lobe(m))
        return 0;
    for (int backend = 0; backend < 2; backend++) {
        brdffit_context *ctx = NULL;
        brdffit_error err;
        ck_assert_msg(tu_context(backend ? BRDFFIT_BACKEND_HOST : BRDFFIT_BACKEND_OPENCL, &ctx, &err)
                          == BRDFFIT_OK, "%s", err.message);
        bf_pass_driver dr;
        ck_assert_int_eq(bf_driver_open(&dr, ctx, s, m, &err), BRDFFIT_E_INVALID_ARGUMENT);
        ck_assert_msg(strstr(err.message, brdffit_model_get(m)->name) && strstr(err.message, "lobe"),
                      "%s", err.message);
        if (backend == 0) {
            cl_kernel full, value;
            ck_assert_int_eq(bf_context_kernels(ctx, m, &full, &value, &err), BRDFFIT_E_INVALID_ARGUMENT);
            ck_assert_int_eq(brdffit_context_prepare(ctx, m, &err), BRDFFIT_OK); /* nothing to build */
        }
        brdffit_context_free(ctx);
    }
    return 1;
}

START_TEST(kernel_equals_host)
{
    brdffit_model m = (brdffit_model)_i;
    brdffit_samples *s = load_samples("gold-metallic-paint");
    if (refused_without_lobe(m, s)) {
        brdffit_samples_free(s);
        return;
    }
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_driver dr;
    ck_assert_msg(bf_driver_open(&dr, ctx, s, m, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_par pp;
    some_point(m, &pp);
    assert_kernel_equals_host(&dr, &pp);
    bf_driver_close(&dr);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* The sum of the metric weights A is 1/3 of ... by construction: 3A = 1. */
START_TEST(weights_normalised)
{
    brdffit_samples *s = load_samples("blue-rubber");
    bf_pass_par pp;
    some_point(BRDFFIT_WARD, &pp);
    double h[BF_NMOM_MAX];
    bf_host_loop(s, NULL, BRDFFIT_WARD, 1, 0, &pp, h);
    /* a2 = w cos^2 / (3 sum w) so 3 A = sum w cos^2 / sum w, in (0, 1] */
    ck_assert(3 * h[BF_MOM_A] > 0.1 && 3 * h[BF_MOM_A] <= 1.0);
    /* the set's own sum of a2 (what the fit scales its secant estimate by) is the pass's A */
    ck_assert_msg(tu_reldiff(s->sum_a2, h[BF_MOM_A]) <= 1e-12, "sum_a2 %.17g, A %.17g", s->sum_a2,
                  h[BF_MOM_A]);
    brdffit_samples_free(s);
}
END_TEST

/* The screening subset (bf_samples_every): every 8th sample of the set with
 * its fields and metric weights, harmless padding, its sum of a2 that of
 * those weights (about an eighth of the set's), and He's value moments over
 * it (host loop, with the memo and the subset's bin rows) equal to the sums
 * of bf_accumulate over those samples of the full set one at a time (no memo,
 * no rows) to 1e-12. */
START_TEST(subset_every_8th)
{
    brdffit_samples *s = load_samples("blue-rubber"), *sub = NULL;
    brdffit_error err;
    ck_assert_msg(bf_samples_every(s, 8, &sub, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_uint_eq(sub->n, (s->n + 7) / 8);
    ck_assert(sub->npad >= sub->n && sub->npad % BF_PAD == 0);
    for (size_t m = 0; m < sub->n; m++) {
        for (int f = 0; f < BF_NFIELDS; f++)
            ck_assert(sub->data[f * sub->npad + m] == s->data[f * s->npad + 8 * m]);
        ck_assert_int_eq(sub->bin[m], s->bin[8 * m]);
    }
    for (size_t m = sub->n; m < sub->npad; m++)
        ck_assert(sub->data[BF_F_A2 * sub->npad + m] == 0.0 && sub->data[BF_F_IZ * sub->npad + m] == 1.0);
    bf_pass_par pp;
    some_point(BRDFFIT_HE, &pp);
    double h[BF_NMOM_MAX], ref[BF_NMOM_MAX] = { 0 };
    int nmom = bf_nmom(3, 0);
    bf_pass_bins bins;
    ck_assert_msg(bf_pass_bins_make(sub, 1, &bins, &err) == BRDFFIT_OK, "%s", err.message);
    bf_host_loop(sub, &bins, BRDFFIT_HE, 3, 0, &pp, h);
    bf_pass_bins_free(&bins);
    for (size_t i = 0; i < s->n; i += 8)
        bf_host_sample(s, NULL, i, BRDFFIT_HE, 3, 0, &pp, ref, NULL);
    for (int i = 0; i < nmom; i++)
        ck_assert_msg(tu_reldiff(h[i], ref[i]) <= 1e-12, "moment %d: subset %.17g samples %.17g", i,
                      h[i], ref[i]);
    ck_assert_msg(tu_reldiff(sub->sum_a2, ref[BF_MOM_A]) <= 1e-12, "subset sum_a2 %.17g, A %.17g",
                  sub->sum_a2, ref[BF_MOM_A]);
    ck_assert(sub->sum_a2 > 0.1 * s->sum_a2 && sub->sum_a2 < 0.15 * s->sum_a2);
    brdffit_samples_free(sub);
    brdffit_samples_free(s);
}
END_TEST

/* The bin subset (bf_samples_bins): exactly the samples whose theta_h,
 * theta_d and phi_d indices are on the steps, in table order, with their
 * fields and metric weights, harmless padding, and its sum of a2 theirs;
 * for He's screening steps, a few others, and every sample (all 1). */
static const int bins_steps[][3] = { { 2, 3, 6 }, { 3, 3, 12 }, { 1, 1, 1 }, { 5, 1, 7 } };

START_TEST(subset_of_bins)
{
    brdffit_samples *s = load_samples("blue-rubber"), *sub = NULL;
    brdffit_error err;
    const int *step = bins_steps[_i];
    ck_assert_msg(bf_samples_bins(s, step, &sub, &err) == BRDFFIT_OK, "%s", err.message);
    size_t m = 0;
    double a2 = 0.0;
    for (size_t i = 0; i < s->n; i++) {
        int h, j, k; /* theta_h, theta_d, phi_d */
        bf_bin_ijk((size_t)s->bin[i], &h, &j, &k);
        if (h % step[0] || j % step[1] || k % step[2])
            continue;
        ck_assert_uint_lt(m, sub->n);
        ck_assert_int_eq(sub->bin[m], s->bin[i]);
        for (int f = 0; f < BF_NFIELDS; f++)
            ck_assert(sub->data[f * sub->npad + m] == s->data[f * s->npad + i]);
        a2 += s->data[BF_F_A2 * s->npad + i];
        m++;
    }
    ck_assert_uint_eq(sub->n, m);
    const double share = 1.0 / (step[0] * step[1] * step[2]); /* of the samples, roughly */
    ck_assert_msg(m > 0.75 * share * (double)s->n && m < 1.25 * share * (double)s->n,
                  "%zu of %zu samples on steps %d %d %d", m, s->n, step[0], step[1], step[2]);
    for (size_t q = sub->n; q < sub->npad; q++)
        ck_assert(sub->data[BF_F_A2 * sub->npad + q] == 0.0 && sub->data[BF_F_IZ * sub->npad + q] == 1.0);
    ck_assert_msg(tu_reldiff(sub->sum_a2, a2) <= 1e-12, "sum_a2 %.17g, its samples' %.17g", sub->sum_a2, a2);
    brdffit_samples_free(sub);
    brdffit_samples_free(s);
}
END_TEST

/* A MERL table's sample set whose pairs of mirror bins (i, j, k) and
 * (i, j, 180 - k) differ (each value times 1 + up to 20%, a hash of its bin
 * and channel) and every 7th bin masked, so that some samples' partners are
 * missing. */
static brdffit_samples *mirror_test_samples(const char *material)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    ck_assert_msg(tu_merl_read(material, &t, &err) == BRDFFIT_OK, "%s", err.message);
    double *v = brdffit_table_values(t);
    for (size_t b = 0; b < BF_NBINS; b++)
        for (int c = 0; c < 3; c++) {
            double *x = &v[(size_t)c * BF_NBINS + b];
            unsigned h = (unsigned)(b * 2654435761u) ^ (unsigned)(c * 40503u);
            h ^= h >> 15;
            *x = b % 7 == 0 ? -1.0 : *x >= 0.0 ? *x * (1.0 + 0.2 * (h % 1000) / 1000.0) : *x;
        }
    brdffit_samples *s = NULL;
    ck_assert_msg(brdffit_samples_create(t, NULL, &s, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
    return s;
}

/* The mirror set (bf_samples_mirror): every sample at k <= 90 and every one
 * at k > 90 whose partner 180 - k is not in the set, in table order, each at
 * its own directions; a merged sample's weight the pair's sum and its value
 * their weighted mean; the set's sums of the weights; and what the pairs
 * hold beyond their merged values (pair_see) their sum of
 * a2_1 a2_2 (rho_1 - rho_2)^2 / (a2_1 + a2_2), counted here sample by sample. */
START_TEST(mirror_set_merges_pairs)
{
    brdffit_samples *s = mirror_test_samples("blue-rubber"), *m = NULL;
    brdffit_error err;
    ck_assert_msg(bf_samples_mirror(s, &m, &err) == BRDFFIT_OK, "%s", err.message);
    long *at = malloc(BF_NBINS * sizeof *at);
    ck_assert_ptr_nonnull(at);
    for (size_t b = 0; b < BF_NBINS; b++)
        at[b] = -1;
    for (size_t i = 0; i < s->n; i++)
        at[s->bin[i]] = (long)i;
    size_t q = 0, pairs = 0;
    double see[3] = { 0 }, a2sum = 0.0;
    for (size_t i = 0; i < s->n; i++) {
        int h, j, k;
        bf_bin_ijk((size_t)s->bin[i], &h, &j, &k);
        long p = k == 0 || k == 90 ? -1 : at[s->bin[i] - k + (180 - k)];
        if (k > 90 && p >= 0)
            continue; /* merged into its partner */
        ck_assert_uint_lt(q, m->n);
        ck_assert_int_eq(m->bin[q], s->bin[i]);
        for (int f = BF_F_IX; f <= BF_F_VH; f++)
            ck_assert(m->data[f * m->npad + q] == s->data[f * s->npad + i]);
        const double a1 = s->data[BF_F_A2 * s->npad + i];
        const double a2 = p >= 0 ? s->data[BF_F_A2 * s->npad + p] : 0.0;
        ck_assert(m->data[BF_F_A2 * m->npad + q] == a1 + a2);
        for (int c = 0; c < 3; c++) {
            const double r1 = s->data[(BF_F_R + c) * s->npad + i];
            const double r2 = p >= 0 ? s->data[(BF_F_R + c) * s->npad + p] : 0.0;
            ck_assert(tu_reldiff(m->data[(BF_F_R + c) * m->npad + q], (a1 * r1 + a2 * r2) / (a1 + a2)) <= 1e-15);
            see[c] += a1 * a2 * (r1 - r2) * (r1 - r2) / (a1 + a2);
        }
        a2sum += a1 + a2;
        pairs += p >= 0;
        q++;
    }
    ck_assert_uint_eq(m->n, q);
    ck_assert_uint_eq(m->n + pairs, s->n);
    ck_assert_msg(pairs > 0.4 * (double)s->n && m->n < 0.6 * (double)s->n, "%zu pairs of %zu samples",
                  pairs, s->n);
    ck_assert_msg(pairs < s->n / 2, "every sample paired: the masked bins left none alone");
    for (int c = 0; c < 3; c++)
        ck_assert_msg(see[c] > 0.0 && tu_reldiff(m->pair_see[c], see[c]) <= 1e-12,
                      "channel %d: pair_see %.17g, counted %.17g", c, m->pair_see[c], see[c]);
    ck_assert(tu_reldiff(a2sum, s->sum_a2) <= 1e-12 && m->sum_a2 == s->sum_a2);
    ck_assert(s->pair_see[0] == 0.0 && s->pair_see[1] == 0.0 && s->pair_see[2] == 0.0);
    for (size_t r = m->n; r < m->npad; r++)
        ck_assert(m->data[BF_F_A2 * m->npad + r] == 0.0);
    free(at);
    brdffit_samples_free(m);
    brdffit_samples_free(s);
}
END_TEST

/* A pass over the mirror set (bf_driver_run, which adds pair_see) gives the
 * set's own sums, by the host C loop over the set itself, to 1e-9 relative:
 * every model, value and full passes, both backends.  The pairs' values
 * differ, so pair_see is a share of sum a2 e^2 that the check would see
 * missing. */
START_TEST(mirror_sums_are_the_sets)
{
    brdffit_model model = (brdffit_model)_i;
    brdffit_samples *s = mirror_test_samples("gold-metallic-paint");
    if (refused_without_lobe(model, s)) {
        brdffit_samples_free(s);
        return;
    }
    const brdffit_samples *m = NULL;
    brdffit_error err;
    ck_assert_msg(bf_samples_mirror_kept(s, &m, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_par pp;
    some_point(model, &pp);
    for (int backend = 0; backend < 2; backend++) {
        brdffit_context *ctx = NULL;
        ck_assert_msg(tu_context(backend ? BRDFFIT_BACKEND_HOST : BRDFFIT_BACKEND_OPENCL, &ctx, &err)
                          == BRDFFIT_OK, "%s", err.message);
        bf_pass_driver dr;
        ck_assert_msg(bf_driver_open(&dr, ctx, m, model, &err) == BRDFFIT_OK, "%s", err.message);
        bf_pass_bins bins;
        ck_assert_msg(bf_pass_bins_make(s, 1, &bins, &err) == BRDFFIT_OK, "%s", err.message);
        for (int full = 0; full <= 1; full++) {
            int np = full ? dr.np : 0, nmom = bf_nmom(dr.nk, np);
            double k[BF_NMOM_MAX], h[BF_NMOM_MAX];
            ck_assert_msg(bf_driver_run(&dr, full, &pp, k, &err) == BRDFFIT_OK, "%s", err.message);
            bf_host_loop(s, bf_lobe_has_own_fd((int)model) ? &bins : NULL, model, dr.nk, np, &pp, h);
            for (int i = 0; i < nmom; i++)
                ck_assert_msg(tu_reldiff(k[i], h[i]) <= 1e-9, "%s backend %d full=%d moment %d: mirror %.17g set %.17g",
                              brdffit_model_get(model)->name, backend, full, i, k[i], h[i]);
            const double see = h[bf_mom_chan(0, dr.nk, np) + BF_MC_SEE];
            ck_assert_msg(m->pair_see[0] > 1e-6 * see, "pair_see %.3g of %.3g", m->pair_see[0], see);
        }
        bf_pass_bins_free(&bins);
        bf_driver_close(&dr);
        brdffit_context_free(ctx);
    }
    brdffit_samples_free(s);
}
END_TEST

/* He's full pass with the pass state (its memos, its bin rows and bf_fold,
 * which sums the vectors a bin's row serves once per bin) against
 * bf_accumulate sample by sample with none: every moment within 1e-8
 * relative (the forward differences' K(p_j) - K(p_0) cancel to ~1e-7 of K,
 * so either path's rounding of K, ~1e-16, shows at ~1e-9 in the moments of
 * G: measured up to 1.6e-9), at a smooth point where the rows serve most
 * samples (_i = 0: alum-bronze's fit) and at He's typical start (_i = 1,
 * tau = 16, sigma0 = 0.5), where the rows serve the lanes a little rougher
 * than flat with ln K carried to their g (bf_he_near_serve: at least 15% of
 * the samples, measured 19%). */
/* bf_host_sample (src/lib/pass_host.c) compiled here, where He's hit
 * counters count (BF_HE_COUNT_HITS; the library is built without them). */
static void counted_sample(const brdffit_samples *s, const bf_pass_bins *bins, size_t i, int np,
                           const bf_pass_par *pp, double *mom, bf_pass_state *ps)
{
    const size_t npad = s->npad;
    const double *f = s->data;
    bf_geom g = { f[BF_F_IX * npad + i], f[BF_F_IY * npad + i], f[BF_F_IZ * npad + i],
                  f[BF_F_OX * npad + i], f[BF_F_OY * npad + i], f[BF_F_OZ * npad + i],
                  f[BF_F_NH * npad + i], f[BF_F_VH * npad + i] };
    double rho[3] = { f[BF_F_R * npad + i], f[BF_F_G * npad + i], f[BF_F_B * npad + i] };
    bf_lobe_bins(&ps->lobe, bins->hd[i]);
    bf_accumulate(BRDFFIT_HE, 3, np, pp, &g, rho, f[BF_F_A2 * npad + i], mom, ps);
}

START_TEST(fold_equals_plain)
{
    brdffit_samples *s = load_samples("alum-bronze");
    bf_pass_par pp;
    const double start[3] = { 16.0, 0.5, 2.0 };
    if (_i == 1)
        he_at(&pp, start);
    else
        he_at_alum_bronze_fit(&pp);
    const int np = 3, nmom = bf_nmom(3, np);
    double fold[BF_NMOM_MAX] = { 0 }, plain[BF_NMOM_MAX] = { 0 };
    bf_pass_state ps;
    bf_pass_bins bins;
    brdffit_error err;
    ck_assert_msg(bf_pass_bins_make(s, 1, &bins, &err) == BRDFFIT_OK, "%s", err.message);
    bf_host_begin(s, &bins, BRDFFIT_HE, np, &pp, &ps);
    for (size_t i = 0; i < s->n; i++) {
        counted_sample(s, &bins, i, np, &pp, fold, &ps);
        bf_host_sample(s, NULL, i, BRDFFIT_HE, 3, np, &pp, plain, NULL);
    }
    bf_accumulate_end(3, np, &pp, fold, &ps);
    bf_pass_bins_free(&bins);
    for (int i = 0; i < nmom; i++)
        ck_assert_msg(tu_reldiff(fold[i], plain[i]) <= 1e-8, "point %d moment %d: fold %.17g plain %.17g",
                      _i, i, fold[i], plain[i]);
    if (_i == 0)
        ck_assert_msg(ps.lobe.he.bhits >= 0.5 * (double)s->n, "the fold summed %g of %zu samples",
                      ps.lobe.he.bhits, s->n);
    else
        ck_assert_msg(ps.lobe.he.nhits >= 0.15 * (double)s->n, "the rows carried %g of %zu samples",
                      ps.lobe.he.nhits, s->n);
    brdffit_samples_free(s);
}
END_TEST

/* He's kernel pass on the refinement's stride subset (every 12th sample) at
 * a smooth fit, where most vectors are flat and their lanes lie in two bins
 * (served by a select between two bins' rows) or in more (a gather), equals
 * the host C loop's, which takes each sample's row alone, to 1e-9 relative,
 * value and full passes; the subset has vectors of both kinds. */
START_TEST(kernel_equals_host_on_stride_subset)
{
    brdffit_samples *s = load_samples("alum-bronze"), *sub = NULL;
    brdffit_error err;
    ck_assert_msg(bf_samples_every(s, 12, &sub, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    const size_t w = (size_t)ctx->width; /* the kernel's lanes a vector */
    long two = 0, more = 0;
    for (size_t v = 0; v + w <= sub->n; v += w) {
        int distinct = 1; /* a vector's samples are consecutive: count the changes of bin */
        for (size_t l = 1; l < w; l++)
            distinct += sub->bin[v + l] / 180 != sub->bin[v + l - 1] / 180;
        two += distinct == 2;
        more += distinct > 2;
    }
    ck_assert_msg(two > 0 && more > 0, "vectors of two bins %ld, of more %ld", two, more);
    bf_pass_driver dr;
    ck_assert_msg(bf_driver_open(&dr, ctx, sub, BRDFFIT_HE, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_par pp;
    he_at_alum_bronze_fit(&pp);
    assert_kernel_equals_host(&dr, &pp);
    bf_driver_close(&dr);
    brdffit_context_free(ctx);
    brdffit_samples_free(sub);
    brdffit_samples_free(s);
}
END_TEST

/* The samples of s in bins that a He pass at pp sums whole from the bin
 * table (bf_he_bin_whole: every sample flat for certain, one run). */
static size_t samples_in_whole_bins(const brdffit_samples *s, const bf_pass_bins *bins,
                                    const bf_pass_par *pp)
{
    const double cot_sure = bf_he_cot_sure(pp->p[0][0], pp->p[0][1]);
    size_t n = 0;
    for (size_t i = 0; i < s->n; i++) {
        const int h = (int)bins->hd[i];
        n += bins->table[BF_B_START1 * BF_NHD_PAD + h] > 0.0
             && bins->table[BF_B_COTLO * BF_NHD_PAD + h] >= cot_sure
             && bins->table[BF_B_COTW * BF_NHD_PAD + h] == bins->table[BF_B_COTLO * BF_NHD_PAD + h];
    }
    return n;
}

/* He's sums at pp sample by sample, with no memo, rows or bin sums. */
static void he_plain_sums(const brdffit_samples *s, int np, const bf_pass_par *pp, double *mom)
{
    for (int m = 0; m < BF_NMOM_MAX; m++)
        mom[m] = 0.0;
    for (size_t i = 0; i < s->n; i++)
        bf_host_sample(s, NULL, i, BRDFFIT_HE, 3, np, pp, mom, NULL);
}

/* He's pass sums the bins whose samples are all flat from the bin table's
 * sums (bf_pass_whole_bins) instead of their samples; the host loop and the kernel
 * then equal the sums sample by sample with no rows to 1e-8 relative (as
 * fold_equals_plain), value and full passes, on a set, on its mirror set
 * (the fits' passes) and on He's screening subset (every 3rd theta_h and
 * theta_d: a work-item's bins far apart), at alum-bronze's fit, where most
 * samples lie in such bins. */
START_TEST(whole_bins_equal_plain)
{
    brdffit_samples *s = load_samples("alum-bronze");
    const brdffit_samples *set = s;
    brdffit_error err;
    static const int screen_bins[3] = { 3, 3, 12 }; /* He's screening subset: sparse bins */
    if (_i == 1)
        ck_assert_msg(bf_samples_mirror_kept(s, &set, &err) == BRDFFIT_OK, "%s", err.message);
    if (_i == 2)
        ck_assert_msg(bf_samples_bins_kept(s, screen_bins, &set, &err) == BRDFFIT_OK, "%s",
                      err.message);
    bf_pass_par pp;
    he_at_alum_bronze_fit(&pp);
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_driver dr;
    ck_assert_msg(bf_driver_open(&dr, ctx, set, BRDFFIT_HE, &err) == BRDFFIT_OK, "%s", err.message);
    size_t whole = samples_in_whole_bins(set, &dr.bins, &pp);
    ck_assert_msg(whole >= set->n / 2, "%zu of %zu samples in whole bins", whole, set->n);
    for (int full = 0; full <= 1; full++) {
        const int np = full ? 3 : 0, nmom = bf_nmom(3, np);
        double plain[BF_NMOM_MAX], host[BF_NMOM_MAX], kern[BF_NMOM_MAX];
        he_plain_sums(set, np, &pp, plain);
        bf_host_loop(set, &dr.bins, BRDFFIT_HE, 3, np, &pp, host);
        ck_assert_msg(bf_driver_run(&dr, full, &pp, kern, &err) == BRDFFIT_OK, "%s", err.message);
        for (int c = 0; c < 3; c++) /* the driver adds the mirror set's pair_see */
            kern[bf_mom_chan(c, 3, np) + BF_MC_SEE] -= set->pair_see[c];
        for (int i = 0; i < nmom; i++) {
            ck_assert_msg(tu_reldiff(host[i], plain[i]) <= 1e-8, "set %d full %d moment %d: host %.17g plain %.17g",
                          _i, full, i, host[i], plain[i]);
            ck_assert_msg(tu_reldiff(kern[i], plain[i]) <= 1e-8, "set %d full %d moment %d: kernel %.17g plain %.17g",
                          _i, full, i, kern[i], plain[i]);
        }
    }
    bf_driver_close(&dr);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* A set whose values are He's own at pp (rho = d / pi + s K, K sample by
 * sample): the pass's sum of a^2 e^2 stays at the rounding of the residuals
 * (below 1e-20 of the sum of a^2 rho^2 in every channel, host loop and
 * kernel), as the bin sums take e about each bin's line of its values.
 * Summed from the raw sums of a^2 rho^2, a^2 rho and a^2 rho q instead,
 * it would keep the rounding of those, ~1e-16 of them. */
START_TEST(whole_bins_keep_close_residuals)
{
    brdffit_samples *s = load_samples("alum-bronze");
    bf_pass_par pp;
    he_at_alum_bronze_fit(&pp);
    double *F = s->data, srr[3] = { 0.0, 0.0, 0.0 };
    for (size_t i = 0; i < s->n; i++) {
        const size_t np = s->npad;
        bf_geom g = { F[BF_F_IX * np + i], F[BF_F_IY * np + i], F[BF_F_IZ * np + i],
                      F[BF_F_OX * np + i], F[BF_F_OY * np + i], F[BF_F_OZ * np + i],
                      F[BF_F_NH * np + i], F[BF_F_VH * np + i] };
        double K[3];
        bf_lobe_fd(BRDFFIT_HE, &g, pp.p, 0, pp.lam, K, NULL, NULL);
        for (int c = 0; c < 3; c++) {
            const double rho = pp.d[c] * (1.0 / BF_PI) + pp.s[c] * K[c];
            F[(BF_F_R + c) * np + i] = rho;
            srr[c] += F[BF_F_A2 * np + i] * rho * rho;
        }
    }
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_driver dr; /* its bin table made now, from the values above */
    ck_assert_msg(bf_driver_open(&dr, ctx, s, BRDFFIT_HE, &err) == BRDFFIT_OK, "%s", err.message);
    size_t whole = samples_in_whole_bins(s, &dr.bins, &pp);
    ck_assert_msg(whole >= s->n / 2, "%zu of %zu samples in whole bins", whole, s->n);
    double host[BF_NMOM_MAX], kern[BF_NMOM_MAX];
    bf_host_loop(s, &dr.bins, BRDFFIT_HE, 3, 0, &pp, host);
    ck_assert_msg(bf_driver_run(&dr, 0, &pp, kern, &err) == BRDFFIT_OK, "%s", err.message);
    for (int c = 0; c < 3; c++) {
        const int see = bf_mom_chan(c, 3, 0) + BF_MC_SEE;
        ck_assert_msg(srr[c] > 0.0 && fabs(host[see]) <= 1e-20 * srr[c], "channel %d: host see %.3g of %.3g",
                      c, host[see], srr[c]);
        ck_assert_msg(fabs(kern[see]) <= 1e-20 * srr[c], "channel %d: kernel see %.3g of %.3g", c,
                      kern[see], srr[c]);
    }
    bf_driver_close(&dr);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* A set out of table order (the first sample of a bin moved past the next
 * bin's: that bin is then two runs) has no bin summed whole: every bin's
 * START1 is 0 and its COTW -1, though the moved sample's bin and the next
 * are flat enough, and the host loop's sums equal those sample by sample to
 * 1e-8 relative. */
START_TEST(unordered_set_summed_by_samples)
{
    brdffit_samples *s = load_samples("alum-bronze"), *t = NULL;
    size_t *idx = malloc(s->n * sizeof *idx), f = s->n / 2, e, e2, n = 0;
    ck_assert_ptr_nonnull(idx);
    const int h = s->bin[f] / 180;
    while (f > 0 && s->bin[f - 1] / 180 == h) /* the first sample of bin h */
        f--;
    for (e = f; e < s->n && s->bin[e] / 180 == h; e++) /* its end, and the next bin's */
        ;
    for (e2 = e; e2 < s->n && s->bin[e2] / 180 == s->bin[e] / 180; e2++)
        ;
    ck_assert(e - f > 1 && e2 > e && e2 < s->n);
    for (size_t i = 0; i < s->n; i++) {
        if (i != f)
            idx[n++] = i;
        if (i + 1 == e2)
            idx[n++] = f;
    }
    brdffit_error err;
    ck_assert_msg(bf_samples_take(s, idx, n, &t, &err) == BRDFFIT_OK, "%s", err.message);
    bf_pass_bins bins;
    ck_assert_msg(bf_pass_bins_make(t, 1, &bins, &err) == BRDFFIT_OK, "%s", err.message);
    const int h2 = s->bin[e] / 180;
    for (int b = 0; b < BF_NHD; b++)
        ck_assert(bins.table[BF_B_START1 * BF_NHD_PAD + b] == 0.0
                  && bins.table[BF_B_COTW * BF_NHD_PAD + b] < 0.0);
    bf_pass_par pp;
    he_at_alum_bronze_fit(&pp);
    const double cot_sure = bf_he_cot_sure(pp.p[0][0], pp.p[0][1]);
    ck_assert(bins.table[BF_B_COTLO * BF_NHD_PAD + h] >= cot_sure); /* they would have been */
    ck_assert(bins.table[BF_B_COTLO * BF_NHD_PAD + h2] >= cot_sure);
    double plain[BF_NMOM_MAX], host[BF_NMOM_MAX];
    he_plain_sums(t, 3, &pp, plain);
    bf_host_loop(t, &bins, BRDFFIT_HE, 3, 3, &pp, host);
    for (int i = 0; i < bf_nmom(3, 3); i++)
        ck_assert_msg(tu_reldiff(host[i], plain[i]) <= 1e-8, "moment %d: host %.17g plain %.17g", i,
                      host[i], plain[i]);
    bf_pass_bins_free(&bins);
    brdffit_samples_free(t);
    free(idx);
    brdffit_samples_free(s);
}
END_TEST

/* One sample's terms added to mom, each named moment from its definition
 * (bf_pass.h's header comment): the oracle of neighbour_sums and
 * pairs_sum_as_ones. */
static void moments_by_name(int nk, int np, const bf_pass_par *pp, double a2, const double *K0,
                            double (*G)[BF_MAX_NP], const double *rho, double *mom)
{
    mom[BF_MOM_A] += a2;
    for (int k = 0; k < nk; k++) {
        double *m = mom + bf_mom_lobe(k, np);
        m[BF_MK_SK] += a2 * K0[k];
        m[BF_MK_SKK] += a2 * K0[k] * K0[k];
        for (int j = 0; j < np; j++) {
            m[bf_mk_sg(j)] += a2 * G[k][j];
            m[bf_mk_skg(np, j)] += a2 * K0[k] * G[k][j];
            for (int l = j; l < np; l++)
                m[bf_mk_sgg(np, j, l)] += a2 * G[k][j] * G[k][l];
        }
    }
    for (int c = 0; c < 3; c++) {
        int k = nk > 1 ? c : 0;
        double e = rho[c] - pp->d[c] / BF_PI - pp->s[c] * K0[k], *m = mom + bf_mom_chan(c, nk, np);
        m[BF_MC_SE] += a2 * e;
        m[BF_MC_SKE] += a2 * e * K0[k];
        m[BF_MC_SEE] += a2 * e * e;
        for (int j = 0; j < np; j++)
            m[bf_mc_sge(j)] += a2 * e * G[k][j];
    }
}

/* Model m's sums at pp sample by sample, each moment written out here
 * (moments_by_name) from bf_lobe_fd's K(p_0) and neighbours K(p_j), G_j =
 * (K(p_j) - K(p_0)) / h_j: the forward differences as a pass of a lobe
 * without partials takes them (one lobe, nk = 1). */
static void neighbour_sums(const brdffit_samples *s, brdffit_model m, int np, const bf_pass_par *pp,
                           double *mom)
{
    const size_t P = s->npad;
    for (int i = 0; i < BF_NMOM_MAX; i++)
        mom[i] = 0.0;
    for (size_t i = 0; i < s->n; i++) {
        const double *f = s->data + i;
        bf_geom g = { f[BF_F_IX * P], f[BF_F_IY * P], f[BF_F_IZ * P], f[BF_F_OX * P],
                      f[BF_F_OY * P], f[BF_F_OZ * P], f[BF_F_NH * P], f[BF_F_VH * P] };
        const double a2 = f[BF_F_A2 * P], rho[3] = { f[BF_F_R * P], f[BF_F_G * P], f[BF_F_B * P] };
        double K0[3], Kj[BF_MAX_NP][3], G[3][BF_MAX_NP];
        bf_lobe_fd((int)m, &g, pp->p, np, pp->lam, K0, Kj, NULL);
        for (int j = 0; j < np; j++)
            G[0][j] = (Kj[j][0] - K0[0]) * pp->inv_h[j];
        moments_by_name(1, np, pp, a2, K0, G, rho, mom);
    }
}

/* A full pass of a lobe with partials takes G_j from them,
 * dK . (p_j - p_0) / h_j (bf_pass_partials), not from its neighbours; its
 * sums, host loop and kernel, equal those taken from the neighbours
 * (neighbour_sums) to 1e-8 relative: the difference quotient rounds at
 * ~1e-16 K / h ~ 1e-10 of G at some_point's h = 1e-6.  Every model with
 * partials (bf_lobe_fd_kind), on every 8th sample of gold-metallic-paint. */
START_TEST(partials_equal_neighbours)
{
    brdffit_samples *s = load_samples("gold-metallic-paint"), *sub = NULL;
    brdffit_error err;
    ck_assert_msg(bf_samples_every(s, 8, &sub, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    int models = 0;
    for (int mi = 0; mi < brdffit_model_count(); mi++) {
        const brdffit_model m = (brdffit_model)mi;
        if (bf_lobe_fd_kind(mi) != BF_FD_KIND_PARTIALS)
            continue;
        models++;
        bf_pass_par pp;
        some_point(m, &pp);
        bf_pass_driver dr;
        ck_assert_msg(bf_driver_open(&dr, ctx, sub, m, &err) == BRDFFIT_OK, "%s", err.message);
        const int np = dr.np, nmom = bf_nmom(1, np);
        ck_assert_int_eq(dr.nk, 1);
        ck_assert_int_ge(np, 1);
        double want[BF_NMOM_MAX], host[BF_NMOM_MAX], kern[BF_NMOM_MAX];
        neighbour_sums(sub, m, np, &pp, want);
        bf_host_loop(sub, &dr.bins, m, 1, np, &pp, host);
        ck_assert_msg(bf_driver_run(&dr, 1, &pp, kern, &err) == BRDFFIT_OK, "%s", err.message);
        for (int i = 0; i < nmom; i++) {
            ck_assert_msg(tu_reldiff(host[i], want[i]) <= 1e-8, "%s moment %d: host %.17g neighbours %.17g",
                          brdffit_model_get(m)->name, i, host[i], want[i]);
            ck_assert_msg(tu_reldiff(kern[i], want[i]) <= 1e-8, "%s moment %d: kernel %.17g neighbours %.17g",
                          brdffit_model_get(m)->name, i, kern[i], want[i]);
        }
        bf_driver_close(&dr);
    }
    int want = 0; /* every model with a lobe but He (its own derivatives) */
    for (int m = 0; m < brdffit_model_count(); m++)
        want += bf_model_has_lobe((brdffit_model)m) && bf_lobe_fd_kind(m) != BF_FD_KIND_OWN;
    ck_assert_int_eq(want, BRDFFIT_MODEL_COUNT - 4); /* not He, gltf, gltf-ext, openpbr */
    ck_assert_int_eq(models, want);
    brdffit_context_free(ctx);
    brdffit_samples_free(sub);
    brdffit_samples_free(s);
}
END_TEST

/* The named moment offsets of kernels/bf_layout.h (used by the kernel, the
 * host loop and the fit alike) tile [0, bf_nmom(nk, np)) exactly: every
 * moment has one name and no two names share a slot, for every nk and np. */
START_TEST(moment_layout)
{
    for (int nk = 1; nk <= 3; nk += 2)
        for (int np = 0; np <= BF_MAX_NP; np++) {
            int nmom = bf_nmom(nk, np), seen[BF_NMOM_MAX];
            ck_assert_int_le(nmom, BF_NMOM_MAX);
            memset(seen, 0, sizeof seen);
            seen[BF_MOM_A]++;
            for (int k = 0; k < nk; k++) {
                int b = bf_mom_lobe(k, np);
                seen[b + BF_MK_SK]++;
                seen[b + BF_MK_SKK]++;
                for (int j = 0; j < np; j++) {
                    seen[b + bf_mk_sg(j)]++;
                    seen[b + bf_mk_skg(np, j)]++;
                    for (int l = j; l < np; l++)
                        seen[b + bf_mk_sgg(np, j, l)]++;
                }
                ck_assert_int_le(bf_mk_sgg(np, np - 1, np - 1), bf_kblk(np) - 1);
            }
            for (int c = 0; c < 3; c++) {
                int b = bf_mom_chan(c, nk, np);
                seen[b + BF_MC_SE]++;
                seen[b + BF_MC_SKE]++;
                seen[b + BF_MC_SEE]++;
                for (int j = 0; j < np; j++)
                    seen[b + bf_mc_sge(j)]++;
            }
            for (int m = 0; m < BF_NMOM_MAX; m++)
                ck_assert_msg(seen[m] == (m < nmom), "nk %d np %d: moment %d named %d times", nk,
                              np, m, seen[m]);
        }
    ck_assert_int_eq(bf_nmom(3, BF_MAX_NP), BF_NMOM_MAX);
}
END_TEST

/* tu_env_put puts back a changed, a newly set and an unset variable. */
static void expect_env(const char *name, const char *want)
{
    const char *v = getenv(name);
    if (want)
        ck_assert_msg(v && strcmp(v, want) == 0, "%s = %s, expected %s", name, v ? v : "(unset)", want);
    else
        ck_assert_msg(v == NULL, "%s = %s, expected it unset", name, v);
}

START_TEST(env_restored)
{
    static const char *const names[] = { "HOME", "OCL_ICD_VENDORS", "BRDFFIT_DEVICE" };
    char *before[3];
    for (int i = 0; i < 3; i++)
        before[i] = getenv(names[i]) ? strdup(getenv(names[i])) : NULL;
    tu_env e;
    tu_env_get(&e);
    setenv("HOME", "/nonexistent-home", 1);
    setenv("OCL_ICD_VENDORS", "/nonexistent-vendors", 1);
    unsetenv("BRDFFIT_DEVICE");
    setenv("BRDFFIT_DEVICE", "9:9", 1);
    tu_env_put(&e);
    for (int i = 0; i < 3; i++) {
        expect_env(names[i], before[i]);
        free(before[i]);
    }
    /* and an unset one comes back unset */
    unsetenv("BRDFFIT_CL_OPTIONS");
    tu_env_get(&e);
    setenv("BRDFFIT_CL_OPTIONS", "-DX=1", 1);
    tu_env_put(&e);
    expect_env("BRDFFIT_CL_OPTIONS", NULL);
}
END_TEST

START_TEST(device_selection)
{
    brdffit_error err;
    brdffit_context *ctx = NULL;
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    /* default: the first PoCL CPU device */
    ck_assert_msg(brdffit_context_create(&co, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_int_eq(brdffit_context_backend(ctx), BRDFFIT_BACKEND_OPENCL);
    ck_assert_ptr_nonnull(strstr(brdffit_context_describe(ctx), "opencl"));
    brdffit_context_free(ctx);
    /* by index and by name */
    co.device = "0:0";
    ck_assert_msg(brdffit_context_create(&co, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_context_free(ctx);
    co.device = "Portable Computing Language";
    ck_assert_msg(brdffit_context_create(&co, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_context_free(ctx);
    /* no such device: OPENCL fails with NO_DEVICE, AUTO falls back to the host and says why */
    co.device = "no-such-device-xyz";
    co.backend = BRDFFIT_BACKEND_OPENCL;
    ctx = (brdffit_context *)&co;
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_E_NO_DEVICE);
    ck_assert_ptr_null(ctx);
    ck_assert_ptr_nonnull(strstr(err.message, "no-such-device-xyz"));
    co.backend = BRDFFIT_BACKEND_AUTO;
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_context_backend(ctx), BRDFFIT_BACKEND_HOST);
    ck_assert_ptr_nonnull(strstr(brdffit_context_describe(ctx), "no-such-device-xyz"));
    brdffit_context_free(ctx);
    /* the environment variable does the same */
    setenv("BRDFFIT_DEVICE", "9:9", 1);
    co.device = NULL;
    co.backend = BRDFFIT_BACKEND_OPENCL;
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_E_NO_DEVICE);
    co.backend = (brdffit_backend)42;
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert_int_eq(brdffit_context_create(NULL, NULL, &err), BRDFFIT_E_INVALID_ARGUMENT);
}
END_TEST

/* With no OpenCL device at all the fit runs through the host C path, and the
 * result says so.  OCL_ICD_VENDORS pointing at an empty directory makes the
 * ICD loader find no platform, as on a machine without OpenCL. */
START_TEST(no_platform_falls_back_to_host)
{
    char dir[] = "/tmp/brdffit-noicd-XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    setenv("OCL_ICD_VENDORS", dir, 1);
    brdffit_error err;
    brdffit_context *ctx = NULL;
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    co.backend = BRDFFIT_BACKEND_OPENCL;
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_E_NO_DEVICE);
    ck_assert(strlen(err.message) > 0);
    co.backend = BRDFFIT_BACKEND_AUTO;
    ck_assert_int_eq(brdffit_context_create(&co, &ctx, &err), BRDFFIT_OK);
    ck_assert_int_eq(brdffit_context_backend(ctx), BRDFFIT_BACKEND_HOST);
    ck_assert_ptr_nonnull(strstr(brdffit_context_describe(ctx), "host"));

    /* a small fit through the host path: a Ward table, recovered */
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    ck_assert_int_eq(brdffit_table_create(&t, &err), BRDFFIT_OK);
    brdffit_params p = { { 0.05, 0.04, 0.03 }, { 0.04, 0.03, 0.02 }, { 0.2, 0, 0 }, { 0 } };
    ck_assert_int_eq(brdffit_table_fill_model(t, BRDFFIT_WARD, &p, BRDFFIT_SCALE_STANDARD, &err), BRDFFIT_OK);
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.cutoff_deg = 30; /* fewer samples: the host path is single-threaded */
    ck_assert_int_eq(brdffit_samples_create(t, &so, &s, &err), BRDFFIT_OK);
    brdffit_fit_options fo;
    brdffit_fit_options_default(&fo);
    fo.starts = 4;
    fo.refine = 1;
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_WARD, &fo, &r, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_int_eq(r.backend, BRDFFIT_BACKEND_HOST);
    ck_assert_msg(fabs(r.params.p[0] - 0.2) < 1e-4, "alpha %g", r.params.p[0]);
    ck_assert(isfinite(r.error) && r.error < 1e-6);
    brdffit_samples_free(s);
    brdffit_table_free(t);
    brdffit_context_free(ctx);
    ck_assert_int_eq(rmdir(dir), 0);
}
END_TEST

/* Unset POCL_CACHE_DIR: the context makes a writable one, and kernels build. */
START_TEST(pocl_cache_out_of_the_box)
{
    char home[] = "/tmp/brdffit-home-XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(home));
    unsetenv("POCL_CACHE_DIR");
    unsetenv("XDG_CACHE_HOME");
    setenv("HOME", home, 1);
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    const char *cache = getenv("POCL_CACHE_DIR");
    ck_assert_ptr_nonnull(cache);
    ck_assert_ptr_nonnull(strstr(cache, home));
    struct stat st;
    ck_assert_int_eq(stat(cache, &st), 0);
    ck_assert(S_ISDIR(st.st_mode));
    cl_kernel kf, kv;
    ck_assert_msg(bf_context_kernels(ctx, BRDFFIT_WARD, &kf, &kv, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_context_free(ctx);
    ck_assert_int_eq(tu_remove_tree(home), 0);
}
END_TEST

/* A small synthetic sample set: Ward within a 30 deg cutoff. */
static brdffit_samples *small_samples(void)
{
    brdffit_error err;
    brdffit_table *t = NULL;
    brdffit_samples *s = NULL;
    brdffit_params p = { { 0.1, 0.1, 0.1 }, { 0.2, 0.2, 0.2 }, { 0.1 }, { 0 } };
    ck_assert_msg(brdffit_table_create(&t, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(brdffit_table_fill_model(t, BRDFFIT_WARD, &p, BRDFFIT_SCALE_STANDARD, &err) ==
                      BRDFFIT_OK, "%s", err.message);
    brdffit_sample_options so;
    brdffit_sample_options_default(&so);
    so.cutoff_deg = 30;
    ck_assert_msg(brdffit_samples_create(t, &so, &s, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_table_free(t);
    return s;
}

/* brdffit_context_prepare builds a model's kernels ahead: the fit then
 * reports no build time; without it the first fit builds them and reports
 * the build (within its seconds) as seconds_build, the later ones 0. */
START_TEST(prepare_builds_ahead)
{
    brdffit_samples *s = small_samples();
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(brdffit_context_build_seconds(ctx, BRDFFIT_WARD) == 0.0);
    ck_assert_msg(brdffit_context_prepare(ctx, BRDFFIT_WARD, &err) == BRDFFIT_OK, "%s", err.message);
    double built = brdffit_context_build_seconds(ctx, BRDFFIT_WARD);
    ck_assert(built > 0.0);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_WARD, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(r.seconds_build == 0.0);
    ck_assert_msg(brdffit_context_prepare(ctx, BRDFFIT_WARD, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(brdffit_context_build_seconds(ctx, BRDFFIT_WARD) == built); /* not built again */

    /* no prepare: the first fit of a model builds, the second does not */
    ck_assert(brdffit_context_build_seconds(ctx, BRDFFIT_BLINN_PHONG) == 0.0);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_BLINN_PHONG, NULL, &r, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert(r.seconds_build > 0.0 && r.seconds_build < r.seconds);
    ck_assert(r.seconds_build == brdffit_context_build_seconds(ctx, BRDFFIT_BLINN_PHONG));
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_BLINN_PHONG, NULL, &r, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert(r.seconds_build == 0.0);

    ck_assert_int_eq(brdffit_context_prepare(ctx, (brdffit_model)99, &err), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(err.status, BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_int_eq(brdffit_context_prepare(NULL, BRDFFIT_WARD, &err), BRDFFIT_E_INVALID_ARGUMENT);
    brdffit_context_free(ctx);

    /* the host path has nothing to build */
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_HOST, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(brdffit_context_prepare(ctx, BRDFFIT_WARD, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(brdffit_context_build_seconds(ctx, BRDFFIT_WARD) == 0.0);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_WARD, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(r.seconds_build == 0.0);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* A kernel that does not build reports BRDFFIT_E_KERNEL_BUILD with the log. */
START_TEST(build_failure_carries_log)
{
    setenv("BRDFFIT_CL_OPTIONS", "-DBF_WIDTH=5", 1); /* bf_common.h: #error */
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    cl_kernel kf, kv;
    /* the compiler inside PoCL also writes its diagnostics to stderr: kept
     * from the run's output, and looked at */
    tu_capture cap;
    ck_assert_int_eq(tu_capture_begin(&cap), 0);
    brdffit_status st = bf_context_kernels(ctx, BRDFFIT_WARD, &kf, &kv, &err);
    brdffit_error err2;
    brdffit_status st2 = brdffit_context_prepare(ctx, BRDFFIT_COOK_TORRANCE, &err2);
    char *printed = tu_capture_end(&cap);
    ck_assert_int_eq(st, BRDFFIT_E_KERNEL_BUILD);
    ck_assert_int_eq(err.status, BRDFFIT_E_KERNEL_BUILD);
    ck_assert_ptr_nonnull(strstr(err.message, "build log"));
    ck_assert_ptr_nonnull(strstr(err.message, "BF_WIDTH must be 4 or 8")); /* the compiler's words */
    /* brdffit_context_prepare reports the same */
    ck_assert_int_eq(st2, BRDFFIT_E_KERNEL_BUILD);
    ck_assert_ptr_nonnull(strstr(err2.message, "BF_WIDTH must be 4 or 8"));
    /* what reached stderr is the compiler's count of its errors ("2 errors generated.") */
    ck_assert_msg(strstr(printed, "error") != NULL, "stderr: %s", printed);
    free(printed);
    ck_assert(brdffit_context_build_seconds(ctx, BRDFFIT_COOK_TORRANCE) == 0.0);
    brdffit_context_free(ctx);
}
END_TEST

/* Ward's moments (alpha = 0.3) over 200 directions of data rho, taken at
 * the reference d, s of pp, into mom (nk = 1, np = 0). */
static void ward_moments(const bf_pass_par *pp, double *mom)
{
    memset(mom, 0, BF_NMOM_MAX * sizeof *mom);
    for (int i = 0; i < 200; i++) {
        double ti = 0.007 * i, to = 0.007 * (200 - i), ph = 0.031 * i;
        double wi[3] = { sin(ti), 0.0, cos(ti) };
        double wo[3] = { sin(to) * cos(ph), sin(to) * sin(ph), cos(to) };
        double h[3] = { wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2] };
        double hn = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        bf_geom g = { wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], h[2] / hn,
                      (wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2]) / hn };
        double rho[3] = { 0.1 + 0.05 * sin(i), 0.2 + 0.03 * cos(i), 0.05 + 0.01 * sin(3.0 * i) };
        bf_accumulate((int)BRDFFIT_WARD, 1, 0, pp, &g, rho, 1.0 / 200, mom, NULL);
    }
}

/* He's vectors are summed in pairs (bf_acc_two, bf_accumulate): the pair's
 * moments are those of its two members, for every nk and np: against each
 * moment summed from its definition, and against bf_acc_one twice. */
START_TEST(pairs_sum_as_ones)
{
    bf_pass_par pp;
    memset(&pp, 0, sizeof pp);
    for (int c = 0; c < 3; c++)
        pp.d[c] = 0.1 + 0.05 * c, pp.s[c] = 0.7 - 0.2 * c;
    srand(31);
    for (int nk = 1; nk <= 3; nk += 2)
        for (int np = 0; np <= BF_MAX_NP; np++)
            for (int rep = 0; rep < 50; rep++) {
                double a2[2], K0[2][3], G[2][3][BF_MAX_NP], rho[2][3];
                for (int v = 0; v < 2; v++) {
                    a2[v] = rand() / (double)RAND_MAX;
                    for (int k = 0; k < 3; k++) {
                        K0[v][k] = 3.0 * rand() / RAND_MAX;
                        rho[v][k] = rand() / (double)RAND_MAX;
                        for (int j = 0; j < BF_MAX_NP; j++)
                            G[v][k][j] = 2.0 * rand() / RAND_MAX - 1.0;
                    }
                }
                double two[BF_NMOM_MAX] = { 0 }, ones[BF_NMOM_MAX] = { 0 }, def[BF_NMOM_MAX] = { 0 };
                bf_acc_two(nk, np, &pp, a2[0], K0[0], G[0], rho[0], a2[1], K0[1], G[1], rho[1], two);
                for (int v = 0; v < 2; v++) {
                    bf_acc_one(nk, np, &pp, a2[v], K0[v], G[v], rho[v], ones);
                    moments_by_name(nk, np, &pp, a2[v], K0[v], G[v], rho[v], def);
                }
                for (int m = 0; m < bf_nmom(nk, np); m++) {
                    double tol = 1e-14 * (fabs(def[m]) + 1.0);
                    ck_assert_msg(fabs(two[m] - def[m]) <= tol && fabs(ones[m] - def[m]) <= tol,
                                  "nk %d np %d moment %d: pair %.17g, one by one %.17g, by name %.17g",
                                  nk, np, m, two[m], ones[m], def[m]);
                }
            }
}
END_TEST

/* r^T r from moments taken at a reference far from the best d, s is lost to
 * cancellation (the fit once got a spurious 0 there): bf_linear_ref_far says
 * so, and says nothing at the best, where r^T r is that of a pass taken at
 * the best itself. */
START_TEST(ref_far_detected)
{
    bf_pass_par pp;
    memset(&pp, 0, sizeof pp);
    pp.p[0][0] = 0.3;
    double mom[BF_NMOM_MAX];
    bf_linear ref = { { 0, 0, 0 }, { 1e12, 1e12, 1e12 } }, best, best2;
    memcpy(pp.s, ref.s, sizeof pp.s);
    ward_moments(&pp, mom);
    double rr = bf_linear_best(mom, 1, 0, &ref, &best);
    ck_assert_msg(bf_linear_ref_far(mom, 1, 0, rr), "s_ref = 1e12: rr %g not flagged", rr);
    memcpy(pp.d, best.d, sizeof pp.d);
    memcpy(pp.s, best.s, sizeof pp.s);
    ward_moments(&pp, mom);
    double rr2 = bf_linear_best(mom, 1, 0, &best, &best2);
    ck_assert(rr2 > 0);
    ck_assert_msg(!bf_linear_ref_far(mom, 1, 0, rr2), "at the best: rr %g flagged", rr2);
    memcpy(pp.d, best2.d, sizeof pp.d);
    memcpy(pp.s, best2.s, sizeof pp.s);
    ward_moments(&pp, mom);
    double see = 0.0;
    for (int c = 0; c < 3; c++)
        see += mom[bf_mom_chan(c, 1, 0) + BF_MC_SEE];
    ck_assert_msg(fabs(rr2 - see) <= 1e-9 * see, "rr %.17g, at the best itself %.17g", rr2, see);
}
END_TEST

/* bf_pass_order: every run taken once whatever the count of work-items, and
 * for the counts a pass uses (16 a compute unit), the first chunk of
 * work-items that PoCL's pthread device deals to one thread (1 + items / 2)
 * takes 40-60% of its runs from each half of the table. */
START_TEST(run_order_is_a_permutation)
{
    static unsigned char seen[600];
    for (size_t n = 1; n <= sizeof seen; n++) {
        cl_uint order = bf_pass_order(n);
        ck_assert_uint_ge(order, 1);
        ck_assert(n <= 2 ? order == 1 : order < n);
        memset(seen, 0, n);
        for (size_t gid = 0; gid < n; gid++)
            seen[(gid * order) % n]++;
        for (size_t r = 0; r < n; r++)
            ck_assert_msg(seen[r] == 1, "items %zu, order %u: run %zu taken %d times", n,
                          (unsigned)order, r, seen[r]);
    }
    for (size_t cus = 1; cus <= 32; cus *= 2) {
        size_t n = 16 * cus, chunk = 1 + n / 2, low = 0;
        cl_uint order = bf_pass_order(n);
        for (size_t gid = 0; gid < chunk; gid++)
            low += (gid * order) % n < n / 2;
        ck_assert_msg(low >= 0.4 * chunk && low <= 0.6 * chunk, "items %zu: %zu of %zu in the first half",
                      n, low, chunk);
    }
}
END_TEST

Suite *pass_suite(void)
{
    Suite *s = suite_create("pass");
    TCase *tc = tcase_create("kernel");
    tcase_set_timeout(tc, 300);
    tcase_set_tags(tc, TU_NEEDS_SHARED);
    tcase_add_loop_test(tc, kernel_equals_host, 0, brdffit_model_count());
    tcase_add_test(tc, weights_normalised);
    tcase_add_test(tc, subset_every_8th);
    tcase_add_loop_test(tc, fold_equals_plain, 0, 2);
    tcase_add_test(tc, partials_equal_neighbours);
    tcase_add_test(tc, kernel_equals_host_on_stride_subset);
    tcase_add_loop_test(tc, whole_bins_equal_plain, 0, 3);
    tcase_add_test(tc, whole_bins_keep_close_residuals);
    tcase_add_test(tc, unordered_set_summed_by_samples);
    tcase_add_test(tc, mirror_set_merges_pairs);
    tcase_add_loop_test(tc, mirror_sums_are_the_sets, 0, brdffit_model_count());
    tcase_add_loop_test(tc, subset_of_bins, 0, (int)(sizeof bins_steps / sizeof bins_steps[0]));
    suite_add_tcase(s, tc);
    TCase *tl = tcase_create("layout");
    tcase_add_test(tl, moment_layout);
    tcase_add_test(tl, pairs_sum_as_ones);
    tcase_add_test(tl, ref_far_detected);
    tcase_add_test(tl, run_order_is_a_permutation);
    suite_add_tcase(s, tl);
    TCase *tp = tcase_create("prepare"); /* a synthetic table: no ../shared */
    tcase_set_timeout(tp, 300);
    tcase_add_test(tp, prepare_builds_ahead);
    suite_add_tcase(s, tp);
    /* the tests that change the environment: the fixture puts it back */
    TCase *te = tcase_create("environment");
    tcase_set_timeout(te, 300);
    tcase_add_checked_fixture(te, tu_env_save, tu_env_restore);
    tcase_add_test(te, env_restored);
    tcase_add_test(te, device_selection);
    tcase_add_test(te, no_platform_falls_back_to_host);
    tcase_add_test(te, pocl_cache_out_of_the_box);
    tcase_add_test(te, build_failure_carries_log);
    suite_add_tcase(s, te);
    return s;
}
