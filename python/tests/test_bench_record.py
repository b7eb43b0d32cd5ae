# SPDX-License-Identifier: MIT
"""bench/record, the one writer of bench/results.tsv's rows (the benchmark's
C code and bench/python run it): its header, its six fields, what it refuses."""

import os
import re
import subprocess

from conftest import REPO

RECORD = os.path.join(REPO, "bench", "record")
HEADER = ["date", "commit", "machine", "benchmark", "metric", "value"]


def record(*args):
    return subprocess.run([RECORD, *args], capture_output=True, text=True)


def rows(path):
    with open(path) as f:
        return [line.rstrip("\n").split("\t") for line in f]


def test_header_then_one_row_a_figure(tmp_path):
    out = str(tmp_path / "results.tsv")
    assert record("fit/ggx/alum-bronze", "fit seconds", "0.0187", out).returncode == 0
    assert record("pass/he/alum-bronze/fit", "full/stream ratio", "3.9e-1", out).returncode == 0
    got = rows(out)
    assert got[0] == HEADER and len(got) == 3
    for row in got[1:]:
        assert len(row) == 6
        assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", row[0])
        assert re.fullmatch(r"[0-9a-f]{12}(-dirty)?|unknown", row[1])
        assert row[2]
    assert got[1][3:] == ["fit/ggx/alum-bronze", "fit seconds", "0.0187"]
    assert got[2][3:] == ["pass/he/alum-bronze/fit", "full/stream ratio", "3.9e-1"]


def test_tabs_and_newlines_in_names_become_spaces(tmp_path):
    out = str(tmp_path / "results.tsv")
    assert record("a\tb", "c\nd", "1", out).returncode == 0
    assert rows(out)[1][3:] == ["a b", "c d", "1"]


def test_refuses_what_is_not_a_figure(tmp_path):
    out = str(tmp_path / "results.tsv")
    for args in (["fit/x", "seconds", "nan", out], ["fit/x", "seconds", "", out],
                 ["fit/x", "seconds"], ["a", "b", "1", out, "extra"]):
        done = record(*args)
        assert done.returncode == 2, args
        assert done.stderr
    assert not os.path.exists(out)
