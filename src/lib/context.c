/* context.c -- brdffit_context: device selection, PoCL set-up and the
 * per-model program cache (kernel sources embedded at build time). */
#define _POSIX_C_SOURCE 200809L
#include "context.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

extern const char *const bf_kernel_sources[];
extern const size_t bf_kernel_source_count;

void brdffit_context_options_default(brdffit_context_options *opt)
{
    if (!opt)
        return;
    opt->backend = BRDFFIT_BACKEND_AUTO;
    opt->device = NULL;
}

/* mkdir -p for a short path; 0 when dir exists and is writable afterwards. */
static int make_dirs(const char *dir)
{
    char tmp[1024];
    if (snprintf(tmp, sizeof tmp, "%s", dir) >= (int)sizeof tmp)
        return -1;
    for (char *p = tmp + 1; *p; p++) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(tmp, 0700) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    }
    if (mkdir(tmp, 0700) != 0 && errno != EEXIST)
        return -1;
    return access(tmp, W_OK | X_OK) == 0 ? 0 : -1;
}

/* PoCL needs a writable cache directory: without one it reports no device
 * or fails builds with -11 and an empty log.  Give it one when unset. */
static void ensure_pocl_cache(void)
{
    const char *cur = getenv("POCL_CACHE_DIR");
    if (cur && *cur)
        return;
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME"), *tmp = getenv("TMPDIR");
    char uid[32];
    snprintf(uid, sizeof uid, "%ld", (long)getuid());
    /* the first that can be made writable: $XDG_CACHE_HOME/brdffit/pocl,
     * ~/.cache/brdffit/pocl, $TMPDIR (or /tmp)/brdffit-pocl-UID */
    const struct { const char *base, *tail; } cand[3] = {
        { xdg, "/brdffit/pocl" },
        { home, "/.cache/brdffit/pocl" },
        { tmp && *tmp ? tmp : "/tmp", "/brdffit-pocl-" },
    };
    for (int i = 0; i < 3; i++) {
        char dir[1024];
        if (!cand[i].base || !*cand[i].base)
            continue;
        if (snprintf(dir, sizeof dir, "%s%s%s", cand[i].base, cand[i].tail, i == 2 ? uid : "") >=
            (int)sizeof dir)
            continue;
        if (make_dirs(dir) == 0) {
            setenv("POCL_CACHE_DIR", dir, 0);
            return;
        }
    }
}

static void info_string(cl_platform_id p, cl_device_id d, cl_uint what, char *buf, size_t len)
{
    buf[0] = '\0';
    if (d)
        clGetDeviceInfo(d, what, len, buf, NULL);
    else
        clGetPlatformInfo(p, what, len, buf, NULL);
    buf[len - 1] = '\0';
}

static int has_fp64(cl_device_id d)
{
    cl_device_fp_config cfg = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof cfg, &cfg, NULL) != CL_SUCCESS)
        return 0;
    return cfg != 0;
}

/* Pick a device.  spec: NULL (default), "P:D" indices, or a substring of
 * "platform name / device name".  Returns BRDFFIT_E_NO_DEVICE with why. */
static brdffit_status pick_device(const char *spec, cl_platform_id *pp, cl_device_id *dp,
                                  brdffit_error *err)
{
    cl_platform_id plats[16];
    cl_uint np = 0;
    cl_int rc = clGetPlatformIDs(16, plats, &np);
    if (rc != CL_SUCCESS || np == 0)
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "no OpenCL platform (clGetPlatformIDs: %d)", (int)rc);
    if (np > 16)
        np = 16;
    int want_p = -1, want_d = -1;
    if (spec && *spec) {
        char extra;
        if (sscanf(spec, "%d:%d%c", &want_p, &want_d, &extra) != 2)
            want_p = want_d = -1;
    }
    cl_platform_id first_p = NULL, best_p = NULL;
    cl_device_id first_d = NULL, best_d = NULL;
    for (cl_uint i = 0; i < np; i++) {
        cl_device_id devs[16];
        cl_uint nd = 0;
        if (clGetDeviceIDs(plats[i], CL_DEVICE_TYPE_ALL, 16, devs, &nd) != CL_SUCCESS)
            continue;
        if (nd > 16)
            nd = 16;
        char pname[256];
        info_string(plats[i], NULL, CL_PLATFORM_NAME, pname, sizeof pname);
        for (cl_uint j = 0; j < nd; j++) {
            char dname[256], full[600];
            info_string(NULL, devs[j], CL_DEVICE_NAME, dname, sizeof dname);
            snprintf(full, sizeof full, "%s / %s", pname, dname);
            if (spec && *spec) {
                int match = want_p >= 0 ? ((int)i == want_p && (int)j == want_d)
                                        : strstr(full, spec) != NULL;
                if (match) {
                    if (!has_fp64(devs[j]))
                        return bf_fail(err, BRDFFIT_E_NO_DEVICE,
                                       "device '%s' (%s) has no double precision", spec, full);
                    *pp = plats[i];
                    *dp = devs[j];
                    return BRDFFIT_OK;
                }
                continue;
            }
            if (!has_fp64(devs[j]))
                continue;
            if (!first_d) {
                first_p = plats[i];
                first_d = devs[j];
            }
            cl_device_type type = 0;
            clGetDeviceInfo(devs[j], CL_DEVICE_TYPE, sizeof type, &type, NULL);
            if (!best_d && strstr(pname, "Portable Computing Language") && (type & CL_DEVICE_TYPE_CPU)) {
                best_p = plats[i];
                best_d = devs[j];
            }
        }
    }
    if (spec && *spec)
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "no OpenCL device matches '%s'", spec);
    if (!best_d) {
        best_p = first_p;
        best_d = first_d;
    }
    if (!best_d)
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "no OpenCL device with double precision");
    *pp = best_p;
    *dp = best_d;
    return BRDFFIT_OK;
}

