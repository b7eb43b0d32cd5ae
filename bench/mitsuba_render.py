# SPDX-License-Identifier: MIT
"""The Mitsuba 3 plugin's speed (docs/mitsuba.md): a fit exported by
`brdffit export --format mitsuba` (256 x 256, 64 samples a pixel, the
default lights) rendered with llvm_ad_rgb through brdffit.mitsuba; prints
and records (bench/record) the wall time of the render, the seconds inside
the plugin's methods and their share.  Run with a Python that has mitsuba
(make bench-mitsuba uses the tests' venv).

usage: mitsuba_render.py BRDFFIT OUTDIR [--record] [--model NAME] [--rounds N]
"""

import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(REPO, "python"))

# A GGX fit of a MERL-like metallic paint (the numbers of `brdffit fit
# blue-metallic-paint.binary --model ggx`), written as a file of fits so the
# benchmark needs no table.
FITS = {
    "ggx": {"d": [0.0, 0.0, 0.004684], "s": [0.07513, 0.07053, 0.143], "p": [1.0, 0.2563]},
    "cook-torrance": {"d": [0.01705, 0.0128, 0.0485], "s": [0.04621, 0.04398, 0.08396],
                      "p": [1.0, 0.2314]},
    "ward": {"d": [0.01202, 0.008103, 0.02822], "s": [0.0837, 0.07951, 0.1719], "p": [0.2348]},
}


def record(args, bench, metric, value):
    print(f"{bench}\t{metric}\t{value:.6g}")
    if args.record:
        subprocess.run([os.path.join(HERE, "record"), bench, metric, f"{value:.6g}"], check=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("brdffit")
    ap.add_argument("outdir")
    ap.add_argument("--record", action="store_true")
    ap.add_argument("--model", default="ggx", choices=sorted(FITS))
    ap.add_argument("--rounds", type=int, default=2)
    args = ap.parse_args()
    try:
        import mitsuba as mi
    except ImportError:
        sys.exit(f"bench-mitsuba: {sys.executable} has no mitsuba (pip install mitsuba)")
    mi.set_variant("llvm_ad_rgb")
    import brdffit.mitsuba as bm

    bm.register()
    os.makedirs(args.outdir, exist_ok=True)
    fit = dict(FITS[args.model], kind="fit", material="bench", model=args.model, status="ok")
    fits = os.path.join(args.outdir, "fits.jsonl")
    with open(fits, "w") as f:
        f.write(json.dumps(fit) + "\n")
    subprocess.run([args.brdffit, "export", fits, "--format", "mitsuba", "--size", "256",
                    "--spp", "64", "--out", args.outdir], check=True, stdout=subprocess.DEVNULL)
    scene = mi.load_file(os.path.join(args.outdir, f"bench-{args.model}.xml"))
    mi.render(scene, spp=1)  # compiles the kernels once
    best = None
    for _ in range(args.rounds):
        bm.reset_stats()
        t = time.perf_counter()
        img = mi.render(scene, spp=64)
        img.numpy()  # the render is done when its pixels are read
        wall = time.perf_counter() - t
        if best is None or wall < best[0]:
            best = (wall, dict(bm.stats))
    wall, st = best
    name = f"mitsuba/{args.model}/256x256-64spp"
    record(args, name, "render seconds", wall)
    record(args, name, "plugin seconds", st["seconds"])
    record(args, name, "plugin percent", 100.0 * st["seconds"] / wall)
    record(args, name, "plugin calls", st["calls"])
    record(args, name, "plugin Mlanes", st["lanes"] / 1e6)


if __name__ == "__main__":
    main()
