# SPDX-License-Identifier: MIT
"""Sphere renders of a measured table or a model into NumPy arrays (one C
call an image), and the image error between two renders.

Conventions (scene, camera, shading frame, lights, environment map,
coverage) are those of brdffit_render_options in include/brdffit.h: an
orthographic view of a unit sphere filling the size x size image, row 0 at
the top, wo = (0, 0, 1); RGBA float32, linear radiance in the units of the
lights' irradiance per steradian; A the coverage (0 off the sphere, 1 on it,
COVERAGE_MASKED where a table lookup met a masked bin)."""

import ctypes
from dataclasses import dataclass
from typing import Tuple

import numpy as np

from . import _abi, _lib
from ._arrays import c_int, real_array
from ._source import shading_source
from .errors import InvalidArgumentError, Status
from .models import _vector3
from .table import interp_id, scale_id

_BAD = Status.INVALID_ARGUMENT
COVERAGE_MASKED = _abi.COVERAGE_MASKED


@dataclass(frozen=True)
class Light:
    """A directional light: ``dir`` toward the light in the camera frame (x
    right, y up, z toward the viewer; need not be unit), ``rgb`` the
    irradiance E per channel (one number: the same for R, G, B)."""

    dir: Tuple[float, float, float]
    rgb: Tuple[float, float, float] = (1.0, 1.0, 1.0)


def default_lights():
    """The library's default lights (brdffit_render_default_lights): the key
    light and the grazing rim light."""
    buf = (_abi.Light * 2)()
    n = _lib.cdll().brdffit_render_default_lights(buf)
    return [Light(tuple(buf[k].dir), tuple(buf[k].rgb)) for k in range(n)]


def _set_lights(opt, lights):
    if lights is None:
        opt.nlights = _abi.RENDER_DEFAULT_LIGHTS
        return
    try:
        lights = list(lights)
    except TypeError:
        raise InvalidArgumentError(_BAD, "lights: a sequence of Light or (dir, rgb)") from None
    if len(lights) > _abi.RENDER_MAX_LIGHTS:
        raise InvalidArgumentError(
            _BAD, f"lights: {len(lights)} lights, at most {_abi.RENDER_MAX_LIGHTS}")
    for k, light in enumerate(lights):
        if not isinstance(light, Light):
            try:
                light = Light(*light)
            except TypeError:
                raise InvalidArgumentError(
                    _BAD, f"lights[{k}]: {light!r} is not a Light or a (dir, rgb) pair") from None
        d = _vector3(f"lights[{k}].dir", light.dir)
        if np.ndim(light.dir) == 0:
            raise InvalidArgumentError(_BAD, f"lights[{k}].dir: a direction of 3 numbers")
        e = _vector3(f"lights[{k}].rgb", light.rgb)
        for c in range(3):
            opt.lights[k].dir[c] = d[c]
            opt.lights[k].rgb[c] = e[c]
    opt.nlights = len(lights)


def _set_env(opt, env, env_samples):
    """Point opt at env's rows (float32, rows of contiguous RGB texels, any
    row stride; other arrays are copied so), kept alive as long as opt."""
    opt.env_samples = c_int("env_samples", env_samples)
    if env is None:
        return
    try:
        arr = np.asarray(env)
    except (TypeError, ValueError):
        raise InvalidArgumentError(_BAD, "env: not an array of numbers") from None
    if arr.dtype.kind not in "fiu":
        real_array("env", arr)  # raises, naming what it holds
    if arr.ndim != 3 or arr.shape[2] != 3:
        raise InvalidArgumentError(
            _BAD, f"env: shape {arr.shape} {arr.dtype}, expected (height, width, 3) RGB radiance")
    h, w = c_int("env height", arr.shape[0]), c_int("env width", arr.shape[1])
    rows_ok = (arr.dtype == np.float32 and arr.flags.aligned and arr.strides[2] == 4
               and arr.strides[1] == 12 and arr.strides[0] >= 12 * w and arr.strides[0] % 4 == 0)
    if not rows_ok:
        arr = np.ascontiguousarray(arr, dtype=np.float32)
    opt.env = arr.ctypes.data
    opt.env_array = arr  # what opt.env points into
    opt.env_width, opt.env_height = w, h
    opt.env_stride = arr.strides[0] // 4 if h > 1 else 3 * w


def _image_out(out, n):
    """The (n, n, 4) float32 array to render into and its row stride in floats."""
    if out is None:
        out = np.empty((n, n, 4), dtype=np.float32)
    ok = (isinstance(out, np.ndarray) and out.dtype == np.float32 and out.shape == (n, n, 4)
          and out.flags.writeable and out.flags.aligned and out.strides[2] == 4
          and out.strides[1] == 16 and out.strides[0] >= 16 * n and out.strides[0] % 4 == 0)
    if not ok:
        raise InvalidArgumentError(
            _BAD, f"out: must be a writable float32 array of shape ({n}, {n}, 4) whose rows "
            "are contiguous RGBA pixels (any row stride, e.g. a slice of a larger image)")
    return out, out.strides[0] // 4 if n > 1 else 4 * n


