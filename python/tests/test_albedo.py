# SPDX-License-Identifier: MIT
"""albedo: a model's directional albedo against closed forms and a brute-force
sum over brdffit.eval on a grid of wi written here, a table's against its
lookups, and the library's messages for bad arguments."""

import numpy as np
import pytest

CT = [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.35]


def grid(n):
    """Midpoints of n x n cells in (cos theta_i, phi_i) and each cell's solid angle."""
    mu = (np.arange(n) + 0.5) / n
    phi = 2 * np.pi * (np.arange(n) + 0.5) / n
    mu, phi = np.meshgrid(mu, phi, indexing="ij")
    st = np.sqrt(1 - mu ** 2)
    wi = np.stack([st * np.cos(phi), st * np.sin(phi), mu], axis=-1).reshape(-1, 3)
    return wi, 2 * np.pi / (n * n)


def view(theta_o, n):
    t = np.radians(theta_o)
    return np.tile([np.sin(t), 0.0, np.cos(t)], (n, 1))


def test_shapes_and_lambertian(brdffit):
    d = [0.7, 0.4, 0.1]
    a = brdffit.albedo("ward", d + [0, 0, 0, 0.1])
    assert a.shape == (18, 3) and a.dtype == np.float64
    assert np.allclose(a, np.tile(d, (18, 1)), rtol=0, atol=1e-12)
    one = brdffit.albedo("ward", d + [0, 0, 0, 0.1], theta_o=30)
    assert one.shape == (3,)
    assert brdffit.albedo.__module__ == "brdffit.albedo"


def test_closed_forms_at_the_normal(brdffit):
    # Lafortune's mirror lobe: (n+2)/(2 pi) cos^n theta_i at the normal integrates to 1
    for n in (1.0, 100.0, 1e6):
        a = brdffit.albedo("lafortune", [0, 0, 0, 1, 1, 1, -0.5, 0.5, n], theta_o=0)
        assert a == pytest.approx([1, 1, 1], abs=1e-4)
    # Blinn-Phong: 4 (n+2) [2 (1 - 2^-(n+4)/2) / (n+4) - (1 - 2^-(n+2)/2) / (n+2)]
    n = 50.0
    want = 4 * (n + 2) * (2 * (1 - 2 ** (-(n + 4) / 2)) / (n + 4)
                          - (1 - 2 ** (-(n + 2) / 2)) / (n + 2))
    a = brdffit.albedo("blinn-phong", [0, 0, 0, 1, 1, 1, n], theta_o=0)
    assert a[0] == pytest.approx(want, abs=1e-4)


@pytest.mark.parametrize("theta_o", [20.0, 60.0])
def test_model_against_brute_force(brdffit, theta_o):
    wi, dw = grid(1000)
    f = brdffit.eval("cook-torrance", CT, wi, view(theta_o, len(wi)))
    want = (f * wi[:, 2:3]).sum(axis=0) * dw
    got = brdffit.albedo("cook-torrance", CT, theta_o=theta_o)
    assert np.allclose(got, want, rtol=0, atol=2e-4), (got, want)


def test_table_against_its_lookups(brdffit):
    params = [0.2, 0.1, 0.05, 0.6, 0.6, 0.6, 0.8, 0.3]
    t = brdffit.Table.from_model("ggx", params)
    wi, dw = grid(600)
    f = t.lookup(wi, view(40, len(wi)), interp="trilinear")
    want = (np.maximum(f, 0) * wi[:, 2:3]).sum(axis=0) * dw
    got, share = brdffit.albedo(t, theta_o=[40.0], masked=True)
    assert got.shape == (1, 3) and share.shape == (1,)
    assert np.allclose(got[0], want, rtol=0, atol=5e-4), (got, want)
    assert 0 <= share[0] < 0.01
    model = brdffit.albedo("ggx", params, theta_o=40)
    assert np.allclose(got[0], model, rtol=0, atol=0.02)


def test_bad_arguments(brdffit):
    for bad in (90, -1, float("nan")):
        with pytest.raises(brdffit.InvalidArgumentError, match="theta_o_deg"):
            brdffit.albedo("cook-torrance", CT, theta_o=[0, bad])
    with pytest.raises(brdffit.ParamRangeError):
        brdffit.albedo("cook-torrance", CT[:-1] + [5.0])
    with pytest.raises(brdffit.InvalidArgumentError, match="masked"):
        brdffit.albedo("cook-torrance", CT, masked=True)
    with pytest.raises(brdffit.InvalidArgumentError, match="theta_o"):
        brdffit.albedo("cook-torrance", CT, theta_o="40")
