# SPDX-License-Identifier: MIT
"""brdffit export --format gltf: the .gltf file of a fit of model gltf or
gltf-ext, read back three ways: as JSON and bytes here (the buffer's layout,
the sphere's vertices, the material's values against the fit record's), by
pygltflib (it parses and validates the file), and by Blender's glTF importer
(bpy), whose Principled BSDF must show the file's values.  pygltflib and bpy
are pip-installed into the tools' virtual environment (toolvenv.py); without
pip or the network the tests that need them are skipped, saying so.  Then the program's refusals:
fits of other models, failed fits, values outside glTF's ranges, names that
are not file names, formats it does not write."""

import base64
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import CLI, REPO
from toolvenv import last_line as _last_line, run as _run, tool_python

EXTENSIONS = ["KHR_materials_ior", "KHR_materials_specular"]
PARAM_NAMES = ["metallic", "roughness", "ior", "specular"]
BPY = "bpy==5.0.1"   # a wheel for Python 3.11 (cp311)

# glTF 2.0: componentType -> (bytes, numpy dtype), type -> components
COMPONENT = {5126: (4, "<f4"), 5123: (2, "<u2"), 5125: (4, "<u4")}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}


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


CORE = record("red-plastic", "gltf", [0.8, 0.05, 0.0125], [1, 1, 1], [0.0, 0.45, 1.5, 1.0])
EXT = record("warm-metal", "gltf-ext", [0.912345678901, 0.70123, 0.3], [0.95, 0.8, 0.6],
             [0.85, 0.2345678, 2.25, 0.75], status="limit")


def write_jsonl(path, records):
    path.write_text("".join(json.dumps(r) + "\n" for r in records))
    return str(path)


def export(tmp_path, *args, out="out"):
    return subprocess.run([CLI, "export", *args, "--out", str(tmp_path / out)],
                          capture_output=True, text=True, timeout=60)


def close(a, b, rel=1e-8):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def program_version():
    return subprocess.run([CLI, "--version"], capture_output=True, text=True,
                          check=True).stdout.split()[1]


# ------------------------------------------------------------------ reading a .gltf here

def buffer_bytes(doc):
    (buf,) = doc["buffers"]
    prefix = "data:application/octet-stream;base64,"
    assert buf["uri"].startswith(prefix), buf["uri"][:60]
    data = base64.b64decode(buf["uri"][len(prefix):], validate=True)
    assert len(data) == buf["byteLength"]
    return data


