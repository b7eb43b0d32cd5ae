# SPDX-License-Identifier: MIT
"""The openpbr model against an independent implementation of OpenPBR
Surface 1.1's equations (base and specular layers), its albedo table against
a direct numerical integration, and the white furnace.

``reference`` is written from the specification's text and MaterialX's
choices as docs/openpbr.md lists them, not from the library's kernel: GGX D
and Smith's height-correlated G2 in Heitz's Lambda form, the dielectric
Fresnel from Snell's law at the modulated IOR of the specification's
equation (modulated_ior), F82-tint as the specification prints it, the
multiple-scattering compensation 1 + Fss (1 - Ess) / Ess, and the
non-reciprocal albedo scaling of the diffuse by 1 - E at the view direction.

The albedo E of the dielectric lobe (with the exact Fresnel) and Ess (with
F = 1) are the one part the reference takes from the library, recovered from
its values (``library_albedo``); the table they come from is tested on its
own against a numerical integration over the hemisphere
(``test_albedo_table``)."""

import numpy as np
import pytest

import brdffit

ROUGHNESS_MIN = 1e-3  # the library's floor, as the glTF models'
F0_MAX = 0.99999      # MaterialX's clamp of specular_weight F_s
MU_BAR = 1.0 / 7.0
# The albedo table's error bound (docs/openpbr.md): at cos theta_V >= 0.05
TABLE_ATOL = 1e-3
TABLE_MU_MIN = 0.05


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _dot(a, b):
    return np.sum(a * b, axis=-1)


def direction(theta_deg, phi_deg):
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])


def smith_lambda(mu, a2):
    """Heitz 2014: Lambda(mu) = (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2."""
    tan2 = (1 - mu * mu) / (mu * mu)
    return 0.5 * (-1 + np.sqrt(1 + a2 * tan2))


def ggx_dvis(alpha, L, V):
    """D G2 / (4 (N.L) (N.V)): D = 1 / (pi alpha^2 cos^4 (1 + tan^2 / alpha^2)^2),
    G2 = 1 / (1 + Lambda(L) + Lambda(V))."""
    H = _unit(L + V)
    c = H[..., 2]
    a2 = alpha * alpha
    D = 1 / (np.pi * a2 * c**4 * (1 + (1 - c * c) / (c * c) / a2) ** 2)
    G2 = 1 / (1 + smith_lambda(L[..., 2], a2) + smith_lambda(V[..., 2], a2))
    return D * G2 / (4 * L[..., 2] * V[..., 2])


def fresnel_dielectric(c, eta):
    """Unpolarised Fresnel reflectance from Snell's law (n1 = 1, n2 = eta)."""
    s2 = (1 - c * c) / (eta * eta)
    ct = np.sqrt(np.maximum(1 - s2, 0))
    rs = (c - eta * ct) / (c + eta * ct)
    rp = (eta * c - ct) / (eta * c + ct)
    return 0.5 * (rs * rs + rp * rp)


def modulated_f0(ior, weight):
    """F0 of the specification's modulated IOR: specular_weight F_s, capped."""
    fs = abs((1 - ior) / (1 + ior)) ** 2
    return min(weight * fs, F0_MAX)


def modulated_eta(ior, weight):
    """Equation (modulated_ior): eta' = (1 + eps) / (1 - eps), eps = sgn(eta - 1) sqrt(xi F_s)."""
    eps = np.sign(ior - 1) * np.sqrt(modulated_f0(ior, weight))
    return (1 + eps) / (1 - eps)


def f82_tint(f0, tint, mu):
    """F82-tint as printed: Schlick less mu (1 - mu)^6 / (mu_bar (1 - mu_bar)^6)
    (F_Schlick(mu_bar) - tint F_Schlick(mu_bar)); clamped to [0, 1]."""
    schlick = lambda m: f0 + (1 - f0) * (1 - m) ** 5
    corr = mu * (1 - mu) ** 6 / (MU_BAR * (1 - MU_BAR) ** 6)
    f = schlick(mu) - corr * (schlick(MU_BAR) - tint * schlick(MU_BAR))
    return np.clip(f, 0, 1)


