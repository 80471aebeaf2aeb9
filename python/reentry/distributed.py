"""Optimisation and flight campaigns on Dask (``dask.distributed``): no home-made
distribution layer.

* Optimisation: the algorithm's ask/tell loop stays in the client; each batch of decisions is
  cut into chunks, one Dask task per chunk (so task overhead stays small against the
  evaluations), and the evaluations are told back by index. The run is bit-identical to the
  single-machine run with the same seed (the algorithms only depend on the evaluations, which
  are pure functions of the decisions).
* Dispersion campaigns (:func:`run_dispersions`): the campaign's ``(mode, case)`` jobs are
  cut into chunks of consecutive jobs, one task per chunk; a task carries the campaign's spec
  (a short JSON text), each worker process builds the campaign once (cached) and flies its
  jobs; the results come back keyed by job position and are assembled into host-sim's table.
* Scenario campaigns: a list of cases (scenarios) is cut into chunks of consecutive indices, one task
  per chunk; every result carries its case index and the table is assembled by index, so a
  task re-run after a worker died (Dask reschedules tasks lost with a worker, ``retries``
  covers exceptions) can neither lose nor duplicate a case.

Command line: ``python -m reentry.distributed {optimize,dispersions,campaign,bench,
bench-dispersions} --help`` (or
``reentry-dask``), with ``--scheduler tcp://HOST:8786`` or a ``LocalCluster`` of
``--workers N`` processes (no dashboard and no fixed port; ``--dashboard :0`` for one on a free
port). See docs/reference/python.md.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
import tempfile
import time
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence

import numpy as np

from .design import DesignProblem, RobustDesignProblem, design_run_config_of_flags, run_design
from .dispersions import DispersionCampaign
from .flight import _source, fly_summary, scenario_dict
from .optim import (
    TestProblem, evaluate_batch, evolve, from_options, generations_for, run_variable_length,
)
from . import _native


# --------------------------------------------------------------------------- tasks


def _evaluate_chunk(problem, start: int, xs: np.ndarray):
    """Task: evaluations of decisions ``xs`` (rows), keyed by their first index."""
    return start, evaluate_batch(problem, xs.tolist())


def _fly_chunk(start: int, cases: Sequence[Any]):
    """Task: summaries of consecutive cases, keyed by their first index."""
    return start, [_fly_case(c) for c in cases]


_CAMPAIGNS: Dict[str, DispersionCampaign] = {}


def _campaign_of(spec_json: str) -> DispersionCampaign:
    """The campaign of a spec, built once per worker process (its set-up flies nominal
    flights) and kept (the two most recent specs)."""
    c = _CAMPAIGNS.get(spec_json)
    if c is None:
        c = DispersionCampaign(_spec=spec_json)
        while len(_CAMPAIGNS) >= 2:
            _CAMPAIGNS.pop(next(iter(_CAMPAIGNS)))
        _CAMPAIGNS[spec_json] = c
    return c


def _fly_dispersion_chunk(spec_json: str, start: int, jobs: Sequence[tuple]):
    """Task: case results (JSON texts) of consecutive jobs, keyed by their first position."""
    return start, _campaign_of(spec_json).fly_jobs(jobs)


def _fly_case(case) -> Dict[str, Any]:
    return fly_summary(case)


def _chunks(n: int, chunk_size: int) -> List[range]:
    return [range(s, min(n, s + chunk_size)) for s in range(0, n, chunk_size)]


def _assemble(n: int, keyed: Sequence[tuple], what: str) -> List[Any]:
    """Place keyed chunk results by index; refuse gaps and duplicates."""
    out: List[Any] = [None] * n
    seen = np.zeros(n, dtype=bool)
    for start, results in keyed:
        for k, r in enumerate(results):
            i = start + k
            if seen[i]:
                raise RuntimeError(f"{what} {i} returned twice")
            seen[i] = True
            out[i] = r
    if not seen.all():
        raise RuntimeError(f"{what} {int(np.flatnonzero(~seen)[0])} is missing")
    return out


def default_chunk_size(n: int, workers: int, chunks_per_worker: int = 2) -> int:
    """Chunks of about ``n / (chunks_per_worker * workers)`` items: a few tasks per worker
    (load balance, and a lost task costs little) and few tasks in all (low overhead)."""
    return max(1, math.ceil(n / max(1, chunks_per_worker * workers)))


def _worker_count(client) -> int:
    return max(1, sum(w.get("nthreads", 1) for w in client.scheduler_info()["workers"].values()))


# --------------------------------------------------------------------------- optimisation


def dask_batch_evaluator(
    client, problem, chunk_size: Optional[int] = None, retries: int = 3
) -> Callable[[List[List[float]]], List[tuple]]:
    """A ``map_batch`` for :func:`reentry.evolve` that evaluates each batch on the Dask
    cluster of ``client``. The problem is shipped once (``scatter``, broadcast); it must
    pickle (ours do)."""
    [problem_future] = client.scatter([problem], broadcast=True, hash=False)

    def map_batch(xs: List[List[float]]) -> List[tuple]:
        n = len(xs)
        if n == 0:
            return []
        c = chunk_size or default_chunk_size(n, _worker_count(client))
        arr = np.asarray(xs, dtype=float)
        parts = _chunks(n, c)
        futures = client.map(
            _evaluate_chunk,
            [problem_future] * len(parts),
            [p.start for p in parts],
            [arr[p.start : p.stop] for p in parts],
            pure=False,
            retries=retries,
        )
        return _assemble(n, client.gather(futures), "evaluation")

    return map_batch


def evolve_on_dask(algorithm, problem, generations: int, client, chunk_size=None, observer=None):
    """:func:`reentry.evolve` with every batch evaluated on Dask (same result, bit for bit)."""
    return evolve(
        algorithm,
        problem,
        generations,
        map_batch=dask_batch_evaluator(client, problem, chunk_size),
        observer=observer,
    )


def _fly_robust_chunk(problem, decision: int, x: Sequence[float], indices: Sequence[int]):
    """Task: one part of a robust decision's evaluation (its cases ``indices``), keyed by the
    decision's position and the part's first case."""
    return decision, indices[0], problem.fly_cases(list(x), list(indices))


def robust_batch_evaluator(
    client, problem, cases_per_task: Optional[int] = None, retries: int = 3
) -> Callable[[List[List[float]]], List[tuple]]:
    """A ``map_batch`` for :func:`reentry.evolve` that splits each batch of a
    :class:`reentry.RobustDesignProblem` over decisions and flights: one Dask task per
    decision and chunk of ``cases_per_task`` consecutive cases (default: a decision's cases
    cut into enough chunks that the batch makes at least two tasks per worker thread: a batch
    of one decision still spreads its flights over the cluster). Each task sets its decision's campaign up again (one
    nominal flight) and flies its cases; the client gathers the parts of each decision and
    the library evaluates them (:meth:`~reentry.RobustDesignProblem.evaluate_parts`), so the
    evaluations, and the run, are those of the single-machine run, bit for bit."""
    [problem_future] = client.scatter([problem], broadcast=True, hash=False)
    k = problem.cases

    def map_batch(xs: List[List[float]]) -> List[tuple]:
        n = len(xs)
        if n == 0:
            return []
        parts_per_decision = max(1, math.ceil(2 * _worker_count(client) / n))
        c = cases_per_task or max(1, math.ceil(k / parts_per_decision))
        chunks = _chunks(k, c)
        jobs = [(i, ch) for i in range(n) for ch in chunks]
        futures = client.map(
            _fly_robust_chunk,
            [problem_future] * len(jobs),
            [i for i, _ in jobs],
            [list(map(float, xs[i])) for i, _ in jobs],
            [list(ch) for _, ch in jobs],
            pure=False,
            retries=retries,
        )
        parts: List[List[Optional[str]]] = [[] for _ in range(n)]
        for decision, _first, part in client.gather(futures):
            parts[decision].append(part)
        return [problem.evaluate_parts(p) for p in parts]

    return map_batch


def run_design_on_dask(
    out,
    config=None,
    *,
    client,
    resume: bool = False,
    generations: Optional[int] = None,
    chunk_size: Optional[int] = None,
    label: Optional[str] = None,
) -> dict:
    """:func:`reentry.run_design` with every batch evaluated on the Dask cluster of
    ``client``: the run directory, checkpoints and result of ``host-sim optimize --config
    config --out out`` (or ``--resume out``), bit for bit. A nominal run's batches are split
    over decisions (:func:`dask_batch_evaluator`), a robust run's (a ``[robust]`` section)
    over decisions and flights (:func:`robust_batch_evaluator`). The run is checkpointed after
    every generation: a lost worker's tasks are retried by Dask, and a run whose client or
    scheduler died resumes from its directory (``resume=True``), here or with the CLI."""
    path = os.path.join(os.fspath(out), "config.toml") if resume else os.fspath(config)
    if _native.run_file_info(path)[0] == "robust":
        map_batch = robust_batch_evaluator(client, RobustDesignProblem(path), chunk_size)
    else:
        map_batch = dask_batch_evaluator(client, DesignProblem(path), chunk_size)
    return run_design(
        out, None if resume else config, resume=resume, generations=generations,
        map_batch=map_batch, label=label,
    )


# --------------------------------------------------------------------------- campaigns


def _flatten(d: Dict[str, Any], prefix: str = "") -> Dict[str, Any]:
    out: Dict[str, Any] = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, key + "."))
        elif isinstance(v, list):
            out[key] = json.dumps(v)
        else:
            out[key] = v
    return out


def summaries_table(summaries: Sequence[Dict[str, Any]]):
    """One row per case (index ``case``), the summary's fields flattened
    (``peak_heat_flux_kw_m2.value``; lists as JSON text)."""
    import pandas as pd

    df = pd.DataFrame([_flatten(s) for s in summaries])
    df.index.name = "case"
    return df


def fly_campaign(cases: Sequence[Any], client=None, chunk_size: Optional[int] = None, retries: int = 3):
    """Fly every case (a scenario: dict, TOML text or path) and return the summaries table
    (:func:`summaries_table`). ``client=None`` flies them here, in order; with a Dask client
    the cases are flown on its workers in chunks of consecutive indices and gathered by index:
    the same table, bit for bit. Scenario errors raise :class:`reentry.ScenarioError` naming
    the case's file/field/value."""
    cases = list(cases)
    for c in cases:  # fail early, in the client, on malformed input
        _source(c, None)
    if client is None:
        return summaries_table([_fly_case(c) for c in cases])
    n = len(cases)
    c = chunk_size or default_chunk_size(n, _worker_count(client))
    parts = _chunks(n, c)
    futures = client.map(
        _fly_chunk,
        [p.start for p in parts],
        [cases[p.start : p.stop] for p in parts],
        pure=False,
        retries=retries,
    )
    return summaries_table(_assemble(n, client.gather(futures), "case"))


