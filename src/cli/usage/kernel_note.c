/* SPDX-License-Identifier: MIT */
/* kernel_note.c -- on a terminal, a line on stderr while a model's OpenCL
 * kernels are built, so that the wait of a first fit is explained: PoCL
 * compiles them once per machine (tens of seconds) and loads them from its
 * cache after.  The library says whether a model's kernels are built in a
 * context and how long building them took (brdffit_context_build_seconds);
 * where PoCL caches them is $POCL_CACHE_DIR, which a context sets when it is
 * unset.  Nothing is printed when the stream is not a terminal. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <stdlib.h>
#include <unistd.h>

/* A build at least this long was a compilation: its line stays, with the time. */
#define COMPILED_SECONDS 1.0

int kernel_note_begin(FILE *f, const brdffit_context *ctx, brdffit_model model)
{
    if (!isatty(fileno(f)) || brdffit_context_backend(ctx) != BRDFFIT_BACKEND_OPENCL ||
        brdffit_context_build_seconds(ctx, model) > 0)
        return 0;
    const char *cache = getenv("POCL_CACHE_DIR");
    fprintf(f, "\r\033[Kbrdffit: compiling the OpenCL kernels of %s, once per machine (cached in ",
            brdffit_model_get(model)->name);
    plain_string(f, cache && *cache ? cache : "PoCL's cache");
    fputs(")...", f);
    fflush(f);
    return 1;
}

void kernel_note_end(FILE *f, int shown, const brdffit_context *ctx, brdffit_model model)
{
    if (!shown)
        return;
    double s = brdffit_context_build_seconds(ctx, model);
    if (s >= COMPILED_SECONDS)
        fprintf(f, " %.0f s\n", s);
    else
        fputs("\r\033[K", f); /* loaded from the cache, or failed: the line goes */
    fflush(f);
}
