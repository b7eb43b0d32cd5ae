# SPDX-License-Identifier: MIT
"""NumPy arrays in and out of the C calls: (..., 3) direction pairs, no copy
when the caller's arrays are already float64 and C-contiguous; C ints."""

import operator

import numpy as np

from .errors import InvalidArgumentError, Status


_INT_MIN, _INT_MAX = -(2 ** 31), 2 ** 31 - 1


def c_int(name, value):
    """value as a Python int that a C int holds (InvalidArgumentError otherwise:
    ctypes would silently wrap it)."""
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


def _as_directions(name, a):
    try:
        arr = np.asarray(a, dtype=np.float64)
    except (TypeError, ValueError):
        raise InvalidArgumentError(
            Status.INVALID_ARGUMENT, f"{name}: not an array of numbers"
        ) from None
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
