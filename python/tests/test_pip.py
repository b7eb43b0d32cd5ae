# SPDX-License-Identifier: MIT
"""pip install ./python and pip wheel ./python, the way a user runs them: in a
copy of the checkout without a build (python/setup.py builds the library with
the checkout's Makefile), into a fresh venv (pip's isolated build gets
setuptools from the index; the venv gets NumPy from it).  The installed
package is imported from another folder with no BRDFFIT_LIBRARY, loads the
library inside it and fits a table; the wheel holds the package and the
library and nothing else, tagged for this platform.  About a minute: the copy
compiles the library from scratch."""

import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import zipfile

import pytest

from conftest import LIBRARY, PYDIR, REPO

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="the library is built for Linux (ELF, .so.1)")

SONAME = "libbrdffit.so.1"


def header_version():
    with open(os.path.join(REPO, "include", "brdffit.h")) as f:
        text = f.read()
    return ".".join(re.search(r"#define BRDFFIT_VERSION_%s (\d+)" % k, text).group(1)
                    for k in ("MAJOR", "MINOR", "PATCH"))


def clean_env(**extra):
    """The environment of a user's shell: no library override, no make jobserver."""
    drop = ("BRDFFIT_LIBRARY", "PYTHONPATH", "PYTHONHOME", "LD_LIBRARY_PATH", "VIRTUAL_ENV",
            "MAKEFLAGS", "MFLAGS", "MAKELEVEL")
    env = {k: v for k, v in os.environ.items() if k not in drop}
    env.update(extra)
    return env


def run(cmd, cwd, **extra):
    return subprocess.run(cmd, cwd=cwd, env=clean_env(**extra), capture_output=True, text=True)


def checkout_files():
    """The checkout's files as a clone has them, with any uncommitted change
    (tracked and untracked, not ignored); None when it is not a git checkout."""
    if shutil.which("git") is None:
        return None
    r = subprocess.run(["git", "-C", REPO, "ls-files", "-z", "-c", "-o", "--exclude-standard"],
                       capture_output=True)
    if r.returncode != 0:
        return None
    return [f for f in r.stdout.decode().split("\0")
            if f and os.path.isfile(os.path.join(REPO, f))]


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    """A copy of the checkout without build/ (a git repository with every file
    staged when git is there, so `git status` shows what the builds leave),
    and a fresh venv (not activated) with pip able to reach the index."""
    top = tmp_path_factory.mktemp("pip")
    src = top / "brdffit"
    files = checkout_files()
    if files is None:
        shutil.copytree(REPO, src, symlinks=True, ignore=shutil.ignore_patterns(
            "build", "build-*", "__pycache__", "*.egg-info", ".git"))
    else:
        for f in files:
            dest = src / f
            dest.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(os.path.join(REPO, f), dest, follow_symlinks=False)
        for cmd in (["git", "init", "-q"], ["git", "add", "-A"]):
            subprocess.run(cmd, cwd=src, check=True, capture_output=True)
    assert not (src / "build").exists()

    venv = top / "venv"
    r = run([sys.executable, "-m", "venv", str(venv)], top)
    if r.returncode != 0:
        last = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
        pytest.skip(f"{sys.executable} -m venv failed (Debian: apt-get install python3-venv): "
                    f"{last}")
    py = str(venv / "bin" / "python")
    # pip's isolated build needs setuptools from the index (PyPI or pip's configured one)
    r = run([py, "-m", "pip", "download", "--no-deps", "-q", "-d", str(top / "probe"),
             "setuptools>=64"], top)
    if r.returncode != 0:
        last = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
        pytest.skip(f"pip's index is unreachable, and the isolated build gets setuptools from "
                    f"it: {last}")
    return {"src": src, "venv": venv, "python": py, "top": top}


