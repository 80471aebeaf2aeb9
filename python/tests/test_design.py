"""The re-entry design problems (host-sim design): round trips against `host-sim optimize`,
the variable-length problem against its chromosomes and the fixed-length problem, pickling,
errors; pygmo and pymoo compatibility where installed; an optimisation on Dask."""

import pickle

import numpy as np
import pytest

import reentry


def bits(a):
    return np.asarray(a, dtype=float).view(np.uint64)


def read_population(path):
    """host-sim's population.csv: header, then rows (empty fields pad variable lengths)."""
    lines = path.read_text().splitlines()
    head = lines[0].split(",")
    rows = [r.split(",") for r in lines[1:]]
    return head, rows


def test_nsga2_on_design_problem_equals_host_sim_optimize(host_sim, tmp_path):
    host_sim(
        "optimize", "--problem", "srm", "nsga2", "--population", "8",
        "--generations", "1", "--seed", "5", "--threads", "1", "--out", tmp_path,
    )
    head, rows = read_population(tmp_path / "population.csv")
    expected = np.array([[float(v) for v in r] for r in rows])
    p = reentry.DesignProblem("srm")
    a = reentry.Nsga2(seed=5, population=8)
    reentry.evolve(a, p, 1)
    pop = a.population
    got = np.hstack([pop.x, pop.f, pop.g, pop.violation[:, None]])
    assert head[-1] == "violation" and got.shape == expected.shape
    assert np.array_equal(bits(got), bits(expected))
    # Not a trivial population: the flights differ.
    assert len(set(pop.f[:, 0])) > 4


def test_variable_length_problem_equals_host_sim_scea_population(host_sim, tmp_path):
    host_sim(
        "optimize", "--problem", "srm", "scea", "--population", "8",
        "--generations", "1", "--seed", "7", "--neighbours", "4", "--threads", "1", "--out", tmp_path,
    )
    head, rows = read_population(tmp_path / "population.csv")
    nx = sum(1 for h in head if h.startswith("x"))
    v = reentry.VariableDesignProblem("srm")
    assert v.nodes == (4, 8) and v.node_genes == 2
    lengths = set()
    for r in rows:
        genes = [float(x) for x in r[:nx] if x != ""]
        lengths.add(len(genes))
        nodes = [genes[k : k + 2] for k in range(0, len(genes), 2)]
        f, g = v.evaluate_chromosome(nodes)
        expected = [float(x) for x in r[nx:-1]]
        assert np.array_equal(bits(f + g), bits(expected))
    assert len(lengths) > 1, "the SCEA population should mix node counts"


def test_padded_decision_is_the_chromosome_and_the_fixed_problem():
    fixed = reentry.DesignProblem("srm")
    v = reentry.VariableDesignProblem("srm")
    lo, hi = (np.asarray(b) for b in v.get_bounds())
    assert (lo[-1], hi[-1]) == (2.0, 6.0) and v.get_nix() == 1
    assert len(lo) == len(fixed.get_bounds()[0]) + 1
    rng = np.random.default_rng(3)
    x = lo + rng.random(len(lo)) * (hi - lo)
    # All six free nodes: the fixed-length problem's evaluation, bit for bit.
    x[-1] = 6.0
    assert np.array_equal(bits(sum(v.evaluate(x.tolist()), [])), bits(sum(fixed.evaluate(x[:-1].tolist()), [])))
    # Three nodes (a real value rounds): the chromosome of the first three; the rest ignored.
    x[-1] = 3.2
    nodes, alt = v.chromosome(x.tolist())
    assert alt is None and nodes == [x[k : k + 2].tolist() for k in (0, 2, 4)]
    y = x.copy()
    y[6:12] = lo[6:12]
    assert v.evaluate(x.tolist()) == v.evaluate(y.tolist()) == v.evaluate_chromosome(nodes)
    table, _ = v.table(nodes)
    assert len(table) == 5 and all(a[0] > b[0] for a, b in zip(table, table[1:]))
    with pytest.raises(reentry.OptimError, match="free-node count"):
        x[-1] = 7.0
        v.evaluate(x.tolist())
    with pytest.raises(reentry.OptimError, match="decision 1"):
        v.evaluate_batch([y.tolist(), y[:-1].tolist()])


