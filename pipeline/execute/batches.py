"""Batches: one engine call each, one record and some of the grid's members; what a worker
runs for one (`simulate_batch`), and how many members a batch holds by default."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

import engine

from ..grid import buildings_for, contact_for
from .run import run_model

KEEP_SECONDS = 5.0
"""s: the most compute a part of a batch takes before its work is kept, here, on a dask worker
or in a Zarr store, whatever the batch size: each part is sized from the last one's pace
(`part_size`), the first from FIRST_PART members. A member's peaks do not depend on the members
run beside it, so the parts give the batch's numbers."""
FIRST_PART = 256
"""Members of the first part a run (or a Zarr store's batch) measures its pace on."""


def part_size(pace: float | None, samples: int) -> int:
    """Members of the next part: about KEEP_SECONDS of compute at `pace` (s per member and
    record sample, the last part's; None before any: FIRST_PART) under a record of `samples`
    samples; at least 1."""
    if pace is None:
        return FIRST_PART
    return max(1, int(KEEP_SECONDS / max(pace * samples, 1e-12)))


def reporter(report: tuple[str, str]):
    """progress(step, n_steps) on a dask worker: sends [tag, step / n_steps] to the client's
    event topic, report = (topic, tag)."""
    from distributed import get_worker

    worker, (topic, tag) = get_worker(), report

    def progress(step, n_steps):
        worker.log_event(topic, [tag, step / n_steps])

    return progress


@dataclass(frozen=True)
class Batch:
    """One engine call of a run.

    record: index into the run's records; members: which of the grid's members (an index
    array or a slice of grid.members); size: how many; key: unique among the run's batches
    (it names the batch in progress reports and its dask task); place: where the store puts
    its results (the store's own; None when the store needs nothing).
    """

    record: int
    members: np.ndarray | slice
    size: int
    key: str
    place: object = None


def simulate_batch(accel: np.ndarray, accel_dt: float, members: np.ndarray,
                   building: engine.Building, dt: float, moat: str | None = None,
                   factor: float | None = None, bumper_positions=None,
                   backend: str | None = None, progress=None,
                   report: tuple[str, str] | None = None) -> dict[str, np.ndarray]:
    """Peaks of (b,) members (members.MEMBER_DTYPE) under one record (m/s^2 every accel_dt s):
    peak name -> (b, ...) array, the run's model's quantities (engine.model.Model.quantities:
    its peaks, with collapsed and collapse_time for a building that can collapse). building:
    the sweep's; a member's isolator parameters replace its own (grid.buildings_for). moat:
    None for a planar run (accel (N,)), else the moat of a run in plan under a record pair
    (accel (N, 2), each member at its angle): PEAKS as resultants, then PLAN_PEAKS (and
    TORSION_PEAKS for a building that twists, its bumpers at bumper_positions). factor: the
    record's intensity factor (None: 1); members carrying a level run at factor x level
    (engine's scale), those without (NaN) at the record as it is. backend: the engine's time
    loop (engine.simulate's; None: its default).

    progress(step, n_steps) is called as the engine goes; on a dask worker, report =
    (topic, tag) sends [tag, step / n_steps] to the client's event topic instead.
    """
    if report is not None:
        progress = reporter(report)
    model = run_model(moat, building)
    plan = {} if not model.in_plan else {
        "moat": engine.Moat(moat, mu_wall=members["mu_wall"],
                            bumper_positions=bumper_positions
                            if model.takes("bumper_positions") else None),
        "angle": members["angle"]}
    result = engine.simulate(accel, accel_dt, contact_for(members),
                             building=buildings_for(members, building), dt=dt,
                             progress=progress, backend=backend,
                             scale=member_scale(members, factor), **plan)
    if not building.can_collapse and np.any(result.collapsed):
        # Without a collapse criterion only a numerical instability ends a run: its peaks
        # would be those of a run cut short, so the sweep stops rather than store them.
        first = int(np.argmax(result.collapsed))
        raise engine.EngineError(
            f"a member became numerically unstable at t = {result.collapse_time[first]:g} s "
            f"(its state was no longer finite); give the building a collapse_drift_ratio to "
            f"count such runs as collapses")
    return {q.name: np.asarray(getattr(result, q.name), dtype=q.dtype)
            for q in model.quantities(building.can_collapse)}


def member_scale(members: np.ndarray, factor: float | None) -> np.ndarray | None:
    """(b,) factors multiplying the record for each member (engine.simulate's scale): the
    record's factor times the member's level; None when the members carry no level (a grid
    without intensity: the record as it is, bit for bit)."""
    level = members["level"]
    if np.all(np.isnan(level)):
        return None
    # factor * level, in this order and nothing else: the product a study computes by hand
    # (a pair's MCE_R factor times the level) gives the same bits.
    return level.copy() if factor is None else factor * level


def default_batch_size(n_members: int, n_records: int, workers: int,
                       max_batch: int = 4096, *, steps: int = 80_000,
                       member_step_seconds: float = 35e-9, min_batch_seconds: float = 0.5) -> int:
    """Default members per engine batch, sized for the compiled kernel.

    With the kernel a batch costs ~35 ns per member-step and nearly nothing else, so the only
    reasons for large batches are dask's overhead per task (a few ms: a batch of at least
    min_batch_seconds keeps it under 5%) and memory (max_batch members, ~2 KB each). Batches
    should be small enough that every worker has several (4 per worker), so that no worker
    idles while another finishes a long record; the executor further splits the batches of
    records longer than the typical one (`record_batch_sizes`). steps: a typical record's
    number of steps (80,000 = 40 s at 0.5 ms).
    """
    workers = max(workers, 1)
    floor = math.ceil(min_batch_seconds / (max(steps, 1) * member_step_seconds))
    wanted = 4 * workers if workers > 1 else 1
    per_record = max(math.ceil(n_members / max_batch), math.ceil(wanted / max(n_records, 1)))
    size = math.ceil(n_members / per_record)
    return max(1, min(max_batch, n_members, max(size, floor)))


def record_batch_sizes(records, batch_size: int) -> list[int]:
    """Members per batch for each record: batch_size for records up to the median length,
    fewer for longer ones so that every batch is about as long as a typical one (a long
    record's batch would otherwise keep one worker busy after the others finish)."""
    lengths = [max(len(rec.accel) * rec.dt, 1e-9) for rec in records]
    typical = float(np.median(lengths)) if lengths else 1.0
    return [max(1, math.floor(batch_size * min(1.0, typical / length))) for length in lengths]
