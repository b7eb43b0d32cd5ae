/* context.h -- the fitting context (OpenCL state, program cache) and the data
 * pass it runs, shared by context.c, pass.c and fit.c. */
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
    cl_program program[BRDFFIT_MODEL_COUNT];   /* built on first use */
    cl_kernel kfull[BRDFFIT_MODEL_COUNT], kvalue[BRDFFIT_MODEL_COUNT];
};

/* Lobe coordinates a fit uses for a model (Lafortune: direction + n = 2). */
int bf_model_ncoords(brdffit_model model);

/* The two kernels of a model, building its program on first use.  A build
 * failure returns BRDFFIT_E_KERNEL_BUILD with the build log in err. */
brdffit_status bf_context_kernels(brdffit_context *ctx, brdffit_model model, cl_kernel *full,
                                  cl_kernel *value, brdffit_error *err);

/* A sample set bound to a context for a series of passes of one model. */
typedef struct bf_passer {
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
    int passes;
} bf_passer;

brdffit_status bf_passer_open(bf_passer *ps, brdffit_context *ctx, const brdffit_samples *samples,
                              brdffit_model model, brdffit_error *err);
/* One pass at pp: mom[bf_nmom(nk, full ? np : 0)] in double.  Non-finite sums
 * give BRDFFIT_E_FIT_FAILED. */
brdffit_status bf_passer_run(bf_passer *ps, int full, const bf_pass_par *pp, double *mom,
                             brdffit_error *err);
void bf_passer_close(bf_passer *ps);

/* The plain single-threaded C loop over the samples (the host path, and the
 * reference the kernel is tested and benchmarked against). */
void bf_pass_host(const brdffit_samples *samples, brdffit_model model, int nk, int np,
                  const bf_pass_par *pp, double *mom);

#endif /* BRDFFIT_CONTEXT_H */
