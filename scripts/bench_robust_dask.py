"""Throughput of a robust design run (issue 25 item 2): the example robust run
(examples/optimize-robust-srm.toml: the SRM stack's campaign of K dispersed flights per
candidate) flown by host-sim's threads and on Dask LocalClusters, each run writing the same run
directory (checked: the checkpoints are equal). Prints flights per second and per core, and the
cost of a 64 x 128 run with K = 100 extrapolated from the best per-core rate.

    python scripts/bench_robust_dask.py [--population 8] [--generations 2] [--cases 20]
        [--threads 1,2] [--workers 1,2]

Needs the reentry package (python/) and dask.distributed. Timings are the runs' evolution
wall times (`wall_time_s`: the final member campaigns are not counted)."""

import argparse
import os
import tempfile
from pathlib import Path

import reentry
from dask.distributed import Client
from reentry.distributed import local_cluster, run_design_on_dask

REPO = Path(__file__).resolve().parents[1]


def run_file(directory: Path, population: int, generations: int, cases: int, threads: int) -> Path:
    base = REPO / "examples" / "srm-glide-replanning.toml"
    lines = []
    for line in (REPO / "examples" / "optimize-robust-srm.toml").read_text().splitlines():
        key = line.split("=")[0].strip()
        line = {
            "population": f"population = {population}",
            "generations": f"generations = {generations}",
            "cases": f"cases = {cases}",
            "threads": f"threads = {threads}",
            "base": f'base = "{base}"',
        }.get(key, line)
        lines.append(line)
    p = directory / f"robust-{threads}.toml"
    p.write_text("\n".join(lines) + "\n")
    return p


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--population", type=int, default=8)
    ap.add_argument("--generations", type=int, default=2)
    ap.add_argument("--cases", type=int, default=20)
    ints = lambda s: [int(x) for x in s.split(",")]  # noqa: E731
    ap.add_argument("--threads", type=ints, default=[1, 2])
    ap.add_argument("--workers", type=ints, default=[1, 2])
    a = ap.parse_args()
    flights = a.population * (a.generations + 1) * a.cases
    rows = []
    checkpoints = set()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for t in a.threads:
            out = tmp / f"threads-{t}"
            last = reentry.run_design(out, run_file(tmp, a.population, a.generations, a.cases, t))
            rows.append((f"host-sim, {t} thread(s)", t, last["wall_time_s"]))
            checkpoints.add((out / "checkpoint.json").read_text())
        cfg = run_file(tmp, a.population, a.generations, a.cases, 1)
        for w in a.workers:
            out = tmp / f"dask-{w}"
            with local_cluster(w) as cluster, Client(cluster) as client:
                last = run_design_on_dask(out, cfg, client=client)
            rows.append((f"Dask, {w} worker process(es)", w, last["wall_time_s"]))
            checkpoints.add((out / "checkpoint.json").read_text())
    print(f"robust SRM run: population {a.population}, {a.generations} generations, K = {a.cases}: "
          f"{flights} campaign flights; machine load average {os.getloadavg()[0]:.1f}")
    print("| evaluation | wall [s] | flights/s | flights/s per core |")
    print("| --- | --- | --- | --- |")
    for name, cores, wall in rows:
        print(f"| {name} | {wall:.2f} | {flights / wall:.1f} | {flights / wall / cores:.1f} |")
    print(f"same run directory everywhere (checkpoint.json): {len(checkpoints) == 1}")
    best = max(flights / wall / cores for _, cores, wall in rows)
    big = 64 * 129 * 100
    print(f"64 x 128 with K = 100: {big} flights; at {best:.1f} flights/s per core: "
          f"{big / best / 3600:.1f} core-hours, {big / best / 3600 / 64:.2f} h on 64 cores "
          "(linear scaling assumed)")
    return 0 if len(checkpoints) == 1 else 1


if __name__ == "__main__":
    raise SystemExit(main())
