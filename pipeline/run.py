"""Running a sweep: engine batches, in this process or on dask workers, resumable on disk.

Each batch is one `engine.simulate` call: one record, at most `batch_size` members. Workers
return peak arrays and this process alone writes them (no races on shared files). Finished
batches are kept in a work folder as .npz files holding their members (grid.MEMBER_DTYPE), so
a killed sweep rerun with the same arguments computes only the members it is missing. Every
member is looked up by its context key (record content, dt, building, engine source) and its
member record: the
engine's results do not depend on the batch a member ran in, so the batch size and the
number of workers may change between runs without invalidating anything.
"""
from __future__ import annotations

import hashlib
import json
import logging
import math
import os
import sys
import tempfile
import threading
import time
import uuid
import zipfile
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import engine

from .errors import Interrupted
from .grid import MEMBER_DTYPE, Grid, contact_for
from .provenance import engine_fingerprint, record_hash

# Peak arrays kept per simulation: name -> (trailing shape, dtype).
PEAKS = {
    "peak_total_accel": ((5,), np.float64),
    "peak_interstory_drift": ((4,), np.float64),
    "peak_isolator_disp": ((), np.float64),
    "max_indentation": ((), np.float64),
    "max_impact_force": ((), np.float64),
    "n_impacts": ((), np.int64),
    "impact_energy": ((), np.float64),
}
# One BLAS and one numba thread per worker process: workers are the parallelism; more threads
# only contend for the same cores.
BLAS_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
            "NUMBA_NUM_THREADS": "1"}
CACHE_FORMAT = 3  # bump when the work-folder layout, the member record or the peak set change


@dataclass(frozen=True)
class Batch:
    """One engine call: record index, (b,) indices into the grid's members, and its key."""

    record: int
    members: np.ndarray
    key: str


def simulate_batch(accel: np.ndarray, accel_dt: float, members: np.ndarray,
                   building: engine.Building, dt: float, progress=None,
                   report: tuple[str, str] | None = None) -> dict[str, np.ndarray]:
    """Peaks of (b,) members (grid.MEMBER_DTYPE) under one record (m/s^2 every accel_dt s).

    progress(step, n_steps) is called as the engine goes; on a dask worker, report =
    (topic, tag) sends [tag, step / n_steps] to the client's event topic instead.
    """
    if report is not None:
        from distributed import get_worker

        worker, (topic, tag) = get_worker(), report

        def progress(step, n_steps):
            worker.log_event(topic, [tag, step / n_steps])

    result = engine.simulate(accel, accel_dt, contact_for(members), building=building, dt=dt,
                             progress=progress)
    return {name: np.asarray(getattr(result, name), dtype=dtype)
            for name, (_, dtype) in PEAKS.items()}


