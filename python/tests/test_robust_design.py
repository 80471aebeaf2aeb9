"""The robust design problem (host-sim design::RobustProblem) from Python: its evaluations
are host-sim optimize's, bit for bit; split over flights and decisions on Dask they are the
local ones; it pickles; bad input raises host-sim's message."""

import pickle
from pathlib import Path

import numpy as np
import pytest

import reentry
REPO = Path(__file__).resolve().parents[2]


def bits(a):
    return np.asarray(a, dtype=float).view(np.uint64)


def run_file(tmp_path, cases=3, mode="stored"):
    """examples/optimize-robust-srm.toml, small: NSGA-II 8 x 1 generation, `cases` flights."""
    text = (REPO / "examples" / "optimize-robust-srm.toml").read_text()
    base = (REPO / "examples" / "srm-glide-replanning.toml").as_posix()
    for old, new in [
        ('base = "srm-glide-replanning.toml"', f'base = "{base}"'),
        ("population = 16", "population = 8"),
        ("generations = 10", "generations = 1"),
        ("cases = 20", f"cases = {cases}"),
        ('mode = "replan-reversals"', f'mode = "{mode}"'),
    ]:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "robust.toml"
    path.write_text(text)
    return path


def test_robust_evaluations_equal_host_sim_optimize(host_sim, tmp_path):
    path = run_file(tmp_path)
    out = tmp_path / "run"
    host_sim("optimize", "--config", path, "--out", out)
    lines = (out / "population.csv").read_text().splitlines()
    head = lines[0].split(",")
    rows = np.array([[float(v) for v in r.split(",")] for r in lines[1:]])
    p = reentry.RobustDesignProblem(path)
    n = len(p.get_bounds()[0])
    assert (p.get_nobj(), p.get_nic(), p.cases, p.mode) == (2, 1, 3, "stored")
    assert head[n:] == ["f1", "f2", "g1", "violation"]
    ev = p.evaluate_batch(rows[:, :n].tolist())
    got = np.array([f + g for f, g in ev])
    assert np.array_equal(bits(got), bits(rows[:, n : n + 3]))
    # Not a trivial population: the campaigns differ.
    assert len(set(got[:, 0])) > 4


def test_robust_problem_pickles_and_refuses_what_it_cannot_fly(tmp_path):
    p = reentry.RobustDesignProblem(run_file(tmp_path))
    q = pickle.loads(pickle.dumps(p))
    x = np.mean(p.get_bounds(), axis=0).tolist()
    assert bits(q.evaluate(x)[0]).tolist() == bits(p.evaluate(x)[0]).tolist()
    assert "[robust]" in q.config_toml() and "[problem]" in q.config_toml()
    with pytest.raises(TypeError):
        reentry.RobustDesignProblem("srm")
    text = run_file(tmp_path).read_text().replace("cases = 3", "cases = 0")
    with pytest.raises(reentry.DesignError, match="`robust.dispersions.cases` = 0"):
        reentry.RobustDesignProblem(text)
    with pytest.raises(reentry.DesignError, match="field `robust` is missing"):
        reentry.RobustDesignProblem(text.split("[robust]")[0])


def test_robust_batch_on_dask_split_over_flights_equals_local(client, tmp_path):
    from reentry.distributed import robust_batch_evaluator

    p = reentry.RobustDesignProblem(run_file(tmp_path, cases=4, mode="stored-reversals"))
    lo, hi = (np.asarray(b) for b in p.get_bounds())
    xs = [(lo + (hi - lo) * t).tolist() for t in (0.3, 0.5, 0.7)]
    local = p.evaluate_batch(xs)
    for per_task in (1, 3, None):
        remote = robust_batch_evaluator(client, p, cases_per_task=per_task)(xs)
        assert [bits(f).tolist() + bits(g).tolist() for f, g in remote] == [
            bits(f).tolist() + bits(g).tolist() for f, g in local
        ], per_task
    # Parts in another order give the same evaluation; a part missing is refused.
    x = xs[1]
    parts = [p.fly_cases(x, [2, 3]), p.fly_cases(x, [0]), p.fly_cases(x, [1])]
    assert bits(p.evaluate_parts(parts)[0]).tolist() == bits(local[1][0]).tolist()
    with pytest.raises(reentry.CampaignError, match="missing"):
        p.evaluate_parts(parts[:2])


def test_robust_settings_are_genes_after_the_encodings(tmp_path):
    """`[[robust.settings]]`: one gene per setting after the encoding's, its range the bounds;
    two values give different campaigns; a range the scenario refuses raises host-sim's
    message naming the run file and the entry."""
    path = run_file(tmp_path, cases=2, mode="stored-reversals")
    text = path.read_text() + (
        '\n[[robust.settings]]\nfield = "guidance.lateral.corridor_width_final_deg"\n'
        "range = [1.0, 10.0]\n"
    )
    path.write_text(text)
    p = reentry.RobustDesignProblem(path)
    lo, hi = p.get_bounds()
    assert len(lo) == 13 and (lo[12], hi[12]) == (1.0, 10.0)
    assert "[[robust.settings]]" in p.config_toml()
    x = np.mean(p.get_bounds(), axis=0).tolist()
    y = x[:12] + [10.0]
    x[12] = 1.0
    assert p.evaluate(x) != p.evaluate(y)
    with pytest.raises(reentry.DesignError) as e:
        reentry.RobustDesignProblem(text.replace("range = [1.0, 10.0]", "range = [0.0, 10.0]"))
    assert "`robust.settings[0].range` = [0, 10]" in str(e.value)
