"""The optimisers through ask/tell, the test problems, pygmo compatibility and :func:`evolve`.

The algorithms are host-sim's (MOEA/D, NSGA-II and MHACO with pagmo's semantics, SCEA, see
docs/reference/optimisers.md). They only ask for decisions and are told evaluations back by index, so
whoever evaluates (Python, Rust, Dask workers, in any order) the run is the same, bit for bit,
for the same seed.
"""

from __future__ import annotations

import json
import os
from typing import Callable, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import _native

Evaluation = Tuple[List[float], List[float]]
"""``(objectives, constraints)`` of one decision."""

BatchEvaluator = Callable[[List[List[float]]], List[Evaluation]]


class Population(NamedTuple):
    """An algorithm's population: decisions ``x`` (n, dim), objectives ``f`` (n, nobj),
    constraint values ``g`` (n, nic), total violations (n,) (``sys.float_info.max`` for a
    failed evaluation)."""

    x: np.ndarray
    f: np.ndarray
    g: np.ndarray
    violation: np.ndarray


class PygmoMethods:
    """pygmo's user-defined-problem methods over ``evaluate``/``evaluate_batch`` (mixed into
    our native problems): ``fitness`` (objectives then inequality constraints), ``batch_fitness``
    (decisions concatenated in, fitness vectors concatenated out), ``has_batch_fitness``."""

    __slots__ = ()

    def fitness(self, x) -> np.ndarray:
        """pygmo fitness: objectives then inequality constraints (NaN for a failed flight)."""
        f, g = self.evaluate(np.asarray(x, dtype=float).tolist())
        return np.asarray(list(f) + list(g), dtype=float)

    def batch_fitness(self, dvs) -> np.ndarray:
        """pygmo batch fitness: decisions concatenated in, fitness vectors concatenated out
        (one Rust call, GIL released)."""
        dim = len(self.get_bounds()[0])
        xs = np.asarray(dvs, dtype=float).reshape(-1, dim).tolist()
        return np.asarray(
            [v for f, g in self.evaluate_batch(xs) for v in list(f) + list(g)], dtype=float
        )

    def has_batch_fitness(self) -> bool:
        """pygmo: ``batch_fitness`` is implemented."""
        return True


class TestProblem(PygmoMethods, _native.TestProblem):
    """A host-sim test problem (``zdt1`` ... ``zdt6``, ``dtlz1`` ... ``dtlz7``, ``constr``)
    evaluated in Rust. Has pygmo's problem methods (``fitness``, ``batch_fitness``,
    ``get_bounds``, ``get_nobj``, ``get_nic``, ``get_nec``), so ``pygmo.problem(TestProblem(
    "zdt1"))`` works, and ``evaluate``/``evaluate_batch`` returning ``(f, g)``."""

    __test__ = False  # not a pytest class

    def get_name(self) -> str:
        return f"reentry {self.name}"


class PygmoProblem:
    """Any problem of ours (``evaluate_batch`` returning ``(f, g)``) as a pygmo user-defined
    problem: ``pygmo.problem(PygmoProblem(p))``. Pickles when ``p`` does, so pygmo's
    archipelagos and Dask can ship it."""

    def __init__(self, problem):
        self.problem = problem

    def fitness(self, x) -> np.ndarray:
        f, g = self.problem.evaluate_batch([np.asarray(x, dtype=float).tolist()])[0]
        return np.asarray(list(f) + list(g), dtype=float)

    def batch_fitness(self, dvs) -> np.ndarray:
        dim = len(self.get_bounds()[0])
        xs = np.asarray(dvs, dtype=float).reshape(-1, dim).tolist()
        return np.asarray(
            [v for f, g in self.problem.evaluate_batch(xs) for v in list(f) + list(g)],
            dtype=float,
        )

    def has_batch_fitness(self) -> bool:
        return True

    def get_bounds(self):
        return self.problem.get_bounds()

    def get_nobj(self) -> int:
        return self.problem.get_nobj()

    def get_nic(self) -> int:
        return self.problem.get_nic()

    def get_nec(self) -> int:
        return 0

    def get_name(self) -> str:
        return f"reentry {getattr(self.problem, 'name', type(self.problem).__name__)}"


