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

/* The bin table of a sample set (BF_B_* in kernels/bf_he_rows.h) and room for a pass's
 * bin rows, for a model whose pass makes them (He); all NULL: none. */
typedef struct bf_pass_bins {
    const double *hd;    /* npad: each sample's bin hd (padding: the last one's) */
    const double *table; /* BF_BFIELDS x BF_NHD_PAD                             */
    double *rows;        /* BF_BK_FIELDS x nrows: the host loop's rows          */
    int nrows;           /* rows per field: room for row_runs runs of bins      */
} bf_pass_bins;

/* The bin table of s, with nrows for row_runs runs of bins (the kernel's
 * work-items; 1 for the host loop).  hd and table are kept with s (made by
 * the first driver of s that asks: bf_derived_get) and live as long as s;
 * rows are b's own, freed by bf_pass_bins_free. */
brdffit_status bf_pass_bins_make(const brdffit_samples *s, int row_runs, bf_pass_bins *b,
                                 brdffit_error *err);
void bf_pass_bins_free(bf_pass_bins *b);
/* s's bin table made now (and kept with s) if it was not. */
brdffit_status bf_pass_bins_prepare(const brdffit_samples *s, brdffit_error *err);

/* A sample set bound to a context for a series of passes of one model. */
typedef struct bf_pass_driver {
    brdffit_context *ctx;
    const brdffit_samples *samples;
    brdffit_model model;
    int nk, np;                       /* lobes (1|3) and lobe coordinates   */
    cl_kernel kfull, kvalue;
    cl_mem data, par, out;
    bf_pass_bins bins;                /* the bin table (models with bin rows) */
    cl_mem bhd, btable, brows;        /* its buffers (or one small stand-in) */
    size_t items;                     /* work-items per pass               */
    cl_uint vec_per_item;
    cl_uint order;                    /* work-item gid takes run gid * order
                                       * mod items (bf_pass_order)          */
    double *rows;                     /* items x BF_NMOM_MAX, host side    */
    double seconds;                   /* time spent in passes              */
    double seconds_build;             /* of the kernels, when open built them */
    int passes;
} bf_pass_driver;

/* The stride in which a pass's work-items take the runs of samples: work-item
 * gid takes run (gid * order) mod items, and writes its sums to that run's
 * row, so the host adds the rows in run order whatever the order (the sums
 * are the same to the bit).  PoCL's pthread device deals a kernel's
 * work-groups to its threads in contiguous chunks, the first holding about
 * half of them (guided: 1 + remaining / threads); a He pass's runs at small
 * theta_h make most of the bin rows, so in run order one thread took most of
 * the rows while the other waited.  order is the integer nearest
 * items (sqrt(5) - 1) / 2 that is prime to items (1 for items <= 2), so any
 * contiguous chunk of work-items takes runs spread over the whole table
 * (He's stride-subset passes the most shortened: docs/performance.md). */
cl_uint bf_pass_order(size_t items);

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

/* What bf_host_loop does: a run's pass state ps cleared and, with bins
 * (NULL or a table of NULLs: none), the model's bin rows made into it at pp
 * (bf_host_begin); then each sample i added to mom by bf_accumulate
 * (kernels/bf_pass.h) with ps (NULL: no memos, no rows) and its bin
 * (bf_host_sample). */
struct bf_pass_state;
void bf_host_begin(const brdffit_samples *samples, const bf_pass_bins *bins, brdffit_model model,
                   int np, const bf_pass_par *pp, struct bf_pass_state *ps);
void bf_host_sample(const brdffit_samples *samples, const bf_pass_bins *bins, size_t i,
                    brdffit_model model, int nk, int np, const bf_pass_par *pp, double *mom,
                    struct bf_pass_state *ps);

/* The plain single-threaded C loop over the samples (the host backend, and
 * the reference the kernel is tested and benchmarked against); with bins
 * (NULL or a table of NULLs: none) the model's bin rows, as the kernel
 * makes them. */
void bf_host_loop(const brdffit_samples *samples, const bf_pass_bins *bins, brdffit_model model,
                  int nk, int np, const bf_pass_par *pp, double *mom);

#endif /* BRDFFIT_PASS_H */
