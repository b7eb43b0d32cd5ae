/* SPDX-License-Identifier: MIT */
/* pass.h -- the host side of a data pass.  A pass computes the moments of
 * kernels/bf_layout.h over a sample set at one point bf_pass_par; it runs
 * either as the OpenCL kernel (kernels/bf_pass.cl, enqueued by the driver)
 * or as the plain C loop bf_host_loop.  The driver (pass.c) binds a sample
 * set to a context for a series of passes and picks between them by the
 * context's backend. */
#ifndef BRDFFIT_PASS_H
#define BRDFFIT_PASS_H

#include "internal.h"

#include <CL/cl.h>

#include "bf_layout.h"

/* A sample set bound to a context for a series of passes of one model. */
typedef struct bf_pass_driver {
    brdffit_context *ctx;
    const brdffit_samples *samples;
    brdffit_model model;
    int nk, np;                       /* lobes (1|3) and lobe coordinates   */
    cl_kernel kfull, kvalue;
    cl_mem data, par, out;
    size_t items;                     /* work-items per pass               */
    cl_uint vec_per_item;
    double *rows;                     /* items x BF_NMOM_MAX, host side    */
    double seconds;                   /* time spent in passes              */
    double seconds_build;             /* of the kernels, when open built them */
    int passes;
} bf_pass_driver;

/* Bind samples to ctx for passes of model (on OpenCL: the model's kernels,
 * built here when the context has not built them yet (their build time in
 * seconds_build, else 0), and the buffers).
 * Call bf_driver_close afterwards whatever this returns. */
brdffit_status bf_driver_open(bf_pass_driver *dr, brdffit_context *ctx,
                              const brdffit_samples *samples, brdffit_model model,
                              brdffit_error *err);
/* One pass at pp: mom[bf_nmom(nk, full ? np : 0)] in double.  Non-finite sums
 * give BRDFFIT_E_FIT_FAILED. */
brdffit_status bf_driver_run(bf_pass_driver *dr, int full, const bf_pass_par *pp, double *mom,
                             brdffit_error *err);
void bf_driver_close(bf_pass_driver *dr);

/* Sample i of samples added to mom by bf_accumulate (kernels/bf_pass.h),
 * with the pass state ps (a run's, or NULL: no memos): what bf_host_loop
 * does for each sample. */
struct bf_pass_state;
void bf_host_sample(const brdffit_samples *samples, size_t i, brdffit_model model, int nk,
                    int np, const bf_pass_par *pp, double *mom, struct bf_pass_state *ps);

/* The plain single-threaded C loop over the samples (the host backend, and
 * the reference the kernel is tested and benchmarked against). */
void bf_host_loop(const brdffit_samples *samples, brdffit_model model, int nk, int np,
                  const bf_pass_par *pp, double *mom);

#endif /* BRDFFIT_PASS_H */
