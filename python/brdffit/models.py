# SPDX-License-Identifier: MIT
"""The models of the library's registry, and parameter sets."""

import ctypes
from dataclasses import dataclass
from typing import Tuple

import numpy as np

from . import _abi, _arrays, _lib
from .errors import InvalidArgumentError, Status, UnknownModelError

_BAD = Status.INVALID_ARGUMENT


@dataclass(frozen=True)
class Param:
    """One lobe parameter of a model: name, unit ("" when dimensionless),
    inclusive bounds and a typical starting value, in the paper's units; how a
    fit maps it (``map``: "log", "linear" or "direction") and a few words on
    what it is."""

    name: str
    unit: str
    lower: float
    upper: float
    start: float
    map: str
    description: str


@dataclass(frozen=True)
class Model:
    """A model of the registry: ``id`` (brdffit_model), ``name``
    ("cook-torrance"), ``title`` ("Cook-Torrance"), its lobe ``params`` and
    whether its lobe differs per channel (``chromatic``), the number of
    starting points a fit screens by default (``default_starts``), how the
    two colours of a Params enter (``colour_form``: "ds", f = d/pi + s K,
    "gltf", the glTF material, or "openpbr", OpenPBR Surface's base and
    specular layers) and their names (``colour_names``: ("d", "s"), or
    ("base_color", "specular_color") for the glTF and OpenPBR models)."""

    id: int
    name: str
    title: str
    params: Tuple[Param, ...]
    chromatic: bool
    default_starts: int
    colour_form: str = "ds"
    colour_names: Tuple[str, str] = ("d", "s")

    @property
    def nparams(self):
        return len(self.params)

    @property
    def param_names(self):
        return tuple(p.name for p in self.params)

    def __str__(self):
        return self.name

    def __repr__(self):
        return f"brdffit.model({self.name!r})"


def _text(raw):
    return raw.decode("utf-8", "replace") if raw else ""


_cache = {}  # Library -> tuple of Model


def models():
    """Every model of the library's registry, in id order."""
    lib = _lib.library()
    found = _cache.get(id(lib))
    if found is not None and found[0] is lib:
        return found[1]
    out = []
    for m in range(lib.cdll.brdffit_model_count()):
        mi = lib.cdll.brdffit_model_get(m).contents
        params = tuple(
            Param(
                name=_text(pi.name),
                unit=_text(pi.unit),
                lower=pi.lower,
                upper=pi.upper,
                start=pi.start,
                map=_abi.PARAM_MAPS.get(pi.map, str(pi.map)),
                description=_text(pi.description),
            )
            for pi in (mi.params[k] for k in range(mi.nparams))
        )
        out.append(Model(mi.id, _text(mi.name), _text(mi.title), params, bool(mi.chromatic),
                         mi.default_starts,
                         colour_form=_abi.COLOUR_FORMS.get(mi.colour_form, str(mi.colour_form)),
                         colour_names=(_text(mi.colour_names[0]), _text(mi.colour_names[1]))))
    result = tuple(out)
    _cache[id(lib)] = (lib, result)
    return result


def model(which):
    """The Model for a name ("cook-torrance", "cook_torrance"), an id, or a
    Model.  Raises UnknownModelError."""
    if isinstance(which, Model):
        return which
    all_models = models()
    if isinstance(which, (int, np.integer)) and not isinstance(which, bool):
        if 0 <= int(which) < len(all_models):
            return all_models[int(which)]
        raise UnknownModelError(Status.UNKNOWN_MODEL, f"no model with id {int(which)}")
    if isinstance(which, str):
        out = _abi.c_enum()
        _lib.call("brdffit_model_from_name", _arrays.c_text("model", which), ctypes.byref(out))
        if not 0 <= out.value < len(all_models):
            raise UnknownModelError(Status.UNKNOWN_MODEL,
                                    f"model '{which}' has id {out.value}, beyond the "
                                    f"{len(all_models)} models the registry lists")
        return all_models[out.value]
    raise InvalidArgumentError(_BAD, f"a model is a name, an id or a Model, not {type(which).__name__}")


def _vector3(name, value, default=None):
    if value is None:
        value = default
    arr = _arrays.real_array(name, value).reshape(-1)
    if arr.size == 1:
        arr = np.repeat(arr, 3)
    if arr.size != 3:
        raise InvalidArgumentError(_BAD, f"{name}: {arr.size} numbers, expected 3 (R, G, B)")
    return arr


