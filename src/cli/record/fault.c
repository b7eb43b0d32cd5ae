/* SPDX-License-Identifier: MIT */
/* fault.c -- fault injection for the tests of the batch: with
 * BRDFFIT_FAULT=POINT:N in the environment, the N-th time the program passes
 * POINT it is killed (SIGKILL) there, as a power cut or `kill -9` would.
 * Points: "record" (after a journal record is written and synced), "torn" (in
 * the middle of writing a journal record), "page" (after a page of the report),
 * "asset" (after the renders and plots of a material, before their record).
 * Compiled in only with -DBRDFFIT_FAULTS (build/brdffit-faults, the tests'
 * build of the program); otherwise batch.h makes the hooks no-ops. */
#define _POSIX_C_SOURCE 200809L
#include "batch.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>

#ifdef BRDFFIT_FAULTS
int cli_fault_hit(const char *point)
{
    static int count; /* passes of the configured point */
    const char *f = getenv("BRDFFIT_FAULT");
    size_t n = strlen(point);
    if (!f || strncmp(f, point, n) != 0 || f[n] != ':')
        return 0;
    return ++count == atoi(f + n + 1);
}

void cli_fault_point(const char *point)
{
    if (cli_fault_hit(point))
        raise(SIGKILL);
}
#endif
