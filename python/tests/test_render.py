# SPDX-License-Identifier: MIT
"""render, default_lights, image_error: a Lambertian sphere equals its closed
form, a render equals brdffit.eval at each pixel's directions and the
program's EXR file (read by OpenEXR's C++ library, not the program's
reader), the environment and the caller's row stride, and the library's
messages for bad arguments."""

import json
import os
import subprocess

import numpy as np
import pytest

CT = [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.15]   # cook-torrance d, s, F0, m
MATTE = [0.2, 0.5, 0.8, 0.0, 0.0, 0.0, 10.0]    # blinn-phong with s = 0: f = d / pi

EXRDUMP = r"""
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <cstdio>
#include <exception>
#include <vector>
/* exrdump FILE.exr OUT.raw: R, G, B, A as float32, row 0 at the top; prints "W H". */
int main(int argc, char **argv)
{
    if (argc != 3)
        return 2;
    try {
        Imf::InputFile f(argv[1]);
        Imath::Box2i dw = f.header().dataWindow();
        int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        std::vector<float> px((size_t)w * h * 4);
        Imf::FrameBuffer fb;
        static const char *const names[4] = { "R", "G", "B", "A" };
        char *base = (char *)px.data() - ((size_t)dw.min.y * w + dw.min.x) * 16;
        for (int c = 0; c < 4; c++)
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + 4 * c, 16, 16 * (size_t)w));
        f.setFrameBuffer(fb);
        f.readPixels(dw.min.y, dw.max.y);
        FILE *out = fopen(argv[2], "wb");
        if (!out || fwrite(px.data(), 4, px.size(), out) != px.size() || fclose(out) != 0)
            return 1;
        printf("%d %d\n", w, h);
    } catch (const std::exception &e) {
        fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
"""


@pytest.fixture(scope="session")
def exrdump(tmp_path_factory):
    """An EXR reader built on OpenEXR's C++ API (Imf::InputFile)."""
    d = tmp_path_factory.mktemp("exrdump")
    src, exe = d / "exrdump.cpp", d / "exrdump"
    src.write_text(EXRDUMP)
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "OpenEXR"], check=True,
                           capture_output=True, text=True).stdout.split()
    subprocess.run([os.environ.get("CXX", "c++"), "-O1", "-o", str(exe), str(src), *flags],
                   check=True)

    def read(path):
        raw = path.parent / (path.name + ".raw")
        out = subprocess.run([str(exe), str(path), str(raw)], check=True, capture_output=True,
                             text=True).stdout.split()
        w, h = int(out[0]), int(out[1])
        return np.fromfile(raw, dtype=np.float32).reshape(h, w, 4)

    return read


def sphere(n):
    """Per pixel (the render scene of docs/conventions.md): on-sphere mask and the normal, camera frame."""
    c = (np.arange(n) + 0.5) * 2 / n
    x = (c - 1)[None, :].repeat(n, 0)
    y = (1 - c)[:, None].repeat(n, 1)
    r2 = x * x + y * y
    on = r2 < 1
    nz = np.sqrt(np.clip(1 - r2, 0, None))
    return on, np.stack([x, y, nz], axis=-1)


def test_default_lights(brdffit):
    key, rim = brdffit.default_lights()
    assert key == brdffit.Light((-1.0, 1.0, 1.5), (1.0, 1.0, 1.0))
    assert rim == brdffit.Light((1.0, 0.25, -0.6), (0.5, 0.5, 0.5))


def test_lambertian_under_one_light_is_the_cosine_law(brdffit):
    n, light, e = 96, np.array([0.3, -0.5, 0.8]), np.array([2.0, 1.0, 0.5])
    img = brdffit.render("blinn-phong", MATTE, size=n, lights=[(light, e)])
    assert img.shape == (n, n, 4) and img.dtype == np.float32
    on, normal = sphere(n)
    cos = np.clip(normal @ (light / np.linalg.norm(light)), 0, None)
    want = np.array(MATTE[:3]) / np.pi * e * cos[..., None]
    assert np.array_equal(img[..., 3], on.astype(np.float32))   # coverage: 1 on, 0 off
    assert np.all(img[~on][:, :3] == 0)
    assert np.allclose(img[on][:, :3], want[on], rtol=2e-6, atol=1e-9)
    assert (cos[on] == 0).sum() > 100 and (cos[on] > 0.99).sum() > 10  # lit and unlit parts
    # no lights at all: black
    assert not np.any(brdffit.render("blinn-phong", MATTE, size=16, lights=[])[..., :3])


