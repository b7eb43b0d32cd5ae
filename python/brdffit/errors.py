# SPDX-License-Identifier: MIT
"""Exceptions: every failing library call raises one, with the status and the
library's message ("path: truncated at byte N (...)" and the like)."""

import enum


class Status(enum.IntEnum):
    """brdffit_status, value for value (include/brdffit.h)."""

    OK = 0
    INVALID_ARGUMENT = 1
    NO_MEMORY = 2
    FILE_OPEN = 3
    FILE_NOT_REGULAR = 4
    FILE_READ = 5
    FILE_EMPTY = 6
    FILE_TRUNCATED = 7
    FILE_DIMS = 8
    FILE_TRAILING = 9
    FILE_NONFINITE = 10
    FILE_WRITE = 11
    UNKNOWN_MODEL = 12
    PARAM_RANGE = 13
    NO_SAMPLES = 14
    NO_DEVICE = 15
    OPENCL = 16
    KERNEL_BUILD = 17
    FIT_FAILED = 18
    CACHE_DIR = 19
    TOO_FEW_SAMPLES = 20
    VALUE_RANGE = 21
    OPTIONS_SIZE = 22


class BrdffitError(Exception):
    """A failed call.  ``status`` is a :class:`Status` (or the plain int of a
    status this package does not know; None for library loading faults),
    ``message`` the library's message."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status
        self.message = message

    def __reduce__(self):
        return (type(self), (self.status, self.message))


class LibraryError(BrdffitError):
    """libbrdffit could not be found or loaded, or is not the version and
    layout this package was written for (``status`` is None)."""

    def __init__(self, message):
        super().__init__(None, message)

    def __reduce__(self):
        return (type(self), (self.message,))


class InvalidArgumentError(BrdffitError, ValueError):
    """A bad argument: wrong shape, non-finite direction, unknown option."""


class OutOfMemoryError(BrdffitError, MemoryError):
    """The library could not allocate."""


class FileError(BrdffitError):
    """A file that could not be read or written; the subclasses say how."""


class FileOpenError(FileError):
    """Missing or unreadable file."""


class FileNotRegularError(FileError):
    """A directory or other non-file."""


class FileReadError(FileError):
    """An I/O error while reading."""


class FileEmptyError(FileError):
    """Zero bytes."""


class FileTruncatedError(FileError):
    """Fewer bytes than the header promises."""


class FileDimsError(FileError):
    """Dimensions other than 90 x 90 x 180."""


class FileTrailingError(FileError):
    """Bytes after the last sample."""


class FileNonfiniteError(FileError):
    """NaN or inf stored in the table."""


class FileWriteError(FileError):
    """Could not write a file."""


class UnknownModelError(BrdffitError, ValueError):
    """No model of that name or id."""


class ParamRangeError(BrdffitError, ValueError):
    """A parameter NaN, inf or outside its bounds."""


class NoSamplesError(BrdffitError):
    """No valid sample to fit."""


class NoDeviceError(BrdffitError):
    """No OpenCL platform or device (or none matches)."""


class OpenCLError(BrdffitError):
    """An OpenCL call failed."""


class KernelBuildError(BrdffitError):
    """The OpenCL program did not build (the log is in the message)."""


class FitFailedError(BrdffitError):
    """The optimiser could not produce a result."""


class CacheDirError(BrdffitError):
    """PoCL's kernel cache directory is unusable (the message says which and why)."""


class TooFewSamplesError(BrdffitError, ValueError):
    """Fewer distinct sample geometries than the model's unknowns."""


class ValueRangeError(BrdffitError, ValueError):
    """A finite value too large: stored above BRDFFIT_VALUE_MAX (bin and value in the
    message), or a render input or pixel beyond what a render can represent (named)."""


class OptionsSizeError(BrdffitError, ValueError):
    """An options struct of a size the library does not take (a mirror of another layout)."""


_CLASSES = {
    Status.INVALID_ARGUMENT: InvalidArgumentError,
    Status.NO_MEMORY: OutOfMemoryError,
    Status.FILE_OPEN: FileOpenError,
    Status.FILE_NOT_REGULAR: FileNotRegularError,
    Status.FILE_READ: FileReadError,
    Status.FILE_EMPTY: FileEmptyError,
    Status.FILE_TRUNCATED: FileTruncatedError,
    Status.FILE_DIMS: FileDimsError,
    Status.FILE_TRAILING: FileTrailingError,
    Status.FILE_NONFINITE: FileNonfiniteError,
    Status.FILE_WRITE: FileWriteError,
    Status.UNKNOWN_MODEL: UnknownModelError,
    Status.PARAM_RANGE: ParamRangeError,
    Status.NO_SAMPLES: NoSamplesError,
    Status.NO_DEVICE: NoDeviceError,
    Status.OPENCL: OpenCLError,
    Status.KERNEL_BUILD: KernelBuildError,
    Status.FIT_FAILED: FitFailedError,
    Status.CACHE_DIR: CacheDirError,
    Status.TOO_FEW_SAMPLES: TooFewSamplesError,
    Status.VALUE_RANGE: ValueRangeError,
    Status.OPTIONS_SIZE: OptionsSizeError,
}


def error_class(status):
    """The exception class raised for a status."""
    try:
        return _CLASSES.get(Status(status), BrdffitError)
    except ValueError:
        return BrdffitError


def make_error(status, message):
    """The exception for a status and message (an unknown status keeps its int)."""
    try:
        st = Status(status)
    except ValueError:
        st = int(status)
    return error_class(status)(st, message)
