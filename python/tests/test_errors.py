# SPDX-License-Identifier: MIT
"""Every fallible library call the package makes raises the exception of its
status carrying the library's own message (the brdffit_error it filled)."""

import ctypes

import numpy as np
import pytest


def test_unknown_model_name_has_the_librarys_message(brdffit):
    with pytest.raises(brdffit.UnknownModelError) as e:
        brdffit.model("phong")
    assert e.value.status == brdffit.Status.UNKNOWN_MODEL
    names = ", ".join(m.name for m in brdffit.models())
    assert e.value.message == f"no model named 'phong' (models: {names})"


def test_scale_factors_unknown_scale(brdffit):
    from brdffit import _lib

    f = np.empty(3)
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        _lib.call("brdffit_scale_factors", 7, f.ctypes.data)
    assert e.value.message == "brdffit_scale_factors: unknown scale 7 (0 standard, 1 flat)"


def test_eval_bad_parameter_has_the_librarys_message(brdffit):
    with pytest.raises(brdffit.ParamRangeError) as e:
        brdffit.eval("ward", [0.1, 0.1, 0.1, 0.2, 0.2, 0.2, 7.0], [0, 0, 1.0], [0, 0, 1.0])
    assert e.value.message.startswith("ward: alpha = 7 outside [")


def test_lookup_opposite_directions(brdffit):
    t = brdffit.Table.zeros()
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        t.lookup([[0.6, 0, 0.8]], [[-0.6, 0, -0.8]])
    assert e.value.message == (
        "brdffit_table_lookup_batch: pair 0 of 1 (1 bad pair, rgb -1 there): "
        "wo = (-0.6, 0, -0.8) is opposite to wi: no half vector")


def test_samples_get_index_beyond_the_set(brdffit):
    from brdffit import _abi, _lib

    t = brdffit.Table.zeros()
    s = brdffit.Samples(t)
    out = _abi.Sample()
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        _lib.call("brdffit_samples_get", s._h.ptr, s.count, ctypes.byref(out))
    assert e.value.message == (
        f"brdffit_samples_get: index {s.count}, but the set has {s.count} samples")


def test_sized_results_set_and_checked(brdffit):
    from brdffit import _abi, _lib

    assert _abi.Sample().size == ctypes.sizeof(_abi.Sample)
    assert _abi.FitResult().size == ctypes.sizeof(_abi.FitResult)
    s = brdffit.Samples(brdffit.Table.zeros())
    out = _abi.Sample()
    out.size = 8
    with pytest.raises(brdffit.OptionsSizeError) as e:
        _lib.call("brdffit_samples_get", s._h.ptr, 0, ctypes.byref(out))
    assert e.value.message.startswith(
        "brdffit_sample: size 8 is smaller than its first sized layout")


def test_image_error_non_finite_pixel(brdffit):
    ref = np.ones((2, 3, 4), dtype=np.float32)
    img = ref.copy()
    img[1, 2, 1] = np.nan
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        brdffit.image_error(ref, img)
    assert e.value.message == "brdffit_image_error: img pixel (col 2, row 1) channel G = nan"


def test_curve_theta_o_options_size(brdffit):
    from brdffit import _abi, _lib

    opt = _abi.CurveOptions()
    _lib.cdll().brdffit_curve_options_init(ctypes.byref(opt), ctypes.sizeof(opt))
    assert opt.size == ctypes.sizeof(opt)
    out = np.empty(opt.npoints)
    opt.size = ctypes.sizeof(opt) + 8
    with pytest.raises(brdffit.OptionsSizeError) as e:
        _lib.call("brdffit_curve_theta_o", ctypes.byref(opt), out.ctypes.data)
    assert e.value.status == brdffit.Status.OPTIONS_SIZE
    assert e.value.message.startswith(
        f"brdffit_curve_options: size {ctypes.sizeof(opt) + 8} is larger than this library's "
        f"struct ({ctypes.sizeof(opt)} bytes)")