def dispersion_results(
    campaign: DispersionCampaign, client, chunk_size: Optional[int] = None, retries: int = 3
) -> List[str]:
    """Fly every job of ``campaign`` on the Dask cluster of ``client``: chunks of consecutive
    jobs (default about 2 per worker thread), one task each, gathered by job position (gaps
    and duplicates refused; a task lost with a worker is re-run by the scheduler, ``retries``
    re-runs tasks that raised). Returns the ``CaseResult`` JSON texts in ``campaign.jobs()``
    order: the same texts, bit for bit, as ``campaign.run_local()``."""
    jobs = campaign.jobs()
    n = len(jobs)
    c = chunk_size or default_chunk_size(n, _worker_count(client))
    parts = _chunks(n, c)
    spec = campaign.spec_json()
    futures = client.map(
        _fly_dispersion_chunk,
        [spec] * len(parts),
        [p.start for p in parts],
        [jobs[p.start : p.stop] for p in parts],
        pure=False,
        retries=retries,
    )
    return _assemble(n, client.gather(futures), "job")


def run_dispersions(
    campaign: DispersionCampaign,
    client=None,
    chunk_size: Optional[int] = None,
    retries: int = 3,
    out: Optional[str] = None,
    threads: Optional[int] = None,
):
    """Run a dispersion campaign and return its table (:meth:`DispersionCampaign.table`).
    ``client=None``: in this process (host-sim ``run_campaign``, ``threads`` threads);
    with a Dask client: on its workers (:func:`dispersion_results`), the same table bit for
    bit. ``out``: also write the CLI's files there (summary.json, cases-<mode>.csv, plots)."""
    if client is None:
        results = campaign.run_local(threads)
    else:
        results = dispersion_results(campaign, client, chunk_size, retries)
    if out:
        campaign.write(out, results)
    return campaign.table(results)


