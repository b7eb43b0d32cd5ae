/* SPDX-License-Identifier: MIT */
/* abi.c -- the layout of the public structs as compiled: reported to FFI
 * mirrors, and used to read a caller's sized options struct, and to write a
 * caller's sized result, by its size. */
#include "internal.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

typedef struct abi_member {
    brdffit_struct_kind kind;
    const char *name;
    size_t offset, size;
} abi_member;

#define M(kind, type, member) { kind, #member, offsetof(type, member), sizeof(((type *)0)->member) }

/* Every member of every public struct, in declaration order. */
static const abi_member members[] = {
    M(BRDFFIT_STRUCT_ERROR, brdffit_error, status),
    M(BRDFFIT_STRUCT_ERROR, brdffit_error, message),

    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, id),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, name),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, title),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, nparams),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, chromatic),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, default_starts),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, params),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, colour_form),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, colour_names),
    M(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info, in_default_set),

    M(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info, name),
    M(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info, unit),
    M(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info, lower),
    M(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info, upper),
    M(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info, start),
    M(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info, map),
    M(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info, description),

    M(BRDFFIT_STRUCT_PARAMS, brdffit_params, d),
    M(BRDFFIT_STRUCT_PARAMS, brdffit_params, s),
    M(BRDFFIT_STRUCT_PARAMS, brdffit_params, p),
    M(BRDFFIT_STRUCT_PARAMS, brdffit_params, lambda_um),

    M(BRDFFIT_STRUCT_SAMPLE_OPTIONS, brdffit_sample_options, size),
    M(BRDFFIT_STRUCT_SAMPLE_OPTIONS, brdffit_sample_options, scale),
    M(BRDFFIT_STRUCT_SAMPLE_OPTIONS, brdffit_sample_options, cutoff_deg),

    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, size),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, wi),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, wo),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, rgb),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, weight),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, i),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, j),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, k),

    M(BRDFFIT_STRUCT_CONTEXT_OPTIONS, brdffit_context_options, size),
    M(BRDFFIT_STRUCT_CONTEXT_OPTIONS, brdffit_context_options, backend),
    M(BRDFFIT_STRUCT_CONTEXT_OPTIONS, brdffit_context_options, device),

    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, size),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, starts),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, refine),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, ftol),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, xtol),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, gtol),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, max_evals),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, lambda_um),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, metric),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, all_errors),

    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, size),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, model),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, params),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, error),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, cminpack_info),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, iterations),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, passes),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, seconds),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, seconds_solver),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, seconds_passes),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, samples),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, backend),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, at_bound),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, flags),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, seconds_build),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, errors),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, metric),
    M(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result, metric_iterations),

    M(BRDFFIT_STRUCT_LIGHT, brdffit_light, dir),
    M(BRDFFIT_STRUCT_LIGHT, brdffit_light, rgb),

    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, size),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, width),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, nlights),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, lights),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, env),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, env_width),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, env_height),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, env_stride),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, env_samples),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, interp),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, scale),
    M(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options, threads),

    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, size),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, ntheta_i),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, npoints),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, theta_i_deg),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, interp),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, scale),
};

#undef M

typedef struct abi_struct {
    const char *name;
    size_t size;
} abi_struct;

#define S(kind, type) [kind] = { #type, sizeof(type) }

/* Every public struct by kind. */
static const abi_struct structs[] = {
    S(BRDFFIT_STRUCT_ERROR, brdffit_error),
    S(BRDFFIT_STRUCT_MODEL_INFO, brdffit_model_info),
    S(BRDFFIT_STRUCT_PARAMS, brdffit_params),
    S(BRDFFIT_STRUCT_SAMPLE_OPTIONS, brdffit_sample_options),
    S(BRDFFIT_STRUCT_SAMPLE, brdffit_sample),
    S(BRDFFIT_STRUCT_CONTEXT_OPTIONS, brdffit_context_options),
    S(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options),
    S(BRDFFIT_STRUCT_FIT_RESULT, brdffit_fit_result),
    S(BRDFFIT_STRUCT_PARAM_INFO, brdffit_param_info),
    S(BRDFFIT_STRUCT_LIGHT, brdffit_light),
    S(BRDFFIT_STRUCT_RENDER_OPTIONS, brdffit_render_options),
    S(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options),
};

#undef S

#define NSTRUCTS (sizeof structs / sizeof structs[0])
#define NMEMBERS (sizeof members / sizeof members[0])

size_t brdffit_struct_size(brdffit_struct_kind kind)
{
    return (size_t)kind < NSTRUCTS ? structs[kind].size : 0;
}

size_t brdffit_struct_offset(brdffit_struct_kind kind, const char *member)
{
    if (!member)
        return SIZE_MAX;
    for (size_t m = 0; m < NMEMBERS; m++)
        if (members[m].kind == kind && strcmp(members[m].name, member) == 0)
            return members[m].offset;
    return SIZE_MAX;
}

