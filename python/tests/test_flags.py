# SPDX-License-Identifier: MIT
"""The fit result's named bits: AtBound and FitFlag equal the header's
brdffit_at_bound and brdffit_fit_flag name for name and value for value,
at_bound_names names what `brdffit fit --json` names, the raw ints stay."""

import json
import re
import subprocess

from test_library import header_text

# Ashikhmin-Shirley at dark-blue-paint's published parameters with d_r = d_g = 0
# (as the fidelity suite's zero_d case): the fit comes back to d_r = d_g = 0 exactly
D0 = [0.0, 0.0, 0.0229, 0.217, 0.159, 0.111, 0.122, 16.9]


def header_bits(name):
    """{NAME: value} of an enum of bit values (1u << k, 7u) in the header."""
    m = re.search(r"typedef enum %s \{(.*?)\} %s;" % (name, name), header_text(), re.S)
    assert m, f"enum {name} not in the header"
    out = {}
    for line in re.sub(r"/\*.*?\*/", "", m.group(1), flags=re.S).split(","):
        line = line.strip()
        if not line:
            continue
        mm = re.fullmatch(r"(\w+)\s*=\s*(\d+)u(?:\s*<<\s*(\d+))?", line)
        assert mm, f"cannot read enum member {line!r}"
        out[mm.group(1)] = int(mm.group(2)) << int(mm.group(3) or 0)
    return out


def test_named_bits_are_the_headers(brdffit):
    c = header_bits("brdffit_at_bound")
    assert len(c) == 11 and c["BRDFFIT_AT_BOUND_S_B"] == 1 << 14
    assert {"BRDFFIT_AT_BOUND_" + k: int(v) for k, v in brdffit.AtBound.__members__.items()} == c
    c = header_bits("brdffit_fit_flag")
    assert {"BRDFFIT_FIT_" + k: int(v) for k, v in brdffit.FitFlag.__members__.items()} == c
    A = brdffit.AtBound
    assert A.LOBE == A.P0 | A.P1 | A.P2 | A.P3


def result(brdffit, model, at_bound=0, flags=0):
    return brdffit.FitResult(
        model=brdffit.model(model), params=None, error=0.0, status=brdffit.Status.OK,
        cminpack_info=1, iterations=1, passes=1, seconds=0.0, seconds_solver=0.0,
        seconds_passes=0.0, samples=1, backend="host",
        at_bound=brdffit.AtBound(at_bound), flags=brdffit.FitFlag(flags))


def test_at_bound_names(brdffit):
    A = brdffit.AtBound
    assert result(brdffit, "cook-torrance").at_bound_names == []
    r = result(brdffit, "cook-torrance", A.P1 | A.D_G | A.S_R | A.S_B)
    assert r.at_bound_names == ["m", "d_g", "s_r", "s_b"]
    assert int(r.at_bound) == (1 << 1) | (1 << 9) | (1 << 12) | (1 << 14)
    he = brdffit.model("he").params
    assert result(brdffit, "he", A.P0 | A.P2).at_bound_names == [he[0].name, he[2].name]
    r = result(brdffit, "gltf-ext", A.P3 | A.D_R)
    assert r.at_bound_names == ["specular", "base_color_r"]
    assert result(brdffit, "ward", 0, brdffit.FitFlag.LIMIT).converged is False


def test_a_fit_on_a_bound_names_what_the_program_names(brdffit, ctx, cli, tmp_path):
    table = brdffit.Table.from_model("ashikhmin-shirley", D0)
    path = tmp_path / "d0.binary"
    table.write(path)
    r = brdffit.fit(ctx, brdffit.Samples(table), "ashikhmin-shirley")
    out = subprocess.run([cli, "fit", str(path), "--json", "--model", "ashikhmin-shirley"],
                         check=True, capture_output=True, text=True).stdout
    [rec] = [json.loads(line) for line in out.splitlines() if line.strip()]
    assert isinstance(r.at_bound, brdffit.AtBound) and isinstance(r.at_bound, int)
    assert r.at_bound & brdffit.AtBound.D_R and r.at_bound & brdffit.AtBound.D_G
    assert not r.at_bound & (brdffit.AtBound.D_B | brdffit.AtBound.LOBE)
    assert r.at_bound_names == rec["at_bound"] == ["d_r", "d_g"]
    assert r.flags == brdffit.FitFlag(0) == 0 and rec["flags"] == []


def test_a_fit_stopped_on_its_limit_is_flagged(brdffit, ctx, alum_bronze):
    s = brdffit.Samples(brdffit.Table.read(alum_bronze))
    r = brdffit.fit(ctx, s, "cook-torrance", starts=1, max_evals=2)
    assert r.flags == brdffit.FitFlag.LIMIT and int(r.flags) == 1
    assert r.cminpack_info == 5 and not r.converged
