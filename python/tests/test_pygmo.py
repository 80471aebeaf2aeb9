"""pygmo compatibility: our problems as pygmo UDPs, pygmo's algorithms on them, ours on pygmo's."""

import numpy as np
import pytest

import reentry

pg = pytest.importorskip("pygmo")


@pytest.mark.parametrize("name,udp", [("zdt1", lambda: pg.zdt(1)), ("dtlz2", lambda: pg.dtlz(2, 12, 3))])
def test_fitness_equals_pygmo(name, udp):
    ours = pg.problem(reentry.TestProblem(name, 3))
    theirs = pg.problem(udp())
    assert ours.get_bounds()[0].tolist() == theirs.get_bounds()[0].tolist()
    assert ours.get_nobj() == theirs.get_nobj() and ours.get_nic() == 0
    rng = np.random.default_rng(1)
    lo, hi = ours.get_bounds()
    xs = lo + rng.random((10, len(lo))) * (hi - lo)
    for x in xs:
        np.testing.assert_allclose(ours.fitness(x), theirs.fitness(x), rtol=1e-12, atol=1e-15)
    batch = ours.batch_fitness(xs.ravel())
    assert np.array_equal(batch, np.concatenate([ours.fitness(x) for x in xs]))


def test_constrained_problem_fitness_has_pygmo_layout():
    p = pg.problem(reentry.TestProblem("constr"))
    assert (p.get_nobj(), p.get_nec(), p.get_nic()) == (2, 0, 2)
    f, g = reentry.TestProblem("constr").evaluate([0.5, 1.0])
    assert p.fitness([0.5, 1.0]).tolist() == f + g


def test_pygmo_algorithm_on_our_problem():
    prob = pg.problem(reentry.TestProblem("zdt1"))
    pop = pg.population(prob, 40, seed=1)
    hv0 = pg.hypervolume(pop.get_f()).compute([1.1, 11.0])
    pop = pg.algorithm(pg.nsga2(gen=30, seed=1)).evolve(pop)
    hv1 = pg.hypervolume(pop.get_f()).compute([1.1, 11.0])
    assert hv1 > hv0
    assert pop.problem.get_fevals() >= 40 * 31


def test_pygmo_moead_with_batch_evaluator_on_our_wrapped_problem():
    prob = pg.problem(reentry.PygmoProblem(reentry.TestProblem("zdt2")))
    assert prob.has_batch_fitness()
    pop = pg.population(prob, 40, seed=2)
    pop = pg.algorithm(pg.moead(gen=10, seed=2)).evolve(pop)
    assert len(pop) == 40 and pop.problem.get_fevals() == 40 * 11


def test_our_moead_on_a_pygmo_problem():
    udp = pg.problem(pg.zdt(1))
    ours = reentry.Moead(seed=1, population=20, neighbours=8, batch_size=20)
    reentry.evolve(ours, udp, 5)
    ref = reentry.Moead(seed=1, population=20, neighbours=8, batch_size=20)
    reentry.evolve(ref, reentry.TestProblem("zdt1"), 5)
    # Same algorithm, objectives equal to 1e-12: the runs agree (here exactly).
    np.testing.assert_allclose(ours.population.f, ref.population.f, rtol=1e-9)
