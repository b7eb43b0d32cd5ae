/* SPDX-License-Identifier: MIT */
/* test_subsets.c -- what a sample set keeps for its fits (samples_derived.c,
 * subsets.c): the screening subsets kept with the set are the subsets made
 * afresh, to the bit, and made once; He's bin table is shared by every
 * driver of the set, each with rows of its own; brdffit_samples_prepare
 * makes exactly what a fit would (the mirror set among it), and a fit of a prepared set is the fit of
 * a fresh one.  (Fits of one set from several threads at once: test_threads.c.) */
#include "testutil.h"
#include "pass.h"
#include "registry.h"
#include "samples.h"
#include "subsets.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

/* The synthetic table's set at the default cutoff (~1e6 samples): large
 * enough for every model's screening subsets; no ../shared. */
static brdffit_samples *full_samples(void)
{
    brdffit_error err;
    brdffit_samples *s = NULL;
    ck_assert_msg(tu_ward_duer_samples(0, &s, &err) == BRDFFIT_OK, "%s", err.message);
    return s;
}

/* Two sets with the same samples, fields, weights, bins and sums, to the bit. */
static void assert_same_set(const brdffit_samples *a, const brdffit_samples *b)
{
    ck_assert_uint_eq(a->n, b->n);
    ck_assert_uint_eq(a->npad, b->npad);
    ck_assert(memcmp(a->data, b->data, (size_t)BF_NFIELDS * a->npad * sizeof *a->data) == 0);
    ck_assert(memcmp(a->w, b->w, a->n * sizeof *a->w) == 0);
    ck_assert(memcmp(a->bin, b->bin, a->n * sizeof *a->bin) == 0);
    ck_assert(a->sum_a2 == b->sum_a2 && a->sum_w == b->sum_w);
}

