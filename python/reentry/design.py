"""The re-entry mission-design problems (host-sim ``design``, docs/reference/mission-design.md) as
pygmo user-defined problems and, optionally, pymoo problems.

* :class:`DesignProblem`: the thesis' fixed-length guidance problem (presets ``horus-2b``,
  ``srm``, ``srm-altitude``, or any ``[problem]`` settings): a decision is the free nodes'
  genes (normalised energy, angle of attack [deg] if free, bank angle [deg]) and the entry
  altitude [km] when it is a variable; two objectives (``-theta/pi``, heat load in GJ/m^2),
  three inequality constraints (``<= 0`` feasible: heat flux, g-load, g-load rate).
* :class:`VariableDesignProblem`: the variable-length problem of SCEA (4 to 8 table nodes),
  over chromosomes (:meth:`~VariableDesignProblem.evaluate_chromosome`) or, for pygmo and our
  ask/tell algorithms, over a padded fixed-size vector whose last variable (integer) is the
  number of free nodes used.
* :class:`RobustDesignProblem`: the same profile judged by a dispersion campaign of the base
  scenario's guidance stack (host-sim ``design::RobustProblem``).
* :func:`pymoo_problem`: any of them as a ``pymoo.core.problem.Problem``.
* :func:`run_design`: a whole design run from a run file into a run directory, or resumed
  from one (host-sim ``design::run``: what ``host-sim optimize --config/--resume`` runs), its
  batches optionally evaluated by a ``map_batch`` (on Dask:
  :func:`reentry.distributed.run_design_on_dask`).

Every evaluation is one closed-loop flight in Rust (GIL released). A failed flight (rejected
scenario, time limit, ground) evaluates to NaN objectives and constraints, host-sim's failed
individual: our algorithms rank it last; pygmo's ``unconstrain`` treats NaN constraints as
violated; :func:`pymoo_problem` replaces NaN by ``failure_value``.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from typing import Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from .optim import PygmoMethods

ProblemLike = Union[None, str, "os.PathLike[str]", Mapping]


def _problem_source(problem: ProblemLike) -> dict:
    """Keyword arguments of the native constructors for a preset name, TOML text, a file or
    a dict."""
    if problem is None:
        return {}
    if isinstance(problem, Mapping):
        return {"toml": _native.json_to_toml(json.dumps(dict(problem)))}
    if isinstance(problem, os.PathLike):
        return {"path": os.fspath(problem)}
    if isinstance(problem, str):
        if problem in _native.design_presets():
            return {"preset": problem}
        if "\n" in problem or "=" in problem:
            return {"toml": problem}
        return {"path": problem}
    raise TypeError(
        f"problem must be a preset name, TOML text, a path or a dict, not {type(problem).__name__}"
    )


def _rebuild(cls, config_toml: str, base_dir: str, nodes: Optional[Tuple[int, int]]):
    kw = {} if nodes is None else {"nodes": nodes}
    return cls(config_toml, base_dir=base_dir, **kw)


class DesignProblem(PygmoMethods, _native.DesignProblem):
    """A fixed-length re-entry design problem (host-sim ``design::ReentryProblem``).

    ``problem``: a preset (``"horus-2b"`` default, ``"srm"``, ``"srm-altitude"``; on the
    analytical simulator ``"srm-analytical"``, ``"srm-analytical-altitude"``), TOML text or
    a dict with the ``[problem]`` fields (``base``, ``encoding``, ``limits``, ``objectives``;
    or a whole ``host-sim optimize`` configuration with a ``problem`` table), or a TOML file.
    ``base_dir``: the folder a scenario-file ``base`` is relative to (default: the file's
    folder, else the current one). Raises :class:`reentry.DesignError` with host-sim's message.

    pygmo: ``pygmo.problem(DesignProblem("srm"))`` (``fitness``, ``batch_fitness``,
    ``get_bounds``, ``get_nobj``, ``get_nic``, ``get_nec``); pickles (Dask, pygmo islands)."""

    def __new__(cls, problem: ProblemLike = None, *, base_dir=None):
        return super().__new__(cls, base_dir=base_dir, **_problem_source(problem))

    def __reduce__(self):
        return (_rebuild, (type(self), self.config_toml(), os.fspath(self.base_dir), None))

    def get_name(self) -> str:
        """pygmo: the problem's name."""
        return "reentry design problem"

    def get_extra_info(self) -> str:
        """pygmo: the settings (TOML)."""
        return self.config_toml()