def evaluate_batch(problem, xs: Sequence[Sequence[float]]) -> List[Evaluation]:
    """``(objectives, constraints)`` of each decision, in order.

    Uses ``problem.evaluate_batch`` (ours: one Rust call, GIL released) if it exists, else
    pygmo's ``batch_fitness`` or ``fitness`` (fitness vector split into ``get_nobj()``
    objectives and ``get_nic()`` inequality constraints)."""
    xs = [list(map(float, x)) for x in xs]
    if hasattr(problem, "evaluate_batch"):
        return [(list(f), list(g)) for f, g in problem.evaluate_batch(xs)]
    nobj = problem.get_nobj() if hasattr(problem, "get_nobj") else 1
    nic = problem.get_nic() if hasattr(problem, "get_nic") else 0
    has_batch = hasattr(problem, "batch_fitness") and (
        not hasattr(problem, "has_batch_fitness") or problem.has_batch_fitness()
    )
    if has_batch and xs:
        flat = np.asarray(problem.batch_fitness(np.concatenate(xs)), dtype=float)
        rows = flat.reshape(len(xs), -1)
    else:
        rows = [np.asarray(problem.fitness(np.asarray(x)), dtype=float) for x in xs]
    return [(r[:nobj].tolist(), r[nobj : nobj + nic].tolist()) for r in rows]


class _Algorithm:
    """Common ask/tell interface of :class:`Moead`, :class:`Nsga2` and :class:`Mhaco`."""

    def __init__(self, native: "_native.Optimizer"):
        self._native = native

    def ask(self, problem) -> np.ndarray:
        """The next batch of decisions, shape (n, dim) (the same batch until all are told).
        ``problem`` is any object with ``get_bounds()`` (and ``get_nobj()``, ``get_nic()``)."""
        return np.asarray(self._native.ask(problem), dtype=float).reshape(
            -1, len(problem.get_bounds()[0])
        )

    def tell(self, index: int, objectives, constraints=()) -> None:
        """Tell the evaluation of decision ``index`` of the batch (any order; NaN marks a
        failed evaluation). Raises :class:`OptimError` for an index outside the batch, told
        twice, or of the wrong size."""
        self._native.tell(
            int(index),
            np.asarray(objectives, dtype=float).tolist(),
            np.asarray(constraints, dtype=float).tolist(),
        )

    def tell_batch(self, evaluations: Sequence[Evaluation], indices=None) -> None:
        """Tell ``(f, g)`` evaluations for ``indices`` (default: 0, 1, ...)."""
        idx = range(len(evaluations)) if indices is None else indices
        for i, (f, g) in zip(idx, evaluations):
            self.tell(i, f, g)

    def is_told(self, index: int) -> bool:
        """Whether decision ``index`` of the open batch has been told."""
        return self._native.is_told(int(index))

    @property
    def population(self) -> Population:
        x, f, g, v = self._native.population()
        n = len(x)
        return Population(
            np.asarray(x, dtype=float).reshape(n, -1),
            np.asarray(f, dtype=float).reshape(n, -1),
            np.asarray(g, dtype=float).reshape(n, -1),
            np.asarray(v, dtype=float),
        )

    @property
    def generation(self) -> int:
        """Completed generations (0 until the initial population is complete)."""
        return self._native.generation

    @property
    def evaluations(self) -> int:
        return self._native.evaluations

    @property
    def is_initialised(self) -> bool:
        return self._native.is_initialised

    @property
    def name(self) -> str:
        return self._native.name

    def to_json(self) -> str:
        """The whole state (resuming from it gives the bit-identical run)."""
        return self._native.to_json()

    @classmethod
    def from_json(cls, text: str) -> "_Algorithm":
        obj = cls.__new__(cls)
        obj._native = _native.Optimizer.from_json(text)
        return obj

    def __reduce__(self):
        return (type(self).from_json, (self.to_json(),))

    def run_report(
        self,
        problem,
        seed: int,
        wall_time_s: float,
        reference: Optional[Sequence[float]] = None,
        threads: int = 1,
        name: Optional[str] = None,
        generations: Optional[int] = None,
        out=None,
    ) -> str:
        """The finished run's summary line as ``host-sim optimize`` prints it; with ``out``,
        its run directory as ``host-sim optimize --out`` writes it (population.csv, front.csv,
        summary.json; written by host-sim, atomically). ``problem``: the :class:`TestProblem`
        run (default name, reference point and true front hypervolume are its own), or any
        other problem with ``name`` and ``reference`` given (no true front). ``seed``: the
        run's seed; ``wall_time_s``: the evolution's wall time; ``threads``: the evaluation
        threads or workers reported; ``generations``: default the completed generations."""
        return self._native.run_report(
            problem,
            int(seed),
            float(wall_time_s),
            None if reference is None else [float(r) for r in reference],
            int(threads),
            name,
            None if generations is None else int(generations),
            None if out is None else os.fspath(out),
        )

    def evolve_in_rust(self, problem: TestProblem, generations: int) -> None:
        """host-sim's own ``evolve`` (serial, in Rust) on a test problem: the reference the
        Python and Dask loops are checked against."""
        self._native.evolve_test_problem(problem, int(generations))


