# SPDX-License-Identifier: MIT
"""brdffit: fit analytic BRDF models to measured MERL reflectance tables.

A NumPy interface to libbrdffit (ctypes; no compiler needed).  The library is
found at first use (see load_library) and checked against the version and
struct layouts this package was written for.

    import brdffit
    t = brdffit.Table.read("alum-bronze.binary")
    s = brdffit.Samples(t, cutoff=80, scale="standard")
    with brdffit.Context() as ctx:
        r = brdffit.fit(ctx, s, "cook-torrance")
    rgb = brdffit.eval("cook-torrance", r.params, wi, wo)   # (n, 3) arrays
    img = brdffit.render(r)                                 # (256, 256, 4) RGBA
    theta_o, curves = brdffit.incidence_curves(t)           # (4, 180, 3) measured
    a = brdffit.albedo(r)                                   # (18, 3) at theta_o 0..85

Conventions (frame, units, scales, the Error metric) are those of
include/brdffit.h: wi toward the light, wo toward the viewer, z the normal,
BRDF values in 1/sr without the cosine factor.
"""

from ._lib import Library, load_library
from ._version import __version__
from .errors import (
    BrdffitError,
    CacheDirError,
    FileDimsError,
    FileEmptyError,
    FileError,
    FileNonfiniteError,
    FileNotRegularError,
    FileOpenError,
    FileReadError,
    FileTrailingError,
    FileTruncatedError,
    FileWriteError,
    FitFailedError,
    InvalidArgumentError,
    KernelBuildError,
    LibraryError,
    NoDeviceError,
    NoSamplesError,
    OpenCLError,
    OptionsSizeError,
    OutOfMemoryError,
    ParamRangeError,
    Status,
    TooFewSamplesError,
    UnknownModelError,
    ValueRangeError,
)
from .albedo import albedo
from .curves import incidence_curves
from .evaluate import eval  # noqa: A004 (the C API's name)
from .fitting import METRICS, AtBound, Context, FitFlag, FitResult, error_of, fit
from .models import Model, Param, Params, metric_name, model, models
from .render import COVERAGE_MASKED, Light, default_lights, flip, image_error, render
from .samples import Sample, Samples
from .table import Table, scale_factors


def library_version():
    """The loaded library's version string ("1.0.0")."""
    from ._lib import library

    return library().version


def version():
    """The loaded library's version string, as brdffit_version() returns it
    ("1.0.0"); the same as library_version()."""
    return library_version()


def release_memory():
    """Hand the large arrays the library keeps for reuse back to the system
    (brdffit_release_memory): the bytes released.  The library keeps a freed
    table's or sample set's arrays (4 MB and up; at most 16 and 1 GiB) for the
    next ones of about their size."""
    from ._lib import cdll

    return int(cdll().brdffit_release_memory())


__all__ = [
    "METRICS", "AtBound", "BrdffitError", "COVERAGE_MASKED", "CacheDirError", "Context", "FileDimsError",
    "FileEmptyError", "FileError", "FileNonfiniteError", "FileNotRegularError", "FileOpenError",
    "FileReadError", "FileTrailingError", "FileTruncatedError", "FileWriteError", "FitFailedError",
    "FitFlag", "FitResult", "InvalidArgumentError", "KernelBuildError", "Library", "LibraryError",
    "Light", "Model", "NoDeviceError", "NoSamplesError", "OpenCLError", "OptionsSizeError",
    "OutOfMemoryError", "Param", "ParamRangeError", "Params", "Sample", "Samples", "Status", "Table",
    "TooFewSamplesError", "UnknownModelError", "ValueRangeError", "__version__",
    "albedo", "default_lights", "error_of", "eval", "fit", "flip", "image_error",
    "incidence_curves",
    "library_version", "load_library", "metric_name", "model", "models", "release_memory", "render",
    "scale_factors", "version",
]
