/* SPDX-License-Identifier: MIT */
/* affine_pool.c -- the threads of the affine engine's passes (affine.h): a
 * process-wide set of workers that sleep between passes.  A pass wakes them
 * and waits for them: a woken thread that has slept runs promptly on a
 * machine busy with other work, where a thread made for each pass waits
 * behind the others for its first turn.  One pass at a time uses the
 * workers; a pass that finds them in use, or a process that cannot make
 * them, runs its jobs in the calling thread.  The workers are made again in
 * a child process after fork (they are not copied). */
#define _DEFAULT_SOURCE
#include "affine.h"

#include <pthread.h>
#include <unistd.h>

static struct {
    pthread_mutex_t mu;
    pthread_cond_t go, done;
    pid_t pid;          /* the process the workers run in (0: none yet) */
    void (*fn)(void *);
    char *jobs;
    size_t size;        /* bytes a job */
    int njobs, next, pending;
} pool = { PTHREAD_MUTEX_INITIALIZER, PTHREAD_COND_INITIALIZER, PTHREAD_COND_INITIALIZER,
           0, NULL, NULL, 0, 0, 0, 0 };
static pthread_mutex_t pool_use = PTHREAD_MUTEX_INITIALIZER;

static void *worker(void *arg)
{
    (void)arg;
    pthread_mutex_lock(&pool.mu);
    for (;;) {
        while (pool.next >= pool.njobs)
            pthread_cond_wait(&pool.go, &pool.mu);
        int k = pool.next++;
        void (*fn)(void *) = pool.fn;
        void *job = pool.jobs + (size_t)k * pool.size;
        pthread_mutex_unlock(&pool.mu);
        fn(job);
        pthread_mutex_lock(&pool.mu);
        if (--pool.pending == 0)
            pthread_cond_signal(&pool.done);
    }
    return NULL;
}

/* Make nw workers in this process, once; 0 when none could be made. */
static int start_workers(int nw)
{
    if (pool.pid == getpid())
        return 1;
    pool.next = pool.njobs = pool.pending = 0;
    int made = 0;
    pthread_attr_t at;
    if (pthread_attr_init(&at) != 0)
        return 0;
    pthread_attr_setdetachstate(&at, PTHREAD_CREATE_DETACHED);
    for (int k = 0; k < nw; k++) {
        pthread_t t;
        if (pthread_create(&t, &at, worker, NULL) == 0)
            made++;
    }
    pthread_attr_destroy(&at);
    if (made > 0)
        pool.pid = getpid();
    return made > 0;
}

void bf_affine_run(void (*fn)(void *), void *jobs, size_t size, int njobs, int nworkers)
{
    char *j = jobs;
    if (njobs <= 1 || pthread_mutex_trylock(&pool_use) != 0) {
        for (int k = 0; k < njobs; k++)
            fn(j + (size_t)k * size);
        return;
    }
    pthread_mutex_lock(&pool.mu);
    if (!start_workers(nworkers)) {
        pthread_mutex_unlock(&pool.mu);
        pthread_mutex_unlock(&pool_use);
        for (int k = 0; k < njobs; k++)
            fn(j + (size_t)k * size);
        return;
    }
    pool.fn = fn;
    pool.jobs = j;
    pool.size = size;
    pool.next = 0;
    pool.pending = njobs;
    pool.njobs = njobs;
    pthread_cond_broadcast(&pool.go);
    while (pool.pending > 0)
        pthread_cond_wait(&pool.done, &pool.mu);
    pool.njobs = 0;
    pthread_mutex_unlock(&pool.mu);
    pthread_mutex_unlock(&pool_use);
}
