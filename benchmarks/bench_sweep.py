"""Throughput of `pipeline.sweep`: simulations per second against batch size and workers.

    python benchmarks/bench_sweep.py [--seconds 20] [--members 64] [--workers 0 2]

A synthetic record (a 1.5 s sine under a sin^2 envelope, 0.5 g) at the engine's default dt,
bumpers on a gap grid; each configuration runs once. The engine's time step has a fixed cost
of some tens of microseconds plus a small cost per member, so large batches win until the
workers run out of batches.
"""
from __future__ import annotations

import argparse
import time

import numpy as np


def main(argv=None) -> None:
    import pipeline
    from pipeline.records import Record

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seconds", type=float, default=20.0, help="record length, s")
    p.add_argument("--members", type=int, default=64, help="grid members per record")
    p.add_argument("--records", type=int, default=2, help="number of records")
    p.add_argument("--workers", type=int, nargs="+", default=[0, 2])
    p.add_argument("--batch-sizes", type=int, nargs="+", default=[1, 16, 512])
    args = p.parse_args(argv)

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
