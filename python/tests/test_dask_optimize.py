"""``reentry-dask optimize`` is ``host-sim optimize`` on the test problems: the same flags and
defaults, and, in this process (``--local``) or on a 2-process Dask cluster, the same run
directory (population.csv and front.csv byte for byte, summary.json but for the wall time and
the thread count), written by host-sim."""

import json

import pytest

pytest.importorskip("dask.distributed")

from reentry.distributed import main  # noqa: E402

CASES = {
    # MOEA/D with a population of 20 needs --neighbours below 20; batches of the population
    # spread over the workers.
    "moead-zdt1": [
        "--problem", "zdt1", "moead", "--population", "20", "--neighbours", "5",
        "--batch-size", "20", "--generations", "4", "--seed", "3",
    ],
    "nsga2-constr-archive": [
        "--problem", "constr", "nsga2", "--population", "24", "--archive", "12",
        "--generations", "4", "--seed", "5",
    ],
    "moead-sbx-dtlz2-dra": [
        "--problem", "dtlz2", "--objectives", "3", "moead", "--population", "16", "--weights",
        "low-discrepancy", "--moead-operator", "sbx", "--mutation-probability", "0.1",
        "--batch-size", "4", "--resource-allocation", "--evaluations", "60", "--ref", "2,2,2",
        "--archive", "8",
    ],
    "scea-zdt1": [
        "--problem", "zdt1", "scea", "--population", "20", "--neighbours", "5",
        "--batch-size", "20", "--scea-genes", "random", "--generations", "4", "--seed", "3",
    ],
    "mhaco-constr": [
        "--problem", "constr", "mhaco", "--population", "20", "--ker", "10",
        "--n-gen-mark", "3", "--mhaco-constraints", "objectives", "--generations", "5",
        "--seed", "2",
    ],
}


def _read(d):
    return (
        (d / "population.csv").read_text(),
        (d / "front.csv").read_text(),
        json.loads((d / "summary.json").read_text()),
    )


def _same_run(ours, theirs, threads):
    pop, front, summary = _read(ours)
    hs_pop, hs_front, hs_summary = _read(theirs)
    assert pop == hs_pop
    assert front == hs_front
    assert summary["threads"] == threads
    for s in (summary, hs_summary):
        assert s.pop("wall_time_s") >= 0.0
        s.pop("threads")
    assert summary == hs_summary
    return hs_summary


@pytest.mark.parametrize("case", list(CASES))
def test_optimize_writes_host_sims_run_directory(host_sim, client, tmp_path, case, capsys):
    args = CASES[case]
    hs = host_sim("optimize", *args, "--out", tmp_path / "host-sim")
    assert main(["optimize", *args, "--local", "--out", str(tmp_path / "local")]) == 0
    printed = capsys.readouterr().out.splitlines()[0]
    address = client.scheduler.address
    assert main(["optimize", *args, "--scheduler", address, "--out", str(tmp_path / "dask")]) == 0
    summary = _same_run(tmp_path / "local", tmp_path / "host-sim", 1)
    _same_run(tmp_path / "dask", tmp_path / "host-sim", 2)
    # The printed line is host-sim's but for the wall time.
    hs_line = hs.stdout.splitlines()[0]
    cut = lambda line: line.split(" in ")[0] + line.split(" s,", 1)[1]  # noqa: E731
    assert cut(printed) == cut(hs_line)
    # The options reached the algorithm: the summary reports them.
    if "--archive" in args:
        assert summary["front_source"] == "archive"
        assert summary["archive_capacity"] == int(args[args.index("--archive") + 1])
    if "--moead-operator" in args:
        assert summary["moead_operator"] == "sbx" and summary["resource_allocation"] is True
    if "--evaluations" in args:
        assert summary["evaluations"] >= 60 and summary["reference_point"] == [2.0, 2.0, 2.0]
    assert summary["population"] == int(args[args.index("--population") + 1])


@pytest.mark.parametrize(
    "args",
    [
        ["--problem", "vlmop1", "scea", "--population", "20", "--neighbours", "5",
         "--scea-genes", "random", "--generations", "5", "--seed", "3"],
        ["--problem", "vlmop4", "mhaco", "--population", "20", "--ker", "10",
         "--generations", "5", "--seed", "2"],
    ],
    ids=["scea-vlmop1", "mhaco-vlmop4"],
)
def test_optimize_on_a_variable_length_problem_is_host_sims_run(host_sim, tmp_path, args, capsys):
    """A variable-length problem: host-sim's run (``reentry.run_variable_length``) with
    ``--local``, the CLI's files; on a cluster it is refused before anything runs; MOEA/D and
    NSGA-II are refused with host-sim's reason."""
    hs = host_sim("optimize", *args, "--out", tmp_path / "host-sim")
    assert main(["optimize", *args, "--local", "--out", str(tmp_path / "local")]) == 0
    printed = capsys.readouterr().out.splitlines()[0]
    _same_run(tmp_path / "local", tmp_path / "host-sim", 1)
    cut = lambda line: line.split(" in ")[0] + line.split(" s,", 1)[1]  # noqa: E731
    assert cut(printed) == cut(hs.stdout.splitlines()[0])
    assert main(["optimize", *args, "--workers", "2", "--out", str(tmp_path / "dask")]) == 2
    assert "add --local" in capsys.readouterr().err
    assert not (tmp_path / "dask").exists()
    problem = args[:2]
    assert main(["optimize", *problem, "nsga2", "--local"]) == 1
    reason = capsys.readouterr().err.split("nsga2: ", 1)[1].strip()
    hs = host_sim("optimize", *problem, "nsga2", check=False)
    assert hs.returncode != 0 and reason in hs.stderr, (reason, hs.stderr)


