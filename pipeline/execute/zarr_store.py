"""The Zarr store, for sweeps too large for one NetCDF file or one client's memory.

`pipeline.sweep(..., out="big.zarr")` writes a Zarr store instead of NetCDF. The client
writes the template first: every variable, coordinate and attribute of the NetCDF archive of
the same sweep (pipeline.archive's builders), the data still lazy. Each batch of members is
then exactly one chunk region of its block's variables: records are chunked by 1, the swept
dimensions in C order by 1 up to one dimension cut in blocks, so that a chunk holds a
contiguous range of the block's members. Whoever runs the batch (this process, or a dask
worker) writes its peaks into that region, a part of about batches.KEEP_SECONDS of compute
at a time, counts them in its element of `batch_members_done` and, the region full, sets its
element of `batch_done` (one chunk per batch: no two writers share a chunk). The results never
pass through the client, which holds only the member table and the batch list.

`batch_done` and `batch_members_done` are the resume record (RESUME_RECORD): a rerun with the
same sweep skips the batches marked done and runs only the members not yet written of the
others; the store's `sweep_key` attribute (pipeline.execute.keys: engine, records, dt,
building, members) must match, so a store of another sweep is refused, not mixed. When every
batch is done the client adds the derived variables (amplification ratios, story ductility;
chunk by chunk, through dask) and sets the attribute `complete = 1`; a store without it is
unfinished. It opens with
`xr.open_zarr(path)`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import SweepError
from ..writing import archive_key
from . import batches
from .keys import region_key, sweep_key

TARGET_CHUNK = 4096  # members per chunk (= per batch) at most
ZARR_FORMAT = 2
RESUME_RECORD = {
    "batch_done": (np.int8, "1", "1 once the batch's chunk region is written (the resume "
                   "record)"),
    "batch_members_done": (np.int32, "1", "members of the batch's region written so far (a "
                           "batch runs in parts, each kept as it ends: a run resumed goes on "
                           "from here)")}
"""What a Zarr store adds to the archive's variables, along `batch` (one element per chunk
region): name -> (dtype, units, long name)."""


@dataclass(frozen=True)
class Region:
    """One chunk region: its index in batch_done, record index, block prefix, member range
    within the block and the region of the block's variables (a tuple of slices over record
    and the block's dims)."""

    index: int
    record: int
    prefix: str
    offset: int  # the block's first member in grid.members
    start: int
    stop: int
    region: tuple