class Moead(_Algorithm):
    """MOEA/D with pagmo's defaults (host-sim ``AlgorithmSpec`` ``moead`` / ``moead-sbx``;
    docs/reference/optimisers.md).

    ``operator``: ``"de"`` (pagmo's DE variation, ``cr`` and ``f``) or ``"sbx"`` (Zhang &
    Li's SBX, ``eta_c`` and ``crossover_probability``), as ``host-sim optimize
    --moead-operator``; ``weights``: ``"grid"``, ``"low-discrepancy"``, ``"random"``;
    ``decomposition``: ``"tchebycheff"``, ``"weighted"``, ``"pbi"``; ``batch_size``
    offspring per ask (1: pagmo's steady state); ``neighbours`` defaults to 20, or
    ``population - 1`` for smaller populations; ``archive``: capacity of an external archive
    of the feasible non-dominated solutions (``None``: none, pagmo's semantics). Bad settings
    raise :class:`OptimError` at the first ``ask``."""

    def __init__(
        self,
        seed: int = 1,
        population: int = 100,
        weights: str = "grid",
        decomposition: str = "tchebycheff",
        neighbours: Optional[int] = None,
        cr: float = 1.0,
        f: float = 0.5,
        eta_m: float = 20.0,
        realb: float = 0.9,
        limit: int = 2,
        preserve_diversity: bool = True,
        mutation_probability: Optional[float] = None,
        batch_size: int = 1,
        operator: str = "de",
        eta_c: float = 20.0,
        crossover_probability: float = 1.0,
        archive: Optional[int] = None,
    ):
        if operator not in ("de", "sbx"):
            raise ValueError(f"operator = {operator!r}: use 'de' or 'sbx'")
        if neighbours is None:
            # The thesis' 20, or population - 1 for small populations (host-sim's
            # MoeadConfig::default_neighbours).
            neighbours = max(2, min(20, int(population) - 1))
        config = dict(
            population=population,
            weights=weights,
            decomposition=decomposition,
            neighbours=neighbours,
            cr=cr,
            f=f,
            eta_m=eta_m,
            realb=realb,
            limit=limit,
            preserve_diversity=preserve_diversity,
            mutation_probability=mutation_probability,
            batch_size=batch_size,
        )
        if archive is not None:
            config["archive"] = archive
        if operator == "sbx":
            spec = dict(
                moead=config, sbx=dict(eta_c=eta_c, crossover_probability=crossover_probability)
            )
            native = _native.Optimizer.from_spec("moead-sbx", json.dumps(spec), int(seed))
        else:
            native = _native.Optimizer.moead(json.dumps(config), int(seed))
        super().__init__(native)


class Nsga2(_Algorithm):
    """NSGA-II with pagmo's defaults (host-sim ``Nsga2``; population a multiple of 4;
    ``archive`` as for :class:`Moead`)."""

    def __init__(
        self,
        seed: int = 1,
        population: int = 100,
        cr: float = 0.95,
        eta_c: float = 10.0,
        m: float = 0.01,
        eta_m: float = 50.0,
        archive: Optional[int] = None,
    ):
        config = dict(population=population, cr=cr, eta_c=eta_c, m=m, eta_m=eta_m)
        if archive is not None:
            config["archive"] = archive
        super().__init__(_native.Optimizer.nsga2(json.dumps(config), int(seed)))


class Mhaco(_Algorithm):
    """MHACO, pagmo's ``maco`` semantics (host-sim ``Mhaco``; docs/reference/optimisers.md).

    ``constraints``: ``"feasibility-first"`` (default) or, for the thesis' constraints as
    objectives, ``{"as-objectives": {"scales": None, "cap": 2.0, "penalty": 0.5}}``."""

    def __init__(
        self,
        seed: int = 1,
        population: int = 100,
        ker: int = 63,
        q: float = 1.0,
        threshold: int = 1,
        n_gen_mark: int = 7,
        evalstop: int = 100_000,
        focus: float = 0.0,
        constraints="feasibility-first",
    ):
        config = dict(
            population=population,
            ker=ker,
            q=q,
            threshold=threshold,
            n_gen_mark=n_gen_mark,
            evalstop=evalstop,
            focus=focus,
            constraints=constraints,
        )
        super().__init__(_native.Optimizer.mhaco(json.dumps(config), int(seed)))


