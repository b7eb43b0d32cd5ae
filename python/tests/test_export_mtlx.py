# SPDX-License-Identifier: MIT
"""brdffit export --format mtlx: the MaterialX document of a fit of model
openpbr, read two ways: as XML here (the document's layout, its element
names, the inputs against the fit record's values to 9 significant digits),
and by MaterialX's own library (the `materialx` package): it loads the file
with its standard libraries, validates it, finds the open_pbr_surface
nodedef and the record's values, and its GLSL and OSL shader generators
make code for the material.  MaterialX is pip-installed into the tools'
virtual environment (toolvenv.py); without pip or the network those tests
are skipped, saying so.  Then the program's refusals: fits of other models,
failed fits, values outside OpenPBR's ranges, names that are not file names;
and the batch's .mtlx files and page section."""

import html
import json
import os
import re
import subprocess
import xml.etree.ElementTree as ET

import pytest

from conftest import CLI
from toolvenv import run as _run, tool_python

MATERIALX = "materialx==1.39.5"
PARAM_NAMES = ["base_metalness", "specular_roughness", "specular_ior", "specular_weight"]
# the inputs written, in order: (name, type, where the value comes from)
INPUTS = [("base_weight", "float", 1.0), ("base_color", "color3", "d"),
          ("base_metalness", "float", 0), ("base_diffuse_roughness", "float", 0.0),
          ("specular_weight", "float", 3), ("specular_color", "color3", "s"),
          ("specular_roughness", "float", 1), ("specular_ior", "float", 2)]
# inputs left out: their nodedef defaults are what the file means (0: the layer is off)
OFF = ["coat_weight", "fuzz_weight", "transmission_weight", "subsurface_weight",
       "thin_film_weight", "emission_luminance"]
NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def record(material, model, d, s, p, status="ok"):
    """A fit record as `brdffit fit --json` writes it (the fields export reads)."""
    failed = status not in ("ok", "limit")
    return {"kind": "fit", "material": material, "file": None, "size": None, "hash": None,
            "settings": {"version": "1.0.0", "metric": "ngan-l2", "scale": "standard",
                         "cutoff_deg": 80, "starts": 0},
            "model": model, "param_names": PARAM_NAMES,
            "colour_names": ["base_color", "specular_color"],
            "status": status, "status_code": 18 if failed else 0,
            "message": "the optimiser could not produce a result" if failed else "",
            "d": None if failed else d, "s": None if failed else s, "p": None if failed else p,
            "lambda_um": None, "error": None if failed else 0.05,
            "flags": ["limit"] if status == "limit" else []}


PLASTIC = record("red-plastic", "openpbr", [0.8, 0.05, 0.0125], [1, 1, 1],
                 [0.0, 0.45, 1.5, 1.0])
METAL = record("warm-metal", "openpbr", [0.912345678901, 0.70123, 0.3],
               [0.95, 0.812345678901234, 0.6], [0.85, 0.2345678, 2.25, 0.75], status="limit")
GLTF = record("red-plastic", "gltf", [0.8, 0.05, 0.0125], [1, 1, 1], [0.0, 0.45, 1.5, 1.0])


def write_jsonl(path, records):
    path.write_text("".join(json.dumps(r) + "\n" for r in records))
    return str(path)


def export(tmp_path, *args, out="out", fmt="mtlx"):
    return subprocess.run([CLI, "export", *args, "--format", fmt, "--out", str(tmp_path / out)],
                          capture_output=True, text=True, timeout=60)


def nine_digits(a, b):
    return abs(a - b) <= 5e-9 * max(abs(a), abs(b), 1e-300)


def want_value(rec, source):
    """The value an input must hold: the record's colour or parameter, or a constant."""
    if source in ("d", "s"):
        return rec[source]
    return rec["p"][source] if isinstance(source, int) else source


