# SPDX-License-Identifier: MIT
"""The glTF models against an independent implementation of the specification.

``reference`` below is written from the specification's text, not from the
library's kernel: glTF 2.0 Appendix B ("BRDF Implementation": specular_brdf
as G D / (4 |N.L| |N.V|) with the Heaviside factors, Schlick's Fresnel,
conductor_fresnel, fresnel_mix, the metal/dielectric mix), with the
"Implementation" sections of KHR_materials_ior (f0 = ((ior - 1)/(ior + 1))^2)
and KHR_materials_specular (fresnel_mix with ``weight`` = specularFactor and
``f0_color`` = specularColorFactor, f0 clamped to 1, the diffuse weighted by
1 - weight max_value(fr)).

The one choice the specification leaves that the reference must share:
alpha = 0 "cannot be evaluated directly" and "should be clamped to a small
positive value"; the library floors roughness at 1e-3 (alpha = 1e-6,
BF_GLTF_ROUGHNESS_MIN of kernels/bf_gltf.h), and so does the reference."""

import numpy as np
import pytest

import brdffit

ROUGHNESS_MIN = 1e-3  # the library's floor (kernels/bf_gltf.h)
RTOL = 1e-12
# Values within 1e-60 1/sr of each other count as equal (zero to any
# renderer): at L = V, where (1 - |V.H|)^5 is 0, one rounding of V.H leaves
# it at 1e-80 instead, which a black base colour and f0 = 0 do not hide.
ATOL = 1e-60


def _dot(a, b):
    return np.sum(a * b, axis=-1)


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def heaviside(x):
    """chi+(x): 1 where x > 0, else 0."""
    return np.where(x > 0, 1.0, 0.0)


def specular_brdf(alpha, N, L, V):
    """Appendix B: G D / (4 |N.L| |N.V|), D Trowbridge-Reitz, G the
    height-correlated Smith masking-shadowing function."""
    H = _unit(L + V)
    nh, nl, nv = _dot(N, H), _dot(N, L), _dot(N, V)
    hl, hv = _dot(H, L), _dot(H, V)
    a2 = alpha * alpha
    D = a2 * heaviside(nh) / (np.pi * (nh * nh * (a2 - 1) + 1) ** 2)
    G = (2 * np.abs(nl) * np.abs(nv) * heaviside(hl) * heaviside(hv)) / (
        np.abs(nv) * np.sqrt(a2 + (1 - a2) * nl * nl) + np.abs(nl) * np.sqrt(a2 + (1 - a2) * nv * nv)
    )
    return G * D / (4 * np.abs(nl) * np.abs(nv))


def fresnel_w(L, V):
    """(1 - |V.H|)^5, with |V.H| of two unit vectors at most 1 (rounding can
    give 1 + 1e-16 at L = V)."""
    H = _unit(L + V)
    return (1 - np.minimum(np.abs(_dot(V, H)), 1.0)) ** 5


def conductor_fresnel(f0, bsdf, L, V):
    """Appendix B: bsdf * (f0 + (1 - f0) (1 - |V.H|)^5), per channel."""
    w = fresnel_w(L, V)[..., None]
    return bsdf[..., None] * (f0 + (1 - f0) * w)


def fresnel_mix(f0_color, ior, weight, base, layer, L, V):
    """KHR_materials_specular's fresnel_mix (Appendix B's with weight 1 and
    f0_color white): f0 = ((1 - ior)/(1 + ior))^2 f0_color clamped to 1,
    fr = f0 + (1 - f0) (1 - |V.H|)^5, (1 - weight max_value(fr)) base +
    weight fr layer."""
    f0 = ((1 - ior) / (1 + ior)) ** 2 * np.asarray(f0_color, dtype=np.float64)
    f0 = np.minimum(f0, 1.0)
    w = fresnel_w(L, V)[..., None]
    fr = f0 + (1 - f0) * w
    return (1 - weight * np.max(fr, axis=-1, keepdims=True)) * base + weight * fr * layer[..., None]


