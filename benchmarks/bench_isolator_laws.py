"""What each isolator law costs per member-step, against the bilinear building, planar and in
plan.

    python benchmarks/bench_isolator_laws.py [--repeats 5] [--batch 256] [--steps 8000]

The paper's building on each law (the bilinear isolator; a friction pendulum, R 2.2 m, mu
0.05-0.10; a triple friction pendulum, L 0.3/2.0/2.0 m, d 0.05/0.3/0.3 m, mu 0.02/0.04/0.08),
no wall, B copies under a FEMA P695 pair (RSN953, its strong motion from 2.5 s; the planar
runs its x component) scaled from 0.5 to 1.5 across the batch (the bearings slide, the
triple friction pendulum's elements all in regime III or beyond), --steps steps of 0.5 ms,
the compiled loop on one thread. Each round runs every law once, planar then plan (the laws
interleaved: the shared machine's load falls on all alike); per law the median over
--repeats rounds, in ns per member-step, and the median of each round's ratio to the bilinear
building's. Writes benchmarks/results/bench_isolator_laws.json.
"""
from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DT = 5e-4
START = 2.5  # s of the record


def isolators() -> dict:
    """name -> engine.Isolator of each law benchmarked."""
    from engine import Isolator

    return {"bilinear": Isolator.bilinear(),
            "friction_pendulum": Isolator.friction_pendulum(radius=2.2, mu_slow=0.05,
                                                            mu_fast=0.10, rate=30.0),
            "triple_friction_pendulum": Isolator.triple_friction_pendulum(
                L1=0.3, L2=2.0, L3=2.0, d1=0.05, d2=0.3, d3=0.3, mu1=0.02, mu2=0.04,
                mu3=0.08)}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--batch", type=int, default=256)
    p.add_argument("--steps", type=int, default=8000)
    args = p.parse_args(argv)

    import numba

    import engine
    from pipeline.records import load_pair, pair_accel

    numba.set_num_threads(1)
    accel, acc_dt = pair_accel(*load_pair("RSN953"))
    first = int(round(START / acc_dt))
    accel = accel[first: first + int(np.ceil(args.steps * DT / acc_dt)) + 1]
    scale = np.linspace(0.5, 1.5, args.batch)
    contact = engine.Contact.none(args.batch)
    runs = {}
    for name, isolator in isolators().items():
        building = engine.Building(isolator=isolator)
        for model, record in (("planar", accel[:, 0]), ("plan", accel)):
            def run(record=record, building=building):
                return engine.simulate(record, acc_dt, contact, building, DT, scale=scale,
                                       backend="numba")
            runs[name, model] = run
            run()  # compiled (or loaded from the cache) before any timing
    times = {key: [] for key in runs}
    for _ in range(args.repeats):
        for key, run in runs.items():
            start = time.perf_counter()
            run()
            times[key].append(time.perf_counter() - start)
    steps = round((accel.shape[0] - 1) * acc_dt / DT)
    out = {"batch": args.batch, "steps": steps, "repeats": args.repeats, "laws": {}}
    print(f"B = {args.batch}, {steps} steps of {DT * 1e3:g} ms, medians of {args.repeats}")
    for name in isolators():
        for model in ("planar", "plan"):
            ns = [t / (args.batch * steps) * 1e9 for t in times[name, model]]
            ratio = statistics.median(t / b for t, b in zip(times[name, model],
                                                            times["bilinear", model],
                                                            strict=True))
            out["laws"][f"{name}/{model}"] = {"ns_per_member_step": statistics.median(ns),
                                              "x_bilinear": ratio}
            print(f"{name:26s} {model:6s} {statistics.median(ns):7.1f} ns per member-step"
                  f"  {ratio:5.2f} x the bilinear building")
    target = ROOT / "benchmarks" / "results" / "bench_isolator_laws.json"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
