# SPDX-License-Identifier: MIT
"""Finding, loading and checking libbrdffit; the one handle every call uses.

Where the library comes from, first match wins:
  1. the path given to brdffit.load_library(path);
  2. $BRDFFIT_LIBRARY;
  3. next to the package: libbrdffit.so.1 in the package's own folder (the
     copy `pip install ./python` puts there, or the link `make install` does);
  4. the system: the dynamic loader's search for libbrdffit.so.1
     (LD_LIBRARY_PATH, ld.so.cache), then ctypes.util.find_library.
A path given in 1 or 2 that does not load is an error; it never falls
through to another library.

A library is used only when its version has the major and minor version this
package was written for and every struct mirror in brdffit._abi has the size
and member offsets the library reports; otherwise LibraryError says what
differs.
"""

import ctypes
import ctypes.util
import os
import threading

from . import _abi
from ._version import LIBRARY_VERSION
from .errors import InvalidArgumentError, LibraryError, Status, make_error

SONAME = "libbrdffit.so.1"
_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))

_lock = threading.Lock()
_loaded = None  # the Library in use


class Library:
    """A loaded and checked libbrdffit: ``path``, ``version``, ``cdll``."""

    def __init__(self, cdll, path, version):
        self.cdll = cdll
        self.path = path
        self.version = version

    def __reduce_ex__(self, protocol):
        raise TypeError(
            "a brdffit.Library cannot be pickled or copied: it is the C library loaded in "
            "this process; call brdffit.load_library in each process"
        )

    def __repr__(self):
        return f"<brdffit library {self.version} at {self.path}>"


def _candidates():
    """(where, path or name) in search order, for the default search."""
    env = os.environ.get("BRDFFIT_LIBRARY")
    if env:
        return [("$BRDFFIT_LIBRARY", env)]
    found = [("next to the package", os.path.join(_PACKAGE_DIR, SONAME))]
    found.append(("the system", SONAME))
    name = ctypes.util.find_library("brdffit")
    if name and name != SONAME:
        found.append(("the system (find_library)", name))
    return found


def _parse_version(text):
    parts = text.split(".")
    try:
        return tuple(int(p) for p in parts[:3])
    except ValueError:
        return None


def check_library(cdll, path):
    """Check a loaded CDLL against this package; returns its version string
    or raises LibraryError naming every difference."""
    try:
        version_fn = cdll.brdffit_version
    except AttributeError:
        raise LibraryError(f"{path}: not libbrdffit (no brdffit_version)") from None
    version_fn.restype = ctypes.c_char_p
    version_fn.argtypes = []
    raw = version_fn()
    version = raw.decode("ascii", "replace") if raw else ""
    parsed = _parse_version(version)
    want = ".".join(str(v) for v in LIBRARY_VERSION)
    if parsed is None or len(parsed) < 2 or parsed[:2] != tuple(LIBRARY_VERSION):
        raise LibraryError(
            f"{path}: libbrdffit version {version or '(none)'}, but this brdffit "
            f"package (python/) was written for {want}.x: use the library of the same "
            "release (or set BRDFFIT_LIBRARY to it)"
        )
    try:
        size_fn = cdll.brdffit_struct_size
        offset_fn = cdll.brdffit_struct_offset
    except AttributeError:
        raise LibraryError(
            f"{path}: libbrdffit {version} has no brdffit_struct_size/brdffit_struct_offset, "
            "so its struct layouts cannot be checked: refused"
        ) from None
    size_fn.restype, size_fn.argtypes = _abi.FUNCTIONS["brdffit_struct_size"]
    offset_fn.restype, offset_fn.argtypes = _abi.FUNCTIONS["brdffit_struct_offset"]
    unknown = ctypes.c_size_t(-1).value
    problems = []
    for mirror, kind in _abi.STRUCT_KINDS.items():
        name = mirror.__name__
        c_size = size_fn(kind)
        if c_size != ctypes.sizeof(mirror):
            problems.append(
                f"struct {name} (kind {kind}): {c_size} bytes in the library, "
                f"{ctypes.sizeof(mirror)} in the mirror"
            )
        for field in mirror._fields_:
            member = field[0]
            c_off = offset_fn(kind, member.encode())
            py_off = getattr(mirror, member).offset
            if c_off == unknown:
                problems.append(f"struct {name}: the library has no member '{member}'")
            elif c_off != py_off:
                problems.append(
                    f"struct {name}: member '{member}' at offset {c_off} in the library, "
                    f"{py_off} in the mirror"
                )
    if problems:
        raise LibraryError(
            f"{path}: libbrdffit {version} does not have the struct layout this brdffit "
            "package was written for:\n  " + "\n  ".join(problems)
        )
    missing = []
    for fname, (restype, argtypes) in _abi.FUNCTIONS.items():
        try:
            fn = getattr(cdll, fname)
        except AttributeError:
            missing.append(fname)
            continue
        fn.restype = restype
        fn.argtypes = argtypes
    if missing:
        raise LibraryError(f"{path}: libbrdffit {version} lacks {', '.join(missing)}")
    return version


def _open(path):
    return ctypes.CDLL(path)


def load_library(path=None):
    """Load and check libbrdffit and use it from now on; returns the Library.

    path: a file to load; None searches ($BRDFFIT_LIBRARY, next to the
    package, the system).  Raises LibraryError when nothing loads or the
    library is not the one this package was written for."""
    global _loaded
    with _lock:
        if path is not None:
            where = [("the given path", os.fspath(path))]
            if "\0" in os.fsdecode(where[0][1]):
                raise InvalidArgumentError(
                    Status.INVALID_ARGUMENT, f"load_library: {path!r} contains a NUL byte (no path can)")
        else:
            where = _candidates()
        tried = []
        for label, cand in where:
            explicit = label in ("the given path", "$BRDFFIT_LIBRARY")
            if not explicit and os.sep in cand and not os.path.exists(cand):
                tried.append(f"{label}: {cand} (absent)")
                continue
            try:
                cdll = _open(cand)
            except OSError as e:
                if explicit:
                    raise LibraryError(f"cannot load libbrdffit from {label} {cand}: {e}") from None
                tried.append(f"{label}: {cand} ({e})")
                continue
            version = check_library(cdll, cand)
            _loaded = Library(cdll, cand, version)
            return _loaded
        raise LibraryError(
            "libbrdffit not found; looked at:\n  "
            + "\n  ".join(tried)
            + "\nbuild it (make) and set BRDFFIT_LIBRARY=/path/to/libbrdffit.so.1, "
            "call brdffit.load_library(path), or install it (make install)"
        )


def library():
    """The Library in use, loading it by the default search on first use."""
    lib = _loaded
    if lib is None:
        lib = load_library()
    return lib


def cdll():
    return library().cdll


def raise_status(status, err=None, fallback=None):
    """Raise the exception for a non-zero status (message from err, else fallback,
    else the library's brdffit_strerror)."""
    message = ""
    if err is not None:
        message = err.message.decode("utf-8", "replace")
    if not message:
        message = fallback or ""
    if not message:
        text = cdll().brdffit_strerror(status)
        message = text.decode("utf-8", "replace") if text else f"status {status}"
    raise make_error(status, message)


def call(fname, *args):
    """Call a brdffit function whose last argument is a brdffit_error *;
    raise on failure."""
    err = _abi.Error()
    status = getattr(cdll(), fname)(*args, ctypes.byref(err))
    if status != 0:
        raise_status(status, err)
    return status


def strerror(status):
    text = cdll().brdffit_strerror(status)
    return text.decode("utf-8", "replace") if text else ""
