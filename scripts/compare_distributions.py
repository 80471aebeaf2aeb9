#!/usr/bin/env python3
"""Hypervolume distributions of the per-seed rows written by `compare_pygmo.py --csv`.

Not part of CI. For every (algorithm, tool, file): number of seeds, median, quartiles, mean
and standard deviation of the final hypervolume, the median of seeds 1..10, and how many
disjoint blocks of ten consecutive seeds (1-10, 11-20, ...) have a median at or above the
issue's goal (MOEA/D 0.848, NSGA-II 0.869). Pairs of samples of the same algorithm are
compared with a two-sided Mann-Whitney U test (needs scipy).

    /tmp/venv/bin/python scripts/compare_pygmo.py --repeats 1 --seeds 500 --tools pygmo --csv /tmp/pygmo.csv
    /tmp/venv/bin/python scripts/compare_pygmo.py --repeats 1 --seeds 500 --tools host-sim --csv /tmp/ours.csv
    /tmp/venv/bin/python scripts/compare_distributions.py /tmp/pygmo.csv /tmp/ours.csv
"""

import csv
import itertools
import os
import statistics
import sys

GOAL = {"moead": 0.848, "nsga2": 0.869}


def load(path):
    samples = {}
    with open(path) as fh:
        for row in csv.DictReader(fh):
            key = (row["algorithm"], row["tool"], os.path.basename(path))
            samples.setdefault(key, []).append((int(row["seed"]), float(row["hypervolume"])))
    return {k: [hv for _, hv in sorted(v)] for k, v in samples.items()}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    samples = {}
    for path in sys.argv[1:]:
        samples.update(load(path))
    print(f"{'algorithm':9} {'tool':9} {'file':24} {'seeds':>5} {'median':>7} {'q1':>7} {'q3':>7} "
          f"{'mean':>7} {'sd':>7} {'1..10':>7}  blocks >= goal")
    for (alg, tool, name), hv in sorted(samples.items()):
        q1, _, q3 = statistics.quantiles(hv, n=4)
        blocks = [statistics.median(hv[i:i + 10]) for i in range(0, len(hv) - 9, 10)]
        hits = sum(b >= GOAL.get(alg, float("inf")) for b in blocks)
        print(f"{alg:9} {tool:9} {name:24} {len(hv):5d} {statistics.median(hv):7.4f} {q1:7.4f} {q3:7.4f} "
              f"{statistics.mean(hv):7.4f} {statistics.stdev(hv):7.4f} {statistics.median(hv[:10]):7.4f}  "
              f"{hits}/{len(blocks)}")
    try:
        from scipy.stats import mannwhitneyu
    except ImportError:
        print("(scipy not installed: no Mann-Whitney tests)")
        return
    for a, b in itertools.combinations(sorted(samples), 2):
        if a[0] == b[0]:
            p = mannwhitneyu(samples[a], samples[b]).pvalue
            print(f"Mann-Whitney {a[0]}: {a[1]} ({a[2]}) vs {b[1]} ({b[2]}): p = {p:.3f}")


if __name__ == "__main__":
    main()
