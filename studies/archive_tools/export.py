"""`bumpers export ARCHIVE --csv OUT.csv | --pelicun OUT.csv`: a sweep archive's peaks as a
table a spreadsheet reads, or as a demand sample in pelicun's convention.

    bumpers export results/my_sweep.nc --csv results/my_sweep.csv
    bumpers export results/my_sweep.nc --pelicun results/demands.csv --story-height-m 3.5

--csv: one row per run (every block: bumpers, baseline, unconstrained), columns record, the
swept coordinates, block, then one per peak per floor / story / wall / direction, named with
its units (`peak_total_accel_floor4 [m s-2]`), SI as in the archive, and the block's validity
flags (`invalid_floor_accel` and kin, 1 where the run is outside the model's range:
pipeline.assess.validity) (table.runs_table).

--pelicun: one row per run of one block (default the bumpers'), in the order of the --csv rows
of that block; columns in FEMA P-58 / pelicun's `EVENT-TYPE-LOCATION-DIRECTION` convention,
the event 1: `1-PFA-<floor>-<dir>` the peak floor acceleration in g (pelicun's g,
9.80665 m/s^2, so that pelicun reads back the archive's m/s^2 exactly) and
`1-PID-<story>-<dir>` the peak interstory drift ratio (deflection / story height, rad), with
pelicun's units row (`Units,g,...,rad,...`) under the header, as pelicun's
DemandModel.load_sample reads it (pelicun's own test data: tests/basic/data/model/
test_DemandModel/load_sample/demand_sample_A.csv). Location 0 is the isolation slab (level 0
of the archive: the lowest floor of an isolated building), story i joins levels i-1 and i;
direction 1 in the planar model, 1 and 2 (x, y) in plan. No PFV: the archive's floor
velocities are relative to the ground and resultants in plan, and whether FEMA P-58's PFV is
that velocity or the total one, per direction, is not checked against the standard.

Bad input (a missing file, no sweep archive, an unknown block or selection, no story heights)
is one `error:` line and exit status 2; the output is written to a temporary file beside it and
renamed, so it is whole or absent (pipeline.writing.Staged).
"""
from __future__ import annotations

import argparse
import sys

import numpy as np

from ..common.recipe import OneLineParser
from .table import BLOCKS, ArchiveError, open_archive, runs_table, select

PELICUN_G = 9.80665
"""m/s^2 in pelicun's unit g (its settings/default_units.json): the standard gravity, not the
9.81 the building uses for weights (engine.units.G)."""
PELICUN_EVENT = 1
"""The event (hazard level) field of every pelicun column; pelicun drops it on reading."""


def parser() -> argparse.ArgumentParser:
    p = OneLineParser(
        prog="bumpers export",
        description="Write a sweep archive's peaks (pipeline.sweep or `bumpers sweep`, NetCDF "
                    "or Zarr) as a CSV table, one row per run, or as a pelicun demand sample "
                    "(FEMA P-58 demand types PFA in g, PID in rad, with pelicun's units row).")
    p.add_argument("archive", metavar="ARCHIVE", help="the sweep's archive (.nc or .zarr)")
    out = p.add_mutually_exclusive_group(required=True)
    out.add_argument("--csv", metavar="OUT.csv",
                     help="one row per run: record, the swept coordinates, block (bumpers, "
                          "baseline, unconstrained), then one column per peak per floor / "
                          "story, named with its SI units, e.g. 'peak_total_accel_floor4 "
                          "[m s-2]'")
    out.add_argument("--pelicun", metavar="OUT.csv",
                     help="pelicun's demand sample: one row per run of --block, columns "
                          "1-PFA-<floor>-<dir> (g) and 1-PID-<story>-<dir> (drift ratio, rad), "
                          "a units row under the header")
    p.add_argument("--block", choices=tuple(BLOCKS.values()), default=None,
                   help="the block of runs to export (--csv default: all; --pelicun default: "
                        "bumpers)")
    p.add_argument("--sel", action="append", default=[], metavar="DIM=VALUE",
                   help="only the runs at this value of a swept dimension, e.g. --sel gap=0.2 "
                        "(repeatable): a pelicun sample is usually the records at one "
                        "configuration")
    p.add_argument("--story-height-m", nargs="+", type=float, metavar="H",
                   help="--pelicun: the story heights in m (one for every story, or one per "
                        "story), for the drift ratios; needed when the archive has no "
                        "building_story_height attribute")
    return p


