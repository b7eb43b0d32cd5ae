# SPDX-License-Identifier: MIT
"""The C ABI of libbrdffit, written once: struct mirrors, enums, signatures.

Every ctypes struct here mirrors one struct of include/brdffit.h member by
member.  At load time brdffit._lib compares each mirror's size and every
member's offset with what the library reports (brdffit_struct_size and
brdffit_struct_offset) and refuses the library on any difference, so a
mirror that drifted from the header is an error, never garbage.  The
options structs start with ``size``, which brdffit_*_options_init(opt, size)
sets: the library reads the members within it.  The results the library
fills (Sample, FitResult) start with ``size`` too, which their constructor
sets to the mirror's size: the library writes the members within it.
"""

import ctypes as C

MAX_LOBE_PARAMS = 4
MESSAGE_MAX = 2048
MERL_NTH, MERL_NTD, MERL_NPD = 90, 90, 180
MERL_BINS = MERL_NTH * MERL_NTD * MERL_NPD
MERL_SHAPE = (3, MERL_NTH, MERL_NTD, MERL_NPD)
RENDER_MAX_LIGHTS = 16      # BRDFFIT_RENDER_MAX_LIGHTS
RENDER_DEFAULT_LIGHTS = -1  # BRDFFIT_RENDER_DEFAULT_LIGHTS (nlights)
RENDER_MAX_WIDTH = 16384    # brdffit_render_options.width: 1..16384
COVERAGE_MASKED = 0.5       # BRDFFIT_COVERAGE_MASKED
CURVE_MAX_THETA_I = 16      # BRDFFIT_CURVE_MAX_THETA_I
CURVE_MAX_POINTS = 100000   # brdffit_curve_options.npoints: 2..100000

c_enum = C.c_int  # every brdffit_* enum is an int-sized C enum
_d3 = C.c_double * 3
_dp = C.c_double * MAX_LOBE_PARAMS


class Error(C.Structure):
    _fields_ = [("status", c_enum), ("message", C.c_char * MESSAGE_MAX)]


class ParamInfo(C.Structure):
    _fields_ = [
        ("name", C.c_char_p),
        ("unit", C.c_char_p),
        ("lower", C.c_double),
        ("upper", C.c_double),
        ("start", C.c_double),
        ("map", c_enum),
        ("description", C.c_char_p),
    ]


class ModelInfo(C.Structure):
    _fields_ = [
        ("id", c_enum),
        ("name", C.c_char_p),
        ("title", C.c_char_p),
        ("nparams", C.c_int),
        ("chromatic", C.c_int),
        ("default_starts", C.c_int),
        ("params", C.POINTER(ParamInfo)),
        ("colour_form", C.c_int),
        ("colour_names", C.c_char_p * 2),
        ("in_default_set", C.c_int),
    ]


class Params(C.Structure):
    _fields_ = [("d", _d3), ("s", _d3), ("p", _dp), ("lambda_um", _d3)]


class SampleOptions(C.Structure):
    _fields_ = [("size", C.c_size_t), ("scale", c_enum), ("cutoff_deg", C.c_double)]