class VariableDesignProblem(PygmoMethods, _native.VariableDesignProblem):
    """The variable-length re-entry design problem (host-sim ``design::VariableReentry``,
    what ``host-sim optimize scea`` solves): ``nodes = (min, max)`` table nodes,
    fixed end nodes included (default 4 to the encoding's 8).

    Chromosome view: :meth:`evaluate_chromosome` ``(nodes, altitude_km)`` with 2 to 6 free
    nodes of :attr:`node_genes` genes. pygmo / ask/tell view: a padded vector of
    ``max - 2`` nodes' genes, the entry altitude [km] if a variable, then the number of free
    nodes used (``get_nix() == 1``: pygmo's integer part; our real-valued algorithms' values
    are rounded to the nearest integer); only the first ``count`` nodes are flown."""

    def __new__(cls, problem: ProblemLike = None, *, base_dir=None, nodes=None):
        return super().__new__(cls, base_dir=base_dir, nodes=nodes, **_problem_source(problem))

    def __reduce__(self):
        return (
            _rebuild,
            (type(self), self.config_toml(), os.fspath(self.base_dir), tuple(self.nodes)),
        )

    def get_name(self) -> str:
        """pygmo: the problem's name."""
        return "reentry variable-length design problem"

    def get_extra_info(self) -> str:
        """pygmo: the settings (TOML) and node range."""
        return f"nodes = {list(self.nodes)}\n" + self.config_toml()


class RobustDesignProblem(PygmoMethods, _native.RobustDesignProblem):
    """The robust re-entry design problem (host-sim ``design::RobustProblem``,
    docs/reference/mission-design.md "Robust design"): a decision is the stored profile's free
    nodes, as in :class:`DesignProblem`; its evaluation flies a seeded dispersion campaign of
    ``cases`` flights of the base scenario's guidance stack (the same draws for every
    decision) and returns the ``[robust]`` statistics as objectives and one constraint (the
    fraction of flights that fail or break a limit, over its maximum; ``<= 0`` feasible).

    ``run``: a run file (path), TOML text or a dict with the ``problem`` and ``robust``
    tables (e.g. ``examples/optimize-robust-srm.toml``; other keys are not read).
    ``base_dir``: the folder the scenario-file ``base`` is relative to (default: the file's
    folder, else the current one). Raises :class:`reentry.DesignError` with host-sim's
    message.

    On Dask, :func:`reentry.distributed.robust_batch_evaluator` splits each batch over
    decisions and flights (:meth:`fly_cases`, :meth:`evaluate_parts`): the same evaluations,
    bit for bit. Pickles (Dask, pygmo islands)."""

    def __new__(cls, run, *, base_dir=None):
        src = _problem_source(run)
        if "preset" in src:
            raise TypeError("a robust problem needs a run file with [problem] and [robust]")
        return super().__new__(cls, base_dir=base_dir, **src)

    def __reduce__(self):
        return (_rebuild_robust, (type(self), self.config_toml(), os.fspath(self.base_dir)))

    def get_name(self) -> str:
        """pygmo: the problem's name."""
        return "reentry robust design problem"

    def get_extra_info(self) -> str:
        """pygmo: the settings (TOML)."""
        return self.config_toml()


def _rebuild_robust(cls, config_toml: str, base_dir: str):
    return cls(config_toml, base_dir=base_dir)


def pymoo_problem(problem, failure_value: float = 1e30):
    """``problem`` (any of ours with ``get_bounds``, ``get_nobj``, ``get_nic`` and
    ``evaluate_batch``) as a vectorised ``pymoo.core.problem.Problem``: ``out["F"]`` the
    objectives, ``out["G"]`` the inequality constraints (``<= 0`` feasible, pymoo's convention
    too). A population is one ``evaluate_batch`` call (GIL released). A failed flight's NaN
    values become ``failure_value`` (an infeasible, dominated point: pymoo cannot rank NaN).
    Needs pymoo (``pip install pymoo``)."""
    from pymoo.core.problem import Problem

    lo, hi = (np.asarray(b, dtype=float) for b in problem.get_bounds())
    nobj, nic = problem.get_nobj(), problem.get_nic()

    class _Reentry(Problem):
        def __init__(self):
            super().__init__(n_var=len(lo), n_obj=nobj, n_ieq_constr=nic, xl=lo, xu=hi)
            self.reentry_problem = problem

        def _evaluate(self, x, out, *args, **kwargs):
            ev = problem.evaluate_batch(np.asarray(x, dtype=float).reshape(-1, len(lo)).tolist())
            f = np.asarray([e[0] for e in ev], dtype=float).reshape(-1, nobj)
            g = np.asarray([e[1] for e in ev], dtype=float).reshape(-1, nic)
            out["F"] = np.where(np.isnan(f), failure_value, f)
            if nic:
                out["G"] = np.where(np.isnan(g), failure_value, g)

    return _Reentry()