def check_inputs(inputs, rec):
    """inputs: {name: (type, value text)} of the node, the record's to 9 digits."""
    assert list(inputs) == [n for n, _, _ in INPUTS], list(inputs)
    for name, typ, source in INPUTS:
        got_type, text = inputs[name]
        assert got_type == typ, (name, got_type)
        want = want_value(rec, source)
        if typ == "color3":
            got = [float(x) for x in text.split(",")]
            assert re.fullmatch(r"[^,]+, [^,]+, [^,]+", text), text
            assert len(got) == 3 and all(nine_digits(g, w) for g, w in zip(got, want)), (name, text)
        else:
            assert nine_digits(float(text), want), (name, text, want)


def check_file(path, rec):
    """The document: <materialx version 1.39 colorspace lin_rec709> holding an
    open_pbr_surface node with the record's inputs and a surfacematerial using
    it; names MaterialX takes, the record's name in the material's doc."""
    text = path.read_text(encoding="utf-8")
    assert text.startswith('<?xml version="1.0" encoding="UTF-8"?>\n')
    root = ET.fromstring(text.encode("utf-8"))
    assert root.tag == "materialx"
    assert root.attrib == {"version": "1.39", "colorspace": "lin_rec709"}
    shader, material = list(root)
    assert shader.tag == "open_pbr_surface" and material.tag == "surfacematerial"
    assert shader.get("type") == "surfaceshader"
    assert shader.get("nodedef") == "ND_open_pbr_surface_surfaceshader"
    assert all(i.tag == "input" for i in shader)
    check_inputs({i.get("name"): (i.get("type"), i.get("value")) for i in shader}, rec)
    assert material.get("type") == "material" and material.get("nodedef") == "ND_surfacematerial"
    assert material.get("doc") == f"{rec['material']}-{rec['model']}"
    (use,) = list(material)
    assert use.attrib == {"name": "surfaceshader", "type": "surfaceshader",
                          "nodename": shader.get("name")}
    for name in (shader.get("name"), material.get("name")):
        assert NAME.match(name), name
    assert shader.get("name") != material.get("name")
    return root


def shape(e):
    """An element's tag, attributes and children: what it says, not its indentation."""
    return e.tag, e.attrib, [shape(c) for c in e]


def out_file(tmp_path, rec, out="out"):
    return tmp_path / out / f"{rec['material']}-{rec['model']}.mtlx"


# ------------------------------------------------------------------ the file itself

def test_files_of_two_fits(tmp_path):
    fits = write_jsonl(tmp_path / "fits.jsonl", [PLASTIC, METAL])
    r = export(tmp_path, fits)
    assert r.returncode == 0, r.stderr
    paths = [str(out_file(tmp_path, PLASTIC)), str(out_file(tmp_path, METAL))]
    assert r.stdout.split("\n")[:-1] == paths
    assert sorted(os.listdir(tmp_path / "out")) == sorted(os.path.basename(p) for p in paths)
    root = check_file(out_file(tmp_path, PLASTIC), PLASTIC)
    assert root[0].get("name") == "SR_red_plastic_openpbr"
    assert root[1].get("name") == "red_plastic_openpbr"
    check_file(out_file(tmp_path, METAL), METAL)


@pytest.mark.parametrize("name", ['m "quoted" <&> \\ tab\there \u00e9', "9 lives: a.b",
                                  "line\nfeed\rreturn"])
def test_a_name_is_escaped_and_made_an_element_name(tmp_path, name):
    rec = dict(PLASTIC, material=name)
    r = export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [rec]))
    assert r.returncode == 0, r.stderr
    check_file(out_file(tmp_path, rec), rec)  # doc holds the name exactly


