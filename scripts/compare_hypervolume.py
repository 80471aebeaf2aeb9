#!/usr/bin/env python3
"""Side-by-side exact hypervolume: host-sim against moocore and pygmo on identical fronts.

Not part of CI. Setup (once; pygmo is optional, its columns are "-" without it):
    python3 -m venv .venv-peers && .venv-peers/bin/pip install moocore==0.3.2 pygmo numpy
    cargo build --release -p host-sim
Run from the workspace root:
    .venv-peers/bin/python scripts/compare_hypervolume.py [--repeat 51] [--rounds 5] [--out /tmp/hv-fronts]
    [--dims 3,4,5,6,7,8] [--contrib-dims 3,4,5] [--contrib-repeat 5]

It writes each random front (points on the unit sphere or the unit simplex, non-negative
orthant, reference point 1.1 in every objective) as CSV, times moocore.hypervolume and
pygmo.hypervolume(...).compute (median of --repeat calls, in-process), runs
`host-sim hypervolume FRONT.csv --ref ... --repeat K` on the same CSV (median it reports), and
checks that the three values agree to 1e-12 relative. Prints a Markdown table. On a shared
machine the wall-clock medians also count the time a process waits for a core, so the table
also gives CPU time per computation: moocore's median `time.process_time`, host-sim's from
the child CPU time of a run with 2K repeats less one with K.
`--check-pagmo7 DIR` also prints moocore's and pygmo's value for pagmo2's 7-objective front.
"""

import argparse
import pathlib
import resource
import subprocess
import sys
import time

import moocore
import numpy as np

try:
    import pygmo
except ImportError:  # pygmo is optional
    pygmo = None

# Front size per dimension: the sizes up to 5-D; above, sizes at which moocore takes
# well under a second per call (its time grows steeply with the dimension).
SIZES = {3: 2000, 4: 1000, 5: 1000, 6: 300, 7: 100, 8: 50}
# Front size per dimension for all exclusive contributions (moocore's 4-D and 5-D
# hv_contributions recompute the hypervolume without each point: ~1 s at 4-D n = 1000).
CONTRIB_SIZES = {3: 2000, 4: 1000, 5: 300}


def front(kind, d, n, seed):
    rng = np.random.default_rng(seed)
    if kind == "sphere":
        v = np.abs(rng.standard_normal((n, d)))
        return v / np.linalg.norm(v, axis=1, keepdims=True)
    v = rng.exponential(size=(n, d))
    return v / v.sum(axis=1, keepdims=True)


def median_time(f, repeat, clock=time.perf_counter):
    times = []
    value = None
    for _ in range(repeat):
        t = clock()
        value = f()
        times.append(clock() - t)
    return value, float(np.median(times))


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def ours_cpu(binary, path, ref, repeat):
    """CPU time of one computation: the child CPU time of a run with 2K repeats less that of
    a run with K (start-up and parsing cancel). On a loaded machine the wall-clock median
    also counts the time the process waits for a core; CPU time does not."""
    cpu = []
    for k in (repeat, 2 * repeat):
        t = children_cpu()
        ours(binary, path, ref, k)
        cpu.append(children_cpu() - t)
    return max(cpu[1] - cpu[0], 0.0) / repeat


def ours(binary, path, ref, repeat):
    out = subprocess.run(
        [binary, "hypervolume", str(path), "--ref", ",".join(repr(float(r)) for r in ref),
         "--repeat", str(repeat)],
        check=True, capture_output=True, text=True).stdout
    kv = dict(line.split(": ", 1) for line in out.splitlines() if ": " in line)
    return float(kv["hypervolume"]), float(kv["median_time_s"])


def ours_contributions(binary, path, ref, repeat):
    out = subprocess.run(
        [binary, "hypervolume", str(path), "--ref", ",".join(repr(float(r)) for r in ref),
         "--contributions", "--repeat", str(repeat)],
        check=True, capture_output=True, text=True).stdout
    kv = dict(line.split(": ", 1) for line in out.splitlines() if ": " in line)
    rows = [line.split(",") for line in out.splitlines()
            if line and line[0].isdigit() and "," in line]
    values = np.array([float(v) for _, v in sorted((int(i), v) for i, v in rows)])
    return values, float(kv["contributions_median_time_s"])


