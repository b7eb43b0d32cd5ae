# SPDX-License-Identifier: MIT
"""The wheel's build step (pyproject.toml names setuptools; the metadata is
there): `pip install ./python` and `pip wheel ./python` build libbrdffit with
the project's Makefile in the checkout around this folder (make
build/libbrdffit.so: the project's own flags, an existing build reused) and
put a copy of it in the package, brdffit/libbrdffit.so.1, where brdffit._lib
looks after $BRDFFIT_LIBRARY.  The kernel sources are compiled into the
library, so that one file is all the package needs besides the system's
OpenCL and cminpack.

The library is native code loaded through ctypes, not an extension module:
the wheel is tagged py3-none-<platform> (any Python 3, this platform only).

The Makefile's first-build step that installs Debian packages (.ci/install-deps)
is skipped here: a pip build never calls apt, and it would look for the test
tools of whatever python3 is on PATH.  When a build dependency is missing the
compiler says which header; `make deps` in the checkout installs them.

An editable install (pip install -e ./python) links brdffit/libbrdffit.so.1
to the checkout's build/libbrdffit.so.1 instead, so a rebuild is seen.

A source distribution would not hold the C sources (they are outside this
folder), so building one is refused: build wheels from a checkout.
"""

import os
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py
from setuptools.command.sdist import sdist

try:
    from setuptools.command.bdist_wheel import bdist_wheel  # setuptools >= 70.1
except ImportError:  # older setuptools: the wheel package's
    from wheel.bdist_wheel import bdist_wheel

HERE = os.path.dirname(os.path.abspath(__file__))
CHECKOUT = os.path.dirname(HERE)
SONAME = "libbrdffit.so.1"
BUILD = "build"  # the Makefile's default build folder, relative to CHECKOUT


def build_library():
    """Run the checkout's Makefile for the shared library; its path."""
    for need in ("Makefile", os.path.join("include", "brdffit.h")):
        if not os.path.exists(os.path.join(CHECKOUT, need)):
            raise SystemExit(
                f"brdffit: {os.path.join(CHECKOUT, need)} not found: the package is built "
                "from a checkout of the project (pip install ./python, pip wheel ./python), "
                "whose Makefile builds the library it carries"
            )
    cmd = ["make", "-C", CHECKOUT, "BUILD=" + BUILD, "DEPS_STAMP=", f"{BUILD}/libbrdffit.so"]
    if "MAKEFLAGS" not in os.environ:  # under make, its jobserver decides
        cmd.insert(1, f"-j{os.cpu_count() or 1}")
    print("brdffit: " + " ".join(cmd), flush=True)
    if subprocess.call(cmd) != 0:
        raise SystemExit(
            "brdffit: building libbrdffit failed (above); a missing header means a missing "
            f"build dependency: `make deps` in {CHECKOUT} installs them (Debian)"
        )
    path = os.path.join(CHECKOUT, BUILD, SONAME)
    if not os.path.exists(path):
        raise SystemExit(f"brdffit: the Makefile ran but {path} is not there")
    return path


class BuildPy(build_py):
    def run(self):
        if not getattr(self, "editable_mode", False):
            # only this build's modules: a module since removed from brdffit/
            # must not stay in the wheel from an earlier build
            shutil.rmtree(os.path.join(self.build_lib, "brdffit"), ignore_errors=True)
        super().run()
        lib = build_library()
        if getattr(self, "editable_mode", False):
            link = os.path.join(HERE, "brdffit", SONAME)
            if os.path.lexists(link):
                os.remove(link)
            os.symlink(os.path.relpath(lib, os.path.dirname(link)), link)
        else:
            dest = os.path.join(self.build_lib, "brdffit", SONAME)
            shutil.copyfile(lib, dest)  # the file itself, not the build's symlink
            os.chmod(dest, 0o755)


class NativeDistribution(Distribution):
    """A distribution with native code (the library): installed to platlib,
    its wheel not pure."""

    def has_ext_modules(self):
        return True


class BdistWheel(bdist_wheel):
    def get_tag(self):
        _, _, platform = super().get_tag()
        return "py3", "none", platform


class Sdist(sdist):
    def run(self):
        raise SystemExit(
            "brdffit: no source distribution: the C sources it needs are outside python/; "
            "build a wheel from a checkout instead (pip wheel ./python)"
        )


setup(distclass=NativeDistribution, cmdclass={"build_py": BuildPy, "bdist_wheel": BdistWheel, "sdist": Sdist})
