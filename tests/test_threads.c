/* SPDX-License-Identifier: MIT */
/* test_threads.c -- one context per thread, as the header says: four threads
 * create their FIRST contexts at the same moment (in a fresh process, where
 * PoCL's set-up has not happened yet) and fit at once; each gets the backend
 * it asked for and the Error a sequential fit gets.  Four threads fit one
 * large set at once, each making the screening subsets it needs, which the
 * set keeps (samples_derived.c): each is made once, and every fit is the
 * sequential one.  `make tsan` runs this suite under ThreadSanitizer. */
#define _POSIX_C_SOURCE 200809L
#include "testutil.h"
#include "samples.h"

#include <check.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NTHREADS 4

/* What a thread asks for, and the context and fit it got. */
typedef struct worker {
    brdffit_backend want;
    brdffit_model model;
    const brdffit_samples *samples;
    pthread_barrier_t *start;
    int st_context, st_fit;
    brdffit_backend got, fit_backend;
    double error;
    char message[512];
} worker;

/* The synthetic table's sample set within 25 deg (a small one: the host
 * path is one thread and TSan is slow), or NULL. */
static brdffit_samples *small_samples(void)
{
    brdffit_samples *s = NULL;
    brdffit_error err;
    return tu_ward_duer_samples(25, &s, &err) == BRDFFIT_OK ? s : NULL;
}

static void fit_options(brdffit_fit_options *fo)
{
    brdffit_fit_options_default(fo);
    fo->starts = 3;
    fo->max_evals = 60;
}

static void create_and_fit(worker *w)
{
    brdffit_error err;
    brdffit_context_options co;
    brdffit_context_options_default(&co);
    co.backend = w->want;
    brdffit_context *ctx = NULL;
    w->st_context = brdffit_context_create(&co, &ctx, &err);
    w->st_fit = -1;
    if (w->st_context != BRDFFIT_OK) {
        snprintf(w->message, sizeof w->message, "%.500s", err.message);
        return;
    }
    w->got = brdffit_context_backend(ctx);
    brdffit_fit_options fo;
    fit_options(&fo);
    brdffit_fit_result r;
    brdffit_fit_result_init(&r);
    w->st_fit = brdffit_fit(ctx, w->samples, w->model, &fo, &r, &err);
    if (w->st_fit == BRDFFIT_OK) {
        w->error = r.error;
        w->fit_backend = r.backend;
    } else {
        snprintf(w->message, sizeof w->message, "%.500s", err.message);
    }
    brdffit_context_free(ctx);
}

/* What w will ask for: a context of backend want, and a fit of model on s. */
static void worker_ask(worker *w, brdffit_backend want, brdffit_model model,
                       const brdffit_samples *s)
{
    w->want = want;
    w->model = model;
    w->samples = s;
}

static void *thread_main(void *arg)
{
    worker *w = arg;
    pthread_barrier_wait(w->start);
    create_and_fit(w);
    return NULL;
}

/* The workers' fits (want, model and samples set) in NTHREADS threads that
 * start at one moment; 0 when every thread was started. */
static int fit_in_threads(worker *ws)
{
    pthread_barrier_t start;
    pthread_barrier_init(&start, NULL, NTHREADS);
    pthread_t tid[NTHREADS];
    int started[NTHREADS], rc = 0;
    for (int i = 0; i < NTHREADS; i++) {
        ws[i].start = &start;
        started[i] = pthread_create(&tid[i], NULL, thread_main, &ws[i]) == 0;
        rc |= !started[i];
    }
    for (int i = 0; i < NTHREADS; i++)
        if (started[i])
            pthread_join(tid[i], NULL);
    pthread_barrier_destroy(&start);
    return rc;
}

/* Child results: the threads', then the same fits one after the other. */
typedef struct threads_seen {
    int setup_ok;
    worker threaded[NTHREADS], sequential[NTHREADS];
} threads_seen;

static const brdffit_backend asked[NTHREADS] = { BRDFFIT_BACKEND_OPENCL, BRDFFIT_BACKEND_OPENCL,
                                                 BRDFFIT_BACKEND_HOST, BRDFFIT_BACKEND_AUTO };
static const brdffit_model fitted[NTHREADS] = { BRDFFIT_WARD_DUER, BRDFFIT_BLINN_PHONG,
                                                BRDFFIT_WARD_DUER, BRDFFIT_WARD_DUER };