def accessor_array(doc, data, k):
    """Accessor k as a (count, ncomp) array, its view's size and alignment checked."""
    acc = doc["accessors"][k]
    view = doc["bufferViews"][acc["bufferView"]]
    size, dtype = COMPONENT[acc["componentType"]]
    ncomp = NCOMP[acc["type"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    assert start % 4 == 0 and view.get("byteOffset", 0) % 4 == 0, (k, view)
    assert "byteStride" not in view  # tightly packed
    nbytes = acc["count"] * ncomp * size
    assert acc.get("byteOffset", 0) + nbytes <= view["byteLength"], (k, view)
    assert view["byteLength"] - nbytes < 4, "a view holds only its accessor (and padding)"
    assert view.get("byteOffset", 0) + view["byteLength"] <= len(data)
    return np.frombuffer(data, dtype=dtype, count=acc["count"] * ncomp,
                         offset=start).reshape(acc["count"], ncomp)


def check_mesh(doc):
    """The sphere: counts and byte lengths agree, positions on the unit sphere
    with the min/max the file states, unit normals pointing out, texture
    coordinates in [0, 1], triangles counter-clockwise seen from outside."""
    data = buffer_bytes(doc)
    views = doc["bufferViews"]
    spans = sorted((v.get("byteOffset", 0), v["byteLength"]) for v in views)
    for (o1, n1), (o2, _) in zip(spans, spans[1:]):
        assert o1 + n1 <= o2, "bufferViews overlap"
    (prim,) = doc["meshes"][0]["primitives"]
    assert prim.get("mode", 4) == 4
    attrs = prim["attributes"]
    pos = accessor_array(doc, data, attrs["POSITION"]).astype(np.float64)
    nor = accessor_array(doc, data, attrs["NORMAL"]).astype(np.float64)
    uv = accessor_array(doc, data, attrs["TEXCOORD_0"])
    idx = accessor_array(doc, data, prim["indices"]).ravel().astype(np.int64)
    for name, arr in (("POSITION", pos), ("NORMAL", nor), ("TEXCOORD_0", uv)):
        assert len(arr) == len(pos), name
    for name, k in attrs.items():
        assert views[doc["accessors"][k]["bufferView"]]["target"] == 34962, name
    assert views[doc["accessors"][prim["indices"]]["bufferView"]]["target"] == 34963
    assert doc["accessors"][prim["indices"]]["componentType"] in (5123, 5125)
    assert len(pos) >= 64 * 32
    np.testing.assert_allclose(np.linalg.norm(pos, axis=1), 1, atol=1e-6)
    np.testing.assert_allclose(np.linalg.norm(nor, axis=1), 1, atol=1e-6)
    np.testing.assert_allclose(nor, pos, atol=1e-6)  # a sphere about the origin
    acc = doc["accessors"][attrs["POSITION"]]
    assert acc["min"] == pos.min(axis=0).tolist() and acc["max"] == pos.max(axis=0).tolist()
    assert uv.min() >= 0 and uv.max() <= 1
    assert len(idx) % 3 == 0 and idx.min() >= 0 and idx.max() < len(pos)
    tri = pos[idx.reshape(-1, 3)]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = np.linalg.norm(cross, axis=1)
    assert area.min() > 0, "a degenerate triangle"
    assert (np.einsum("ij,ij->i", cross, tri.mean(axis=1)) > 0).all(), "a triangle faces in"
    # the triangles close the sphere: their area is nearly the sphere's
    assert 0.99 * 4 * math.pi < area.sum() / 2 < 4 * math.pi


def check_material(doc, rec):
    """The file's material is the record's, its extensions as the model's."""
    ext = rec["model"] == "gltf-ext"
    (mat,) = doc["materials"]
    assert mat["name"] == f"{rec['material']}-{rec['model']}"
    pbr = mat["pbrMetallicRoughness"]
    assert len(pbr["baseColorFactor"]) == 4 and pbr["baseColorFactor"][3] == 1
    for got, want in zip(pbr["baseColorFactor"], rec["d"]):
        assert close(got, want), (got, want)
    assert close(pbr["metallicFactor"], rec["p"][0])
    assert close(pbr["roughnessFactor"], rec["p"][1])
    assert "extensionsRequired" not in doc
    if not ext:
        assert "extensionsUsed" not in doc and "extensions" not in mat
        return
    assert doc["extensionsUsed"] == EXTENSIONS
    assert sorted(mat["extensions"]) == EXTENSIONS
    assert close(mat["extensions"]["KHR_materials_ior"]["ior"], rec["p"][2])
    spec = mat["extensions"]["KHR_materials_specular"]
    assert close(spec["specularFactor"], rec["p"][3])
    for got, want in zip(spec["specularColorFactor"], rec["s"]):
        assert close(got, want), (got, want)


def check_file(path, rec):
    with open(path) as f:
        doc = json.load(f)
    assert doc["asset"] == {"version": "2.0", "generator": f"brdffit {program_version()}"}
    assert len(doc["scenes"]) == len(doc["nodes"]) == len(doc["meshes"]) == 1
    assert doc["scenes"][doc.get("scene", 0)]["nodes"] == [0]
    assert doc["nodes"][0]["mesh"] == 0
    assert doc["meshes"][0]["primitives"][0]["material"] == 0
    check_mesh(doc)
    check_material(doc, rec)
    return doc


# ------------------------------------------------------------------ the file itself

def test_files_of_a_core_and_an_extended_fit(tmp_path):
    fits = write_jsonl(tmp_path / "fits.jsonl", [CORE, EXT])
    r = export(tmp_path, fits, "--format", "gltf")
    assert r.returncode == 0, r.stderr
    paths = [str(tmp_path / "out" / "red-plastic-gltf.gltf"),
             str(tmp_path / "out" / "warm-metal-gltf-ext.gltf")]
    assert r.stdout.split("\n")[:-1] == paths
    assert sorted(os.listdir(tmp_path / "out")) == sorted(os.path.basename(p) for p in paths)
    check_file(paths[0], CORE)
    check_file(paths[1], EXT)


def test_a_name_is_one_json_string(tmp_path):
    rec = dict(CORE, material='m "quoted" \\ tab\there \u00e9')
    r = export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [rec]))
    assert r.returncode == 0, r.stderr
    check_file(tmp_path / "out" / f"{rec['material']}-gltf.gltf", rec)


