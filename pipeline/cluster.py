"""Connecting to a dask.distributed cluster, and refusing one that cannot run a sweep.

A sweep submitted to a cluster whose workers cannot import the project, or run another
version of it, fails far from its cause (dask reports a cancelled future; the real error is in
a worker's log) or, worse, mixes results of two engines. So before any batch is submitted the
client checks, each failure being one ClusterError line that names the cause and the fix:
the scheduler answers (CONNECT_TIMEOUT), it has workers (WORKERS_TIMEOUT), every worker can
import the project, and every worker's engine fingerprint (pipeline.provenance) equals this
process's. A worker that dies during the run needs nothing from here: the scheduler gives its
batches to the others (results do not depend on where a batch runs).
"""
from __future__ import annotations

from contextlib import contextmanager

from .errors import ClusterError

CONNECT_TIMEOUT = 5.0  # s
WORKERS_TIMEOUT = 10.0  # s
START_HINT = ("start a scheduler with `dask scheduler` and workers with `dask worker "
              "tcp://HOST:8786 --nthreads 1` (see README, Running on a cluster)")
# Expressions evaluated on the workers with the builtin eval: a builtin is found by name on
# any worker, whereas a function of this project cannot even be unpickled on a worker that
# lacks the project, which is the case to detect.
CAN_IMPORT = "__import__('importlib.util').util.find_spec('engine') is not None " \
             "and __import__('importlib.util').util.find_spec('pipeline') is not None"
FINGERPRINT = "__import__('pipeline.provenance').provenance.engine_fingerprint()"


@contextmanager
def connect(address: str):
    """A checked Client of the scheduler at `address` (closed on exit)."""
    from distributed import Client

    try:
        client = Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError) as err:
        raise ClusterError(f"scheduler {address}: no answer within {CONNECT_TIMEOUT:g} s "
                           f"({type(err).__name__}); check the address, or {START_HINT}"
                           ) from None
    with client:
        check_workers(client)
        yield client


def check_workers(client) -> None:
    """Refuse a cluster without workers, with workers lacking the project, or at another
    version of it (ClusterError)."""
    from .provenance import engine_fingerprint

    address = client.scheduler.address
    try:
        client.wait_for_workers(1, timeout=WORKERS_TIMEOUT)
    except TimeoutError:
        raise ClusterError(f"scheduler {address} has no workers after {WORKERS_TIMEOUT:g} s: "
                           f"start some with `dask worker {address} --nthreads 1` on machines "
                           "where this project is installed") from None
    found = client.run(eval, CAN_IMPORT, on_error="return")
    missing = sorted(worker for worker, ok in found.items() if ok is not True)
    if missing:
        raise ClusterError(f"workers {', '.join(missing)} cannot import this project "
                           "(engine, pipeline): install it on every worker machine at the same "
                           "commit (`pip install -e /path/to/bumpers`) and restart the workers")
    mine = engine_fingerprint()
    theirs = client.run(eval, FINGERPRINT, on_error="return")
    other = sorted(worker for worker, fingerprint in theirs.items() if fingerprint != mine)
    if other:
        raise ClusterError(f"workers {', '.join(other)} run another version of this project "
                           f"(engine fingerprint differs from {mine[:12]}): install the same "
                           "commit on every worker and restart them")