size_t bf_struct_members_end(brdffit_struct_kind kind)
{
    size_t end = 0;
    for (size_t m = 0; m < NMEMBERS; m++)
        if (members[m].kind == kind && members[m].offset + members[m].size > end)
            end = members[m].offset + members[m].size;
    return end;
}

/* The smallest size the library takes of a sized struct the caller gives:
 * `size` alone for an options struct (every member has a default); a
 * result's first sized layout, its members up to the one named. */
static size_t smallest_size(brdffit_struct_kind kind, const char **last)
{
    *last = NULL;
    if (kind == BRDFFIT_STRUCT_FIT_RESULT)
        *last = "flags";
    else if (kind == BRDFFIT_STRUCT_SAMPLE)
        *last = "k";
    for (size_t m = 0; *last && m < NMEMBERS; m++)
        if (members[m].kind == kind && strcmp(members[m].name, *last) == 0)
            return members[m].offset + members[m].size;
    return sizeof(size_t);
}

/* The size a caller's sized struct of `kind` (`size` is its first member)
 * claims, checked against this library's struct. */
static brdffit_status options_size(brdffit_struct_kind kind, const void *opt, size_t *size,
                                   brdffit_error *err)
{
    const abi_struct *s = &structs[kind];
    const char *last;
    size_t smallest = smallest_size(kind, &last);
    memcpy(size, opt, sizeof *size);
    if (*size == 0 && last)
        return bf_fail(err, BRDFFIT_E_OPTIONS_SIZE,
                       "%s: size 0 (set it with %s_init() or to sizeof(%s): the struct's size "
                       "as the caller was compiled; %zu bytes in this library)",
                       s->name, s->name, s->name, s->size);
    if (*size == 0)
        return bf_fail(err, BRDFFIT_E_OPTIONS_SIZE,
                       "%s: size 0 (set it with %s_default(): the struct's size as the "
                       "caller was compiled; %zu bytes in this library)",
                       s->name, s->name, s->size);
    if (*size < smallest && last)
        return bf_fail(err, BRDFFIT_E_OPTIONS_SIZE,
                       "%s: size %zu is smaller than its first sized layout (%zu bytes: `size` "
                       "up to '%s')",
                       s->name, *size, smallest, last);
    if (*size < smallest)
        return bf_fail(err, BRDFFIT_E_OPTIONS_SIZE,
                       "%s: size %zu is smaller than its `size` member (%zu bytes)", s->name,
                       *size, sizeof *size);
    if (*size > s->size)
        return bf_fail(err, BRDFFIT_E_OPTIONS_SIZE,
                       "%s: size %zu is larger than this library's struct (%zu bytes): the "
                       "caller was compiled against a newer brdffit.h than this library %s",
                       s->name, *size, s->size, brdffit_version());
    for (size_t m = 0; m < NMEMBERS; m++) {
        const abi_member *a = &members[m];
        if (a->kind == kind && *size > a->offset && *size < a->offset + a->size)
            return bf_fail(err, BRDFFIT_E_OPTIONS_SIZE,
                           "%s: size %zu ends inside member '%s' (bytes %zu..%zu): not the size "
                           "of a struct of whole members",
                           s->name, *size, a->name, a->offset, a->offset + a->size);
    }
    return BRDFFIT_OK;
}

/* The members of `kind` but `size` that lie wholly within the first n bytes, src to dst. */
static void copy_members(brdffit_struct_kind kind, void *dst, const void *src, size_t n)
{
    for (size_t m = 0; m < NMEMBERS; m++) {
        const abi_member *a = &members[m];
        if (a->kind == kind && a->offset > 0 && a->offset + a->size <= n)
            memcpy((char *)dst + a->offset, (const char *)src + a->offset, a->size);
    }
}

brdffit_status bf_options_read(brdffit_struct_kind kind, const void *opt, void *out,
                               brdffit_error *err)
{
    if (!opt)
        return BRDFFIT_OK;
    size_t size;
    brdffit_status st = options_size(kind, opt, &size, err);
    if (st == BRDFFIT_OK)
        copy_members(kind, out, opt, size);
    return st;
}

brdffit_status bf_sized_check(brdffit_struct_kind kind, const void *out, brdffit_error *err)
{
    size_t size;
    return options_size(kind, out, &size, err);
}

brdffit_status bf_options_write(brdffit_struct_kind kind, const void *src, void *out,
                                brdffit_error *err)
{
    size_t size;
    brdffit_status st = options_size(kind, out, &size, err);
    if (st == BRDFFIT_OK)
        copy_members(kind, out, src, size);
    return st;
}

void bf_options_init(brdffit_struct_kind kind, const void *dflt, void *opt, size_t size)
{
    size_t have = structs[kind].size;
    if (!opt || size < sizeof size)
        return;
    memset(opt, 0, size < have ? size : have);
    memcpy(opt, &size, sizeof size);
    copy_members(kind, opt, dflt, size < have ? size : have);
}
