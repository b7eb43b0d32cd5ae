# SPDX-License-Identifier: MIT
"""Finding and checking the library: the four places, version and layout
checks that refuse a mismatched library, the mirrors equal to the header,
make install (pip install: test_pip.py)."""

import ctypes
import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import LIBRARY, PYDIR, REPO

HEADER = os.path.join(REPO, "include", "brdffit.h")


def header_text():
    with open(HEADER) as f:
        return f.read()


def header_enum(name):
    """{NAME: value} of a typedef enum in the header (values implicit or explicit)."""
    m = re.search(r"typedef enum %s \{(.*?)\} %s;" % (name, name), header_text(), re.S)
    assert m, f"enum {name} not in the header"
    out, value = {}, -1
    for line in m.group(1).splitlines():
        line = re.sub(r"/\*.*?\*/", "", line).strip().rstrip(",")
        if not line:
            continue
        mm = re.match(r"(\w+)(?:\s*=\s*(\d+))?$", line)
        assert mm, f"cannot read enum line {line!r}"
        value = int(mm.group(2)) if mm.group(2) else value + 1
        out[mm.group(1)] = value
    return out


def run_python(code, env_extra, pythonpath, cwd):
    env = {k: v for k, v in os.environ.items() if k not in ("BRDFFIT_LIBRARY", "PYTHONPATH")}
    env.update(env_extra)
    env["PYTHONPATH"] = pythonpath
    return subprocess.run(
        [sys.executable, "-c", code], env=env, cwd=cwd, capture_output=True, text=True
    )


def package_copy(tmp_path):
    dest = tmp_path / "site"
    shutil.copytree(os.path.join(PYDIR, "brdffit"), dest / "brdffit",
                    ignore=shutil.ignore_patterns("__pycache__", "*.so*"))
    return dest


def compile_fake(tmp_path, name, source):
    src = tmp_path / (name + ".c")
    src.write_text(source)
    out = tmp_path / ("lib" + name + ".so")
    cc = os.environ.get("CC", "cc")
    subprocess.run([cc, "-shared", "-fPIC", "-o", str(out), str(src)], check=True)
    return str(out)


# ---------------------------------------------------------------- where it is found

def test_explicit_path(brdffit, lib_path):
    lib = brdffit.load_library(lib_path)
    assert lib.path == lib_path
    assert lib.version == brdffit.library_version()
    assert re.fullmatch(r"\d+\.\d+\.\d+", lib.version)
    assert "brdffit library" in repr(lib)


def test_explicit_path_missing(brdffit, tmp_path):
    with pytest.raises(brdffit.LibraryError, match="the given path .*nope.so") as e:
        brdffit.load_library(str(tmp_path / "nope.so"))
    assert e.value.status is None
    brdffit.library_version()  # the library in use is still the good one