def context_key(record, dt: float, building: engine.Building) -> str:
    """Everything besides the member record that determines a member's result."""
    text = json.dumps({"format": CACHE_FORMAT, "engine": engine_fingerprint(),
                       "record": record_hash(record.accel, record.dt), "dt": float(dt).hex(),
                       "building": repr(building)}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


class WorkFolder:
    """Finished batches on disk: `<key>.npz` with the context, members and peaks."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self.path.mkdir(parents=True, exist_ok=True)

    def load(self) -> dict[tuple[str, bytes], dict[str, np.ndarray]]:
        """(context, member record bytes) -> that member's peaks, from every readable batch."""
        found = {}
        for file in sorted(self.path.glob("*.npz")):
            try:
                with np.load(file, allow_pickle=False) as data:
                    context, members = str(data["context"]), data["members"]
                    peaks = {name: data[name] for name in PEAKS}
            except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
                continue  # a damaged file (killed mid-write elsewhere) is simply recomputed
            if members.dtype != MEMBER_DTYPE:
                continue  # written by another version: its keys cannot match
            for i, member in enumerate(members):
                found[context, member.tobytes()] = {name: value[i]
                                                    for name, value in peaks.items()}
        return found

    def save(self, key: str, context: str, members: np.ndarray,
             peaks: dict[str, np.ndarray]):
        """Write atomically: a batch file is complete or absent."""
        fd, tmp = tempfile.mkstemp(dir=self.path, prefix=f".{key}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                np.savez(f, context=np.array(context), members=members, **peaks)
            os.replace(tmp, self.path / f"{key}.npz")
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise


class Progress:
    """'done/total simulations, elapsed, time left' on stderr, once a run passes `delay` s.

    Thread-safe: dask reports running batches from the client's event-loop thread.
    """

    def __init__(self, total: int, done: int = 0, quiet: bool = False, stream=None,
                 delay: float = 2.0):
        self.total, self.done = total, done
        self.start_done = done
        self.partial: dict = {}  # running batch -> simulations' worth done
        self.quiet = quiet
        self.stream = sys.stderr if stream is None else stream
        self.tty = getattr(self.stream, "isatty", lambda: False)()
        self.delay = delay
        self.every = 0.5 if self.tty else 10.0  # a log file gets a line now and then
        self.t0 = time.monotonic()
        self.last = -math.inf
        self.last_line = ""
        self.lock = threading.Lock()

    def advance(self, n: int, batch=None) -> None:
        """n more simulations finished (those of `batch`, if it was reported running)."""
        with self.lock:
            self.done += n
            self.partial.pop(batch, None)
            self._draw()

    def running(self, batch, n: float) -> None:
        """`batch` has done n simulations' worth so far."""
        with self.lock:
            self.partial[batch] = n
            self._draw()

    def close(self) -> None:
        with self.lock:
            self._draw(final=True)

    def interrupted(self) -> None:
        """End a bar left open on a terminal, so the next line starts clean."""
        with self.lock:
            if self.tty and self.last_line and not self.quiet:
                self.stream.write("\n")
                self.stream.flush()
            self.quiet = True

    def _draw(self, final: bool = False) -> None:
        now = time.monotonic()
        elapsed = now - self.t0
        if self.quiet or elapsed < self.delay or (not final and now - self.last < self.every):
            return
        done = self.done + sum(self.partial.values())
        rate = (done - self.start_done) / elapsed
        left = (self.total - done) / rate if rate > 0 else math.nan
        line = (f"sweep: {100 * done / max(self.total, 1):3.0f}% ({int(self.done)} of "
                f"{self.total} simulations finished), {_clock(elapsed)} elapsed, "
                f"~{_clock(left)} left")
        if final and line == self.last_line and not self.tty:
            return  # already said
        self.last, self.last_line = now, line
        end = "\n" if final or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + line + end)
        self.stream.flush()


def _clock(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "?"
    minutes, sec = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}:{minutes:02d}:{sec:02d}" if hours else f"{minutes}:{sec:02d}"


def default_batch_size(n_members: int, n_records: int, workers: int,
                       max_batch: int = 4096, *, steps: int = 80_000,
                       member_step_seconds: float = 35e-9, min_batch_seconds: float = 0.5) -> int:
    """Default members per engine batch, sized for the compiled kernel.

    With the kernel a batch costs ~35 ns per member-step and nearly nothing else, so the only
    reasons for large batches are dask's overhead per task (a few ms: a batch of at least
    min_batch_seconds keeps it under 5%) and memory (max_batch members, ~2 KB each). Batches
    should be small enough that every worker has several (4 per worker), so that no worker
    idles while another finishes a long record; `run` further splits the batches of records
    longer than the typical one. steps: a typical record's number of steps (80,000 = 40 s at
    0.5 ms).
    """
    workers = max(workers, 1)
    floor = math.ceil(min_batch_seconds / (max(steps, 1) * member_step_seconds))
    wanted = 4 * workers if workers > 1 else 1
    per_record = max(math.ceil(n_members / max_batch), math.ceil(wanted / max(n_records, 1)))
    size = math.ceil(n_members / per_record)
    return max(1, min(max_batch, n_members, max(size, floor)))


def _record_batch_sizes(records, batch_size: int) -> list[int]:
    """Members per batch for each record: batch_size for records up to the median length,
    fewer for longer ones so that every batch is about as long as a typical one (a long
    record's batch would otherwise keep one worker busy after the others finish)."""
    lengths = [max(len(rec.accel) * rec.dt, 1e-9) for rec in records]
    typical = float(np.median(lengths)) if lengths else 1.0
    return [max(1, math.floor(batch_size * min(1.0, typical / length))) for length in lengths]


def run(grid: Grid, records, dt: float, building: engine.Building, *, workers: int = 2,
        scheduler=None, work_dir: Path | None = None, batch_size: int = 512,
        quiet: bool = False) -> list[dict[str, np.ndarray]]:
    """Simulate every member of `grid` under every record.

    records: objects with name, dt (s) and accel (m/s^2); scheduler: None, a dask.distributed
    address or Client; workers <= 1 without a scheduler runs here, in this process.
    Returns one dict per record: peak name -> (M, ...) array in the grid's member order.
    """
    members = grid.members
    n_members = members.size
    results = [{name: np.zeros((n_members, *shape), dtype) for name, (shape, dtype)
                in PEAKS.items()} for _ in records]
    contexts = [context_key(rec, dt, building) for rec in records]
    work = WorkFolder(work_dir) if work_dir is not None else None
    cached = work.load() if work is not None else {}

    batches = []
    in_process = scheduler is None and workers <= 1
    # Splitting long records keeps worker processes equally busy; in this process the
    # kernel's threads share each batch anyway, and bigger batches balance them better.
    record_sizes = [batch_size] * len(records) if in_process \
        else _record_batch_sizes(records, batch_size)
    for r, context in enumerate(contexts):
        missing = []
        for i, member in enumerate(members):
            peaks = cached.get((context, member.tobytes()))
            if peaks is None:
                missing.append(i)
            else:
                for name, value in peaks.items():
                    results[r][name][i] = value
        size = record_sizes[r]
        for start in range(0, len(missing), size):
            which = np.array(missing[start:start + size])
            key = hashlib.sha256(context.encode() + members[which].tobytes()).hexdigest()
            batches.append(Batch(r, which, key))
    # Longest records first: a long record's batch starting last would leave workers idle.
    batches.sort(key=lambda b: -len(records[b.record].accel) * records[b.record].dt)
    n_todo = sum(b.members.size for b in batches)
    progress = Progress(len(records) * n_members, len(records) * n_members - n_todo, quiet)

    def finish(batch: Batch, peaks: dict[str, np.ndarray]) -> None:
        if work is not None:
            work.save(batch.key, contexts[batch.record], members[batch.members], peaks)
        for name, value in peaks.items():
            results[batch.record][name][batch.members] = value
        progress.advance(batch.members.size, batch.key)

    try:
        if batches and in_process:
            for batch in batches:
                rec = records[batch.record]
                size = batch.members.size
                # The kernel returns to Python every ~1% of the steps to report progress,
                # which is also where Ctrl-C takes effect: always pass the callback.
                peaks = simulate_batch(rec.accel, rec.dt, members[batch.members], building, dt,
                                       progress=lambda step, steps, b=batch.key, s=size:
                                       progress.running(b, s * step / steps))
                finish(batch, peaks)
        elif batches:
            _run_on_dask(batches, records, members, building, dt, workers, scheduler,
                         progress, finish)
    except KeyboardInterrupt:
        progress.interrupted()
        kept = progress.done if work is not None else 0
        raise Interrupted(int(kept), progress.total, work_dir) from None
    progress.close()
    return results


def _run_on_dask(batches, records, members, building, dt, workers, scheduler, progress,
                 finish) -> None:
    """Submit every batch; finish() each as it completes, here in the client process."""
    from distributed import as_completed

    with _client(workers, scheduler) as client:
        sizes = {b.key: b.members.size for b in batches}
        topic = f"bumpers-progress-{uuid.uuid4().hex}"

        def on_event(event):  # (timestamp, [batch key, fraction done])
            key, fraction = event[1]
            progress.running(key, sizes[key] * fraction)

        client.subscribe_topic(topic, on_event)
        try:
            accel = {r: client.scatter(np.asarray(records[r].accel), hash=False)
                     for r in sorted({b.record for b in batches})}
            futures = {}
            for batch in batches:
                future = client.submit(simulate_batch, accel[batch.record],
                                       records[batch.record].dt, members[batch.members],
                                       building, dt, report=(topic, batch.key),
                                       key=f"bumpers-batch-{batch.record}-{batch.key}")
                futures[future] = batch
            for future in as_completed(futures, loop=client.loop):
                finish(futures[future], future.result())
        except KeyboardInterrupt:
            # Stop quietly: cancel what is queued; shutting down then makes dask log lost
            # scattered data and closed comms, which say nothing to the user.
            _silence_dask()
            client.cancel(list(futures), force=True)
            raise
        finally:
            client.unsubscribe_topic(topic)


@contextmanager
def _client(workers: int, scheduler):
    """A dask.distributed Client: given, at an address, or on a new local cluster."""
    from distributed import Client, LocalCluster

    from .cluster import connect

    if scheduler is not None and not isinstance(scheduler, str):
        yield scheduler  # a Client the caller owns and closes
    elif scheduler is not None:
        with connect(scheduler) as client:
            yield client
    else:
        with _main_hidden(), \
                LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                             dashboard_address=None, silence_logs=logging.ERROR,
                             env=BLAS_ENV) as cluster, \
                Client(cluster, set_as_default=False) as client:
            yield client


def _silence_dask() -> None:
    for name in ("distributed", "tornado", "asyncio"):
        logging.getLogger(name).setLevel(logging.CRITICAL)


@contextmanager
def _main_hidden():
    """While local worker processes may start, hide the __main__ module's file and spec.

    Worker processes are spawned, and a spawned process re-runs the parent's main script
    (multiprocessing's preparation data names it) unless that script has no file or spec. A
    script calling sweep without the `if __name__ == "__main__":` guard would then start
    sweeps, and clusters, inside its own workers. The workers need nothing from __main__: they
    run pipeline.run.simulate_batch, found by import.
    """
    main = sys.modules.get("__main__")
    saved = {name: main.__dict__[name] for name in ("__file__", "__spec__")
             if main is not None and name in main.__dict__}
    try:
        if main is not None:
            main.__dict__.pop("__file__", None)
            if "__spec__" in saved:
                main.__spec__ = None
        yield
    finally:
        if main is not None:
            main.__dict__.update(saved)
