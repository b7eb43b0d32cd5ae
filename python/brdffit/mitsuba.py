# SPDX-License-Identifier: MIT
"""Mitsuba 3 BSDFs that evaluate brdffit's models and MERL tables through the
library (docs/mitsuba.md).

    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")          # or scalar_rgb
    import brdffit.mitsuba
    brdffit.mitsuba.register()
    img = mi.render(mi.load_file("alum-bronze-ggx.xml"))

register() adds two BSDF plugins to the variant in use:

- ``brdffit``: a model at given parameters.  ``<string name="model">`` (a
  registry name), the colours ``<rgb name="d">`` and ``<rgb name="s">``
  (for the glTF models also by their names ``base_color``,
  ``specular_color``), each lobe parameter as ``<float>`` under its registry
  name (``alpha``, ``F0``, ``Cxy``, ``sigma0``...; missing: the registry's
  typical value) and, for He, ``<rgb name="lambda_um">``.
- ``brdffit_measured``: a MERL table, ``<string name="filename">``, looked up
  trilinearly at the standard scale as ``brdffit render`` does.

Frames: Mitsuba's ``si.wi`` points toward the viewer (brdffit's wo) and the
``wo`` argument of eval/pdf toward the light (brdffit's wi); both are in the
local frame, z the normal, as brdffit's.  eval returns f(wi, wo) cos(theta)
of Mitsuba's wo (the cosine factor Mitsuba's integrators expect).  Both BSDFs
are reflection only and one-sided: a direction at or below the horizon gives 0.

Sampling: a mixture of cosine-weighted hemisphere sampling (weight 1 - w)
and Trowbridge-Reitz (GGX) half-vector sampling of D(h) cos(theta_h) about
the normal (weight w), alpha taken from the model's parameters (lobe_alpha);
pdf is exactly that mixture's density, sample's weight f cos / pdf.

Every call converts Mitsuba's arrays to NumPy once and calls the library's
batch evaluator once: in the LLVM variants register() turns off Dr.Jit's
symbolic loops and calls, so a BSDF method receives a whole wavefront of
evaluated lanes.  The package imports without Mitsuba; this module imports
it only in register().
"""

import math
import time

import numpy as np

from .evaluate import eval as _eval
from .models import Params, model as _model
from .table import Table

# The mixture's GGX weight bounds: cosine sampling always keeps 1 - W_MAX.
W_MIN, W_MAX = 0.2, 0.8
ALPHA_MIN, ALPHA_MAX = 1e-3, 1.0


def _exponent_alpha(n):
    """The GGX width of a cos^n(theta_h) lobe of about the same spread."""
    return math.sqrt(2.0 / (max(n, 0.0) + 2.0))


# How each model's lobe parameters give the sampler's GGX alpha (by registry name).
LOBE_ALPHA = {
    "ward": lambda p: p["alpha"],
    "ward-duer": lambda p: p["alpha"],
    "blinn-phong": lambda p: _exponent_alpha(p["n"]),
    "lafortune": lambda p: _exponent_alpha(p["n"]),
    "cook-torrance": lambda p: p["m"],
    "ashikhmin-shirley": lambda p: _exponent_alpha(p["n"]),
    "he": lambda p: 2.0 * p["sigma0"] / p["tau"],
    "ggx": lambda p: p["alpha"],
    "gltf": lambda p: p["roughness"] ** 2,
    "gltf-ext": lambda p: p["roughness"] ** 2,
}


def lobe_alpha(model_name, values):
    """The sampler's GGX alpha for a model's lobe parameters ({name: value}),
    in [ALPHA_MIN, ALPHA_MAX]."""
    a = LOBE_ALPHA[model_name](values)
    return min(max(float(a), ALPHA_MIN), ALPHA_MAX)


def lobe_weight(model_name, d, s, values):
    """The share of samples the GGX lobe takes: the specular colour's share
    of the colours (for the glTF models, metallic and the dielectric's
    Fresnel), in [W_MIN, W_MAX]."""
    if model_name in ("gltf", "gltf-ext"):
        m = values["metallic"]
        ls = m * float(np.mean(d)) + (1 - m) * 0.04 * values.get("specular", 1.0)
        ld = (1 - m) * float(np.mean(d))
    else:
        ls, ld = float(np.mean(s)), float(np.mean(d))
    w = ls / (ls + ld) if ls + ld > 0 else 0.5
    return min(max(w, W_MIN), W_MAX)


# ---------------------------------------------------------------- the sampler (NumPy)

