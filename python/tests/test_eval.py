# SPDX-License-Identifier: MIT
"""eval: one C call for all pairs, equal to the C evaluator and to the
reference values of ../shared/data/model-reference.tsv."""

import ctypes
import subprocess

import numpy as np
import pytest

from conftest import shared


def read_tsv(rel):
    rows, header = [], None
    with open(shared(rel)) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            fields = line.rstrip("\n").split("\t")
            if header is None:
                header = fields
                continue
            rows.append(dict(zip(header, fields)))
    return rows


def num(s):
    return float(s) if s != "" else 0.0


def reference_rows():
    by_model = {}
    for r in read_tsv("data/model-reference.tsv"):
        by_model.setdefault(r["model"], []).append(r)
    return by_model


def c_eval_one(cdll, brdffit, m, params, wi, wo):
    """brdffit_eval (the C evaluator, one pair per call)."""
    cp = params.to_c()
    a = np.ascontiguousarray(wi, dtype=np.float64)
    b = np.ascontiguousarray(wo, dtype=np.float64)
    rgb = np.empty(3)
    assert cdll.brdffit_eval(m.id, ctypes.byref(cp), a.ctypes.data, b.ctypes.data,
                             rgb.ctypes.data, None) == 0
    return rgb


@pytest.mark.shared
def test_reference_values_equal_the_c_evaluator(brdffit, cdll, cli):
    rows_by_model = reference_rows()
    assert sum(len(v) for v in rows_by_model.values()) == 384
    for name, rows in rows_by_model.items():
        m = brdffit.model(name)
        for material in sorted({r["material"] for r in rows}):
            mine = [r for r in rows if r["material"] == material]
            r0 = mine[0]
            vec = [num(r0[k]) for k in ("d_r", "d_g", "d_b", "s_r", "s_g", "s_b")]
            vec += [num(r0["p%d" % k]) for k in range(m.nparams)]
            params = brdffit.Params.from_vector(vec)
            wi = np.array([[num(r["wi_" + c]) for c in "xyz"] for r in mine])
            wo = np.array([[num(r["wo_" + c]) for c in "xyz"] for r in mine])
            ref = np.array([[num(r["f_" + c]) for c in "rgb"] for r in mine])
            got = brdffit.eval(name, params, wi, wo)  # every pair of this material at once
            assert got.shape == (len(mine), 3)
            for k in range(len(mine)):  # bit for bit the C evaluator's value
                assert np.array_equal(got[k], c_eval_one(cdll, brdffit, m, params, wi[k], wo[k]))
            # and the reference to the C suite's bound, max(1e-12, 2 n eps) for exponents
            n_exp = {"blinn-phong": 0, "lafortune": 2, "ashikhmin-shirley": 1}.get(name)
            tol = max(1e-12, 2 * params.p[n_exp] * 2.220446049250313e-16) if n_exp is not None \
                else 1e-12
            rel = np.abs(got - ref) / np.maximum(np.maximum(np.abs(got), np.abs(ref)), 1e-300)
            assert rel.max() <= tol, (name, material, rel.max())
        # the program's `eval` prints the same digits (%.17g round-trips)
        args = [cli, "eval", name] + [repr(float(x)) for x in params.vector()]
        args += ["--wi"] + [repr(float(x)) for x in wi[-1]] + ["--wo"] + [repr(float(x)) for x in wo[-1]]
        out = subprocess.run(args, check=True, capture_output=True, text=True).stdout.split()
        assert [float(x) for x in out] == got[-1].tolist()


@pytest.mark.shared
def test_he_equals_the_c_evaluator(brdffit, cdll):
    rows = read_tsv("data/he-reference.tsv")
    assert len(rows) > 50
    wi = np.array([[num(r["wi_" + c]) for c in "xyz"] for r in rows])
    wo = np.array([[num(r["wo_" + c]) for c in "xyz"] for r in rows])
    m = brdffit.model("he")
    for r0 in rows[:5]:
        params = brdffit.Params(0.0, 1.0, [num(r0["tau"]), num(r0["sigma0"]), num(r0["n"])])
        got = brdffit.eval(m, params, wi, wo)
        for k in range(len(rows)):
            assert np.array_equal(got[k], c_eval_one(cdll, brdffit, m, params, wi[k], wo[k]))


