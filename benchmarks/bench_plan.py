"""The compiled loop in plan against the planar one and against a one-model OpenSeesPy 3D run.

    python benchmarks/bench_plan.py [--repeats 3] [--no-opensees]

The paper's building, the bare linear wall at 20 cm (a square moat in plan), a FEMA P695 pair
(RSN953, Northridge, Beverly Hills - Mulhol; the planar runs its x component), 20 s at dt
0.5 ms, one thread: ns per member-step at B = 1 and B = 1024, planar and in plan, the plan /
planar cost ratio (the issue's target: at most 2.5), and OpenSeesPy's 3D model of the same
building (tests/reference/opensees_plan.py) for one, whose ratio to the kernel at B = 1 is the
speed-up per core (target: at least 100). Medians of --repeats runs, planar and plan
interleaved; the plan / planar ratio is the median of the ratios of each round's pair of runs.
Writes benchmarks/results/bench_plan.json.
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the tests package: tests.reference

from vs_opensees import median_time  # noqa: E402 - this folder is the script's path

DT = 5e-4
GAP = 0.20
K_WALL = 2.5e9
SECONDS = 20.0
PAIR = "RSN953"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--no-opensees", action="store_true", help="the engine alone")
    args = p.parse_args(argv)

    import numba

    import engine
    from pipeline.records import load_pair, pair_accel

    numba.set_num_threads(1)
    accel, acc_dt = pair_accel(*load_pair(PAIR))
    accel = accel[: int(SECONDS / acc_dt) + 1]
    steps = int(np.floor((len(accel) - 1) * acc_dt / DT + 1e-9)) + 1

    def planar(size):
        engine.simulate(accel[:, 0], acc_dt, engine.Contact.linear(np.full(size, GAP)), dt=DT)

    def plan(size):
        engine.simulate(accel, acc_dt, engine.Contact.linear(np.full(size, GAP)), dt=DT,
                        moat="rectangular")

    planar(1), plan(1)  # compile, or load from the cache
    row = {}
    for size, key in ((1, "b1"), (1024, "b1024")):
        # planar and plan interleaved, round by round: the machine's load changes between
        # rounds, and a ratio of two runs made side by side cancels most of it
        times = {"planar": [], "plan": []}
        for _ in range(args.repeats):
            for name, run in (("planar", planar), ("plan", plan)):
                start = time.perf_counter()
                run(size)
                times[name].append(time.perf_counter() - start)
        for name in times:
            unit = "ns_per_step" if size == 1 else "ns_per_member_step"
            row[f"{name}_{unit}_{key}"] = statistics.median(times[name]) / (size * steps) * 1e9
        row[f"plan_over_planar_{key}"] = statistics.median(
            p / q for p, q in zip(times["plan"], times["planar"], strict=True))
    print(f"{PAIR}, {SECONDS:g} s at {DT * 1e3:g} ms ({steps} steps), linear walls at "
          f"{GAP * 100:g} cm, the paper's building, one thread")
    print(f"{'':>8} {'B=1 ns/step':>12} {'B=1024 ns/member-step':>22}")
    for name in ("planar", "plan"):
        print(f"{name:>8} {row[f'{name}_ns_per_step_b1']:>12.1f} "
              f"{row[f'{name}_ns_per_member_step_b1024']:>22.1f}")
    print(f"plan / planar: {row['plan_over_planar_b1']:.2f} (B=1), "
          f"{row['plan_over_planar_b1024']:.2f} (B=1024)")
    if not args.no_opensees:
        from tests.reference.opensees_plan import plan_peaks

        seconds = median_time(lambda: plan_peaks(accel, acc_dt, gap=GAP, k=K_WALL, dt=DT),
                              max(1, args.repeats // 2))
        row.update(opensees_seconds=seconds,
                   ratio_b1=seconds / (row["plan_ns_per_step_b1"] * steps * 1e-9),
                   ratio_b1024=seconds / (row["plan_ns_per_member_step_b1024"] * steps * 1e-9))
        print(f"OpenSeesPy 3D: {seconds:.2f} s for one model: the plan kernel is "
              f"{row['ratio_b1']:.0f}x (B=1) and {row['ratio_b1024']:.0f}x (B=1024) per core")
    out = ROOT / "benchmarks" / "results" / "bench_plan.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"pair": PAIR, "seconds": SECONDS, "dt": DT, **row}, indent=2))
    print("wrote", out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
