# SPDX-License-Identifier: MIT
"""Fixtures of the Python tests: the package from this source tree, the library
built beside it ($BRDFFIT_LIBRARY, else ../build/libbrdffit.so.1), the brdffit
program ($BRDFFIT_CLI, else ../build/brdffit) and ../shared ($BRDFFIT_SHARED)."""

import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
PYDIR = os.path.dirname(HERE)
REPO = os.path.dirname(PYDIR)

sys.path.insert(0, PYDIR)  # the package under test is this tree's, whatever is installed

if not os.environ.get("BRDFFIT_LIBRARY"):
    os.environ["BRDFFIT_LIBRARY"] = os.path.join(REPO, "build", "libbrdffit.so.1")
LIBRARY = os.path.abspath(os.environ["BRDFFIT_LIBRARY"])
os.environ["BRDFFIT_LIBRARY"] = LIBRARY
if not os.environ.get("POCL_CACHE_DIR"):
    os.environ["POCL_CACHE_DIR"] = os.path.join(REPO, "build", "pocl-cache")
    os.makedirs(os.environ["POCL_CACHE_DIR"], mode=0o700, exist_ok=True)  # private: see docs/opencl.md


def _path_from_env(var, default):
    p = os.environ.get(var) or default
    return p if os.path.isabs(p) else os.path.join(REPO, p)


CLI = _path_from_env("BRDFFIT_CLI", os.path.join("build", "brdffit"))
SHARED = _path_from_env("BRDFFIT_SHARED", os.path.join(REPO, "..", "shared"))
HAVE_SHARED = os.path.exists(os.path.join(SHARED, "tools", "merl-table"))


def pytest_configure(config):
    config.addinivalue_line("markers", "shared: reads ../shared ($BRDFFIT_SHARED)")


def pytest_collection_modifyitems(config, items):
    """Without ../shared the tests that read it (marked `shared`, or using a
    MERL table fixture) are deselected: the rest runs, and `make test`, whose
    Check suite says in one line what is missing, fails."""
    if HAVE_SHARED:
        return
    keep, drop = [], []
    for item in items:
        uses = set(getattr(item, "fixturenames", ())) & {"alum_bronze"}
        (drop if uses or item.get_closest_marker("shared") else keep).append(item)
    if drop:
        config.hook.pytest_deselected(items=drop)
        items[:] = keep


@pytest.fixture(scope="session")
def lib_path():
    assert os.path.exists(LIBRARY), f"no library at {LIBRARY}: run make first"
    return LIBRARY


@pytest.fixture(scope="session")
def brdffit(lib_path):
    import brdffit as module

    module.load_library(lib_path)
    return module


@pytest.fixture(scope="session")
def cli():
    assert os.path.exists(CLI), f"no brdffit program at {CLI}: run make first"
    return CLI


def shared(rel):
    path = os.path.join(SHARED, rel)
    assert os.path.exists(path), f"{path} missing: the tests need ../shared (or $BRDFFIT_SHARED)"
    return path


def merl_table(name):
    tool = shared(os.path.join("tools", "merl-table"))
    out = subprocess.run([tool, name], check=True, capture_output=True, text=True)
    return out.stdout.strip()


@pytest.fixture(scope="session")
def alum_bronze():
    return merl_table("alum-bronze")


@pytest.fixture(scope="session")
def ctx(brdffit):
    with brdffit.Context() as c:
        yield c


@pytest.fixture(scope="session")
def cdll(brdffit):
    """The raw library, for comparing with the C functions called one by one."""
    import ctypes

    from brdffit import _abi, _lib

    lib = _lib.cdll()
    P = ctypes.c_void_p
    lib.brdffit_table_lookup.restype = _abi.c_enum
    lib.brdffit_table_lookup.argtypes = [P, P, P, _abi.c_enum, _abi.c_enum, P]
    return lib
