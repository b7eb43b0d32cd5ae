/* SPDX-License-Identifier: MIT */
/* test_alloc.c -- the library's large arrays and the pool that keeps them
 * when freed (src/lib/alloc.c, brdffit_release_memory). */
#define _POSIX_C_SOURCE 200809L
#include "brdffit.h"
#include "internal.h" /* bf_alloc_aligned and the pool's counters */
#include "samples.h"  /* struct brdffit_samples: its arrays */
#include "testutil.h"

#include <check.h>
#include <pthread.h>
#include <sched.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define MB ((size_t)1 << 20)

/* A freed large array serves the next request of at least half its size:
 * the same memory, out of the pool; brdffit_release_memory gives the pool's
 * bytes back once.  Without the pool (AddressSanitizer builds) nothing is
 * kept. */
START_TEST(pool_reuses_freed_array)
{
    brdffit_release_memory();
    ck_assert_uint_eq(bf_alloc_pooled(), 0);
    unsigned char *p = bf_alloc_aligned(8 * MB);
    ck_assert_ptr_nonnull(p);
    ck_assert_uint_eq((uintptr_t)p % 64, 0);
    memset(p, 7, 8 * MB);
    bf_free_aligned(p);
    if (!bf_alloc_pool_on()) {
        ck_assert_uint_eq(bf_alloc_pooled(), 0);
        ck_assert_uint_eq(brdffit_release_memory(), 0);
        return;
    }
    ck_assert_uint_eq(bf_alloc_pooled(), 8 * MB);
    unsigned char *q = bf_alloc_aligned(5 * MB);
    ck_assert_ptr_eq(q, p);
    ck_assert_uint_eq(bf_alloc_pooled(), 0);
    bf_free_aligned(q); /* back with its own size, 8 MB */
    ck_assert_uint_eq(bf_alloc_pooled(), 8 * MB);
    ck_assert_uint_eq(brdffit_release_memory(), 8 * MB);
    ck_assert_uint_eq(bf_alloc_pooled(), 0);
    ck_assert_uint_eq(brdffit_release_memory(), 0);
}
END_TEST

/* A pooled array does not serve a request over twice its size or under
 * half of it, nor a small one (below 4 MB, not pooled at all); the pool
 * keeps at most 16 arrays and 1 GiB. */
START_TEST(pool_bounds)
{
    brdffit_release_memory();
    if (!bf_alloc_pool_on())
        ck_assert_msg(bf_alloc_pooled() == 0, "a build without the pool holds %zu bytes",
                      bf_alloc_pooled());
    void *p = bf_alloc_aligned(10 * MB);
    ck_assert_ptr_nonnull(p);
    bf_free_aligned(p);
    const size_t kept = bf_alloc_pool_on() ? 10 * MB : 0;
    ck_assert_uint_eq(bf_alloc_pooled(), kept);
    void *over = bf_alloc_aligned(21 * MB), *under = bf_alloc_aligned(4 * MB + MB / 2),
         *small = bf_alloc_aligned(3 * MB);
    ck_assert(over && under && small && over != p && under != p && small != p);
    ck_assert_uint_eq(bf_alloc_pooled(), kept);
    bf_free_aligned(small); /* below 4 MB: not pooled */
    ck_assert_uint_eq(bf_alloc_pooled(), kept);
    bf_free_aligned(over);
    bf_free_aligned(under);
    brdffit_release_memory();

    void *blocks[20];
    for (int i = 0; i < 20; i++) {
        blocks[i] = bf_alloc_aligned(4 * MB);
        ck_assert_ptr_nonnull(blocks[i]);
    }
    for (int i = 0; i < 20; i++)
        bf_free_aligned(blocks[i]);
    ck_assert_uint_eq(bf_alloc_pooled(), bf_alloc_pool_on() ? 16 * 4 * MB : 0);
    brdffit_release_memory();

    /* two arrays of 600 MB (never touched: no memory is used): one is kept */
    void *a = bf_alloc_aligned(600 * MB), *b = bf_alloc_aligned(600 * MB);
    ck_assert(a && b);
    bf_free_aligned(a);
    bf_free_aligned(b);
    ck_assert_uint_eq(bf_alloc_pooled(), bf_alloc_pool_on() ? 600 * MB : 0);
    brdffit_release_memory();
}
END_TEST

/* A table's sample set and a He fit of it (which makes the set's mirror set,
 * subsets and bin table) are the same to the bit when they are made in
 * reused memory filled with garbage (NaN bytes) as when made in fresh
 * memory: nothing reads what it did not write. */
