"""Dask: optimisation and campaigns on a LocalCluster of 2 worker processes equal the local
runs bit for bit; a worker killed mid-campaign loses and duplicates nothing."""

import os
import signal
import threading
import time

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


def test_worker_killed_mid_campaign_loses_and_duplicates_nothing(client):
    cases = gamma_sweep_cases(150, -1.7, -1.1)
    local = fly_campaign(cases)
    pids = client.run(os.getpid)  # worker address -> pid
    result, error = {}, {}

    def run():
        try:
            result["df"] = fly_campaign(cases, client, chunk_size=3)
        except BaseException as e:  # pragma: no cover - reported below
            error["e"] = e

    t = threading.Thread(target=run)
    t.start()
    killed = None
    deadline = time.monotonic() + 60
    while killed is None and time.monotonic() < deadline and t.is_alive():
        busy = {w: ks for w, ks in client.processing().items() if ks}
        done = sum(
            1 for f in client.run_on_scheduler(
                lambda dask_scheduler: [ts.state for ts in dask_scheduler.tasks.values()]
            ) if f == "memory"
        )
        if done >= 5 and busy:
            victim = next(iter(busy))
            os.kill(pids[victim], signal.SIGKILL)
            killed = victim
        else:
            time.sleep(0.02)
    assert killed is not None, "the campaign finished before a worker could be killed"
    assert t.is_alive(), "the worker was killed after the campaign had finished"
    t.join(120)
    assert not error, error
    df = result["df"]
    assert list(df.index) == list(range(len(cases)))
    assert df["scenario"].is_unique
    assert local.equals(df)
