"""The dask.distributed client of a run: given, at a scheduler's address, or on a new local
cluster of worker processes; and dask kept quiet when a run is stopped."""
from __future__ import annotations

import logging
import sys
from contextlib import contextmanager

# One BLAS and one numba thread per worker process: workers are the parallelism; more threads
# only contend for the same cores.
BLAS_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
            "NUMBA_NUM_THREADS": "1"}


@contextmanager
def client(workers: int, scheduler):
    """A dask.distributed Client: `scheduler` itself when it is one (the caller owns and
    closes it), a checked Client of the scheduler at that address (pipeline.cluster), or one
    of a new local cluster of `workers` processes, one thread each."""
    from distributed import Client, LocalCluster

    from ..cluster import connect

    if scheduler is not None and not isinstance(scheduler, str):
        yield scheduler
    elif scheduler is not None:
        with connect(scheduler) as connected:
            yield connected
    else:
        with main_hidden(), \
                LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                             dashboard_address=None, silence_logs=logging.ERROR,
                             env=BLAS_ENV) as cluster, \
                Client(cluster, set_as_default=False) as local:
            yield local


def silence_dask() -> None:
    """No more dask log lines: shutting down after a Ctrl-C makes dask log closed comms and
    cancelled tasks, which say nothing to the user."""
    for name in ("distributed", "tornado", "asyncio"):
        logging.getLogger(name).setLevel(logging.CRITICAL)


@contextmanager
def main_hidden():
    """While local worker processes may start, hide the __main__ module's file and spec.

    Worker processes are spawned, and a spawned process re-runs the parent's main script
    (multiprocessing's preparation data names it) unless that script has no file or spec. A
    script calling sweep without the `if __name__ == "__main__":` guard would then start
    sweeps, and clusters, inside its own workers. The workers need nothing from __main__: they
    run the stores' tasks (pipeline.execute), found by import.
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
