# SPDX-License-Identifier: MIT
"""README.md's Python example runs as written (on alum-bronze), and the figures
it would plot are the library's."""

import os
import re
import subprocess
import sys

from conftest import PYDIR, REPO


def readme_example():
    with open(os.path.join(REPO, "README.md")) as f:
        text = f.read()
    section = text[text.index("## Python"):]
    m = re.search(r"```python\n(.*?)```", section, re.S)
    assert m, "no python example in README.md's Python section"
    return m.group(1)


def test_readme_example_runs(tmp_path, alum_bronze, lib_path):
    code = readme_example()
    assert 'Table.read("alum-bronze.binary")' in code
    os.symlink(alum_bronze, tmp_path / "alum-bronze.binary")
    script = tmp_path / "example.py"
    # after the example: check what it computed against the library directly
    script.write_text(code + """
import numpy as np
assert fit.error > 0 and fit.params.p.size == 2
assert measured_img.shape == model_img.shape == (256, 256, 4)
assert np.array_equal(model_img, brdffit.render("cook-torrance", fit.params))
assert np.array_equal(measured_img, brdffit.render(table, lights=brdffit.default_lights()))
assert 0 < err < 1 and covered == (measured_img[..., 3] == 1).sum() > 40000
assert list(curves) == [20, 40, 60, 75]
t_o = np.radians(theta_o)
wo = np.stack([np.sin(t_o), np.zeros_like(t_o), np.cos(t_o)], axis=1)
for theta_i, (meas, mod) in curves.items():
    assert meas.shape == mod.shape == (180,)
    assert np.isfinite(mod).all() and (mod > 0).all()
    assert np.isfinite(meas).sum() > 100
    t_i = np.radians(theta_i)
    wi = np.array([-np.sin(t_i), 0.0, np.cos(t_i)])
    f = brdffit.eval("cook-torrance", fit.params, wi, wo)
    assert np.allclose(mod, np.cbrt(f.mean(axis=1)), rtol=1e-10)
print("example ok", "plotted" if plt is not None else "no matplotlib")
""")
    env = dict(os.environ, PYTHONPATH=PYDIR, BRDFFIT_LIBRARY=lib_path, MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "example ok" in r.stdout
    assert "(3, 90, 90, 180)" in r.stdout
    if "plotted" in r.stdout:
        assert (tmp_path / "incidence.png").stat().st_size > 1000
