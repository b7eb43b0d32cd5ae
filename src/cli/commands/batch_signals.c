/* SPDX-License-Identifier: MIT */
/* batch_signals.c -- SIGINT and SIGTERM during a batch: taken by one thread,
 * they stop the batch after the fit in progress. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

/* SIGINT and SIGTERM are blocked in every thread (PoCL's included: they are
 * made after this) and taken by one thread with sigwait, so that no library
 * call is interrupted: the fit in progress finishes and is journaled, then the
 * batch stops.  A second signal stops the program at once (the journal is
 * whole up to its last synced record; a torn line is ignored next time). */
_Atomic int batch_stop_signal = 0;

static void *signal_waiter(void *arg)
{
    const sigset_t *set = arg;
    for (;;) {
        int sig = 0;
        if (sigwait(set, &sig) != 0)
            continue;
        if (batch_stop_signal)
            _exit(128 + sig);
        batch_stop_signal = sig;
    }
    return NULL;
}

void batch_install_signals(void)
{
    static sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_t t;
    if (pthread_sigmask(SIG_BLOCK, &set, NULL) == 0 &&
        pthread_create(&t, NULL, signal_waiter, &set) == 0)
        pthread_detach(t);
    /* a file-size limit then makes a write fail with EFBIG, reported like a full disk */
    signal(SIGXFSZ, SIG_IGN);
}