def block_chunks(shape: tuple[int, ...], target: int) -> tuple[int, ...]:
    """Chunk sizes over a block's swept dims such that a chunk is a contiguous C-order range
    of members: trailing dims whole while they fit in `target`, one dim cut, the rest 1."""
    chunks = [1] * len(shape)
    size = 1
    for axis in range(len(shape) - 1, -1, -1):
        if size * shape[axis] <= target:
            chunks[axis] = shape[axis]
            size *= shape[axis]
        else:
            chunks[axis] = max(1, target // size)
            break
    return tuple(chunks)


def regions_for(grid, n_records: int, target: int) -> list[Region]:
    """Every chunk region of every block under every record, in a fixed order."""
    out = []
    offset = 0
    for block in grid.blocks:
        chunks = block_chunks(block.shape, target)
        grid_counts = [math.ceil(n / c) for n, c in zip(block.shape, chunks, strict=True)]
        for r in range(n_records):
            for idx in np.ndindex(*grid_counts) if block.shape else [()]:
                lo = [i * c for i, c in zip(idx, chunks, strict=True)]
                hi = [min(n, i * c + c) for i, n, c in zip(idx, block.shape, chunks,
                                                           strict=True)]
                start = int(np.ravel_multi_index(lo, block.shape)) if block.shape else 0
                stop = (int(np.ravel_multi_index([h - 1 for h in hi], block.shape)) + 1
                        if block.shape else 1)
                region = (slice(r, r + 1), *(slice(a, b) for a, b in zip(lo, hi,
                                                                         strict=True)))
                out.append(Region(len(out), r, block.prefix, offset, start, stop, region))
        offset += block.size
    return out


def write_template(path: Path, grid, run, key, n_batches: int, target: int) -> None:
    """Create the store: labelled variables (lazy), coordinates, attributes, batch_done."""
    import dask.array as da
    import xarray as xr
    import zarr

    from ..archive import build_dataset

    def chunks(block):
        return block_chunks(block.shape, target)

    # The labels of the NetCDF archive, its data lazy fill values: nothing of the size of the
    # results is ever held here.
    ds = build_dataset(grid, run, None, chunks=chunks)
    encoding = {name: {"chunks": var.data.chunksize} for name, var in ds.data_vars.items()}
    for name, (dtype, units, long_name) in RESUME_RECORD.items():
        ds[name] = xr.Variable("batch", da.zeros(n_batches, dtype=dtype, chunks=1),
                               {"units": units, "long_name": long_name})
        encoding[name] = {"chunks": (1,)}
    ds.attrs.update(sweep_key=key, configuration_key=key, complete=0,
                    members_per_chunk=target)
    # Zarr format 2: its string and attribute encodings are read by every Zarr library.
    ds.to_zarr(path, mode="w", compute=False, encoding=encoding, consolidated=False,
               zarr_format=ZARR_FORMAT)
    # The template's fill values are the data until a batch writes its region: write the
    # (all-zero) batch_done explicitly so that it reads as 0, not as missing.
    group = zarr.open_group(str(path), mode="r+")
    for name in RESUME_RECORD:
        group[name][:] = 0


def write_batch(accel, accel_dt, members, building, dt, path: str, place: Region,
                how: dict | None = None, progress=None, report=None) -> int:
    """A worker's task: simulate the batch's `members` (batches.simulate_batch, with its
    keywords `how`: moat, factor, bumper_positions, backend) and write their peaks into its
    chunk region `place` of the store at `path`, then mark it done; returns how many members
    it ran. `members` are the region's last ones (those not yet written, when a run resumes a
    region begun): they run in parts of about batches.KEEP_SECONDS of compute each, sized from
    the last part's pace, and each part is written and counted in `batch_members_done` as it
    ends, so that a run stopped within a batch keeps its finished parts."""
    import time

    import zarr

    group = zarr.open_group(path, mode="r+")
    size = place.stop - place.start
    first = size - members.size  # the region's members written before this task
    samples_ = len(accel)
    if report is not None:
        progress = batches.reporter(report)
    start, pace = 0, None
    while start < members.size:
        stop = min(members.size, start + batches.part_size(pace, samples_))
        began = time.perf_counter()
        peaks = batches.simulate_batch(
            accel, accel_dt, members[start:stop], building, dt,
            progress=None if progress is None else
            (lambda step, steps, a=start, n=stop - start:
             progress(a * steps + n * step, members.size * steps)), **(how or {}))
        pace = (time.perf_counter() - began) / ((stop - start) * samples_)
        _write_rows(group, place, first + start, first + stop, peaks)
        start = stop
        if "batch_members_done" in group:  # a store written before it keeps whole batches
            group["batch_members_done"][place.index] = first + start
    group["batch_done"][place.index] = 1
    return members.size


def _write_rows(group, place: Region, a: int, b: int, peaks: dict) -> None:
    """Write peaks of the region's members a:b (in the region's C order) into its variables:
    the region at once when a:b is all of it, else read, filled in and written back (the task
    running a region is the only writer of its chunk)."""
    size = place.stop - place.start
    for name, values in peaks.items():
        target = group[place.prefix + name]
        shape = tuple(s.stop - s.start for s in place.region) + values.shape[1:]
        if (a, b) == (0, size):
            target[place.region] = values.reshape(shape)
            continue
        block = np.array(target[place.region]).reshape((size,) + values.shape[1:])
        block[a:b] = values
        target[place.region] = block.reshape(shape)


class ZarrStore:
    """A sweep written region by region into the Zarr store at `out` (pipeline.execute's
    Store interface): created with its template, or reopened to resume when it holds this
    sweep (SweepError when it holds another); `finish` completes it and opens it lazily.

    batch_size: members per chunk (at most TARGET_CHUNK) of a new store; a store being resumed
    keeps its own chunks. derive: what the peaks mean, added by `finish` (as
    pipeline.archive.build_dataset's; None: peaks only).
    """

    def __init__(self, grid, run, out: Path, batch_size: int, force: bool = False,
                 derive=None):
        import shutil

        import zarr

        self.grid, self.run, self.records = grid, run, run.records
        self.out = self.kept_in = out
        self.derive = derive
        self.total = len(run.records) * grid.n_members
        self.key = sweep_key(grid.every_member, run.contexts())
        target = max(1, min(batch_size, TARGET_CHUNK))
        if force and out.exists() and archive_key(out) != self.key:  # asked to replace it
            if out.is_dir():
                shutil.rmtree(out)
            else:
                out.unlink()
        resuming = out.exists()
        if resuming:
            try:
                group = zarr.open_group(str(out), mode="r")
                same = group.attrs.get("sweep_key") == self.key
            except Exception:  # noqa: BLE001 - anything unreadable is not this sweep's store
                same = False
            if not same:
                told = f"{out} holds another sweep (or no store): it is kept. Give {{}} to " \
                    "replace it, or another {}"
                raise SweepError(told.format("force=True", "out"),
                                 told.format("--force", "--out"))
            target = int(group.attrs["members_per_chunk"])  # the store's chunks, not batch_size
        self.regions = regions_for(grid, len(run.records), target)
        # Members written of each region (a store written before batch_members_done: whole
        # regions only, done or not).
        self.written = np.zeros(len(self.regions), dtype=np.int64)
        if resuming:
            self.done = group["batch_done"][:].astype(bool)
            if "batch_members_done" in group:
                self.written[:] = group["batch_members_done"][:]
        else:
            self.done = np.zeros(len(self.regions), dtype=bool)
            write_template(out, grid, run, self.key, len(self.regions), target)

    def pending(self, sizes: list[int]) -> list[batches.Batch]:
        """The regions not marked done, each of its members not yet written (a region is the
        store's chunk, whatever `sizes`; write_batch keeps its parts)."""
        return [batches.Batch(r.record,
                              slice(r.offset + r.start + int(self.written[r.index]),
                                    r.offset + r.stop),
                              r.stop - r.start - int(self.written[r.index]),
                              region_key(self.key, r.index), r)
                for r in self.regions if not self.done[r.index]]

    def task(self, batch: batches.Batch) -> tuple:
        """Simulate the batch and write its region: write_batch."""
        r, run = batch.place, self.run
        return write_batch, (self.records[batch.record].dt,
                             self.grid.members_of(batch.record)[batch.members],
                             run.building, run.dt, str(self.out), r,
                             run.engine_keywords(batch.record))

    def accept(self, batch: batches.Batch, size: int) -> None:
        """Nothing to do: the worker wrote the region."""

    def finish(self):
        """Derived variables (lazily, chunk by chunk), the `complete` mark, consolidated
        metadata; the store opened lazily."""
        import xarray as xr
        import zarr

        ds = xr.open_zarr(self.out, consolidated=False)
        derived = {} if self.derive is None else {
            name: pair for name, pair in self.derive(ds, self.run.building, self.grid).items()
            if name not in ds}
        if derived:
            variables = {}
            for name, (value, peak) in derived.items():
                # The variable alone, chunked as its peak: its coordinates are in the store
                # already (written again, chunked by record, they would straddle its chunks).
                variables[name] = value.variable.chunk(dict(zip(
                    ds[peak].dims, ds[peak].data.chunksize, strict=True)))
            # mode "a" rewrites the group's attributes with the Dataset's: keep them
            xr.Dataset(variables, attrs=ds.attrs).to_zarr(self.out, mode="a",
                                                          consolidated=False)
        group = zarr.open_group(str(self.out), mode="r+")
        group.attrs["complete"] = 1
        zarr.consolidate_metadata(str(self.out))
        return xr.open_zarr(self.out, consolidated=True)
