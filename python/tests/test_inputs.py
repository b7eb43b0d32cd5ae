# SPDX-License-Identifier: MIT
"""What the package refuses before C sees it: a path or name with a NUL
byte (C would read up to it: another file), arrays and numbers that are not
real (bool, complex, text, objects, dates), and pickling or copying an
object that owns library memory; and the library's refusal of a render it
cannot represent, as the package raises it."""

import copy
import os
import pickle

import numpy as np
import pytest

WARD = [0.1, 0.1, 0.1, 0.2, 0.2, 0.2, 0.1]

NOT_REAL = [
    (np.array([0, 0, 1 + 1j]), r"complex numbers \(complex128\)"),
    (np.array(["0", "0", "1"]), r"text \(<U1\)"),
    (np.array([b"0", b"0", b"1"]), r"bytes \(\|S1\)"),
    (np.array([0, 0, 1], dtype=object), r"Python objects \(object\)"),
    (np.array(["2020-01-01"] * 3, dtype="datetime64[D]"), r"dates \(datetime64"),
    (np.array([1, 2, 3], dtype="timedelta64[s]"), r"time spans \(timedelta64"),
    (np.array([False, False, True]), r"booleans \(bool\)"),
]


def test_nul_in_a_path_refused(brdffit, tmp_path):
    victim = tmp_path / "victim"
    victim.write_bytes(b"not a table, and kept")
    t = brdffit.Table.zeros()
    for path in (str(victim) + "\x00-new.binary", os.fsencode(victim) + b"\x00-new.binary"):
        with pytest.raises(brdffit.InvalidArgumentError, match="contains a NUL byte") as e:
            t.write(path)
        assert e.value.status == brdffit.Status.INVALID_ARGUMENT
        with pytest.raises(brdffit.InvalidArgumentError, match="path: .* contains a NUL byte"):
            brdffit.Table.read(path)
    assert victim.read_bytes() == b"not a table, and kept"
    assert sorted(os.listdir(tmp_path)) == ["victim"]
    with pytest.raises(brdffit.InvalidArgumentError, match="load_library: .* contains a NUL byte"):
        brdffit.load_library(str(tmp_path / "libbrdffit.so.1") + "\x00x")
    with pytest.raises(brdffit.InvalidArgumentError, match="path: a path"):
        t.write(3)
    # the library in use is still the one loaded before
    assert brdffit._lib.library().path == os.environ["BRDFFIT_LIBRARY"]


def test_nul_in_a_name_refused(brdffit):
    with pytest.raises(brdffit.InvalidArgumentError, match="model: 'ward\\\\x00x' contains a NUL"):
        brdffit.model("ward\x00x")
    with pytest.raises(brdffit.InvalidArgumentError, match="device: .* contains a NUL"):
        brdffit.Context(backend="host", device="0:0\x00x")


@pytest.mark.parametrize("arr, what", NOT_REAL)
def test_directions_must_be_real(brdffit, arr, what):
    with pytest.raises(brdffit.InvalidArgumentError, match=f"wi: {what}.*expected real numbers"):
        brdffit.eval("ward", WARD, arr, [0, 0, 1])
    with pytest.raises(brdffit.InvalidArgumentError, match=f"wo: {what}"):
        brdffit.Table.zeros().lookup([0, 0, 1], arr)


