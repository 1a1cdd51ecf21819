"""Writing a 10^6-member sweep's NetCDF archive: its large variables compressed on every core
(pipeline.parallel_deflate) against netCDF4 compressing them in one thread, in one run.

    python benchmarks/bench_archive.py [--members 1000000] [--repeats 3]

The archive of a sweep of `--members` members (one record, gap x wall stiffness): the peaks a
sweep keeps (five floors' accelerations and velocities, four stories' drifts, shears and
residual drifts, nine scalars), smooth in the swept parameters with noise in their last bits,
as a simulation's are (zlib takes them to about 70%, as a 10^6-member sweep of Kobe). Each
writer writes it --repeats times through pipeline.archive.to_netcdf, alternating; medians,
the file's size, the cores; writes benchmarks/results/bench_archive.json.
"""
from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

from pipeline import archive, parallel_deflate

SHAPES = {"peak_total_accel": 5, "peak_floor_velocity": 5, "peak_interstory_drift": 4,
          "peak_story_shear": 4, "residual_interstory_drift": 4}
SCALARS = ("peak_isolator_disp", "max_indentation", "max_impact_force", "impact_energy",
           "peak_isolator_force", "residual_isolator_disp")


def sweep_like(members: int, seed: int = 0) -> xr.Dataset:
    """A sweep archive's variables over (record, gap, wall_k[, floor or story])."""
    rng = np.random.default_rng(seed)
    side = int(round(np.sqrt(members)))
    gap, wall_k = np.linspace(0.05, 0.5, side), np.geomspace(1e9, 1e10, side)
    smooth = (1.0 / gap[:, None]) * np.log(wall_k)[None, :]

    def values(*extra):
        base = smooth.reshape(1, side, side, *([1] * len(extra)))
        return base * (1 + 1e-3 * rng.standard_normal((1, side, side, *extra)))

    data = {name: (("record", "gap", "wall_k", "floor" if n == 5 else "story"),
                   values(n), {"units": "1"}) for name, n in SHAPES.items()}
    data.update({name: (("record", "gap", "wall_k"), values(), {"units": "1"})
                 for name in SCALARS})
    data["n_impacts"] = (("record", "gap", "wall_k"),
                         rng.integers(0, 30, (1, side, side)), {"units": "1"})
    data["invalid_floor_accel"] = (("record", "gap", "wall_k"),
                                   np.zeros((1, side, side), np.int8), {"units": "1"})
    return xr.Dataset(data, coords={"gap": ("gap", gap, {"units": "m"}),
                                    "wall_k": ("wall_k", wall_k, {"units": "N m-1"})})


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--members", type=int, default=10**6, help="the sweep's members")
    p.add_argument("--repeats", type=int, default=3, help="writes of each writer")
    args = p.parse_args(argv)
    ds = sweep_like(args.members)
    serial_bytes = 1 << 62  # no variable is this large: netCDF4 writes every one
    times = {"parallel": [], "serial": []}
    sizes = {}
    with tempfile.TemporaryDirectory() as folder:
        for i in range(args.repeats):
            for name, threshold in (("parallel", parallel_deflate.PARALLEL_BYTES),
                                    ("serial", serial_bytes)):
                parallel_deflate.PARALLEL_BYTES, kept = threshold, parallel_deflate.PARALLEL_BYTES
                path = Path(folder) / f"{name}{i}.nc"
                start = time.perf_counter()
                archive.to_netcdf(ds, path)
                times[name].append(time.perf_counter() - start)
                parallel_deflate.PARALLEL_BYTES = kept
                sizes[name] = path.stat().st_size
    median = {name: statistics.median(t) for name, t in times.items()}
    cores = parallel_deflate._cores()
    print(f"{args.members} members, {ds.nbytes / 1e6:.0f} MB of variables, {cores} cores, "
          f"medians of {args.repeats}:")
    print(f"{'writer':>10} {'s':>7} {'MB':>7}")
    for name in times:
        print(f"{name:>10} {median[name]:7.2f} {sizes[name] / 1e6:7.1f}")
    print(f"parallel / serial: {median['parallel'] / median['serial']:.2f}")
    out = {"members": args.members, "variables_bytes": int(ds.nbytes), "cores": cores,
           "repeats": args.repeats, "seconds": times, "median_s": median,
           "archive_bytes": sizes}
    target = Path(__file__).resolve().parent / "results" / "bench_archive.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(out, indent=2))
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
