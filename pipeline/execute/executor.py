"""The one executor: run a store's remaining batches in this process or on dask, with a
progress line, Ctrl-C turned into pipeline.errors.Interrupted.

A store (netcdf_store.NetCDFStore, zarr_store.ZarrStore) decides what a run keeps and where;
the executor only runs batches. The interface (`Store`):

    store.records          the Record objects run (batches index them)
    store.total            simulations of the whole run (records x members)
    store.kept_in          where finished batches survive an interruption (None: nowhere)
    store.pending(sizes)   the batches still to run; sizes[r] is the most members a batch of
                           record r should hold (a store with fixed batches, Zarr's chunk
                           regions, may ignore it)
    store.task(batch)      (function, args): a worker runs function(accel, *args,
                           progress=None, report=None), accel the record's samples
    store.accept(batch, output)  on the client, as each batch finishes, with what the
                           function returned
    store.part(batch, start, stop)  optional: the batch's members start:stop as a batch of
                           their own, kept on its own (a store without it keeps whole batches,
                           or keeps their parts itself)

Batches of the longest records run first (a long record's batch starting last would leave
workers idle). In this process the compiled kernel spreads each batch over every core with
threads; with workers >= 2 or a scheduler the batches go to dask workers, running batches
reporting their progress through a dask event topic. On dask each record enters the task graph
once, as a task returning its samples on which the record's batches depend: the scheduler
holds the samples, so it computes the record again if every worker holding it dies, and runs a
dead worker's batches on the others (a batch is a pure function of its inputs: the numbers do
not change). Records scattered instead would die with the last worker holding them (dask's
memory manager drops extra replicas within seconds), and every batch of the record with them.
"""
from __future__ import annotations

import time
import uuid
from collections import Counter
from typing import Protocol

import numpy as np

from ..errors import Interrupted
from ..progress import Progress
from ..writing import sigint_held
from .batches import Batch, part_size, record_batch_sizes
from .dask_client import client, silence_dask

# A batch that raises is run again this many times before its error reaches the user: it is a
# pure function of its inputs, so a retry gives the same numbers, and an error with a lasting
# cause comes back. A worker that dies running it is another matter, the scheduler's: the batch
# runs on another worker, until it has been on distributed.scheduler.allowed-failures + 1 dead
# ones (3 + 1 by default), when it fails with KilledWorker.
RETRIES = 2

DEVICE_RESOURCES = {"GPU": 1}
"""What a batch on the device takes of a dask worker (dask's worker resources): one GPU, so
that a scheduler's workers started with `--resources GPU=1` (one per GPU) run one batch each."""


class Store(Protocol):
    """Where a run's results go (see the module docstring)."""

    records: list
    total: int
    kept_in: object

    def pending(self, sizes: list[int]) -> list[Batch]: ...

    def task(self, batch: Batch) -> tuple: ...

    def accept(self, batch: Batch, output) -> None: ...


def execute(store: Store, *, workers: int, scheduler, batch_size: int,
            quiet: bool, device: bool = False) -> None:
    """Run every batch `store` has pending, here (scheduler None and workers <= 1) or on dask
    (scheduler: None for a local cluster of `workers` processes, an address, or a Client).
    device: the batches run on a GPU (backend "cuda"): on a scheduler each takes a worker's
    GPU resource (DEVICE_RESOURCES), one batch at a time on each GPU.
    Ctrl-C raises Interrupted saying how many simulations are kept, and where."""
    records = store.records
    in_process = scheduler is None and workers <= 1
    # Splitting long records keeps worker processes equally busy; in this process the
    # kernel's threads share each batch anyway, and bigger batches balance them better.
    sizes = [batch_size] * len(records) if in_process \
        else record_batch_sizes(records, batch_size)
    batches = sorted(store.pending(sizes),
                     key=lambda b: -len(records[b.record].accel) * records[b.record].dt)
    progress = Progress(store.total, store.total - sum(b.size for b in batches), quiet)
    try:
        if batches and in_process:
            _run_here(store, batches, progress, device)
        elif batches:
            _run_on_dask(store, batches, workers, scheduler, progress, device)
    except KeyboardInterrupt:
        progress.interrupted()
        kept = progress.done if store.kept_in is not None else 0
        raise Interrupted(int(kept), progress.total, store.kept_in) from None
    progress.close()


