"""Shared fixtures: the host-sim binary (for round trips) and a 2-process Dask cluster."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


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
    """A Dask LocalCluster with 2 worker processes, one thread each."""
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as c:
        c.wait_for_workers(2)
        yield c
