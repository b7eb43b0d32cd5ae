/* SPDX-License-Identifier: MIT */
/* context.c -- brdffit_context: device selection, PoCL set-up and the
 * per-model program cache (kernel sources embedded at build time).
 *
 * Threads: PoCL's (and the ICD loader's) first-time set-up is not safe to
 * race, so every call that sets up or tears down OpenCL state -- platform and
 * device queries, contexts, queues, program builds, releases -- runs under
 * one process-wide lock.  The data passes (enqueue, read back) do not: each
 * context has its own queue. */
#define _POSIX_C_SOURCE 200809L
#include "context.h"
#include "registry.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pocl_cache.h"

#include "bf_lobe_pass.h" /* bf_lobe_has_own_fd: a kernel's BF_ROWS */

extern const char *const bf_kernel_sources[];
extern const size_t bf_kernel_source_count;

void brdffit_context_options_init(brdffit_context_options *opt, size_t size)
{
    brdffit_context_options d;
    memset(&d, 0, sizeof d);
    d.size = sizeof d;
    d.backend = BRDFFIT_BACKEND_AUTO;
    d.device = NULL;
    bf_options_init(BRDFFIT_STRUCT_CONTEXT_OPTIONS, &d, opt, size);
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

static pthread_mutex_t cl_lock = PTHREAD_MUTEX_INITIALIZER;

/* spec "P:D" with decimal indices: 1 and the indices (ULONG_MAX when too
 * large to represent, so that it is out of range, never wrapped); 0 when spec
 * is not of that form (then it is a name substring). */
static int index_spec(const char *spec, unsigned long *p, unsigned long *d)
{
    const char *colon = strchr(spec, ':');
    if (!colon || colon == spec || !colon[1])
        return 0;
    for (const char *c = spec; *c; c++)
        if (c != colon && !isdigit((unsigned char)*c))
            return 0;
    errno = 0;
    *p = strtoul(spec, NULL, 10);
    if (errno == ERANGE)
        *p = ULONG_MAX;
    errno = 0;
    *d = strtoul(colon + 1, NULL, 10);
    if (errno == ERANGE)
        *d = ULONG_MAX;
    return 1;
}

#define MAX_PLATFORMS 16
#define MAX_DEVICES 16

/* What the machine has: platform and device ids and names. */
typedef struct cl_inventory {
    cl_uint np;
    cl_platform_id plat[MAX_PLATFORMS];
    cl_uint nd[MAX_PLATFORMS];
    cl_device_id dev[MAX_PLATFORMS][MAX_DEVICES];
} cl_inventory;

static void device_label(const cl_inventory *inv, cl_uint i, cl_uint j, char *buf, size_t len)
{
    char pname[256], dname[256];
    info_string(inv->plat[i], NULL, CL_PLATFORM_NAME, pname, sizeof pname);
    info_string(NULL, inv->dev[i][j], CL_DEVICE_NAME, dname, sizeof dname);
    snprintf(buf, len, "%s / %s", pname, dname);
}

/* "0:0 PoCL / cpu, 0:1 ..." into buf: the choices, for a message. */
static const char *list_devices(const cl_inventory *inv, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (cl_uint i = 0; i < inv->np; i++)
        for (cl_uint j = 0; j < inv->nd[i]; j++) {
            char label[520];
            device_label(inv, i, j, label, sizeof label);
            int w = snprintf(buf + used, len - used, "%s%u:%u %s", used ? ", " : "", (unsigned)i,
                             (unsigned)j, label);
            if (w < 0 || (size_t)w >= len - used)
                return buf;
            used += (size_t)w;
        }
    if (!used)
        snprintf(buf, len, "none");
    return buf;
}

static brdffit_status take_device(const cl_inventory *inv, cl_uint i, cl_uint j, const char *spec,
                                  cl_platform_id *pp, cl_device_id *dp, brdffit_error *err)
{
    char label[520];
    device_label(inv, i, j, label, sizeof label);
    if (!has_fp64(inv->dev[i][j]))
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "device '%.200s' (%s) has no double precision", spec,
                       label);
    *pp = inv->plat[i];
    *dp = inv->dev[i][j];
    return BRDFFIT_OK;
}

/* The device spec names: by index (in range, never wrapped) or by a
 * substring of "platform name / device name". */
