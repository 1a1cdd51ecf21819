"""The compiled loop's cost against the number of stories N, side by side with OpenSeesPy.

    python benchmarks/bench_stories.py [--repeats 3] [--stories 1 4 8 16 30]

Per N: a building of N stories (uniform: 400 t floors on a 500 t slab, stories of 900 MN/m,
the paper's bilinear isolator law scaled to the weight), the bare linear wall at 20 cm, Olive
View 090 (20 s at dt 0.5 ms); the engine on one thread for B = 1 and B = 1024 copies, OpenSeesPy
(tests/reference/opensees_reference.py) for one. Medians of --repeats runs; ns per member-step
and the ratio to OpenSeesPy's sim-steps/s. Writes benchmarks/results/bench_stories.json.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the tests package: tests.reference

from vs_opensees import median_time  # noqa: E402 - this folder is the script's path

DT = 5e-4
GAP = 0.20
SECONDS = 20.0


def building(n: int):
    import engine

    return engine.Building(masses=(500e3,) + (400e3,) * n, story_stiffness=(900e6,) * n)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--stories", type=int, nargs="+", default=[1, 4, 8, 16, 30])
    p.add_argument("--no-opensees", action="store_true", help="the engine alone")
    args = p.parse_args(argv)

    import numba

    import engine
    from pipeline.records import paper_record

    numba.set_num_threads(1)
    rec = paper_record("olive_view")
    accel = rec.accel[: int(SECONDS / rec.dt) + 1]
    steps = int(np.floor((len(accel) - 1) * rec.dt / DT + 1e-9)) + 1
    rows = []
    print(f"Olive View 090, {SECONDS:g} s at {DT * 1e3:g} ms ({steps} steps), linear wall at "
          f"{GAP * 100:g} cm, one thread")
    print(f"{'N':>3} {'B=1 ns/step':>12} {'B=1024 ns/member-step':>22} {'OpenSees s':>11} "
          f"{'x OpenSees B=1':>15} {'x B=1024':>9}")
    for n in args.stories:
        b = building(n)

        def run(size, b=b):
            engine.simulate(accel, rec.dt, engine.Contact.linear(np.full(size, GAP)),
                            building=b, dt=DT)

        run(1)  # compile (once per number of levels) or load from the cache
        one = median_time(lambda: run(1), args.repeats) / steps * 1e9
        many = median_time(lambda: run(1024), args.repeats) / (1024 * steps) * 1e9
        row = {"stories": n, "ns_per_step_b1": one, "ns_per_member_step_b1024": many}
        os_text = ratio_text = "-"
        if not args.no_opensees:
            from tests.reference.opensees_reference import opensees_peaks

            os_s = median_time(lambda b=b: opensees_peaks(
                accel, rec.dt, contact="elastic", gap=GAP, k=2.5e9, dt=DT, masses=b.masses,
                story_k=b.story_stiffness), max(1, args.repeats // 2))
            row.update(opensees_seconds=os_s, ratio_b1=os_s / (one * steps * 1e-9),
                       ratio_b1024=os_s / (many * steps * 1e-9))
            os_text = f"{os_s:.2f}"
            ratio_text = f"{row['ratio_b1']:.0f}"
        rows.append(row)
        print(f"{n:>3} {one:>12.1f} {many:>22.1f} {os_text:>11} {ratio_text:>15} "
              f"{row.get('ratio_b1024', float('nan')):>9.0f}")
    out = ROOT / "benchmarks" / "results" / "bench_stories.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"record": "olive_view", "seconds": SECONDS, "dt": DT,
                               "rows": rows}, indent=2))
    print("wrote", out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
