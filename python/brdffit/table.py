# SPDX-License-Identifier: MIT
"""MERL tables: read, write, make from NumPy or from a model, look up."""

import ctypes

import numpy as np

from . import _abi, _arrays, _lib
from .errors import InvalidArgumentError, Status
from .models import resolve

_BAD = Status.INVALID_ARGUMENT
_CHANNELS = "RGB"


def scale_id(scale):
    """brdffit_scale of "standard" / "flat" (or the int itself)."""
    if isinstance(scale, str):
        if scale in _abi.SCALES:
            return _abi.SCALES[scale]
    elif isinstance(scale, int) and scale in _abi.SCALES.values():
        return scale
    raise InvalidArgumentError(_BAD, f"unknown scale {scale!r} (scales: standard, flat)")


def scale_name(scale):
    return {v: k for k, v in _abi.SCALES.items()}[scale_id(scale)]


def interp_id(interp):
    if isinstance(interp, str) and interp in _abi.INTERPS:
        return _abi.INTERPS[interp]
    if isinstance(interp, int) and interp in _abi.INTERPS.values():
        return interp
    raise InvalidArgumentError(
        _BAD, f"unknown interpolation {interp!r} (interp: nearest, trilinear)"
    )


def scale_factors(scale="standard"):
    """The three channel factors of a scale: stored value x factor = BRDF (1/sr)."""
    f = np.empty(3, dtype=np.float64)
    _lib.call("brdffit_scale_factors", scale_id(scale), f.ctypes.data)
    return f


class Table:
    """A MERL isotropic table: 3 x 90 x 90 x 180 stored values (R, G, B planes;
    theta_h bin, theta_d bin, phi_d bin), in stored units (x the channel scale
    = BRDF).  Negative values mean "not measured" and are masked.

    Make one with Table.read(path), Table.from_array(values),
    Table.from_model(model, params) or Table.zeros().  ``values`` is a
    writable NumPy view of the library's own buffer (no copy); the table's
    memory lives as long as the Table or any such view."""

    __slots__ = ("_h", "__weakref__")

    def __init__(self, _handle):
        self._h = _handle

    @classmethod
    def _wrap(cls, ptr):
        return cls(_arrays.Handle(ptr, _lib.cdll().brdffit_table_free))

    @classmethod
    def read(cls, path):
        """Read and validate a MERL .binary file.  Raises a FileError subclass
        (FileOpenError, FileTruncatedError, FileDimsError, ...) naming the file
        and the fault; InvalidArgumentError for a NUL byte in path."""
        ptr = ctypes.c_void_p()
        _lib.call("brdffit_table_read", _arrays.c_path("path", path), ctypes.byref(ptr))
        return cls._wrap(ptr.value)

    @classmethod
    def zeros(cls):
        """A table with every stored value 0."""
        ptr = ctypes.c_void_p()
        _lib.call("brdffit_table_create", ctypes.byref(ptr))
        return cls._wrap(ptr.value)

    @classmethod
    def from_array(cls, values):
        """A table holding values (shape (3, 90, 90, 180), or (3, 1458000),
        any real dtype: not bool, complex, text or objects), copied once into
        the library's buffer.  NaN or inf is refused (InvalidArgumentError
        naming the channel and bin), as reading a file refuses them."""
        arr = np.asarray(values)
        if arr.dtype.kind not in "fiu":
            _arrays.real_array("values", arr)  # raises, naming what it holds
        if arr.shape not in (_abi.MERL_SHAPE, (3, _abi.MERL_BINS)):
            raise InvalidArgumentError(
                _BAD, f"values: shape {arr.shape}, expected {_abi.MERL_SHAPE}"
            )
        arr = arr.reshape(_abi.MERL_SHAPE)
        if arr.dtype.kind == "f":
            finite = np.isfinite(arr)
            if not finite.all():
                c, i, j, k = (int(x) for x in np.argwhere(~finite)[0])
                raise InvalidArgumentError(
                    _BAD,
                    f"values: {arr[c, i, j, k]} at channel {_CHANNELS[c]}, bin {i},{j},{k} "
                    f"(index {int(np.ravel_multi_index((c, i, j, k), _abi.MERL_SHAPE))})",
                )
        t = cls.zeros()
        np.copyto(t.values, arr, casting="unsafe")
        return t

    @classmethod
    def from_model(cls, model, params, scale="standard"):
        """A table filled from a model: every bin whose directions are both
        above the horizon gets f / scale, the others -1 (as MERL stores them)."""
        m, _, cp = resolve(model, params)
        t = cls.zeros()
        _lib.call("brdffit_table_fill_model", t._h.ptr, m.id, ctypes.byref(cp), scale_id(scale))
        return t

    @property
    def values(self):
        """The stored values, shape (3, 90, 90, 180), float64, a writable view
        of the library's buffer."""
        ptr = _lib.cdll().brdffit_table_values(self._h.ptr)
        addr = ctypes.cast(ptr, ctypes.c_void_p).value
        buf = (ctypes.c_double * (3 * _abi.MERL_BINS)).from_address(addr)
        buf.owner = self._h  # the view keeps the table's memory alive
        return np.frombuffer(buf, dtype=np.float64).reshape(_abi.MERL_SHAPE)

    def write(self, path):
        """Write the table in MERL .binary format (FileWriteError on failure;
        InvalidArgumentError for a NUL byte in path)."""
        _lib.call("brdffit_table_write", self._h.ptr, _arrays.c_path("path", path))

    def lookup(self, wi, wo, scale="standard", interp="nearest", out=None):
        """The table's BRDF value (stored x scale, 1/sr) at direction pairs
        wi, wo of shape (..., 3), per channel: shape (..., 3).  MERL's BRDFRead
        mapping; interp "nearest" (its bin) or "trilinear".  A masked bin
        gives -1 in that channel (trilinear: where any contributing bin is
        masked).  One C call for all pairs; a non-finite or zero direction
        (or wo = -wi) raises InvalidArgumentError with the library's message."""
        a, b, shape = _arrays.pairs(wi, wo)
        rgb = _arrays.output(out, shape)
        s, ip = scale_id(scale), interp_id(interp)
        _lib.call("brdffit_table_lookup_batch", self._h.ptr, a.size // 3, a.ctypes.data,
                  b.ctypes.data, s, ip, rgb.ctypes.data)
        return rgb

    def __reduce_ex__(self, protocol):
        raise _arrays.not_picklable(
            self, "write() and read() it, or pickle its values and use Table.from_array")

    def __repr__(self):
        return "<brdffit.Table 3x90x90x180>"