static brdffit_status pick_named(const cl_inventory *inv, const char *spec, cl_platform_id *pp,
                                 cl_device_id *dp, brdffit_error *err)
{
    char list[1200];
    unsigned long wp, wd;
    if (index_spec(spec, &wp, &wd)) {
        if (wp >= inv->np)
            return bf_fail(err, BRDFFIT_E_NO_DEVICE,
                           "no OpenCL device '%.200s': platform index %.40s out of range (%u platform%s; "
                           "devices: %s)",
                           spec, wp == ULONG_MAX ? "(too large)" : spec, (unsigned)inv->np,
                           inv->np == 1 ? "" : "s", list_devices(inv, list, sizeof list));
        if (wd >= inv->nd[wp])
            return bf_fail(err, BRDFFIT_E_NO_DEVICE,
                           "no OpenCL device '%.200s': device index out of range (platform %lu has %u "
                           "device%s; devices: %s)",
                           spec, wp, (unsigned)inv->nd[wp], inv->nd[wp] == 1 ? "" : "s",
                           list_devices(inv, list, sizeof list));
        return take_device(inv, (cl_uint)wp, (cl_uint)wd, spec, pp, dp, err);
    }
    for (cl_uint i = 0; i < inv->np; i++)
        for (cl_uint j = 0; j < inv->nd[i]; j++) {
            char label[520];
            device_label(inv, i, j, label, sizeof label);
            if (strstr(label, spec))
                return take_device(inv, i, j, spec, pp, dp, err);
        }
    return bf_fail(err, BRDFFIT_E_NO_DEVICE, "no OpenCL device matches '%.200s' (devices: %s)", spec,
                   list_devices(inv, list, sizeof list));
}

/* Pick a device.  spec: NULL or "" (the first PoCL CPU device with double
 * precision, else the first device with it), "P:D" indices, or a substring
 * of "platform name / device name".  BRDFFIT_E_NO_DEVICE says why not.
 * Called under cl_lock. */
static brdffit_status pick_device(const char *spec, cl_platform_id *pp, cl_device_id *dp,
                                  brdffit_error *err)
{
    cl_inventory inv;
    memset(&inv, 0, sizeof inv);
    cl_int rc = clGetPlatformIDs(MAX_PLATFORMS, inv.plat, &inv.np);
    if (rc != CL_SUCCESS || inv.np == 0)
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "no OpenCL platform (clGetPlatformIDs: %d)", (int)rc);
    if (inv.np > MAX_PLATFORMS)
        inv.np = MAX_PLATFORMS;
    for (cl_uint i = 0; i < inv.np; i++) {
        if (clGetDeviceIDs(inv.plat[i], CL_DEVICE_TYPE_ALL, MAX_DEVICES, inv.dev[i], &inv.nd[i]) !=
            CL_SUCCESS)
            inv.nd[i] = 0;
        if (inv.nd[i] > MAX_DEVICES)
            inv.nd[i] = MAX_DEVICES;
    }
    if (spec && *spec)
        return pick_named(&inv, spec, pp, dp, err);
    int first = -1, best = -1;
    for (cl_uint i = 0; i < inv.np; i++) {
        char pname[256];
        info_string(inv.plat[i], NULL, CL_PLATFORM_NAME, pname, sizeof pname);
        for (cl_uint j = 0; j < inv.nd[i]; j++) {
            if (!has_fp64(inv.dev[i][j]))
                continue;
            if (first < 0)
                first = (int)(i * MAX_DEVICES + j);
            cl_device_type type = 0;
            clGetDeviceInfo(inv.dev[i][j], CL_DEVICE_TYPE, sizeof type, &type, NULL);
            if (best < 0 && strstr(pname, "Portable Computing Language") && (type & CL_DEVICE_TYPE_CPU))
                best = (int)(i * MAX_DEVICES + j);
        }
    }
    if (best < 0)
        best = first;
    if (best < 0) {
        char list[1200];
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "no OpenCL device with double precision (devices: %s)",
                       list_devices(&inv, list, sizeof list));
    }
    *pp = inv.plat[best / MAX_DEVICES];
    *dp = inv.dev[best / MAX_DEVICES][best % MAX_DEVICES];
    return BRDFFIT_OK;
}