static brdffit_status open_opencl(brdffit_context *ctx, const char *spec, brdffit_error *err)
{
    ensure_pocl_cache();
    brdffit_status st = pick_device(spec, &ctx->platform, &ctx->device, err);
    if (st != BRDFFIT_OK)
        return st;
    cl_int rc;
    ctx->cl = clCreateContext(NULL, 1, &ctx->device, NULL, NULL, &rc);
    if (!ctx->cl)
        return bf_fail(err, BRDFFIT_E_OPENCL, "clCreateContext failed (%d)", (int)rc);
    ctx->queue = clCreateCommandQueue(ctx->cl, ctx->device, 0, &rc);
    if (!ctx->queue)
        return bf_fail(err, BRDFFIT_E_OPENCL, "clCreateCommandQueue failed (%d)", (int)rc);
    clGetDeviceInfo(ctx->device, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof ctx->compute_units,
                    &ctx->compute_units, NULL);
    const char *extra = getenv("BRDFFIT_CL_OPTIONS"), *w = extra ? strstr(extra, "-DBF_WIDTH=") : NULL;
    ctx->width = w && atoi(w + 11) == 4 ? 4 : 8;
    char pname[200], dname[200];
    info_string(ctx->platform, NULL, CL_PLATFORM_NAME, pname, sizeof pname);
    info_string(NULL, ctx->device, CL_DEVICE_NAME, dname, sizeof dname);
    snprintf(ctx->describe, sizeof ctx->describe, "opencl: %s / %s (%u compute units)", pname, dname,
             (unsigned)ctx->compute_units);
    return BRDFFIT_OK;
}

static void close_opencl(brdffit_context *ctx)
{
    for (int m = 0; m < BRDFFIT_MODEL_COUNT; m++) {
        if (ctx->kfull[m])
            clReleaseKernel(ctx->kfull[m]);
        if (ctx->kvalue[m])
            clReleaseKernel(ctx->kvalue[m]);
        if (ctx->program[m])
            clReleaseProgram(ctx->program[m]);
        ctx->kfull[m] = ctx->kvalue[m] = NULL;
        ctx->program[m] = NULL;
    }
    if (ctx->queue)
        clReleaseCommandQueue(ctx->queue);
    if (ctx->cl)
        clReleaseContext(ctx->cl);
    ctx->queue = NULL;
    ctx->cl = NULL;
}

brdffit_status brdffit_context_create(const brdffit_context_options *opt, brdffit_context **out,
                                      brdffit_error *err)
{
    if (!out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_context_create: out is NULL");
    *out = NULL;
    brdffit_context_options o;
    brdffit_context_options_default(&o);
    if (opt)
        o = *opt;
    if (o.backend != BRDFFIT_BACKEND_AUTO && o.backend != BRDFFIT_BACKEND_OPENCL &&
        o.backend != BRDFFIT_BACKEND_HOST)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "unknown backend %d", (int)o.backend);
    brdffit_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "out of memory for the context");
    const char *spec = o.device ? o.device : getenv("BRDFFIT_DEVICE");
    if (o.backend != BRDFFIT_BACKEND_HOST) {
        brdffit_error why;
        bf_ok(&why);
        brdffit_status st = open_opencl(ctx, spec, &why);
        if (st == BRDFFIT_OK) {
            ctx->backend = BRDFFIT_BACKEND_OPENCL;
            *out = ctx;
            bf_ok(err);
            return BRDFFIT_OK;
        }
        close_opencl(ctx);
        if (o.backend == BRDFFIT_BACKEND_OPENCL) {
            free(ctx);
            if (err)
                *err = why;
            return st;
        }
        snprintf(ctx->describe, sizeof ctx->describe, "host: C, one thread (OpenCL unavailable: %.400s)",
                 why.message);
    } else {
        snprintf(ctx->describe, sizeof ctx->describe, "host: C, one thread (requested)");
    }
    ctx->backend = BRDFFIT_BACKEND_HOST;
    *out = ctx;
    bf_ok(err);
    return BRDFFIT_OK;
}