def test_a_batch_fits_tsv(tmp_path):
    """A batch's fits.tsv (columns found by name; '-' where a fit has no value)."""
    head = ("material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\tp3\terror\tstatus"
            "\tstatus_code\tmessage\n")

    def row(rec, status="ok", code=0, message=""):
        vals = rec["d"] + rec["s"] + rec["p"] if status in ("ok", "limit") else ["-"] * 10
        return "\t".join([rec["material"], rec["model"], *map(str, vals), "0.05", status,
                          str(code), message]) + "\n"
    tsv = tmp_path / "fits.tsv"
    tsv.write_text(head + row(PLASTIC) + row(METAL, "limit") + row(GLTF)
                   + row(dict(PLASTIC, material="broken"), "the fit failed", 18, "no minimum"))
    r = export(tmp_path, str(tsv))
    assert r.returncode == 0, r.stderr
    check_file(out_file(tmp_path, PLASTIC), PLASTIC)
    check_file(out_file(tmp_path, METAL), METAL)
    assert "line 5: broken, openpbr: not fitted (no minimum); skipped" in r.stderr, r.stderr
    assert "gltf: not an OpenPBR model; fit --model openpbr (1 fit skipped)" in r.stderr
    assert len(os.listdir(tmp_path / "out")) == 2


# ------------------------------------------------------------------ what is skipped or refused

def test_other_models_and_failed_fits_are_skipped(tmp_path):
    failed = record("broken", "openpbr", None, None, None, status="the fit failed")
    r = export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [GLTF, GLTF, failed, METAL]))
    assert r.returncode == 0, r.stderr
    assert r.stdout == str(out_file(tmp_path, METAL)) + "\n"
    lines = r.stderr.splitlines()
    assert [ln for ln in lines if "gltf" in ln] == [
        "brdffit: gltf: not an OpenPBR model; fit --model openpbr (2 fits skipped)"]
    assert any("line 3: broken, openpbr: not fitted" in ln and ln.endswith("skipped")
               for ln in lines), r.stderr
    # nothing to write: exit 1, no directory made
    r = export(tmp_path, write_jsonl(tmp_path / "g.jsonl", [GLTF, failed]), out="none")
    assert r.returncode == 1, r.stderr
    assert "nothing written: no fit of model openpbr to export" in r.stderr, r.stderr
    assert not (tmp_path / "none").exists()
    # and the glTF export skips openpbr fits the same way
    r = export(tmp_path, write_jsonl(tmp_path / "o.jsonl", [METAL]), out="g", fmt="gltf")
    assert r.returncode == 1 and "openpbr: not a glTF model" in r.stderr, r.stderr


@pytest.mark.parametrize("change, says", [
    ({"d": [1.25, 0.5, 0.5]}, "base_color r = 1.25 is not in [0, 1]"),
    ({"d": [0.5, -0.01, 0.5]}, "base_color g = -0.01 is not in [0, 1]"),
    ({"s": [0.5, 0.5, 1.5]}, "specular_color b = 1.5 is not in [0, 1]"),
    ({"p": [1.5, 0.5, 1.5, 1]}, "base_metalness = 1.5 is not in [0, 1]"),
    ({"p": [0.5, -2, 1.5, 1]}, "specular_roughness = -2 is not in [0, 1]"),
    ({"p": [0.5, 0.5, 0.8, 1]}, "specular_ior = 0.8 is not a number >= 1"),
    ({"p": [0.5, 0.5, 1.5, -0.25]}, "specular_weight = -0.25 is not a number >= 0"),
    ({"p": [0.5, 0.5, 1e999, 1]}, "not a record"),          # inf in JSON: not a record
    ({"p": [0.5, 0.5, 1.5]}, "no parameters"),
])
def test_values_outside_openpbr_are_refused(tmp_path, change, says):
    bad = dict(PLASTIC, material="bad", **change)
    fits = write_jsonl(tmp_path / "fits.jsonl", [METAL, bad])
    r = export(tmp_path, fits)
    assert r.returncode == 1, r.stderr
    assert f"{fits}: line 2: " in r.stderr and says in r.stderr, r.stderr
    assert os.listdir(tmp_path / "out") == ["warm-metal-openpbr.mtlx"]


