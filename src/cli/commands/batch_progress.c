/* SPDX-License-Identifier: MIT */
/* batch_progress.c -- a batch's progress on stderr: a live line on a
 * terminal, else one line per material. */
#define _POSIX_C_SOURCE 200809L
#include "batch_run.h"

#include <math.h>

double batch_now(void)
{
    return brdffit_seconds();
}
static void hms(char *buf, size_t len, double s)
{
    if (!isfinite(s) || s < 0)
        snprintf(buf, len, "--:--");
    else if (s >= 3600)
        snprintf(buf, len, "%d:%02d:%02d", (int)(s / 3600), (int)fmod(s / 60, 60), (int)fmod(s, 60));
    else
        snprintf(buf, len, "%d:%02d", (int)(s / 60), (int)fmod(s, 60));
}

void batch_progress_live(progress *P, int i, int n, const char *material, const char *model)
{
    if (P->quiet || !P->live)
        return;
    char el[32], eta[32];
    double elapsed = batch_now() - P->t0;
    double per = P->fitted_now ? P->fit_seconds / P->fitted_now : NAN;
    hms(el, sizeof el, elapsed);
    hms(eta, sizeof eta, per * (P->total_fits - P->done_fits));
    fprintf(stderr, "\r\033[K[%d/%d] ", i + 1, n);
    plain_string(stderr, material);
    fprintf(stderr, " %s  fits %d/%d  %s elapsed  ETA %s", model, P->done_fits, P->total_fits, el, eta);
    fflush(stderr);
}

void batch_progress_material(progress *P, int i, int n, const char *material, const char *what)
{
    if (P->quiet)
        return;
    char el[32];
    hms(el, sizeof el, batch_now() - P->t0);
    if (P->live)
        fputs("\r\033[K", stderr);
    fprintf(stderr, "[%d/%d] ", i + 1, n);
    plain_string(stderr, material);
    fprintf(stderr, ": %s (fits %d/%d, %s)\n", what, P->done_fits, P->total_fits, el);
}
