"""Dask: optimisation and campaigns on a LocalCluster of 2 worker processes equal the local
runs bit for bit; a worker killed mid-campaign loses and duplicates nothing."""


import numpy as np
import pytest

import reentry
from reentry.distributed import evolve_on_dask, fly_campaign, gamma_sweep_cases

pytest.importorskip("dask.distributed")


def bits(a):
    return np.asarray(a, dtype=float).view(np.uint64)


@pytest.mark.parametrize(
    "make",
    [
        lambda: reentry.Moead(seed=4, population=30, batch_size=30),
        lambda: reentry.Moead(seed=4, population=30, batch_size=7),
        lambda: reentry.Nsga2(seed=4, population=24),
        lambda: reentry.Mhaco(seed=4, population=20, ker=10),
    ],
    ids=["moead-generation-batches", "moead-batch7", "nsga2", "mhaco"],
)
def test_optimisation_on_dask_equals_local_run(client, make):
    p = reentry.TestProblem("constr")
    local, dist = make(), make()
    local.evolve_in_rust(p, 6)
    evolve_on_dask(dist, p, 6, client, chunk_size=4)
    for u, v in zip(local.population, dist.population):
        assert np.array_equal(bits(u), bits(v))
    assert local.to_json() == dist.to_json()


def test_campaign_on_dask_equals_local_table(client):
    cases = gamma_sweep_cases(9, -1.6, -1.2)
    local = fly_campaign(cases)
    dist = fly_campaign(cases, client, chunk_size=2)
    assert local.equals(dist)
    assert list(dist.index) == list(range(9))
    assert dist["scenario"].is_unique
    num = local.select_dtypes("number")
    assert np.array_equal(bits(num), bits(dist[num.columns]))
    # The sweep changes the flights (the cases are not nine copies of one).
    assert local["range_km"].nunique() == 9


def test_worker_killed_mid_campaign_loses_and_duplicates_nothing(client, kill_a_worker_during):
    cases = gamma_sweep_cases(150, -1.7, -1.1)
    local = fly_campaign(cases)
    df = kill_a_worker_during(lambda: fly_campaign(cases, client, chunk_size=3), 5, 120)
    assert list(df.index) == list(range(len(cases)))
    assert df["scenario"].is_unique
    assert local.equals(df)


def test_command_line_optimize_on_its_own_local_cluster_equals_the_local_run(tmp_path):
    """Issue 14 item 4: without ``--scheduler``, ``reentry-dask optimize`` starts its own
    ``LocalCluster`` (``--workers 2``); its final population equals the ``--local`` run's, in
    every printed digit."""
    import json

    from reentry.distributed import main

    args = [
        "optimize", "--problem", "constr", "nsga2", "--population", "24",
        "--generations", "3", "--seed", "9",
    ]
    assert main(args + ["--local", "--out", str(tmp_path / "local")]) == 0
    assert main(args + ["--workers", "2", "--chunk-size", "6", "--out", str(tmp_path / "dask")]) == 0
    local = (tmp_path / "local" / "population.csv").read_text()
    assert len(local.splitlines()) == 25
    assert (tmp_path / "dask" / "population.csv").read_text() == local
    summary = json.loads((tmp_path / "dask" / "summary.json").read_text())
    assert summary["threads"] == 2  # the cluster's worker threads
    assert summary["evaluations"] == 24 * 4


def _http_status(port: int, path: str):
    import urllib.error
    import urllib.request

    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}{path}", timeout=10) as r:
            return r.status
    except urllib.error.HTTPError as e:
        return e.code


def test_local_cluster_binds_no_fixed_port():
    """With port 8787 taken (by this test, or by whoever holds it), the package's LocalCluster
    starts without Dask's 'Port 8787 is already in use' fall-back: by default it has no
    dashboard and its scheduler's HTTP server is on a free port; ``dashboard_address=":0"``
    serves the dashboard on a free port. (With ``dashboard_address=None`` alone, as before,
    the HTTP server tried 8787 first.)"""
    import socket
    import warnings

    from reentry.distributed import local_cluster

    held = socket.socket()
    try:
        held.bind(("127.0.0.1", 8787))
        held.listen()
    except OSError:
        pass  # taken already: the same situation
    try:
        for address, dashboard in ((None, False), (":0", True)):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                with local_cluster(1, dashboard_address=address) as cluster:
                    port = cluster.scheduler.http_server.port
                    assert port != 8787
                    assert _http_status(port, "/health") == 200
                    assert (_http_status(port, "/status") == 200) == dashboard, address
            in_use = [str(w.message) for w in caught if "already in use" in str(w.message)]
            assert not in_use, in_use
    finally:
        held.close()
