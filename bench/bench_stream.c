/* SPDX-License-Identifier: MIT */
/* bench_stream.c -- `make bench` part 1's bound: how fast the device can read
 * the bytes a data pass reads.  The streaming kernel below walks a pass's
 * sample buffer exactly as bf_pass.cl does (BF_WIDTH-wide vloads of the
 * BF_NFIELDS fields, one contiguous run of vectors per work-item, the
 * driver's work-item count, run length and order of runs (work-item gid
 * takes run gid * order mod items: bf_pass_order), work-groups of 1) and does
 * nothing with them but add them up per field, so its time is the memory
 * (and load) bound of a pass.  Each sum is checked against the host's: the
 * loads cannot be optimised away and a wrong walk is caught (to 1e-9 of the
 * field's sum of |x|: the two add ~1e6 terms in different orders; one vector
 * missed or read twice would be ~1e-5).  The twelve sums are twelve named
 * vectors, not an array: PoCL keeps an array's in memory, and such a walk
 * reads about half as fast, slower than the value passes it is meant to
 * bound (docs/performance.md). */
#define _POSIX_C_SOURCE 200809L
#include "bench_stream.h"
#include "context.h"
#include "samples.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char stream_source[] =
    "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n"
    "#if BF_WIDTH == 8\n"
    "typedef double8 vec;\n"
    "#define VLOAD vload8\n"
    "#define HSUM(v) ((((v).s0 + (v).s1) + ((v).s2 + (v).s3)) + (((v).s4 + (v).s5) + ((v).s6 + (v).s7)))\n"
    "#else\n"
    "typedef double4 vec;\n"
    "#define VLOAD vload4\n"
    "#define HSUM(v) (((v).s0 + (v).s1) + ((v).s2 + (v).s3))\n"
    "#endif\n"
    "#if NFIELDS != 12\n"
    "#error \"bf_stream sums 12 fields: the pass layout (bf_layout.h) changed\"\n"
    "#endif\n"
    "__kernel void bf_stream(__global const double *data, const ulong npad, const uint vec_per_item,\n"
    "                        __global double *out, const uint order)\n"
    "{\n"
    "    const uint run = (uint)(((ulong)get_global_id(0) * order) % get_global_size(0));\n"
    "    vec a0 = (vec)(0.0), a1 = a0, a2 = a0, a3 = a0, a4 = a0, a5 = a0, a6 = a0, a7 = a0, a8 = a0, a9 = a0, a10 = a0, a11 = a0;\n"
    "    const ulong nvec = npad / BF_WIDTH;\n"
    "    const ulong v0 = (ulong)run * vec_per_item, v1 = min(v0 + vec_per_item, nvec);\n"
    "    for (ulong v = v0; v < v1; v++) {\n"
    "        a0 += VLOAD(v, data); a1 += VLOAD(v, data + npad); a2 += VLOAD(v, data + 2 * npad);\n"
    "        a3 += VLOAD(v, data + 3 * npad); a4 += VLOAD(v, data + 4 * npad); a5 += VLOAD(v, data + 5 * npad);\n"
    "        a6 += VLOAD(v, data + 6 * npad); a7 += VLOAD(v, data + 7 * npad); a8 += VLOAD(v, data + 8 * npad);\n"
    "        a9 += VLOAD(v, data + 9 * npad); a10 += VLOAD(v, data + 10 * npad); a11 += VLOAD(v, data + 11 * npad);\n"
    "    }\n"
    "    __global double *o = out + (ulong)run * NFIELDS;\n"
    "    o[0] = HSUM(a0); o[1] = HSUM(a1); o[2] = HSUM(a2); o[3] = HSUM(a3); o[4] = HSUM(a4); o[5] = HSUM(a5);\n"
    "    o[6] = HSUM(a6); o[7] = HSUM(a7); o[8] = HSUM(a8); o[9] = HSUM(a9); o[10] = HSUM(a10); o[11] = HSUM(a11);\n"
    "}\n";

void bench_stream_close(bench_stream *bs)
{
    if (bs->out)
        clReleaseMemObject(bs->out);
    if (bs->kernel)
        clReleaseKernel(bs->kernel);
    if (bs->prog)
        clReleaseProgram(bs->prog);
    free(bs->rows);
    memset(bs, 0, sizeof *bs);
}