def reference(base_color, specular_color, metallic, roughness, ior, specular, wi, wo):
    """The material (per channel, (..., 3)) for light direction wi and view
    direction wo; 0 where either is below the horizon (a BRDF of a surface
    seen or lit from above)."""
    L, V = _unit(wi), _unit(wo)
    L, V = np.broadcast_arrays(L, V)
    N = np.array([0.0, 0.0, 1.0])
    alpha = max(roughness, ROUGHNESS_MIN) ** 2
    base_color = np.asarray(base_color, dtype=np.float64)
    spec = specular_brdf(alpha, N, L, V)
    diffuse = np.broadcast_to(base_color / np.pi, L.shape)
    metal = conductor_fresnel(base_color, spec, L, V)
    dielectric = fresnel_mix(specular_color, ior, specular, diffuse, spec, L, V)
    material = (1 - metallic) * dielectric + metallic * metal
    above = (L[..., 2] > 0) & (V[..., 2] > 0)
    return np.where(above[..., None], material, 0.0)


def core_reference(base_color, metallic, roughness, wi, wo):
    """Appendix B's "full code" (no extension): f0 = 0.04 written as such."""
    L, V = np.broadcast_arrays(_unit(wi), _unit(wo))
    N = np.array([0.0, 0.0, 1.0])
    alpha = max(roughness, ROUGHNESS_MIN) ** 2
    c = np.asarray(base_color, dtype=np.float64)
    fw = fresnel_w(L, V)[..., None]
    spec = specular_brdf(alpha, N, L, V)[..., None]
    diffuse = c / np.pi
    dielectric_fresnel = 0.04 + (1 - 0.04) * fw
    dielectric = diffuse * (1 - dielectric_fresnel) + spec * dielectric_fresnel
    metal = (c + (1 - c) * fw) * spec
    return dielectric * (1 - metallic) + metal * metallic


def direction(theta_deg, phi_deg):
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])


def random_pairs(n, seed):
    rng = np.random.default_rng(seed)
    cos_t = rng.uniform(0.02, 1.0, size=(2, n))
    phi = rng.uniform(0, 2 * np.pi, size=(2, n))
    sin_t = np.sqrt(1 - cos_t**2)
    d = np.stack([sin_t * np.cos(phi), sin_t * np.sin(phi), cos_t], axis=-1)
    return d[0], d[1]


def corner_pairs():
    """Normal incidence, grazing (89.9 deg) light, view or both, random pairs
    and wi = wo at random directions."""
    wi = [direction(0, 0), direction(89.9, 0), direction(30, 180), direction(89.9, 10),
          direction(89.9, 0), direction(60, 45)]
    wo = [direction(0, 0), direction(30, 180), direction(89.9, 0), direction(89.9, 200),
          direction(89.9, 0), direction(60, 45)]
    ri, ro = random_pairs(24, 7)
    same, _ = random_pairs(8, 11)
    return (np.concatenate([np.array(wi), ri, same]),
            np.concatenate([np.array(wo), ro, same]))


BASE_COLOURS = [(0.8, 0.5, 0.1), (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)]
# (ior, specular, specular colour): the extensions' defaults; ior 1 (f0 = 0)
# at half strength; ior 2.2 with a coloured specular colour; ior 3 with
# colours whose product with f0 = 0.25 exceeds 1 in two channels (clamped)
EXTENSIONS = [
    (1.5, 1.0, (1.0, 1.0, 1.0)),
    (1.0, 0.5, (1.0, 1.0, 1.0)),
    (2.2, 1.0, (0.5, 1.0, 2.0)),
    (3.0, 1.0, (0.2, 4.5, 6.0)),
    (3.0, 0.5, (1.0, 2.0, 3.5)),
    (1.5, 0.0, (1.0, 0.3, 1.0)),
]
METALLIC = [0.0, 0.3, 1.0]
ROUGHNESS = [0.0, 0.01, 0.5, 1.0]


def library(model, base, scol, metallic, roughness, ior, specular, wi, wo):
    params = brdffit.Params(base, scol, [metallic, roughness, ior, specular])
    return brdffit.eval(model, params, wi, wo)


