#!/usr/bin/env python3
"""Side-by-side comparison of host-sim's optimisers with pygmo on the same problems and seeds.

Not part of CI. Setup (once):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pygmo==2.20 moocore==0.3.2 numpy
    cargo build --release -p host-sim

Run:

    /tmp/venv/bin/python scripts/compare_pygmo.py            # ZDT1, MOEA/D and NSGA-II, seeds 1..10
    /tmp/venv/bin/python scripts/compare_pygmo.py --problems zdt1 zdt2 zdt3 zdt4 zdt6 --repeats 5
    /tmp/venv/bin/python scripts/compare_pygmo.py --repeats 1 --seeds 500 --tools pygmo --csv /tmp/pygmo.csv

`--tools` runs only the tools named; `--csv FILE` also writes one row per seed (hypervolume,
best wall time, CPU time) for `scripts/compare_distributions.py`.

For every (problem, algorithm, seed) both tools run `--repeats` times; the time of a seed is
the best of its repeats (wall time of the evolution alone: pygmo's `algorithm.evolve`,
host-sim's `wall_time_s` from summary.json, which also includes the initial population's
evaluations). Printed: median and best of those times over the seeds; the median CPU time
(pygmo: process time of `evolve`; host-sim: user + system time of the whole `host-sim optimize`
process, start-up and output included, so an upper bound); and the median, min and max
hypervolume (moocore, reference point (1.1, 1.1)) of the final non-dominated feasible
front. host-sim's own hypervolume is checked against moocore's on every run.
"""

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import moocore
import numpy as np
import pygmo as pg

ZDT_DIM = {"zdt1": 30, "zdt2": 30, "zdt3": 30, "zdt4": 10, "zdt6": 10}
REF = [1.1, 1.1]


def pygmo_run(problem, algorithm, pop_size, gens, seed):
    prob = pg.problem(pg.zdt(int(problem[3:]), ZDT_DIM[problem]))
    pop = pg.population(prob, pop_size, seed=seed)
    if algorithm == "moead":
        algo = pg.algorithm(pg.moead(gen=gens, seed=seed))
    else:
        algo = pg.algorithm(pg.nsga2(gen=gens, seed=seed))
    c0 = time.process_time()
    t0 = time.perf_counter()
    pop = algo.evolve(pop)
    dt = time.perf_counter() - t0
    cpu = time.process_time() - c0
    return dt, front_hv(pop.get_f()), cpu


def front_hv(f):
    f = np.asarray(f, dtype=float)
    nd = f[moocore.is_nondominated(f)]
    return float(moocore.hypervolume(nd, ref=REF))


def ours_run(exe, problem, algorithm, pop_size, gens, seed):
    with tempfile.TemporaryDirectory() as d:
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(
            [exe, "optimize", algorithm, "--problem", problem,
             "--population", str(pop_size), "--generations", str(gens), "--seed", str(seed),
             "--ref", ",".join(map(str, REF)), "--out", d],
            check=True, stdout=subprocess.DEVNULL)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (r1.ru_utime + r1.ru_stime) - (r0.ru_utime + r0.ru_stime)
        with open(os.path.join(d, "summary.json")) as fh:
            s = json.load(fh)
        front = np.loadtxt(os.path.join(d, "front.csv"), delimiter=",", skiprows=1, ndmin=2)
        hv = front_hv(front) if front.size else 0.0
        if abs(hv - s["hypervolume"]) > 1e-12 * max(1.0, hv):
            sys.exit(f"hypervolume mismatch {problem} {algorithm} seed {seed}: "
                     f"host-sim {s['hypervolume']!r} moocore {hv!r}")
        return s["wall_time_s"], hv, cpu


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--host-sim", default=os.path.join(os.path.dirname(__file__), "..", "target", "release", "host-sim"))
    ap.add_argument("--problems", nargs="+", default=["zdt1"], choices=sorted(ZDT_DIM))
    ap.add_argument("--algorithms", nargs="+", default=["moead", "nsga2"], choices=["moead", "nsga2"])
    ap.add_argument("--population", type=int, default=100)
    ap.add_argument("--generations", type=int, default=250)
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--tools", nargs="+", default=["pygmo", "host-sim"], choices=["pygmo", "host-sim"])
    ap.add_argument("--csv", help="also write one row per (problem, algorithm, tool, seed): "
                    "hypervolume, best wall time and CPU time")
    a = ap.parse_args()
    rows = []
    print(f"pygmo {pg.__version__}, moocore {moocore.__version__}; population {a.population}, "
          f"{a.generations} generations, seeds 1..{a.seeds}, best of {a.repeats} per seed")
    print(f"{'problem':8} {'algorithm':9} {'tool':9} {'median ms':>10} {'best ms':>8} {'cpu ms':>7} "
          f"{'median hv':>10} {'min hv':>8} {'max hv':>8}")
    for problem in a.problems:
        for algorithm in a.algorithms:
            for tool, fn in (("pygmo", lambda s: pygmo_run(problem, algorithm, a.population, a.generations, s)),
                             ("host-sim", lambda s: ours_run(a.host_sim, problem, algorithm, a.population, a.generations, s))):
                if tool not in a.tools:
                    continue
                times, hvs, cpus = [], [], []
                for seed in range(1, a.seeds + 1):
                    runs = [fn(seed) for _ in range(a.repeats)]
                    times.append(min(r[0] for r in runs))
                    cpus.append(min(r[2] for r in runs))
                    hvs.append(runs[0][1])
                    rows.append((problem, algorithm, tool, seed, hvs[-1], times[-1], cpus[-1]))
                print(f"{problem:8} {algorithm:9} {tool:9} {1e3 * statistics.median(times):10.1f} "
                      f"{1e3 * min(times):8.1f} {1e3 * statistics.median(cpus):7.1f} "
                      f"{statistics.median(hvs):10.4f} {min(hvs):8.4f} {max(hvs):8.4f}",
                      flush=True)
    if a.csv:
        with open(a.csv, "w") as fh:
            fh.write("problem,algorithm,tool,seed,hypervolume,wall_s,cpu_s\n")
            for r in rows:
                fh.write(",".join(map(str, r)) + "\n")


if __name__ == "__main__":
    main()