def test_nonfinite_values_of_a_tsv_are_refused(tmp_path):
    tsv = tmp_path / "fits.tsv"
    tsv.write_text("material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\tp3\n"
                   "a\topenpbr\t0.5\t0.5\t0.5\t1\t1\t1\t0\tnan\t1.5\t1\n"
                   "b\topenpbr\t0.5\t0.5\t0.5\t1\t1\t1\t0\t0.5\tinf\t1\n")
    r = export(tmp_path, str(tsv))
    assert r.returncode == 1 and "nothing written" in r.stderr, r.stderr
    assert f"{tsv}: line 2: a, openpbr: specular_roughness = nan is not in [0, 1]" in r.stderr
    assert f"{tsv}: line 3: b, openpbr: specular_ior = inf is not a number >= 1" in r.stderr


@pytest.mark.parametrize("name", ["", ".", "..", "a/b", "../escape"])
def test_names_that_are_not_one_path_component(tmp_path, name):
    r = export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [dict(PLASTIC, material=name)]))
    assert r.returncode == 1, r.stderr
    assert "line 1: " in r.stderr and "is not a file name" in r.stderr, r.stderr
    assert not (tmp_path / "out").exists() and not (tmp_path / "escape-openpbr.mtlx").exists()


def test_usage(tmp_path):
    fits = write_jsonl(tmp_path / "fits.jsonl", [PLASTIC])
    r = export(tmp_path, fits, fmt="usd")
    assert r.returncode == 2 and "unknown format 'usd' (formats: gltf, mtlx, mitsuba)" in r.stderr
    help_text = subprocess.run([CLI, "help", "export"], capture_output=True, text=True)
    assert help_text.returncode == 0 and "--format mtlx" in help_text.stdout


# ------------------------------------------------------------------ MaterialX's own library

@pytest.fixture(scope="session")
def materialx_python():
    return tool_python((MATERIALX, "MaterialX"))


MATERIALX_SCRIPT = r"""
import json, os, sys
import MaterialX as mx
from MaterialX import PyMaterialXGenShader as gen
from MaterialX import PyMaterialXGenGlsl as glsl
from MaterialX import PyMaterialXGenOsl as osl

search = mx.FileSearchPath(os.path.dirname(mx.__file__))   # the package's libraries/
stdlib = mx.createDocument()
mx.loadLibraries(mx.getDefaultDataLibraryFolders(), search, stdlib)


def load(path=None, text=None):
    doc = mx.createDocument()
    if path:
        mx.readFromXmlFile(doc, path)
    else:
        mx.readFromXmlString(doc, text)
    doc.importLibrary(stdlib)
    return doc


def generate(generator, material):
    g = generator.create()
    ctx = gen.GenContext(g)
    ctx.registerSourceCodeSearchPath(search)
    return g.generate(material.getName(), material, ctx).getSourceCode(gen.PIXEL_STAGE)


def describe(doc, generate_code):
    valid, message = doc.validate()
    out = {"valid": valid, "message": message, "version": doc.getVersionString(),
           "colorspace": doc.getColorSpace()}
    nodes = [n for n in doc.getNodes() if n.getCategory() == "open_pbr_surface"]
    materials = doc.getMaterialNodes()
    out["counts"] = [len(nodes), len(materials)]
    if len(nodes) != 1 or len(materials) != 1:
        return out
    node, material = nodes[0], materials[0]
    nodedef = node.getNodeDef()
    out["node"] = node.getName()
    out["material"] = material.getName()
    out["doc"] = material.getDocString()
    out["nodedef"] = nodedef.getName() if nodedef else None
    out["shaders"] = [s.getName() for s in mx.getShaderNodes(material)]
    out["inputs"] = {i.getName(): [i.getType(), i.getValueString()] for i in node.getInputs()}
    out["floats"] = {i.getName(): (list(i.getValue().asTuple()) if i.getType() == "color3"
                                   else i.getValue()) for i in node.getInputs()}
    if nodedef:
        out["off"] = {n: nodedef.getActiveInput(n).getValue() for n in json.loads(sys.argv[2])}
    if generate_code:
        out["glsl"] = generate(glsl.GlslShaderGenerator, material)
        out["osl"] = generate(osl.OslShaderGenerator, material)
    return out


path = sys.argv[1]
text = open(path, encoding="utf-8").read()
result = {"file": describe(load(path=path), True)}
# the same document with an input MaterialX does not know must not validate
result["altered"] = describe(load(text=text.replace('"base_color"', '"base_colour"')), False)
if len(sys.argv) > 3:   # elements to paste, put in a <materialx> of their own
    pasted = '<materialx version="1.39" colorspace="lin_rec709">' + sys.argv[3] + "</materialx>"
    result["pasted"] = describe(load(text=pasted), False)
print("MTLX " + json.dumps(result))
"""