START_TEST(reused_memory_same_sets_and_fits)
{
    brdffit_error err;
    brdffit_context *ctx = NULL;
    ck_assert_msg(tu_context(BRDFFIT_BACKEND_AUTO, &ctx, &err) == BRDFFIT_OK, "%s", err.message);
    brdffit_release_memory();
    brdffit_fit_result r[2];
    for (int k = 0; k < 2; k++)
        brdffit_fit_result_init(&r[k]);
    double *data = NULL, *w = NULL;
    int *bin = NULL;
    size_t n = 0, nd = 0;
    for (int round = 0; round < 2; round++) {
        brdffit_samples *s = NULL;
        ck_assert_msg(tu_ward_duer_samples(0.0, &s, &err) == BRDFFIT_OK, "%s", err.message);
        ck_assert_msg(brdffit_fit(ctx, s, BRDFFIT_HE, NULL, &r[round], &err) == BRDFFIT_OK,
                      "%s", err.message);
        if (round == 0) {
            n = s->n;
            nd = (size_t)BF_NFIELDS * s->npad;
            data = malloc(nd * sizeof *data);
            w = malloc(n * sizeof *w);
            bin = malloc(n * sizeof *bin);
            ck_assert(data && w && bin);
            memcpy(data, s->data, nd * sizeof *data);
            memcpy(w, s->w, n * sizeof *w);
            memcpy(bin, s->bin, n * sizeof *bin);
        } else {
            ck_assert_uint_eq(s->n, n);
            ck_assert_uint_eq((size_t)BF_NFIELDS * s->npad, nd);
            ck_assert(memcmp(data, s->data, nd * sizeof *data) == 0);
            ck_assert(memcmp(w, s->w, n * sizeof *w) == 0);
            ck_assert(memcmp(bin, s->bin, n * sizeof *bin) == 0);
        }
        brdffit_samples_free(s);
        /* the set's arrays are pooled now: fill them with NaN bytes */
        size_t filled = bf_alloc_pool_fill(0xff);
        ck_assert_msg(!bf_alloc_pool_on() || filled >= 3, "%zu pooled arrays", filled);
    }
    ck_assert(memcmp(&r[0].error, &r[1].error, sizeof r[0].error) == 0);
    ck_assert(memcmp(&r[0].params, &r[1].params, sizeof r[0].params) == 0);
    free(data);
    free(w);
    free(bin);
    brdffit_context_free(ctx);
    brdffit_release_memory();
}
END_TEST

/* Threads taking and freeing large arrays at once: each finds in its array
 * what it wrote, and the pool ends within its bounds. */
#define THREADS 4
#define ROUNDS 50

static void *churn(void *arg)
{
    const unsigned char tag = (unsigned char)(uintptr_t)arg;
    for (int i = 0; i < ROUNDS; i++) {
        size_t bytes = (4 + (size_t)((i + tag) % 5)) * MB;
        unsigned char *p = bf_alloc_aligned(bytes);
        if (!p)
            return (void *)1;
        p[0] = p[bytes / 2] = p[bytes - 1] = tag;
        sched_yield();
        int ok = p[0] == tag && p[bytes / 2] == tag && p[bytes - 1] == tag;
        bf_free_aligned(p);
        if (!ok)
            return (void *)1;
    }
    return NULL;
}

START_TEST(pool_threads)
{
    brdffit_release_memory();
    pthread_t t[THREADS];
    for (int i = 0; i < THREADS; i++)
        ck_assert_int_eq(pthread_create(&t[i], NULL, churn, (void *)(uintptr_t)(i + 1)), 0);
    for (int i = 0; i < THREADS; i++) {
        void *bad = NULL;
        ck_assert_int_eq(pthread_join(t[i], &bad), 0);
        ck_assert_msg(bad == NULL, "thread %d found another thread's bytes in its array", i);
    }
    ck_assert(bf_alloc_pooled() <= (bf_alloc_pool_on() ? 16 * 8 * MB : 0));
    brdffit_release_memory();
}
END_TEST

Suite *alloc_suite(void)
{
    Suite *s = suite_create("alloc");
    TCase *tc = tcase_create("pool");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, pool_reuses_freed_array);
    tcase_add_test(tc, pool_bounds);
    tcase_add_test(tc, reused_memory_same_sets_and_fits);
    tcase_add_test(tc, pool_threads);
    suite_add_tcase(s, tc);
    return s;
}
