# SPDX-License-Identifier: MIT
"""The PyPI tools some tests check the program's files with (Blender's bpy,
pygltflib, Mitsuba 3, MaterialX, ꟻLIP): pip-installed into one virtual
environment of this Python kept under build/ (made once, reused;
$BRDFFIT_TEST_VENV overrides where).  Without python3-venv, pip or the
network a test that needs a tool is skipped, and the skip says why."""

import os
import shutil
import subprocess
import sys

import pytest

from conftest import REPO

VENV = os.environ.get("BRDFFIT_TEST_VENV") or os.path.join(REPO, "build", "test-venv")


def run(args, timeout=60, **kw):
    return subprocess.run(args, capture_output=True, text=True, timeout=timeout, **kw)


def last_line(r):
    lines = (r.stderr or r.stdout).strip().splitlines()
    return lines[-1] if lines else f"exit status {r.returncode}"


def venv_python():
    """The venv's python, made first when missing or made by another Python."""
    py = os.path.join(VENV, "bin", "python")
    want = f"{sys.version_info[0]}.{sys.version_info[1]}"
    if os.path.exists(py):
        r = run([py, "-c", "import sys; print('%d.%d' % sys.version_info[:2])"])
        if r.returncode != 0 or r.stdout.strip() != want:
            shutil.rmtree(VENV)
    if not os.path.exists(py):
        r = run([sys.executable, "-m", "venv", VENV], timeout=300)
        if r.returncode != 0:
            pytest.skip(f"python3 -m venv failed (Debian: python3-venv): {last_line(r)}")
    return py


def pip_install(py, spec, module):
    """Install spec unless module imports; skip the test, saying why, when pip cannot."""
    if run([py, "-c", f"import {module}"], timeout=120).returncode == 0:
        return
    r = run([py, "-m", "pip", "install", "--disable-pip-version-check", "--retries", "1",
             "--timeout", "30", "-q", spec], timeout=1800)
    if r.returncode != 0:
        pytest.skip(f"pip could not install {spec} into {VENV}: {last_line(r)}")


def tool_python(*specs):
    """The venv's python with each (spec, module) installed and importable."""
    py = venv_python()
    for spec, module in specs:
        pip_install(py, spec, module)
        r = run([py, "-c", f"import {module}"], timeout=120)
        assert r.returncode == 0, f"{spec} installed but does not import: {r.stderr[-2000:]}"
    return py
