# SPDX-License-Identifier: MIT
"""Contexts (device and kernels), fits and Errors."""

import ctypes
import enum
import operator
from dataclasses import dataclass

import numpy as np

from . import _abi, _arrays, _lib
from .errors import InvalidArgumentError, Status
from .models import Model, Params, model as _model, resolve
from .samples import Samples

_BAD = Status.INVALID_ARGUMENT

METRICS = ("ngan-l2", "log", "cube-root")
"""The Error metrics, by their brdffit_metric number (docs/metrics.md)."""


def _metric_id(metric):
    """A metric's number from its name (any case, '_' for '-')."""
    name = str(metric).lower().replace("_", "-") if isinstance(metric, str) else None
    if name not in METRICS:
        raise InvalidArgumentError(
            _BAD, f"unknown metric {metric!r} (metrics: {', '.join(METRICS)})"
        )
    return METRICS.index(name)
_BACKEND_NAMES = {v: k for k, v in _abi.BACKENDS.items()}

AtBound = enum.IntFlag("AtBound", _abi.AT_BOUND_BITS, module=__name__)
AtBound.__doc__ = """brdffit_at_bound: the bits of FitResult.at_bound, named as in C
(BRDFFIT_AT_BOUND_P0 is AtBound.P0): lobe parameter k on a bound is
P0 << k (LOBE: any), d_c = 0 is D_R << c, s_c = 0 is S_R << c."""
FitFlag = enum.IntFlag("FitFlag", _abi.FIT_FLAG_BITS, module=__name__)
FitFlag.__doc__ = """brdffit_fit_flag: the bits of FitResult.flags, named as in C
(BRDFFIT_FIT_LIMIT is FitFlag.LIMIT: stopped on max_evals, not converged)."""


class Context:
    """The OpenCL device (or the host C path) and its per-model kernels.

    backend: "auto" (OpenCL when a device is found, else host C), "opencl"
    (or NoDeviceError) or "host"; device: "PLATFORM:DEVICE" by index or name
    substring (None: $BRDFFIT_DEVICE, else the first PoCL CPU device).  Use
    one context per thread.  close() (or a with block) frees it at once."""

    __slots__ = ("_h", "__weakref__")

    def __init__(self, backend="auto", device=None):
        if backend not in _abi.BACKENDS:
            raise InvalidArgumentError(
                _BAD, f"unknown backend {backend!r} (backends: auto, opencl, host)"
            )
        lib = _lib.cdll()
        opt = _abi.ContextOptions()
        lib.brdffit_context_options_init(ctypes.byref(opt), ctypes.sizeof(opt))
        opt.backend = _abi.BACKENDS[backend]
        if device is not None:
            opt.device = _arrays.c_text("device", str(device))
        ptr = ctypes.c_void_p()
        _lib.call("brdffit_context_create", ctypes.byref(opt), ctypes.byref(ptr))
        self._h = _arrays.Handle(ptr.value, lib.brdffit_context_free)

    def _ptr(self):
        if not self._h.ptr:
            raise InvalidArgumentError(_BAD, "the context is closed")
        return self._h.ptr

    @property
    def backend(self):
        """"opencl" or "host": the path fits take."""
        return _BACKEND_NAMES.get(_lib.cdll().brdffit_context_backend(self._ptr()), "unknown")

    @property
    def description(self):
        """"opencl: Portable Computing Language / ..." or "host: C (...)"."""
        raw = _lib.cdll().brdffit_context_describe(self._ptr())
        return raw.decode("utf-8", "replace") if raw else ""

    def close(self):
        self._h.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __reduce_ex__(self, protocol):
        raise _arrays.not_picklable(self, "make a Context in each process")

    def __repr__(self):
        if not self._h.ptr:
            return "<brdffit.Context closed>"
        return f"<brdffit.Context {self.description}>"


@dataclass(frozen=True)
class FitResult:
    """What brdffit_fit returns.  ``params`` in the paper's units, ``error``
    the Error of params under ``metric``, the metric the fit minimised
    ("ngan-l2" unless asked), ``errors`` its Error under every metric (a dict
    by name; None under "log" and "cube-root" for an "ngan-l2" fit unless
    fit(..., all_errors=True)), ``metric_iterations`` the LM iterations after the "ngan-l2"
    fit (docs/metrics.md), ``status`` the call's Status (OK: a
    result), ``cminpack_info`` lmder's info of the run kept (1..4 converged),
    ``iterations`` its Jacobian evaluations, ``passes`` all data passes
    of the fit, ``seconds`` its wall time (``seconds_solver`` inside
    cminpack, ``seconds_passes`` in data passes, ``seconds_build`` building
    the model's kernels when the fit had to), ``samples`` fitted,
    ``backend`` "opencl" or "host", ``at_bound`` an AtBound of the
    brdffit_at_bound bits (an int: int(at_bound) is the raw mask; lobe
    parameter k on a bound: AtBound.P0 << k; d_c = 0: AtBound.D_R << c; s_c =
    0: AtBound.S_R << c; ``at_bound_names`` names them), ``flags`` a FitFlag
    of the brdffit_fit_flag bits (FitFlag.LIMIT: stopped on max_evals)."""

    model: Model
    params: Params
    error: float
    status: Status
    cminpack_info: int
    iterations: int
    passes: int
    seconds: float
    seconds_solver: float
    seconds_passes: float
    samples: int
    backend: str
    seconds_build: float = 0.0
    at_bound: AtBound = AtBound(0)
    flags: FitFlag = FitFlag(0)
    metric: str = "ngan-l2"
    errors: dict = None
    metric_iterations: int = 0

    @property
    def converged(self):
        """cminpack reported convergence (info 1..4) and the fit did not stop
        on its evaluation limit."""
        return 1 <= self.cminpack_info <= 4 and not self.flags & FitFlag.LIMIT

    @property
    def at_bound_names(self):
        """The parameters on a bound, as the program names them: lobe
        parameters by their registry names ("F0", "m"), then "d_r".."d_b"
        (d_c = 0) and "s_r".."s_b" (s_c = 0); a glTF model's colours by its
        colour_names ("base_color_r": 0 or 1)."""
        bits = int(self.at_bound)
        names = [p.name for k, p in enumerate(self.model.params) if bits & (AtBound.P0 << k)]
        cn = self.model.colour_names
        for first, letter in ((AtBound.D_R, cn[0]), (AtBound.S_R, cn[1])):
            names += [f"{letter}_{c}" for k, c in enumerate("rgb") if bits & (first << k)]
        return names


