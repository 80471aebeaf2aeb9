"""The optimisers through ask/tell: the Python loop equals host-sim's own runs bit for bit."""

import json
import pickle
import random
from pathlib import Path

import numpy as np
import pytest

import reentry
from reentry.distributed import _assemble


def same_state(a, b):
    pa, pb = a.population, b.population
    for u, v in zip(pa, pb):
        assert u.shape == v.shape
        assert np.array_equal(u.view(np.uint64), v.view(np.uint64)), "populations differ in bits"
    assert (a.generation, a.evaluations) == (b.generation, b.evaluations)
    assert a.to_json() == b.to_json()


@pytest.mark.parametrize(
    "make",
    [
        lambda: reentry.Moead(seed=3, population=30, batch_size=1),
        lambda: reentry.Moead(seed=3, population=30, batch_size=7),
        lambda: reentry.Moead(seed=3, population=30, operator="sbx", eta_c=15.0, archive=40),
        lambda: reentry.Nsga2(seed=3, population=24),
        lambda: reentry.Nsga2(seed=3, population=24, archive=30),
        lambda: reentry.Mhaco(seed=3, population=20, ker=10),
        lambda: reentry.Mhaco(
            seed=3, population=20, ker=10,
            constraints={"as-objectives": {"scales": None, "cap": 2.0, "penalty": 0.5}},
        ),
        lambda: reentry.from_options(
            3, algorithm="scea", population=20, neighbours=5, batch_size=3, archive=12
        ),
    ],
    ids=[
        "moead-steady", "moead-batch7", "moead-sbx-archive", "nsga2", "nsga2-archive", "mhaco",
        "mhaco-constraints-as-objectives", "scea",
    ],
)
@pytest.mark.parametrize("name", ["zdt1", "constr"])
def test_python_loop_equals_rust_evolve(make, name):
    p = reentry.TestProblem(name)
    py, rs = make(), make()
    reentry.evolve(py, p, 8)
    rs.evolve_in_rust(p, 8)
    same_state(py, rs)


def test_shuffled_tells_give_the_same_run():
    p = reentry.TestProblem("dtlz2", 3)
    a, b = reentry.Moead(seed=5, population=28, batch_size=10), reentry.Moead(seed=5, population=28, batch_size=10)
    rng = random.Random(1)
    while a.generation < 5:
        xs = a.ask(p)
        evals = p.evaluate_batch(xs.tolist())
        order = list(range(len(xs)))
        rng.shuffle(order)
        for i in order:
            a.tell(i, *evals[i])
    reentry.evolve(b, p, 5 - b.generation if b.is_initialised else 5)
    b.evolve_in_rust(p, a.generation - b.generation)
    same_state(a, b)


def test_equals_host_sim_optimize_population_csv(host_sim, tmp_path):
    host_sim(
        "optimize", "--problem", "zdt2", "nsga2", "--population", "20",
        "--generations", "6", "--seed", "9", "--out", tmp_path,
    )
    rows = (tmp_path / "population.csv").read_text().splitlines()[1:]
    expected = np.array([[float(v) for v in r.split(",")] for r in rows])
    a = reentry.Nsga2(seed=9, population=20)
    reentry.evolve(a, reentry.TestProblem("zdt2"), 6)
    pop = a.population
    got = np.hstack([pop.x, pop.f, pop.violation[:, None]])
    assert np.array_equal(got, expected)


def test_moead_sbx_equals_host_sim_optimize_moead_operator_sbx(host_sim, tmp_path):
    host_sim(
        "optimize", "--problem", "zdt1", "moead", "--moead-operator", "sbx",
        "--population", "20", "--generations", "6", "--seed", "9", "--out", tmp_path,
    )
    rows = (tmp_path / "population.csv").read_text().splitlines()[1:]
    expected = np.array([[float(v) for v in r.split(",")] for r in rows])
    a = reentry.Moead(seed=9, population=20, operator="sbx")
    assert a.name == "moead-sbx"
    reentry.evolve(a, reentry.TestProblem("zdt1"), 6)
    pop = a.population
    got = np.hstack([pop.x, pop.f, pop.violation[:, None]])
    assert np.array_equal(got, expected)