def render(source, params=None, *, size=256, lights=None, env=None, env_samples=256,
           interp="trilinear", scale="standard", threads=0, out=None):
    """A sphere shaded by a measured Table or by a model: a (size, size, 4)
    float32 RGBA array (linear radiance; A the coverage).

    source: a Table (brdffit_render_table), a model (name, id or Model) with
    params, or a fit result (brdffit_render_model).  lights: None for the
    default key and rim lights, else up to 16 Light or (dir, rgb) pairs
    ([] for none).  env: an optional lat-long map of RGB radiance, shape
    (height, width, 3), integrated with env_samples directions per pixel.
    interp and scale: the table lookup's.  threads: 0 for the online CPUs.
    out: an array to fill instead (any row stride).  One C call; bad
    arguments raise the library's message (InvalidArgumentError,
    ParamRangeError, ...)."""
    table, m, cp = shading_source(source, params)
    lib = _lib.cdll()
    opt = _abi.RenderOptions()
    lib.brdffit_render_options_init(ctypes.byref(opt), ctypes.sizeof(opt))
    n = c_int("size", size)
    opt.width = n
    _set_lights(opt, lights)
    _set_env(opt, env, env_samples)
    opt.interp = interp_id(interp)
    opt.scale = scale_id(scale)
    opt.threads = c_int("threads", threads)
    rgba, stride = None, 0
    if 1 <= n <= _abi.RENDER_MAX_WIDTH:
        rgba, stride = _image_out(out, n)
    # with no buffer (a size the library refuses) the call returns its message
    addr = rgba.ctypes.data if rgba is not None else None
    if table is not None:
        _lib.call("brdffit_render_table", table._h.ptr, ctypes.byref(opt), addr, stride)
    else:
        _lib.call("brdffit_render_model", m.id, ctypes.byref(cp), ctypes.byref(opt), addr, stride)
    if rgba is None:
        raise InvalidArgumentError(_BAD, f"render: size {n}")
    return rgba


def _image_in(name, img):
    arr = np.ascontiguousarray(real_array(name, img, np.float32))
    if arr.ndim != 3 or arr.shape[2] != 4 or 0 in arr.shape:
        raise InvalidArgumentError(_BAD, f"{name}: shape {arr.shape}, expected (height, width, 4)")
    return arr


def image_error(ref, img):
    """(error, covered): the RMS of img - ref over the pixels whose reference
    A is 1, relative to the reference's RMS there (brdffit_image_error), and
    the number of those pixels.  Both (height, width, 4) RGBA renders.
    NoSamplesError (the library's message) when no pixel is covered or the
    reference is black on all of them."""
    a, b = _image_in("ref", ref), _image_in("img", img)
    if a.shape != b.shape:
        raise InvalidArgumentError(_BAD, f"image_error: ref {a.shape} and img {b.shape} differ")
    h, w = c_int("height", a.shape[0]), c_int("width", a.shape[1])
    error, covered = ctypes.c_double(), ctypes.c_size_t()
    _lib.call("brdffit_image_error", a.ctypes.data, b.ctypes.data, w, h, 0, ctypes.byref(error),
              ctypes.byref(covered))
    return error.value, covered.value


def flip(ref, test, ppd=0.0):
    """(mean, map): LDR FLIP (NVIDIA's definition, brdffit_flip) of test
    against ref, both (height, width, 3) sRGB-encoded images in [0, 1] (uint8
    images are divided by 255); map the per-pixel FLIP, (height, width)
    float32 in [0, 1]; mean its mean over all pixels.  ppd: pixels per degree
    (0: 67.02, a 0.7 m wide 3840-pixel display at 0.7 m)."""
    imgs = []
    for name, img in (("ref", ref), ("test", test)):
        a = np.asarray(img)
        a = a / np.float32(255) if a.dtype == np.uint8 else a
        a = np.ascontiguousarray(real_array(name, a, np.float32))
        if a.ndim != 3 or a.shape[2] != 3 or 0 in a.shape:
            raise InvalidArgumentError(_BAD, f"{name}: shape {a.shape}, expected (height, width, 3)")
        imgs.append(a)
    a, b = imgs
    if a.shape != b.shape:
        raise InvalidArgumentError(_BAD, f"flip: ref {a.shape} and test {b.shape} differ")
    h, w = c_int("height", a.shape[0]), c_int("width", a.shape[1])
    fmap = np.zeros(a.shape[:2], dtype=np.float32)
    mean = ctypes.c_double()
    _lib.call("brdffit_flip", a.ctypes.data, b.ctypes.data, w, h, 0, float(ppd), fmap.ctypes.data,
              ctypes.byref(mean))
    return mean.value, fmap
