"""A sweep's archive read as runs: the layout pipeline.sweep writes (NetCDF or Zarr; see
pipeline/archive.py), its blocks of runs, their peaks and swept coordinates, and the one-line
refusal of anything else.

An archive holds up to three blocks of runs, named by the prefix of their variables: the
chosen wall law over the full grid (no prefix: "bumpers"), the bare wall at each full gap
("baseline_") and no wall ("unconstrained_"). Each block's peaks share its run dimensions
(record, then the swept parameters it runs over) followed by their own trailing axes
(floor, story, wall, direction).
"""
from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from engine.results import COLLAPSE, PEAKS, PLAN_PEAKS, RESIDUALS
from pipeline.assess.sweep_variables import AMPLIFICATION, STORY_DUCTILITY
from pipeline.assess.validity import FLAGS

TRAILING = ("floor", "story", "wall", "direction")
"""The axes of a run's own results: one column each in a table, never a run."""
BLOCKS = {"": "bumpers", "baseline_": "baseline", "unconstrained_": "unconstrained"}
"""Variable prefix -> the block's name in a table's `block` column."""
QUANTITIES = tuple(q.name for q in (*PEAKS, *PLAN_PEAKS, *RESIDUALS, *COLLAPSE,
                                    STORY_DUCTILITY)) + tuple(FLAGS)
"""What each block of a sweep's archive may hold, by name: its results (peaks, what stays at
the end of the run, how it ended) and their validity flags (a run outside the model's range is
marked in every table, never passed on unmarked)."""
EXPECTED = ("a sweep archive of bumpers (pipeline.sweep or `bumpers sweep`: NetCDF .nc or "
            "Zarr .zarr) with peak_total_accel along (record, ..., floor)")


class ArchiveError(Exception):
    """Bad input: one line, exit status 2."""


def open_archive(path) -> xr.Dataset:
    """The archive at `path`, loaded; ArchiveError (one line) for a missing file, a file that
    is no NetCDF or Zarr archive, an archive of another layout, an unfinished Zarr store."""
    path = Path(path)
    if not path.exists():
        raise ArchiveError(f"{path}: no such file")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if path.is_dir():
                with xr.open_zarr(path) as ds:
                    ds = ds.load()
            else:
                with xr.open_dataset(path) as ds:
                    ds = ds.load()
    except Exception as err:  # noqa: BLE001 - whatever the reader says, it is not one
        raise ArchiveError(f"{path}: not a NetCDF or Zarr archive ({type(err).__name__}); "
                           f"expected {EXPECTED}") from None
    accel = ds.get("peak_total_accel")
    if accel is None or accel.dims[:1] != ("record",) or accel.dims[-1:] != ("floor",):
        found = ", ".join(list(ds.data_vars)[:6]) or "no variables"
        raise ArchiveError(f"{path}: not the layout of a sweep archive (found {found}); "
                           f"expected {EXPECTED}")
    if int(ds.attrs.get("complete", 1)) != 1:
        raise ArchiveError(f"{path}: the Zarr store is unfinished (attribute complete = 0): "
                           "run the same sweep again to fill in its missing batches")
    return ds


def block_variables(ds: xr.Dataset) -> dict[str, list[str]]:
    """Block name -> its variables in the archive (the bumpers block with its amplification
    ratios), for the blocks the archive has, in BLOCKS order."""
    found = {}
    for prefix, block in BLOCKS.items():
        names = [prefix + q for q in QUANTITIES if prefix + q in ds.data_vars]
        if prefix == "":
            names += [name for name in AMPLIFICATION if name in ds.data_vars]
        if names:
            found[block] = names
    return found


def run_dims(var: xr.DataArray) -> tuple[str, ...]:
    """The dimensions of `var` that tell runs apart (its trailing axes left out)."""
    return tuple(d for d in var.dims if d not in TRAILING)


def label(name: str, units: str) -> str:
    """A column's name: the quantity, then its units in brackets (none for "1")."""
    return name if units in ("1", "") else f"{name} [{units}]"


def columns_of(var: xr.DataArray, name: str) -> tuple[list[str], np.ndarray]:
    """(column names, values (runs, columns)) of variable `var` named `name`: one column per
    element of its trailing axes (peak_total_accel_floor4, max_impact_force_wall_wall+x,
    peak_total_accel_xy_floor0_x), its runs in C order over run_dims(var)."""
    lead, tail = run_dims(var), [d for d in var.dims if d in TRAILING]
    values = var.transpose(*lead, *tail).values
    runs = int(np.prod([var.sizes[d] for d in lead], dtype=int))
    values = values.reshape(runs, -1)
    suffixes = [""]
    for dim in tail:
        marks = [f"_{v}" if dim == "direction" else f"_{dim}{v}" for v in var[dim].values]
        suffixes = [s + m for s in suffixes for m in marks]
    units = var.attrs.get("units", "1")
    return [label(name + s, units) for s in suffixes], values