_OPTION_FIELDS = tuple(f[0] for f in _abi.FitOptions._fields_ if f[0] != "size")


def fit_options(**options):
    """A brdffit_fit_options: the library's defaults, then options by name
    (the struct's members: starts, refine, ftol, ...; metric by its name)."""
    opt = _abi.FitOptions()
    _lib.cdll().brdffit_fit_options_init(ctypes.byref(opt), ctypes.sizeof(opt))
    options = dict(options)
    if "metric" in options:
        opt.metric = _metric_id(options.pop("metric"))
    if "all_errors" in options:  # a yes or no: True/False (or 0/1)
        v = options.pop("all_errors")
        if not isinstance(v, (bool, np.bool_, int)) or v not in (0, 1):
            raise InvalidArgumentError(_BAD, f"fit option all_errors: bad value {v!r} (True or False)")
        opt.all_errors = int(v)
    for name, value in options.items():
        if name not in _OPTION_FIELDS:
            raise TypeError(
                f"fit() got an unknown option {name!r} (options: {', '.join(_OPTION_FIELDS)})"
            )
        ctype = dict(_abi.FitOptions._fields_)[name]
        try:
            if issubclass(ctype, ctypes.Array):
                vals = _arrays.real_array(f"fit option {name}", value).reshape(-1)
                if len(vals) != ctype._length_:
                    raise ValueError
                setattr(opt, name, ctype(*vals))
            elif ctype in (ctypes.c_int, ctypes.c_size_t, _abi.c_enum):
                if isinstance(value, (bool, np.bool_)):
                    raise TypeError
                setattr(opt, name, operator.index(value))
            else:
                setattr(opt, name, _arrays.real_number(f"fit option {name}", value))
        except (TypeError, ValueError):
            raise InvalidArgumentError(_BAD, f"fit option {name}: bad value {value!r}") from None
    return opt


def _check_args(ctx, samples):
    if not isinstance(ctx, Context):
        raise InvalidArgumentError(_BAD, f"ctx: a brdffit.Context, not {type(ctx).__name__}")
    if not isinstance(samples, Samples):
        raise InvalidArgumentError(
            _BAD, f"samples: a brdffit.Samples, not {type(samples).__name__}"
        )


def fit(ctx, samples, model, **options):
    """Fit a model to a sample set; returns a FitResult.  options are
    brdffit_fit_options members (starts=, refine=, ftol=, xtol=, gtol=,
    max_evals=, lambda_um=, metric="ngan-l2" | "log" | "cube-root"); unset
    ones keep the library's defaults."""
    _check_args(ctx, samples)
    m = _model(model)
    opt = fit_options(**options)
    r = _abi.FitResult()
    _lib.call(
        "brdffit_fit", ctx._ptr(), samples._h.ptr, m.id, ctypes.byref(opt), ctypes.byref(r)
    )
    return FitResult(
        model=m,
        params=Params.from_c(r.params, m.nparams),
        error=r.error,
        status=Status.OK,
        cminpack_info=r.cminpack_info,
        iterations=r.iterations,
        passes=r.passes,
        seconds=r.seconds,
        seconds_solver=r.seconds_solver,
        seconds_passes=r.seconds_passes,
        samples=r.samples,
        backend=_BACKEND_NAMES.get(r.backend, "unknown"),
        seconds_build=r.seconds_build,
        at_bound=AtBound(r.at_bound),
        flags=FitFlag(r.flags),
        metric=METRICS[r.metric],
        errors={name: None if np.isnan(r.errors[k]) else r.errors[k]
                for k, name in enumerate(METRICS)},
        metric_iterations=r.metric_iterations,
    )


def error_of(ctx, samples, model, params, metric="ngan-l2"):
    """The Error of given parameters on a sample set under a metric
    ("ngan-l2", the default, "log" or "cube-root"; params: a Params, a
    FitResult or d_r d_g d_b s_r s_g s_b p0 [p1 [p2 [p3]]])."""
    _check_args(ctx, samples)
    mid = _metric_id(metric)
    m, _, cp = resolve(model, params)
    out = ctypes.c_double()
    _lib.call(
        "brdffit_error_metric",
        ctx._ptr(),
        samples._h.ptr,
        m.id,
        ctypes.byref(cp),
        mid,
        ctypes.byref(out),
    )
    return out.value


