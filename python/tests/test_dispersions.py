"""Dispersion campaigns (host-sim campaign): the local run equals `host-sim dispersions`
(every case result, and the written files byte for byte); any job order gives the same
results; on a 2-process Dask LocalCluster the table equals the local one bit for bit; a worker
killed mid-campaign loses and duplicates nothing; pickling; errors."""

import filecmp
import json
import os
import pickle

import numpy as np
import pytest

import reentry
from reentry.distributed import dispersion_results, run_dispersions

SRM = dict(builtin="srm-glide", interface_speed_m_s=2500.0)


@pytest.fixture(scope="module")
def small():
    """4 cases x every mode of the SRM glide, and its local results (host-sim run_campaign)."""
    c = reentry.DispersionCampaign(cases=4, **SRM)
    return c, c.run_local(threads=1)


def test_local_campaign_equals_host_sim_dispersions(host_sim, small, tmp_path):
    c, results = small
    cli_dir, py_dir = tmp_path / "cli", tmp_path / "py"
    host_sim(
        "dispersions", "--builtin", "srm-glide", "-n", "4", "--interface-speed", "2500",
        "--threads", "2", "--quiet", "--out", cli_dir,
    )
    assert len(results) == 4 * len(reentry.campaign_modes()) and c.modes == reentry.campaign_modes()
    for (mode, index), text in zip(c.jobs(), results):
        cli = json.loads((cli_dir / "cases" / mode / f"{index:06d}.json").read_text())
        assert cli == json.loads(text), (mode, index)
    files = c.write(py_dir, results)
    names = sorted(os.path.basename(f) for f in files)
    assert "summary.json" in names and "cases-replan-reversals.csv" in names
    for name in names:
        assert filecmp.cmp(py_dir / name, cli_dir / name, shallow=False), name
    # The cases differ (dispersed), and the modes fly differently.
    df = c.table(results)
    assert df["draw.altitude_m"].nunique() == 4
    assert df.groupby("mode")["miss_m"].apply(tuple).nunique() == len(c.modes)


def test_any_job_order_and_thread_count_give_the_same_results(small):
    c, results = small
    jobs = c.jobs()
    order = np.random.default_rng(5).permutation(len(jobs))
    shuffled = c.fly_jobs([jobs[i] for i in order])
    assert [shuffled[list(order).index(k)] for k in range(len(jobs))] == results
    assert c.run_local(threads=2) == results
    r = pickle.loads(pickle.dumps(c))
    assert type(r) is reentry.DispersionCampaign and r.spec_json() == c.spec_json()
    assert r.fly_jobs(jobs[5:7]) == results[5:7]


def test_table_and_write_refuse_gaps_and_duplicates(small, tmp_path):
    c, results = small
    with pytest.raises(ValueError, match=f"{len(results)} jobs"):
        c.table(results[:-1])
    with pytest.raises(ValueError, match="at the place of case"):
        c.table(results[1:] + results[:1])
    with pytest.raises(reentry.CampaignError, match="given twice"):
        c.write(tmp_path, results + results[:1])
    with pytest.raises(reentry.CampaignError, match="missing"):
        c.write(tmp_path, results[1:])


def test_errors_carry_host_sim_messages(host_sim, tmp_path):
    settings = tmp_path / "disp.toml"
    settings.write_text("[dispersions]\nmass = { distribution = \"normal\", three_sigma = 0.5 }\n")
    cli = host_sim("dispersions", "--builtin", "srm-glide", "--settings", settings, "--quiet",
                   "--out", tmp_path / "o", check=False)
    assert cli.returncode != 0
    with pytest.raises(reentry.CampaignError) as e:
        reentry.DispersionCampaign(builtin="srm-glide", settings=settings)
    assert str(e.value) and cli.stderr.strip().endswith(str(e.value))
    assert "dispersions.mass.three_sigma" in str(e.value)
    with pytest.raises(reentry.CampaignError, match="unknown mode"):
        reentry.DispersionCampaign(modes=["sideways"], cases=1, **SRM)
    with pytest.raises(reentry.CampaignError, match="outside the campaign"):
        reentry.DispersionCampaign(cases=2, **SRM).fly_jobs([("stored", 2)])
    # Settings as a dict, overridden like the CLI flags.
    d = reentry.DispersionCampaign(settings={"cases": 7, "seed": 3}, cases=2, **SRM)
    assert (d.cases, d.settings["seed"]) == (2, 3)