def test_optimize_defaults_are_host_sims(host_sim, tmp_path):
    """No flags but the problem and a short run: host-sim's defaults (MOEA/D, population 100,
    steady state, seed 1) on both sides."""
    args = ["--problem", "zdt1", "--generations", "2"]
    host_sim("optimize", *args, "--out", tmp_path / "host-sim")
    assert main(["optimize", *args, "--local", "--out", str(tmp_path / "local")]) == 0
    summary = _same_run(tmp_path / "local", tmp_path / "host-sim", 1)
    assert (summary["algorithm"], summary["population"], summary["seed"]) == ("moead", 100, 1)
    assert summary["evaluations"] == 300


@pytest.mark.parametrize(
    "flags",
    [
        ["moead", "--population", "20", "--neighbours", "25"],
        ["moead", "--population", "20", "--batch-size", "21"],
        ["moead", "--population", "20", "--mutation-probability", "1.5"],
        ["nsga2", "--population", "22"],
        ["mhaco", "--population", "20", "--ker", "21"],
    ],
    ids=["neighbours", "batch-size", "mutation-probability", "nsga2-population", "ker"],
)
def test_optimize_bad_values_give_the_librarys_message(host_sim, flags, capsys):
    args = ["--problem", "zdt1", "--generations", "1", *flags]
    hs = host_sim("optimize", *args, check=False)
    assert hs.returncode != 0
    assert main(["optimize", *args, "--local"]) == 1
    ours = capsys.readouterr().err.strip()
    assert ours.startswith("error: "), ours
    message = ours[len("error: "):]
    assert message and message in hs.stderr, (message, hs.stderr)


@pytest.mark.parametrize(
    "flags, flag",
    [
        (["nsga2", "--neighbours", "5"], "--neighbours"),
        (["mhaco", "--archive", "5"], "--archive"),
        # (argparse would read the value of a flag it does not know as the subcommand.)
        (["--resource-allocation"], "--resource-allocation"),
        (["moead", "--ker", "5"], "--ker"),
    ],
    ids=["nsga2-neighbours", "mhaco-archive", "no-subcommand-resource-allocation", "moead-ker"],
)
def test_optimize_refuses_a_flag_of_another_algorithm_as_host_sim_does(host_sim, flags, flag, capsys):
    """An algorithm's flags belong to its subcommand: both front ends refuse them elsewhere
    (usage error, exit code 2), naming the flag."""
    args = ["--problem", "zdt1", "--generations", "1", *flags]
    hs = host_sim("optimize", *args, check=False)
    assert hs.returncode == 2 and flag in hs.stderr, hs.stderr
    with pytest.raises(SystemExit) as e:
        main(["optimize", *args, "--local"])
    assert e.value.code == 2
    assert flag in capsys.readouterr().err


def test_optimize_common_flags_before_or_after_the_subcommand(tmp_path):
    """The common flags may follow the subcommand; given before it, the subcommand's parser
    keeps them (it sets no defaults of its own)."""
    before = ["--problem", "constr", "--seed", "4", "--population", "24", "--generations", "2", "nsga2"]
    after = ["nsga2", "--problem", "constr", "--seed", "4", "--population", "24", "--generations", "2"]
    for name, args in (("before", before), ("after", after)):
        assert main(["optimize", *args, "--local", "--out", str(tmp_path / name)]) == 0
    a, b = _read(tmp_path / "before"), _read(tmp_path / "after")
    assert a[:2] == b[:2]
    assert (a[2]["algorithm"], a[2]["seed"], a[2]["population"], a[2]["generations"]) == ("nsga2", 4, 24, 2)


def test_optimize_refuses_a_wrong_length_reference_before_the_run(tmp_path, capsys):
    # A million generations: were the reference checked after the run, this would not return.
    out = tmp_path / "run"
    args = ["optimize", "--problem", "zdt1", "--generations", "1000000", "--ref", "1,1,1"]
    assert main([*args, "--out", str(out), "--local"]) == 1
    err = capsys.readouterr().err
    assert "--ref: reference point has 3 values" in err and "2 objectives" in err, err
    assert not out.exists()


@pytest.mark.parametrize("ref, coordinate", [("1,nan", "coordinate 2: must be finite"), ("1,,", "coordinate 2: not a number")])
def test_a_malformed_reference_is_refused_with_host_sims_message(host_sim, ref, coordinate, capsys):
    # One parser (host_sim::optim::reference): the same words from both front ends.
    hs = host_sim("optimize", "--problem", "zdt1", "--ref", ref, check=False)
    assert hs.returncode != 0 and coordinate in hs.stderr, hs.stderr
    with pytest.raises(SystemExit) as e:
        main(["optimize", "--problem", "zdt1", "--ref", ref, "--local"])
    assert e.value.code == 2
    assert coordinate in capsys.readouterr().err