def materialx_check(py, path, rec, tmp_path, pasted=None):
    """MaterialX loads the file with its standard libraries, validates it, sees
    the record's values under ND_open_pbr_surface_surfaceshader, the layers left
    out at weight 0, and generates GLSL and OSL for the material."""
    script = tmp_path / "materialx_check.py"
    script.write_text(MATERIALX_SCRIPT)
    args = [py, str(script), str(path), json.dumps(OFF)] + ([pasted] if pasted else [])
    r = _run(args, timeout=300)
    assert r.returncode == 0, r.stderr[-4000:]
    (line,) = [ln for ln in r.stdout.splitlines() if ln.startswith("MTLX ")]
    got = json.loads(line[5:])
    f = got["file"]
    assert f["valid"] is True, f["message"]
    assert f["version"] == "1.39" and f["colorspace"] == "lin_rec709"
    assert f["counts"] == [1, 1]
    assert f["nodedef"] == "ND_open_pbr_surface_surfaceshader"
    assert f["shaders"] == [f["node"]]
    assert f["doc"] == f"{rec['material']}-{rec['model']}"
    check_inputs({k: tuple(v) for k, v in f["inputs"].items()}, rec)
    for name, typ, source in INPUTS:   # as MaterialX holds them (32-bit floats)
        want = want_value(rec, source)
        got_v = f["floats"][name]
        for g, w in zip(got_v if typ == "color3" else [got_v],
                        want if typ == "color3" else [want]):
            assert abs(g - w) <= 1e-6 * max(1, abs(w)), (name, g, w)
    assert f["off"] == {n: 0 for n in OFF}
    for lang in ("glsl", "osl"):   # the node's function, called with the node's inputs
        code = f[lang]
        assert len(code) > 1000, lang
        assert "NG_open_pbr_surface_surfaceshader" in code, lang
        assert re.search(r"\bSR_\w*_base_color\b", code), lang
    d = rec["d"]
    assert re.search(rf"\bSR_\w*_base_color = vec3\({d[0]:.6f}, {d[1]:.6f}, {d[2]:.6f}\);",
                     f["glsl"]), "the GLSL's base_color uniform is not the record's"
    a = got["altered"]
    assert a["valid"] is False and "base_colour" in a["message"], a["message"]
    if pasted:
        p = got["pasted"]
        assert p["valid"] is True, p["message"]
        assert p["inputs"] == f["inputs"] and p["node"] == f["node"]
    return got


@pytest.mark.parametrize("rec", [PLASTIC, METAL, dict(PLASTIC, material='9 "odd" <&>\tname')],
                         ids=["dielectric", "metal", "odd-name"])
def test_materialx_validates_the_file_and_generates_shaders(tmp_path, materialx_python, rec):
    assert export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [rec])).returncode == 0
    materialx_check(materialx_python, out_file(tmp_path, rec), rec, tmp_path)


