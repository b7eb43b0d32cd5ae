# SPDX-License-Identifier: MIT
"""models(), model(), Params, metric_name: the registry as the library has it."""

import subprocess

import numpy as np
import pytest


def test_models_are_the_registrys(brdffit, cli):
    ms = brdffit.models()
    assert [m.id for m in ms] == list(range(len(ms)))
    names = [m.name for m in ms]
    for expected in ("ward", "ward-duer", "blinn-phong", "lafortune", "cook-torrance",
                     "ashikhmin-shirley", "he"):
        assert expected in names
    # the program lists the same models, parameters and bounds
    out = subprocess.run([cli, "models"], check=True, capture_output=True, text=True).stdout
    for m in ms:
        assert m.name in out and m.title
        assert m.nparams == len(m.params) == len(m.param_names) >= 1
        for p in m.params:
            assert p.name in out
            assert p.lower <= p.start <= p.upper
            assert np.isfinite([p.lower, p.upper, p.start]).all()
            assert isinstance(p.unit, str)
    assert brdffit.models() is ms  # read once per library
    he = brdffit.model("he")
    assert he.chromatic and not brdffit.model("ward").chromatic
    assert he.param_names == ("tau", "sigma0", "n")
    # units, maps and default starts come from the registry too
    assert [p.unit for p in he.params] == ["um", "um", ""]
    for m in ms:  # the program prints the same default starts
        assert m.default_starts >= 1 and f"; {m.default_starts} starts" in out
    assert [p.map for p in brdffit.model("lafortune").params] == ["direction", "direction", "log"]
    assert all(p.description for m in ms for p in m.params)


def test_model_lookup(brdffit):
    ct = brdffit.model("cook-torrance")
    assert brdffit.model("cook_torrance") is ct
    assert brdffit.model("Cook-Torrance") is ct and brdffit.model("COOK_TORRANCE") is ct
    assert brdffit.model("GGX") is brdffit.model("ggx")
    assert brdffit.model(ct.id) is ct
    assert brdffit.model(np.int64(ct.id)) is ct
    assert brdffit.model(ct) is ct
    assert str(ct) == "cook-torrance" and repr(ct) == "brdffit.model('cook-torrance')"
    with pytest.raises(brdffit.UnknownModelError) as e:
        brdffit.model("phong")
    assert e.value.status == brdffit.Status.UNKNOWN_MODEL and "phong" in str(e.value)
    assert isinstance(e.value, ValueError) and isinstance(e.value, brdffit.BrdffitError)
    for bad_id in (-1, len(brdffit.models())):
        with pytest.raises(brdffit.UnknownModelError):
            brdffit.model(bad_id)
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.model(1.5)


def test_params(brdffit):
    p = brdffit.Params([0.1, 0.2, 0.3], 0.5, [0.2, 0.1])
    assert p.d.tolist() == [0.1, 0.2, 0.3] and p.s.tolist() == [0.5] * 3
    assert p.p.tolist() == [0.2, 0.1] and p.lambda_um.tolist() == [0, 0, 0]
    q = brdffit.Params.from_vector([0.1, 0.2, 0.3, 0.5, 0.5, 0.5, 0.2, 0.1])
    assert p == q and q.vector().tolist() == [0.1, 0.2, 0.3, 0.5, 0.5, 0.5, 0.2, 0.1]
    assert p != brdffit.Params([0.1, 0.2, 0.3], 0.5, [0.2, 0.11])
    assert "Params(d=[0.1, 0.2, 0.3]" in repr(p)
    he = brdffit.Params(0.1, 0.2, [10, 0.5, 2], lambda_um=[0.6, 0.5, 0.4])
    assert "lambda_um=[0.6, 0.5, 0.4]" in repr(he)
    c = he.to_c()
    assert list(c.p) == [10, 0.5, 2, 0] and list(c.lambda_um) == [0.6, 0.5, 0.4]
    assert brdffit.Params.from_c(c, 3) == he
    for bad in (lambda: brdffit.Params([1, 2], 0, [1]),
                lambda: brdffit.Params(0, 0, [1, 2, 3, 4, 5]),
                lambda: brdffit.Params("x", 0, [1]),
                lambda: brdffit.Params(0, 0, ["a"]),
                lambda: brdffit.Params.from_vector([1, 2, 3]),
                lambda: brdffit.Params.from_vector(["a"] * 7)):
        with pytest.raises(brdffit.InvalidArgumentError):
            bad()


def test_metric_name(brdffit):
    assert brdffit.metric_name() == "ngan-l2"


def test_errors_carry_status_and_message(brdffit):
    e = brdffit.errors.make_error(brdffit.Status.FILE_TRUNCATED, "x: truncated at byte 9")
    assert type(e) is brdffit.FileTruncatedError and isinstance(e, brdffit.FileError)
    assert e.status == brdffit.Status.FILE_TRUNCATED and str(e) == "x: truncated at byte 9"
    unknown = brdffit.errors.make_error(250, "new")
    assert type(unknown) is brdffit.BrdffitError and unknown.status == 250
    import pickle

    again = pickle.loads(pickle.dumps(e))
    assert type(again) is brdffit.FileTruncatedError and again.status == e.status
    lib_err = pickle.loads(pickle.dumps(brdffit.LibraryError("gone")))
    assert lib_err.status is None and lib_err.message == "gone"
    for status in brdffit.Status:
        if status != brdffit.Status.OK:
            cls = brdffit.errors.error_class(status)
            assert issubclass(cls, brdffit.BrdffitError) and cls is not brdffit.BrdffitError