def compensation(f0, ess):
    """Turquin's 1 + Fss (1 - Ess) / Ess with the Fresnel average F0 + (1 - F0) / 21."""
    return 1 + (f0 + (1 - f0) / 21) * (1 - ess) / ess


def reference(base, scol, metal, rough, ior, weight, wi, wo, E, ess):
    """f per channel for light wi and view wo, given the albedos E (the
    dielectric lobe's, exact Fresnel, F0') and Ess (F = 1) at N.V of each wo."""
    L, V = np.broadcast_arrays(_unit(wi), _unit(wo))
    base = np.asarray(base, dtype=np.float64)
    scol = np.asarray(scol, dtype=np.float64)
    alpha = max(rough, ROUGHNESS_MIN) ** 2
    dvis = ggx_dvis(alpha, L, V)[..., None]
    vh = _dot(V, _unit(L + V))[..., None]
    f0d = modulated_f0(ior, weight)
    ess = ess[..., None]
    comp_d = compensation(f0d, ess)
    ed = np.minimum(E[..., None] * comp_d, 1.0)
    diel = scol * dvis * fresnel_dielectric(vh, modulated_eta(ior, weight)) * comp_d \
        + (1 - ed) * base / np.pi
    met = weight * dvis * f82_tint(base, scol, vh) * compensation(base, ess)
    return (1 - metal) * diel + metal * met


def library(base, scol, metal, rough, ior, weight, wi, wo):
    return brdffit.eval("openpbr", brdffit.Params(base, scol, [metal, rough, ior, weight]), wi, wo)


def mirror(wo):
    return np.stack([-wo[..., 0], -wo[..., 1], wo[..., 2]], axis=-1)


def library_albedo(rough, wo, ior=1.5, weight=1.0):
    """The library's E (at F0' of ior and weight) and Ess at N.V of each wo: a
    white metal is D Vis / Ess (F82 with F0 = 1 is 1, its compensation 1 /
    Ess); the diffuse's weight is 1 - E comp_d."""
    wo = _unit(wo)
    one, zero = (1, 1, 1), (0, 0, 0)
    alpha = max(rough, ROUGHNESS_MIN) ** 2
    # light at 60 deg on the viewer's side: away from a sharp lobe's peak,
    # which would swamp the diffuse and where H's rounding (1e-16) moves
    # tan^2 theta_H / alpha^2 by 1e-4 at alpha = 1e-6
    phi = np.arctan2(wo[..., 1], wo[..., 0])
    wd = np.stack([np.sin(np.pi / 3) * np.cos(phi), np.sin(np.pi / 3) * np.sin(phi),
                   np.full_like(phi, 0.5)], axis=-1)
    ess = ggx_dvis(alpha, wd, wo) / library(one, one, 1.0, rough, 1.5, 1.0, wd, wo)[..., 0]
    d = library(one, one, 0.0, rough, ior, weight, wd, wo) - library(zero, one, 0.0, rough, ior, weight, wd, wo)
    E = (1 - np.pi * d[..., 0]) / compensation(modulated_f0(ior, weight), ess)
    return E, ess


def corner_pairs():
    """Normal incidence, grazing (88 deg) light, view or both, the mirror
    direction, random pairs."""
    wi = [direction(0, 0), direction(88, 0), direction(30, 180), direction(88, 10),
          direction(60, 45), direction(45, 180)]
    wo = [direction(0, 0), direction(30, 180), direction(88, 0), direction(88, 200),
          direction(60, 45), direction(45, 0)]
    rng = np.random.default_rng(7)
    cos_t = rng.uniform(0.05, 1.0, size=(2, 24))
    phi = rng.uniform(0, 2 * np.pi, size=(2, 24))
    sin_t = np.sqrt(1 - cos_t**2)
    d = np.stack([sin_t * np.cos(phi), sin_t * np.sin(phi), cos_t], axis=-1)
    return np.concatenate([np.array(wi), d[0]]), np.concatenate([np.array(wo), d[1]])