void brdffit_context_free(brdffit_context *ctx)
{
    if (!ctx)
        return;
    close_opencl(ctx);
    free(ctx);
}

brdffit_backend brdffit_context_backend(const brdffit_context *ctx)
{
    return ctx ? ctx->backend : BRDFFIT_BACKEND_HOST;
}

const char *brdffit_context_describe(const brdffit_context *ctx)
{
    return ctx ? ctx->describe : "(no context)";
}

brdffit_status bf_context_kernels(brdffit_context *ctx, brdffit_model model, cl_kernel *full,
                                  cl_kernel *value, brdffit_error *err)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (!mi)
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    if (ctx->backend != BRDFFIT_BACKEND_OPENCL)
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "the context has no OpenCL device");
    if (!ctx->program[model]) {
        cl_int rc;
        cl_program prog = clCreateProgramWithSource(ctx->cl, (cl_uint)bf_kernel_source_count,
                                                    (const char **)bf_kernel_sources, NULL, &rc);
        if (!prog)
            return bf_fail(err, BRDFFIT_E_OPENCL, "clCreateProgramWithSource failed (%d)", (int)rc);
        /* -w: PoCL would print its warnings to stderr (the log still has errors).
         * $BRDFFIT_CL_OPTIONS is appended (e.g. -DBF_WIDTH=4 to change the lane width). */
        const char *extra = getenv("BRDFFIT_CL_OPTIONS");
        if (!extra)
            extra = "";
        char opts[512];
        snprintf(opts, sizeof opts, "-cl-std=CL1.2 -w -DBF_MODEL=%d -DBF_NP=%d -DBF_NK=%d %s %.200s",
                 (int)model, bf_model_ncoords(model), mi->chromatic ? 3 : 1,
                 strstr(extra, "-DBF_WIDTH=") ? "" : ctx->width == 4 ? "-DBF_WIDTH=4" : "-DBF_WIDTH=8",
                 extra);
        rc = clBuildProgram(prog, 1, &ctx->device, opts, NULL, NULL);
        if (rc != CL_SUCCESS) {
            /* the log may be longer than the message: keep its end, where the errors are */
            size_t len = 0;
            char *log = NULL;
            if (clGetProgramBuildInfo(prog, ctx->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &len) ==
                    CL_SUCCESS && len > 0 && (log = malloc(len + 1)) != NULL) {
                if (clGetProgramBuildInfo(prog, ctx->device, CL_PROGRAM_BUILD_LOG, len, log, NULL) !=
                    CL_SUCCESS)
                    len = 0;
                log[len] = '\0';
            }
            size_t keep = BRDFFIT_MESSAGE_MAX - 400, n = log ? strlen(log) : 0;
            const char *tail = n > keep ? log + (n - keep) : log;
            clReleaseProgram(prog);
            bf_fail(err, BRDFFIT_E_KERNEL_BUILD, "building the %s kernel (%s) failed (%d); build log%s:\n%s",
                    mi->name, opts, (int)rc, n > keep ? " (end)" : "",
                    n ? tail : "(empty: is POCL_CACHE_DIR writable?)");
            free(log);
            return BRDFFIT_E_KERNEL_BUILD;
        }
        cl_kernel kf = clCreateKernel(prog, "bf_kernel_full", &rc);
        cl_kernel kv = kf ? clCreateKernel(prog, "bf_kernel_value", &rc) : NULL;
        if (!kf || !kv) {
            if (kf)
                clReleaseKernel(kf);
            clReleaseProgram(prog);
            return bf_fail(err, BRDFFIT_E_OPENCL, "clCreateKernel failed (%d)", (int)rc);
        }
        ctx->program[model] = prog;
        ctx->kfull[model] = kf;
        ctx->kvalue[model] = kv;
    }
    *full = ctx->kfull[model];
    *value = ctx->kvalue[model];
    return BRDFFIT_OK;
}