@pytest.mark.parametrize("arr, what", NOT_REAL)
def test_parameters_and_images_must_be_real(brdffit, arr, what):
    with pytest.raises(brdffit.InvalidArgumentError, match=f"^d: {what}"):
        brdffit.Params(arr, 0.1, [0.1])
    with pytest.raises(brdffit.InvalidArgumentError, match=f"^p: {what}"):
        brdffit.Params(0.1, 0.1, arr[:1])
    with pytest.raises(brdffit.InvalidArgumentError, match=f"^params: {what}"):
        brdffit.eval("ward", np.concatenate([arr] * 3)[:7], [0, 0, 1], [0, 0, 1])
    with pytest.raises(brdffit.InvalidArgumentError, match=f"^theta_i: {what}"):
        brdffit.incidence_curves("ward", WARD, theta_i=arr)
    with pytest.raises(brdffit.InvalidArgumentError, match=rf"^lights\[0\].rgb: {what}"):
        brdffit.render("ward", WARD, size=4, lights=[((0, 0, 1), arr)])
    env = np.stack([np.stack([arr, arr])] * 2)  # (2, 2, 3)
    with pytest.raises(brdffit.InvalidArgumentError, match=f"^env: {what}"):
        brdffit.render("ward", WARD, size=4, env=env)
    img = np.zeros((2, 2, 4), dtype=arr.dtype)
    with pytest.raises(brdffit.InvalidArgumentError, match=f"^img: {what}"):
        brdffit.image_error(np.ones((2, 2, 4), dtype=np.float32), img)


def test_table_values_must_be_real(brdffit):
    with pytest.raises(brdffit.InvalidArgumentError, match=r"values: booleans \(bool\)"):
        brdffit.Table.from_array(np.ones((3, 90, 90, 180), dtype=bool))


@pytest.mark.parametrize("value", [True, "80", 80 + 0j, [80]])
def test_numbers_must_be_real(brdffit, value):
    t = brdffit.Table.from_model("ward", WARD)
    with pytest.raises(brdffit.InvalidArgumentError, match="^cutoff: "):
        brdffit.Samples(t, cutoff=value)
    with pytest.raises(brdffit.InvalidArgumentError, match="^fit option ftol: "):
        brdffit.fitting.fit_options(ftol=value)


def test_integers_are_not_bools(brdffit):
    with pytest.raises(brdffit.InvalidArgumentError, match="size: True is not an integer"):
        brdffit.render("ward", WARD, size=True)
    with pytest.raises(brdffit.InvalidArgumentError, match="fit option starts: bad value True"):
        brdffit.fitting.fit_options(starts=True)
    assert brdffit.fitting.fit_options(starts=np.int64(3)).starts == 3
    assert brdffit.fitting.fit_options(ftol=np.float32(0.5)).ftol == 0.5


def test_objects_of_library_memory_are_not_pickled(brdffit):
    t = brdffit.Table.from_model("ward", WARD)
    s = brdffit.Samples(t)
    with brdffit.Context(backend="host") as ctx:
        for obj, advice in ((t, "write\\(\\) and read\\(\\) it"), (s, "make it again from its Table"),
                            (ctx, "make a Context in each process"),
                            (brdffit._lib.library(), "call brdffit.load_library in each process")):
            name = type(obj).__name__
            for attempt in (pickle.dumps, copy.copy, copy.deepcopy):
                with pytest.raises(TypeError, match=f"brdffit.{name} cannot be pickled or copied: "
                                   f".*; {advice}"):
                    attempt(obj)
    # what they hold is plain data and pickles: the values, a fit's parameters
    again = brdffit.Table.from_array(pickle.loads(pickle.dumps(t.values)))
    assert np.array_equal(again.values, t.values)
    p = brdffit.Params.from_vector(WARD)
    assert pickle.loads(pickle.dumps(p)) == p


def test_render_refuses_an_overflowing_environment(brdffit):
    env = np.ones((2, 4, 3), dtype=np.float32)
    env[1, 2, 1] = 1e36
    with pytest.raises(brdffit.ValueRangeError, match=r"texel \(2, 1\) channel 1 is 1e\+36") as e:
        brdffit.render("ward", WARD, size=8, lights=[], env=env)
    assert e.value.status == brdffit.Status.VALUE_RANGE
    env[1, 2, 1] = 1e20
    img = brdffit.render("ward", WARD, size=8, lights=[], env=env, env_samples=16)
    assert np.isfinite(img).all()
    with pytest.raises(brdffit.ValueRangeError, match="beyond the largest float"):
        brdffit.render("ward", [1e300] * 3 + [0.2] * 3 + [0.1], size=8)