def test_shapes_and_no_copy(brdffit):
    p = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.3, 0.2]
    rng = np.random.default_rng(1)
    wi = rng.normal(size=(4, 5, 3))
    wi[..., 2] = np.abs(wi[..., 2])
    wo = rng.normal(size=(4, 5, 3))
    wo[..., 2] = np.abs(wo[..., 2])
    f = brdffit.eval("cook-torrance", p, wi, wo)
    assert f.shape == (4, 5, 3) and f.dtype == np.float64
    flat = brdffit.eval("cook-torrance", p, wi.reshape(-1, 3), wo.reshape(-1, 3))
    assert np.array_equal(flat.reshape(4, 5, 3), f)
    one = brdffit.eval("cook-torrance", p, wi[1, 2], wo[1, 2])
    assert one.shape == (3,) and np.array_equal(one, f[1, 2])
    # broadcasting one direction against many
    bc = brdffit.eval("cook-torrance", p, [0, 0, 1.0], wo)
    assert np.array_equal(bc[2, 3], brdffit.eval("cook-torrance", p, [0, 0, 1.0], wo[2, 3]))
    # lists, float32 and non-contiguous inputs are converted, not refused
    assert np.allclose(brdffit.eval("cook-torrance", p, wi.astype(np.float32), wo), f, rtol=1e-5)
    big = np.zeros((5, 6))
    big[:, ::2] = wi[0]
    assert np.array_equal(brdffit.eval("cook-torrance", p, big[:, ::2], wo[0]), f[0])
    # out= is filled and returned: the same memory
    out = np.empty((4, 5, 3))
    assert brdffit.eval("cook-torrance", p, wi, wo, out=out) is out
    assert np.array_equal(out, f)
    with pytest.raises(brdffit.InvalidArgumentError, match="out"):
        brdffit.eval("cook-torrance", p, wi, wo, out=np.empty((4, 5, 3), dtype=np.float32))
    # zero pairs
    assert brdffit.eval("ward", p[:7], np.empty((0, 3)), np.empty((0, 3))).shape == (0, 3)
    # a fit result and a Params work as params
    params = brdffit.Params.from_vector(p)
    assert np.array_equal(brdffit.eval("cook-torrance", params, wi, wo), f)


def test_bad_input_raises(brdffit):
    p = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.3, 0.2]
    wi = np.array([[0, 0, 1.0], [0.6, 0, 0.8], [np.nan, 0, 1], [0, 0, 0]])
    wo = np.array([[0, 0, 1.0]] * 4)
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        brdffit.eval("cook-torrance", p, wi, wo)
    assert e.value.status == brdffit.Status.INVALID_ARGUMENT
    assert str(e.value) == e.value.message == (
        "brdffit_eval_batch: pair 2 of 4 (2 bad pairs, rgb 0 there): wi = (nan, 0, 1) is not a "
        "finite, non-zero direction")
    with pytest.raises(brdffit.ParamRangeError) as e:
        brdffit.eval("cook-torrance", [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.3, -5.0], wi[:2], wo[:2])
    assert e.value.status == brdffit.Status.PARAM_RANGE and "m" in str(e.value)
    with pytest.raises(brdffit.ParamRangeError):
        brdffit.eval("ward", [np.nan, 0, 0, 0, 0, 0, 0.1], wi[:2], wo[:2])
    with pytest.raises(brdffit.InvalidArgumentError, match="2 lobe parameters"):
        brdffit.eval("cook-torrance", p[:7], wi[:2], wo[:2])
    with pytest.raises(brdffit.InvalidArgumentError, match="shape"):
        brdffit.eval("ward", p[:7], np.zeros((3, 2)), wo[:3])
    with pytest.raises(brdffit.InvalidArgumentError, match="broadcast"):
        brdffit.eval("ward", p[:7], np.zeros((3, 3)), np.zeros((2, 3)))
    with pytest.raises(brdffit.InvalidArgumentError, match="wi"):
        brdffit.eval("ward", p[:7], "up", wo)
    with pytest.raises(brdffit.UnknownModelError):
        brdffit.eval("phong", p[:7], wi[:2], wo[:2])