START_TEST(kept_subsets_are_the_subsets)
{
    brdffit_samples *s = full_samples(), *every = NULL, *bins = NULL;
    brdffit_error err;
    const brdffit_samples *k12 = NULL, *k12b = NULL, *k8 = NULL, *kb = NULL, *kb2 = NULL;
    const int step[3] = { 3, 3, 12 }, other[3] = { 2, 2, 12 };
    ck_assert_uint_eq(bf_derived_count(s), 0);
    ck_assert_msg(bf_samples_every_kept(s, 12, &k12, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(bf_samples_every(s, 12, &every, &err) == BRDFFIT_OK, "%s", err.message);
    assert_same_set(k12, every);
    ck_assert_msg(bf_samples_bins_kept(s, step, &kb, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(bf_samples_bins(s, step, &bins, &err) == BRDFFIT_OK, "%s", err.message);
    assert_same_set(kb, bins);
    /* asked again: the same set, not another; another key: another set */
    ck_assert_msg(bf_samples_every_kept(s, 12, &k12b, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_ptr_eq(k12, k12b);
    ck_assert_msg(bf_samples_every_kept(s, 8, &k8, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_ptr_ne(k8, k12);
    ck_assert_uint_eq(k8->n, (s->n + 7) / 8);
    ck_assert_msg(bf_samples_bins_kept(s, other, &kb2, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_ptr_ne(kb2, kb);
    ck_assert_uint_eq(bf_derived_count(s), 4);
    brdffit_samples_free(every);
    brdffit_samples_free(bins);
    brdffit_samples_free(s); /* and what it keeps (valgrind, ASan: no leak) */
}
END_TEST

/* Two drivers' bin tables of one set: the same hd and table (kept with the
 * set, alive after both are freed), rows of their own. */
START_TEST(bin_table_shared_rows_own)
{
    brdffit_samples *s = full_samples();
    brdffit_error err;
    bf_pass_bins a, b, c;
    ck_assert_msg(bf_pass_bins_make(s, 4, &a, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(bf_pass_bins_make(s, 1, &b, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert(a.hd && a.table && a.rows && b.rows);
    const double *hd = a.hd;
    ck_assert_ptr_eq(a.hd, b.hd);
    ck_assert_ptr_eq(a.table, b.table);
    ck_assert_ptr_ne(a.rows, b.rows);
    ck_assert_int_gt(a.nrows, b.nrows);
    /* every sample's bin, in table order */
    for (size_t i = 0; i < s->n; i++)
        ck_assert(a.hd[i] == (double)(s->bin[i] / 180));
    bf_pass_bins_free(&a);
    bf_pass_bins_free(&b);
    ck_assert_ptr_null(a.rows);
    ck_assert_msg(bf_pass_bins_make(s, 1, &c, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_ptr_eq(c.hd, hd);
    ck_assert(c.hd[s->n - 1] == (double)(s->bin[s->n - 1] / 180));
    ck_assert_uint_eq(bf_derived_count(s), 1);
    bf_pass_bins_free(&c);
    brdffit_samples_free(s);
}
END_TEST

/* brdffit_samples_prepare makes what a fit of the model uses (the fit then
 * makes nothing), once: the mirror set its passes on all samples read, the
 * screening subsets, and for He the bin tables of the mirror set and of its
 * two subsets (none of the set's own). */
START_TEST(prepare_makes_what_fits_use)
{
    brdffit_samples *s = full_samples();
    brdffit_error err;
    ck_assert_msg(brdffit_samples_prepare(s, BRDFFIT_HE, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_int_eq(err.status, BRDFFIT_OK);
    const brdffit_samples *every = NULL, *bins = NULL, *mirror = NULL;
    ck_assert_uint_eq(bf_derived_count(s), 3); /* the mirror set, every 12th, the bin subset */
    ck_assert_msg(bf_samples_mirror_kept(s, &mirror, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_uint_eq(bf_derived_count(mirror), 1); /* its bin table */
    ck_assert_msg(bf_screen_subsets(s, BRDFFIT_HE, &every, &bins, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert(every && bins);
    ck_assert_uint_eq(bf_derived_count(s), 3);
    ck_assert_uint_eq(bf_derived_count(every), 1);
    ck_assert_uint_eq(bf_derived_count(bins), 1);
    ck_assert_msg(brdffit_samples_prepare(s, BRDFFIT_HE, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_uint_eq(bf_derived_count(s), 3);
    /* Cook-Torrance: every 8th sample, no bin tables */
    ck_assert_msg(brdffit_samples_prepare(s, BRDFFIT_COOK_TORRANCE, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert_uint_eq(bf_derived_count(s), 4);
    ck_assert_msg(bf_screen_subsets(s, BRDFFIT_COOK_TORRANCE, &every, &bins, &err) == BRDFFIT_OK,
                  "%s", err.message);
    ck_assert(every && !bins);
    ck_assert_uint_eq(every->n, (s->n + 7) / 8);
    ck_assert_uint_eq(bf_derived_count(every), 0);
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_HE, NULL, &r, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_COOK_TORRANCE, NULL, &r, &err) == BRDFFIT_OK, "%s",
                  err.message);
    ck_assert_uint_eq(bf_derived_count(s), 4); /* the fits made nothing more */
    ck_assert_uint_eq(bf_derived_count(mirror), 1);
    brdffit_context_free(ctx);
    brdffit_samples_free(s);
}
END_TEST

/* A fit of a prepared set is the fit of a fresh one (which makes its own
 * subsets): the same parameters and Error, to the bit; so is a second fit
 * of the set, which finds them made. */
START_TEST(prepared_fit_is_fresh_fit)
{
    const brdffit_model models[] = { BRDFFIT_HE, BRDFFIT_GGX };
    brdffit_model m = models[_i];
    brdffit_samples *fresh = full_samples(), *prepared = full_samples();
    brdffit_error err;
    ck_assert_msg(brdffit_samples_prepare(prepared, m, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_OPENCL, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_fit_result a, b, c;
    brdffit_fit_result_init(&a);
    brdffit_fit_result_init(&b);
    brdffit_fit_result_init(&c);
    ck_assert_msg(brdffit_fit(ctx, fresh, m, NULL, &a, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(brdffit_fit(ctx, prepared, m, NULL, &b, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(brdffit_fit(ctx, fresh, m, NULL, &c, &err) == BRDFFIT_OK, "%s", err.message);
    ck_assert_msg(a.error == b.error && a.error == c.error, "Errors %.17g %.17g %.17g", a.error,
                  b.error, c.error);
    ck_assert(memcmp(&a.params, &b.params, sizeof a.params) == 0);
    ck_assert(memcmp(&a.params, &c.params, sizeof a.params) == 0);
    ck_assert_int_eq(a.passes, b.passes);
    brdffit_context_free(ctx);
    brdffit_samples_free(fresh);
    brdffit_samples_free(prepared);
}
END_TEST

/* Bad arguments: a clear status and message, nothing kept; a set too small
 * for a screening subset keeps only its mirror set (He: and that set's bin
 * table). */
START_TEST(prepare_refuses_and_small_sets)
{
    brdffit_error err;
    memset(&err, 0, sizeof err);
    ck_assert_int_eq(brdffit_samples_prepare(NULL, BRDFFIT_HE, &err), BRDFFIT_E_INVALID_ARGUMENT);
    ck_assert(strstr(err.message, "NULL samples") != NULL);
    brdffit_samples *s = full_samples();
    ck_assert_int_eq(brdffit_samples_prepare(s, (brdffit_model)99, &err), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert(strstr(err.message, "99") != NULL);
    ck_assert_int_eq(brdffit_samples_prepare(s, (brdffit_model)-1, &err), BRDFFIT_E_UNKNOWN_MODEL);
    ck_assert_uint_eq(bf_derived_count(s), 0);
    brdffit_samples_free(s);

    /* a few thousand samples: fewer than 8 x 4096 */
    ck_assert_int_eq(tu_ward_duer_samples(6, &s, &err), BRDFFIT_OK);
    ck_assert_uint_lt(s->n, 8 * BF_SCREEN_MIN_SAMPLES);
    ck_assert_int_eq(brdffit_samples_prepare(s, BRDFFIT_WARD, &err), BRDFFIT_OK);
    ck_assert_uint_eq(bf_derived_count(s), 1);
    const brdffit_samples *mirror = NULL;
    ck_assert_int_eq(bf_samples_mirror_kept(s, &mirror, &err), BRDFFIT_OK);
    ck_assert_uint_eq(bf_derived_count(mirror), 0);
    ck_assert_int_eq(brdffit_samples_prepare(s, BRDFFIT_HE, &err), BRDFFIT_OK);
    ck_assert_uint_eq(bf_derived_count(s), 1);
    ck_assert_uint_eq(bf_derived_count(mirror), 1);
    brdffit_samples_free(s);
}
END_TEST

/* A model that refines on the bin subset first (registry: refine_on_bins)
 * has the subsets it runs on (refine_on_subset, a stride, bins), and its
 * rough test is on one of its lobe coordinates' parameters, inside that
 * parameter's bounds; He is one. */
START_TEST(refine_on_bins_has_its_subsets)
{
    int found = 0;
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        const bf_model_def *def = bf_model_def_get((brdffit_model)m);
        if (!def->refine_on_bins)
            continue;
        found += m == BRDFFIT_HE;
        ck_assert_msg(def->refine_on_subset && def->screen_stride > 1, "model %d", m);
        for (int i = 0; i < 3; i++)
            ck_assert_int_gt(def->screen_bins[i], 0);
        int coord = 0;
        for (int j = 0; j < bf_model_ncoords((brdffit_model)m); j++)
            coord |= bf_model_coord_param((brdffit_model)m, j) == def->rough_param;
        ck_assert_msg(coord, "model %d: rough_param %d is no coordinate's", m, def->rough_param);
        const brdffit_param_info *pi = &def->info.params[def->rough_param];
        ck_assert_msg(def->rough_from > pi->lower && def->rough_from < pi->upper,
                      "model %d: rough_from %g outside (%g, %g)", m, def->rough_from, pi->lower,
                      pi->upper);
    }
    ck_assert_int_eq(found, 1);
}
END_TEST

/* A derived datum whose making fails: its status and message come back,
 * nothing is kept, and the next ask makes it (a failure is not remembered). */
static int fail_next = 1;
enum { TEST_KIND = 99 }; /* a kind of the test's own */

static brdffit_status make_or_fail(const brdffit_samples *s, const int key[3], void **out,
                                   brdffit_error *err)
{
    (void)s;
    if (fail_next)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "no memory for datum %d", key[0]);
    int *v = malloc(sizeof *v);
    if (!v)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "no memory");
    *v = key[0];
    *out = v;
    return BRDFFIT_OK;
}

START_TEST(failed_make_keeps_nothing)
{
    brdffit_samples *s = full_samples();
    brdffit_error err;
    const int key[3] = { 7, 0, 0 };
    const void *d = (const void *)&err;
    fail_next = 1;
    ck_assert_int_eq(bf_derived_get(s, TEST_KIND, key, make_or_fail, free, &d, &err),
                     BRDFFIT_E_NO_MEMORY);
    ck_assert_ptr_null(d);
    ck_assert_str_eq(err.message, "no memory for datum 7");
    ck_assert_uint_eq(bf_derived_count(s), 0);
    fail_next = 0;
    ck_assert_int_eq(bf_derived_get(s, TEST_KIND, key, make_or_fail, free, &d, &err), BRDFFIT_OK);
    ck_assert(d && *(const int *)d == 7);
    ck_assert_uint_eq(bf_derived_count(s), 1);
    brdffit_samples_free(s); /* frees the datum with free() */
}
END_TEST

Suite *subsets_suite(void)
{
    Suite *s = suite_create("subsets");
    TCase *tc = tcase_create("kept");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, kept_subsets_are_the_subsets);
    tcase_add_test(tc, bin_table_shared_rows_own);
    tcase_add_test(tc, prepare_makes_what_fits_use);
    tcase_add_loop_test(tc, prepared_fit_is_fresh_fit, 0, 2);
    tcase_add_test(tc, prepare_refuses_and_small_sets);
    tcase_add_test(tc, failed_make_keeps_nothing);
    tcase_add_test(tc, refine_on_bins_has_its_subsets);
    suite_add_tcase(s, tc);
    return s;
}