# ------------------------------------------------------------------ real fits

@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """`brdffit batch --demo --model ggx,gltf,openpbr`: the page and files."""
    out = tmp_path_factory.mktemp("batch") / "batch"
    r = subprocess.run([CLI, "batch", "--demo", "--model", "ggx,gltf,openpbr", "--no-render",
                        "--no-plot", "--quiet", "--out", str(out)],
                       capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stderr
    (mdir,) = [d for d in out.iterdir() if d.is_dir()]
    return out, mdir


def test_batch_writes_the_mtlx_beside_the_page(batch):
    """The batch writes the openpbr fit's .mtlx beside the material's page, the
    page shows its Error beside GGX's and glTF's, and the elements to paste,
    equal to the file's."""
    out, mdir = batch
    params = json.loads((mdir / "params.json").read_text())
    fits = {f["model"]: f for f in params["fits"]}
    assert set(fits) == {"ggx", "gltf", "openpbr"}
    rec = fits["openpbr"]
    path = mdir / f"{rec['material']}-openpbr.mtlx"
    root = check_file(path, rec)
    assert sorted(p.name for p in mdir.glob("*.mtlx")) == [path.name]
    page = (mdir / "index.html").read_text()
    assert "For a renderer: OpenPBR Surface in MaterialX" in page
    assert f'href="{path.name}"' in page
    pre = [html.unescape(t) for t in re.findall(r"<pre>(.*?)</pre>", page, re.S)]
    (block,) = [t for t in pre if "<open_pbr_surface" in t]
    pasted = ET.fromstring("<materialx>" + block + "</materialx>")
    assert [shape(e) for e in pasted] == [shape(e) for e in root]
    # the Errors of the three models, each the fitted row of its model's
    # group (headed by the model's title) in the page's table
    groups = re.findall(r"<tbody>(.*?)</tbody>", page, re.S)
    for model, title in (("ggx", "GGX"), ("gltf", "glTF 2.0"), ("openpbr", "OpenPBR Surface")):
        (group,) = [g for g in groups if re.search(f'<th class="name[^"]*">{re.escape(title)}<', g)]
        (row,) = re.findall(r'<td class="name">fitted</td>(.*?)</tr>', group, re.S)
        assert f"<td>{fits[model]['error']:.4g}" in row or \
            f'<td class="best">{fits[model]["error"]:.4g}' in row, (model, row)


def test_batch_mtlx_in_materialx(tmp_path, materialx_python, batch):
    out, mdir = batch
    params = json.loads((mdir / "params.json").read_text())
    (rec,) = [f for f in params["fits"] if f["model"] == "openpbr"]
    page = (mdir / "index.html").read_text()
    pre = [html.unescape(t) for t in re.findall(r"<pre>(.*?)</pre>", page, re.S)]
    (block,) = [t for t in pre if "<open_pbr_surface" in t]
    materialx_check(materialx_python, mdir / f"{rec['material']}-openpbr.mtlx", rec, tmp_path,
                    pasted=block)


def test_export_of_a_batch_fits_tsv_equals_the_batch_file(tmp_path, batch):
    out, mdir = batch
    e = export(tmp_path, str(out / "fits.tsv"))
    assert e.returncode == 0, e.stderr
    assert "ggx: not an OpenPBR model" in e.stderr and "gltf: not an OpenPBR model" in e.stderr
    (written,) = os.listdir(tmp_path / "out")
    # the same text; each number the same to its 9 significant digits but the
    # last (fits.tsv holds 10, so export rounds a second time)
    mine, theirs = ((d / written).read_text() for d in (tmp_path / "out", mdir))
    number = r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?"
    assert re.sub(number, "#", mine) == re.sub(number, "#", theirs)
    for a, b in zip(re.findall(number, mine), re.findall(number, theirs)):
        assert abs(float(a) - float(b)) <= 1e-8 * abs(float(b)), (a, b)

