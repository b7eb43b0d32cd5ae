/* SPDX-License-Identifier: MIT */
/* pass.c -- the pass driver: a sample set bound to a context, each pass run
 * as the OpenCL kernel (enqueued here) or as bf_host_loop (pass_host.c).
 * Both return the moments of kernels/bf_layout.h in double. */
#include "pass.h"
#include "context.h"
#include "registry.h"
#include "samples.h"

#include "bf_lobe_pass.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static size_t gcd(size_t a, size_t b)
{
    while (b) {
        size_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

cl_uint bf_pass_order(size_t items)
{
    if (items <= 2)
        return 1;
    const double golden = 0.6180339887498949;
    size_t c = (size_t)(golden * (double)items + 0.5);
    for (size_t d = 0; d < items; d++) { /* the nearest integer prime to items: c - d or c + d */
        if (c > d && gcd(c - d, items) == 1)
            return (cl_uint)(c - d);
        if (c + d < items && gcd(c + d, items) == 1)
            return (cl_uint)(c + d);
    }
    return 1;
}

/* The bin table's buffers; a model without bin rows gets one small buffer
 * for all three kernel arguments (nrows 0: the kernel reads none). */
static cl_int open_bins(bf_pass_driver *dr)
{
    cl_context cl = dr->ctx->cl;
    cl_int rc = CL_SUCCESS;
    const bf_pass_bins *b = &dr->bins;
    if (!b->table) {
        dr->bhd = clCreateBuffer(cl, CL_MEM_READ_WRITE, 8 * sizeof(double), NULL, &rc);
        return rc;
    }
    dr->bhd = clCreateBuffer(cl, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR,
                            dr->samples->npad * sizeof(double), (void *)(uintptr_t)b->hd, &rc);
    if (dr->bhd)
        dr->btable = clCreateBuffer(cl, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR,
                                   (size_t)BF_BFIELDS * BF_NHD_PAD * sizeof(double),
                                   (void *)(uintptr_t)b->table, &rc);
    if (dr->btable)
        dr->brows = clCreateBuffer(cl, CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR,
                                   (size_t)BF_BK_FIELDS * (size_t)b->nrows * sizeof(double), b->rows,
                                   &rc);
    return rc;
}

brdffit_status bf_driver_open(bf_pass_driver *dr, brdffit_context *ctx,
                              const brdffit_samples *samples, brdffit_model model,
                              brdffit_error *err)
{
    memset(dr, 0, sizeof *dr);
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (!mi)
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    if (!bf_model_has_lobe(model))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s has no lobe K: no data pass (a glTF model's fit solves its colours "
                       "on the host)", mi->name);
    if (!ctx || !samples)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "context or samples is NULL");
    if (samples->n == 0)
        return bf_fail(err, BRDFFIT_E_NO_SAMPLES, "the sample set is empty");
    dr->ctx = ctx;
    dr->samples = samples;
    dr->model = model;
    dr->nk = mi->chromatic ? 3 : 1;
    dr->np = bf_model_ncoords(model);
    const int with_rows = bf_lobe_has_own_fd((int)model);
    if (ctx->backend != BRDFFIT_BACKEND_OPENCL)
        return with_rows ? bf_pass_bins_make(samples, 1, &dr->bins, err) : BRDFFIT_OK;

    int built = ctx->program[model] != NULL;
    brdffit_status st = bf_context_kernels(ctx, model, &dr->kfull, &dr->kvalue, err);
    if (st != BRDFFIT_OK)
        return st;
    if (!built)
        dr->seconds_build = ctx->build_seconds[model];
    size_t nvec = samples->npad / (size_t)ctx->width;
    size_t items = (size_t)(ctx->compute_units ? ctx->compute_units : 1) * 16;
    if (items > nvec)
        items = nvec;
    dr->vec_per_item = (cl_uint)((nvec + items - 1) / items);
    dr->items = (nvec + dr->vec_per_item - 1) / dr->vec_per_item;
    dr->order = bf_pass_order(dr->items);
    dr->rows = malloc(dr->items * BF_NMOM_MAX * sizeof *dr->rows);
    if (!dr->rows)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "out of memory for the pass");
    if (with_rows) {
        st = bf_pass_bins_make(samples, (int)dr->items * ctx->width, &dr->bins, err);
        if (st != BRDFFIT_OK)
            return st;
    }
    cl_int rc;
    dr->data = clCreateBuffer(ctx->cl, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR,
                              BF_NFIELDS * samples->npad * sizeof(double), samples->data, &rc);
    if (dr->data)
        dr->par = clCreateBuffer(ctx->cl, CL_MEM_READ_ONLY, sizeof(bf_pass_par), NULL, &rc);
    if (dr->par)
        dr->out = clCreateBuffer(ctx->cl, CL_MEM_WRITE_ONLY, dr->items * BF_NMOM_MAX * sizeof(double),
                                 NULL, &rc);
    if (dr->out)
        rc = open_bins(dr);
    if (rc != CL_SUCCESS) {
        bf_driver_close(dr);
        return bf_fail(err, BRDFFIT_E_OPENCL, "clCreateBuffer failed (%d)", (int)rc);
    }
    return BRDFFIT_OK;
}