/* Called under cl_lock. */
static brdffit_status open_locked(brdffit_context *ctx, const char *spec, brdffit_error *err)
{
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
    const char *w = strstr(ctx->cl_options, "-DBF_WIDTH=");
    ctx->width = w && atoi(w + 11) == 4 ? 4 : 8;
    char pname[200], dname[200];
    info_string(ctx->platform, NULL, CL_PLATFORM_NAME, pname, sizeof pname);
    info_string(NULL, ctx->device, CL_DEVICE_NAME, dname, sizeof dname);
    snprintf(ctx->describe, sizeof ctx->describe, "opencl: %s / %s (%u compute units)", pname, dname,
             (unsigned)ctx->compute_units);
    return BRDFFIT_OK;
}

/* The device, under cl_lock.  The cache directory (bf_pocl_cache_ready)
 * must have been settled first. */
static brdffit_status open_opencl(brdffit_context *ctx, const char *spec, brdffit_error *err)
{
    pthread_mutex_lock(&cl_lock);
    brdffit_status st = open_locked(ctx, spec, err);
    pthread_mutex_unlock(&cl_lock);
    return st;
}

static void close_opencl(brdffit_context *ctx)
{
    pthread_mutex_lock(&cl_lock);
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
    pthread_mutex_unlock(&cl_lock);
}

