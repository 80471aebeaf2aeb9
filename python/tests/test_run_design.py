"""The design run directory from Python (``reentry.run_design``, host-sim ``design::run``):
a run started in Python resumes with ``host-sim optimize --resume`` and the other way round,
and a run on Dask writes the CLI's directory, bit for bit, also after a killed worker and
after its client (with its cluster) was killed mid-run."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import reentry
from reentry.distributed import run_design_on_dask

REPO = Path(__file__).resolve().parents[2]


def _run_file(tmp_path: Path, generations: int, host_sim, name="run.toml", robust=False) -> Path:
    """A small SRM run file (population 6), from ``host-sim optimize --print-config``; with
    ``robust`` the example robust run (NSGA-II, population 8, 4 flights per candidate)."""
    if robust:
        text = (REPO / "examples" / "optimize-robust-srm.toml").read_text()
        base = REPO / "examples" / "srm-glide-replanning.toml"
        lines = []
        for line in text.splitlines():
            key = line.split("=")[0].strip()
            if key == "population":
                line = "population = 8"
            elif key == "neighbours":
                line = "neighbours = 5"
            elif key == "generations":
                line = f"generations = {generations}"
            elif key == "cases":
                line = "cases = 4"
            elif key == "base":
                line = f'base = "{base}"'
            elif key == "nominal_front":
                continue
            lines.append(line)
        text = "\n".join(lines) + "\n"
    else:
        text = host_sim(
            "optimize", "--problem", "srm", "--population", "6", "--generations",
            str(generations), "--print-config", "moead", "--neighbours", "5",
        ).stdout
    p = tmp_path / name
    p.write_text(text)
    return p


def _result(d: Path):
    return (d / "checkpoint.json").read_text(), (d / "front.csv").read_text()


@pytest.fixture(scope="module")
def straight(tmp_path_factory, host_sim):
    """The CLI's uninterrupted run of 3 generations."""
    tmp = tmp_path_factory.mktemp("straight")
    cfg = _run_file(tmp, 3, host_sim)
    host_sim("optimize", "--config", cfg, "--out", tmp / "run")
    return _result(tmp / "run")


def test_python_run_resumes_in_the_cli_and_the_cli_run_in_python(tmp_path, host_sim, straight):
    # Started in Python (host-sim threads), resumed by the CLI.
    one = _run_file(tmp_path, 1, host_sim)
    last = reentry.run_design(tmp_path / "py", one)
    assert last["generation"] == 1 and last["evaluations"] == 12
    host_sim("optimize", "--resume", tmp_path / "py", "--generations", "3")
    assert _result(tmp_path / "py") == straight
    # Started by the CLI, resumed in Python with a Python evaluator.
    host_sim("optimize", "--config", one, "--out", tmp_path / "cli")
    problem = reentry.DesignProblem(tmp_path / "cli" / "config.toml")
    batches = []

    def map_batch(xs):
        batches.append(len(xs))
        return reentry.evaluate_batch(problem, xs)

    last = reentry.run_design(tmp_path / "cli", resume=True, generations=3, map_batch=map_batch)
    assert last["generation"] == 3
    assert sum(batches) == 12, batches
    assert _result(tmp_path / "cli") == straight


def test_run_design_refuses_what_it_cannot_run(tmp_path, host_sim):
    with pytest.raises(ValueError, match="give config"):
        reentry.run_design(tmp_path / "x")
    with pytest.raises(ValueError, match="only with resume"):
        reentry.run_design(tmp_path / "x", _run_file(tmp_path, 1, host_sim), generations=2)
    bad = tmp_path / "bad.toml"
    bad.write_text(_run_file(tmp_path, 1, host_sim).read_text().replace("population = 6", "population = 1"))
    with pytest.raises(reentry.DesignError, match="population"):
        reentry.run_design(tmp_path / "x", bad)
    # An evaluator that raises stops the run with its message; the checkpoint of the last
    # complete generation (none here) is all that is written.
    def broken(xs):
        raise RuntimeError("no cluster")

    with pytest.raises(reentry.DesignError, match="no cluster"):
        reentry.run_design(tmp_path / "y", _run_file(tmp_path, 1, host_sim), map_batch=broken)
    assert not (tmp_path / "y" / "checkpoint.json").exists()


