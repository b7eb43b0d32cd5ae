# SPDX-License-Identifier: MIT
"""brdffit.flip (brdffit_flip) and the image errors of `brdffit render`
against NVIDIA's own FLIP, the flip-evaluator package from PyPI, run in a
subprocess of the tools' virtual environment (toolvenv.py): the means agree
within 1e-3 on renders of a material against its models and on synthetic
pairs; and an image made worse step by step ranks worse each step."""

import json
import subprocess

import numpy as np
import pytest

from toolvenv import run, tool_python

FLIP_SCRIPT = r"""
import json, sys
import numpy as np
import flip_evaluator as flip
out = {}
for ref, test in json.loads(sys.argv[1]):
    r = np.load(ref) if ref.endswith(".npy") else ref
    t = np.load(test) if test.endswith(".npy") else test
    fmap, mean, _ = flip.evaluate(r, t, "LDR", applyMagma=False)
    out[test] = [float(mean), np.asarray(fmap, dtype=np.float64).squeeze().tolist()]
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def flip_python():
    return tool_python(("flip-evaluator", "flip_evaluator"))


def nvidia_flip(py, pairs):
    """{test: (mean, map)} of NVIDIA's FLIP for each (ref, test) path pair
    (PNG files, or .npy float arrays of sRGB values in [0, 1])."""
    r = run([py, "-c", FLIP_SCRIPT, json.dumps([[str(a), str(b)] for a, b in pairs])],
            timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    return {k: (v[0], np.array(v[1])) for k, v in json.loads(r.stdout).items()}


CT = [0.05, 0.08, 0.12, 0.3, 0.25, 0.2, 0.6, 0.3]
# d, s, p of models that miss the Cook-Torrance table by more or less
FITS = {"cook-torrance": CT, "ward": CT[:6] + [0.2], "blinn-phong": CT[:6] + [30],
        "ggx": CT[:6] + [0.6, 0.5]}


def test_render_image_errors_are_nvidias_flip(brdffit, cli, flip_python, tmp_path):
    table = brdffit.Table.from_model("cook-torrance", CT)
    path = tmp_path / "ct.binary"
    table.write(path)
    fits = tmp_path / "fits.jsonl"
    fits.write_text("".join(json.dumps({"material": "ct", "model": m, "status": "ok", "d": p[0:3],
                                        "s": p[3:6], "p": p[6:]}) + "\n" for m, p in FITS.items()))
    out = tmp_path / "out"
    subprocess.run([cli, "render", str(path), "--out", str(out), "--model", ",".join(FITS),
                    "--fits", str(fits), "--size", "128"], check=True, capture_output=True)
    rec = json.loads((out / "renders.json").read_text())
    want = nvidia_flip(flip_python, [(out / "reference.png", out / f"{m}.png") for m in FITS])
    errors = {}
    for m in rec["models"]:
        mean, _ = want[str(out / f"{m['model']}.png")]
        assert abs(m["image_error"] - mean) < 1e-3, (m["model"], m["image_error"], mean)
        errors[m["model"]] = m["image_error"]
    # the exact model is the best, and the ranking is NVIDIA's
    assert min(errors, key=errors.get) == "cook-torrance"
    nv = {m: want[str(out / f"{m}.png")][0] for m in FITS}
    assert sorted(errors, key=errors.get) == sorted(nv, key=nv.get)


def synthetic_pairs(rng):
    y, x = np.mgrid[0:61, 0:77] / 64.0  # a width not a multiple of the vector lanes
    ref = np.stack([0.5 + 0.4 * np.sin(7 * x), y % 1.0, 0.3 + 0.5 * ((x * 8).astype(int) % 2)],
                   -1).clip(0, 1)
    noisy = (ref + rng.normal(0, 0.08, ref.shape)).clip(0, 1)
    shifted = np.roll(ref, 2, axis=1)
    tinted = (ref * [1.1, 0.9, 0.7]).clip(0, 1)
    return ref.astype(np.float32), {"noisy": noisy, "shifted": shifted, "tinted": tinted}


def test_synthetic_pairs_match_nvidia(brdffit, flip_python, tmp_path):
    ref, tests = synthetic_pairs(np.random.default_rng(5))
    np.save(tmp_path / "ref.npy", ref)
    pairs = []
    for name, img in tests.items():
        np.save(tmp_path / f"{name}.npy", img.astype(np.float32))
        pairs.append((tmp_path / "ref.npy", tmp_path / f"{name}.npy"))
    want = nvidia_flip(flip_python, pairs)
    for name, img in tests.items():
        mean, fmap = brdffit.flip(ref, img.astype(np.float32))
        nv_mean, nv_map = want[str(tmp_path / f"{name}.npy")]
        assert abs(mean - nv_mean) < 1e-3, (name, mean, nv_mean)
        assert fmap.shape == nv_map.shape and np.abs(fmap - nv_map).max() < 1e-3, name


def test_worse_images_rank_worse(brdffit):
    """Noise of growing strength, then blur of growing width, on a render:
    each step's FLIP above the last."""
    rgba = brdffit.render("cook-torrance", CT, size=96)
    srgb = np.where(rgba[..., :3] <= 0.0031308, 12.92 * rgba[..., :3],
                    1.055 * np.abs(rgba[..., :3] * 4) ** (1 / 2.4) - 0.055).clip(0, 1)
    ref = (srgb * 255 + 0.5).astype(np.uint8)
    assert brdffit.flip(ref, ref)[0] == 0
    rng = np.random.default_rng(1)
    noise = rng.normal(0, 1, ref.shape)
    last = 0.0
    for sigma in (2, 5, 10, 20, 40):
        img = (ref + sigma * noise).clip(0, 255).astype(np.uint8)
        mean = brdffit.flip(ref, img)[0]
        assert mean > last, (sigma, mean, last)
        last = mean
    last = 0.0
    f = ref.astype(np.float32) / 255
    for r in (1, 2, 4, 8):
        k = np.ones(2 * r + 1) / (2 * r + 1)
        blur = np.apply_along_axis(lambda v: np.convolve(v, k, mode="same"), 1, f)
        blur = np.apply_along_axis(lambda v: np.convolve(v, k, mode="same"), 0, blur)
        mean = brdffit.flip(f, blur.astype(np.float32))[0]
        assert mean > last, (r, mean, last)
        last = mean


def test_flip_refuses_bad_images(brdffit):
    a = np.zeros((4, 5, 3), dtype=np.float32)
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.flip(a, np.zeros((4, 6, 3), dtype=np.float32))
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.flip(np.zeros((4, 5, 4), dtype=np.float32), a)
    b = a.copy()
    b[1, 2, 0] = np.nan
    with pytest.raises(brdffit.InvalidArgumentError) as e:
        brdffit.flip(a, b)
    assert "not finite" in str(e.value) or "nan" in str(e.value).lower()
