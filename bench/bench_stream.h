/* SPDX-License-Identifier: MIT */
/* bench_stream.h -- part 1 of `make bench`: the memory-bandwidth bound of a
 * data pass (bench_stream.c). */
#ifndef BRDFFIT_BENCH_STREAM_H
#define BRDFFIT_BENCH_STREAM_H

#include "pass.h"

/* A plain streaming read of a pass's sample buffer: an OpenCL kernel that
 * loads every field of every sample of dr->data (BF_NFIELDS x npad doubles),
 * in the same vectors, work-items and runs of vectors as the pass, and sums
 * each field; the host checks the sums against its own. */
typedef struct bench_stream {
    cl_program prog;
    cl_kernel kernel;
    cl_mem out;
    size_t items;                     /* work-items of a streaming pass   */
    double *rows;                     /* items x BF_NFIELDS sums read back */
    double ref[BF_NFIELDS], scale[BF_NFIELDS]; /* host sums, and sums of |x| */
} bench_stream;

/* Build the kernel on ctx (OpenCL) for passes of `items` work-items over s,
 * and take the host sums.  0, or -1 after printing why; bench_stream_close
 * in any case. */
int bench_stream_open(bench_stream *bs, const brdffit_context *ctx, const brdffit_samples *s,
                      size_t items);
/* One streaming pass over the buffer of dr (a driver of the same context,
 * samples and work-items): its wall time in *seconds; 0 when every field's sum
 * equals the host's (to 1e-9 of its sum of |x|), -1 (printed) otherwise. */
int bench_stream_run(bench_stream *bs, const bf_pass_driver *dr, double *seconds);
void bench_stream_close(bench_stream *bs);

/* The host's own figures on the same bytes (single thread): the fastest of
 * reps memcpy's of the buffer into another, and sums of all of it. */
int bench_host_memory(const brdffit_samples *s, int reps, double *copy_s, double *sum_s);

#endif