BASE_COLOURS = [(0.8, 0.5, 0.1), (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)]
SPECULAR_COLOURS = [(1.0, 1.0, 1.0), (0.9, 0.6, 0.0), (0.0, 0.2, 0.5)]
METALNESS = [0.0, 0.4, 1.0]
ROUGHNESS = [0.0, 0.02, 0.3, 0.97, 1.0]
IOR_WEIGHT = [(1.0, 1.0), (1.5, 1.0), (3.0, 1.0), (1.5, 0.0), (2.2, 0.5), (10.0, 1.0)]


@pytest.mark.parametrize("rough", ROUGHNESS)
@pytest.mark.parametrize("metal", METALNESS)
@pytest.mark.parametrize("ior_weight", IOR_WEIGHT)
def test_openpbr_equals_the_specification(rough, metal, ior_weight):
    ior, weight = ior_weight
    wi, wo = corner_pairs()
    E, ess = library_albedo(rough, wo, ior, weight)
    # at alpha = 1e-6 the mirror pair's H, rounded to 1e-16, moves D by 1e-4
    # (in the library's form and the reference's alike, differently)
    rtol = 1e-9 if rough > 0.01 else 1e-3
    for base in BASE_COLOURS:
        for scol in SPECULAR_COLOURS:
            got = library(base, scol, metal, rough, ior, weight, wi, wo)
            want = reference(base, scol, metal, rough, ior, weight, wi, wo, E, ess)
            assert np.all(np.isfinite(got)) and np.all(got >= 0)
            np.testing.assert_allclose(got, want, rtol=rtol, atol=1e-12,
                                       err_msg=f"base {base} scol {scol} m {metal} r {rough} "
                                               f"ior {ior} w {weight}")


def test_f82_tint_is_clamped():
    """A dark specular_color over a black metal: the printed F82-tint is
    below 0 near cos 0.5, the model's metal lobe is 0 there, not negative."""
    assert f82_tint(0.0, 0.0, 0.5) == 0.0
    raw = (1 - 0.5) ** 5 - 0.5 * 0.5**6 / (MU_BAR * (1 - MU_BAR) ** 6) * (1 - MU_BAR) ** 5
    assert raw < 0
    wo = direction(60, 0)
    wi = mirror(wo)
    got = library((0, 0, 0), (0, 0, 0), 1.0, 0.3, 1.5, 1.0, wi, wo)
    assert np.all(got == 0.0)


def test_specular_weight_zero_leaves_the_diffuse_alone():
    """specular_weight 0: the dielectric has no lobe (eta' = 1, E = 0) and
    the metal none either; the diffuse is base_color / pi."""
    wi, wo = corner_pairs()
    got = library((0.5, 0.5, 0.5), (1, 1, 1), 0.0, 0.3, 1.5, 0.0, wi, wo)
    np.testing.assert_allclose(got, 0.5 / np.pi, rtol=1e-12)
    metal = library((0.5, 0.5, 0.5), (1, 1, 1), 1.0, 0.3, 1.5, 0.0, wi, wo)
    assert np.all(metal == 0.0)


def test_albedo_scaling_is_at_the_view_direction():
    """With a black base the lobe's compensation, and with base_color C the
    diffuse's weight, take N.V: f(wi, wo) - f(wo, wi) at C is that at 0 plus
    (E_d(N.wi) - E_d(N.wo)) C / pi."""
    wi, wo = direction(20, 0), direction(70, 180)
    c = (0.5, 0.5, 0.5)
    a = library(c, (1, 1, 1), 0.0, 0.5, 1.5, 1.0, wi, wo) - library((0, 0, 0), (1, 1, 1), 0.0, 0.5, 1.5, 1.0, wi, wo)
    b = library(c, (1, 1, 1), 0.0, 0.5, 1.5, 1.0, wo, wi) - library((0, 0, 0), (1, 1, 1), 0.0, 0.5, 1.5, 1.0, wo, wi)
    f0 = modulated_f0(1.5, 1.0)
    Ei, essi = library_albedo(0.5, wi[None])
    Eo, esso = library_albedo(0.5, wo[None])
    ei, eo = Ei * compensation(f0, essi), Eo * compensation(f0, esso)
    assert abs(ei[0] - eo[0]) > 1e-3
    np.testing.assert_allclose(a - b, np.full(3, (ei[0] - eo[0]) * 0.5 / np.pi), rtol=1e-9, atol=1e-15)