def ggx_d(cos_h, alpha):
    """Trowbridge-Reitz D(h) for cos(theta_h) (0 at or below the horizon)."""
    c2 = cos_h * cos_h
    a2 = alpha * alpha
    t = c2 * (a2 - 1.0) + 1.0
    return np.where(cos_h > 0, a2 / (np.pi * t * t), 0.0)


def mixture_pdf(wi, wo, alpha, w):
    """The sampler's density of wo (toward the light) given wi (toward the
    viewer), per solid angle; 0 unless both are above the horizon.  wi, wo:
    (3, n) unit vectors in the local frame."""
    up = (wi[2] > 0) & (wo[2] > 0)
    h = wi + wo
    hl = np.sqrt(np.sum(h * h, axis=0))
    hl = np.where(hl > 0, hl, 1.0)
    cos_h = h[2] / hl
    wo_h = np.abs(np.sum(wo * h, axis=0)) / hl
    spec = ggx_d(cos_h, alpha) * cos_h / (4.0 * np.maximum(wo_h, 1e-12))
    diff = np.maximum(wo[2], 0.0) / np.pi
    return np.where(up, (1.0 - w) * diff + w * spec, 0.0)


def mixture_sample(wi, u0, u1, u2, alpha, w):
    """Directions wo (3, n) drawn from the mixture: u0 picks the lobe, (u1, u2)
    the direction.  A GGX draw may fall below the horizon (the caller gives
    it weight 0)."""
    # cosine-weighted hemisphere
    r = np.sqrt(u1)
    phi = 2.0 * np.pi * u2
    cosd = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(np.maximum(1.0 - u1, 0.0))])
    # GGX half vector from D(h) cos(theta_h): tan^2(theta_h) = alpha^2 u1 / (1 - u1)
    t2 = alpha * alpha * u1 / np.maximum(1.0 - u1, 1e-300)
    ch = 1.0 / np.sqrt(1.0 + t2)
    sh = np.sqrt(np.maximum(1.0 - ch * ch, 0.0))
    h = np.stack([sh * np.cos(phi), sh * np.sin(phi), ch])
    refl = 2.0 * np.sum(wi * h, axis=0) * h - wi
    return np.where(u0 < w, refl, cosd)


# ---------------------------------------------------------------- the evaluators

class ModelLobe:
    """A brdffit model at fixed parameters: f(wi, wo) in brdffit's frame."""

    def __init__(self, model_name, d, s, p, lambda_um=None):
        self.model = _model(model_name)
        self.params = Params(d, s, p, lambda_um)
        values = dict(zip(self.model.param_names, (float(v) for v in p)))
        self.alpha = lobe_alpha(self.model.name, values)
        self.weight = lobe_weight(self.model.name, self.params.d, self.params.s, values)
        _eval(self.model, self.params, (0, 0, 1), (0, 0, 1))  # refuses parameters out of bounds

    def f(self, wi, wo):
        """(n, 3) RGB of f at brdffit's (wi, wo), each (n, 3), both above the horizon."""
        return _eval(self.model, self.params, wi, wo)

    def describe(self):
        p = ", ".join(f"{n}={v:g}" for n, v in zip(self.model.param_names, self.params.p))
        return (f"{self.model.name}: d={list(self.params.d)}, s={list(self.params.s)}, {p}")


class TableLobe:
    """A MERL table looked up trilinearly at the standard scale (masked bins: 0)."""

    def __init__(self, path, alpha=0.1, weight=0.5):
        self.path = path
        self.table = Table.read(path)
        self.alpha = min(max(float(alpha), ALPHA_MIN), ALPHA_MAX)
        self.weight = min(max(float(weight), 0.0), 1.0)

    def f(self, wi, wo):
        return np.maximum(self.table.lookup(wi, wo, scale="standard", interp="trilinear"), 0.0)

    def describe(self):
        return f"MERL table {self.path}"


def _model_from_props(props):
    keys = set(props.keys())
    if "model" not in keys:
        raise ValueError("brdffit BSDF: <string name=\"model\"> is required (e.g. ggx)")
    m = _model(props["model"])
    lower = {k.lower(): k for k in keys}

    def get(name, default):
        key = name if name in keys else lower.get(name.lower())
        return props[key] if key is not None else default

    def colour(names, default):
        for n in names:
            v = get(n, None)
            if v is not None:
                return [float(v[k]) for k in range(3)] if not isinstance(v, float) else [v] * 3
        return default

    d = colour(("d", m.colour_names[0]), [0.5, 0.5, 0.5])
    s = colour(("s", m.colour_names[1]), [1.0, 1.0, 1.0])
    p = [float(get(q.name, q.start)) for q in m.params]
    lam = colour(("lambda_um",), None)
    return ModelLobe(m.name, d, s, p, lam)