def test_a_dask_run_is_the_cli_run_after_a_killed_worker(tmp_path, host_sim, client, straight):
    # Kill one worker process as the first batch goes out (its nanny starts a new one): Dask
    # retries the lost tasks and the run's directory is the CLI's.
    killed = []
    from reentry import distributed

    plain = distributed.dask_batch_evaluator

    def killing(client_, problem, chunk_size=None):
        inner = plain(client_, problem, chunk_size)

        def map_batch(xs):
            if len(killed) == 0 and len(xs) >= 1:
                worker = sorted(client_.scheduler_info()["workers"])[0]
                pid = client_.run(os.getpid, workers=[worker])[worker]
                killed.append(worker)
                # Killed as the batch goes out: the scheduler learns of it while it assigns
                # the batch's tasks (and its nanny starts a new worker).
                os.kill(pid, signal.SIGKILL)
            return inner(xs)

        return map_batch

    distributed.dask_batch_evaluator = killing
    try:
        cfg = _run_file(tmp_path, 3, host_sim)
        run_design_on_dask(tmp_path / "dask", cfg, client=client)
    finally:
        distributed.dask_batch_evaluator = plain
    assert killed
    assert _result(tmp_path / "dask") == straight


_CHILD = """
import sys
from reentry.distributed import local_cluster, run_design_on_dask
import dask.distributed as dd
with local_cluster(2) as cluster, dd.Client(cluster) as client:
    run_design_on_dask(sys.argv[1], sys.argv[2], client=client)
"""


def test_a_robust_dask_run_resumes_after_its_client_and_cluster_were_killed(tmp_path, host_sim, client):
    cfg = _run_file(tmp_path, 3, host_sim, robust=True)
    host_sim("optimize", "--config", cfg, "--out", tmp_path / "cli")
    want = _result(tmp_path / "cli")
    out = tmp_path / "dask"
    child = subprocess.Popen(
        [sys.executable, "-c", _CHILD, str(out), str(cfg)], start_new_session=True,
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )
    try:
        deadline = time.monotonic() + 300
        while not (out / "population" / "gen_0001.csv").exists():
            assert child.poll() is None, "the run ended before it was killed"
            assert time.monotonic() < deadline, "no generation-1 checkpoint in 300 s"
            time.sleep(0.05)
    finally:
        os.killpg(child.pid, signal.SIGKILL)
        child.wait()
    assert not (out / "front.csv").exists(), "killed before the end"
    run_design_on_dask(out, resume=True, client=client)
    assert _result(out) == want


def test_design_run_config_is_a_checked_run_file(tmp_path):
    text = reentry.design_run_config("srm", population=6, neighbours=5, generations=1, seed=4)
    assert "population = 6" in text and "seed = 4" in text and 'base = "srm"' in text
    p = tmp_path / "run.toml"
    p.write_text(text)
    assert reentry.run_design(tmp_path / "run", p)["evaluations"] == 12
    with pytest.raises(reentry.DesignError, match="populaton"):
        reentry.design_run_config("srm", populaton=6)
    with pytest.raises(reentry.DesignError, match="reference"):
        reentry.design_run_config("srm", reference=[1.0])
    with pytest.raises(reentry.DesignError, match="no-such-preset"):
        reentry.design_run_config("no-such-preset")