def run_coordinates(ds: xr.Dataset, dims: tuple[str, ...]) -> dict[str, np.ndarray]:
    """Column -> values (runs,) of the coordinates that tell the runs over `dims` apart, in C
    order: each dimension's own coordinate (record, gap, n_bumpers, ...), then the columns of
    members listed one by one (law, gap, ...: coordinates along member). The records' own
    coordinates (record_pga, ...) and the fixed parameters stay in the archive."""
    shape = [ds.sizes[d] for d in dims]
    grids = np.indices(shape).reshape(len(dims), -1) if dims else np.zeros((0, 1), int)
    found = {}
    ordered = [*(d for d in dims if d in ds.coords), *(c for c in ds.coords if c not in dims)]
    for name in ordered:
        coord = ds.coords[name]
        own = coord.dims == (name,) and name in dims
        along = coord.dims and set(coord.dims) <= set(dims) and not name.startswith("record_") \
            and name not in TRAILING
        if not (own or along):
            continue
        index = tuple(grids[dims.index(d)] for d in coord.dims)
        found[label(name, coord.attrs.get("units", "1"))] = coord.values[index]
    return found


def runs_table(ds: xr.Dataset, blocks=None) -> pd.DataFrame:
    """The archive's runs as one table: a row per run (record, swept coordinates, block, then
    one column per peak per floor / story / wall / direction, named with its units), the
    blocks in BLOCKS order, each in the C order of its dimensions; empty where a block does
    not run over a coordinate (the baseline has no n_bumpers) or has no such peak (the
    amplification ratios are the bumpers' own). `blocks`: the block names to keep (None: all).
    """
    frames = []
    for block, names in block_variables(ds).items():
        if blocks is not None and block not in blocks:
            continue
        prefix = next(p for p, b in BLOCKS.items() if b == block)
        dims = run_dims(ds[prefix + "peak_total_accel"])
        columns = {**run_coordinates(ds, dims), "block": np.full(
            int(np.prod([ds.sizes[d] for d in dims], dtype=int)), block)}
        for name in names:
            if run_dims(ds[name]) != dims:
                continue  # not a per-run variable of this block's layout
            labels, values = columns_of(ds[name], name[len(prefix):])
            columns.update(zip(labels, values.T, strict=True))
        frames.append(pd.DataFrame(columns))
    if not frames:
        raise ArchiveError(f"no runs of the blocks {', '.join(blocks)} in this archive; it has "
                           f"{', '.join(block_variables(ds))}")
    integers = {c for f in frames for c in f.columns if f[c].dtype.kind in "iu"}
    table = pd.concat(frames, ignore_index=True, sort=False)
    for column in integers:  # an integer column stays one where a block leaves it empty
        table[column] = table[column].astype("Int64")
    first = [c for c in table.columns if c not in ("block",) and not _is_result(c)]
    return table[first + ["block"] + [c for c in table.columns if _is_result(c)]]


def _is_result(column: str) -> bool:
    name = column.split(" [")[0]
    return any(name == q or name.startswith(q + "_") for q in (*QUANTITIES, *AMPLIFICATION))


def select(ds: xr.Dataset, selections: list[str]) -> xr.Dataset:
    """`ds` at DIM=VALUE for each selection (numbers matched to 1e-9 relative, strings
    exactly); the dimension then drops out. ArchiveError naming the dims or values there are."""
    for text in selections:
        dim, sep, value = text.partition("=")
        if not sep or dim not in ds.dims or dim in TRAILING:
            runs = [d for d in ds.dims if d not in TRAILING]
            raise ArchiveError(f"--sel {text}: give DIM=VALUE with DIM one of "
                               f"{', '.join(runs)}")
        coord = ds[dim].values
        if coord.dtype.kind in "fiu":
            try:
                number = float(value)
            except ValueError:
                number = np.nan
            hit = np.flatnonzero(np.isclose(coord.astype(float), number, rtol=1e-9, atol=0))
        else:
            hit = np.flatnonzero(coord.astype(str) == value)
        if hit.size == 0:
            shown = ", ".join(f"{v:g}" if coord.dtype.kind in "fiu" else str(v)
                              for v in coord[:12])
            raise ArchiveError(f"--sel {text}: {dim} has no value {value} (it has {shown})")
        ds = ds.isel({dim: int(hit[0])})
    return ds
