"""Shared fixtures: the host-sim binary (for round trips) and a 2-process Dask cluster."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]

# `python -m pytest` run inside python/ puts that source tree first on sys.path; its reentry/
# holds no compiled _native unless `maturin develop` put one there. Then test the installed
# package instead (pytest runs from the repository root and from python/ alike).
_SOURCE = REPO / "python"
_COMPILED = [*(_SOURCE / "reentry").glob("_native*.so"), *(_SOURCE / "reentry").glob("_native*.pyd")]
if not _COMPILED:
    sys.path[:] = [p for p in sys.path if Path(p or os.curdir).resolve() != _SOURCE]


def _host_sim() -> Path | None:
    env = os.environ.get("HOST_SIM")
    if env:
        return Path(env)
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    for profile in ("release", "debug"):
        p = target / profile / "host-sim"
        if p.exists():
            return p
    found = shutil.which("host-sim")
    return Path(found) if found else None


@pytest.fixture(scope="session")
def host_sim():
    """Run the host-sim CLI: ``host_sim(*args) -> CompletedProcess``. Skipped when the binary
    is not built, unless REENTRY_REQUIRE_HOST_SIM=1 (CI), where that is a failure."""
    exe = _host_sim()
    if exe is None or not exe.exists():
        msg = "host-sim binary not found (cargo build --release -p host-sim, or set HOST_SIM)"
        if os.environ.get("REENTRY_REQUIRE_HOST_SIM") == "1":
            pytest.fail(msg)
        pytest.skip(msg)

    def run(*args, check=True):
        return subprocess.run(
            [str(exe), *map(str, args)], cwd=REPO, capture_output=True, text=True, check=check
        )

    return run


@pytest.fixture(scope="module")
def client():
    """A Dask LocalCluster with 2 worker processes, one thread each (no dashboard, no fixed
    port)."""
    distributed = pytest.importorskip("dask.distributed")
    from reentry.distributed import local_cluster

    with local_cluster(2) as cluster, distributed.Client(cluster) as c:
        c.wait_for_workers(2)
        yield c


@pytest.fixture
def kill_a_worker_during(client):
    """Run ``work()`` (a campaign on ``client``) in a thread, SIGKILL one busy worker process
    once ``after_done`` tasks are in memory, and return ``work()``'s result; asserts that the
    kill happened while the campaign was running and that it finished without error within
    ``join_s`` seconds."""
    import signal
    import threading
    import time

    def run(work, after_done: int, join_s: float):
        pids = client.run(os.getpid)  # worker address -> pid
        result, error = {}, {}

        def target():
            try:
                result["r"] = work()
            except BaseException as e:  # pragma: no cover - reported below
                error["e"] = e

        t = threading.Thread(target=target)
        t.start()
        killed = None
        deadline = time.monotonic() + 60
        while killed is None and time.monotonic() < deadline and t.is_alive():
            busy = {w: ks for w, ks in client.processing().items() if ks}
            done = sum(
                1 for state in client.run_on_scheduler(
                    lambda dask_scheduler: [ts.state for ts in dask_scheduler.tasks.values()]
                ) if state == "memory"
            )
            if done >= after_done and busy:
                victim = next(iter(busy))
                os.kill(pids[victim], signal.SIGKILL)
                killed = victim
            else:
                time.sleep(0.02)
        assert killed is not None, "the campaign finished before a worker could be killed"
        assert t.is_alive(), "the worker was killed after the campaign had finished"
        t.join(join_s)
        assert not error, error
        return result["r"]

    return run