@pytest.mark.parametrize("genes", ["population", "random"])
def test_scea_from_options_equals_host_sim_optimize_scea(host_sim, tmp_path, genes):
    """SCEA through ``from_options`` (host-sim's ``RunOptions``/``AlgorithmSpec``) on a
    fixed-length test problem is ``host-sim optimize scea``'s run: its run directory byte for
    byte (summary.json but for the wall time), a checkpoint resumes it bit for bit."""
    host_sim(
        "optimize", "--problem", "zdt1", "scea", "--population", "20", "--neighbours", "5",
        "--batch-size", "4", "--archive", "8", "--scea-genes", genes, "--generations", "6",
        "--seed", "9", "--out", tmp_path / "cli",
    )
    options = dict(
        algorithm="scea", population=20, neighbours=5, batch_size=4, archive=8, scea_genes=genes
    )
    p = reentry.TestProblem("zdt1")
    a = reentry.from_options(9, **options)
    assert a.name == "scea"
    reentry.evolve(a, p, 3)
    b = type(a).from_json(a.to_json())
    reentry.evolve(b, p, 3)
    reentry.evolve(a, p, 3)
    same_state(a, b)
    b.run_report(p, seed=9, wall_time_s=0.0, generations=6, out=tmp_path / "py")
    for f in ("population.csv", "front.csv"):
        assert (tmp_path / "py" / f).read_text() == (tmp_path / "cli" / f).read_text(), f
    summary = [json.loads((tmp_path / d / "summary.json").read_text()) for d in ("py", "cli")]
    for s in summary:
        s.pop("wall_time_s")
    assert summary[0] == summary[1]
    assert summary[0]["algorithm"] == "scea" and summary[0]["front_source"] == "archive"


def test_run_variable_length_is_host_sim_optimize_on_a_vlmop(host_sim, tmp_path):
    """``reentry.run_variable_length`` is ``host-sim optimize --problem vlmopN {scea,mhaco}``:
    the summary line and run directory (population.csv one chromosome per row, front.csv
    byte for byte; summary.json but for the wall time), whatever the thread count; MOEA/D
    and NSGA-II are refused as the CLI refuses them."""
    assert reentry.variable_length_problems() == [f"vlmop{i}" for i in range(1, 6)]
    for problem, algorithm, flags, options in (
        ("vlmop2", "scea", ["--neighbours", "5", "--archive", "6"], dict(neighbours=5, archive=6)),
        ("vlmop5", "mhaco", ["--n-gen-mark", "3"], dict(n_gen_mark=3)),
    ):
        cli = host_sim(
            "optimize", "--problem", problem, "--generations", "4", algorithm, "--population", "20", *flags,
            "--seed", "4", "--threads", "2", "--out", tmp_path / f"cli-{problem}",
        ).stdout.splitlines()[0]
        line = reentry.run_variable_length(
            problem, 4, seed=4, out=tmp_path / f"py-{problem}", algorithm=algorithm,
            population=20, **options,
        )
        cut = lambda s: s.split(" in ")[0] + s.split(" s,", 1)[1]  # noqa: E731
        assert cut(line) == cut(cli), (line, cli)
        py, hs = tmp_path / f"py-{problem}", tmp_path / f"cli-{problem}"
        for f in ("population.csv", "front.csv"):
            assert (py / f).read_text() == (hs / f).read_text(), (problem, f)
        summary = [json.loads((d / "summary.json").read_text()) for d in (py, hs)]
        for s in summary:
            s.pop("wall_time_s")
        assert summary[0].pop("threads") == 1 and summary[1].pop("threads") == 2
        assert summary[0] == summary[1]
    with pytest.raises(reentry.OptimError, match="variable-length problem runs with SCEA or MHACO"):
        reentry.run_variable_length("vlmop1", 2, algorithm="nsga2", population=20)
    # --evaluations is MOEA/D's and NSGA-II's budget, as in the CLI.
    with pytest.raises(reentry.OptimError, match="--evaluations 100: applies to the moead and nsga2"):
        reentry.run_variable_length("vlmop1", 2, evaluations=100, algorithm="scea", population=20)
    with pytest.raises(ValueError, match="not a variable-length problem"):
        reentry.run_variable_length("zdt1", 2, algorithm="scea")


def test_checkpoint_mid_batch_resumes_bit_identically():
    p = reentry.TestProblem("zdt3")
    a = reentry.Moead(seed=2, population=20, neighbours=8, batch_size=6)
    reentry.evolve(a, p, 3)
    xs = a.ask(p)
    a.tell(0, *p.evaluate(xs[0].tolist()))
    b = pickle.loads(pickle.dumps(a))
    assert b.is_told(0) and not b.is_told(1)
    reentry.evolve(a, p, 4)
    reentry.evolve(b, p, 4)
    same_state(a, b)


