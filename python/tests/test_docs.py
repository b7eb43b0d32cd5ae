# SPDX-License-Identifier: MIT
"""Every example in README.md and docs/*.md runs as written, and the facts the
header and docs/conventions.md both state agree with the code.

Fenced blocks (docs/tests.md states the rules):
  ```sh      run with `bash -e` in a scratch folder of the document
  ```c       compiled against the build and run
  ```python  run with this tree's package
  ```text    output shown to the reader: never run
A comment `<!-- not run: REASON -->` on the line right before a block exempts
it; REASON must not be empty.  Any other language is an error, so that no
example escapes by its label.

Each document gets one scratch folder, shared by its blocks in order, holding
the build's program on PATH, `pkg-config brdffit` for the build tree, the MERL
tables below, and `../shared` (a link to the data folder)."""

import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import CLI, HAVE_SHARED, LIBRARY, PYDIR, REPO, SHARED

TABLES = ("alum-bronze", "gold-metallic-paint2")  # the tables the docs name
RUN = ("sh", "c", "python")
NOT_RUN = ("text",)
MIN_RUN_BLOCKS = 20  # README and docs/ hold more; fewer means the harness lost some

FENCE = re.compile(r"^```(\S*)\s*$")
EXEMPT = re.compile(r"^<!--\s*not run:(.*?)-->\s*$")


def documents():
    docs = os.path.join(REPO, "docs")
    names = sorted(n for n in os.listdir(docs) if n.endswith(".md")) if os.path.isdir(docs) else []
    return ["README.md"] + [os.path.join("docs", n) for n in names]


def blocks(rel):
    """(language, first line number, code, exempt reason or None) of each fenced block."""
    with open(os.path.join(REPO, rel), encoding="utf-8") as f:
        lines = f.read().split("\n")
    out, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        lang, start = m.group(1), i + 1
        j = start
        while j < len(lines) and lines[j].rstrip() != "```":
            j += 1
        assert j < len(lines), f"{rel}:{i + 1}: the block is not closed"
        prev = lines[i - 1] if i > 0 else ""
        ex = EXEMPT.match(prev.strip())
        out.append((lang, i + 1, "\n".join(lines[start:j]) + "\n", ex.group(1).strip() if ex else None))
        i = j + 1
    return out


ALL = [(rel, b) for rel in documents() for b in blocks(rel)]


def test_blocks_are_labelled():
    """Every block says what it is, a not-run comment gives a reason, and the
    harness finds a sane number of blocks to run."""
    bad = [f"{rel}:{line}: ```{lang}" for rel, (lang, line, _, _) in ALL if lang not in RUN + NOT_RUN]
    assert not bad, "blocks of no known kind (use sh, c, python or text):\n" + "\n".join(bad)
    empty = [f"{rel}:{line}" for rel, (_, line, _, why) in ALL if why == ""]
    assert not empty, "<!-- not run: --> without a reason before:\n" + "\n".join(empty)
    for rel in documents():
        with open(os.path.join(REPO, rel), encoding="utf-8") as f:
            lines = f.read().split("\n")
        for n, line in enumerate(lines):
            if EXEMPT.match(line.strip()):
                assert n + 1 < len(lines) and FENCE.match(lines[n + 1]), \
                    f"{rel}:{n + 1}: a not-run comment not directly before a block"
    run = [b for _, b in ALL if b[0] in RUN and b[3] is None]
    assert len(run) >= MIN_RUN_BLOCKS, f"only {len(run)} runnable blocks found in {documents()}"
    readme = [b for b in blocks("README.md") if b[0] in RUN]
    assert readme[0][2].startswith("make demo") and "make test" in readme[0][2].split("\n")[1], \
        "README's first commands are `make demo` and `make test`"


def test_readme_length():
    with open(os.path.join(REPO, "README.md"), encoding="utf-8") as f:
        n = len(f.read().split("\n")) - 1
    assert n <= 300, f"README.md has {n} lines (at most 300: the rest belongs in docs/)"


# ---------------------------------------------------------------- running the blocks