static void run_threads(void *arg, void *out, size_t len)
{
    (void)arg;
    (void)len;
    threads_seen *r = out;
    /* POCL_CACHE_DIR unset, so that the library's choice of a cache directory
     * (and its setenv) races too; the directory it will choose lives beside
     * the one `make test` gives, so kernels stay cached between runs */
    const char *given = getenv("POCL_CACHE_DIR");
    char xdg[1024];
    snprintf(xdg, sizeof xdg, "%s/threads-xdg", given && *given ? given : "/tmp/brdffit-test-cache");
    setenv("XDG_CACHE_HOME", xdg, 1);
    unsetenv("POCL_CACHE_DIR");
    brdffit_samples *s = small_samples();
    if (!s)
        return;
    for (int i = 0; i < NTHREADS; i++)
        worker_ask(&r->threaded[i], asked[i], fitted[i], s);
    r->setup_ok = fit_in_threads(r->threaded) == 0;
    for (int i = 0; i < NTHREADS; i++) {
        worker_ask(&r->sequential[i], asked[i], fitted[i], s);
        create_and_fit(&r->sequential[i]);
    }
    brdffit_samples_free(s);
}

START_TEST(first_contexts_in_four_threads)
{
    static threads_seen r;
    int rc = tu_in_child(run_threads, NULL, &r, sizeof r);
    ck_assert_msg(rc == 0, "the child process failed (%d): a crash or a ThreadSanitizer report", rc);
    ck_assert_msg(r.setup_ok, "no sample set or no threads");
    for (int i = 0; i < NTHREADS; i++) {
        const worker *t = &r.threaded[i], *q = &r.sequential[i];
        brdffit_backend want = asked[i] == BRDFFIT_BACKEND_AUTO ? BRDFFIT_BACKEND_OPENCL : asked[i];
        ck_assert_msg(q->st_context == BRDFFIT_OK && q->st_fit == BRDFFIT_OK,
                      "sequential %d: %d/%d %s", i, q->st_context, q->st_fit, q->message);
        ck_assert_msg(t->st_context == BRDFFIT_OK, "thread %d: context %d: %s", i, t->st_context,
                      t->message);
        ck_assert_msg(t->got == want, "thread %d asked for backend %d and got %d", i, asked[i], t->got);
        ck_assert_msg(t->st_fit == BRDFFIT_OK, "thread %d: fit %d: %s", i, t->st_fit, t->message);
        ck_assert_int_eq(t->fit_backend, want);
        ck_assert_int_eq(q->fit_backend, want);
        /* the same passes in the same order: the same Error, to the last bit */
        ck_assert_msg(t->error == q->error, "thread %d: Error %.17g, sequential %.17g", i, t->error,
                      q->error);
        ck_assert(isfinite(t->error));
        if (fitted[i] == BRDFFIT_WARD_DUER) /* the generating model: recovered */
            ck_assert_msg(t->error < 1e-6, "thread %d: Error %g", i, t->error);
    }
}
END_TEST

/* Contexts made and freed in a loop by four threads at once (set-up and
 * tear-down race each other), after the first set-up. */
static void *churn(void *arg)
{
    int *failures = arg;
    for (int k = 0; k < 6; k++) {
        brdffit_error err;
        brdffit_context_options co;
        brdffit_context_options_default(&co);
        co.backend = BRDFFIT_BACKEND_OPENCL;
        brdffit_context *ctx = NULL;
        if (brdffit_context_create(&co, &ctx, &err) != BRDFFIT_OK ||
            brdffit_context_backend(ctx) != BRDFFIT_BACKEND_OPENCL)
            (*failures)++;
        brdffit_context_free(ctx);
    }
    return NULL;
}

static void run_churn(void *arg, void *out, size_t len)
{
    (void)arg;
    (void)len;
    int *failures = out; /* NTHREADS counters */
    pthread_t tid[NTHREADS];
    for (int i = 0; i < NTHREADS; i++)
        pthread_create(&tid[i], NULL, churn, &failures[i]);
    for (int i = 0; i < NTHREADS; i++)
        pthread_join(tid[i], NULL);
}