def test_reentry_dask_optimize_config_and_resume_are_the_cli_run(
    tmp_path, host_sim, client, straight, capsys, monkeypatch
):
    from reentry.distributed import main

    address = client.scheduler.address
    one = _run_file(tmp_path, 1, host_sim)
    out = tmp_path / "dask"
    assert main(["optimize", "--config", str(one), "--scheduler", address, "--out", str(out)]) == 0
    first = capsys.readouterr().out.strip().splitlines()[-1]
    cli = host_sim("optimize", "--config", one, "--out", tmp_path / "cli").stdout.strip()
    # The library's result line, the CLI's but for the wall time and the directory.
    strip = lambda s: s.split(" evaluations in ")[0] + s.split(" s in this run")[1].split("; wrote")[0]  # noqa: E731
    assert strip(first) == strip(cli.splitlines()[-1])
    assert first.endswith(f"; wrote {out}")
    # --resume with a new total on Dask, as host-sim optimize --resume: the straight run.
    assert main(["optimize", "--resume", str(out), "--generations", "3", "--scheduler", address]) == 0
    assert _result(out) == straight
    # The flags the run file decides are refused, as the CLI refuses them.
    assert main(["optimize", "--config", str(one), "--local", "nsga2"]) == 2
    assert main(["optimize", "--resume", str(out), "--seed", "3", "--local"]) == 2
    assert main(["optimize", "--config", str(one), "--evaluations", "30", "--local"]) == 2
    err = capsys.readouterr().err
    assert "nsga2 beside --config" in err and "--seed beside --resume" in err
    # Without --out: the CLI's default directory, runs/optimize-<base>.
    monkeypatch.chdir(tmp_path)
    assert main(["optimize", "--config", str(one), "--local"]) == 0
    assert (tmp_path / "runs" / "optimize-srm" / "front.csv").read_text() == (
        tmp_path / "cli" / "front.csv"
    ).read_text()


def test_reentry_dask_optimize_on_a_preset_is_the_cli_run(tmp_path, host_sim, client, straight, capsys):
    """``reentry-dask optimize --problem srm [FLAGS]`` runs the run file of the flags
    (host-sim's mapping): the CLI's run directory, which ``--resume`` continues on Dask to the
    straight run; the flags the re-entry problems fix are refused with host-sim's reason."""
    from reentry.distributed import main

    flags = ["--problem", "srm", "--population", "6", "--generations", "1", "moead", "--neighbours", "5"]
    # --print-config prints host-sim's run file of the flags.
    assert main(["optimize", *flags, "--print-config"]) == 0
    assert capsys.readouterr().out == host_sim("optimize", *flags, "--print-config").stdout
    out = tmp_path / "dask"
    assert main(["optimize", *flags, "--scheduler", client.scheduler.address, "--out", str(out)]) == 0
    host_sim("optimize", *flags, "--out", tmp_path / "cli")
    assert _result(out) == _result(tmp_path / "cli")
    assert (out / "config.toml").read_text() == (tmp_path / "cli" / "config.toml").read_text()
    assert main(["optimize", "--resume", str(out), "--generations", "3", "--scheduler", client.scheduler.address]) == 0
    assert _result(out) == straight
    capsys.readouterr()
    for extra, flag in ((["--resource-allocation"], "--resource-allocation"), (["--evaluations", "60"], "--evaluations")):
        args = ["optimize", "--problem", "srm", "moead", *extra, "--local", "--out", str(tmp_path / "refused")]
        assert main(args) == 1
        err = capsys.readouterr().err
        hs = host_sim(*args[:-3], check=False)
        assert hs.returncode != 0
        reason = err.split(": ", 2)[-1].strip()
        assert err.startswith(f"error: {flag} does not apply") and reason in hs.stderr, (err, hs.stderr)
    assert not (tmp_path / "refused").exists()
    # SCEA evaluates in process: on Dask it is refused naming the flags, not a file.
    assert main(["optimize", "--problem", "srm", "scea", "--population", "6", "--neighbours", "5",
                 "--generations", "1", "--scheduler", client.scheduler.address,
                 "--out", str(tmp_path / "scea")]) == 1
    assert capsys.readouterr().err.startswith("error: command line: field `algorithm` = scea")
