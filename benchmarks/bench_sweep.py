"""Throughput of `pipeline.sweep`: simulations per second against batch size and workers;
and the host's share of a sweep of a million members.

    python benchmarks/bench_sweep.py [--seconds 20] [--members 64] [--workers 0 2]
    python benchmarks/bench_sweep.py --million [--repeats 3] [--batch-size 1000000]

A synthetic record (a 1.5 s sine under a sin^2 envelope, 0.5 g) at the engine's default dt,
bumpers on a gap grid; each configuration runs once. The engine's time step has a fixed cost
of some tens of microseconds plus a small cost per member, so large batches win until the
workers run out of batches.

--million: 1000 x 1000 members (gap x wall stiffness, the linear wall) under 0.05 s of record
(100 steps), written to a NetCDF archive through its work folder, in this process: what the
sweep costs besides its kernel (the members, contacts, checks, work files, the archive), the
kernel's part printed beside (the engine's own timing of its batches). Medians of --repeats
runs; writes benchmarks/results/bench_sweep_million.json. --batch-size 1000000: the members in
one engine call, as on a GPU (the sweep's default batches are a CPU's).
"""
from __future__ import annotations

import argparse
import time

import numpy as np


def million(repeats: int, batch_size: int | None = None) -> None:
    """The --million benchmark (module docstring)."""
    import json
    import statistics
    import tempfile
    from pathlib import Path

    import pipeline
    from pipeline.execute import batches
    from pipeline.records import Record

    t = np.arange(0.0, 0.05, 0.005)
    record = Record(name="short", rsn=None, event="synthetic", station="", component="",
                    dt=0.005, accel=4.0 * np.sin(2 * np.pi * t / 0.5), source="benchmark")
    kernel, real = [], batches.simulate_batch

    def timed(*args, **kwargs):
        start = time.perf_counter()
        out = real(*args, **kwargs)
        kernel[-1] += time.perf_counter() - start
        return out

    batches.simulate_batch = timed
    walls = []
    with tempfile.TemporaryDirectory() as folder:
        for i in range(repeats + 1):  # the first compiles (or loads) the kernel
            kernel.append(0.0)
            start = time.perf_counter()
            pipeline.sweep([record], gap=list(np.linspace(0.05, 0.50, 1000)),
                           wall_k=list(np.geomspace(1e9, 1e10, 1000)), impact="linear",
                           dt=5e-4, out=Path(folder) / f"s{i}.nc", quiet=True,
                           batch_size=batch_size)
            walls.append(time.perf_counter() - start)
    batches.simulate_batch = real
    wall, engine_s = statistics.median(walls[1:]), statistics.median(kernel[1:])
    out = {"members": 10**6, "steps": 100, "repeats": repeats, "batch_size": batch_size,
           "wall_s": wall,
           "engine_s": engine_s, "host_s": wall - engine_s}
    print(f"10^6 members x 100 steps: {wall:.2f} s end to end, {engine_s:.2f} s in the "
          f"engine's batches, {wall - engine_s:.2f} s the rest (medians of {repeats})")
    target = Path(__file__).resolve().parent / "results" / "bench_sweep_million.json"
    target.parent.mkdir(parents=True, exist_ok=True)  # git-ignored: absent from a clone
    target.write_text(json.dumps(out, indent=2))


def main(argv=None) -> None:
    import pipeline
    from pipeline.records import Record

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--million", action="store_true",
                   help="the host's share of a 10^6-member sweep (module docstring)")
    p.add_argument("--repeats", type=int, default=3, help="--million: runs timed")
    p.add_argument("--batch-size", type=int, default=None,
                   help="--million: members an engine call (default: the sweep's)")
    p.add_argument("--seconds", type=float, default=20.0, help="record length, s")
    p.add_argument("--members", type=int, default=64, help="grid members per record")
    p.add_argument("--records", type=int, default=2, help="number of records")
    p.add_argument("--workers", type=int, nargs="+", default=[0, 2])
    p.add_argument("--batch-sizes", type=int, nargs="+", default=[1, 16, 512])
    args = p.parse_args(argv)
    if args.million:
        million(args.repeats, args.batch_size)
        return

    dt = 0.01
    t = np.arange(0.0, args.seconds, dt)
    records = [Record(name=f"synthetic-{i}", rsn=None, event="synthetic", station="",
                      component="", dt=dt, source="benchmark",
                      accel=4.9 * np.sin(np.pi * t / t[-1]) ** 2
                      * np.sin(2 * np.pi * t / 1.5 + i))
               for i in range(args.records)]
    gaps = np.linspace(0.06, 0.30, args.members)
    total = args.records * args.members
    print(f"{total} simulations of {args.seconds:g} s each")
    for workers in args.workers:
        for batch_size in args.batch_sizes:
            if batch_size < 4 and args.members > 16:
                continue  # hours, and says nothing new
            start = time.perf_counter()
            pipeline.sweep(records, gap=gaps, workers=workers, batch_size=batch_size,
                           quiet=True)
            wall = time.perf_counter() - start
            print(f"workers {workers}  batch {batch_size:4d}: {wall:7.2f} s, "
                  f"{total / wall:7.1f} simulations/s")


if __name__ == "__main__":
    main()