static brdffit_status run_kernel(bf_pass_driver *dr, int full, const bf_pass_par *pp, double *mom,
                                 int nmom, brdffit_error *err)
{
    brdffit_context *ctx = dr->ctx;
    cl_kernel k = full ? dr->kfull : dr->kvalue;
    cl_ulong npad = dr->samples->npad;
    /* pp with the rows' floor, made here once for every work-item; the
     * write may read q until the queue is finished (the blocking read below,
     * or clFinish on a failure) */
    bf_pass_par q = *pp;
    if (dr->bins.table)
        bf_lobe_row_floor((int)dr->model, q.p[0], q.lam, q.row_floor);
    cl_int rc = clEnqueueWriteBuffer(ctx->queue, dr->par, CL_FALSE, 0, sizeof q, &q, 0, NULL, NULL);
    rc |= clSetKernelArg(k, 0, sizeof(cl_mem), &dr->data);
    rc |= clSetKernelArg(k, 1, sizeof npad, &npad);
    rc |= clSetKernelArg(k, 2, sizeof dr->vec_per_item, &dr->vec_per_item);
    rc |= clSetKernelArg(k, 3, sizeof(cl_mem), &dr->par);
    rc |= clSetKernelArg(k, 4, sizeof(cl_mem), &dr->out);
    cl_int nrows = dr->bins.table ? dr->bins.nrows : 0;
    rc |= clSetKernelArg(k, 5, sizeof(cl_mem), &dr->bhd);
    rc |= clSetKernelArg(k, 6, sizeof(cl_mem), dr->btable ? &dr->btable : &dr->bhd);
    rc |= clSetKernelArg(k, 7, sizeof(cl_mem), dr->brows ? &dr->brows : &dr->bhd);
    rc |= clSetKernelArg(k, 8, sizeof nrows, &nrows);
    rc |= clSetKernelArg(k, 9, sizeof dr->order, &dr->order);
    if (rc != CL_SUCCESS) {
        clFinish(ctx->queue);
        return bf_fail(err, BRDFFIT_E_OPENCL, "setting the pass arguments failed (%d)", (int)rc);
    }
    size_t global = dr->items, local = 1;
    rc = clEnqueueNDRangeKernel(ctx->queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
    if (rc != CL_SUCCESS) {
        clFinish(ctx->queue);
        return bf_fail(err, BRDFFIT_E_OPENCL, "clEnqueueNDRangeKernel failed (%d)", (int)rc);
    }
    rc = clEnqueueReadBuffer(ctx->queue, dr->out, CL_TRUE, 0, dr->items * nmom * sizeof(double),
                             dr->rows, 0, NULL, NULL);
    if (rc != CL_SUCCESS)
        return bf_fail(err, BRDFFIT_E_OPENCL, "reading the pass sums failed (%d)", (int)rc);
    for (int m = 0; m < nmom; m++)
        mom[m] = 0.0;
    for (size_t i = 0; i < dr->items; i++)
        for (int m = 0; m < nmom; m++)
            mom[m] += dr->rows[i * nmom + m];
    return BRDFFIT_OK;
}

brdffit_status bf_driver_run(bf_pass_driver *dr, int full, const bf_pass_par *pp, double *mom,
                             brdffit_error *err)
{
    double t0 = bf_now();
    int np = full ? dr->np : 0;
    int nmom = bf_nmom(dr->nk, np);
    brdffit_status st = BRDFFIT_OK;
    if (dr->ctx->backend == BRDFFIT_BACKEND_OPENCL)
        st = run_kernel(dr, full, pp, mom, nmom, err);
    else
        bf_host_loop(dr->samples, &dr->bins, dr->model, dr->nk, np, pp, mom);
    dr->seconds += bf_now() - t0;
    dr->passes++;
    if (st != BRDFFIT_OK)
        return st;
    for (int c = 0; c < 3; c++) /* a mirror set's pairs (samples_mirror.c) */
        mom[bf_mom_chan(c, dr->nk, np) + BF_MC_SEE] += dr->samples->pair_see[c];
    for (int m = 0; m < nmom; m++)
        if (!isfinite(mom[m]))
            return bf_fail(err, BRDFFIT_E_FIT_FAILED, "a data pass gave a non-finite sum (moment %d)", m);
    return BRDFFIT_OK;
}

void bf_driver_close(bf_pass_driver *dr)
{
    cl_mem *bufs[3] = { &dr->bhd, &dr->btable, &dr->brows };
    for (int i = 0; i < 3; i++)
        if (*bufs[i])
            clReleaseMemObject(*bufs[i]);
    dr->bhd = dr->btable = dr->brows = NULL;
    bf_pass_bins_free(&dr->bins);
    if (dr->out)
        clReleaseMemObject(dr->out);
    if (dr->par)
        clReleaseMemObject(dr->par);
    if (dr->data)
        clReleaseMemObject(dr->data);
    free(dr->rows);
    dr->out = dr->par = dr->data = NULL;
    dr->rows = NULL;
}