def test_guidance_settings_reach_the_flights_as_in_the_cli(host_sim, tmp_path):
    """The scenario's ``[guidance.lateral]`` sets the campaign's lateral logic, in the CLI and
    in the bindings alike (both fly the scenario's layers); the former ``[dispersions.guidance]``
    table is refused naming the new key."""
    text = host_sim("simulate", "--builtin", "srm-glide", "--print-scenario").stdout
    assert "max_reversals = 12" in text
    scenario = tmp_path / "srm.toml"
    scenario.write_text(text.replace("max_reversals = 12", "max_reversals = 1"))
    cli_dir = tmp_path / "cli"
    host_sim(
        "dispersions", "--scenario", scenario, "-n", "2", "--interface-speed", "2500",
        "--modes", "stored-reversals", "--quiet", "--out", cli_dir,
    )
    c = reentry.DispersionCampaign(
        scenario, interface_speed_m_s=2500.0, cases=2, modes=["stored-reversals"]
    )
    for (mode, index), text in zip(c.jobs(), c.run_local(threads=1)):
        case = json.loads(text)
        assert case["guidance"]["max_reversals"] == 1 and case["reversals"] <= 1
        assert json.loads((cli_dir / "cases" / mode / f"{index:06d}.json").read_text()) == case
    old = tmp_path / "disp.toml"
    old.write_text("[dispersions.guidance]\nmax_reversals = 1\n")
    with pytest.raises(reentry.CampaignError, match=r"\[guidance.lateral\] max_reversals"):
        reentry.DispersionCampaign(settings=old, cases=2, **SRM)


def test_dispersions_on_dask_equal_local_table(client, small, tmp_path):
    c, results = small
    dist = dispersion_results(c, client, chunk_size=2)
    assert dist == results
    local_df = c.table(results)
    dask_df = run_dispersions(c, client, chunk_size=5, out=tmp_path)
    assert local_df.equals(dask_df)
    num = local_df.select_dtypes("number")
    assert np.array_equal(
        np.asarray(num, dtype=float).view(np.uint64), np.asarray(dask_df[num.columns], dtype=float).view(np.uint64)
    )
    assert (tmp_path / "summary.json").exists()


def test_command_line_on_a_scheduler_writes_the_cli_files_and_an_exact_table(client, small, tmp_path, monkeypatch):
    import pandas as pd
    from reentry.distributed import main

    c, results = small
    table, out = tmp_path / "table.csv", tmp_path / "out"
    rc = main([
        "dispersions", "--builtin", "srm-glide", "-n", "4", "--interface-speed", "2500",
        "--scheduler", client.scheduler.address, "--chunk-size", "5",
        "--table", str(table), "--out", str(out),
    ])
    assert rc == 0
    got = pd.read_csv(table)
    want = c.table(results)
    assert list(got.columns) == list(want.columns)
    num = want.select_dtypes("number").columns
    assert np.array_equal(
        np.asarray(got[num], dtype=float).view(np.uint64), np.asarray(want[num], dtype=float).view(np.uint64)
    )
    ref = tmp_path / "ref"
    c.write(ref, results)
    assert filecmp.cmp(out / "summary.json", ref / "summary.json", shallow=False)
    # A scenario file given by a relative path reaches the workers as an absolute one.
    monkeypatch.chdir(tmp_path)
    (tmp_path / "srm.toml").write_text(reentry.scenario_toml("srm-glide"))
    f = reentry.DispersionCampaign("srm.toml", cases=2, interface_speed_m_s=2500.0, modes=["stored"])
    assert json.loads(f.spec_json())["path"] == str(tmp_path / "srm.toml")
    assert dispersion_results(f, client) == f.run_local()


def test_worker_killed_mid_dispersion_campaign_loses_and_duplicates_nothing(
    client, kill_a_worker_during
):
    c = reentry.DispersionCampaign(cases=40, **SRM)  # 40 cases of every mode, tasks of 3
    local = c.run_local()
    got = kill_a_worker_during(lambda: dispersion_results(c, client, chunk_size=3), 4, 180)
    assert len(got) == len(c.jobs())
    keys = [(json.loads(r)["mode"], json.loads(r)["index"]) for r in got]
    assert len(set(keys)) == len(keys)
    assert got == local
