# SPDX-License-Identifier: MIT
"""`make bench-gltf`: the glTF models beside GGX on the 100 MERL tables.

Runs `brdffit batch` over the tables ../shared/tools/merl-table writes, with
--model ggx,gltf,gltf-ext at the standard scale (no renders or plots), then
prints and records (bench/record) what docs/gltf.md reports: each model's
median Error, the median and quartiles of the glTF models' Error over GGX's
on the same table, on how many tables each ends with metallic 0, 1 or
between and which parameters end on a bound, and the fits' median seconds.

usage: gltf_database.py BRDFFIT OUTDIR [--record] [--materials N] [--read-only]
(--read-only: the figures of the batch already in OUTDIR, none run)
"""
import csv
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = ("ggx", "gltf", "gltf-ext")


def tables(n):
    tool = os.path.join(HERE, "..", "..", "shared", "tools", "merl-table")
    names = subprocess.run([tool, "--list"], check=True, capture_output=True, text=True).stdout.split()
    names = names[:n] if n else names
    paths = subprocess.run([tool, *names], check=True, capture_output=True, text=True).stdout.split()
    return paths


def read_fits(path):
    with open(path, newline="") as f:
        rows = csv.DictReader((line for line in f if not line.startswith("#")), delimiter="\t")
        fits = {}
        for r in rows:
            if r["status"] in ("ok", "limit"):
                fits.setdefault(r["material"], {})[r["model"]] = r
    return {m: v for m, v in fits.items() if all(k in v for k in MODELS)}


def figures(fits, wall):
    mats = sorted(fits)
    err = {k: [float(fits[m][k]["error"]) for m in mats] for k in MODELS}
    out = [("database-gltf/ggx,gltf,gltf-ext", "tables count", len(mats))]
    if wall == wall:  # not NaN: the batch ran here
        out.insert(0, ("database-gltf/ggx,gltf,gltf-ext", "wall seconds", wall))
    for k in MODELS:
        out.append((f"database-gltf/{k}", "median Error", statistics.median(err[k])))
        out.append((f"database-gltf/{k}", "median fit seconds",
                    statistics.median(float(fits[m][k]["seconds"]) for m in mats)))
    # GGX's lobe at normal incidence (s F0) and at grazing (s), green channel
    s_f0 = statistics.quantiles([float(fits[m]["ggx"]["s_g"]) * float(fits[m]["ggx"]["p0"])
                                 for m in mats], n=4)
    out += [("database-gltf/ggx", "s F0 green median", s_f0[1]),
            ("database-gltf/ggx", "s F0 green lower quartile", s_f0[0]),
            ("database-gltf/ggx", "s F0 green upper quartile", s_f0[2]),
            ("database-gltf/ggx", "s above 1 (some channel) count",
             sum(max(float(fits[m]["ggx"][c]) for c in ("s_r", "s_g", "s_b")) > 1 for m in mats))]
    for k in ("gltf", "gltf-ext"):
        ratio = [a / b for a, b in zip(err[k], err["ggx"])]
        q = statistics.quantiles(ratio, n=4)
        out += [(f"database-gltf/{k}", "Error / ggx's median ratio", q[1]),
                (f"database-gltf/{k}", "Error / ggx's lower quartile ratio", q[0]),
                (f"database-gltf/{k}", "Error / ggx's upper quartile ratio", q[2]),
                (f"database-gltf/{k}", "tables within 5% of ggx's Error count",
                 sum(r < 1.05 for r in ratio)),
                (f"database-gltf/{k}", "tables below ggx's Error count", sum(r < 1.0 for r in ratio))]
        metal = [float(fits[m][k]["p0"]) for m in mats]
        out += [(f"database-gltf/{k}", "metallic 0 count", sum(x == 0.0 for x in metal)),
                (f"database-gltf/{k}", "metallic 1 count", sum(x == 1.0 for x in metal)),
                (f"database-gltf/{k}", "metallic between count", sum(0.0 < x < 1.0 for x in metal))]
        bound = {}
        for m in mats:
            for name in fits[m][k]["at_bound"].split(","):
                if name and name != "-":
                    bound[name] = bound.get(name, 0) + 1
        for name in sorted(bound):
            out.append((f"database-gltf/{k}", f"{name} on a bound count", bound[name]))
    return out


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    brdffit, outdir = argv[1], argv[2]
    record = "--record" in argv
    n = int(argv[argv.index("--materials") + 1]) if "--materials" in argv else 0
    wall = float("nan")
    if "--read-only" not in argv:
        paths = tables(n)
        t0 = time.monotonic()
        subprocess.run([brdffit, "batch", *paths, "--model", ",".join(MODELS), "--no-render",
                        "--no-plot", "--out", outdir], check=True, stdout=subprocess.DEVNULL)
        wall = time.monotonic() - t0
    for bench, metric, value in figures(read_fits(os.path.join(outdir, "fits.tsv")), wall):
        print(f"{bench:32s} {metric:42s} {value:.6g}")
        if record:
            subprocess.run([os.path.join(HERE, "record"), bench, metric, f"{value:.6g}"], check=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
