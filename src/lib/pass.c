/* pass.c -- one data pass over a sample set: the OpenCL kernel, or the same
 * maths as a plain C loop on the host.  Both return the moments of
 * kernels/bf_pass.h in double. */
#include "context.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void bf_pass_host(const brdffit_samples *samples, brdffit_model model, int nk, int np,
                  const bf_pass_par *pp, double *mom)
{
    const size_t npad = samples->npad;
    const double *f = samples->data;
    int nmom = bf_nmom(nk, np);
    for (int m = 0; m < nmom; m++)
        mom[m] = 0.0;
    bf_he_memo memo;
    memset(&memo, 0, sizeof memo);
    for (size_t i = 0; i < samples->n; i++) {
        bf_geom g = { f[BF_F_IX * npad + i], f[BF_F_IY * npad + i], f[BF_F_IZ * npad + i],
                      f[BF_F_OX * npad + i], f[BF_F_OY * npad + i], f[BF_F_OZ * npad + i],
                      f[BF_F_NH * npad + i], f[BF_F_VH * npad + i] };
        double rho[3] = { f[BF_F_R * npad + i], f[BF_F_G * npad + i], f[BF_F_B * npad + i] };
        bf_accumulate((int)model, nk, np, pp, &g, rho, f[BF_F_A2 * npad + i], mom, &memo);
    }
}

brdffit_status bf_passer_open(bf_passer *ps, brdffit_context *ctx, const brdffit_samples *samples,
                              brdffit_model model, brdffit_error *err)
{
    memset(ps, 0, sizeof *ps);
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (!mi)
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    if (!ctx || !samples)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "context or samples is NULL");
    if (samples->n == 0)
        return bf_fail(err, BRDFFIT_E_NO_SAMPLES, "the sample set is empty");
    ps->ctx = ctx;
    ps->samples = samples;
    ps->model = model;
    ps->nk = mi->chromatic ? 3 : 1;
    ps->np = bf_model_ncoords(model);
    if (ctx->backend != BRDFFIT_BACKEND_OPENCL)
        return BRDFFIT_OK;

    brdffit_status st = bf_context_kernels(ctx, model, &ps->kfull, &ps->kvalue, err);
    if (st != BRDFFIT_OK)
        return st;
    size_t nvec = samples->npad / (size_t)ctx->width;
    size_t items = (size_t)(ctx->compute_units ? ctx->compute_units : 1) * 16;
    if (items > nvec)
        items = nvec;
    ps->vec_per_item = (cl_uint)((nvec + items - 1) / items);
    ps->items = (nvec + ps->vec_per_item - 1) / ps->vec_per_item;
    ps->rows = malloc(ps->items * BF_NMOM_MAX * sizeof *ps->rows);
    if (!ps->rows)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "out of memory for the pass");
    cl_int rc;
    ps->data = clCreateBuffer(ctx->cl, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR,
                              BF_NFIELDS * samples->npad * sizeof(double), samples->data, &rc);
    if (ps->data)
        ps->par = clCreateBuffer(ctx->cl, CL_MEM_READ_ONLY, sizeof(bf_pass_par), NULL, &rc);
    if (ps->par)
        ps->out = clCreateBuffer(ctx->cl, CL_MEM_WRITE_ONLY, ps->items * BF_NMOM_MAX * sizeof(double),
                                 NULL, &rc);
    if (!ps->out) {
        bf_passer_close(ps);
        return bf_fail(err, BRDFFIT_E_OPENCL, "clCreateBuffer failed (%d)", (int)rc);
    }
    return BRDFFIT_OK;
}

static brdffit_status run_kernel(bf_passer *ps, int full, const bf_pass_par *pp, double *mom,
                                 int nmom, brdffit_error *err)
{
    brdffit_context *ctx = ps->ctx;
    cl_kernel k = full ? ps->kfull : ps->kvalue;
    cl_ulong npad = ps->samples->npad;
    cl_int rc = clEnqueueWriteBuffer(ctx->queue, ps->par, CL_FALSE, 0, sizeof *pp, pp, 0, NULL, NULL);
    rc |= clSetKernelArg(k, 0, sizeof(cl_mem), &ps->data);
    rc |= clSetKernelArg(k, 1, sizeof npad, &npad);
    rc |= clSetKernelArg(k, 2, sizeof ps->vec_per_item, &ps->vec_per_item);
    rc |= clSetKernelArg(k, 3, sizeof(cl_mem), &ps->par);
    rc |= clSetKernelArg(k, 4, sizeof(cl_mem), &ps->out);
    if (rc != CL_SUCCESS)
        return bf_fail(err, BRDFFIT_E_OPENCL, "setting the pass arguments failed (%d)", (int)rc);
    size_t global = ps->items, local = 1;
    rc = clEnqueueNDRangeKernel(ctx->queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
    if (rc != CL_SUCCESS)
        return bf_fail(err, BRDFFIT_E_OPENCL, "clEnqueueNDRangeKernel failed (%d)", (int)rc);
    rc = clEnqueueReadBuffer(ctx->queue, ps->out, CL_TRUE, 0, ps->items * nmom * sizeof(double),
                             ps->rows, 0, NULL, NULL);
    if (rc != CL_SUCCESS)
        return bf_fail(err, BRDFFIT_E_OPENCL, "reading the pass sums failed (%d)", (int)rc);
    for (int m = 0; m < nmom; m++)
        mom[m] = 0.0;
    for (size_t i = 0; i < ps->items; i++)
        for (int m = 0; m < nmom; m++)
            mom[m] += ps->rows[i * nmom + m];
    return BRDFFIT_OK;
}

brdffit_status bf_passer_run(bf_passer *ps, int full, const bf_pass_par *pp, double *mom,
                             brdffit_error *err)
{
    double t0 = bf_now();
    int np = full ? ps->np : 0;
    int nmom = bf_nmom(ps->nk, np);
    brdffit_status st = BRDFFIT_OK;
    if (ps->ctx->backend == BRDFFIT_BACKEND_OPENCL)
        st = run_kernel(ps, full, pp, mom, nmom, err);
    else
        bf_pass_host(ps->samples, ps->model, ps->nk, np, pp, mom);
    ps->seconds += bf_now() - t0;
    ps->passes++;
    if (st != BRDFFIT_OK)
        return st;
    for (int m = 0; m < nmom; m++)
        if (!isfinite(mom[m]))
            return bf_fail(err, BRDFFIT_E_FIT_FAILED, "a data pass gave a non-finite sum (moment %d)", m);
    return BRDFFIT_OK;
}

void bf_passer_close(bf_passer *ps)
{
    if (ps->out)
        clReleaseMemObject(ps->out);
    if (ps->par)
        clReleaseMemObject(ps->par);
    if (ps->data)
        clReleaseMemObject(ps->data);
    free(ps->rows);
    ps->out = ps->par = ps->data = NULL;
    ps->rows = NULL;
}