class Params:
    """A parameter set: Lambertian albedo ``d`` (R, G, B), specular
    coefficient ``s`` (R, G, B), lobe parameters ``p`` in the paper's units,
    and for He the wavelengths ``lambda_um`` (0 = the defaults).  For the glTF
    models ``d`` is the base colour, ``s`` the specular colour and ``p``
    metallic, roughness, ior, specular; for OpenPBR ``d`` is base_color, ``s``
    specular_color and ``p`` base_metalness, specular_roughness,
    specular_ior, specular_weight (Model.colour_names, param_names).

    Params(d, s, p) or Params.from_vector([d_r, d_g, d_b, s_r, s_g, s_b, p0, ...]).
    A single number for d or s means the same for the three channels."""

    __slots__ = ("d", "s", "p", "lambda_um")

    def __init__(self, d, s, p=(), lambda_um=None):
        self.d = _vector3("d", d)
        self.s = _vector3("s", s)
        self.p = np.array(_arrays.real_array("p", p), dtype=np.float64).reshape(-1)
        if self.p.size > _abi.MAX_LOBE_PARAMS:
            raise InvalidArgumentError(
                _BAD, f"p: {self.p.size} lobe parameters, at most {_abi.MAX_LOBE_PARAMS}"
            )
        self.lambda_um = _vector3("lambda_um", lambda_um, default=(0.0, 0.0, 0.0))

    @classmethod
    def from_vector(cls, values):
        """From d_r d_g d_b s_r s_g s_b p0 [p1 [p2 [p3]]] (the program's order)."""
        v = np.array(_arrays.real_array("params", values), dtype=np.float64).reshape(-1)
        if not 6 <= v.size <= 6 + _abi.MAX_LOBE_PARAMS:
            raise InvalidArgumentError(
                _BAD, f"params: {v.size} numbers, expected d_r d_g d_b s_r s_g s_b p0 [p1 [p2 [p3]]]"
            )
        return cls(v[0:3], v[3:6], v[6:])

    def vector(self):
        """d_r d_g d_b s_r s_g s_b p... as one array."""
        return np.concatenate([self.d, self.s, self.p])

    def to_c(self):
        cp = _abi.Params()
        for k in range(3):
            cp.d[k] = self.d[k]
            cp.s[k] = self.s[k]
            cp.lambda_um[k] = self.lambda_um[k]
        for k in range(self.p.size):
            cp.p[k] = self.p[k]
        return cp

    @classmethod
    def from_c(cls, cp, nparams):
        return cls(list(cp.d), list(cp.s), list(cp.p)[:nparams], list(cp.lambda_um))

    def __eq__(self, other):
        if not isinstance(other, Params):
            return NotImplemented
        return all(
            a.shape == b.shape and bool(np.all(a == b))
            for a, b in (
                (self.d, other.d),
                (self.s, other.s),
                (self.p, other.p),
                (self.lambda_um, other.lambda_um),
            )
        )

    def __repr__(self):
        def f(a):
            return "[" + ", ".join(repr(float(x)) for x in a) + "]"

        lam = "" if not np.any(self.lambda_um) else f", lambda_um={f(self.lambda_um)}"
        return f"Params(d={f(self.d)}, s={f(self.s)}, p={f(self.p)}{lam})"


def resolve(model_arg, params_arg) -> Tuple[Model, "Params", _abi.Params]:
    """(Model, Params, C params) from what a caller passed: a Params, an
    object with .params (a fit result), or a sequence d..., s..., p..."""
    m = model(model_arg)
    p = params_arg
    if hasattr(p, "params") and isinstance(getattr(p, "params"), Params):
        p = p.params
    if not isinstance(p, Params):
        p = Params.from_vector(p)
    if p.p.size != m.nparams:
        names = ", ".join(m.param_names)
        raise InvalidArgumentError(
            _BAD, f"{m.name} has {m.nparams} lobe parameters ({names}), got {p.p.size}"
        )
    return m, p, p.to_c()


def metric_name():
    """The Error metric's name ("ngan-l2")."""
    return _text(_lib.cdll().brdffit_metric_name())

