"""Sweeps on a real dask.distributed cluster on localhost: a scheduler and worker processes
started as a user would (`dask scheduler`, `dask worker`), the same numbers as a local run,
a worker killed mid-run, and each way a cluster can be unfit failing in one clear line.
The helpers starting the processes serve tests/pipeline/test_tls.py too (with TLS options)."""
from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import pipeline
from pipeline.errors import ClusterError
from pipeline.histories import segment
from pipeline.records import load_record

PROJECT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _scheduler(tmp_path, *options: str, scheme: str = "tcp", port: int | None = None,
               wait: bool = True) -> tuple[subprocess.Popen, str]:
    """A `dask scheduler` on 127.0.0.1 and its address; `options` replace --no-dashboard (TLS
    files, a dashboard address). wait: until its port accepts connections (killed if never)."""
    port = port or _free_port()
    proc = subprocess.Popen([*_cli("scheduler"), "--host", "127.0.0.1", "--port", str(port),
                             "--protocol", scheme, *(options or ["--no-dashboard"])],
                            cwd=tmp_path, env=ENV, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    address = f"{scheme}://127.0.0.1:{port}"
    try:
        if wait:
            _wait_for_port(port, proc)
    except BaseException:
        _stop(proc)
        raise
    return proc, address


def _wait_for_port(port: int, proc: subprocess.Popen, timeout: float = 60) -> None:
    deadline = time.monotonic() + timeout
    while True:
        with socket.socket() as s:
            if s.connect_ex(("127.0.0.1", port)) == 0:
                return
        assert proc.poll() is None and time.monotonic() < deadline, "scheduler did not start"
        time.sleep(0.05)


def _cli(command: str) -> list[str]:
    return [sys.executable, "-m", "distributed.cli.dask_" + command]


def _worker(tmp_path, address: str, preload: str | None = None, nanny: bool = True,
            options: tuple[str, ...] = ()):
    argv = [*_cli("worker"), address, "--nthreads", "1", "--nworkers", "1",
            "--no-dashboard", "--host", "127.0.0.1", *options]
    if preload:
        script = tmp_path / f"preload_{abs(hash(preload))}.py"
        script.write_text(preload)
        argv += ["--preload", str(script)]
    if not nanny:
        argv.append("--no-nanny")
    return subprocess.Popen(argv, cwd=tmp_path, env=ENV, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)


def _stop(*procs) -> None:
    """Stop dask processes: SIGINT, and SIGKILL for any still running after 5 s (a scheduler
    can linger for its own timeouts; nothing of a test depends on a clean exit)."""
    for proc in procs:
        proc.send_signal(signal.SIGINT)
    deadline = time.monotonic() + 5.0
    for proc in procs:
        try:
            proc.wait(timeout=max(deadline - time.monotonic(), 0.1))
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def _wait_for_workers(address: str, n: int, security=None) -> None:
    from distributed import Client

    with Client(address, timeout=30, security=security, set_as_default=False) as client:
        client.wait_for_workers(n, timeout=60)


@pytest.fixture(scope="module")
def record():
    return segment(load_record("pacoima"), 12.0)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A scheduler with two workers (no nanny: a killed worker stays dead)."""
    tmp = tmp_path_factory.mktemp("cluster")
    scheduler, address = _scheduler(tmp)
    workers = [_worker(tmp, address, nanny=False) for _ in range(2)]
    try:
        _wait_for_workers(address, 2)
        yield address, workers
    finally:
        _stop(*workers, scheduler)


GRID = {"gap": [0.12, 0.15, 0.18, 0.21], "n_bumpers": [4, 8, 16], "baseline": True,
        "unconstrained": True, "quiet": True}


def test_cluster_run_equals_local_run(cluster, record):
    address, _ = cluster
    here = pipeline.sweep([record], **GRID)
    there = pipeline.sweep([record], scheduler=address, batch_size=3, **GRID)
    for name in here.data_vars:
        np.testing.assert_array_equal(here[name].values, there[name].values, err_msg=name)


def test_worker_killed_mid_run(cluster, record, tmp_path):
    """One of two workers is killed once batches are finishing: its batches run on the other,
    and the archive holds the numbers of a local run."""
    address, workers = cluster
    out = tmp_path / "killed.nc"
    work = tmp_path / "killed.nc.work"
    grid = {**GRID, "gap": list(np.round(np.linspace(0.10, 0.25, 16), 3))}
    done = {}
    thread = threading.Thread(target=lambda: done.update(ds=pipeline.sweep(
        [record], scheduler=address, batch_size=2, out=out, **grid)))
    thread.start()
    deadline = time.monotonic() + 120
    while not list(work.glob("*.npz")) and time.monotonic() < deadline:
        time.sleep(0.02)
    victim = workers[1]
    victim.kill()
    victim.wait(timeout=10)
    thread.join(timeout=300)
    assert "ds" in done, "the sweep did not finish after a worker died"
    here = pipeline.sweep([record], **grid)
    for name in here.data_vars:
        np.testing.assert_array_equal(here[name].values, done["ds"][name].values,
                                      err_msg=name)


def test_nothing_listening(record):
    """Connection refused: said at once (more address mistakes: test_tls.py)."""
    start = time.monotonic()
    with pytest.raises(ClusterError, match="nothing listens there \\(connection refused\\)"):
        pipeline.sweep([record], gap=0.2, scheduler=f"tcp://127.0.0.1:{_free_port()}",
                       quiet=True)
    assert time.monotonic() - start < 5


HIDE = """
import sys
class _Hide:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("engine", "pipeline", "studies"):
            raise ModuleNotFoundError(f"No module named {name!r}")
sys.meta_path.insert(0, _Hide())
"""
OTHER_VERSION = """
import pipeline.provenance
pipeline.provenance.engine_fingerprint = lambda: "0" * 64
"""


def test_unfit_clusters_fail_in_one_line(tmp_path, record, monkeypatch):
    """No workers, then a worker without the project, then one at another version: each
    refused before any batch is submitted, with the cause and the fix."""
    from pipeline import cluster

    monkeypatch.setattr(cluster, "WORKERS_TIMEOUT", 2.0)  # the wait itself is not under test
    scheduler, address = _scheduler(tmp_path)
    try:
        with pytest.raises(ClusterError, match="has no workers after 2 s: start some with "
                                               f"`dask worker {address}"):
            pipeline.sweep([record], gap=0.2, scheduler=address, quiet=True)
        for preload, match in ((HIDE, "cannot import this project"),
                               (OTHER_VERSION, "run another version of this project")):
            worker = _worker(tmp_path, address, preload=preload)
            try:
                _wait_for_workers(address, 1)
                with pytest.raises(ClusterError, match=match) as caught:
                    pipeline.sweep([record], gap=0.2, scheduler=address, quiet=True)
                assert "\n" not in str(caught.value)
            finally:
                _stop(worker)
                time.sleep(1.0)  # the scheduler forgets the worker
    finally:
        _stop(scheduler)