def gamma_sweep_cases(
    n: int, gamma_from_deg: float, gamma_to_deg: float, builtin: str = "horus-2b-reference", path=None
) -> List[dict]:
    """``n`` copies of a scenario with the entry flight-path angle swept linearly [deg] (a
    simple deterministic campaign of scenarios; dispersion campaigns: :func:`run_dispersions`)."""
    base = scenario_dict(builtin, path)
    cases = []
    for g in np.linspace(gamma_from_deg, gamma_to_deg, n):
        sc = json.loads(json.dumps(base))
        sc.setdefault("entry", {})["flight_path_angle_deg"] = float(g)
        sc["name"] = f"{base.get('name', 'case')}-gamma{float(g):.6f}"
        cases.append(sc)
    return cases


# --------------------------------------------------------------------------- command line


def local_cluster(workers: int, threads_per_worker: int = 1, dashboard_address: Optional[str] = None):
    """A ``LocalCluster`` of ``workers`` worker processes that binds no fixed port, so it
    coexists with other runs and with a user's own Dask on the machine.

    ``dashboard_address=None`` (default): no dashboard, and the scheduler's HTTP server (health
    and metrics routes, which ``distributed`` starts even without a dashboard, by default on
    port 8787) on a free port of the loopback interface. An address turns the dashboard on
    there: ``":0"`` (a free port, see ``client.dashboard_link``), ``":8787"`` (Dask's usual
    port, with its fall-back to a free one and a warning when taken), ``"127.0.0.1:8790"``."""
    if int(workers) < 1:
        raise ValueError(f"local_cluster: workers = {workers}: use at least 1 (a cluster without workers never runs a task)")
    if int(threads_per_worker) < 1:
        raise ValueError(f"local_cluster: threads_per_worker = {threads_per_worker}: use at least 1")
    from dask.distributed import LocalCluster

    kwargs: Dict[str, Any] = dict(n_workers=workers, threads_per_worker=threads_per_worker, processes=True)
    if dashboard_address is None:
        # dashboard_address=None alone turns the dashboard off but still binds the HTTP server
        # to distributed's default port 8787; the scheduler's own address sets where it binds.
        return LocalCluster(dashboard_address=None, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"}, **kwargs)
    return LocalCluster(dashboard_address=dashboard_address, **kwargs)


@contextlib.contextmanager
def client_for(
    scheduler: Optional[str], workers: int, threads_per_worker: int = 1, dashboard_address: Optional[str] = None
) -> Iterator[Any]:
    """A Dask client: connected to ``scheduler`` (``tcp://host:port``) or to a new
    ``LocalCluster`` of ``workers`` worker processes (:func:`local_cluster`: no dashboard and
    no fixed port unless ``dashboard_address`` is given)."""
    from dask.distributed import Client

    if scheduler:
        with Client(scheduler) as client:
            yield client
        return
    with local_cluster(workers, threads_per_worker, dashboard_address) as cluster, Client(cluster) as client:
        if dashboard_address is not None:
            print(f"Dask dashboard: {client.dashboard_link}", file=sys.stderr)
        yield client


def _write_atomic(path: str, text: str) -> None:
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _write_table(df, path: str) -> None:
    if path.endswith(".parquet"):
        d = os.path.dirname(os.path.abspath(path))
        fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-", suffix=".parquet")
        os.close(fd)
        df.to_parquet(tmp)
        os.replace(tmp, path)
    else:
        _write_atomic(path, df.to_csv(float_format="%.17g"))


#: ``reentry-dask optimize``'s algorithm flags, as host-sim ``RunOptions`` fields (the
#: flags' names with underscores; unset ones take host-sim optimize's defaults).
_OPTION_FLAGS = (
    "algorithm", "moead_operator", "population", "weights", "neighbours", "mutation_probability",
    "batch_size", "archive", "resource_allocation", "ker", "n_gen_mark", "mhaco_constraints",
    "scea_genes",
)


def _options(a) -> Dict[str, Any]:
    # An algorithm's subcommand holds only its own flags: the others are absent.
    return {k: getattr(a, k) for k in _OPTION_FLAGS if getattr(a, k, None) is not None}


def _reference_arg(text: str) -> List[float]:
    """``--ref``: host-sim's parser (finite numbers, comma-separated), its message on error."""
    try:
        return _native.parse_reference(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


#: ``--generations``'s default, host-sim optimize's (a resumed run keeps its own total unless
#: another is given).
_DEFAULT_GENERATIONS = 250

#: The flags ``--resume`` refuses (the run keeps its config.toml), with their defaults.
_NOT_WITH_RESUME = (
    ("problem", "zdt1"), ("population", None), ("evaluations", None), ("seed", 1),
    ("objectives", 3), ("ref", None), ("out", None),
)


def _cmd_optimize_run_file(a) -> int:
    """``--config FILE`` or ``--resume DIR``: host-sim optimize's design run and run directory
    (:func:`reentry.run_design`), its batches on Dask unless ``--local``."""
    def refuse(why: str) -> int:
        print(f"error: command line: {why}", file=sys.stderr)
        return 2

    if a.algorithm is not None:
        return refuse(
            f"{a.algorithm} beside --config or --resume: the run file decides the algorithm "
            "and its settings; drop the subcommand"
        )
    if a.evaluations is not None:
        return refuse("--evaluations beside --config or --resume: the run file sets generations")
    resume = a.resume is not None
    if resume:
        given = [f"--{k}" for k, default in _NOT_WITH_RESUME if getattr(a, k) != default]
        if given:
            return refuse(f"{', '.join(given)} beside --resume: the run keeps its config.toml")
        out, config = a.resume, None
        kind_of = os.path.join(out, "config.toml")
    else:
        out, config = a.out, a.config
        kind_of = config
    generations = (
        a.generations if resume and a.generations != _DEFAULT_GENERATIONS else None
    )
    return _run_design_run(a, out, config, kind_of, resume, generations)


def _run_design_run(a, out, config, kind_of, resume: bool, generations, label=None) -> int:
    """The design run of ``config`` (or ``--resume``) into ``out`` (default: the CLI's
    directory of the run file ``kind_of``), here or on Dask; prints the library's line.
    ``label``: what errors call the run file (default its path)."""
    _kind, default_dir = _native.run_file_info(kind_of)  # a bad file: its error, exit 1
    out = out or os.fspath(default_dir)
    if a.local:
        last = run_design(out, config, resume=resume, generations=generations, label=label)
        where = "in this process (the run file's threads)"
    else:
        with client_for(a.scheduler, a.workers, dashboard_address=a.dashboard) as client:
            last = run_design_on_dask(
                out, config, client=client, resume=resume, generations=generations,
                chunk_size=a.chunk_size, label=label,
            )
            where = a.scheduler or f"LocalCluster({a.workers} processes)"
    if last.get("line"):
        print(last["line"])
    print(f"evaluated {where}", file=sys.stderr)
    return 0


def _flags_run_file(a) -> str:
    """The run file of the flags on the design preset ``--problem``, mapped and checked by
    host-sim (:func:`reentry.design_run_config_of_flags`, what ``host-sim optimize
    --print-config`` prints; the flags the re-entry problems fix refused there)."""
    return design_run_config_of_flags(
        a.problem, generations=a.generations, seed=a.seed, reference=a.ref,
        evaluations=a.evaluations, **_options(a),
    )


def _cmd_optimize_preset(a) -> int:
    """A design preset (``--problem srm``, ...): the run file of the flags
    (:func:`_flags_run_file`) run as with ``--config``: host-sim optimize's run directory,
    which either side resumes."""
    text = _flags_run_file(a)
    with tempfile.TemporaryDirectory() as tmp:
        config = os.path.join(tmp, "config.toml")
        with open(config, "w", encoding="utf-8") as f:
            f.write(text)
        # The run file is the flags': its errors name them, not a file gone with tmp.
        return _run_design_run(a, a.out, config, config, False, None, label="command line")


def _cmd_optimize_variable_length(a) -> int:
    """A variable-length test problem (``vlmop1`` ... ``vlmop5``): host-sim's run
    (:func:`reentry.run_variable_length`) in this process; its evaluations are not split
    over Dask, so ``--local`` is required rather than a cluster left idle."""
    if not a.local:
        print(
            f"error: command line: --problem {a.problem}: a variable-length problem evaluates "
            "in this process (host-sim's run): add --local",
            file=sys.stderr,
        )
        return 2
    line = run_variable_length(
        a.problem, a.generations, a.seed, evaluations=a.evaluations, reference=a.ref,
        out=a.out, **_options(a),
    )
    print(line)
    print("evaluated in this process, 1 evaluation thread(s)", file=sys.stderr)
    if a.out:
        print(f"wrote {a.out}")
    return 0


def _cmd_optimize(a) -> int:
    if a.print_config:
        if a.config is not None or a.resume is not None:
            print(
                "error: command line: --print-config prints the run file of the flags; drop "
                "--config and --resume",
                file=sys.stderr,
            )
            return 2
        print(_flags_run_file(a), end="")
        return 0
    if a.config is not None or a.resume is not None:
        return _cmd_optimize_run_file(a)
    if a.problem in _native.design_presets():
        return _cmd_optimize_preset(a)
    if a.problem in _native.variable_length_problems():
        return _cmd_optimize_variable_length(a)
    problem = TestProblem(a.problem, a.objectives)
    reference = a.ref  # None: the problem's own
    if reference is not None:  # refused before the run, not after it
        _native.check_reference(reference, problem.get_nobj())
    options = _options(a)
    algo = from_options(a.seed, **options)
    generations = (
        a.generations
        if a.evaluations is None
        else generations_for(a.evaluations, problem.get_nobj(), **options)
    )
    t0 = time.perf_counter()
    if a.local:
        evolve(algo, problem, generations)
        threads, where = 1, "in this process"
    else:
        with client_for(a.scheduler, a.workers, dashboard_address=a.dashboard) as client:
            evolve_on_dask(algo, problem, generations, client, a.chunk_size)
            threads = _worker_count(client)
            where = a.scheduler or f"LocalCluster({a.workers} processes)"
    wall = time.perf_counter() - t0
    line = algo.run_report(
        problem, a.seed, wall, reference=reference, threads=threads,
        name=a.problem, generations=generations, out=a.out,
    )
    print(line)
    print(f"evaluated {where}, {threads} evaluation thread(s)", file=sys.stderr)
    if a.out:
        print(f"wrote {a.out}")
    return 0


def _campaign(a) -> DispersionCampaign:
    return DispersionCampaign(
        a.scenario,
        builtin=None if a.scenario else a.builtin,
        settings=a.settings,
        cases=a.cases,
        seed=a.seed,
        interface_speed_m_s=a.interface_speed,
        modes=a.modes,
    )


def _cmd_dispersions(a) -> int:
    t0 = time.perf_counter()
    campaign = _campaign(a)
    if a.local:
        df = run_dispersions(campaign, out=a.out, threads=a.threads)
    else:
        with client_for(a.scheduler, a.workers, dashboard_address=a.dashboard) as client:
            df = run_dispersions(campaign, client, a.chunk_size, out=a.out)
    wall = time.perf_counter() - t0
    print(
        f"{len(df)} flights ({campaign.cases} cases x {len(campaign.modes)} modes) in "
        f"{wall:.2f} s ({len(df) / wall:.1f} flights/s)",
        file=sys.stderr,
    )
    if a.table:
        _write_table(df.set_index(["mode", "index"]), a.table)
    return 0


def _cases(a) -> List[dict]:
    return gamma_sweep_cases(a.cases, a.gamma_from_deg, a.gamma_to_deg, a.builtin, a.scenario)


def _cmd_campaign(a) -> int:
    cases = _cases(a)
    t0 = time.perf_counter()
    if a.local:
        df = fly_campaign(cases)
    else:
        with client_for(a.scheduler, a.workers, dashboard_address=a.dashboard) as client:
            df = fly_campaign(cases, client, a.chunk_size)
    wall = time.perf_counter() - t0
    print(f"{len(df)} cases in {wall:.2f} s ({len(df) / wall:.1f} flights/s)", file=sys.stderr)
    if a.out:
        _write_table(df, a.out)
    else:
        print(df.to_csv(float_format="%.17g"), end="")
    return 0


def _noop(i: int) -> int:
    """Bench task: nothing (the cost of a task round trip)."""
    return i


def _fly_chunk_timed(start: int, cases: Sequence[Any]):
    """Bench task: :func:`_fly_chunk` plus the seconds spent flying inside the task."""
    t0 = time.perf_counter()
    out = _fly_chunk(start, cases)
    return out[0], out[1], time.perf_counter() - t0


def _best(f, rounds: int):
    best = None
    for _ in range(rounds):
        t0 = time.perf_counter()
        r = f()
        dt = time.perf_counter() - t0
        if best is None or dt < best[0]:
            best = (dt, r)
    return best


def _cmd_bench(a) -> int:
    """Flights per second in process (serial) and on LocalClusters of 1..N worker processes,
    for several campaign sizes (best of --rounds), with the task-overhead fraction
    1 - (seconds flown inside tasks) / (wall x workers)."""
    sizes = sorted(set(a.sizes))
    all_cases = gamma_sweep_cases(max(sizes), a.gamma_from_deg, a.gamma_to_deg, a.builtin, a.scenario)
    pick = lambda n: all_cases[:: max(1, len(all_cases) // n)][:n]  # noqa: E731
    fly_campaign(all_cases[:2])  # warm up
    serial = {n: _best(lambda: fly_campaign(pick(n)), a.rounds) for n in sizes}
    print("| campaign size | where | chunk | wall [s] | flights/s | task-overhead fraction |")
    print("|---|---|---|---|---|---|")
    for n in sizes:
        print(f"| {n} | serial, in process | - | {serial[n][0]:.3f} | {n / serial[n][0]:.1f} | - |")
    for w in a.workers_list:
        t0 = time.perf_counter()
        with client_for(None, w, dashboard_address=a.dashboard) as client:
            client.wait_for_workers(w)
            startup = time.perf_counter() - t0
            client.gather(client.map(_fly_chunk, range(2 * w), [all_cases[:1]] * (2 * w), pure=False))
            noop, _ = _best(lambda: client.gather(client.map(_noop, range(500), pure=False)), a.rounds)
            for n in sizes:
                cases = pick(n)
                c = a.chunk_size or default_chunk_size(n, w)
                parts = _chunks(n, c)

                def run():
                    futs = client.map(
                        _fly_chunk_timed,
                        [p.start for p in parts],
                        [cases[p.start : p.stop] for p in parts],
                        pure=False,
                    )
                    return client.gather(futs)

                wall, res = _best(run, a.rounds)
                table = summaries_table(_assemble(n, [(r[0], r[1]) for r in res], "case"))
                if not table.equals(serial[n][1]):
                    raise RuntimeError("Dask campaign differs from the local one")
                busy = sum(r[2] for r in res)
                print(
                    f"| {n} | Dask LocalCluster, {w} process(es) | {c} | {wall:.3f} | "
                    f"{n / wall:.1f} | {1 - busy / (wall * w):.2f} |"
                )
            print(
                f"(LocalCluster of {w} process(es): {startup:.2f} s to start; 500 empty tasks "
                f"{noop:.3f} s, {noop / 500 * 1e3:.2f} ms per task)"
            )
    return 0


def _fly_dispersion_chunk_timed(spec_json: str, start: int, jobs: Sequence[tuple]):
    """Bench task: :func:`_fly_dispersion_chunk` plus the wall and CPU seconds spent inside
    the task (CPU: this thread's, which flies the jobs with the GIL released)."""
    t0, c0 = time.perf_counter(), time.thread_time()
    out = _fly_dispersion_chunk(spec_json, start, jobs)
    return out[0], out[1], time.perf_counter() - t0, time.thread_time() - c0


def _serial_cpu(c: DispersionCampaign):
    """Bench: the jobs flown in this thread; (results, CPU seconds)."""
    c0 = time.thread_time()
    r = c.fly_jobs(c.jobs())
    return r, time.thread_time() - c0


def _cmd_bench_dispersions(a) -> int:
    """Dispersion flights per second: one thread in process, host-sim's rayon campaign with
    all threads, and LocalClusters of --workers-list processes (one thread each), for several
    campaign sizes (best of --rounds), checking every table equals the serial one; with the
    task-overhead fraction 1 - (seconds inside tasks) / (wall x workers)."""
    sizes = sorted(set(a.sizes))
    camps = {n: _campaign_sized(a, n) for n in sizes}
    print(f"load average before: {os.getloadavg()}", file=sys.stderr)
    serial = {}
    print("| flights | where | chunk | wall [s] | flights/s | task-overhead fraction | CPU ms per flight |")
    print("|---|---|---|---|---|---|---|")
    for n, c in camps.items():
        wall, (res, cpu) = _best(lambda: _serial_cpu(c), a.rounds)
        serial[n] = (wall, res)
        flights = len(c.jobs())
        print(
            f"| {flights} | in process, 1 thread | - | {wall:.3f} | {flights / wall:.1f} | - | "
            f"{cpu / flights * 1e3:.1f} |"
        )
        wall, res = _best(lambda: c.run_local(), a.rounds)
        if res != serial[n][1]:
            raise RuntimeError("run_local differs from the serial run")
        print(f"| {flights} | in process, host-sim rayon ({os.cpu_count()} threads) | - | {wall:.3f} | {flights / wall:.1f} | - | - |")
    for w in a.workers_list:
        t0 = time.perf_counter()
        with client_for(None, w, dashboard_address=a.dashboard) as client:
            client.wait_for_workers(w)
            startup = time.perf_counter() - t0
            t1 = time.perf_counter()
            for c in camps.values():  # each worker builds each campaign's set-up once
                client.run(_campaign_of, c.spec_json())
            setup = time.perf_counter() - t1
            noop, _ = _best(lambda: client.gather(client.map(_noop, range(500), pure=False)), a.rounds)
            for n, camp in camps.items():
                jobs = camp.jobs()
                flights = len(jobs)
                c = a.chunk_size or default_chunk_size(flights, w)
                parts = _chunks(flights, c)
                spec = camp.spec_json()

                def run():
                    futs = client.map(
                        _fly_dispersion_chunk_timed,
                        [spec] * len(parts),
                        [p.start for p in parts],
                        [jobs[p.start : p.stop] for p in parts],
                        pure=False,
                    )
                    return client.gather(futs)

                wall, res = _best(run, a.rounds)
                got = _assemble(flights, [(r[0], r[1]) for r in res], "job")
                if got != serial[n][1]:
                    raise RuntimeError("Dask campaign differs from the local one")
                busy = sum(r[2] for r in res)
                cpu = sum(r[3] for r in res)
                print(
                    f"| {flights} | Dask LocalCluster, {w} process(es) | {c} | {wall:.3f} | "
                    f"{flights / wall:.1f} | {1 - busy / (wall * w):.2f} | {cpu / flights * 1e3:.1f} |"
                )
            print(
                f"(LocalCluster of {w} process(es): {startup:.2f} s to start, {setup:.2f} s for "
                f"the workers' campaign set-ups; 500 empty tasks {noop:.3f} s, "
                f"{noop / 500 * 1e3:.2f} ms per task)"
            )
    print(f"load average after: {os.getloadavg()}", file=sys.stderr)
    return 0


def _campaign_sized(a, n: int) -> DispersionCampaign:
    return DispersionCampaign(
        a.scenario,
        builtin=None if a.scenario else a.builtin,
        cases=n,
        seed=a.seed,
        interface_speed_m_s=a.interface_speed,
        modes=a.modes,
    )


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line entry point (``python -m reentry.distributed`` / ``reentry-dask``)."""
    p = argparse.ArgumentParser(prog="reentry-dask", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)

    def dashboard(sp, d=lambda v: v):
        sp.add_argument(
            "--dashboard",
            metavar="ADDRESS",
            default=d(None),
            help="with a LocalCluster: its Dask dashboard at ADDRESS (':0' a free port, ':8787'); "
            "default: no dashboard and no fixed port",
        )

    def where(sp, d=lambda v: v):
        # d: the defaults (optimize's algorithm subcommands: none, see optimize_common).
        g = sp.add_mutually_exclusive_group()
        g.add_argument("--scheduler", default=d(None), help="Dask scheduler address, e.g. tcp://10.0.0.1:8786")
        g.add_argument("--workers", type=int, default=d(2), help="LocalCluster worker processes (default 2)")
        g.add_argument("--local", action="store_true", default=d(False), help="no Dask: evaluate in this process")
        sp.add_argument("--chunk-size", type=int, default=d(None), help="items per Dask task (default: about 2 tasks per worker)")
        dashboard(sp, d)

    def optimize_common(sp, top: bool):
        # host-sim optimize's global flags, on `optimize` (top) and again on each algorithm's
        # subcommand so they may follow it; there without defaults (argparse.SUPPRESS), which
        # would overwrite the values given before the subcommand.
        d = (lambda v: v) if top else (lambda v: argparse.SUPPRESS)
        sp.add_argument(
            "--problem", default=d("zdt1"),
            help="a test problem (zdt1, dtlz2, constr, ...) or a design preset (horus-2b, srm, "
            "srm-altitude; the reference point default [0, 2, 10, ...], no true front)",
        )
        sp.add_argument("--objectives", type=int, default=d(3), help="objectives of a DTLZ problem (default 3)")
        sp.add_argument("--population", type=int, default=d(None), help="population size (default 100)")
        gens = sp.add_mutually_exclusive_group()
        gens.add_argument(
            "--generations", type=int, default=d(_DEFAULT_GENERATIONS),
            help=f"generations after the initial population (default {_DEFAULT_GENERATIONS}; with "
            "--resume: a new total, else the run's own)"
        )
        gens.add_argument(
            "--evaluations", type=int, default=d(None), metavar="E",
            help="moead and nsga2: budget in evaluations, initial population included, instead "
            "of --generations (the fewest whole generations that reach it)",
        )
        sp.add_argument("--seed", type=int, default=d(1), help="seed of the run (default 1)")
        sp.add_argument(
            "--ref", type=_reference_arg, default=d(None), metavar="R1,R2,...",
            help="hypervolume reference point (default: the problem's)",
        )
        sp.add_argument("--out", metavar="DIR", default=d(None), help="write population.csv, front.csv and summary.json here")
        sp.add_argument(
            "--print-config", action="store_true", default=d(False),
            help="print the run file of these flags on a design preset (host-sim optimize "
            "--print-config's text) and exit",
        )
        runs = sp.add_mutually_exclusive_group()
        runs.add_argument(
            "--config", metavar="FILE", default=d(None),
            help="a design run file: host-sim optimize --config's run and run directory "
            "(config.toml, checkpoints, records, front, member scenarios), batches on Dask",
        )
        runs.add_argument(
            "--resume", metavar="DIR", default=d(None),
            help="continue the design run in DIR from its last checkpoint (--generations: a "
            "new total), as host-sim optimize --resume; the CLI resumes it too",
        )
        where(sp, d)

    o = sub.add_parser(
        "optimize",
        help="host-sim optimize on a test or design problem (moead, nsga2, mhaco, scea), batches "
        "evaluated on Dask; the same subcommands, flags, defaults and --out files",
        description="host-sim optimize's subcommands (the algorithm, default moead), flags, "
        "defaults and run directory (population.csv, front.csv, summary.json, written by "
        "host-sim) with each batch of decisions evaluated on Dask; the run equals host-sim "
        "optimize's bit for bit. MOEA/D asks --batch-size decisions at a time (default 1, "
        "pagmo's steady state): use --batch-size > 1 (e.g. the population) to spread its "
        "evaluations over the workers. A design preset (--problem srm, ...) writes host-sim's "
        "design run directory (config.toml, checkpoints, records; --resume continues it).",
    )
    optimize_common(o, True)
    algorithms = o.add_subparsers(
        dest="algorithm", metavar="{moead,nsga2,mhaco,scea}",
        help="the algorithm and its own flags (default: moead with its defaults)",
    )

    def algorithm(name, help):
        sp = algorithms.add_parser(name, help=help, description=help)
        optimize_common(sp, False)
        return sp

    def archive(sp, who):
        sp.add_argument(
            "--archive", type=int, default=None, metavar="N",
            help=f"{who}: external archive of at most N feasible non-dominated solutions; "
            "the front written and scored is then the archive's (default none)",
        )

    def decomposition(sp, who):
        # MOEA/D's and SCEA's flags (host-sim's DecompositionArgs).
        sp.add_argument(
            "--weights", choices=["grid", "low-discrepancy", "random"], default=None,
            help="weight generation (default grid)",
        )
        sp.add_argument(
            "--neighbours", type=int, default=None,
            help="neighbourhood size (default 20, or population - 1 for populations of 20 or less)",
        )
        sp.add_argument(
            "--mutation-probability", type=float, default=None, metavar="P",
            help="per-variable mutation probability (default 1/variables)",
        )
        sp.add_argument(
            "--batch-size", type=int, default=None,
            help="offspring per ask (default 1: pagmo's steady state, one decision per batch, "
            "so no two evaluations run at once; use > 1 to spread them over the Dask workers)",
        )
        archive(sp, who)
        sp.add_argument(
            "--resource-allocation", action="store_const", const=True, default=None,
            help="MOEA/D-DRA's dynamic resource allocation (default off)",
        )

    m = algorithm("moead", "MOEA/D (pagmo semantics)")
    decomposition(m, "MOEA/D")
    m.add_argument(
        "--moead-operator", choices=["de", "sbx"], default=None,
        help="variation: de (pagmo's MOEA/D-DE, default) or sbx (Zhang & Li 2007)",
    )
    archive(algorithm("nsga2", "NSGA-II (pagmo semantics)"), "NSGA-II")
    h = algorithm("mhaco", "MHACO (pagmo's maco)")
    h.add_argument("--ker", type=int, default=None, metavar="K", help="solution archive size (default min(63, population))")
    h.add_argument("--n-gen-mark", type=int, default=None, metavar="G", help="n_gen_mark (default 7)")
    h.add_argument(
        "--mhaco-constraints", choices=["feasibility-first", "objectives"], default=None,
        help="constraint handling (default feasibility-first)",
    )
    c = algorithm("scea", "SCEA (structured chromosomes; on the fixed-length problems MOEA/D's loop)")
    decomposition(c, "SCEA")
    c.add_argument(
        "--scea-genes", choices=["random", "population", "history"], default=None,
        help="genes of appended nodes: random (the thesis' SCEA) or population (alias history; "
        "default)",
    )
    o.set_defaults(run=_cmd_optimize)

    def dispersion_args(sp, cases: bool):
        sp.add_argument("--builtin", default="horus-2b-reference", help="built-in scenario (horus-2b-reference, horus-2b-stored, srm-glide)")
        sp.add_argument("--scenario", help="scenario TOML file (instead of --builtin)")
        if cases:
            sp.add_argument("--settings", help="TOML file with a [dispersions] section")
            sp.add_argument("-n", "--cases", type=int, default=None, help="cases per mode (overrides the settings)")
        sp.add_argument("--seed", type=int, default=None)
        sp.add_argument("--interface-speed", type=float, default=None, help="terminal interface speed [m/s]")
        sp.add_argument(
            "--modes", type=lambda s: s.split(","), default=None,
            help="comma separated: stored, stored-reversals, replan-reversals (default all)",
        )

    d = sub.add_parser(
        "dispersions",
        help="a dispersion campaign (host-sim dispersions) on Dask: the CLI's files and/or a table",
    )
    dispersion_args(d, True)
    d.add_argument("--out", help="write host-sim dispersions' files here (summary.json, cases-<mode>.csv, plots)")
    d.add_argument("--table", help="write the case table (.csv with %%.17g, or .parquet with pyarrow)")
    d.add_argument("--threads", type=int, default=None, help="with --local: host-sim threads")
    where(d)
    d.set_defaults(run=_cmd_dispersions)

    bd = sub.add_parser("bench-dispersions", help="dispersion flights/s in process and on LocalClusters")
    dispersion_args(bd, False)
    bd.add_argument("--workers-list", type=lambda s: [int(x) for x in s.split(",")], default=[1, 2])
    bd.add_argument("--sizes", type=lambda s: [int(x) for x in s.split(",")], default=[4, 16, 64], help="cases per mode")
    bd.add_argument("--rounds", type=int, default=2, help="keep the best of this many runs")
    bd.add_argument("--chunk-size", type=int, default=None)
    dashboard(bd)
    bd.set_defaults(run=_cmd_bench_dispersions)

    for name, helptext, run in (
        ("campaign", "fly a flight-path-angle sweep of a scenario on Dask, write the summaries table", _cmd_campaign),
        ("bench", "flights/s serial and on LocalClusters of --workers-list processes", _cmd_bench),
    ):
        c = sub.add_parser(name, help=helptext)
        c.add_argument("--builtin", default="horus-2b-reference")
        c.add_argument("--scenario", help="scenario TOML file (instead of --builtin)")
        if name == "campaign":
            c.add_argument("--cases", type=int, default=100)
        c.add_argument("--gamma-from-deg", type=float, default=-1.6)
        c.add_argument("--gamma-to-deg", type=float, default=-1.2)
        if name == "campaign":
            c.add_argument("--out", help="table file (.csv, or .parquet with pyarrow)")
            where(c)
        else:
            ints = lambda s: [int(x) for x in s.split(",")]  # noqa: E731
            c.add_argument("--workers-list", type=ints, default=[1, 2])
            c.add_argument("--sizes", type=ints, default=[10, 30, 100, 300], help="campaign sizes")
            c.add_argument("--rounds", type=int, default=3, help="keep the best of this many runs")
            c.add_argument("--chunk-size", type=int, default=None)
            dashboard(c)
        c.set_defaults(run=run)

    a = p.parse_args(argv)
    try:
        return a.run(a)
    except _native.ReentryError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