int bench_stream_open(bench_stream *bs, const brdffit_context *ctx, const brdffit_samples *s,
                      size_t items)
{
    memset(bs, 0, sizeof *bs);
    if (ctx->backend != BRDFFIT_BACKEND_OPENCL) {
        fprintf(stderr, "bench: the streaming read needs an OpenCL context\n");
        return -1;
    }
    bs->items = items;
    const char *src = stream_source;
    cl_int rc;
    bs->prog = clCreateProgramWithSource(ctx->cl, 1, &src, NULL, &rc);
    char opts[128];
    snprintf(opts, sizeof opts, "-cl-std=CL1.2 -DBF_WIDTH=%d -DNFIELDS=%d", ctx->width, (int)BF_NFIELDS);
    if (bs->prog)
        rc = clBuildProgram(bs->prog, 1, &ctx->device, opts, NULL, NULL);
    if (rc == CL_SUCCESS)
        bs->kernel = clCreateKernel(bs->prog, "bf_stream", &rc);
    if (bs->kernel)
        bs->out = clCreateBuffer(ctx->cl, CL_MEM_WRITE_ONLY, items * BF_NFIELDS * sizeof(double), NULL,
                                 &rc);
    bs->rows = malloc(items * BF_NFIELDS * sizeof *bs->rows);
    if (!bs->out || !bs->rows) {
        fprintf(stderr, "bench: setting up the streaming kernel failed (%d)\n", (int)rc);
        return -1;
    }
    for (int f = 0; f < BF_NFIELDS; f++) {
        const double *x = s->data + (size_t)f * s->npad;
        double sum = 0.0, mag = 0.0;
        for (size_t i = 0; i < s->npad; i++)
            sum += x[i], mag += fabs(x[i]);
        bs->ref[f] = sum;
        bs->scale[f] = mag;
    }
    return 0;
}

int bench_stream_run(bench_stream *bs, const bf_pass_driver *dr, double *seconds)
{
    const brdffit_context *ctx = dr->ctx;
    cl_ulong npad = dr->samples->npad;
    cl_uint vpi = dr->vec_per_item;
    if (dr->items != bs->items || !dr->data) {
        fprintf(stderr, "bench: the streaming kernel was set up for another pass layout\n");
        return -1;
    }
    double t0 = bf_now();
    cl_int rc = clSetKernelArg(bs->kernel, 0, sizeof(cl_mem), &dr->data);
    rc |= clSetKernelArg(bs->kernel, 1, sizeof npad, &npad);
    rc |= clSetKernelArg(bs->kernel, 2, sizeof vpi, &vpi);
    rc |= clSetKernelArg(bs->kernel, 3, sizeof(cl_mem), &bs->out);
    rc |= clSetKernelArg(bs->kernel, 4, sizeof dr->order, &dr->order);
    size_t global = dr->items, local = 1;
    if (rc == CL_SUCCESS)
        rc = clEnqueueNDRangeKernel(ctx->queue, bs->kernel, 1, NULL, &global, &local, 0, NULL, NULL);
    if (rc == CL_SUCCESS)
        rc = clEnqueueReadBuffer(ctx->queue, bs->out, CL_TRUE, 0, dr->items * BF_NFIELDS * sizeof(double),
                                 bs->rows, 0, NULL, NULL);
    double sum[BF_NFIELDS] = { 0 };
    for (size_t i = 0; rc == CL_SUCCESS && i < dr->items; i++)
        for (int f = 0; f < BF_NFIELDS; f++)
            sum[f] += bs->rows[i * BF_NFIELDS + f];
    *seconds = bf_now() - t0;
    if (rc != CL_SUCCESS) {
        fprintf(stderr, "bench: the streaming kernel failed (%d)\n", (int)rc);
        return -1;
    }
    for (int f = 0; f < BF_NFIELDS; f++)
        if (!(fabs(sum[f] - bs->ref[f]) <= 1e-9 * bs->scale[f])) {
            fprintf(stderr, "bench: the streaming kernel's sum of field %d is %.17g, the host's %.17g\n", f,
                    sum[f], bs->ref[f]);
            return -1;
        }
    return 0;
}

int bench_host_memory(const brdffit_samples *s, int reps, double *copy_s, double *sum_s)
{
    size_t n = (size_t)BF_NFIELDS * s->npad;
    double *dst = malloc(n * sizeof *dst);
    if (!dst) {
        fprintf(stderr, "bench: out of memory\n");
        return -1;
    }
    memset(dst, 0, n * sizeof *dst); /* pages mapped before the timing */
    *copy_s = *sum_s = 1e30;
    double check = 0.0;
    for (int r = 0; r < reps; r++) {
        double t0 = bf_now();
        memcpy(dst, s->data, n * sizeof *dst);
        *copy_s = fmin(*copy_s, bf_now() - t0);
        /* eight accumulators: the adds' latency does not bound the loop */
        double acc[8] = { 0 };
        t0 = bf_now();
        for (size_t i = 0; i + 8 <= n; i += 8)
            for (int k = 0; k < 8; k++)
                acc[k] += s->data[i + k];
        *sum_s = fmin(*sum_s, bf_now() - t0);
        check = dst[n / 2] + acc[0] + acc[1] + acc[2] + acc[3] + acc[4] + acc[5] + acc[6] + acc[7];
    }
    free(dst);
    return isfinite(check) ? 0 : -1; /* uses both results */
}