needs_shared = pytest.mark.skipif(
    not HAVE_SHARED,
    reason=f"the examples read MERL tables made by {SHARED}/tools/merl-table, which is absent",
)


@pytest.fixture(scope="session")
def doc_env(tmp_path_factory, lib_path, cli):
    """The environment of every block: the build's program first on PATH, a
    pkg-config file for the build tree, the package on PYTHONPATH."""
    root = tmp_path_factory.mktemp("docs")
    pc = root / "pkgconfig"
    pc.mkdir()
    build = os.path.dirname(lib_path)
    (pc / "brdffit.pc").write_text(
        f"Name: brdffit\nDescription: the build tree\nVersion: 0\n"
        f"Libs: -L{build} -Wl,-rpath,{build} -lbrdffit\n"
        f"Libs.private: -Wl,-Bdynamic -lcminpack -lOpenCL -lm -pthread\n"
        f"Cflags: -I{os.path.join(REPO, 'include')}\n")
    bindir = root / "bin"
    bindir.mkdir()
    os.symlink(os.path.abspath(cli), bindir / "brdffit")
    paths = []
    for name in TABLES:
        r = subprocess.run([os.path.join(SHARED, "tools", "merl-table"), name],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        paths.append(r.stdout.strip())
    env = dict(os.environ)
    env.update(PATH=f"{bindir}{os.pathsep}{env.get('PATH', '')}",
               PKG_CONFIG_PATH=str(pc), PYTHONPATH=PYDIR, BRDFFIT_LIBRARY=LIBRARY,
               MPLBACKEND="Agg")
    env.pop("PKG_CONFIG_LIBDIR", None)
    return root, env, paths


@pytest.fixture(scope="session")
def scratch(doc_env):
    """One scratch folder per document, made once: its blocks run in order in it."""
    root, _, tables = doc_env
    made = {}

    def get(rel):
        if rel not in made:
            base = root / re.sub(r"\W", "_", rel)
            work = base / "work"
            work.mkdir(parents=True)
            os.symlink(os.path.abspath(SHARED), base / "shared")  # ../shared from work/
            for path in tables:
                shutil.copy(path, work / os.path.basename(path))
            made[rel] = work
        return made[rel]

    return get


def c_program(code):
    """The file a C block names in its first comment ("/* NAME.c: ...") and
    the command lines its comment gives ("./NAME ARGS"), else ./NAME."""
    m = re.match(r"\s*/\*\s*([\w-]+)\.c\b", code)
    name = m.group(1) if m else "example"
    head = code.split("*/", 1)[0]
    runs = [ln.strip(" *\t") for ln in head.split("\n") if ln.strip(" *\t").startswith(f"./{name}")]
    return name, runs or [f"./{name}"]


RUNNABLE = [pytest.param(rel, b, id=f"{rel}:{b[1]}-{b[0]}")
            for rel, b in ALL if b[0] in RUN and b[3] is None]


@needs_shared
@pytest.mark.parametrize("rel,block", RUNNABLE)
def test_example_runs(rel, block, doc_env, scratch):
    lang, line, code, _ = block
    _, env, _ = doc_env
    work = scratch(rel)
    where = f"{rel}:{line} ({lang} block)"
    if lang == "sh":
        cmds = [["bash", "-e", "-c", code]]
    elif lang == "python":
        (work / f"block{line}.py").write_text(code)
        cmds = [[sys.executable, f"block{line}.py"]]
    else:
        name, runs = c_program(code)
        (work / f"{name}.c").write_text(code)
        cc = os.environ.get("CC", "cc")
        flags = subprocess.run(["pkg-config", "--cflags", "--libs", "brdffit"], env=env,
                               capture_output=True, text=True, check=True).stdout.split()
        r = subprocess.run([cc, "-std=c11", "-Wall", "-Werror", "-o", name, f"{name}.c", *flags, "-lm"],
                           cwd=work, env=env, capture_output=True, text=True)
        assert r.returncode == 0, f"{where} does not compile:\n{r.stderr}"
        if shutil.which(os.environ.get("CXX", "c++")):  # the header promises C++ too
            r = subprocess.run([os.environ.get("CXX", "c++"), "-std=c++11", "-x", "c++", "-Wall",
                                "-Werror", "-fsyntax-only", f"{name}.c", *flags],
                               cwd=work, env=env, capture_output=True, text=True)
            assert r.returncode == 0, f"{where} does not compile as C++:\n{r.stderr}"
        cmds = [["bash", "-e", "-c", run] for run in runs]
    for cmd in cmds:
        r = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, (f"{where} failed (exit status {r.returncode}) in {work}:\n"
                                   f"--- stdout\n{r.stdout}--- stderr\n{r.stderr}")


# ---------------------------------------------------------------- one fact, one value

def read(rel):
    with open(os.path.join(REPO, rel), encoding="utf-8") as f:
        return f.read()


def define(rel, name):
    m = re.search(rf"^#define {name} +([-0-9.e]+)", read(rel), re.M)
    assert m, f"no #define {name} in {rel}"
    return float(m.group(1))


def one(pattern, text, where):
    found = set(re.findall(pattern, text, re.S))
    assert found, f"{where} does not state /{pattern}/"
    assert len(found) == 1, f"{where} states /{pattern}/ with different values: {sorted(found)}"
    return found.pop()


HEADER = os.path.join("include", "brdffit.h")
CONVENTIONS = os.path.join("docs", "conventions.md")


def test_he_floor_stated_as_in_the_kernel():
    """The He floor of a data pass: the header and docs/conventions.md state
    e^-N of K at normal incidence, N the kernel's BF_HE_ROW_FLOOR."""
    floor = define(os.path.join("kernels", "bf_he_rows.h"), "BF_HE_ROW_FLOOR")
    for rel in (HEADER, CONVENTIONS):
        text = re.sub(r"[\s*]+", " ", read(rel))  # a statement may wrap across comment lines
        n = one(r"e\^-(\d+(?:\.\d+)?) of K at normal incidence", text, rel)
        assert float(n) == floor, f"{rel} states the He floor e^-{n}; the kernel's is e^-{floor:g}"


def test_conventions_agree_with_the_code():
    """The figures the header and docs/conventions.md both state are the code's."""
    cos_floor = define(os.path.join("kernels", "bf_models.h"), "BF_COS_FLOOR")
    scale = read(os.path.join("src", "lib", "scale.c"))
    samples = read(os.path.join("src", "lib", "samples.c"))
    models = read(os.path.join("src", "lib", "models.c"))
    cutoff = float(one(r"cutoff_deg = ([0-9.]+);", samples, "src/lib/samples.c"))
    lam = one(r"dflt\[3\] = \{ ([0-9., ]+) \}", models, "src/lib/models.c")
    lam = tuple(float(x) for x in lam.split(","))
    assert re.search(r"1\.15 / 1500\.0", scale) and re.search(r"1\.66 / 1500\.0", scale)
    for rel in (HEADER, CONVENTIONS):
        text = re.sub(r"[\s*]+", " ", read(rel))
        assert float(one(r"cos ?θ? ?(?:theta )?= ([0-9.e-]+) \(5\.7e-5", text, rel)) == cos_floor, rel
        assert "(1, 1.15, 1.66) / 1500" in text, f"{rel}: the standard scale"
        assert re.search(r"1/1500 for all|\(1, 1, 1\) / 1500", text), f"{rel}: the flat scale"
        assert float(one(r"cutoff,? \(?default (\d+)", text, rel)) == cutoff, rel
        stated = one(r"(0\.\d+), (0\.\d+), (0\.\d+)\)? ?(?:um|µm)", text, rel)
        assert tuple(float(x) for x in stated) == lam, f"{rel}: He's wavelengths {stated}"
    # the models each document lists are the registry's
    names = re.findall(r'\{ *BRDFFIT_\w+, *"([a-z-]+)"', read(os.path.join("src", "lib", "registry.c")))
    assert len(names) == 11, names
    conv = read(CONVENTIONS)
    head = read(HEADER)
    for name in names:
        assert f"| {name} |" in conv, f"{CONVENTIONS}: no lobe row for {name}"
        assert re.search(rf"^ \* +{name} \[", head, re.M), f"{HEADER}: no lobe line for {name}"
