# SPDX-License-Identifier: MIT
"""eval: a model's BRDF at many direction pairs in one C call."""

import ctypes

from . import _arrays, _lib
from .models import resolve


def eval(model, params, wi, wo, out=None):  # noqa: A001 (the C API's name)
    """f(wi, wo) per channel, without the cosine factor, in 1/sr.

    model: a name, id or Model; params: a Params, a fit result, or
    d_r d_g d_b s_r s_g s_b p0 [p1 [p2 [p3]]]; wi, wo: arrays of shape (..., 3)
    (broadcast against each other; wi toward the light, wo toward the
    viewer; need not be unit).  Returns an array of shape (..., 3) (R, G, B),
    or fills out.  One brdffit_eval_batch call for all pairs; no copy of
    float64 C-contiguous inputs.  Raises ParamRangeError for parameters
    outside the model's bounds, InvalidArgumentError for a non-finite or
    zero direction (the library's message: the first such pair, flat index
    over the broadcast pairs, and how many)."""
    m, _, cp = resolve(model, params)
    a, b, shape = _arrays.pairs(wi, wo)
    rgb = _arrays.output(out, shape)
    _lib.call("brdffit_eval_batch", m.id, ctypes.byref(cp), a.size // 3, a.ctypes.data,
              b.ctypes.data, rgb.ctypes.data)
    return rgb