def test_render_equals_eval_at_each_pixel(brdffit):
    """The model's render under the default lights equals sum over the lights
    of brdffit.eval(wi, wo) E cos in the shading frame of docs/conventions.md."""
    n = 64
    fit_like = brdffit.FitResult(
        model=brdffit.model("cook-torrance"), params=brdffit.Params.from_vector(CT), error=0.0,
        status=brdffit.Status.OK, cminpack_info=1, iterations=1, passes=1, seconds=0.0,
        seconds_solver=0.0, seconds_passes=0.0, samples=1, backend="host")
    img = brdffit.render(fit_like, size=n)
    on, nrm = sphere(n)
    nrm = nrm[on]
    t = np.stack([nrm[:, 2], np.zeros(len(nrm)), -nrm[:, 0]], axis=1)
    t /= np.linalg.norm(t, axis=1)[:, None]
    b = np.cross(nrm, t)

    def local(v):
        v = np.broadcast_to(v, nrm.shape)
        return np.stack([(v * t).sum(1), (v * b).sum(1), (v * nrm).sum(1)], axis=1)

    wo = local(np.array([0.0, 0.0, 1.0]))
    want = np.zeros((len(nrm), 3))
    for light in brdffit.default_lights():
        d = np.array(light.dir) / np.linalg.norm(light.dir)
        cos = nrm @ d
        lit = cos > 0
        f = brdffit.eval("cook-torrance", CT, local(d)[lit], wo[lit])
        want[lit] += f * np.array(light.rgb) * cos[lit, None]
    assert np.allclose(img[on][:, :3], want, rtol=1e-5, atol=1e-7)
    assert np.all(img[on][:, 3] == 1)


def test_render_equals_the_programs_exr(brdffit, cli, exrdump, tmp_path):
    """`brdffit render` of a table and of a model's fit, read back from its EXR
    files, is the Python render bit for bit (both the reference with its
    masked rim and the model)."""
    table = brdffit.Table.from_model("cook-torrance", CT)
    path = tmp_path / "synth.binary"
    table.write(path)
    fits = tmp_path / "fits.jsonl"
    fits.write_text(json.dumps({"material": "synth", "model": "cook-torrance", "status": "ok",
                                "d": CT[0:3], "s": CT[3:6], "p": CT[6:]}) + "\n")
    out = tmp_path / "out"
    subprocess.run([cli, "render", str(path), "--out", str(out), "--model", "cook-torrance",
                    "--fits", str(fits), "--size", "80"], check=True, capture_output=True)
    ref = brdffit.render(table, size=80)
    model = brdffit.render("cook-torrance", CT, size=80)
    assert np.array_equal(exrdump(out / "reference.exr"), ref)
    assert np.array_equal(exrdump(out / "cook-torrance.exr"), model)
    masked = ref[..., 3] == brdffit.COVERAGE_MASKED
    assert masked.sum() > 0 and set(np.unique(ref[..., 3])) == {0.0, 0.5, 1.0}
    # the program's image error and pixel counts are the library's, through Python
    err, covered = brdffit.image_error(ref, model)
    rec = json.loads((out / "renders.json").read_text())
    assert (rec["covered"], rec["masked"]) == (covered, int(masked.sum()))
    assert covered == int((ref[..., 3] == 1).sum())
    [m] = rec["models"]
    assert m["model"] == "cook-torrance" and m["relative_rms"] == err > 0


def test_render_options(brdffit, alum_bronze):
    t = brdffit.Table.read(alum_bronze)
    tri = brdffit.render(t, size=48)
    near = brdffit.render(t, size=48, interp="nearest")
    flat = brdffit.render(t, size=48, scale="flat")
    assert not np.array_equal(tri, near)
    cov = tri[..., 3] == 1
    ratio = flat[cov][:, :3] / np.where(tri[cov][:, :3] > 0, tri[cov][:, :3], np.nan)
    want = brdffit.scale_factors("flat") / brdffit.scale_factors("standard")
    assert np.allclose(np.nanmedian(ratio, axis=0), want, rtol=1e-5)
    # threads change nothing
    assert np.array_equal(brdffit.render(t, size=48, threads=1), tri)
    assert np.array_equal(brdffit.render(t, size=48, threads=3), tri)


def test_render_into_a_strided_buffer(brdffit):
    canvas = np.full((40, 100, 4), -7.0, dtype=np.float32)
    view = canvas[4:36, 10:42]
    got = brdffit.render("cook-torrance", CT, size=32, out=view)
    assert got is view
    assert np.array_equal(view, brdffit.render("cook-torrance", CT, size=32))
    outside = np.ones(canvas.shape[:2], bool)
    outside[4:36, 10:42] = False
    assert np.all(canvas[outside] == -7.0)
    for bad in (np.empty((32, 32, 4)), np.empty((32, 32, 3), np.float32),
                np.empty((32, 32, 4), np.float32)[:, ::2], np.empty((33, 33, 4), np.float32)):
        with pytest.raises(brdffit.InvalidArgumentError, match="out: must be"):
            brdffit.render("cook-torrance", CT, size=32, out=bad)