def _run_here(store: Store, batches: list[Batch], progress: Progress,
              device: bool = False) -> None:
    pace = {"last": None}  # s per member and record sample, the last part's (None: not yet)
    for whole in batches:
        samples_ = len(store.records[whole.record].accel)
        for batch in _parts(store, whole, samples_, pace, device):
            function, args = store.task(batch)
            # The kernel returns to Python every ~1% of the steps to report progress, which is
            # also where Ctrl-C takes effect: always pass the callback.
            output, seconds = timed(function, store.records[batch.record].accel, *args,
                                    progress=lambda step, steps, b=batch:
                                    progress.running(b.key, b.size * step / steps))
            if batch.size:  # a Zarr region whose members were all written, killed before
                pace["last"] = seconds / (batch.size * samples_)  # it was marked done
            with sigint_held():  # a batch kept is a batch counted: Interrupted says so
                store.accept(batch, output)
                progress.advance(batch.size, batch.key)


def timed(function, accel, *args, **keywords) -> tuple:
    """(function(accel, *args, **keywords), the seconds it took): a batch's task, timed where
    it runs (here or on a dask worker), so that the next parts are sized from its pace."""
    started = time.perf_counter()
    output = function(accel, *args, **keywords)
    return output, time.perf_counter() - started


def _parts(store: Store, batch: Batch, samples_: int, pace, device: bool):
    """The batch in parts of about batches.KEEP_SECONDS of compute each, sized as they come
    from the last part's pace (pace["last"]: s per member and sample, None before any); the
    batch whole where the store keeps whole batches only (a Zarr store keeps the parts of a
    batch itself: zarr_store.write_batch), or on the device (one launch holds a batch)."""
    if device or not hasattr(store, "part"):
        yield batch
        return
    start = 0
    while start < batch.size:
        stop = min(batch.size, start + part_size(pace["last"], samples_))
        yield batch if (start, stop) == (0, batch.size) else store.part(batch, start, stop)
        start = stop


def _run_on_dask(store: Store, batches: list[Batch], workers: int, scheduler,
                 progress: Progress, device: bool = False) -> None:
    """Run the batches on dask, in parts of about KEEP_SECONDS of compute as in this process
    (`_parts`, where the store keeps parts), each accepted here in the client as it completes:
    twice as many parts in flight as the workers have threads, the next one sized from the
    last one's pace as each ends (device: whole batches, each taking a worker's GPU,
    DEVICE_RESOURCES)."""
    from distributed import as_completed

    needs = {"resources": DEVICE_RESOURCES} if device else {}
    records = store.records
    run = uuid.uuid4().hex  # in every key and the topic: runs sharing a scheduler never mix
    with client(workers, scheduler) as dask:
        sizes = {}  # part key -> members, for the progress events
        topic = f"bumpers-progress-{run}"

        def on_event(event):  # (timestamp, [batch key, fraction done])
            key, fraction = event[1]
            if key in sizes:
                progress.running(key, sizes[key] * fraction)

        dask.subscribe_topic(topic, on_event)
        accel, futures = {}, {}
        left = Counter()  # members of each record not yet accepted
        for batch in batches:
            left[batch.record] += batch.size
        pace = {"last": None}
        parts = (part for whole in batches  # in this order: the longest records first
                 for part in _parts(store, whole, len(records[whole.record].accel), pace,
                                    device))

        def submit(done) -> None:
            part = next(parts, None)
            if part is None:
                return
            function, args = store.task(part)
            sizes[part.key] = part.size
            future = dask.submit(timed, function, accel[part.record], *args,
                                 report=(topic, part.key), retries=RETRIES,
                                 key=f"bumpers-batch-{run}-{part.key}", **needs)
            futures[future] = part
            done.add(future)

        try:
            for r in sorted(left):
                accel[r] = dask.submit(samples, np.asarray(records[r].accel),
                                       key=f"bumpers-record-{run}-{r}")
            done = as_completed([], loop=dask.loop)
            for _ in range(max(2, 2 * sum(dask.nthreads().values()))):
                submit(done)
            for future in done:
                part = futures.pop(future)
                output, seconds = future.result()
                if part.size:  # see _run_here
                    pace["last"] = seconds / (part.size * len(records[part.record].accel))
                with sigint_held():
                    store.accept(part, output)
                    progress.advance(part.size, part.key)
                # Forgotten by the scheduler once accepted: a result held by a worker that dies
                # later is not computed again, nor a record all of whose parts are in.
                future.release()
                sizes.pop(part.key, None)
                left[part.record] -= part.size
                if not left[part.record]:
                    accel.pop(part.record).release()
                submit(done)
        except KeyboardInterrupt:
            # Stop quietly: cancel what is queued; shutting down then makes dask log closed
            # comms and cancelled tasks, which say nothing to the user.
            silence_dask()
            dask.cancel([*futures, *accel.values()], force=True)
            raise
        finally:
            dask.unsubscribe_topic(topic)
            for future in (*futures, *accel.values()):  # a Client the caller owns keeps none
                future.release()


def samples(accel: np.ndarray) -> np.ndarray:
    """A record's task on a dask worker: its samples (m/s^2, (N,) or (N, 2) for a pair), which
    the task carries in the graph."""
    return accel