START_TEST(contexts_made_and_freed_in_four_threads)
{
    int failures[NTHREADS];
    int rc = tu_in_child(run_churn, NULL, failures, sizeof failures);
    ck_assert_msg(rc == 0, "the child process failed (%d): a crash or a ThreadSanitizer report", rc);
    for (int i = 0; i < NTHREADS; i++)
        ck_assert_msg(failures[i] == 0, "thread %d: %d of 6 contexts failed", i, failures[i]);
}
END_TEST

/* The synthetic table's sample set at the default cutoff (~1e6 samples):
 * large enough for every model's screening subsets; or NULL. */
static brdffit_samples *large_samples(void)
{
    brdffit_samples *s = NULL;
    brdffit_error err;
    return tu_ward_duer_samples(0, &s, &err) == BRDFFIT_OK ? s : NULL;
}

/* Two He fits (the mirror set, every 12th sample, the bin subset, three
 * bin tables) and two of models screened on every 8th sample, at once on
 * one set. */
static const brdffit_model shared_fitted[NTHREADS] = { BRDFFIT_HE, BRDFFIT_COOK_TORRANCE,
                                                       BRDFFIT_HE, BRDFFIT_WARD_DUER };

typedef struct shared_seen {
    int setup_ok;
    size_t kept;        /* what the set keeps after the threads' fits */
    size_t kept_mirror; /* and what its mirror set keeps */
    worker threaded[NTHREADS], sequential[NTHREADS];
} shared_seen;

static void run_shared(void *arg, void *out, size_t len)
{
    (void)arg;
    (void)len;
    shared_seen *r = out;
    brdffit_samples *s = large_samples(), *fresh = large_samples();
    if (!s || !fresh)
        goto done;
    for (int i = 0; i < NTHREADS; i++)
        worker_ask(&r->threaded[i], BRDFFIT_BACKEND_OPENCL, shared_fitted[i], s);
    r->setup_ok = fit_in_threads(r->threaded) == 0;
    r->kept = bf_derived_count(s);
    const brdffit_samples *mirror = NULL;
    brdffit_error err;
    r->kept_mirror = bf_samples_mirror_kept(s, &mirror, &err) == BRDFFIT_OK ? bf_derived_count(mirror) : 0;
    for (int i = 0; i < NTHREADS; i++) { /* each on a set of its own, made afresh */
        worker_ask(&r->sequential[i], BRDFFIT_BACKEND_OPENCL, shared_fitted[i], fresh);
        create_and_fit(&r->sequential[i]);
        brdffit_samples_free(fresh);
        fresh = i + 1 < NTHREADS ? large_samples() : NULL;
    }
done:
    brdffit_samples_free(s);
    brdffit_samples_free(fresh);
}

START_TEST(one_set_fitted_in_four_threads)
{
    static shared_seen r;
    int rc = tu_in_child(run_shared, NULL, &r, sizeof r);
    ck_assert_msg(rc == 0, "the child process failed (%d): a crash or a ThreadSanitizer report", rc);
    ck_assert_msg(r.setup_ok, "no sample set or no threads");
    /* the mirror set, every 12th, He's bin subset, every 8th: each made once */
    ck_assert_uint_eq(r.kept, 4);
    ck_assert_uint_eq(r.kept_mirror, 1); /* the mirror set's bin table, once */
    for (int i = 0; i < NTHREADS; i++) {
        const worker *t = &r.threaded[i], *q = &r.sequential[i];
        ck_assert_msg(t->st_context == BRDFFIT_OK && t->st_fit == BRDFFIT_OK, "thread %d: %d/%d %s",
                      i, t->st_context, t->st_fit, t->message);
        ck_assert_msg(q->st_context == BRDFFIT_OK && q->st_fit == BRDFFIT_OK,
                      "sequential %d: %d/%d %s", i, q->st_context, q->st_fit, q->message);
        ck_assert_msg(t->error == q->error, "thread %d (%s): Error %.17g, alone %.17g", i,
                      brdffit_model_get(shared_fitted[i])->name, t->error, q->error);
    }
}
END_TEST

Suite *threads_suite(void)
{
    Suite *s = suite_create("threads");
    TCase *tc = tcase_create("threads");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, first_contexts_in_four_threads);
    tcase_add_test(tc, contexts_made_and_freed_in_four_threads);
    tcase_add_test(tc, one_set_fitted_in_four_threads);
    suite_add_tcase(s, tc);
    return s;
}