def e_integrated(mu, alpha, f0s, n=1500, nphi=600):
    """E at each F0 of f0s (the exact Fresnel at IOR (1 + sqrt F0) / (1 -
    sqrt F0); F0 = 1: F = 1) by a plain product quadrature over the half
    vectors: E = int D G2 F (V.H) / (N.V) dH over the H whose reflected L is
    above the horizon, theta_H through tan theta_H = alpha tan(pi x / 2) (D's
    mass evenly over x; Gauss-Legendre), the midpoint rule in the azimuth."""
    x, wx = np.polynomial.legendre.leggauss(n)
    x, wx = 0.5 * (x + 1), 0.5 * wx
    t = np.tan(np.pi * x / 2)
    th = np.arctan(alpha * t)
    dth = alpha * (np.pi / 2) / np.cos(np.pi * x / 2) ** 2 / (1 + (alpha * t) ** 2)
    phi = 2 * np.pi * (np.arange(nphi) + 0.5) / nphi
    TH, PH = np.meshgrid(th, phi, indexing="ij")
    W = (wx * dth)[:, None] * np.sin(TH) * (2 * np.pi / nphi)
    h = np.stack([np.sin(TH) * np.cos(PH), np.sin(TH) * np.sin(PH), np.cos(TH)], -1)
    V = np.array([np.sqrt(1 - mu * mu), 0, mu])
    vh = h @ V
    lz = 2 * vh * h[..., 2] - mu
    ok = (lz > 0) & (vh > 0)
    a2 = alpha * alpha
    c = np.cos(TH)
    D = a2 / (np.pi * (c * c * (a2 - 1) + 1) ** 2)
    G2 = 1 / (1 + smith_lambda(mu, a2) + smith_lambda(np.where(ok, lz, 1.0), a2))
    e = np.where(ok, D * G2 * vh / mu, 0) * W
    out = []
    for f0 in f0s:
        q = np.sqrt(f0)
        F = 1.0 if f0 >= 1 else fresnel_dielectric(np.clip(vh, 1e-12, 1), (1 + q) / (1 - q))
        out.append(np.sum(e * F))
    return out


def test_albedo_table():
    """The library's E and Ess against e_integrated, within TABLE_ATOL for
    cos theta_V >= TABLE_MU_MIN: at the table's nodes, between them, at the
    roughness floor and at 1, for IORs 1, 1.5, 3, 10 (specular_ior's upper
    bound) and F = 1 (measured
    worst: docs/openpbr.md)."""
    rng = np.random.default_rng(3)
    pts = [(mu, r) for mu in (TABLE_MU_MIN, 0.1, 0.37, 0.8, 1.0) for r in (0.0, 0.1, 0.33, 0.7, 1.0)]
    pts += list(zip(np.exp(rng.uniform(np.log(TABLE_MU_MIN), 0, 12)), rng.uniform(0, 1, 12)))
    iors = (1.0, 1.5, 3.0, 10.0)
    worst = 0.0
    for mu, r in pts:
        wo = np.array([[np.sqrt(1 - mu * mu), 0.0, mu]])
        f0s = [modulated_f0(ior, 1.0) for ior in iors] + [1.0]
        want = e_integrated(mu, max(r, ROUGHNESS_MIN) ** 2, f0s)
        for ior, w in zip(iors, want):
            got, ess = library_albedo(r, wo, ior)
            worst = max(worst, abs(got[0] - w))
            assert abs(got[0] - w) <= TABLE_ATOL, f"mu {mu} r {r} ior {ior}: table {got[0]} integral {w}"
        assert abs(ess[0] - want[-1]) <= TABLE_ATOL, f"mu {mu} r {r}: Ess {ess[0]} integral {want[-1]}"
    assert worst > 0  # the two are computed apart