@pytest.mark.parametrize("ext", EXTENSIONS)
@pytest.mark.parametrize("metallic", METALLIC)
@pytest.mark.parametrize("roughness", ROUGHNESS)
def test_gltf_ext_equals_the_specification(ext, metallic, roughness):
    ior, specular, scol = ext
    wi, wo = corner_pairs()
    for base in BASE_COLOURS:
        got = library("gltf-ext", base, scol, metallic, roughness, ior, specular, wi, wo)
        want = reference(base, scol, metallic, roughness, ior, specular, wi, wo)
        assert np.all(np.isfinite(got))
        np.testing.assert_allclose(got, want, rtol=RTOL, atol=ATOL,
                                   err_msg=f"base {base} ext {ext} m {metallic} r {roughness}")


def test_roughness_zero_is_floored():
    """Roughness 0 is evaluated as roughness 1e-3, bit for bit, and equals the
    reference (floored alike).  At normal incidence H = N: D = 1/(pi alpha^2)
    and Vis = 1/4, so a white metal (F = 1) gives 1/(4 pi alpha^2) at alpha =
    (1e-3)^2; the specification's form of D, (N.H)^2 (alpha^2 - 1) + 1, loses
    about 4 of the 16 digits to cancellation at alpha^2 = 1e-12."""
    n = direction(0, 0)
    alpha = ROUGHNESS_MIN**2
    floor = library("gltf-ext", (1, 1, 1), (1, 1, 1), 1.0, ROUGHNESS_MIN, 1.5, 1.0, n, n)
    zero = library("gltf-ext", (1, 1, 1), (1, 1, 1), 1.0, 0.0, 1.5, 1.0, n, n)
    np.testing.assert_array_equal(zero, floor)
    want = reference((1, 1, 1), (1, 1, 1), 1.0, 0.0, 1.5, 1.0, n, n)
    np.testing.assert_allclose(zero, want, rtol=RTOL, atol=0)
    np.testing.assert_allclose(zero, np.full(3, 1 / (4 * np.pi * alpha**2)), rtol=1e-3)
    # without the floor the value would be infinite (alpha = 0 at H = N)
    assert np.all(np.isfinite(zero))


@pytest.mark.parametrize("roughness", [0.01, 0.5, 1.0])
def test_mirror_pairs(roughness):
    """The specular peak (wo the mirror of wi), where D is largest."""
    wi = np.array([direction(t, 30) for t in (10, 45, 80, 89.9)])
    wo = wi * np.array([-1.0, -1.0, 1.0])
    for metallic in METALLIC:
        got = library("gltf-ext", (0.7, 0.2, 0.4), (1, 2, 1), metallic, roughness, 2.2, 0.8, wi, wo)
        want = reference((0.7, 0.2, 0.4), (1, 2, 1), metallic, roughness, 2.2, 0.8, wi, wo)
        np.testing.assert_allclose(got, want, rtol=RTOL, atol=ATOL)


def test_below_the_horizon_is_zero():
    above, below = direction(40, 0), direction(100, 180)
    for wi, wo in ((below, above), (above, below), (below, below)):
        for model in ("gltf", "gltf-ext"):
            got = library(model, (0.5, 0.5, 0.5), (1, 1, 1), 0.5, 0.5, 1.5, 1.0, wi, wo)
            assert np.all(got == 0.0)
            assert np.all(reference((0.5,) * 3, (1, 1, 1), 0.5, 0.5, 1.5, 1.0, wi, wo) == 0)


@pytest.mark.parametrize("metallic", METALLIC)
@pytest.mark.parametrize("roughness", ROUGHNESS)
def test_core_gltf_equals_appendix_b_and_gltf_ext_at_the_defaults(metallic, roughness):
    wi, wo = corner_pairs()
    for base in BASE_COLOURS:
        core = library("gltf", base, (1, 1, 1), metallic, roughness, 1.5, 1.0, wi, wo)
        ext = library("gltf-ext", base, (1, 1, 1), metallic, roughness, 1.5, 1.0, wi, wo)
        np.testing.assert_array_equal(core, ext)
        np.testing.assert_allclose(core, core_reference(base, metallic, roughness, wi, wo),
                                   rtol=RTOL, atol=ATOL)


