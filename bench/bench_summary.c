/* SPDX-License-Identifier: MIT */
/* bench_summary.c -- see bench_summary.h. */
#include "bench_summary.h"

#include <stdio.h>

void bench_summary_print(const bench_summary *s)
{
    int any = 0;
    for (int m = 0; m < brdffit_model_count(); m++)
        any |= s->fit_seconds[m] > 0;
    if (!any)
        return;
    printf("\nfigures for README: one complete fit per model on alum-bronze (part 2, the fastest\n"
           "run), its data passes, and a full pass at the typical start / the streaming read (part 1)\n");
    printf("%-18s %9s %7s %10s\n", "model", "fit s", "passes", "full/read");
    for (int m = 0; m < brdffit_model_count(); m++) {
        if (!(s->fit_seconds[m] > 0))
            continue;
        printf("%-18s %9.3f %7d", brdffit_model_get((brdffit_model)m)->name, s->fit_seconds[m],
               s->passes[m]);
        if (s->full_per_read[m] > 0)
            printf(" %9.2fx", s->full_per_read[m]);
        printf("\n");
    }
    if (s->he_per_ct > 0)
        printf("he fit / cook-torrance fit: %.1fx\n", s->he_per_ct);
}
