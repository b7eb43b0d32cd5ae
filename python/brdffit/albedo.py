# SPDX-License-Identifier: MIT
"""The directional albedo a(theta_o) = integral of f(wi, wo) cos theta_i dwi
over the hemisphere, per channel, of a model at parameters or of a measured
table (brdffit_albedo_model, brdffit_albedo_table in include/brdffit.h):
how much of the light from wo the surface reflects; above 1, more than it
receives."""

import ctypes

import numpy as np

from . import _lib
from ._arrays import real_array
from ._source import shading_source
from .errors import InvalidArgumentError, Status
from .table import interp_id, scale_id

#: The angles the fit records use: 0, 5, ..., 85 degrees.
THETA_O = tuple(range(0, 90, 5))


def albedo(source, params=None, theta_o=THETA_O, *, interp="trilinear", scale="standard",
           masked=False):
    """The albedo at each theta_o (degrees, each in [0, 90)), shape
    (len(theta_o), 3) float64 ((3,) for a single number).

    source: a Table (brdffit_albedo_table: its lookups at interp and scale; a
    masked channel counts 0 there, as in the renders), a model (name, id or
    Model) with params, or a fit result (brdffit_albedo_model).  masked=True
    (tables only) returns (albedo, share) with share, per angle, the part of
    the cosine-weighted hemisphere where some channel was masked.  Bad
    arguments raise the library's message."""
    table, m, cp = shading_source(source, params)
    if masked and table is None:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT,
                                   "masked: a model has no masked bins (pass a Table)")
    single = np.ndim(theta_o) == 0
    angles = np.ascontiguousarray(real_array("theta_o", theta_o), dtype=np.float64).reshape(-1)
    n = angles.size
    rgb = np.empty((n, 3), dtype=np.float64)
    share = np.zeros(n, dtype=np.float64)
    if table is not None:
        _lib.call("brdffit_albedo_table", table._h.ptr, scale_id(scale), interp_id(interp),
                  ctypes.c_size_t(n), angles.ctypes.data, rgb.ctypes.data, share.ctypes.data)
    else:
        _lib.call("brdffit_albedo_model", m.id, ctypes.byref(cp), ctypes.c_size_t(n),
                  angles.ctypes.data, rgb.ctypes.data)
    out = rgb[0] if single else rgb
    if masked:
        return out, (share[0] if single else share)
    return out