def test_a_batch_fits_tsv(tmp_path):
    """A batch's fits.tsv (columns found by name; '-' where a fit has no value)."""
    head = ("material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\tp3\terror\tstatus"
            "\tstatus_code\titerations\tpasses\tcminpack_info\tseconds\tsamples\tat_bound"
            "\tflags\tbackend\tpublished_error\tratio\tfile\tsize\thash\tmessage\n")

    def row(rec, status="ok", code=0, message=""):
        vals = rec["d"] + rec["s"] + rec["p"] if status in ("ok", "limit") else ["-"] * 10
        return "\t".join([rec["material"], rec["model"], *map(str, vals), "0.05", status,
                          str(code), "3", "9", "1", "1.0", "1000", "", "", "opencl", "-", "-",
                          "-", "-", "-", message]) + "\n"
    tsv = tmp_path / "fits.tsv"
    tsv.write_text(head + row(CORE) + row(EXT, "limit")
                   + row(dict(CORE, material="broken"), "the fit failed", 18, "no minimum")
                   + "alum-bronze\tward\t0.1\t0.1\t0.1\t0.2\t0.2\t0.2\t0.05\t\t\t\t0.1\tok\t0"
                   + "\t-" * 15 + "\n")
    r = export(tmp_path, str(tsv))
    assert r.returncode == 0, r.stderr
    check_file(tmp_path / "out" / "red-plastic-gltf.gltf", CORE)
    check_file(tmp_path / "out" / "warm-metal-gltf-ext.gltf", EXT)
    assert "line 4: broken, gltf: not fitted (no minimum); skipped" in r.stderr, r.stderr
    assert "ward: not a glTF model; fit --model gltf or gltf-ext" in r.stderr, r.stderr
    assert not (tmp_path / "out" / "broken-gltf.gltf").exists()


# ------------------------------------------------------------------ what is skipped or refused

def test_other_models_and_failed_fits_are_skipped(tmp_path):
    ward = dict(record("alum-bronze", "ward", [0.1] * 3, [0.2] * 3, [0.05]),
                param_names=["alpha"])
    failed = record("broken", "gltf-ext", None, None, None, status="the fit failed")
    fits = write_jsonl(tmp_path / "fits.jsonl", [ward, ward, failed, EXT])
    r = export(tmp_path, fits)
    assert r.returncode == 0, r.stderr
    assert r.stdout == str(tmp_path / "out" / "warm-metal-gltf-ext.gltf") + "\n"
    lines = r.stderr.splitlines()
    assert [ln for ln in lines if "ward" in ln] == [
        "brdffit: ward: not a glTF model; fit --model gltf or gltf-ext (2 fits skipped)"]
    assert any("line 3: broken, gltf-ext: not fitted" in ln and ln.endswith("skipped")
               for ln in lines), r.stderr
    # nothing to write: exit 1, no directory made
    r = export(tmp_path, write_jsonl(tmp_path / "w.jsonl", [ward, failed]), out="none")
    assert r.returncode == 1 and "nothing written" in r.stderr, r.stderr
    assert not (tmp_path / "none").exists()


@pytest.mark.parametrize("change, says", [
    ({"d": [1.25, 0.5, 0.5]}, "base colour r = 1.25 is not in [0, 1]"),
    ({"d": [0.5, -0.01, 0.5]}, "base colour g = -0.01 is not in [0, 1]"),
    ({"p": [1.5, 0.5, 1.5, 1]}, "metallic = 1.5 is not in [0, 1]"),
    ({"p": [0.5, 2, 1.5, 1]}, "roughness = 2 is not in [0, 1]"),
    ({"p": [0.5, 0.5, 0.8, 1], "model": "gltf-ext"}, "ior = 0.8 is not a number >= 1"),
    ({"p": [0.5, 0.5, 1.5, 1.2], "model": "gltf-ext"}, "specular = 1.2 is not in [0, 1]"),
    ({"p": [0.5, 0.5, 1e999, 1]}, "not a record"),          # inf in JSON: not a record
    ({"p": [0.5, 0.5, 1.5]}, "no parameters"),
])
def test_values_outside_gltf_are_refused(tmp_path, change, says):
    bad = dict(CORE, material="bad", **change)
    fits = write_jsonl(tmp_path / "fits.jsonl", [EXT, bad])
    r = export(tmp_path, fits)
    assert r.returncode == 1, r.stderr
    assert f"{fits}: line 2: " in r.stderr and says in r.stderr, r.stderr
    assert os.listdir(tmp_path / "out") == ["warm-metal-gltf-ext.gltf"]