def git_leftovers(src):
    """What `git status` in the copy shows besides the files staged at the start."""
    if not (src / ".git").exists():
        return None
    r = subprocess.run(["git", "status", "--porcelain", "--untracked-files=all"], cwd=src,
                       capture_output=True, text=True, check=True)
    return [line for line in r.stdout.splitlines() if not line.startswith("A  ")]


def test_pip_wheel_carries_the_library(fresh):
    src, out = fresh["src"], fresh["top"] / "wheels"
    r = run([fresh["python"], "-m", "pip", "wheel", "--no-deps", "-w", str(out), "./python"], src)
    assert r.returncode == 0, r.stdout + r.stderr
    wheels = list(out.glob("*.whl"))
    assert len(wheels) == 1, wheels
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    assert wheels[0].name == f"brdffit-{header_version()}-py3-none-{platform}.whl"

    with zipfile.ZipFile(wheels[0]) as z:
        names = set(z.namelist())
        info = f"brdffit-{header_version()}.dist-info/"
        modules = {"brdffit/" + f for f in os.listdir(os.path.join(PYDIR, "brdffit"))
                   if f.endswith(".py")}
        assert names - {n for n in names if n.startswith(info)} == modules | {"brdffit/" + SONAME}
        assert {n[len(info):] for n in names if n.startswith(info)} <= \
            {"METADATA", "WHEEL", "RECORD", "top_level.txt"}
        wheel_meta = z.read(info + "WHEEL").decode()
        assert "Root-Is-Purelib: false" in wheel_meta
        assert f"Tag: py3-none-{platform}" in wheel_meta
        lib = z.read("brdffit/" + SONAME)
        mode = z.getinfo("brdffit/" + SONAME).external_attr >> 16
    # the library the checkout's Makefile built, the file itself
    with open(src / "build" / SONAME, "rb") as f:
        assert lib == f.read()
    assert lib[:4] == b"\x7fELF" and mode & 0o111
    assert git_leftovers(src) in (None, []), git_leftovers(src)


def test_pip_install_into_a_fresh_venv(fresh):
    src, py = fresh["src"], fresh["python"]
    r = run([py, "-m", "pip", "install", "./python"], src)
    assert r.returncode == 0, r.stdout + r.stderr
    assert git_leftovers(src) in (None, []), git_leftovers(src)

    elsewhere = fresh["top"] / "elsewhere"
    elsewhere.mkdir()
    # the library mapped into the process is the package's own; a tiny fit
    # (the kernels are inside the library: no source tree needed)
    code = r"""
import json, os
import brdffit
lib = brdffit.load_library()
maps = sorted({line.split(None, 5)[5].strip() for line in open("/proc/self/maps")
               if "libbrdffit" in line})
truth = [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.15]
s = brdffit.Samples(brdffit.Table.from_model("cook-torrance", truth))
with brdffit.Context() as ctx:
    r = brdffit.fit(ctx, s, "cook-torrance")
print(json.dumps({"version": brdffit.version(), "package": brdffit.__version__,
                  "file": brdffit.__file__, "path": lib.path, "maps": maps,
                  "error": r.error, "params": list(r.params.vector())}))
"""
    r = run([py, "-c", code], elsewhere)
    assert r.returncode == 0, r.stderr
    got = json.loads(r.stdout.strip().splitlines()[-1])
    assert got["version"] == header_version() == got["package"]
    pkg = os.path.dirname(got["file"])
    assert pkg.startswith(str(fresh["venv"]) + os.sep), got["file"]
    assert got["path"] == os.path.join(pkg, SONAME)
    assert os.path.isfile(got["path"]) and not os.path.islink(got["path"])
    assert got["maps"] == [got["path"]]
    assert got["error"] < 1e-6
    assert got["params"] == pytest.approx([0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.15], rel=1e-4)

    # $BRDFFIT_LIBRARY still overrides the library inside the package
    r = run([py, "-c", "import brdffit; print(brdffit.load_library().path)"], elsewhere,
            BRDFFIT_LIBRARY=LIBRARY)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == LIBRARY