def test_altitude_variable_and_scenario_of_a_decision():
    p = reentry.DesignProblem("srm-altitude")
    lo, hi = (np.asarray(b) for b in p.get_bounds())
    assert len(lo) == 13 and (lo[-1], hi[-1]) == (50.0, 110.0)
    energies = [0.9, 0.8, 0.65, 0.5, 0.35, 0.2]
    x = [v for e in energies for v in (e, 45.0)] + [80.0]
    f, g = p.evaluate(x)
    table, alt = p.decode(x)
    assert alt == 80e3 and len(table) == 8
    # The scenario file of the decision flies to the same objectives (it stores degrees:
    # round-off, not bits).
    s = reentry.fly_summary(p.scenario_toml(x))
    assert s["termination"] == "altitude"
    assert np.isclose(f[0], -s["flown_range_angle_deg"] / 180.0, rtol=1e-9, atol=0)
    assert np.isclose(f[1], s["heat_load_mj_m2"] / 1e3, rtol=1e-9, atol=0)
    assert np.isclose(g[1], s["peak_g_load"]["value"] / 3.0 - 1.0, rtol=1e-9, atol=0)
    assert np.isclose(s["final_state"]["altitude_km"], 25.0, atol=1e-6)
    v = reentry.VariableDesignProblem("srm-altitude", nodes=(3, 5))
    assert v.nodes == (3, 5) and len(v.get_bounds()[0]) == 3 * 2 + 1 + 1
    nodes, alt_km = v.chromosome(v.get_bounds()[1])
    assert alt_km == 110.0 and len(nodes) == 3


def test_config_text_dict_and_pickle():
    toml = reentry.DesignProblem("srm").config_toml()
    assert 'base = "srm"' in toml
    d = {"base": "srm", "encoding": {"nodes": 5, "first": {"energy": 1.0, "alpha_deg": 0.0,
         "sigma_deg": 0.0}, "last": {"energy": 0.0, "alpha_deg": 0.0, "sigma_deg": 0.0},
         "energy": [0.1, 0.95], "alpha_deg": [0.0, 45.0], "sigma_deg": [0.0, 60.0],
         "free_alpha": False}}
    p = reentry.DesignProblem(d)
    assert p.get_bounds()[1] == [0.95, 60.0] * 3
    q = reentry.DesignProblem({"problem": d, "algorithm": "moead"})
    assert q.config_toml() == p.config_toml()
    x = [0.8, 30.0, 0.5, 45.0, 0.2, 10.0]
    r = pickle.loads(pickle.dumps(p))
    assert type(r) is reentry.DesignProblem and r.evaluate(x) == p.evaluate(x)
    v = reentry.VariableDesignProblem("srm", nodes=(3, 6))
    w = pickle.loads(pickle.dumps(v))
    assert type(w) is reentry.VariableDesignProblem and w.nodes == (3, 6)
    assert w.get_bounds() == v.get_bounds()


def test_errors_carry_host_sim_messages(host_sim):
    with pytest.raises(reentry.DesignError) as e:
        reentry.DesignProblem("not a preset = 1")
    assert "(TOML string)" in str(e.value)
    cli = host_sim("optimize", "--problem", "srm", "--print-config", check=False)
    text = cli.stdout.replace('sigma_deg = [0.0, 90.0]', 'sigma_deg = [0.0, -90.0]', 1)
    assert text != cli.stdout
    with pytest.raises(reentry.DesignError, match="sigma_deg"):
        reentry.DesignProblem(text)
    with pytest.raises(reentry.DesignError, match="encoding.nodes"):
        reentry.VariableDesignProblem("srm", nodes=(2, 8))
    with pytest.raises(reentry.OptimError, match="decision has 3 variables"):
        reentry.DesignProblem("srm").evaluate([0.5, 1.0, 2.0])


@pytest.mark.parametrize(
    "cli, options",
    [
        ([], {}),
        (
            ["--population", "12", "--generations", "7", "--seed", "4", "--threads", "2",
             "--ref", "0.5,3", "nsga2", "--archive", "9"],
            dict(population=12, generations=7, seed=4, threads=2, reference=[0.5, 3],
                 algorithm="nsga2", archive=9),
        ),
        (
            ["scea", "--population", "10", "--neighbours", "4", "--batch-size", "2",
             "--mutation-probability", "0.2", "--scea-genes", "random"],
            dict(algorithm="scea", population=10, neighbours=4, batch_size=2,
                 mutation_probability=0.2, scea_genes="random"),
        ),
        (
            ["mhaco", "--mhaco-constraints", "objectives", "--population", "16"],
            dict(algorithm="mhaco", mhaco_constraints="objectives", population=16),
        ),
    ],
    ids=["defaults", "nsga2", "scea", "mhaco-objectives"],
)
def test_run_config_of_flags_is_host_sims_print_config(host_sim, cli, options):
    """The flags-to-run-file mapping is host-sim's (``ReentryRunConfig::of_flags``), the one
    ``host-sim optimize --print-config`` prints."""
    expected = host_sim("optimize", "--problem", "srm", *cli, "--print-config").stdout
    assert reentry.design_run_config_of_flags("srm", **options) == expected
    with pytest.raises(reentry.DesignError, match="neighbors"):
        reentry.design_run_config_of_flags("srm", neighbors=4)


