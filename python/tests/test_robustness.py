"""Issue 24: sizes without bounds are refused naming the option, the MOEA/D neighbourhood
default adapts to small populations, and tampered optimiser states never panic or hang."""

import json
import random
import threading

import pytest

import reentry
from reentry.distributed import local_cluster


def test_sizes_without_bounds_are_refused_naming_the_option():
    p = reentry.TestProblem("zdt1")
    with pytest.raises(Exception, match="population"):
        reentry.Moead(population=10**9).ask(p)
    with pytest.raises(Exception, match="population"):
        reentry.Nsga2(population=10**9).ask(p)
    with pytest.raises(ValueError, match="n = 1000000000000"):
        p.pareto_front(10**12)
    with pytest.raises(ValueError, match="workers = 0"):
        local_cluster(0)


def test_small_moead_population_needs_no_neighbours():
    p = reentry.TestProblem("zdt1")
    a = reentry.Moead(seed=1, population=8)
    reentry.evolve(a, p, 2)
    assert a.generation == 2
    with pytest.raises(Exception, match="--neighbours"):
        reentry.Moead(seed=1, population=8, neighbours=20).ask(p)


def _mutate(state, rng):
    nodes = []

    def walk(v, parent, key):
        if parent is not None:
            nodes.append((parent, key))
        if isinstance(v, dict):
            for k, x in v.items():
                walk(x, v, k)
        elif isinstance(v, list):
            for i, x in enumerate(v):
                walk(x, v, i)

    walk(state, None, None)
    parent, key = rng.choice(nodes)
    hostile = [0, -1, 999, 10**6, 1e300, -1e300, 0.5, "NaN", "x", None, [], {}, True]
    r = rng.randrange(len(hostile) + 2)
    if r == len(hostile) and isinstance(parent, dict):
        del parent[key]
    elif r == len(hostile) + 1 and isinstance(parent, list):
        parent.insert(key, parent[key])
    else:
        parent[key] = hostile[r % len(hostile)]


def test_tampered_states_never_panic_or_hang():
    p = reentry.TestProblem("constr")
    states = []
    for make in (
        lambda: reentry.Moead(seed=2, population=12, batch_size=5),
        lambda: reentry.Nsga2(seed=2, population=12),
        lambda: reentry.Mhaco(seed=2, population=12, ker=6),
    ):
        a = make()
        reentry.evolve(a, p, 2)
        xs = a.ask(p)
        a.tell(0, *p.evaluate(xs[0].tolist()))
        states.append((type(a), a.to_json()))
    rng = random.Random(20261201)
    refused = 0
    for case in range(60):
        cls, text = states[case % len(states)]
        state = json.loads(text)
        _mutate(state, rng)
        try:
            obj = cls.from_json(json.dumps(state))
        except ValueError as e:
            assert "field" in str(e), f"case {case}: {e}"
            refused += 1
            continue
        outcome = []

        def run():
            try:
                reentry.evolve(obj, p, 1)
                outcome.append("ok")
            except BaseException as e:  # a PanicException is a BaseException
                outcome.append(e)

        t = threading.Thread(target=run, daemon=True)
        t.start()
        t.join(60)
        assert outcome, f"case {case}: no answer in 60 s (hang)"
        e = outcome[0]
        assert e == "ok" or type(e).__name__ != "PanicException", f"case {case}: {e!r}"
        assert e == "ok" or isinstance(e, Exception), f"case {case}: {e!r}"
    assert refused > 20, refused
