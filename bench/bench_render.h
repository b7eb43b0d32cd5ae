/* SPDX-License-Identifier: MIT */
/* bench_render.h -- part 5 of `make bench`: a material's renders and plots (bench_render.c). */
#ifndef BRDFFIT_BENCH_RENDER_H
#define BRDFFIT_BENCH_RENDER_H

/* Time the reference and every model's render (256^2, default lights), every
 * model's plot, all the material's files, and the environment renders
 * (128^2, 256 samples); print them.  0 or 1. */
int bench_renders(int quick);

#endif
