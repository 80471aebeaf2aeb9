#!/usr/bin/env python3
"""Print pygmo 2.20 objective values of ZDT1-4, 6 and DTLZ1-7 (3 objectives) at pseudo-random
decisions, as the Rust table of `validate_pygmo_zdt_and_dtlz_objectives`
(host-sim/src/optim/problems/mod.rs). Not part of CI; venv as in scripts/compare_pygmo.py."""
import pygmo as pg, numpy as np
rng = np.random.default_rng(12345)
out = []
for pid, dim in [(1,30),(2,30),(3,30),(4,10),(6,10)]:
    p = pg.problem(pg.zdt(pid, dim))
    lb, ub = p.get_bounds()
    for _ in range(2):
        x = lb + (ub - lb) * np.round(rng.random(dim), 3)
        out.append(("zdt%d" % pid, x.tolist(), p.fitness(x).tolist()))
for pid, dim in [(1,7),(2,12),(3,12),(4,12),(5,12),(6,12),(7,22)]:
    p = pg.problem(pg.dtlz(pid, dim, 3))
    for _ in range(2):
        x = np.round(rng.random(dim), 3)
        out.append(("dtlz%d" % pid, x.tolist(), p.fitness(x).tolist()))
for name, x, f in out:
    print(f'    ("{name}", &[{", ".join(repr(v) for v in x)}], &[{", ".join(repr(v) for v in f)}]),')
