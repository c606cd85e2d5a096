"""Sweeps on a Dask LocalCluster of 2 worker processes (issue 55): the same rows as the local
sweep, row for row; and a worker killed mid-run, the result still complete and the same. A folder
of papers audited on the cluster (issue 66): the same frame as the local audit."""

import os
import signal
import threading
import time
from pathlib import Path

import distributed
import pytest

import impactcheck as ic
import impactcheck.dask as icd

ROOT = Path(__file__).resolve().parents[2]
SCENE = str(ROOT / "scenes" / "hertz.toml")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_a_sweep_on_two_workers_is_the_local_sweep_row_for_row(client):
    vary = {"impactor.v0": (0.1, 10, 5000)}
    local = ic.sweep_rows(SCENE, vary)
    assert icd.sweep_rows(SCENE, vary, client) == local
    frame = icd.sweep(SCENE, vary, client, shards=7)
    whole = ic.sweep(SCENE, vary)
    # every number the same; a warning's wording is written in full once per shard (a later
    # row of the shard says `like row N:` with its own numbers), so that column is by shard
    numbers = [c for c in whole.columns if c != "warnings"]
    assert frame[numbers].equals(whole[numbers])
    assert list(frame.index) == list(range(5000))


def test_a_folder_audited_on_two_workers_is_the_local_audit(client):
    folder = ROOT / "tests" / "papers"
    local = ic.audit_many(folder)
    frame = icd.audit_many(folder, client)
    assert len(frame) > 1
    assert frame.equals(local)
    assert list(frame.index) == list(local.index)
    assert frame.attrs["total"] == local.attrs["total"]


def test_a_worker_killed_mid_run_loses_no_row(client):
    vary = {"impactor.v0": (0.1, 10, 200000)}
    local = ic.sweep_rows(SCENE, vary)
    pids = client.run(os.getpid)
    victim = sorted(pids.values())[0]

    def kill_soon():
        time.sleep(1.0)
        os.kill(victim, signal.SIGKILL)

    t = threading.Thread(target=kill_soon)
    t.start()
    started = time.monotonic()
    rows = icd.sweep_rows(SCENE, vary, client, shards=8)
    t.join()
    # the sweep outlived the kill (it was mid-run), the worker is gone (its nanny started a new
    # one), and every row is there, in order
    assert time.monotonic() - started > 1.0
    client.wait_for_workers(2, timeout=60)
    assert victim not in client.run(os.getpid).values()
    assert rows == local


def test_the_dask_submodule_is_reachable_after_importing_the_package_alone():
    # a fresh interpreter: nothing has imported impactcheck.dask by name
    import subprocess
    import sys

    code = "import impactcheck as ic, sys; assert 'impactcheck.dask' not in sys.modules; print(callable(ic.dask.sweep))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "True"
