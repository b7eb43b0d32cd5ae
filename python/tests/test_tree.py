# SPDX-License-Identifier: MIT
"""The tracked tree (git ls-files) says what the code does, not how it came to
be: no line names a working period, an issue by number or a compound ordinal
(WORDS).  pytest's fixture scope of that name (its API) is the one allowed use."""

import os
import re
import shutil
import subprocess

import pytest

from conftest import REPO

# The words, and the examples below, spelled so that this file does not
# match them itself.
WORDS = re.compile(r"\bsessio[n]s?\b|issu[e] [0-9]+|twent[y]-|thirt[y]-|fort[y]-", re.I)
ALLOWED = 'scope="session"'
HITS = ["the Thirt" + "y-first run", "see Issu" + "e 15", "in this sessio" + "n", "two sessio" + "ns"]
MISSES = ["sessionless", "an issue tracker", "issue #15", "twenty", "forty two"]


def tracked_files():
    if not shutil.which("git") or not os.path.exists(os.path.join(REPO, ".git")):
        pytest.skip("not a git checkout")
    out = subprocess.run(["git", "-C", REPO, "ls-files", "-z"], check=True, capture_output=True).stdout
    return [p for p in out.decode().split("\0") if p]


def offending_lines(path):
    """'path:line: text' for each line of path with one of the words."""
    try:
        with open(os.path.join(REPO, path), encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
    except (IsADirectoryError, FileNotFoundError):  # a submodule, a deleted file
        return []
    return [f"{path}:{i}: {line.strip()}" for i, line in enumerate(lines, 1)
            if WORDS.search(line.replace(ALLOWED, ""))]


def test_words_match_what_they_should():
    assert all(WORDS.search(text) for text in HITS), HITS
    assert not any(WORDS.search(text) for text in MISSES), MISSES
    assert not WORDS.search('@pytest.fixture(scope="session")'.replace(ALLOWED, ""))


def test_no_development_process_words():
    found = [hit for path in tracked_files() for hit in offending_lines(path)]
    assert not found, "lines naming how the code came to be:\n" + "\n".join(found)
