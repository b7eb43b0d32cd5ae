# SPDX-License-Identifier: MIT
"""README.md's Python example computes what it says (the library's own
figures), and without matplotlib it says why it drew nothing.
(python/tests/test_docs.py runs every example; this one also checks them.)"""

import os
import re
import subprocess
import sys

import pytest

from conftest import PYDIR, REPO


def readme_example():
    with open(os.path.join(REPO, "README.md")) as f:
        text = f.read()
    section = text[text.index("**From Python**"):]
    m = re.search(r"```python\n(.*?)```", section, re.S)
    assert m, "no python example after README.md's **From Python**"
    return m.group(1)


CHECKS = """
import numpy as np
assert fit.error > 0 and fit.params.p.size == 2
assert measured_img.shape == model_img.shape == (256, 256, 4)
assert np.array_equal(model_img, brdffit.render("ggx", fit.params))
assert np.array_equal(measured_img, brdffit.render(table, lights=brdffit.default_lights()))
assert 0 < err < 1 and covered == (measured_img[..., 3] == 1).sum() > 40000
assert theta_o.shape == (180,) and measured.shape == model.shape == (180, 3)
t_o = np.radians(theta_o)
wo_ = np.stack([np.sin(t_o), np.zeros_like(t_o), np.cos(t_o)], axis=1)
wi_ = np.array([-np.sin(np.radians(60)), 0.0, np.cos(np.radians(60))])
assert np.allclose(model, brdffit.eval("ggx", fit.params, wi_, wo_), rtol=1e-12)
assert np.isfinite(measured).sum() > 300
print("example ok", "plotted" if plt is not None else "not plotted")
"""


def run_example(tmp_path, alum_bronze, lib_path, hide_matplotlib):
    (tmp_path / "merl").mkdir()
    os.symlink(alum_bronze, tmp_path / "merl" / "alum-bronze.binary")
    code = readme_example()
    assert 'Table.read("merl/alum-bronze.binary")' in code
    (tmp_path / "example.py").write_text(code + CHECKS)
    path = [PYDIR]
    if hide_matplotlib:  # a matplotlib that cannot be imported, found first
        fake = tmp_path / "no-mpl" / "matplotlib"
        fake.mkdir(parents=True)
        (fake / "__init__.py").write_text("raise ImportError('matplotlib hidden by the test')\n")
        path.insert(0, str(fake.parent))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(path), BRDFFIT_LIBRARY=lib_path,
               MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, "example.py"], cwd=tmp_path, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "example ok" in r.stdout
    return r.stdout


def test_readme_example_without_matplotlib(tmp_path, alum_bronze, lib_path):
    out = run_example(tmp_path, alum_bronze, lib_path, hide_matplotlib=True)
    assert "not plotted" in out
    assert "matplotlib is not installed" in out and "incidence.png not written" in out
    assert not (tmp_path / "incidence.png").exists()


def test_readme_example_plots(tmp_path, alum_bronze, lib_path):
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        pytest.skip("matplotlib is not installed here: the plotting branch cannot run")
    out = run_example(tmp_path, alum_bronze, lib_path, hide_matplotlib=False)
    assert "example ok plotted" in out
    assert (tmp_path / "incidence.png").stat().st_size > 1000
