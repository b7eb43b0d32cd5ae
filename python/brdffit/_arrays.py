# SPDX-License-Identifier: MIT
"""NumPy arrays in and out of the C calls: (..., 3) direction pairs, no copy
when the caller's arrays are already float64 and C-contiguous; C ints; real
numbers (not bool, complex, text, objects or times); paths and strings for
C (no NUL byte, where C would end them)."""

import operator
import os

import numpy as np

from .errors import InvalidArgumentError, Status


_INT_MIN, _INT_MAX = -(2 ** 31), 2 ** 31 - 1


# What an array of each non-real dtype kind holds, for messages.
_NOT_REAL = {
    "b": "booleans",
    "c": "complex numbers",
    "U": "text",
    "S": "bytes",
    "O": "Python objects",
    "M": "dates (datetime64)",
    "m": "time spans (timedelta64)",
    "V": "records",
}


def real_array(name, value, dtype=np.float64):
    """value as an array of dtype; InvalidArgumentError naming the argument
    unless it holds real numbers (ints or floats): NumPy would otherwise
    parse text, drop imaginary parts and take True for 1."""
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError):
        raise InvalidArgumentError(Status.INVALID_ARGUMENT, f"{name}: not an array of numbers") from None
    if arr.dtype.kind not in "fiu":
        what = _NOT_REAL.get(arr.dtype.kind, str(arr.dtype))
        raise InvalidArgumentError(
            Status.INVALID_ARGUMENT, f"{name}: {what} ({arr.dtype}), expected real numbers"
        )
    return arr.astype(dtype, copy=False)


def real_number(name, value):
    """value as a Python float, refused (InvalidArgumentError) unless a real
    number: not a bool, a string, a complex number or an array."""
    arr = real_array(name, value)
    if arr.ndim != 0:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT, f"{name}: {value!r} is not a number")
    return float(arr)


def c_path(name, path):
    """path (str, bytes or os.PathLike) as bytes for C; InvalidArgumentError
    for a NUL byte in it (C would read the path only up to it, another
    file)."""
    try:
        raw = os.fsencode(path)
    except TypeError:
        raise InvalidArgumentError(
            Status.INVALID_ARGUMENT, f"{name}: a path (str, bytes or os.PathLike), not "
            f"{type(path).__name__}"
        ) from None
    if b"\0" in raw:
        raise InvalidArgumentError(
            Status.INVALID_ARGUMENT, f"{name}: {path!r} contains a NUL byte (no path can)"
        )
    return raw


def c_text(name, text):
    """A str as UTF-8 for C; InvalidArgumentError for a NUL in it (C would
    read only up to it)."""
    if not isinstance(text, str):
        raise InvalidArgumentError(
            Status.INVALID_ARGUMENT, f"{name}: a str, not {type(text).__name__}"
        )
    if "\0" in text:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT, f"{name}: {text!r} contains a NUL")
    return text.encode("utf-8")


def not_picklable(obj, advice):
    """The TypeError of pickling or copying an object that owns library memory."""
    return TypeError(
        f"a brdffit.{type(obj).__name__} cannot be pickled or copied: it owns memory of the "
        f"C library, valid only in this process; {advice}"
    )


def c_int(name, value):
    """value as a Python int that a C int holds (InvalidArgumentError otherwise:
    ctypes would silently wrap it; a bool is not taken for 0 or 1)."""
    if isinstance(value, (bool, np.bool_)):
        raise InvalidArgumentError(Status.INVALID_ARGUMENT, f"{name}: {value!r} is not an integer")
    try:
        v = operator.index(value)
    except TypeError:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT,
                                   f"{name}: {value!r} is not an integer") from None
    if not _INT_MIN <= v <= _INT_MAX:
        raise InvalidArgumentError(Status.INVALID_ARGUMENT, f"{name}: {v} is out of range")
    return v


class Handle:
    """An owned C object, freed with its free function when the last Python
    reference (the wrapper, or a NumPy view of its memory) goes."""

    __slots__ = ("ptr", "free", "__weakref__")

    def __init__(self, ptr, free):
        self.ptr = ptr
        self.free = free

    def close(self):
        ptr, self.ptr = self.ptr, None
        if ptr:
            self.free(ptr)

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown: nothing left to report to
            pass

    def __reduce_ex__(self, protocol):
        raise not_picklable(self, "make the object again where it is needed")


def _as_directions(name, a):
    arr = real_array(name, a)
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise InvalidArgumentError(
            Status.INVALID_ARGUMENT,
            f"{name}: shape {arr.shape}, expected (..., 3) (x, y, z per direction)",
        )
    return arr


def pairs(wi, wo):
    """wi, wo as C-contiguous float64 arrays of one shape (..., 3), broadcast
    against each other; and that shape."""
    a = _as_directions("wi", wi)
    b = _as_directions("wo", wo)
    if a.shape != b.shape:
        try:
            a, b = np.broadcast_arrays(a, b)
        except ValueError:
            raise InvalidArgumentError(
                Status.INVALID_ARGUMENT, f"wi {a.shape} and wo {b.shape} do not broadcast"
            ) from None
    return np.ascontiguousarray(a), np.ascontiguousarray(b), a.shape


def output(out, shape):
    """A float64 C-contiguous array of shape for results: out itself, or new."""
    if out is None:
        return np.empty(shape, dtype=np.float64)
    if (
        not isinstance(out, np.ndarray)
        or out.dtype != np.float64
        or out.shape != tuple(shape)
        or not out.flags.c_contiguous
        or not out.flags.writeable
    ):
        raise InvalidArgumentError(
            Status.INVALID_ARGUMENT,
            f"out: must be a writable C-contiguous float64 array of shape {tuple(shape)}",
        )
    return out