# ---------------------------------------------------------------- Mitsuba

_registered = set()

# What the BSDFs' methods have done since the last reset_stats(): calls,
# lanes (directions) and seconds inside them (conversions included).
stats = {"calls": 0, "lanes": 0, "seconds": 0.0}

# Dr.Jit's LLVM kernels of Mitsuba 3.x use llvm.maximum, which LLVM 14 and 15
# cannot compile for x86 ("Cannot select: fmaximum"): the process aborts.
LLVM_MIN = (16, 0, 0)


def reset_stats():
    stats.update(calls=0, lanes=0, seconds=0.0)


def _timed(method):
    def run(self, *args):
        t = time.perf_counter()
        out, n = method(self, *args)
        stats["calls"] += 1
        stats["lanes"] += n
        stats["seconds"] += time.perf_counter() - t
        return out
    run.__name__ = method.__name__
    return run


def _check_llvm(dr):
    version = tuple(dr.detail.llvm_version()) if hasattr(dr.detail, "llvm_version") else None
    if version is not None and version < LLVM_MIN:
        raise RuntimeError(
            f"Dr.Jit loaded LLVM {'.'.join(map(str, version))}: Mitsuba's LLVM variants need "
            f"LLVM {LLVM_MIN[0]} or newer (Debian 12: apt-get install libllvm19; or set "
            "DRJIT_LIBLLVM_PATH), or use scalar_rgb")


def register():
    """Register ``brdffit`` and ``brdffit_measured`` with the Mitsuba variant
    in use (mi.set_variant first); in the LLVM and CUDA variants, turn off
    Dr.Jit's symbolic loops and calls so the BSDFs see evaluated arrays.
    Calling it again for the same variant does nothing."""
    import drjit as dr
    import mitsuba as mi

    variant = mi.variant()
    if variant is None:
        raise RuntimeError("brdffit.mitsuba.register(): call mitsuba.set_variant() first")
    if variant.startswith("llvm"):
        _check_llvm(dr)
    if not variant.startswith("scalar"):
        dr.set_flag(dr.JitFlag.SymbolicLoops, False)
        dr.set_flag(dr.JitFlag.SymbolicCalls, False)
    if not variant.endswith("_rgb"):
        raise RuntimeError(f"brdffit's BSDFs are RGB: variant {variant} (use scalar_rgb or llvm_ad_rgb)")
    if variant in _registered:
        return
    classes = _classes(mi, dr)
    mi.register_bsdf("brdffit", lambda props: classes[0](props))
    mi.register_bsdf("brdffit_measured", lambda props: classes[1](props))
    _registered.add(variant)