def test_errors_carry_host_sim_messages(host_sim):
    cli = host_sim("optimize", "--problem", "dtlz2", "--population", "100", check=False)
    p = reentry.TestProblem("dtlz2", 3)
    with pytest.raises(reentry.OptimError) as e:
        reentry.Moead(population=100).ask(p)
    assert "91" in str(e.value) and "105" in str(e.value)
    assert cli.stderr.strip().endswith(str(e.value))
    a = reentry.Nsga2(population=8)
    a.ask(p)
    with pytest.raises(reentry.OptimError, match="outside the batch"):
        a.tell(99, [0.0, 0.0, 0.0])
    a.tell(0, [0.0, 0.0, 0.0])
    with pytest.raises(reentry.OptimError, match="already told"):
        a.tell(0, [0.0, 0.0, 0.0])
    with pytest.raises(reentry.ProblemError, match="unknown; use one of zdt1"):
        reentry.TestProblem("zdt5x")
    with pytest.raises(ValueError, match="changed"):
        a.ask(reentry.TestProblem("zdt1"))


def test_failed_evaluations_are_kept_as_failed_individuals():
    p = reentry.TestProblem("zdt1")
    a = reentry.Nsga2(seed=1, population=8)
    xs = a.ask(p)
    for i in range(len(xs)):
        f, g = p.evaluate(xs[i].tolist())
        a.tell(i, [float("nan")] * 2 if i == 3 else f, g)
    assert a.population.violation[3] == np.finfo(float).max


def test_hypervolume_and_true_fronts():
    p = reentry.TestProblem("zdt1")
    assert p.front_hypervolume([1.1, 1.1]) == pytest.approx(0.87667, abs=1e-5)
    front = p.pareto_front(5000)
    hv = reentry.hypervolume(front, [1.1, 1.1])
    assert 0.8760 < hv < 0.87667  # a sample of the front: slightly below the exact value
    with pytest.raises(reentry.OptimError):
        reentry.hypervolume([[0.5, 0.5]], [1.0, float("nan")])


def test_assembly_refuses_gaps_and_duplicates():
    assert _assemble(4, [(2, ["c", "d"]), (0, ["a", "b"])], "case") == ["a", "b", "c", "d"]
    with pytest.raises(RuntimeError, match="case 1 returned twice"):
        _assemble(3, [(0, ["a", "b"]), (1, ["b", "c"])], "case")
    with pytest.raises(RuntimeError, match="case 2 is missing"):
        _assemble(3, [(0, ["a", "b"])], "case")


def test_wrong_dimension_is_an_optim_error_naming_the_decision():
    p = reentry.TestProblem("zdt1")
    with pytest.raises(reentry.OptimError, match="decision has 3 variables, the problem expects 30"):
        p.evaluate([0.1, 0.2, 0.3])
    with pytest.raises(reentry.OptimError, match="decision 1: decision has 2 variables"):
        p.evaluate_batch([[0.5] * 30, [0.1, 0.2]])


def test_rust_releases_the_gil_while_it_runs():
    """Issue 14 item 1: the GIL is released while Rust runs, so other Python threads go on.
    A Rust-side run (``evolve_in_rust``) sized to last at least 0.2 s runs in a thread while
    this thread records a time stamp every millisecond or so: with the GIL held for the whole call, no
    iteration could fall in the middle half of it."""
    import threading
    import time

    p = reentry.TestProblem("zdt1")

    def timed(generations):
        algo = reentry.Nsga2(seed=1, population=32)
        t0 = time.perf_counter()
        algo.evolve_in_rust(p, generations)
        return t0, time.perf_counter()

    generations = 64
    while True:
        t0, t1 = timed(generations)
        if t1 - t0 >= 0.2 or generations >= 1 << 20:
            break
        generations *= 2
    assert t1 - t0 >= 0.2, f"{generations} generations took only {t1 - t0:.3f} s"

    window = {}
    worker = threading.Thread(target=lambda: window.update(span=timed(generations)))
    stamps = []
    worker.start()
    while worker.is_alive():
        stamps.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    t0, t1 = window["span"]
    lo, hi = t0 + 0.25 * (t1 - t0), t1 - 0.25 * (t1 - t0)
    inside = sum(lo < s < hi for s in stamps)
    assert inside > 0, f"no Python ran during the middle of a {t1 - t0:.3f} s Rust call"