def story_heights(ds, given) -> np.ndarray:
    """The story heights (m), one per story: the archive's building_story_height, else
    --story-height-m; ArchiveError when neither says or they disagree."""
    n = ds.sizes["story"]
    stated = ds.attrs.get("building_story_height")
    if stated is not None and not isinstance(stated, str):
        heights = np.atleast_1d(np.asarray(stated, dtype=float))
        if given is not None and not np.allclose(np.broadcast_to(given, n) if len(given) == 1
                                                 else given, heights):
            raise ArchiveError(f"--story-height-m: the archive's building has story heights "
                               f"{', '.join(f'{h:g}' for h in heights)} m; leave the option "
                               "out")
        return heights
    if given is None:
        raise ArchiveError("--pelicun needs story heights for the drift ratios and the archive "
                           "has none (no building_story_height): give --story-height-m H "
                           f"(one, or {n}: one per story)")
    if len(given) not in (1, n) or not all(np.isfinite(given)) or min(given) <= 0:
        raise ArchiveError(f"--story-height-m: give one positive height or {n} (one per "
                           f"story), in m; got {' '.join(f'{h:g}' for h in given)}")
    # A story's height as the building declares a plausible one (a 300 m story, a slip for
    # cm or mm, would make every drift ratio 100 times too small).
    from engine.building import FIELDS
    from engine.parameters import interval, outside

    plausible = FIELDS["story_height"].plausible
    odd = np.asarray(given, float)[outside(np.asarray(given, float),
                                           interval("story_height", plausible))]
    if odd.size:
        raise ArchiveError(f"--story-height-m: a story {odd[0]:g} m high is implausible "
                           f"(outside {plausible} m); give the heights in m")
    return np.broadcast_to(np.asarray(given, dtype=float), (n,)).copy()


def pelicun_sample(ds, block: str, heights: np.ndarray):
    """The demand sample of `block`'s runs as a DataFrame: its columns pelicun's demand
    labels, its first row the units ("Units"), then one row per run (0, 1, ...)."""
    import pandas as pd

    prefix = next(p for p, b in BLOCKS.items() if b == block)
    if prefix + "peak_total_accel" not in ds:
        there = [b for p, b in BLOCKS.items() if p + "peak_total_accel" in ds]
        raise ArchiveError(f"--block {block}: the archive has no {block} runs (it has "
                           f"{', '.join(there)})")
    planar = prefix + "peak_total_accel_xy" not in ds
    accel = ds[prefix + ("peak_total_accel" if planar else "peak_total_accel_xy")]
    drift = ds[prefix + ("peak_interstory_drift" if planar else "peak_interstory_drift_xy")]
    drift = drift / xr_heights(drift, heights)
    columns = {}
    for kind, var, along, unit, scale in (("PFA", accel, "floor", "g", 1 / PELICUN_G),
                                          ("PID", drift, "story", "rad", 1.0)):
        lead = [d for d in var.dims if d not in (along, "direction")]
        values = var.transpose(*lead, along, *(() if planar else ("direction",))).values
        values = values.reshape(int(np.prod([var.sizes[d] for d in lead], dtype=int)),
                                var.sizes[along], -1) * scale
        for i, location in enumerate(var[along].values):
            for j in range(values.shape[2]):
                columns[f"{PELICUN_EVENT}-{kind}-{int(location)}-{j + 1}"] = \
                    (unit, values[:, i, j])
    frame = pd.DataFrame({name: values for name, (_, values) in columns.items()})
    units = pd.DataFrame([{name: unit for name, (unit, _) in columns.items()}], index=["Units"])
    return pd.concat([units, frame.astype(object)])


def xr_heights(drift, heights: np.ndarray):
    """The story heights as a DataArray along `drift`'s story axis."""
    import xarray as xr

    return xr.DataArray(heights, dims="story", coords={"story": drift["story"].values})


def main(argv: list[str] | None = None) -> int:
    args = parser().parse_args(argv)
    from pipeline.errors import SweepError
    from pipeline.writing import Staged, check_out

    out = args.csv or args.pelicun
    try:
        if not out.lower().endswith(".csv"):
            raise ArchiveError(f"{out}: the output is a CSV file: give a name ending in .csv")
        target = check_out(out)
        ds = select(open_archive(args.archive), args.sel)
        if args.csv:
            table = runs_table(ds, None if args.block is None else [args.block])
        else:
            table = pelicun_sample(ds, args.block or "bumpers",
                                   story_heights(ds, args.story_height_m))
        with Staged() as stage:
            table.to_csv(stage.path(target), index=args.pelicun is not None)
            stage.commit()
    except (ArchiveError, SweepError) as err:
        print("error: " + " ".join(str(err).split()), file=sys.stderr)
        return 2
    rows = len(table) - (1 if args.pelicun else 0)
    print(f"wrote {target} ({rows} run{'' if rows == 1 else 's'}, {table.shape[1]} columns)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