def design_run_config(preset: str = "horus-2b", **settings) -> str:
    """The run file of a design preset as TOML text: the thesis' settings (``host-sim optimize
    --problem PRESET --print-config``) with the top-level ``settings`` over them (``population``,
    ``generations``, ``seed``, ``threads``, ``batch_size``, ``neighbours``, ``algorithm``,
    ``reference``, ...; ``problem`` replaces the whole ``[problem]`` table), checked as a run
    file is: a bad value raises :class:`DesignError` naming the field."""
    return _native.run_config_toml(preset, json.dumps(settings))


def design_run_config_of_flags(
    preset: str,
    *,
    generations: Optional[int] = None,
    seed: Optional[int] = None,
    threads: Optional[int] = None,
    reference: Optional[Sequence[float]] = None,
    evaluations: Optional[int] = None,
    **options,
) -> str:
    """The run file of ``host-sim optimize``'s flags on a design preset, as TOML text: what
    ``host-sim optimize --problem PRESET [ALGORITHM FLAGS] --print-config`` prints, mapped by
    host-sim (``ReentryRunConfig::of_flags``). ``options``: the algorithm flags by their
    names with underscores, as for :func:`reentry.from_options` (``algorithm``,
    ``population``, ``neighbours``, ``batch_size``, ``archive``, ``mhaco_constraints``,
    ``scea_genes``, ...); missing flags take the CLI's defaults. Checked as a run file is: a
    bad value raises :class:`DesignError` naming the field, and so does a flag the re-entry
    problems fix (``resource_allocation``, ``moead_operator="sbx"``, ``ker``, ``n_gen_mark``,
    ``evaluations``), as the CLI refuses it."""
    flags = dict(preset=preset, options=options)
    for name, value in (
        ("generations", generations), ("seed", seed), ("threads", threads),
        ("reference", None if reference is None else [float(r) for r in reference]),
        ("evaluations", evaluations),
    ):
        if value is not None:
            flags[name] = value
    return _native.run_config_of_flags(json.dumps(flags))


def run_design(
    out: "os.PathLike[str] | str",
    config: "os.PathLike[str] | str | None" = None,
    *,
    resume: bool = False,
    generations: Optional[int] = None,
    map_batch=None,
    label: Optional[str] = None,
) -> dict:
    """Run the run file ``config`` into the run directory ``out`` (replacing a previous run
    there), or with ``resume=True`` continue the run in ``out`` from its last checkpoint
    (``generations``: a new total, by default the run's own): host-sim's run, its directory
    and checkpoints, so a run started here resumes with ``host-sim optimize --resume`` and the
    other way round, bit for bit. ``map_batch(xs)`` evaluates each batch of decisions into
    ``(f, g)`` pairs in order (default: host-sim's ``threads`` of the run file); it must
    return what the problem's own evaluation returns (the Dask evaluators do) for the run to
    be the CLI's. Fixed-length algorithms only with ``map_batch`` (SCEA runs in process).
    ``label``: what the run's errors call the run file (default its path).
    Returns the last generation's record (``generation``, ``evaluations``,
    ``feasible_fraction``, ``hypervolume``, ``front``, ...) and ``wall_time_s``. Raises
    :class:`DesignError` naming the file, field and value."""
    text = _native.run_design(
        os.fspath(out),
        None if config is None else os.fspath(config),
        resume=resume,
        generations=generations,
        map_batch=map_batch,
        label=label,
    )
    return json.loads(text)


def design_presets() -> list:
    """Names of the built-in design problems."""
    return list(_native.design_presets())


__all__ = [
    "DesignProblem",
    "RobustDesignProblem",
    "VariableDesignProblem",
    "design_presets",
    "design_run_config",
    "design_run_config_of_flags",
    "pymoo_problem",
    "run_design",
]
