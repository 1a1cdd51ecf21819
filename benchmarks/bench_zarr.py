"""A 10^6-member sweep into a Zarr store on local dask workers: wall time and client memory.

    python benchmarks/bench_zarr.py [--members-per-dim 100] [--seconds 2] [--workers 2]

The grid is gap x thickness x strain (100 x 100 x 100 = 10^6 bumper configurations by
default) under `--seconds` s of Pacoima Dam 164 from 1 s before its PGA, at the engine's
step. Workers write their batches into the store; the client keeps only the member table and
the batch list, so its peak memory (ru_maxrss of this process) stays far below the results'
size. Prints a table and writes benchmarks/results/zarr.json. Not a test: it takes minutes.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import resource
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).resolve().parent / "results"


def main(argv=None) -> int:
    import pipeline
    from pipeline.records import load_record

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--members-per-dim", type=int, default=100,
                   help="values of each of gap, thickness, strain (default 100: 10^6)")
    p.add_argument("--seconds", type=float, default=2.0, help="record length, s")
    p.add_argument("--workers", type=int, default=2, help="local dask worker processes")
    p.add_argument("--keep", metavar="PATH", help="write the store here and keep it")
    args = p.parse_args(argv)

    n = args.members_per_dim
    full = load_record("pacoima")
    # The strong-motion window: from 1 s before the PGA, so that members pound and differ.
    first = max(int(np.argmax(np.abs(full.accel))) - int(1.0 / full.dt), 0)
    record = dataclasses.replace(full, name="Pacoima-164-window",
                                 accel=full.accel[first:first + int(args.seconds / full.dt)])
    grid = dict(gap=np.round(np.linspace(0.10, 0.30, n), 6).tolist(),
                thickness=np.round(np.linspace(0.02, 0.08, n), 6).tolist(),
                strain=np.round(np.linspace(0.5, 1.0, n), 6).tolist())
    folder = Path(tempfile.mkdtemp(prefix="bench_zarr_"))
    store = Path(args.keep) if args.keep else folder / "sweep.zarr"
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    start = time.perf_counter()
    ds = pipeline.sweep([record], workers=args.workers, out=store, **grid)
    wall = time.perf_counter() - start
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    members = n ** 3
    check = float(ds.peak_isolator_disp.isel(record=0, gap=0, thickness=0, strain=0))
    size_mb = sum(f.stat().st_size for f in store.rglob("*") if f.is_file()) / 2 ** 20
    row = {"members": members, "record_seconds": args.seconds, "workers": args.workers,
           "wall_s": wall, "simulations_per_s": members / wall,
           "client_peak_rss_mb": peak_mb, "client_rss_before_mb": base / 1024,
           "store_mb": size_mb, "first_peak_isolator_disp_m": check}
    print(f"{'members':>9} {'record s':>8} {'workers':>7} {'wall s':>8} {'sims/s':>9} "
          f"{'client peak MB':>14} {'store MB':>8}")
    print(f"{members:9d} {args.seconds:8g} {args.workers:7d} {wall:8.1f} "
          f"{members / wall:9.0f} {peak_mb:14.0f} {size_mb:8.2f}")
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "zarr.json").write_text(json.dumps(row, indent=2))
    print("wrote", RESULTS / "zarr.json", file=sys.stderr)
    if not args.keep:
        shutil.rmtree(folder, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