def test_nonfinite_values_of_a_tsv_are_refused(tmp_path):
    tsv = tmp_path / "fits.tsv"
    tsv.write_text("material\tmodel\td_r\td_g\td_b\ts_r\ts_g\ts_b\tp0\tp1\tp2\tp3\n"
                   "a\tgltf\t0.5\t0.5\t0.5\t1\t1\t1\t0\tnan\t1.5\t1\n"
                   "b\tgltf\t0.5\t0.5\t0.5\t1\t1\t1\t0\t0.5\tinf\t1\n")
    r = export(tmp_path, str(tsv))
    assert r.returncode == 1 and "nothing written" in r.stderr, r.stderr
    assert f"{tsv}: line 2: a, gltf: roughness = nan is not a finite number" in r.stderr, r.stderr
    assert f"{tsv}: line 3: b, gltf: ior = inf is not a finite number" in r.stderr, r.stderr


@pytest.mark.parametrize("name", ["", ".", "..", "a/b", "../escape"])
def test_names_that_are_not_one_path_component(tmp_path, name):
    r = export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [dict(CORE, material=name)]))
    assert r.returncode == 1, r.stderr
    assert "line 1: " in r.stderr and "is not a file name" in r.stderr, r.stderr
    assert not (tmp_path / "out").exists() and not (tmp_path / "escape-gltf.gltf").exists()


def test_usage(tmp_path):
    fits = write_jsonl(tmp_path / "fits.jsonl", [CORE])
    r = export(tmp_path, fits, "--format", "obj")
    assert r.returncode == 2 and "unknown format 'obj' (formats: gltf, mitsuba)" in r.stderr, r.stderr
    r = subprocess.run([CLI, "export", fits], capture_output=True, text=True)
    assert r.returncode == 2 and "--out DIR" in r.stderr, r.stderr
    r = export(tmp_path, str(tmp_path / "missing.jsonl"))
    assert r.returncode == 1 and "missing.jsonl: cannot open" in r.stderr, r.stderr
    (tmp_path / "a-file").write_text("")
    r = export(tmp_path, write_jsonl(tmp_path / "two.jsonl", [CORE, EXT]), out="a-file")
    assert r.returncode == 1 and r.stdout == "", r.stderr
    assert r.stderr.count("cannot create the directory") == 1, r.stderr
    help_text = subprocess.run([CLI, "help", "export"], capture_output=True, text=True)
    assert help_text.returncode == 0 and "--format gltf" in help_text.stdout


# ------------------------------------------------------------------ real fits