def _classes(mi, dr):
    """The two BSDF classes, made against the variant in use."""
    scalar = mi.variant().startswith("scalar")
    flags = (mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.DiffuseReflection
             | mi.BSDFFlags.FrontSide)

    def to_np3(v):
        """A Dr.Jit 3-vector as a float64 (3, n) array."""
        return np.array(v, dtype=np.float64).reshape(3, -1)

    def to_np1(v):
        """A Dr.Jit float (or a Python number) as a float64 (n,) array."""
        return np.array(v, dtype=np.float64).reshape(-1)

    def mask(active, n):
        if isinstance(active, bool):
            return np.full(n, active)
        return np.broadcast_to(np.array(active, dtype=bool).reshape(-1), (n,))

    def color(rgb):
        """(3, n) float64 as a Color3f."""
        if scalar:
            return mi.Color3f(float(rgb[0, 0]), float(rgb[1, 0]), float(rgb[2, 0]))
        return mi.Color3f(rgb.astype(np.float32))

    def floats(a):
        return mi.Float(float(a[0])) if scalar else mi.Float(a.astype(np.float32))

    def vec(a):
        if scalar:
            return mi.Vector3f(float(a[0, 0]), float(a[1, 0]), float(a[2, 0]))
        return mi.Vector3f(a.astype(np.float32))

    def unit(a):
        n = np.sqrt(np.sum(a * a, axis=0))
        return a / np.where(n > 0, n, 1.0)

    class _Base(mi.BSDF):
        def __init__(self, props, lobe):
            mi.BSDF.__init__(self, props)
            self.lobe = lobe
            self.m_flags = flags
            self.m_components = [mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide,
                                 mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide]

        def _value(self, wi, wo, ok):
            """f cos(theta of wo) (3, n) where ok (both above the horizon), else 0."""
            out = np.zeros(wi.shape)
            if np.any(ok):
                f = self.lobe.f(wo[:, ok].T, wi[:, ok].T)  # brdffit: wi to the light
                out[:, ok] = f.T * wo[2, ok]
            return out

        def _inputs(self, si, wo, active):
            wi = unit(to_np3(si.wi))
            wo = unit(to_np3(wo))
            n = max(wi.shape[1], wo.shape[1])
            wi = np.broadcast_to(wi, (3, n))
            wo = np.broadcast_to(wo, (3, n))
            ok = mask(active, n) & (wi[2] > 0) & (wo[2] > 0)
            return wi, wo, ok

        @_timed
        def _eval(self, ctx, si, wo, active):
            wi, wo, ok = self._inputs(si, wo, active)
            return color(self._value(wi, wo, ok)), ok.size

        @_timed
        def _pdf(self, ctx, si, wo, active):
            wi, wo, ok = self._inputs(si, wo, active)
            pdf = np.where(ok, mixture_pdf(wi, wo, self.lobe.alpha, self.lobe.weight), 0)
            return floats(pdf), ok.size

        @_timed
        def _eval_pdf(self, ctx, si, wo, active):
            wi, wo, ok = self._inputs(si, wo, active)
            pdf = np.where(ok, mixture_pdf(wi, wo, self.lobe.alpha, self.lobe.weight), 0)
            return (color(self._value(wi, wo, ok)), floats(pdf)), ok.size

        def eval(self, ctx, si, wo, active=True):
            return self._eval(ctx, si, wo, active)

        def pdf(self, ctx, si, wo, active=True):
            return self._pdf(ctx, si, wo, active)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self._eval_pdf(ctx, si, wo, active)

        def sample(self, ctx, si, sample1, sample2, active=True):
            return self._sample(ctx, si, sample1, sample2, active)

        @_timed
        def _sample(self, ctx, si, sample1, sample2, active):
            wi = unit(to_np3(si.wi))
            u0 = to_np1(sample1)
            u = np.array(sample2, dtype=np.float64).reshape(2, -1)
            n = max(wi.shape[1], u0.size, u.shape[1])
            wi = np.broadcast_to(wi, (3, n))
            u0, u = np.broadcast_to(u0, (n,)), np.broadcast_to(u, (2, n))
            wo = unit(mixture_sample(wi, u0, u[0], u[1], self.lobe.alpha, self.lobe.weight))
            ok = mask(active, n) & (wi[2] > 0) & (wo[2] > 0)
            pdf = np.where(ok, mixture_pdf(wi, wo, self.lobe.alpha, self.lobe.weight), 0.0)
            ok &= pdf > 0
            value = self._value(wi, wo, ok)
            weight = np.where(ok, value / np.where(ok, pdf, 1.0), 0.0)
            bs = dr.zeros(mi.BSDFSample3f) if scalar else dr.zeros(mi.BSDFSample3f, n)
            bs.wo = vec(wo)
            bs.pdf = floats(pdf)
            bs.eta = 1.0
            glossy = u0 < self.lobe.weight
            if scalar:
                bs.sampled_type = mi.UInt32(int(mi.BSDFFlags.GlossyReflection if glossy[0]
                                                 else mi.BSDFFlags.DiffuseReflection))
                bs.sampled_component = mi.UInt32(0 if glossy[0] else 1)
            else:
                bs.sampled_type = mi.UInt32(np.where(glossy, int(mi.BSDFFlags.GlossyReflection),
                                                     int(mi.BSDFFlags.DiffuseReflection))
                                            .astype(np.uint32))
                bs.sampled_component = mi.UInt32(np.where(glossy, 0, 1).astype(np.uint32))
            return (bs, color(weight)), n

        def traverse(self, callback):
            pass

        def to_string(self):
            return f"{type(self).__name__}[{self.lobe.describe()}]"

    class BrdffitBSDF(_Base):
        def __init__(self, props):
            _Base.__init__(self, props, _model_from_props(props))

    class BrdffitMeasuredBSDF(_Base):
        def __init__(self, props):
            keys = set(props.keys())
            if "filename" not in keys:
                raise ValueError("brdffit_measured BSDF: <string name=\"filename\"> (a MERL "
                                 "table) is required")
            alpha = props["alpha"] if "alpha" in keys else 0.1
            weight = props["lobe_weight"] if "lobe_weight" in keys else 0.5
            _Base.__init__(self, props, TableLobe(props["filename"], alpha, weight))

    return BrdffitBSDF, BrdffitMeasuredBSDF