def test_scenario_file_base_and_failed_flights(tmp_path):
    # A base scenario file (relative to the problem file) whose 2500 s time limit cuts the
    # long glides: those flights fail (NaN, host-sim's failed evaluation), steep ones finish.
    base = reentry.scenario_toml("srm-glide").replace("max_time_s = 5000.0", "max_time_s = 2500.0")
    (tmp_path / "short.toml").write_text(base)
    cfg = reentry.DesignProblem("srm").config_toml().replace('base = "srm"', 'base = "short.toml"')
    (tmp_path / "problem.toml").write_text(cfg)
    p = reentry.DesignProblem(tmp_path / "problem.toml")
    energies = [0.9, 0.8, 0.65, 0.5, 0.35, 0.2]
    glide = [v for e in energies for v in (e, 0.0)]
    steep = [v for e in energies for v in (e, 90.0)]
    f, g = p.evaluate(glide)
    assert np.isnan(f + g).all()
    assert reentry.fly_summary(p.scenario_toml(glide))["termination"] == "max_time"
    f, g = p.evaluate(steep)
    assert np.isfinite(f + g).all()
    # Our algorithms keep a failed evaluation as a failed individual (worst violation).
    a = reentry.Nsga2(seed=1, population=8)
    a.ask(p)
    for i in range(8):
        a.tell(i, *p.evaluate((glide if i % 2 else steep)))
    v = a.population.violation
    assert (v[1::2] == np.finfo(float).max).all() and (v[0::2] < 100.0).all()
    # pymoo cannot rank NaN: its adapter gives the failure a finite, infeasible value.
    try:
        import pymoo  # noqa: F401
    except ImportError:
        return
    out = reentry.pymoo_problem(p, failure_value=1e30).evaluate(
        np.array([glide, steep]), return_values_of=["F", "G"]
    )
    assert (out[0][0] == 1e30).all() and (out[1][0] == 1e30).all()
    assert np.array_equal(out[0][1], np.array(p.evaluate(steep)[0]))


def test_design_optimisation_on_dask_equals_local(client):
    from reentry.distributed import evolve_on_dask

    p = reentry.DesignProblem("srm")
    local, dist = reentry.Nsga2(seed=3, population=8), reentry.Nsga2(seed=3, population=8)
    reentry.evolve(local, p, 1)
    evolve_on_dask(dist, p, 1, client, chunk_size=3)
    assert local.to_json() == dist.to_json()


# ------------------------------------------------------------------------- pygmo, pymoo


def test_pygmo_udp_layout_and_algorithm():
    pg = pytest.importorskip("pygmo")
    udp = reentry.DesignProblem("srm")
    prob = pg.problem(udp)
    assert (prob.get_nobj(), prob.get_nic(), prob.get_nec(), prob.get_nx()) == (2, 3, 0, 12)
    lo, hi = prob.get_bounds()
    rng = np.random.default_rng(2)
    xs = lo + rng.random((3, len(lo))) * (hi - lo)
    for x in xs:
        f, g = udp.evaluate(x.tolist())
        assert np.array_equal(prob.fitness(x), np.array(f + g))
    assert np.array_equal(udp.batch_fitness(xs.ravel()), np.concatenate([udp.fitness(x) for x in xs]))
    # pygmo's NSGA-II needs an unconstrained problem: death penalty (NaN constraints of
    # failed flights count as violated).
    pop = pg.population(pg.unconstrain(prob, method="death penalty"), 8, seed=1)
    pop = pg.algorithm(pg.nsga2(gen=1, seed=1)).evolve(pop)
    assert pop.problem.get_fevals() == 16
    var = pg.problem(reentry.VariableDesignProblem("srm"))
    assert (var.get_nix(), var.get_nx()) == (1, 13)
    x = var.get_bounds()[1]
    assert var.fitness(x).tolist() == udp.fitness(x[:-1]).tolist()


def test_pymoo_problem_and_algorithm():
    pytest.importorskip("pymoo")
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.optimize import minimize

    udp = reentry.DesignProblem("srm")
    prob = reentry.pymoo_problem(udp)
    assert (prob.n_var, prob.n_obj, prob.n_ieq_constr) == (12, 2, 3)
    lo, hi = (np.asarray(b) for b in udp.get_bounds())
    xs = lo + np.random.default_rng(4).random((4, 12)) * (hi - lo)
    out = prob.evaluate(xs, return_values_of=["F", "G"])
    ev = udp.evaluate_batch(xs.tolist())
    assert np.array_equal(out[0], np.array([f for f, _ in ev]))
    assert np.array_equal(out[1], np.array([g for _, g in ev]))
    res = minimize(prob, NSGA2(pop_size=8), ("n_gen", 2), seed=1, verbose=False)
    assert res.algorithm.evaluator.n_eval == 16
    assert res.pop.get("F").shape == (8, 2)