@pytest.fixture(scope="module")
def real_fits(tmp_path_factory):
    """`brdffit demo --model gltf,gltf-ext --json`: both models fitted to the
    built-in material, and exported."""
    d = tmp_path_factory.mktemp("real")
    r = subprocess.run([CLI, "demo", "--model", "gltf,gltf-ext", "--json"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    (d / "fits.jsonl").write_text(r.stdout)
    recs = [json.loads(ln) for ln in r.stdout.splitlines()]
    assert [x["model"] for x in recs] == ["gltf", "gltf-ext"]
    e = export(d, str(d / "fits.jsonl"))
    assert e.returncode == 0, e.stderr
    return [(d / "out" / f"{x['material']}-{x['model']}.gltf", x) for x in recs]


def test_real_fits(real_fits):
    for path, rec in real_fits:
        check_file(path, rec)


def test_real_batch_fits_tsv(tmp_path):
    """A batch's fits.tsv of the two models (and ward, skipped), exported."""
    r = subprocess.run([CLI, "batch", "--demo", "--model", "gltf,gltf-ext,ward", "--no-render",
                        "--no-plot", "--quiet", "--out", str(tmp_path / "batch")],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    tsv = tmp_path / "batch" / "fits.tsv"
    rows = [ln.split("\t") for ln in tsv.read_text().splitlines() if not ln.startswith("#")]
    head, rows = rows[0], [dict(zip(rows[0], row)) for row in rows[1:]]
    assert head[8:12] == ["p0", "p1", "p2", "p3"]
    e = export(tmp_path, str(tsv))
    assert e.returncode == 0, e.stderr
    assert "ward: not a glTF model; fit --model gltf or gltf-ext (1 fit skipped)" in e.stderr
    written = 0
    for row in rows:
        if row["model"] == "ward":
            continue
        rec = {"material": row["material"], "model": row["model"],
               "d": [float(row[k]) for k in ("d_r", "d_g", "d_b")],
               "s": [float(row[k]) for k in ("s_r", "s_g", "s_b")],
               "p": [float(row[f"p{k}"]) for k in range(4)]}
        check_file(tmp_path / "out" / f"{rec['material']}-{rec['model']}.gltf", rec)
        written += 1
    assert written == 2 and len(os.listdir(tmp_path / "out")) == 2


def test_batch_report_has_the_gltf_files_and_the_material_to_paste(tmp_path):
    """A batch with the glTF models writes each fit's .gltf beside its page, and
    the page shows the material object to paste, equal to the file's."""
    import html
    import re
    out = tmp_path / "batch"
    r = subprocess.run([CLI, "batch", "--demo", "--model", "gltf,gltf-ext,ward", "--no-render",
                        "--no-plot", "--quiet", "--out", str(out)],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    (mdir,) = [d for d in out.iterdir() if d.is_dir()]
    params = json.loads((mdir / "params.json").read_text())
    page = (mdir / "index.html").read_text()
    pasted = [json.loads(html.unescape(t)) for t in re.findall(r"<pre>(.*?)</pre>", page, re.S)]
    fits = [f for f in params["fits"] if f["model"] in ("gltf", "gltf-ext")]
    assert len(fits) == 2 and len(pasted) == 2
    for rec, mat in zip(fits, pasted):
        doc = check_file(mdir / f"{rec['material']}-{rec['model']}.gltf", rec)
        assert mat == doc["materials"][0]
        assert f'href="{rec["material"]}-{rec["model"]}.gltf"' in page
    assert not list(mdir.glob("*ward*.gltf"))


# ------------------------------------------------------------------ pygltflib and Blender

@pytest.fixture(scope="session")
def pygltflib_python():
    return tool_python(("pygltflib", "pygltflib"))


@pytest.fixture(scope="session")
def bpy_python():
    return tool_python((BPY, "bpy"))


PYGLTFLIB_SCRIPT = r"""
import json, sys
from pygltflib import GLTF2
from pygltflib.validator import validate
g = GLTF2().load(sys.argv[1])
validate(g)
m = g.materials[0]
data = g.decode_data_uri(g.buffers[0].uri)
print(json.dumps({"version": g.asset.version, "used": g.extensionsUsed,
                  "required": g.extensionsRequired, "name": m.name,
                  "base": m.pbrMetallicRoughness.baseColorFactor,
                  "metallic": m.pbrMetallicRoughness.metallicFactor,
                  "roughness": m.pbrMetallicRoughness.roughnessFactor,
                  "extensions": m.extensions, "nbytes": len(data),
                  "counts": [a.count for a in g.accessors]}))
"""


def pygltflib_check(py, path, rec, tmp_path):
    """pygltflib loads and validates the file and sees the record's material."""
    script = tmp_path / "read.py"
    script.write_text(PYGLTFLIB_SCRIPT)
    r = _run([py, str(script), str(path)])
    assert r.returncode == 0, r.stderr
    got = json.loads(r.stdout)
    doc = json.loads(path.read_text())
    assert got["version"] == "2.0" and got["name"] == f"{rec['material']}-{rec['model']}"
    assert got["required"] in (None, [])
    assert got["used"] in ((EXTENSIONS,) if rec["model"] == "gltf-ext" else (None, []))
    assert got["nbytes"] == doc["buffers"][0]["byteLength"]
    assert got["counts"] == [a["count"] for a in doc["accessors"]]
    assert all(close(a, b) for a, b in zip(got["base"], rec["d"] + [1]))
    assert close(got["metallic"], rec["p"][0]) and close(got["roughness"], rec["p"][1])
    if rec["model"] == "gltf-ext":
        assert close(got["extensions"]["KHR_materials_ior"]["ior"], rec["p"][2])


@pytest.mark.parametrize("rec", [CORE, EXT], ids=["gltf", "gltf-ext"])
def test_pygltflib_reads_the_file(tmp_path, pygltflib_python, rec):
    assert export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [rec])).returncode == 0
    pygltflib_check(pygltflib_python,
                    tmp_path / "out" / f"{rec['material']}-{rec['model']}.gltf", rec, tmp_path)


def test_pygltflib_reads_real_fits(tmp_path, pygltflib_python, real_fits):
    for path, rec in real_fits:
        pygltflib_check(pygltflib_python, path, rec, tmp_path)


BLENDER_SCRIPT = r"""
import json, sys
import bpy
bpy.ops.wm.read_factory_settings(use_empty=True)
result = bpy.ops.import_scene.gltf(filepath=sys.argv[1])
out = {"result": sorted(result), "materials": {}}
for mat in bpy.data.materials:
    for node in mat.node_tree.nodes if mat.node_tree else ():
        if node.type != "BSDF_PRINCIPLED":
            continue
        vals = {}
        for name in ("Base Color", "Metallic", "Roughness", "IOR", "Specular IOR Level",
                     "Specular Tint"):
            if name in node.inputs:
                v = node.inputs[name].default_value
                vals[name] = list(v) if hasattr(v, "__len__") else v
                vals[name + " linked"] = node.inputs[name].is_linked
        out["materials"][mat.name] = vals
print("BSDF " + json.dumps(out))
"""


def blender_check(py, path, tmp_path):
    """Blender's glTF importer gives its Principled BSDF the file's values.
    A core file shows the core material: ior 1.5, specular 1 (Blender's
    Specular IOR Level 0.5: its level is specularFactor / 2), white tint."""
    script = tmp_path / "import.py"
    script.write_text(BLENDER_SCRIPT)
    r = _run([py, str(script), str(path)], timeout=180)
    assert r.returncode == 0, r.stderr[-4000:]
    (line,) = [ln for ln in r.stdout.splitlines() if ln.startswith("BSDF ")]
    got = json.loads(line[5:])
    assert got["result"] == ["FINISHED"]
    mat = json.loads(path.read_text())["materials"][0]
    bsdf = got["materials"][mat["name"]]
    pbr = mat["pbrMetallicRoughness"]
    for name in ("Base Color", "Metallic", "Roughness", "IOR"):
        assert not bsdf[name + " linked"], name
    np.testing.assert_allclose(bsdf["Base Color"][:3], pbr["baseColorFactor"][:3], atol=1e-6)
    assert abs(bsdf["Metallic"] - pbr["metallicFactor"]) <= 1e-6
    assert abs(bsdf["Roughness"] - pbr["roughnessFactor"]) <= 1e-6
    ext = mat.get("extensions", {})
    ior = ext.get("KHR_materials_ior", {}).get("ior", 1.5)
    spec = ext.get("KHR_materials_specular", {})
    assert abs(bsdf["IOR"] - ior) <= 1e-6
    assert abs(bsdf["Specular IOR Level"] - spec.get("specularFactor", 1) / 2) <= 1e-6
    np.testing.assert_allclose(bsdf["Specular Tint"][:3],
                               spec.get("specularColorFactor", [1, 1, 1]), atol=1e-6)


@pytest.mark.parametrize("rec", [CORE, EXT], ids=["gltf", "gltf-ext"])
def test_blender_imports_the_material(tmp_path, bpy_python, rec):
    assert export(tmp_path, write_jsonl(tmp_path / "fits.jsonl", [rec])).returncode == 0
    blender_check(bpy_python, tmp_path / "out" / f"{rec['material']}-{rec['model']}.gltf",
                  tmp_path)


def test_blender_imports_real_fits(tmp_path, bpy_python, real_fits):
    for path, _ in real_fits:
        blender_check(bpy_python, path, tmp_path)
