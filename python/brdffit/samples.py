# SPDX-License-Identifier: MIT
"""Sample sets: the valid bins of a table, as a fit uses them."""

import ctypes
from typing import NamedTuple, Tuple

from . import _abi, _arrays, _lib
from .errors import InvalidArgumentError, Status
from .table import Table, scale_id, scale_name


class Sample(NamedTuple):
    """One sample: unit directions, measured BRDF value (stored x scale), the
    bin's solid-angle weight and the bin (i, j, k)."""

    wi: Tuple[float, float, float]
    wo: Tuple[float, float, float]
    rgb: Tuple[float, float, float]
    weight: float
    bin: Tuple[int, int, int]


class Samples:
    """The valid samples of a table: all channels >= 0, both directions above
    the horizon and within ``cutoff`` degrees (None: the library's default,
    80), values times the channel ``scale`` ("standard" or "flat").  The
    samples are copied out of the table: the table may go."""

    __slots__ = ("_h", "__weakref__")

    def __init__(self, table, cutoff=None, scale="standard"):
        if not isinstance(table, Table):
            raise InvalidArgumentError(
                Status.INVALID_ARGUMENT, f"table: a brdffit.Table, not {type(table).__name__}"
            )
        lib = _lib.cdll()
        opt = _abi.SampleOptions()
        lib.brdffit_sample_options_init(ctypes.byref(opt), ctypes.sizeof(opt))
        if cutoff is not None:
            opt.cutoff_deg = _arrays.real_number("cutoff", cutoff)
        opt.scale = scale_id(scale)
        ptr = ctypes.c_void_p()
        _lib.call("brdffit_samples_create", table._h.ptr, ctypes.byref(opt), ctypes.byref(ptr))
        self._h = _arrays.Handle(ptr.value, lib.brdffit_samples_free)

    def __len__(self):
        return self.count

    @property
    def count(self):
        """Number of valid samples."""
        return _lib.cdll().brdffit_samples_count(self._h.ptr)

    @property
    def masked(self):
        """Bins with a negative stored value in some channel."""
        return _lib.cdll().brdffit_samples_masked(self._h.ptr)

    @property
    def beyond_cutoff(self):
        """Bins with valid values whose directions fall outside the cutoff."""
        return _lib.cdll().brdffit_samples_beyond_cutoff(self._h.ptr)

    def _options(self):
        opt = _abi.SampleOptions()
        _lib.cdll().brdffit_sample_options_init(ctypes.byref(opt), ctypes.sizeof(opt))
        _lib.call("brdffit_samples_options", self._h.ptr, ctypes.byref(opt))
        return opt

    @property
    def cutoff(self):
        """The cutoff in degrees."""
        return self._options().cutoff_deg

    @property
    def scale(self):
        """The channel scale's name."""
        return scale_name(self._options().scale)

    def prepare(self, *models):
        """Make now what fits of these models (names, ids or Models; none:
        every model) derive from the set and share: the mirror set their
        passes on all samples read, their screening subsets and He's bin
        tables, kept with the set, so that no fit's ``seconds``
        include making them (without this the first fit that needs one makes
        it).  Returns self."""
        from .models import model as _model, models as _models

        for m in (models or _models()):
            _lib.call("brdffit_samples_prepare", self._h.ptr, _model(m).id)
        return self

    def __getitem__(self, index):
        n = self.count
        if not isinstance(index, int):
            raise TypeError("Samples index must be an int")
        if index < 0:
            index += n
        if not 0 <= index < n:
            raise IndexError(f"sample {index} out of range (count {n})")
        s = _abi.Sample()
        _lib.call("brdffit_samples_get", self._h.ptr, index, ctypes.byref(s))
        return Sample(tuple(s.wi), tuple(s.wo), tuple(s.rgb), s.weight, (s.i, s.j, s.k))

    def __reduce_ex__(self, protocol):
        raise _arrays.not_picklable(self, "make it again from its Table where it is needed")

    def __repr__(self):
        return (
            f"<brdffit.Samples {self.count} samples, cutoff {self.cutoff:g} deg, "
            f"scale {self.scale}>"
        )