def test_environment_variable(tmp_path):
    site = package_copy(tmp_path)
    r = run_python("import brdffit; print(brdffit.load_library().path)",
                   {"BRDFFIT_LIBRARY": LIBRARY}, str(site), str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == LIBRARY


def test_environment_variable_wrong_does_not_fall_through(tmp_path):
    site = package_copy(tmp_path)
    os.symlink(LIBRARY, site / "brdffit" / "libbrdffit.so.1")  # would load, if tried
    r = run_python("import brdffit; brdffit.models()",
                   {"BRDFFIT_LIBRARY": str(tmp_path / "absent.so")}, str(site), str(tmp_path))
    assert r.returncode != 0
    assert "LibraryError" in r.stderr and "$BRDFFIT_LIBRARY" in r.stderr
    assert "absent.so" in r.stderr


def test_next_to_package(tmp_path):
    site = package_copy(tmp_path)
    os.symlink(LIBRARY, site / "brdffit" / "libbrdffit.so.1")
    r = run_python("import brdffit; print(brdffit.load_library().path); print(len(brdffit.models()))",
                   {}, str(site), str(tmp_path))
    assert r.returncode == 0, r.stderr
    path, count = r.stdout.split()
    assert path == str(site / "brdffit" / "libbrdffit.so.1")
    assert int(count) >= 7


def test_system_search(tmp_path):
    site = package_copy(tmp_path)
    r = run_python("import brdffit; print(brdffit.load_library().path); print(brdffit.library_version())",
                   {"LD_LIBRARY_PATH": os.path.dirname(LIBRARY)}, str(site), str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert r.stdout.split()[0] == "libbrdffit.so.1"


def test_not_found_says_where_it_looked(brdffit, monkeypatch):
    from brdffit import _lib

    monkeypatch.delenv("BRDFFIT_LIBRARY")
    monkeypatch.setattr(_lib, "SONAME", "libbrdffit-absent-for-test.so.1")
    monkeypatch.setattr(_lib.ctypes.util, "find_library", lambda name: None)
    with pytest.raises(brdffit.LibraryError) as e:
        brdffit.load_library()
    msg = str(e.value)
    assert "not found" in msg and "next to the package" in msg and "the system" in msg
    assert "BRDFFIT_LIBRARY" in msg


# ---------------------------------------------------------------- version and layout checks

def test_version_mismatch_refused(brdffit, tmp_path):
    fake = compile_fake(tmp_path, "fakeversion",
                        'const char *brdffit_version(void) { return "9.4.2"; }\n')
    with pytest.raises(brdffit.LibraryError) as e:
        brdffit.load_library(fake)
    assert "9.4.2" in str(e.value) and "0.1.x" in str(e.value).replace(
        ".".join(map(str, brdffit._version.LIBRARY_VERSION)) + ".x", "0.1.x")
    assert fake in str(e.value)


def test_expected_version_differs_refused(brdffit, lib_path, monkeypatch):
    from brdffit import _lib

    major, minor = brdffit._version.LIBRARY_VERSION
    monkeypatch.setattr(_lib, "LIBRARY_VERSION", (major, minor + 1))
    with pytest.raises(brdffit.LibraryError, match=r"written for %d\.%d\.x" % (major, minor + 1)):
        brdffit.load_library(lib_path)


def test_library_without_introspection_refused(brdffit, tmp_path):
    major, minor = brdffit._version.LIBRARY_VERSION
    fake = compile_fake(tmp_path, "fakenosize",
                        'const char *brdffit_version(void) { return "%d.%d.0"; }\n' % (major, minor))
    with pytest.raises(brdffit.LibraryError, match="brdffit_struct_size"):
        brdffit.load_library(fake)


def test_library_with_other_layout_refused(brdffit, tmp_path):
    major, minor = brdffit._version.LIBRARY_VERSION
    fake = compile_fake(tmp_path, "fakelayout", """
#include <stddef.h>
#include <string.h>
const char *brdffit_version(void) { return "%d.%d.7"; }
size_t brdffit_struct_size(int kind) { return kind == 7 ? 8 : 0; }
size_t brdffit_struct_offset(int kind, const char *m) { return strcmp(m, "error") ? 0 : (size_t)-1; }
""" % (major, minor))
    with pytest.raises(brdffit.LibraryError) as e:
        brdffit.load_library(fake)
    msg = str(e.value)
    assert "struct FitResult (kind 7): 8 bytes in the library" in msg
    assert "the library has no member 'error'" in msg


def test_not_a_brdffit_library_refused(brdffit):
    libm = ctypes.util.find_library("m")
    with pytest.raises(brdffit.LibraryError, match="not libbrdffit"):
        brdffit.load_library(libm)


def test_mirror_that_drifted_is_refused(brdffit, lib_path, monkeypatch):
    """A mirror with a member in the wrong place, or one too many, is caught
    by the size and offset check against the library, not read as garbage."""
    from brdffit import _abi

    class Swapped(ctypes.Structure):  # iterations and passes swapped: same size
        _fields_ = [f if f[0] not in ("iterations", "passes") else
                    ({"iterations": "passes", "passes": "iterations"}[f[0]], f[1])
                    for f in _abi.FitResult._fields_]

    class Longer(ctypes.Structure):
        _fields_ = _abi.FitResult._fields_ + [("extra", ctypes.c_double)]

    class InPadding(ctypes.Structure):  # an int in the tail padding: the same size
        _fields_ = _abi.FitResult._fields_ + [("extra", ctypes.c_int)]

    cases = [(Swapped, "member 'iterations' at offset"), (Longer, "bytes in the library")]
    if ctypes.sizeof(InPadding) == ctypes.sizeof(_abi.FitResult):  # tail padding to hide in
        cases.append((InPadding, "the library has no member 'extra'"))
    kinds = dict(_abi.STRUCT_KINDS)
    kinds.pop(_abi.FitResult)
    for mirror, problem in cases:
        monkeypatch.setattr(_abi, "STRUCT_KINDS", {**kinds, mirror: 7})
        with pytest.raises(brdffit.LibraryError, match=problem):
            brdffit.load_library(lib_path)


def test_mirrors_match_the_library(brdffit):
    from brdffit import _abi, _lib

    lib = _lib.cdll()
    for mirror, kind in _abi.STRUCT_KINDS.items():
        assert lib.brdffit_struct_size(kind) == ctypes.sizeof(mirror), mirror.__name__
        for name, *_ in mirror._fields_:
            assert lib.brdffit_struct_offset(kind, name.encode()) == getattr(mirror, name).offset
    assert lib.brdffit_struct_size(999) == 0


def test_struct_kinds_are_the_headers():
    from brdffit import _abi

    kinds = header_enum("brdffit_struct_kind")
    c_names = {}
    for struct_name in re.findall(r"BRDFFIT_STRUCT_(\w+) = \d+,?\s*/\* (\w+)", header_text()):
        c_names[struct_name[0]] = struct_name[1]
    assert set(_abi.STRUCT_KINDS.values()) == set(kinds.values())
    for mirror, kind in _abi.STRUCT_KINDS.items():
        name = [k for k, v in kinds.items() if v == kind][0]
        assert c_names[name.replace("BRDFFIT_STRUCT_", "")].replace("_", "") == \
            "brdffit" + mirror.__name__.lower()


def test_status_enum_is_the_headers():
    from brdffit import Status

    c = header_enum("brdffit_status")
    py = {"BRDFFIT_" + ("" if s.name == "OK" else "E_") + s.name: int(s) for s in Status}
    c.pop("BRDFFIT_STATUS_COUNT")
    assert py == c


def test_pinned_enums_are_the_headers():
    from brdffit import _abi

    assert header_enum("brdffit_scale") == {"BRDFFIT_SCALE_" + k.upper(): v
                                           for k, v in _abi.SCALES.items()}
    assert header_enum("brdffit_interp") == {"BRDFFIT_INTERP_" + k.upper(): v
                                            for k, v in _abi.INTERPS.items()}
    assert header_enum("brdffit_backend") == {"BRDFFIT_BACKEND_" + k.upper(): v
                                             for k, v in _abi.BACKENDS.items()}


def test_versions_agree_with_the_header(brdffit):
    text = header_text()
    v = [int(re.search(r"#define BRDFFIT_VERSION_%s (\d+)" % k, text).group(1))
         for k in ("MAJOR", "MINOR", "PATCH")]
    assert brdffit.__version__ == "%d.%d.%d" % tuple(v)
    assert tuple(brdffit._version.LIBRARY_VERSION) == tuple(v[:2])
    assert brdffit.library_version() == "%d.%d.%d" % tuple(v)


def test_every_function_is_declared_in_the_header():
    from brdffit import _abi

    text = header_text()
    for name in _abi.FUNCTIONS:
        assert re.search(r"\b%s\(" % name, text), name


# ---------------------------------------------------------------- installing

def _clean_env():
    return {k: v for k, v in os.environ.items()
            if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "BRDFFIT_LIBRARY", "PYTHONPATH")}


def test_make_install_puts_the_package_beside_the_library(tmp_path):
    dest = tmp_path / "dest"
    build = os.path.dirname(LIBRARY)
    r = subprocess.run(["make", "-C", REPO, "install", "DESTDIR=" + str(dest), "PREFIX=/opt/bf",
                        "BUILD=" + build], capture_output=True, text=True, env=_clean_env())
    assert r.returncode == 0, r.stdout + r.stderr
    found = list(dest.glob("opt/bf/lib/python3*/dist-packages/brdffit/__init__.py"))
    assert len(found) == 1, list(dest.rglob("*"))
    pkg = found[0].parent
    link = pkg / "libbrdffit.so.1"
    assert link.is_symlink() and not os.path.isabs(os.readlink(link))
    assert os.path.samefile(link, dest / "opt/bf/lib/libbrdffit.so.1")
    r = run_python("import brdffit; print(brdffit.load_library().path)", {},
                   str(pkg.parent), str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str(link)