brdffit_status brdffit_context_create(const brdffit_context_options *opt, brdffit_context **out,
                                      brdffit_error *err)
{
    if (!out)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_context_create: out is NULL");
    *out = NULL;
    brdffit_context_options o;
    brdffit_context_options_default(&o);
    brdffit_status ost = bf_options_read(BRDFFIT_STRUCT_CONTEXT_OPTIONS, opt, &o, err);
    if (ost != BRDFFIT_OK)
        return ost;
    if (o.backend != BRDFFIT_BACKEND_AUTO && o.backend != BRDFFIT_BACKEND_OPENCL &&
        o.backend != BRDFFIT_BACKEND_HOST)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "unknown backend %d", (int)o.backend);
    brdffit_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return bf_fail(err, BRDFFIT_E_NO_MEMORY, "out of memory for the context");
    if (o.backend != BRDFFIT_BACKEND_HOST) {
        brdffit_error why;
        bf_ok(&why);
        /* first: it may set POCL_CACHE_DIR, so no getenv of ours runs before it */
        brdffit_status st = bf_pocl_cache_ready(&why);
        if (st == BRDFFIT_OK) {
            const char *spec = o.device ? o.device : getenv("BRDFFIT_DEVICE");
            const char *extra = getenv("BRDFFIT_CL_OPTIONS");
            snprintf(ctx->cl_options, sizeof ctx->cl_options, "%s", extra ? extra : "");
            st = open_opencl(ctx, spec, &why);
        }
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
        ctx->fallback = why;
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

brdffit_status brdffit_context_fallback(const brdffit_context *ctx, brdffit_error *why)
{
    if (!ctx)
        return bf_fail(why, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_context_fallback: ctx is NULL");
    if (ctx->fallback.status == BRDFFIT_OK) {
        bf_ok(why);
        return BRDFFIT_OK;
    }
    if (why)
        *why = ctx->fallback;
    return ctx->fallback.status;
}

/* The end of a failed build's log (where the errors are) into err. */
static brdffit_status build_failed(brdffit_context *ctx, cl_program prog, const char *model,
                                   const char *opts, cl_int rc, brdffit_error *err)
{
    size_t len = 0;
    char *log = NULL;
    if (clGetProgramBuildInfo(prog, ctx->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &len) == CL_SUCCESS &&
        len > 0 && (log = malloc(len + 1)) != NULL) {
        if (clGetProgramBuildInfo(prog, ctx->device, CL_PROGRAM_BUILD_LOG, len, log, NULL) != CL_SUCCESS)
            len = 0;
        log[len] = '\0';
    }
    size_t keep = BRDFFIT_MESSAGE_MAX - 400, n = log ? strlen(log) : 0;
    const char *tail = n > keep ? log + (n - keep) : log;
    char empty[400], shown[200];
    const char *cache = getenv("POCL_CACHE_DIR");
    snprintf(empty, sizeof empty, "(empty: is PoCL's cache directory %s still writable?)",
             cache ? bf_path_brief(cache, shown, sizeof shown) : "(unset)");
    bf_fail(err, BRDFFIT_E_KERNEL_BUILD, "building the %s kernel (%s) failed (%d); build log%s:\n%s", model,
            opts, (int)rc, n > keep ? " (end)" : "", n ? tail : empty);
    free(log);
    return BRDFFIT_E_KERNEL_BUILD;
}

/* Build a model's program and make its two kernels.  Called under cl_lock. */
static brdffit_status build_locked(brdffit_context *ctx, brdffit_model model,
                                   const brdffit_model_info *mi, brdffit_error *err)
{
    cl_int rc;
    cl_program prog = clCreateProgramWithSource(ctx->cl, (cl_uint)bf_kernel_source_count,
                                                (const char **)bf_kernel_sources, NULL, &rc);
    if (!prog)
        return bf_fail(err, BRDFFIT_E_OPENCL, "clCreateProgramWithSource failed (%d)", (int)rc);
    /* -w: PoCL would print its warnings to stderr (the log still has errors).
     * $BRDFFIT_CL_OPTIONS (read when the context was made) is appended
     * (e.g. -DBF_WIDTH=4 to change the lane width). */
    const char *extra = ctx->cl_options;
    char opts[512];
    snprintf(opts, sizeof opts, "-cl-std=CL1.2 -w -DBF_MODEL=%d -DBF_NP=%d -DBF_NK=%d -DBF_ROWS=%d %s %.200s",
             (int)model, bf_model_ncoords(model), mi->chromatic ? 3 : 1, bf_lobe_has_own_fd((int)model),
             strstr(extra, "-DBF_WIDTH=") ? "" : ctx->width == 4 ? "-DBF_WIDTH=4" : "-DBF_WIDTH=8", extra);
    rc = clBuildProgram(prog, 1, &ctx->device, opts, NULL, NULL);
    if (rc != CL_SUCCESS) {
        build_failed(ctx, prog, mi->name, opts, rc, err);
        clReleaseProgram(prog);
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
    return BRDFFIT_OK;
}

brdffit_status brdffit_context_prepare(brdffit_context *ctx, brdffit_model model,
                                       brdffit_error *err)
{
    if (!ctx)
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT, "brdffit_context_prepare: ctx is NULL");
    if (!brdffit_model_get(model))
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    if (ctx->backend == BRDFFIT_BACKEND_OPENCL && bf_model_has_lobe(model)) { /* the glTF models: no kernel */
        cl_kernel full, value;
        brdffit_status st = bf_context_kernels(ctx, model, &full, &value, err);
        if (st != BRDFFIT_OK)
            return st;
    }
    bf_ok(err);
    return BRDFFIT_OK;
}

double brdffit_context_build_seconds(const brdffit_context *ctx, brdffit_model model)
{
    if (!ctx || !brdffit_model_get(model) || !ctx->program[model])
        return 0.0;
    return ctx->build_seconds[model];
}

brdffit_status bf_context_kernels(brdffit_context *ctx, brdffit_model model, cl_kernel *full,
                                  cl_kernel *value, brdffit_error *err)
{
    const brdffit_model_info *mi = brdffit_model_get(model);
    if (!mi)
        return bf_fail(err, BRDFFIT_E_UNKNOWN_MODEL, "model id %d is not a model", (int)model);
    if (!bf_model_has_lobe(model))
        return bf_fail(err, BRDFFIT_E_INVALID_ARGUMENT,
                       "%s has no OpenCL kernel (no lobe K: its colours enter as the glTF "
                       "material's, evaluated on the host)", mi->name);
    if (ctx->backend != BRDFFIT_BACKEND_OPENCL)
        return bf_fail(err, BRDFFIT_E_NO_DEVICE, "the context has no OpenCL device");
    if (!ctx->program[model]) {
        pthread_mutex_lock(&cl_lock);
        double t0 = bf_now();
        brdffit_status st = build_locked(ctx, model, mi, err);
        double took = bf_now() - t0;
        pthread_mutex_unlock(&cl_lock);
        if (st != BRDFFIT_OK)
            return st;
        ctx->build_seconds[model] = took;
    }
    *full = ctx->kfull[model];
    *value = ctx->kvalue[model];
    return BRDFFIT_OK;
}