def directional_albedo(base, scol, metal, rough, ior, weight, wo, n=400, nphi=200):
    """int f(wi, wo) cos theta_i dwi over the light directions, through the
    half vectors about wo's mirror direction (dwi = 4 (V.H) dH)."""
    alpha = max(rough, ROUGHNESS_MIN) ** 2
    x, wx = np.polynomial.legendre.leggauss(n)
    x, wx = 0.5 * (x + 1), 0.5 * wx
    t = np.tan(np.pi * x / 2)
    th = np.arctan(max(alpha, 0.05) * t)
    dth = max(alpha, 0.05) * (np.pi / 2) / np.cos(np.pi * x / 2) ** 2 / (1 + (max(alpha, 0.05) * t) ** 2)
    phi = 2 * np.pi * (np.arange(nphi) + 0.5) / nphi
    TH, PH = np.meshgrid(th, phi, indexing="ij")
    W = (wx * dth)[:, None] * np.sin(TH) * (2 * np.pi / nphi)
    h = np.stack([np.sin(TH) * np.cos(PH), np.sin(TH) * np.sin(PH), np.cos(TH)], -1).reshape(-1, 3)
    vh = h @ wo
    wi = 2 * vh[:, None] * h - wo
    ok = (wi[:, 2] > 1e-9) & (vh > 0)
    f = library(base, scol, metal, rough, ior, weight, np.where(ok[:, None], wi, [0, 0, 1.0]), np.broadcast_to(wo, wi.shape))
    return np.sum(np.where(ok[:, None], f * wi[:, 2:3] * 4 * vh[:, None], 0) * W.reshape(-1, 1), axis=0)


@pytest.mark.parametrize("metal", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("rough", [0.25, 0.5, 1.0])
def test_white_furnace(metal, rough):
    """A white base and specular colour reflect at most what arrives, over
    the view angles and the dielectric's IOR and weight (the quadrature's
    own error: below 1e-3 at these roughnesses)."""
    for ior, weight in ((1.0, 1.0), (1.5, 1.0), (3.0, 1.0), (1.5, 0.5), (10.0, 1.0)):
        for theta in (0, 45, 75):
            wo = direction(theta, 0)
            e = directional_albedo((1, 1, 1), (1, 1, 1), metal, rough, ior, weight, wo)
            assert np.all(np.isfinite(e))
            assert np.all(e <= 1 + 1e-3), f"m {metal} r {rough} ior {ior} w {weight} theta {theta}: {e}"
            assert np.all(e >= 0.45 * weight), f"m {metal} r {rough} ior {ior} w {weight} theta {theta}: {e}"


@pytest.mark.parametrize("corner", [(0.0, 0.0, 1.0, 0.0), (1.0, 1.0, 10.0, 1.0), (0.0, 1.0, 1.0, 1.0),
                                    (1.0, 0.0, 10.0, 0.0), (0.5, 0.0, 10.0, 1.0)])
def test_finite_at_the_bounds(corner):
    """Every parameter at a bound, colours 0 and 1, grazing and normal
    directions: finite and >= 0."""
    metal, rough, ior, weight = corner
    wi, wo = corner_pairs()
    wi = np.concatenate([wi, [direction(89.99, 0), direction(0, 0)]])
    wo = np.concatenate([wo, [direction(89.99, 180), direction(89.99, 0)]])
    for base in ((0, 0, 0), (1, 1, 1)):
        for scol in ((0, 0, 0), (1, 1, 1)):
            f = library(base, scol, metal, rough, ior, weight, wi, wo)
            assert np.all(np.isfinite(f)) and np.all(f >= 0), (corner, base, scol)
