"""Hypervolume of `host-sim optimize` over many seeds (standard library only; not part of CI).

Runs `host-sim optimize A --problem P --seed S [extra flags] --out DIR` for seeds
1..N (--first-seed F: F..F+N-1) and reads each run's summary.json (hypervolume of the reported
front, its source: population or archive; evaluations). Prints the median over the first ten
seeds, and the median, quartiles, mean, min, max over all N seeds, the evaluations per run, and
how many disjoint ten-seed blocks (F..F+9, F+10..F+19, ...) have a median at or above --goal.

    cargo build --release -p host-sim
    python3 scripts/hv_survey.py --algorithm moead --seeds 500 --goal 0.848
    python3 scripts/hv_survey.py --algorithm moead --seeds 500 --goal 0.848 -- --archive 100
    python3 scripts/hv_survey.py --algorithm moead --seeds 50 --first-seed 11 -- --resource-allocation --evaluations 25100
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--host-sim", default=os.path.join(os.path.dirname(__file__), "..", "target", "release", "host-sim"))
    ap.add_argument("--problem", default="zdt1")
    ap.add_argument("--algorithm", default="moead", help="host-sim optimize's subcommand (default moead); the extra flags are its own or the common ones")
    ap.add_argument("--seeds", type=int, default=100)
    ap.add_argument("--first-seed", type=int, default=1, help="seeds first..first+N-1 (default 1)")
    ap.add_argument("--goal", type=float, default=None)
    ap.add_argument("--csv", help="write one row per seed: seed,hypervolume,front_size,front_source")
    ap.add_argument("extra", nargs="*", help="further host-sim optimize flags (after --)")
    a = ap.parse_args()
    hv, rows = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(a.first_seed, a.first_seed + a.seeds):
            out = os.path.join(tmp, f"s{seed}")
            subprocess.run([a.host_sim, "optimize", a.algorithm, "--problem", a.problem,
                            "--seed", str(seed), "--out", out, *a.extra],
                           check=True, stdout=subprocess.DEVNULL)
            with open(os.path.join(out, "summary.json")) as f:
                s = json.load(f)
            hv.append(s["hypervolume"])
            rows.append((seed, s["hypervolume"], s["front_size"], s["front_source"], s["evaluations"]))
    if a.csv:
        with open(a.csv, "w") as f:
            f.write("seed,hypervolume,front_size,front_source,evaluations\n")
            for r in rows:
                f.write(",".join(map(str, r)) + "\n")
    q = statistics.quantiles(hv, n=4) if len(hv) >= 2 else [hv[0]] * 3
    sources = sorted({r[3] for r in rows})
    print(f"{a.algorithm} {a.problem} {' '.join(a.extra)} (front: {', '.join(sources)})")
    evals = sorted({r[4] for r in rows})
    print(f"  evaluations per run: {', '.join(map(str, evals))}")
    last = a.first_seed + a.seeds - 1
    if len(hv) >= 10:
        print(f"  seeds {a.first_seed}..{a.first_seed + 9}: median {statistics.median(hv[:10]):.4f}")
    print(f"  seeds {a.first_seed}..{last}: median {statistics.median(hv):.4f} q1 {q[0]:.4f} q3 {q[2]:.4f} "
          f"mean {statistics.fmean(hv):.4f} min {min(hv):.4f} max {max(hv):.4f}")
    if a.goal is not None and len(hv) >= 10:
        blocks = [statistics.median(hv[i:i + 10]) for i in range(0, len(hv) - 9, 10)]
        print(f"  ten-seed blocks (from seed {a.first_seed}) with median >= {a.goal}: {sum(b >= a.goal for b in blocks)}/{len(blocks)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
