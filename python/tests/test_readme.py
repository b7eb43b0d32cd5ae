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
for theta_i, (meas, mod) in curves.items():
    assert meas.shape == mod.shape == (180,)
    assert np.isfinite(mod).all() and (mod > 0).all()
    assert np.isfinite(meas).sum() > 100
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
