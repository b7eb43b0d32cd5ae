/* SPDX-License-Identifier: MIT */
/* context.h -- the fitting context inside the library: OpenCL state and the
 * per-model program cache (context.c). */
#ifndef BRDFFIT_CONTEXT_H
#define BRDFFIT_CONTEXT_H

#include "internal.h"

#include <CL/cl.h>

struct brdffit_context {
    brdffit_backend backend;          /* OPENCL or HOST: the path in use */
    char describe[512];
    cl_platform_id platform;
    cl_device_id device;
    cl_context cl;
    cl_command_queue queue;
    cl_uint compute_units;
    int width;                        /* lanes per work-item vector (BF_WIDTH) */
    char cl_options[256];             /* $BRDFFIT_CL_OPTIONS when the context was made */
    brdffit_error fallback;           /* AUTO on the host path: why OpenCL was not used */
    cl_program program[BRDFFIT_MODEL_COUNT];   /* built on first use */
    cl_kernel kfull[BRDFFIT_MODEL_COUNT], kvalue[BRDFFIT_MODEL_COUNT];
    double build_seconds[BRDFFIT_MODEL_COUNT]; /* wall time of each model's build */
};

/* The two kernels of a model (bf_kernel_full, bf_kernel_value), building its
 * program on first use.  A build failure returns BRDFFIT_E_KERNEL_BUILD with
 * the build log in err. */
brdffit_status bf_context_kernels(brdffit_context *ctx, brdffit_model model, cl_kernel *full,
                                  cl_kernel *value, brdffit_error *err);

#endif /* BRDFFIT_CONTEXT_H */
