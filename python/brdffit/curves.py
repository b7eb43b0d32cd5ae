# SPDX-License-Identifier: MIT
"""Incidence-plane curves of a measured table or a model: the data of the
paper's cube-root BRDF plots, as NumPy arrays (one C call for all of them).

Directions (brdffit_curve_options in include/brdffit.h): for each theta_i,
wi = (-sin ti, 0, cos ti) and wo = (sin to, 0, cos to) with theta_o =
-90 + 180 (k + 0.5) / points degrees (no sample on the horizon; theta_o > 0
the mirror side).  Values: f per channel in 1/sr, no cosine factor, no cube
root; a measured value whose lookup meets a masked bin is -1 in that
channel."""

import ctypes

import numpy as np

from . import _abi, _lib
from ._arrays import c_int, real_array
from ._source import shading_source
from .errors import InvalidArgumentError, Status
from .table import interp_id, scale_id

_BAD = Status.INVALID_ARGUMENT


def incidence_curves(source, params=None, *, theta_i=(20, 40, 60, 75), points=180,
                     interp="trilinear", scale="standard"):
    """(theta_o, rgb): the points' theta_o in degrees, shape (points,), and f
    along each curve, shape (len(theta_i), points, 3) float64 ((points, 3)
    for a single number theta_i).

    source: a Table (brdffit_curve_table), a model (name, id or Model) with
    params, or a fit result (brdffit_curve_model).  theta_i: 1..16 angles in
    [0, 90) degrees; points: 2..100000.  Bad arguments raise the library's
    message."""
    table, m, cp = shading_source(source, params)
    lib = _lib.cdll()
    opt = _abi.CurveOptions()
    lib.brdffit_curve_options_init(ctypes.byref(opt), ctypes.sizeof(opt))
    single = np.ndim(theta_i) == 0
    angles = np.array(real_array("theta_i", theta_i), dtype=np.float64).reshape(-1)
    if angles.size > _abi.CURVE_MAX_THETA_I:
        raise InvalidArgumentError(
            _BAD, f"theta_i: {angles.size} angles, at most {_abi.CURVE_MAX_THETA_I}")
    opt.ntheta_i = angles.size
    for a, t in enumerate(angles):
        opt.theta_i_deg[a] = t
    n = opt.npoints = c_int("points", points)
    opt.interp, opt.scale = interp_id(interp), scale_id(scale)
    rgb = None
    if angles.size and 2 <= n <= _abi.CURVE_MAX_POINTS:
        rgb = np.empty((angles.size, n, 3), dtype=np.float64)
    # with no buffer (options the library refuses) the call returns its message
    addr = rgb.ctypes.data if rgb is not None else None
    stride = rgb.strides[0] // 8 if rgb is not None else 0
    if table is not None:
        _lib.call("brdffit_curve_table", table._h.ptr, ctypes.byref(opt), addr, stride)
    else:
        _lib.call("brdffit_curve_model", m.id, ctypes.byref(cp), ctypes.byref(opt), addr, stride)
    if rgb is None:
        raise InvalidArgumentError(_BAD, f"curves: {angles.size} theta_i, {n} points")
    theta_o = np.empty(n, dtype=np.float64)
    _lib.call("brdffit_curve_theta_o", ctypes.byref(opt), theta_o.ctypes.data)
    return theta_o, (rgb[0] if single else rgb)