class _SizedResult(C.Structure):
    """A struct the library fills: ``size`` (its first member) set on creation."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.size = C.sizeof(self)


class Sample(_SizedResult):
    _fields_ = [
        ("size", C.c_size_t),
        ("wi", _d3),
        ("wo", _d3),
        ("rgb", _d3),
        ("weight", C.c_double),
        ("i", C.c_int),
        ("j", C.c_int),
        ("k", C.c_int),
    ]


class ContextOptions(C.Structure):
    _fields_ = [("size", C.c_size_t), ("backend", c_enum), ("device", C.c_char_p)]


class FitOptions(C.Structure):
    _fields_ = [
        ("size", C.c_size_t),
        ("starts", C.c_int),
        ("refine", C.c_int),
        ("ftol", C.c_double),
        ("xtol", C.c_double),
        ("gtol", C.c_double),
        ("max_evals", C.c_int),
        ("lambda_um", _d3),
        ("metric", C.c_int),
        ("all_errors", C.c_int),
    ]


class FitResult(_SizedResult):
    _fields_ = [
        ("size", C.c_size_t),
        ("model", c_enum),
        ("params", Params),
        ("error", C.c_double),
        ("cminpack_info", C.c_int),
        ("iterations", C.c_int),
        ("passes", C.c_int),
        ("seconds", C.c_double),
        ("seconds_solver", C.c_double),
        ("seconds_passes", C.c_double),
        ("samples", C.c_size_t),
        ("backend", c_enum),
        ("at_bound", C.c_uint),
        ("flags", C.c_uint),
        ("seconds_build", C.c_double),
        ("errors", C.c_double * 3),
        ("metric", C.c_int),
        ("metric_iterations", C.c_int),
    ]


class Light(C.Structure):
    _fields_ = [("dir", _d3), ("rgb", _d3)]


class RenderOptions(C.Structure):
    _fields_ = [
        ("size", C.c_size_t),
        ("width", C.c_int),
        ("nlights", C.c_int),
        ("lights", Light * RENDER_MAX_LIGHTS),
        ("env", C.c_void_p),  # const float *: the address of the caller's array
        ("env_width", C.c_int),
        ("env_height", C.c_int),
        ("env_stride", C.c_size_t),
        ("env_samples", C.c_int),
        ("interp", c_enum),
        ("scale", c_enum),
        ("threads", C.c_int),
    ]


class CurveOptions(C.Structure):
    _fields_ = [
        ("size", C.c_size_t),
        ("ntheta_i", C.c_int),
        ("npoints", C.c_int),
        ("theta_i_deg", C.c_double * CURVE_MAX_THETA_I),
        ("interp", c_enum),
        ("scale", c_enum),
    ]


# brdffit_struct_kind of each mirror (the values of the C enum).
STRUCT_KINDS = {
    Error: 0,
    ModelInfo: 1,
    Params: 2,
    SampleOptions: 3,
    Sample: 4,
    ContextOptions: 5,
    FitOptions: 6,
    FitResult: 7,
    ParamInfo: 8,
    Light: 9,
    RenderOptions: 10,
    CurveOptions: 11,
}

# brdffit_at_bound and brdffit_fit_flag: the bits of brdffit_fit_result's
# at_bound and flags, by the C name less its prefix (BRDFFIT_AT_BOUND_,
# BRDFFIT_FIT_).
AT_BOUND_BITS = {
    "P0": 1 << 0, "P1": 1 << 1, "P2": 1 << 2, "P3": 1 << 3, "LOBE": 15,
    "D_R": 1 << 8, "D_G": 1 << 9, "D_B": 1 << 10,
    "S_R": 1 << 12, "S_G": 1 << 13, "S_B": 1 << 14,
}
FIT_FLAG_BITS = {"LIMIT": 1 << 0}

# brdffit_param_map (pinned values).
PARAM_MAPS = {0: "log", 1: "linear", 2: "direction"}
COLOUR_FORMS = {0: "ds", 1: "gltf", 2: "openpbr"}  # brdffit_model_info.colour_form (BRDFFIT_COLOUR_*)

# brdffit_scale, brdffit_interp, brdffit_backend (pinned values).
SCALES = {"standard": 0, "flat": 1}
INTERPS = {"nearest": 0, "trilinear": 1}
BACKENDS = {"auto": 0, "opencl": 1, "host": 2}

_P = C.c_void_p  # opaque handles and array data (passed as addresses)
_status = c_enum
_err = C.POINTER(Error)

# name: (restype, argtypes), every function the package calls.
FUNCTIONS = {
    "brdffit_version": (C.c_char_p, []),
    "brdffit_struct_size": (C.c_size_t, [c_enum]),
    "brdffit_struct_offset": (C.c_size_t, [c_enum, C.c_char_p]),
    "brdffit_strerror": (C.c_char_p, [_status]),
    "brdffit_metric_name": (C.c_char_p, []),
    "brdffit_release_memory": (C.c_size_t, []),
    # models
    "brdffit_model_count": (C.c_int, []),
    "brdffit_model_get": (C.POINTER(ModelInfo), [c_enum]),
    "brdffit_model_param": (C.POINTER(ParamInfo), [c_enum, C.c_int]),
    "brdffit_model_from_name": (_status, [C.c_char_p, C.POINTER(c_enum), _err]),
    "brdffit_params_check": (_status, [c_enum, C.POINTER(Params), _err]),
    "brdffit_eval": (_status, [c_enum, C.POINTER(Params), _P, _P, _P, _err]),
    "brdffit_eval_batch": (_status, [c_enum, C.POINTER(Params), C.c_size_t, _P, _P, _P, _err]),
    # tables
    "brdffit_scale_factors": (_status, [c_enum, _P, _err]),
    "brdffit_scale_name": (C.c_char_p, [c_enum]),
    "brdffit_table_create": (_status, [C.POINTER(_P), _err]),
    "brdffit_table_read": (_status, [C.c_char_p, C.POINTER(_P), _err]),
    "brdffit_table_write": (_status, [_P, C.c_char_p, _err]),
    "brdffit_table_free": (None, [_P]),
    "brdffit_table_values": (C.POINTER(C.c_double), [_P]),
    "brdffit_table_fill_model": (_status, [_P, c_enum, C.POINTER(Params), c_enum, _err]),
    "brdffit_table_lookup": (_status, [_P, _P, _P, c_enum, c_enum, _P, _err]),
    "brdffit_table_lookup_batch": (
        _status, [_P, C.c_size_t, _P, _P, c_enum, c_enum, _P, _err]),
    # samples
    "brdffit_sample_options_init": (None, [C.POINTER(SampleOptions), C.c_size_t]),
    "brdffit_samples_create": (_status, [_P, C.POINTER(SampleOptions), C.POINTER(_P), _err]),
    "brdffit_samples_free": (None, [_P]),
    "brdffit_samples_count": (C.c_size_t, [_P]),
    "brdffit_samples_masked": (C.c_size_t, [_P]),
    "brdffit_samples_beyond_cutoff": (C.c_size_t, [_P]),
    "brdffit_samples_get": (_status, [_P, C.c_size_t, C.POINTER(Sample), _err]),
    "brdffit_samples_options": (_status, [_P, C.POINTER(SampleOptions), _err]),
    "brdffit_samples_prepare": (_status, [_P, c_enum, _err]),
    # contexts and fits
    "brdffit_context_options_init": (None, [C.POINTER(ContextOptions), C.c_size_t]),
    "brdffit_context_create": (_status, [C.POINTER(ContextOptions), C.POINTER(_P), _err]),
    "brdffit_context_free": (None, [_P]),
    "brdffit_context_backend": (c_enum, [_P]),
    "brdffit_context_describe": (C.c_char_p, [_P]),
    "brdffit_fit_options_init": (None, [C.POINTER(FitOptions), C.c_size_t]),
    "brdffit_fit": (
        _status,
        [_P, _P, c_enum, C.POINTER(FitOptions), C.POINTER(FitResult), _err],
    ),
    "brdffit_error_of": (
        _status,
        [_P, _P, c_enum, C.POINTER(Params), C.POINTER(C.c_double), _err],
    ),
    "brdffit_error_metric": (
        _status,
        [_P, _P, c_enum, C.POINTER(Params), c_enum, C.POINTER(C.c_double), _err],
    ),
    # renders and incidence-plane curves
    "brdffit_render_default_lights": (C.c_int, [C.POINTER(Light)]),
    "brdffit_render_options_init": (None, [C.POINTER(RenderOptions), C.c_size_t]),
    "brdffit_render_table": (
        _status, [_P, C.POINTER(RenderOptions), _P, C.c_size_t, _err]),
    "brdffit_render_model": (
        _status,
        [c_enum, C.POINTER(Params), C.POINTER(RenderOptions), _P, C.c_size_t, _err],
    ),
    "brdffit_image_error": (
        _status,
        [_P, _P, C.c_int, C.c_int, C.c_size_t, C.POINTER(C.c_double), C.POINTER(C.c_size_t),
         _err],
    ),
    "brdffit_flip": (
        _status,
        [_P, _P, C.c_int, C.c_int, C.c_size_t, C.c_double, _P, C.POINTER(C.c_double), _err],
    ),
    # directional albedo
    "brdffit_albedo_model": (
        _status, [c_enum, C.POINTER(Params), C.c_size_t, _P, _P, _err]),
    "brdffit_albedo_table": (
        _status, [_P, c_enum, c_enum, C.c_size_t, _P, _P, _P, _err]),
    "brdffit_curve_options_init": (None, [C.POINTER(CurveOptions), C.c_size_t]),
    "brdffit_curve_theta_o": (_status, [C.POINTER(CurveOptions), _P, _err]),
    "brdffit_curve_table": (_status, [_P, C.POINTER(CurveOptions), _P, C.c_size_t, _err]),
    "brdffit_curve_model": (
        _status,
        [c_enum, C.POINTER(Params), C.POINTER(CurveOptions), _P, C.c_size_t, _err],
    ),
}
