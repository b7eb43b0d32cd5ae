# SPDX-License-Identifier: MIT
"""Table: read, bad files raising the right exception, values as a view,
from_array, from_model, write, lookup equal to the C lookup."""

import ctypes
import gc
import os
import struct

import numpy as np
import pytest

BINS = 90 * 90 * 180


@pytest.fixture(scope="module")
def good_file(brdffit, tmp_path_factory):
    """A small valid MERL file written by the library (a Cook-Torrance table)."""
    path = str(tmp_path_factory.mktemp("tables") / "ct.binary")
    brdffit.Table.from_model("cook-torrance", [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.15]).write(path)
    return path


def test_read_real_table(brdffit, alum_bronze):
    t = brdffit.Table.read(alum_bronze)
    v = t.values
    assert v.shape == (3, 90, 90, 180) and v.dtype == np.float64
    with open(alum_bronze, "rb") as f:
        raw = f.read()
    assert struct.unpack("<3i", raw[:12]) == (90, 90, 180)
    assert np.array_equal(v.reshape(-1), np.frombuffer(raw, dtype="<f8", offset=12))
    assert repr(t) == "<brdffit.Table 3x90x90x180>"
    t2 = brdffit.Table.read(os.fsencode(alum_bronze))  # bytes paths too
    assert np.array_equal(t2.values, v)


def test_values_is_a_view_that_keeps_the_table(brdffit, cdll):
    t = brdffit.Table.zeros()
    a, b = t.values, t.values
    assert np.shares_memory(a, b) and a.flags.writeable
    addr = ctypes.cast(cdll.brdffit_table_values(t._h.ptr), ctypes.c_void_p).value
    assert a.ctypes.data == addr  # the library's own buffer: no copy
    a[1, 2, 3, 4] = 7.5
    assert b[1, 2, 3, 4] == 7.5
    del t, b
    gc.collect()
    assert a[1, 2, 3, 4] == 7.5 and a.sum() == 7.5  # still the live buffer


@pytest.mark.parametrize("make, cls, text", [
    (lambda d, good: os.path.join(d, "missing.binary"), "FileOpenError", "missing.binary"),
    (lambda d, good: d, "FileNotRegularError", None),
    (lambda d, good: _write(d, "empty.binary", b""), "FileEmptyError", "empty.binary"),
    (lambda d, good: _write(d, "short.binary", struct.pack("<3i", 90, 90, 180) + b"\0" * 1000),
     "FileTruncatedError", "short.binary"),
    (lambda d, good: _write(d, "header.binary", b"\x5a\0\0"), "FileTruncatedError", None),
    (lambda d, good: _write(d, "dims.binary", struct.pack("<3i", 90, 90, 360) + b"\0" * 64),
     "FileDimsError", "360"),
    (lambda d, good: _write(d, "trailing.binary", open(good, "rb").read() + b"x"),
     "FileTrailingError", "trailing.binary"),
    (lambda d, good: _write(d, "nan.binary", _with_nan(good)), "FileNonfiniteError", "NaN"),
])
def test_bad_files_raise_the_right_exception(brdffit, tmp_path, good_file, make, cls, text):
    path = make(str(tmp_path), good_file)
    with pytest.raises(getattr(brdffit, cls)) as e:
        brdffit.Table.read(path)
    err = e.value
    assert type(err).__name__ == cls and isinstance(err, brdffit.FileError)
    assert err.status == getattr(brdffit.Status, _status_name(cls))
    assert path in str(err) or os.path.basename(path) in str(err)
    if text:
        assert text in str(err)


def _status_name(cls):
    return {"FileOpenError": "FILE_OPEN", "FileNotRegularError": "FILE_NOT_REGULAR",
            "FileEmptyError": "FILE_EMPTY", "FileTruncatedError": "FILE_TRUNCATED",
            "FileDimsError": "FILE_DIMS", "FileTrailingError": "FILE_TRAILING",
            "FileNonfiniteError": "FILE_NONFINITE"}[cls]


def _write(d, name, data):
    path = os.path.join(d, name)
    with open(path, "wb") as f:
        f.write(data)
    return path


def _with_nan(good):
    data = bytearray(open(good, "rb").read())
    data[12 + 8 * 1000: 12 + 8 * 1001] = struct.pack("<d", float("nan"))
    return bytes(data)


def test_write_and_read_back(brdffit, tmp_path):
    rng = np.random.default_rng(3)
    values = rng.uniform(-1, 100, size=(3, 90, 90, 180))
    t = brdffit.Table.from_array(values)
    assert np.array_equal(t.values, values) and not np.shares_memory(t.values, values)
    path = str(tmp_path / "rand.binary")
    t.write(path)
    assert os.path.getsize(path) == 12 + 3 * BINS * 8
    assert np.array_equal(brdffit.Table.read(path).values, values)
    with pytest.raises(brdffit.FileWriteError) as e:
        t.write(str(tmp_path / "no" / "such" / "dir.binary"))
    assert e.value.status == brdffit.Status.FILE_WRITE and "dir.binary" in str(e.value)