def test_environment(brdffit):
    """A constant radiance-1 environment renders a Lambertian sphere to d; a
    map passed as a row-strided float32 view or as a float64 copy renders the
    same."""
    img = brdffit.render("blinn-phong", MATTE, size=32, lights=[], env=np.ones((8, 16, 3)),
                         env_samples=64)
    on, _ = sphere(32)
    assert np.allclose(img[on][:, :3], MATTE[:3], rtol=1e-5)
    rng = np.random.default_rng(3)
    big = rng.uniform(0, 2, size=(8, 24, 3)).astype(np.float32)
    view = big[:, 4:20]                                # rows 24 texels apart
    a = brdffit.render("cook-torrance", CT, size=32, lights=[], env=view, env_samples=32)
    b = brdffit.render("cook-torrance", CT, size=32, lights=[], env=view.astype(np.float64),
                       env_samples=32)
    c = brdffit.render("cook-torrance", CT, size=32, lights=[], env=np.ascontiguousarray(view),
                       env_samples=32)
    assert np.array_equal(a, b) and np.array_equal(a, c) and a[on][:, :3].max() > 0
    d = brdffit.render("cook-torrance", CT, size=32, lights=[], env=big[:, :16], env_samples=32)
    assert not np.array_equal(a, d)                    # the stride was honoured


def test_image_error(brdffit):
    ref = brdffit.render("cook-torrance", CT, size=40)
    assert brdffit.image_error(ref, ref) == (0.0, int((ref[..., 3] == 1).sum()))
    img = ref.copy()
    img[..., :3] *= 1.25
    err, covered = brdffit.image_error(ref, img)
    assert err == pytest.approx(0.25, rel=1e-6) and covered > 1000
    other = brdffit.render("ward", [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2], size=40)
    cov = ref[..., 3] == 1
    d = other[cov][:, :3].astype(np.float64) - ref[cov][:, :3]
    want = np.sqrt((d * d).sum() / (ref[cov][:, :3].astype(np.float64) ** 2).sum())
    assert brdffit.image_error(ref, other)[0] == pytest.approx(want, rel=1e-12)
    with pytest.raises(brdffit.NoSamplesError, match="no pixel of the reference is covered"):
        brdffit.image_error(np.zeros((4, 4, 4)), np.zeros((4, 4, 4)))
    black = ref.copy()
    black[..., :3] = 0
    with pytest.raises(brdffit.NoSamplesError, match="black"):
        brdffit.image_error(black, ref)
    with pytest.raises(brdffit.InvalidArgumentError, match="differ"):
        brdffit.image_error(ref, ref[:20])
    with pytest.raises(brdffit.InvalidArgumentError, match="height, width, 4"):
        brdffit.image_error(ref[..., :3], ref[..., :3])


@pytest.mark.parametrize("kwargs, error, message", [
    ({"size": 0}, "InvalidArgumentError", r"render: width 0 \(1\.\.16384\)"),
    ({"size": 20000}, "InvalidArgumentError", r"render: width 20000 \(1\.\.16384\)"),
    ({"size": 2 ** 40}, "InvalidArgumentError", "size: 1099511627776 is out of range"),
    ({"size": 2.5}, "InvalidArgumentError", "size: 2.5 is not an integer"),
    ({"lights": [((0, 0, 0), 1)]}, "InvalidArgumentError",
     r"render: light 0: direction \(0, 0, 0\) must be finite and non-zero"),
    ({"lights": [((0, 0, 1), 1), ((0, 1, 1), (1, -1, 1))]}, "InvalidArgumentError",
     r"render: light 1: irradiance \(1, -1, 1\) must be finite and >= 0"),
    ({"lights": [((0, 0, 1), 1)] * 17}, "InvalidArgumentError", "17 lights, at most 16"),
    ({"lights": [(0, 0, 1)]}, "InvalidArgumentError", "not a Light or a"),
    ({"env": np.full((2, 4, 3), np.nan)}, "InvalidArgumentError",
     r"render: environment texel \(0, 0\) channel 0 is nan"),
    ({"env": -np.ones((2, 4, 3))}, "InvalidArgumentError", "radiance must be finite and >= 0"),
    ({"env": np.ones((2, 4))}, "InvalidArgumentError", r"expected \(height, width, 3\)"),
    ({"env": np.ones((2, 4, 3)), "env_samples": 0}, "InvalidArgumentError",
     r"render: env_samples = 0 \(1\.\.65536\)"),
    ({"interp": "cubic"}, "InvalidArgumentError", "unknown interpolation"),
    ({"scale": "log"}, "InvalidArgumentError", "unknown scale"),
])
def test_render_bad_arguments(brdffit, kwargs, error, message):
    with pytest.raises(getattr(brdffit, error), match=message) as e:
        brdffit.render("cook-torrance", CT, size=kwargs.pop("size", 16), **kwargs)
    assert e.value.status == brdffit.Status.INVALID_ARGUMENT


def test_render_bad_sources(brdffit):
    with pytest.raises(brdffit.ParamRangeError, match="m") as e:
        brdffit.render("cook-torrance", CT[:7] + [-1.0], size=8)
    assert e.value.status == brdffit.Status.PARAM_RANGE
    with pytest.raises(brdffit.UnknownModelError):
        brdffit.render("phong", CT, size=8)
    with pytest.raises(brdffit.InvalidArgumentError, match="needs params"):
        brdffit.render("cook-torrance", size=8)
    with pytest.raises(brdffit.InvalidArgumentError, match="given with a Table"):
        brdffit.render(brdffit.Table.zeros(), CT, size=8)
