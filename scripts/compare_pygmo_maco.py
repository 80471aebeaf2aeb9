#!/usr/bin/env python3
"""MHACO side by side with pygmo's `maco` (issue 9 performance setting).

ZDT1 with 30 variables, population 100, 250 generations (25,100 evaluations), seeds 1..10,
single thread: wall time per run and the hypervolume of the final non-dominated set w.r.t.
(1.1, 1.1) (true front 0.8767). pygmo runs with its defaults (ker 63, q 1, threshold 1,
n_gen_mark 7) and with n_gen_mark 15; host-sim runs `host-sim optimize mhaco`
(pagmo's defaults) and reports the wall time of the evolution alone from summary.json.
The criterion bench (`cargo bench -p host-sim --bench optim -- mhaco`) times both settings
of ours without process start-up.

Not part of CI. Set up once:
    python3 -m venv /tmp/venv-pygmo && /tmp/venv-pygmo/bin/pip install pygmo==2.20.0
Run from the repository root:
    cargo build --release -p host-sim
    /tmp/venv-pygmo/bin/python scripts/compare_pygmo_maco.py [--host-sim target/release/host-sim]
"""

import argparse
import json
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import pygmo as pg

GENERATIONS = 250
POPULATION = 100
SEEDS = range(1, 11)
REF = [1.1, 1.1]


def front_hv(fitness):
    # Points that do not strictly dominate the reference point add nothing (and pygmo's
    # hypervolume refuses them), as in host-sim.
    inside = [f for f in fitness if f[0] < REF[0] and f[1] < REF[1]]
    if not inside:
        return 0.0
    ndf = pg.non_dominated_front_2d(inside)
    return pg.hypervolume([inside[i] for i in ndf]).compute(REF)


def run_pygmo(seed, n_gen_mark):
    prob = pg.problem(pg.zdt(prob_id=1, param=30))
    pop = pg.population(prob, size=POPULATION, seed=seed)
    algo = pg.algorithm(pg.maco(gen=GENERATIONS, ker=63, n_gen_mark=n_gen_mark, seed=seed))
    start = time.perf_counter()
    pop = algo.evolve(pop)
    elapsed = time.perf_counter() - start
    return elapsed, front_hv(pop.get_f())


def run_host_sim(binary, seed):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run(
            [binary, "optimize", "mhaco", "--problem", "zdt1",
             "--population", str(POPULATION), "--generations", str(GENERATIONS),
             "--seed", str(seed), "--out", out],
            check=True, capture_output=True)
        summary = json.loads((Path(out) / "summary.json").read_text())
    return summary["wall_time_s"], summary["hypervolume"]


def report(name, results):
    times = [t for t, _ in results]
    hvs = sorted(h for _, h in results)
    print(f"{name:34} best {min(times) * 1e3:7.1f} ms, median {statistics.median(times) * 1e3:7.1f} ms;"
          f" hypervolume median {statistics.median(hvs):.4f} ({hvs[0]:.4f}-{hvs[-1]:.4f})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--host-sim", default="target/release/host-sim")
    args = parser.parse_args()
    print(f"pygmo {pg.__version__}; ZDT1 30 vars, population {POPULATION}, {GENERATIONS} generations, seeds 1-10", flush=True)
    for n_gen_mark in (7, 15):
        report(f"pygmo maco ker 63 n_gen_mark {n_gen_mark}", [run_pygmo(s, n_gen_mark) for s in SEEDS])
    if Path(args.host_sim).exists():
        report("host-sim mhaco (pagmo defaults)", [run_host_sim(args.host_sim, s) for s in SEEDS])
    else:
        print(f"{args.host_sim} not found: build it with cargo build --release -p host-sim")


if __name__ == "__main__":
    main()