def check_pagmo7(data_dir):
    tok = (pathlib.Path(data_dir) / "testcases" / "c_max_t1_d7_n64").read_text().split()
    v = [float(x) for x in tok]
    d, n = int(v[1]), int(v[2])
    ref = np.array(v[3:3 + d])
    pts = np.array(v[3 + d:3 + d + n * d]).reshape(n, d)
    print(f"pagmo2 c_max_t1_d7_n64: file {v[3 + d + n * d]!r}, "
          f"moocore {moocore.hypervolume(pts, ref=ref)!r}, "
          f"pygmo {pygmo.hypervolume(pts).compute(ref)!r}" if pygmo else "pygmo -")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=21)
    ap.add_argument("--out", default="/tmp/hv-fronts")
    ap.add_argument("--bin", default="target/release/host-sim")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=1,
                    help="measure every case this many times and keep each tool's best "
                         "median (damps the noise of a shared machine)")
    ap.add_argument("--check-pagmo7", metavar="DIR")
    ap.add_argument("--dims", default="3,4,5,6,7,8",
                    help="hypervolume cases (comma-separated dimensions, sizes from SIZES)")
    ap.add_argument("--contrib-dims", default="3,4,5",
                    help="all-contributions cases (dimensions, sizes from CONTRIB_SIZES)")
    ap.add_argument("--contrib-repeat", type=int, default=5,
                    help="repeats of the contributions timings (moocore's take ~1 s at 4-D)")
    ap.add_argument("--no-pygmo", action="store_true", help="skip pygmo even if installed")
    a = ap.parse_args()
    use_pygmo = pygmo is not None and not a.no_pygmo
    dims = [int(x) for x in a.dims.split(",") if x]
    cdims = [int(x) for x in a.contrib_dims.split(",") if x]
    if a.check_pagmo7:
        check_pagmo7(a.check_pagmo7)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    pv = pygmo.__version__ if use_pygmo else "-"
    print(f"moocore {moocore.__version__}, pygmo {pv}, numpy {np.__version__}; "
          f"median of {a.repeat} runs (best of {a.rounds} rounds), times in ms")
    print()
    print("| front | d | n | hypervolume | host-sim | moocore | pygmo | host-sim CPU | moocore CPU "
          "| CPU ratio | max rel. diff |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    worst = 0.0
    for d in dims:
        n = SIZES[d]
        for kind in ("sphere", "simplex"):
            pts = front(kind, d, n, a.seed)
            ref = np.full(d, 1.1)
            path = out / f"{kind}_d{d}_n{n}.csv"
            np.savetxt(path, pts, delimiter=",", fmt="%.17g")
            pts = np.loadtxt(path, delimiter=",")  # exactly what host-sim reads
            hv_obj = pygmo.hypervolume(pts) if use_pygmo else None
            t_m = t_p = t_o = c_m = c_o = float("inf")
            hv_p = None
            for _ in range(a.rounds):  # rounds interleave the three tools
                hv_m, t = median_time(lambda: moocore.hypervolume(pts, ref=ref), a.repeat)
                t_m = min(t_m, t)
                if hv_obj is not None:
                    hv_p, t = median_time(lambda: hv_obj.compute(ref), a.repeat)
                    t_p = min(t_p, t)
                hv_o, t = ours(a.bin, path, ref, a.repeat)
                t_o = min(t_o, t)
                _, t = median_time(lambda: moocore.hypervolume(pts, ref=ref), a.repeat,
                                   time.process_time)
                c_m = min(c_m, t)
                c_o = min(c_o, ours_cpu(a.bin, path, ref, a.repeat))
            others = [hv_m] + ([hv_p] if hv_p is not None else [])
            rel = max(abs(hv_o - v) for v in others) / abs(hv_m)
            worst = max(worst, rel)
            tp = f"{t_p * 1e3:.3f}" if hv_p is not None else "-"
            print(f"| {kind} | {d} | {n} | {hv_o:.15g} | {t_o * 1e3:.3f} | {t_m * 1e3:.3f} "
                  f"| {tp} | {c_o * 1e3:.3f} | {c_m * 1e3:.3f} | {c_o / c_m:.2f} | {rel:.1e} |",
                  flush=True)
    print()
    print("All exclusive contributions: host-sim `--contributions` against "
          "moocore.hv_contributions (wall-clock medians, best of the rounds); the difference "
          "is relative to the hypervolume.")
    print()
    print("| front | d | n | host-sim | moocore | ratio | max diff / HV |")
    print("|---|---|---|---|---|---|---|")
    for d in cdims:
        n = CONTRIB_SIZES[d]
        for kind in ("sphere", "simplex"):
            path = out / f"{kind}_d{d}_n{n}.csv"
            np.savetxt(path, front(kind, d, n, a.seed), delimiter=",", fmt="%.17g")
            pts = np.loadtxt(path, delimiter=",")
            ref = np.full(d, 1.1)
            t_m = t_o = float("inf")
            for _ in range(a.rounds):
                c_m, t = median_time(lambda: moocore.hv_contributions(pts, ref=ref),
                                     a.contrib_repeat)
                t_m = min(t_m, t)
                c_o, t = ours_contributions(a.bin, path, ref, a.contrib_repeat)
                t_o = min(t_o, t)
            rel = float(np.max(np.abs(c_o - c_m))) / moocore.hypervolume(pts, ref=ref)
            worst = max(worst, rel)
            print(f"| {kind} | {d} | {n} | {t_o * 1e3:.3f} | {t_m * 1e3:.3f} | {t_o / t_m:.3f} "
                  f"| {rel:.1e} |", flush=True)
    print()
    ok = worst <= 1e-12
    print(f"values agree to 1e-12 relative: {'yes' if ok else 'NO'} (worst {worst:.1e})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
