# SPDX-License-Identifier: MIT
"""`make bench` (Python part): brdffit.eval on 1,000,000 direction pairs from
NumPy against the same brdffit_eval_batch call from C (bench_eval_c, linked to
the same libbrdffit.so), per model, on the same pairs.

Rounds alternate C and Python (load bursts on a shared machine hit both); each
side's figure is the fastest call over all rounds.  The Python call is the
plain brdffit.eval(model, params, wi, wo) (it allocates its (n, 3) result each
time); the C call writes into a buffer allocated once.  Target: Python within
1.5x of C.  With --record SCRIPT (bench/record) each model's figures are
appended to bench/results.tsv as eval/MODEL/N-pairs.

Usage: eval_numpy.py BENCH_EVAL_C [--pairs N] [--rounds R] [--reps K] [--models a,b]
                     [--record SCRIPT]
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import brdffit  # noqa: E402

# A typical parameter set per model (the alum-bronze rows of Ngan et al. where known).
PARAMS = {
    "ward": [0.0851, 0.0586, 0.0294, 0.0484, 0.0274, 0.0135, 0.0357],
    "ward-duer": [0.0856, 0.0585, 0.0291, 0.032, 0.0189, 0.00986, 0.0374],
    "blinn-phong": [0.0864, 0.0597, 0.0302, 0.015, 0.00818, 0.00381, 1290.0],
    "lafortune": [0.0923, 0.0625, 0.0311, 0.322, 0.193, 0.105, -0.579, 0.574, 630.0],
    "cook-torrance": [0.0886, 0.0602, 0.0299, 0.118, 0.0698, 0.0371, 0.203, 0.0367],
    "ashikhmin-shirley": [0.0889, 0.0604, 0.03, 0.117, 0.0693, 0.0368, 0.929, 2360.0],
    "he": [0.0851, 0.0586, 0.0294, 0.3, 0.2, 0.1, 24.0, 0.514, 2.33],
    "ggx": [0.0886, 0.0602, 0.0299, 0.118, 0.0698, 0.0371, 0.9, 0.05],
}


def hemisphere(rng, n):
    """n directions uniform on the upper hemisphere."""
    z = rng.uniform(0.0, 1.0, n)
    phi = rng.uniform(0.0, 2 * np.pi, n)
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def record(script, benchmark, figures):
    """Each (metric, value) of figures appended through script (argv, no shell)."""
    for metric, value in figures:
        done = subprocess.run([script, benchmark, metric, f"{value:.6g}"], check=False)
        if done.returncode != 0:
            print(f"bench: {benchmark} {metric}: {script} exited {done.returncode}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bench_eval_c")
    ap.add_argument("--pairs", type=int, default=1_000_000)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--models", default=None)
    ap.add_argument("--record", default=None)
    args = ap.parse_args()

    lib = brdffit.load_library()
    names = args.models.split(",") if args.models else [m.name for m in brdffit.models()]
    rng = np.random.default_rng(2005)
    wi = hemisphere(rng, args.pairs)
    wo = hemisphere(rng, args.pairs)
    print(f"Python eval vs C eval_batch: {args.pairs:,} direction pairs (uniform upper "
          f"hemisphere), fastest of {args.rounds} rounds x {args.reps} calls, alternating")
    print(f"library {lib.path} ({lib.version}), Python {sys.version.split()[0]}, "
          f"NumPy {np.__version__}")
    print(f"{'model':<18} {'C ms':>9} {'Python ms':>10} {'ratio':>7}")
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "pairs.bin")
        with open(path, "wb") as f:
            np.array([args.pairs], dtype=np.uint64).tofile(f)
            wi.tofile(f)
            wo.tofile(f)
        for name in names:
            if name not in PARAMS:
                print(f"{name:<18} (no parameter set in this bench)")
                continue
            params = PARAMS[name]
            c_best = py_best = float("inf")
            for _ in range(args.rounds):
                out = subprocess.run(
                    [args.bench_eval_c, path, str(args.reps), name] + [repr(x) for x in params],
                    check=True, capture_output=True, text=True).stdout
                c_best = min(c_best, float(out))
                for _ in range(args.reps):
                    t0 = time.perf_counter()
                    brdffit.eval(name, params, wi, wo)
                    py_best = min(py_best, (time.perf_counter() - t0) * 1e3)
            ratio = py_best / c_best
            worst = max(worst, ratio)
            print(f"{name:<18} {c_best:9.2f} {py_best:10.2f} {ratio:6.3f}x", flush=True)
            if args.record:
                record(args.record, f"eval/{name}/{args.pairs}-pairs",
                       [("C ms", c_best), ("Python ms", py_best), ("Python/C ratio", ratio)])
    verdict = "met" if worst <= 1.5 else "NOT met"
    print(f"worst ratio {worst:.3f}x (target <= 1.5x: {verdict})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
