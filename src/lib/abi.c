/* SPDX-License-Identifier: MIT */
/* abi.c -- the layout of the public structs as compiled, for FFI mirrors. */
#include "brdffit.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

typedef struct abi_member {
    brdffit_struct_kind kind;
    const char *name;
    size_t offset;
} abi_member;

#define M(kind, type, member) { kind, #member, offsetof(type, member) }

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

    M(BRDFFIT_STRUCT_SAMPLE_OPTIONS, brdffit_sample_options, cutoff_deg),
    M(BRDFFIT_STRUCT_SAMPLE_OPTIONS, brdffit_sample_options, scale),

    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, wi),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, wo),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, rgb),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, weight),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, i),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, j),
    M(BRDFFIT_STRUCT_SAMPLE, brdffit_sample, k),

    M(BRDFFIT_STRUCT_CONTEXT_OPTIONS, brdffit_context_options, backend),
    M(BRDFFIT_STRUCT_CONTEXT_OPTIONS, brdffit_context_options, device),

    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, starts),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, refine),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, ftol),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, xtol),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, gtol),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, max_evals),
    M(BRDFFIT_STRUCT_FIT_OPTIONS, brdffit_fit_options, lambda_um),

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
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, theta_i_deg),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, npoints),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, interp),
    M(BRDFFIT_STRUCT_CURVE_OPTIONS, brdffit_curve_options, scale),
};

#undef M

size_t brdffit_struct_size(brdffit_struct_kind kind)
{
    switch (kind) {
    case BRDFFIT_STRUCT_ERROR: return sizeof(brdffit_error);
    case BRDFFIT_STRUCT_MODEL_INFO: return sizeof(brdffit_model_info);
    case BRDFFIT_STRUCT_PARAMS: return sizeof(brdffit_params);
    case BRDFFIT_STRUCT_SAMPLE_OPTIONS: return sizeof(brdffit_sample_options);
    case BRDFFIT_STRUCT_SAMPLE: return sizeof(brdffit_sample);
    case BRDFFIT_STRUCT_CONTEXT_OPTIONS: return sizeof(brdffit_context_options);
    case BRDFFIT_STRUCT_FIT_OPTIONS: return sizeof(brdffit_fit_options);
    case BRDFFIT_STRUCT_FIT_RESULT: return sizeof(brdffit_fit_result);
    case BRDFFIT_STRUCT_PARAM_INFO: return sizeof(brdffit_param_info);
    case BRDFFIT_STRUCT_LIGHT: return sizeof(brdffit_light);
    case BRDFFIT_STRUCT_RENDER_OPTIONS: return sizeof(brdffit_render_options);
    case BRDFFIT_STRUCT_CURVE_OPTIONS: return sizeof(brdffit_curve_options);
    }
    return 0;
}

size_t brdffit_struct_offset(brdffit_struct_kind kind, const char *member)
{
    if (!member)
        return SIZE_MAX;
    for (size_t m = 0; m < sizeof members / sizeof members[0]; m++)
        if (members[m].kind == kind && strcmp(members[m].name, member) == 0)
            return members[m].offset;
    return SIZE_MAX;
}