@pytest.mark.parametrize("scol,p", [
    ((1, 1, 1), [0.5, 0.5, 1.4, 1.0]),
    ((1, 1, 1), [0.5, 0.5, 1.5, 0.9]),
    ((1, 0.5, 1), [0.5, 0.5, 1.5, 1.0]),
    ((1, 1, 1), [1.5, 0.5, 1.5, 1.0]),
    ((1, 1, 1), [0.5, -0.1, 1.5, 1.0]),
])
def test_core_gltf_refuses_what_only_the_extensions_have(scol, p):
    n = direction(0, 0)
    with pytest.raises(brdffit.ParamRangeError) as e:
        brdffit.eval("gltf", brdffit.Params((0.5, 0.5, 0.5), scol, p), n, n)
    assert e.value.status == brdffit.Status.PARAM_RANGE
    assert "gltf" in str(e.value)


@pytest.mark.parametrize("model", ["gltf", "gltf-ext"])
@pytest.mark.parametrize("base", [(1.2, 0.5, 0.5), (0.5, -0.01, 0.5), (0.5, 0.5, np.nan)])
def test_base_colour_outside_0_1_is_refused(model, base):
    n = direction(0, 0)
    with pytest.raises(brdffit.ParamRangeError, match="base_color"):
        brdffit.eval(model, brdffit.Params(base, (1, 1, 1), [0.5, 0.5, 1.5, 1.0]), n, n)


@pytest.mark.parametrize("p", [[0.5, 0.5, 0.99, 1.0], [0.5, 0.5, 1.5, 1.01], [0.5, 1.01, 1.5, 1.0]])
def test_gltf_ext_refuses_parameters_out_of_range(p):
    n = direction(0, 0)
    with pytest.raises(brdffit.ParamRangeError):
        brdffit.eval("gltf-ext", brdffit.Params((0.5,) * 3, (1, 1, 1), p), n, n)
    with pytest.raises(brdffit.ParamRangeError, match="specular_color"):
        brdffit.eval("gltf-ext", brdffit.Params((0.5,) * 3, (1, -1, 1), [0.5, 0.5, 1.5, 1]), n, n)


def directional_albedo(model, params, theta_i, n=400):
    """int f(wi, wo) cos(theta_o) dwo over the hemisphere (midpoint rule in
    cos theta_o and phi_o)."""
    mu = (np.arange(n) + 0.5) / n
    phi = (np.arange(2 * n) + 0.5) / (2 * n) * 2 * np.pi
    M, P = np.meshgrid(mu, phi, indexing="ij")
    s = np.sqrt(1 - M * M)
    wo = np.stack([s * np.cos(P), s * np.sin(P), M], axis=-1)
    f = brdffit.eval(model, params, direction(theta_i, 0), wo)
    return np.sum(f * M[..., None], axis=(0, 1)) * (1.0 / n) * (2 * np.pi / (2 * n))


@pytest.mark.parametrize("theta_i", [0.0, 60.0, 89.9])
def test_white_furnace_albedo_is_finite(theta_i):
    """A white base colour: the metal's single-scattering albedo stays at
    most 1 (F = 1 everywhere, the microfacet BRDF loses the light that
    scatters more than once), the dielectric's stays finite and near 1."""
    for roughness in (0.5, 1.0):
        metal = directional_albedo("gltf", brdffit.Params(1, 1, [1, roughness, 1.5, 1]), theta_i)
        assert np.all(np.isfinite(metal)) and np.all(metal > 0.3) and np.all(metal <= 1.0 + 1e-2)
        diel = directional_albedo("gltf", brdffit.Params(1, 1, [0, roughness, 1.5, 1]), theta_i)
        assert np.all(np.isfinite(diel)) and np.all(diel > 0.5) and np.all(diel < 1.5)
    sharp = directional_albedo("gltf-ext", brdffit.Params(1, (1, 5, 30), [0, 0, 3, 1]), theta_i)
    assert np.all(np.isfinite(sharp))


def test_models_describe_their_colours():
    for name in ("gltf", "gltf-ext"):
        m = brdffit.model(name)
        assert m.colour_names == ("base_color", "specular_color")
        assert m.param_names == ("metallic", "roughness", "ior", "specular")
    assert brdffit.model("ggx").colour_names == ("d", "s")
