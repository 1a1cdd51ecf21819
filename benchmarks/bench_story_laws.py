"""What yielding and deteriorating stories with P-Delta cost per member-step, against the
linear building, side by side with OpenSeesPy's leaning-column model in one run.

    python benchmarks/bench_story_laws.py [--repeats 3] [--stories 4 8] [--scales 1 1.5]
                                          [--no-opensees]

Per N: a building of N stories (500 t slab, 400 t floors, stories of 900 MN/m, 3.5 m high,
the paper's isolator law scaled to the weight), the bare linear wall at 20 cm, Olive View 090
(20 s at dt 0.5 ms), the compiled loop on one thread, B = 1024 copies: linear stories (the
paper's model), bilinear stories with P-Delta and the collapse check, IMK stories with P-Delta
and the collapse check; the stories' strengths those the code would design
(pipeline.motions.superstructure) at the default site: at the record's scale 1 they stay
elastic, at 1.5 they yield and deteriorate without collapsing (at 2 the 8-story building
collapses, and a collapsed member costs nothing more: --scales). OpenSeesPy
(tests/reference/opensees_pdelta.py: Steel01 stories, a PDelta leaning column) for one member
of the bilinear model at scale 1. Medians of --repeats runs; ns per member-step, the ratio to
the linear building (the budget: at most 1.5) and to OpenSeesPy.
Writes benchmarks/results/bench_story_laws.json.
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
BATCH = 1024
HEIGHT = 3.5


def buildings(n: int) -> dict:
    """name -> engine.Building: linear, and the code-designed bilinear and IMK ones."""
    import engine
    from pipeline.motions.superstructure import code_designed_building
    from pipeline.motions.target import isolation_design

    base = engine.Building(masses=(500e3,) + (400e3,) * n, story_stiffness=(900e6,) * n,
                           story_height=(HEIGHT,) * n)
    design = isolation_design(0.9, base)
    return {"linear": base,
            **{f"{law}+P-Delta": code_designed_building(design, base, story_law=law).building
               for law in ("bilinear", "imk")}}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--stories", type=int, nargs="+", default=[4, 8])
    p.add_argument("--scales", type=float, nargs="+", default=[1.0, 1.5],
                   help="record scales: 1 keeps the stories elastic, 1.5 yields them")
    p.add_argument("--no-opensees", action="store_true", help="the engine alone")
    args = p.parse_args(argv)

    import numba

    import engine
    from pipeline.records import paper_record

    numba.set_num_threads(1)
    rec = paper_record("olive_view")
    accel = rec.accel[: int(SECONDS / rec.dt) + 1]
    steps = int(np.floor((len(accel) - 1) * rec.dt / DT + 1e-9)) + 1
    contact = engine.Contact.linear(np.full(BATCH, GAP))
    rows = []
    print(f"Olive View 090, {SECONDS:g} s at {DT * 1e3:g} ms ({steps} steps), linear wall at "
          f"{GAP * 100:g} cm, one thread, B = {BATCH}")
    print(f"{'N':>3} {'scale':>5} {'stories':>18} {'ns/member-step':>15} {'x linear':>9} "
          f"{'yielded':>8} {'collapsed':>10} {'x OpenSees':>11}")
    for n, scale in ((n, scale) for n in args.stories for scale in args.scales):
        linear_ns = None
        for name, b in buildings(n).items():
            def run(b=b, scale=scale):
                return engine.simulate(accel, rec.dt, contact, building=b, dt=DT, scale=scale)

            result = run()  # compile (once per number of levels) or load from the cache
            ns = median_time(run, args.repeats) / (BATCH * steps) * 1e9
            linear_ns = ns if linear_ns is None else linear_ns
            law = b.story_law
            yielded = bool(np.any(result.peak_interstory_drift[0]
                                  > np.asarray(b.story_yield_drift))) \
                if not law.is_linear else False
            row = {"stories": n, "scale": scale, "model": name, "ns_per_member_step": ns,
                   "ratio_to_linear": ns / linear_ns, "yielded": yielded,
                   "collapsed": int(result.collapsed.sum())}
            os_text = "-"
            if name == "bilinear+P-Delta" and not args.no_opensees and scale == 1.0:
                from tests.reference.opensees_pdelta import opensees_pdelta_peaks

                yields = law.values["yield_force"]
                os_s = median_time(lambda b=b, yields=yields: opensees_pdelta_peaks(
                    accel, rec.dt, masses=b.masses, story_k=b.story_stiffness,
                    story_yield=yields, story_height=b.story_height, p_delta=True,
                    contact="elastic", gap=GAP, k=2.5e9, dt=DT), 1)
                row.update(opensees_seconds=os_s, ratio_opensees=os_s / (ns * steps * 1e-9))
                os_text = f"{row['ratio_opensees']:.0f}"
            rows.append(row)
            print(f"{n:>3} {scale:>5g} {name:>18} {ns:>15.1f} {ns / linear_ns:>9.2f} "
                  f"{str(yielded):>8} {row['collapsed']:>10} {os_text:>11}")
    out = ROOT / "benchmarks" / "results" / "bench_story_laws.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps({"record": "olive_view", "seconds": SECONDS, "dt": DT,
                               "batch": BATCH, "rows": rows}, indent=2))
    print("wrote", out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
