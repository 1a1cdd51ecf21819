"""Zarr archives for sweeps too large for one NetCDF file or one client's memory.

`pipeline.sweep(..., out="big.zarr")` writes a Zarr store instead of NetCDF. The client
writes the template first: every variable, coordinate and attribute of the NetCDF archive of
the same sweep (pipeline.archive's builders), the data still lazy. Each batch of members is
then exactly one chunk region of its block's variables: records are chunked by 1, the swept
dimensions in C order by 1 up to one dimension cut in blocks, so that a chunk holds a
contiguous range of the block's members. Whoever runs the batch (this process, or a dask
worker) writes its peaks into that region and sets its own element of `batch_done` (one chunk
per batch: no two writers share a chunk). The results never pass through the client, which
holds only the member table and the batch list.

`batch_done` is the resume record: a rerun with the same sweep skips the batches marked
done; the store's `sweep_key` attribute (engine, records, dt, building, members) must match,
so a store of another sweep is refused, not mixed. When every batch is done the client adds
the amplification ratios (chunk by chunk, through dask) and sets the attribute
`complete = 1`; a store without it is unfinished. It opens with `xr.open_zarr(path)`.
"""
from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import Interrupted, SweepError

TARGET_CHUNK = 4096  # members per chunk (= per batch) at most
ZARR_FORMAT = 2


@dataclass(frozen=True)
class ZarrBatch:
    """One chunk region: record index, block prefix, member range within the block and the
    region of the block's variables (a tuple of slices over record and the block's dims)."""

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


def batches_for(grid, n_records: int, target: int) -> list[ZarrBatch]:
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
                out.append(ZarrBatch(len(out), r, block.prefix, offset, start, stop, region))
        offset += block.size
    return out


def sweep_key(grid, contexts: list[str]) -> str:
    digest = hashlib.sha256(json.dumps(contexts).encode())
    digest.update(np.ascontiguousarray(grid.members).data)  # no copy of a large table
    return digest.hexdigest()


def write_template(path: Path, grid, records, names, dt, building, arguments, key,
                   n_batches: int, target: int) -> None:
    """Create the store: labelled variables (lazy), coordinates, attributes, batch_done."""
    import dask.array as da
    import xarray as xr

    from .archive import build_dataset

    def chunks(block):
        return block_chunks(block.shape, target)

    # The labels of the NetCDF archive, its data lazy fill values: nothing of the size of the
    # results is ever held here.
    ds = build_dataset(grid, records, None, dt, building, names, arguments, chunks=chunks)
    encoding = {name: {"chunks": var.data.chunksize} for name, var in ds.data_vars.items()}
    ds["batch_done"] = xr.Variable("batch", da.zeros(n_batches, dtype=np.int8, chunks=1),
                                   {"units": "1", "long_name": "1 once the batch's chunk "
                                    "region is written (the resume record)"})
    encoding["batch_done"] = {"chunks": (1,)}
    ds.attrs.update(sweep_key=key, complete=0, members_per_chunk=target)
    # Zarr format 2: its string and attribute encodings are read by every Zarr library.
    ds.to_zarr(path, mode="w", compute=False, encoding=encoding, consolidated=False,
               zarr_format=ZARR_FORMAT)
    # The template's fill values are the data until a batch writes its region: write the
    # (all-zero) batch_done explicitly so that it reads as 0, not as missing.
    import zarr

    zarr.open_group(str(path), mode="r+")["batch_done"][:] = 0


def run_batch(path: str, accel, accel_dt, members, building, dt, prefix: str, region,
              index: int) -> int:
    """Simulate one batch and write its peaks into its chunk region; returns its size."""
    import zarr

    from .run import simulate_batch

    peaks = simulate_batch(accel, accel_dt, members, building, dt)
    group = zarr.open_group(path, mode="r+")
    for name, values in peaks.items():
        target = group[prefix + name]
        shape = tuple(s.stop - s.start for s in region) + values.shape[1:]
        target[region] = values.reshape(shape)
    group["batch_done"][index] = 1
    return members.size


def run_zarr(grid, records, names, dt, building, arguments, out: Path, contexts, *,
             workers: int, scheduler, batch_size: int, quiet: bool):
    """Run the sweep into the store at `out` (resuming it when it holds this sweep) and
    return it opened lazily."""
    import xarray as xr
    import zarr

    from .run import Progress, _client

    target = max(1, min(batch_size, TARGET_CHUNK))
    key = sweep_key(grid, contexts)
    resuming = out.exists()
    if resuming:
        try:
            group = zarr.open_group(str(out), mode="r")
            same = group.attrs.get("sweep_key") == key
        except Exception:  # noqa: BLE001 - anything unreadable is not this sweep's store
            same = False
        if not same:
            raise SweepError(f"out: {out} holds another sweep (or no store): remove it or "
                             "choose another path")
        target = int(group.attrs["members_per_chunk"])  # the store's chunks, not batch_size
    batches = batches_for(grid, len(records), target)
    done = np.zeros(len(batches), dtype=bool)
    if resuming:
        done = group["batch_done"][:].astype(bool)
    else:
        write_template(out, grid, records, names, dt, building, arguments, key,
                       len(batches), target)
    members = grid.members
    todo = [b for b in batches if not done[b.index]]
    total = len(records) * grid.n_members
    progress = Progress(total, total - sum(b.stop - b.start for b in todo), quiet)

    def task_args(b: ZarrBatch, accel):
        rows = members[b.offset + b.start:b.offset + b.stop]
        return (str(out), accel, records[b.record].dt, rows, building, dt, b.prefix,
                b.region, b.index)

    try:
        if todo and scheduler is None and workers <= 1:
            for b in todo:
                progress.advance(run_batch(*task_args(b, records[b.record].accel)))
        elif todo:
            from distributed import as_completed

            with _client(workers, scheduler) as client:
                accel = {r: client.scatter(np.asarray(records[r].accel), hash=False)
                         for r in sorted({b.record for b in todo})}
                futures = [client.submit(run_batch, *task_args(b, accel[b.record]),
                                         key=f"bumpers-zarr-{key[:12]}-{b.index}")
                           for b in todo]
                try:
                    for future in as_completed(futures, loop=client.loop):
                        progress.advance(future.result())
                except KeyboardInterrupt:
                    client.cancel(futures, force=True)
                    raise
    except KeyboardInterrupt:
        progress.interrupted()
        raise Interrupted(int(progress.done), total, out) from None
    progress.close()
    _finish(out, grid)
    return xr.open_zarr(out, consolidated=True)


def _finish(out: Path, grid) -> None:
    """Amplification ratios (lazily, chunk by chunk) and the `complete` mark."""
    import xarray as xr
    import zarr

    from .archive import AMPLIFICATION

    if grid.block("baseline_") is not None:
        ds = xr.open_zarr(out, consolidated=False)
        if "amplification_total_accel" not in ds:
            ratios = {}
            for name, (peak, long_name) in AMPLIFICATION.items():
                ratio = (ds[peak] / ds["baseline_" + peak]).transpose(*ds[peak].dims)
                ratio.attrs = {"units": "1", "long_name": long_name}
                ratios[name] = ratio.chunk(dict(zip(ds[peak].dims, ds[peak].data.chunksize,
                                                    strict=True)))
            # mode "a" rewrites the group's attributes with the Dataset's: keep them
            xr.Dataset(ratios, attrs=ds.attrs).to_zarr(out, mode="a", consolidated=False)
    group = zarr.open_group(str(out), mode="r+")
    group.attrs["complete"] = 1
    zarr.consolidate_metadata(str(out))
