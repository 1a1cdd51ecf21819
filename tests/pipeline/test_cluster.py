"""Sweeps on a real dask.distributed cluster on localhost: a scheduler and worker processes
started as a user would (`dask scheduler`, `dask worker`), the same numbers as a local run,
workers killed mid-run, and each way a cluster can be unfit failing in one clear line.
The helpers starting the processes serve tests/pipeline/test_cluster_tls.py too (with TLS
options)."""
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
import xarray

import pipeline
from pipeline.errors import ClusterError
from pipeline.histories import segment
from pipeline.records import load_record
from tests.helpers import wait_until
from tests.pipeline.small_sweep import no_compute

PROJECT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1",
       # A scheduler or worker asked to reach a worker just killed retries its address until
       # dask's connect timeout (30 s by default; one suite run in several waited it out in
       # test_workers_killed_mid_run): 10 s on localhost still leaves any live peer time to
       # answer on two loaded cores.
       "DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT": "10s"}


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


def _wait_for_port(port: int, proc: subprocess.Popen) -> None:
    def listening():
        with socket.socket() as s:
            return s.connect_ex(("127.0.0.1", port)) == 0

    def running():
        assert proc.poll() is None, "scheduler did not start"

    wait_until(listening, "the scheduler's port", check=running)


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
    """Until the scheduler lists n workers (at least n; exactly none for n = 0: a stopped
    worker forgotten)."""
    from distributed import Client

    with Client(address, timeout=30, security=security, set_as_default=False) as client:
        if n:
            client.wait_for_workers(n, timeout=60)
        else:
            wait_until(lambda: not client.scheduler_info()["workers"], "the workers' removal")


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


def _batch_runner(watcher, workers: list, sweep: threading.Thread, work: Path,
                  record_holder: bool, timeout: float = 60) -> tuple[subprocess.Popen | None, str]:
    """The process of `workers` to kill, and its address: once a batch of the running `sweep`
    is kept in `work` (the kernels are loaded, batches flow), one the scheduler has a batch
    processing on; with record_holder, one holding the record's samples besides. (None, "")
    if the sweep ended first."""
    pids = watcher.run(os.getpid)  # worker address -> pid
    by_pid = {proc.pid: proc for proc in workers}
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and sweep.is_alive():
        if list(work.glob("*.npz")):
            holders = {address for key, where in watcher.who_has().items()
                       if str(key).startswith("bumpers-record-") for address in where}
            for address, keys in watcher.processing().items():
                if any(str(key).startswith("bumpers-batch-") for key in keys) \
                        and (address in holders or not record_holder):
                    return by_pid[pids[address]], address
        time.sleep(0.01)
    assert not sweep.is_alive(), "no batch of the sweep ran on a worker"
    return None, ""


def test_workers_killed_mid_run(cluster, record, tmp_path, monkeypatch):
    """Three sweeps, each losing one of its two workers (SIGKILL) while it runs a batch, the
    first time a worker holding the record's samples: the other runs the lost batches (and the
    record's task again if it had no copy), each archive holds the numbers of a local run, and
    the progress never counts past the total. A new worker replaces the dead one between
    sweeps."""
    from distributed import Client

    from pipeline.execute import executor

    address, workers = cluster
    # ~1 s a sweep on two workers at this step: several batches still to run at the kill.
    grid = {**GRID, "gap": list(np.round(np.linspace(0.10, 0.25, 16), 3)), "dt": 2.5e-4}
    here = pipeline.sweep([record], **grid)
    counted = []  # (done, done + running, total) at every report

    class Counted(executor.Progress):
        def _draw(self, final=False):
            counted.append((self.done, self.done + sum(self.partial.values()), self.total))
            super()._draw(final)

    monkeypatch.setattr(executor, "Progress", Counted)
    with Client(address, timeout=30, set_as_default=False) as watcher:
        for run in range(3):
            out = tmp_path / f"killed{run}.nc"
            done = {}

            def sweep(out=out, done=done):
                try:
                    done["ds"] = pipeline.sweep([record], scheduler=address, batch_size=2,
                                                out=out, **grid)
                except Exception as err:  # noqa: BLE001 - said by the assertion below
                    done["error"] = err

            thread = threading.Thread(target=sweep)
            thread.start()
            try:
                victim, gone = _batch_runner(watcher, workers, thread,
                                             out.with_name(out.name + ".work"), run == 0)
                assert victim is not None, f"sweep {run} ended before a worker was killed"
                victim.kill()
                victim.wait(timeout=10)
            finally:
                thread.join(timeout=120)
            assert "ds" in done, f"sweep {run} failed: {done.get('error')!r}"
            with xarray.open_dataset(out) as saved:
                for name in here.data_vars:
                    xarray.testing.assert_identical(saved[name], here[name])
            # The dead worker out of the scheduler's list first: asked to reach it, the
            # scheduler would retry its address for dask's connect timeout (30 s).
            wait_until(lambda gone=gone: gone not in watcher.ncores(),
                       "the dead worker's removal", pause=0.01)
            workers[workers.index(victim)] = _worker(tmp_path, address, nanny=False)
            watcher.wait_for_workers(2, timeout=60)
    assert counted and all(running <= total and done <= total
                           for done, running, total in counted)


def test_nothing_listening(record, monkeypatch):
    """Connection refused: said before any simulation (more address mistakes:
    test_cluster_tls.py)."""
    no_compute(monkeypatch)
    with pytest.raises(ClusterError, match="nothing listens there \\(connection refused\\)"):
        pipeline.sweep([record], gap=0.2, scheduler=f"tcp://127.0.0.1:{_free_port()}",
                       quiet=True)


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
                _wait_for_workers(address, 0)  # the scheduler forgets the worker
    finally:
        _stop(scheduler)


class _Listed:
    """A client whose scheduler lists workers, some of which died since (a stand-in: what
    Client.run(..., on_error="return") gives for them is the connection's error)."""

    class scheduler:  # noqa: N801 - as Client.scheduler
        address = "tcp://127.0.0.1:1"

    def __init__(self, answers):
        self.answers = answers

    def wait_for_workers(self, n, timeout=None):
        return None

    def run(self, function, code, on_error="raise"):
        return {worker: (answer(code) if callable(answer) else answer)
                for worker, answer in self.answers.items()}


def test_a_worker_that_died_during_the_check_is_gone_not_another_version():
    from distributed.comm.core import CommClosedError

    from pipeline.cluster import FINGERPRINT, check_workers
    from pipeline.errors import ClusterError

    alive = eval  # a live worker evaluates the check here, in this process
    check_workers(_Listed({"tcp://a:1": alive, "tcp://b:1": CommClosedError("closed")}))
    with pytest.raises(ClusterError, match="no worker .* could be reached"):
        check_workers(_Listed({"tcp://b:1": OSError("refused")}))
    with pytest.raises(ClusterError, match="another version"):
        check_workers(_Listed({"tcp://a:1": lambda code: "x" if code == FINGERPRINT
                               else True}))