def test_from_array_converts_and_refuses(brdffit):
    flat = np.arange(3 * BINS, dtype=np.float32).reshape(3, BINS)
    t = brdffit.Table.from_array(flat)
    assert t.values[2, 89, 89, 179] == float(flat[2, -1])
    assert np.array_equal(brdffit.Table.from_array(np.ones((3, 90, 90, 180), dtype=np.int16)).values,
                          np.ones((3, 90, 90, 180)))
    bad = np.zeros((3, 90, 90, 180))
    bad[1, 2, 3, 4] = np.inf
    with pytest.raises(brdffit.InvalidArgumentError, match=r"channel G, bin 2,3,4"):
        brdffit.Table.from_array(bad)
    with pytest.raises(brdffit.InvalidArgumentError, match="shape"):
        brdffit.Table.from_array(np.zeros((3, 90, 90, 90)))
    with pytest.raises(brdffit.InvalidArgumentError, match=r"values: complex numbers \(complex128\)"):
        brdffit.Table.from_array(np.zeros((3, 90, 90, 180), dtype=complex))
    assert not brdffit.Table.zeros().values.any()


def test_from_model_and_scales(brdffit):
    p = [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.15]
    std = brdffit.Table.from_model("cook-torrance", p)
    flat = brdffit.Table.from_model("cook-torrance", p, scale="flat")
    fs, ff = brdffit.scale_factors("standard"), brdffit.scale_factors("flat")
    assert np.allclose(fs, np.array([1, 1.15, 1.66]) / 1500, rtol=1e-15)
    assert np.array_equal(ff, np.full(3, 1 / 1500))
    wi = np.array([[0.0, 0.0, 1.0], [0.3, 0.1, 0.9]])
    wo = np.array([[0.0, 0.0, 1.0], [-0.2, 0.0, 0.95]])
    a = std.lookup(wi, wo, scale="standard")
    b = flat.lookup(wi, wo, scale="flat")
    assert np.allclose(a, b, rtol=1e-12)
    assert (std.values < 0).any()  # below the horizon: -1, as MERL stores it
    with pytest.raises(brdffit.InvalidArgumentError, match="scale"):
        brdffit.scale_factors("linear")
    with pytest.raises(brdffit.ParamRangeError):
        brdffit.Table.from_model("cook-torrance", p[:-1] + [-1])


def test_lookup_equals_the_c_lookup(brdffit, cdll, alum_bronze):
    t = brdffit.Table.read(alum_bronze)
    rng = np.random.default_rng(7)
    n = 300
    wi = rng.normal(size=(n, 3))
    wo = rng.normal(size=(n, 3))
    wi[:, 2] = np.abs(wi[:, 2])
    wo[:, 2] = np.abs(wo[:, 2])
    wi[0], wo[0] = [0, 0, 1], [0, 0, 1]
    for scale in ("standard", "flat"):
        for interp in ("nearest", "trilinear"):
            got = t.lookup(wi, wo, scale=scale, interp=interp)
            assert got.shape == (n, 3)
            for k in range(n):
                one = np.empty(3)
                a, b = np.ascontiguousarray(wi[k]), np.ascontiguousarray(wo[k])
                assert cdll.brdffit_table_lookup(
                    t._h.ptr, a.ctypes.data, b.ctypes.data, brdffit._abi.SCALES[scale],
                    brdffit._abi.INTERPS[interp], one.ctypes.data, None) == 0
                assert np.array_equal(got[k], one)
    # a bin's own directions give its stored value x scale
    v = t.values
    s = brdffit.Samples(t)[12345]
    i, j, k = s.bin
    got = t.lookup(s.wi, s.wo)
    assert np.allclose(got, v[:, i, j, k] * brdffit.scale_factors(), rtol=1e-15)
    out = np.empty((n, 3))
    assert t.lookup(wi, wo, out=out) is out


def test_lookup_bad_input(brdffit):
    t = brdffit.Table.zeros()
    wi = np.array([[0, 0, 1.0], [0, 0, 0], [0.1, 0.2, 0.9]])
    wo = np.array([[0, 0, 1.0]] * 3)
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        t.lookup(wi, wo)
    assert e.value.message == (
        "brdffit_table_lookup_batch: pair 1 of 3 (1 bad pair, rgb -1 there): wi = (0, 0, 0) is "
        "not a finite, non-zero direction")
    with pytest.raises(brdffit.InvalidArgumentError, match="interp"):
        t.lookup(wi, wo, interp="cubic")
    with pytest.raises(brdffit.InvalidArgumentError, match="scale"):
        t.lookup(wi, wo, scale=5)
    masked = brdffit.Table.from_array(-np.ones((3, 90, 90, 180)))
    assert (masked.lookup(wi[[0, 2]], wo[[0, 2]]) == -1).all()
