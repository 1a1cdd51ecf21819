"""The compiled loop of buildings that twist against the plan kernel and against a one-model
OpenSeesPy 3-D run of the same building.

    python benchmarks/bench_torsion.py [--repeats 3] [--no-opensees]

The paper's building on a 30 x 20 m slab, its mass 10% of b_x off centre, on four bearings at
the slab's corners (and on the default 4 x 4 grid, for scale), the bare linear wall at 20 cm
(every corner a contact point), a FEMA P695 pair (RSN953, Northridge, Beverly Hills -
Mulhol), 20 s at dt 0.5 ms, one thread: ns per member-step at B = 1 and B = 1024 in plan and
twisting, the twisting / plan cost ratio with four bearings (the issue's target: at most 3),
and OpenSeesPy's 3-D model (tests/reference/opensees_torsion.py: a rigid diaphragm, the four
bearings, the eccentric mass, gap elements at the corners) for one, whose ratio to the
kernel at B = 1 is the speed-up per core (target: at least 100). Medians of --repeats runs,
plan and twisting interleaved; a ratio is the median of the ratios of each round's runs.
Writes benchmarks/results/bench_torsion.json.
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
PLAN = (30.0, 20.0)
ECCENTRICITY = (0.1 * PLAN[0], 0.0)
CORNER_BEARINGS = ((-15.0, -10.0), (15.0, -10.0), (15.0, 10.0), (-15.0, 10.0))


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
    buildings = {
        "four": engine.Building(torsion=engine.Torsion(
            plan_size=PLAN, mass_offset=ECCENTRICITY, isolator_positions=CORNER_BEARINGS)),
        "grid": engine.Building(torsion=engine.Torsion(plan_size=PLAN,
                                                       mass_offset=ECCENTRICITY)),
    }

    def runner(building, moat="rectangular"):
        def run(size):
            engine.simulate(accel, acc_dt, engine.Contact.linear(np.full(size, GAP)), building,
                            dt=DT, moat=moat)
        return run

    runs = {"plan": runner(engine.Building()), "twisting, 4 bearings": runner(buildings["four"]),
            "twisting, 16 bearings": runner(buildings["grid"])}
    for run in runs.values():
        run(1)  # compile, or load from the cache
    row = {}
    for size, key in ((1, "b1"), (1024, "b1024")):
        # interleaved, round by round: a ratio of runs made side by side cancels most of the
        # machine's changing load
        times = {name: [] for name in runs}
        for _ in range(args.repeats):
            for name, run in runs.items():
                start = time.perf_counter()
                run(size)
                times[name].append(time.perf_counter() - start)
        for name, values in times.items():
            row[f"{_slug(name)}_ns_per_member_step_{key}"] = \
                statistics.median(values) / (size * steps) * 1e9
        for name in list(runs)[1:]:
            row[f"{_slug(name)}_over_plan_{key}"] = statistics.median(
                t / p for t, p in zip(times[name], times["plan"], strict=True))
    print(f"{PAIR}, {SECONDS:g} s at {DT * 1e3:g} ms ({steps} steps), linear walls at "
          f"{GAP * 100:g} cm, the paper's building on a {PLAN[0]:g} x {PLAN[1]:g} m slab, "
          f"mass offset {ECCENTRICITY[0]:g} m, one thread")
    print(f"{'':>22} {'B=1 ns/step':>12} {'B=1024 ns/member-step':>22} {'/ plan (B=1024)':>16}")
    for name in runs:
        s = _slug(name)
        ratio = row.get(f"{s}_over_plan_b1024")
        print(f"{name:>22} {row[f'{s}_ns_per_member_step_b1']:>12.1f} "
              f"{row[f'{s}_ns_per_member_step_b1024']:>22.1f} "
              f"{'' if ratio is None else f'{ratio:.2f}':>16}")
    if not args.no_opensees:
        from tests.reference.opensees_torsion import torsion_peaks

        seconds = median_time(lambda: torsion_peaks(
            accel, acc_dt, plan_size=PLAN, positions=np.array(CORNER_BEARINGS),
            eccentricity=ECCENTRICITY, gap=GAP, k=K_WALL, dt=DT), max(1, args.repeats // 2))
        kernel = row["twisting_4_bearings_ns_per_member_step_b1"] * steps * 1e-9
        batch = row["twisting_4_bearings_ns_per_member_step_b1024"] * steps * 1e-9
        row.update(opensees_seconds=seconds, ratio_b1=seconds / kernel,
                   ratio_b1024=seconds / batch)
        print(f"OpenSeesPy 3-D (4 bearings): {seconds:.2f} s for one model: the twisting "
              f"kernel is {row['ratio_b1']:.0f}x (B=1) and {row['ratio_b1024']:.0f}x (B=1024) "
              "per core")
    out = ROOT / "benchmarks" / "results" / "bench_torsion.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"pair": PAIR, "seconds": SECONDS, "dt": DT, **row}, indent=2))
    print("wrote", out)
    return 0


def _slug(name: str) -> str:
    return name.replace(", ", "_").replace(" ", "_")


if __name__ == "__main__":
    raise SystemExit(main())
