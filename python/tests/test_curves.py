# SPDX-License-Identifier: MIT
"""incidence_curves: the angles of the header's formula, a model's curves
equal to brdffit.eval and a table's to Table.lookup at the same directions
(computed here from the documented formula), and the library's messages for
bad arguments."""

import numpy as np
import pytest

CT = [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.15]


def directions(theta_i, theta_o):
    ti, to = np.radians(theta_i), np.radians(theta_o)
    wi = np.stack([-np.sin(ti), np.zeros_like(ti), np.cos(ti)], axis=-1)
    wo = np.stack([np.sin(to), np.zeros_like(to), np.cos(to)], axis=-1)
    return wi, wo


def test_angles_and_shapes(brdffit):
    theta_o, rgb = brdffit.incidence_curves("cook-torrance", CT)
    assert rgb.shape == (4, 180, 3) and rgb.dtype == np.float64
    assert np.allclose(theta_o, -90 + 180 * (np.arange(180) + 0.5) / 180, rtol=0, atol=1e-12)
    theta_o, one = brdffit.incidence_curves("cook-torrance", CT, theta_i=40, points=7)
    assert one.shape == (7, 3) and theta_o.shape == (7,)
    assert theta_o[0] == pytest.approx(-90 + 180 * 0.5 / 7, abs=1e-12)
    _, rgb = brdffit.incidence_curves("cook-torrance", CT, theta_i=[0, 89.9], points=2)
    assert rgb.shape == (2, 2, 3)


@pytest.mark.parametrize("model, params", [
    ("cook-torrance", CT),
    ("lafortune", [0.1, 0.1, 0.1, 0.6, 0.5, 0.4, -0.6, 0.5, 20.0]),
    ("he", [0.05, 0.06, 0.07, 0.8, 0.7, 0.6, 3.0, 0.5, 2.0]),
])
def test_model_curves_equal_eval(brdffit, model, params):
    theta_i = (0, 20, 45.5, 75, 89)
    theta_o, rgb = brdffit.incidence_curves(model, params, theta_i=theta_i, points=91)
    for a, t in enumerate(theta_i):
        wi, wo = directions(np.full(91, t), theta_o)
        want = brdffit.eval(model, params, wi, wo)
        # NumPy's sin/cos and the C library's may round differently; near
        # grazing (theta_i 89) the lobes' 1/cos and exponents amplify it to ~2e-12
        assert np.allclose(rgb[a], want, rtol=1e-10, atol=0), (model, t)
    # the mirror side (theta_o = theta_i) holds the peak of a specular lobe
    _, ct = brdffit.incidence_curves("cook-torrance", CT, theta_i=30, points=180)
    assert abs(theta_o_of_peak(ct) - 30) <= 1.5


def theta_o_of_peak(rgb):
    n = len(rgb)
    return -90 + 180 * (int(np.argmax(rgb.mean(axis=1))) + 0.5) / n


def test_a_fit_result_is_a_source(brdffit, ctx):
    s = brdffit.Samples(brdffit.Table.from_model("cook-torrance", CT))
    r = brdffit.fit(ctx, s, "cook-torrance", starts=2)
    _, a = brdffit.incidence_curves(r)
    _, b = brdffit.incidence_curves("cook-torrance", r.params)
    assert np.array_equal(a, b)


@pytest.mark.parametrize("interp, scale", [("trilinear", "standard"), ("nearest", "flat")])
def test_table_curves_equal_lookup(brdffit, alum_bronze, interp, scale):
    t = brdffit.Table.read(alum_bronze)
    theta_o, rgb = brdffit.incidence_curves(t, interp=interp, scale=scale)
    grid = np.broadcast_to(np.array([20.0, 40, 60, 75])[:, None], rgb.shape[:2])
    wi, wo = directions(grid, np.broadcast_to(theta_o, rgb.shape[:2]))
    want = t.lookup(wi, wo, interp=interp, scale=scale)
    same = np.isclose(rgb, want, rtol=1e-12, atol=0)
    if interp == "nearest":  # a direction a rounding step off a bin edge may take the neighbour
        assert same.mean() > 0.999
    else:
        assert same.all()
        assert (rgb == -1).any()   # trilinear reaches bins below the horizon near grazing
    assert (rgb[rgb != -1] > 0).all()


@pytest.mark.parametrize("kwargs, message", [
    ({"theta_i": 95}, r"curves: theta_i = 95 deg \(must be in \[0, 90\)\)"),
    ({"theta_i": [20, -1]}, r"curves: theta_i = -1 deg"),
    ({"theta_i": float("nan")}, r"curves: theta_i = nan deg"),
    ({"theta_i": []}, r"curves: ntheta_i = 0 \(1\.\.16\)"),
    ({"theta_i": list(range(17))}, "theta_i: 17 angles, at most 16"),
    ({"theta_i": "forty"}, r"theta_i: text \(<U5\), expected real numbers"),
    ({"points": 1}, r"curves: npoints = 1 \(2\.\.100000\)"),
    ({"points": 10 ** 6}, r"curves: npoints = 1000000 \(2\.\.100000\)"),
    ({"points": 2 ** 40}, "points: 1099511627776 is out of range"),
    ({"interp": "cubic"}, "unknown interpolation"),
])
def test_bad_arguments(brdffit, kwargs, message):
    for source in ((brdffit.Table.zeros(), None), ("cook-torrance", CT)):
        with pytest.raises(brdffit.InvalidArgumentError, match=message) as e:
            brdffit.incidence_curves(*source, **kwargs)
        assert e.value.status == brdffit.Status.INVALID_ARGUMENT


def test_bad_parameters(brdffit):
    with pytest.raises(brdffit.ParamRangeError) as e:
        brdffit.incidence_curves("ward", [0.1] * 6 + [-0.2])
    assert e.value.status == brdffit.Status.PARAM_RANGE and "ward" in str(e.value).lower()