def from_options(seed: int = 1, **options) -> _Algorithm:
    """The algorithm of ``host-sim optimize``'s algorithm flags on the test problems, by the
    flags' names with underscores (``algorithm="moead"``, ``"nsga2"``, ``"mhaco"`` or
    ``"scea"``, ``moead_operator``, ``population``, ``weights``, ``neighbours``,
    ``mutation_probability``, ``batch_size``, ``archive``, ``resource_allocation``, ``ker``,
    ``n_gen_mark``, ``mhaco_constraints``, ``scea_genes``; missing ones take the CLI's
    defaults), mapped onto host-sim's ``AlgorithmSpec`` by host-sim (``RunOptions``), as the
    CLI maps them. SCEA runs on the decisions as chromosomes of fixed genes only, as
    ``host-sim optimize scea`` does on the fixed-length test problems. An unknown name raises ``ValueError``;
    a bad value :class:`OptimError` at the first ``ask``, with the library's message."""
    return _Algorithm(_native.Optimizer.from_options(json.dumps(options), int(seed)))


def generations_for(evaluations: int, objectives: int, **options) -> int:
    """The generations ``host-sim optimize --evaluations`` runs for these options (as for
    :func:`from_options`) on a problem of ``objectives`` objectives: the fewest whole
    generations whose evaluations, initial population included, reach ``evaluations``."""
    return _native.Optimizer.generations_for(json.dumps(options), int(evaluations), int(objectives))


def run_variable_length(
    problem: str,
    generations: int,
    seed: int = 1,
    *,
    evaluations: Optional[int] = None,
    reference: Optional[Sequence[float]] = None,
    threads: int = 1,
    out: "os.PathLike[str] | str | None" = None,
    **options,
) -> str:
    """``host-sim optimize --problem PROBLEM {scea,mhaco} ...`` on a variable-length test
    problem (``vlmop1`` ... ``vlmop5``, :func:`variable_length_problems`): host-sim's run
    (``VariableLengthRun``: SCEA, or ``algorithm="mhaco"`` as the variable-length MHACO), in
    this process on ``threads`` evaluation threads, ``options`` as for :func:`from_options`,
    ``evaluations`` instead of ``generations`` as ``--evaluations`` (the fewest whole
    generations that reach it), ``reference`` by default the problem's. Returns host-sim's summary line; with ``out`` the
    run directory ``host-sim optimize --out`` writes (population.csv one chromosome per row,
    front.csv, summary.json), written by host-sim. MOEA/D and NSGA-II raise
    :class:`OptimError` (real vectors only)."""
    return _native.run_variable_length(
        problem, json.dumps(options), int(seed), int(generations),
        evaluations=None if evaluations is None else int(evaluations),
        reference=None if reference is None else [float(r) for r in reference],
        threads=int(threads), out=None if out is None else os.fspath(out),
    )


def variable_length_problems() -> List[str]:
    """Names of the variable-length test problems (``vlmop1`` ... ``vlmop5``)."""
    return list(_native.variable_length_problems())


def evolve(
    algorithm: _Algorithm,
    problem,
    generations: int,
    map_batch: Optional[BatchEvaluator] = None,
    observer: Optional[Callable[[_Algorithm], None]] = None,
) -> _Algorithm:
    """Run host-sim's ``evolve`` loop on ``algorithm``: complete the initial population if
    needed, then ``generations`` more generations, resuming an open batch by evaluating only
    its untold decisions. The loop is the library's; only the evaluation is ``map_batch``'s.

    ``map_batch(xs)`` evaluates a list of decisions into ``(f, g)`` pairs in order (default:
    :func:`evaluate_batch` here; :func:`reentry.distributed.dask_batch_evaluator` on Dask).
    ``observer(algorithm)`` is called after each completed generation. An exception in
    ``map_batch`` stops the run at that batch and is raised as :class:`OptimError` with its
    message; the evaluations told before it are kept."""
    if map_batch is None:
        map_batch = lambda xs: evaluate_batch(problem, xs)  # noqa: E731
    notify = None if observer is None else (lambda: observer(algorithm))
    algorithm._native.evolve_batches(problem, int(generations), map_batch, notify)
    return algorithm
