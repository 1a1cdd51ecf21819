"""The engine against OpenSeesPy, side by side in one run: same building, record, dt and cores.

    python benchmarks/vs_opensees.py [--repeats 3] [--max-batch 16384] [--quick]

Model: the paper's building (tests/reference/opensees_reference.py builds it in OpenSees) with
a moat wall at a 25 cm gap: --contact elastic (default; OpenSees ElasticPPGap, engine linear
law with COR 1, k 2.5e9 N/m) or jankowski (beta 2.75e10 N/m^1.5, COR 0.5; OpenSees'
JankowskiImpact is slower: it prints every impact and returns a tangent of the wrong sign),
under Sylmar Converter 142 (pipeline.records.paper_record), dt 0.5 ms. OpenSeesPy: one model,
one `analyze` call over the record (Newmark, Newton). Engine: `engine.simulate` on B copies of
the same member, the whole call (set-up included). Medians of --repeats runs. Per core: the
process is pinned to one core and numba runs one thread. Tables:
1. sim-steps/s (members x steps per second) and the ratio to OpenSeesPy, numba and numpy
   backends, B = 1 ... 4096; peaks of both against OpenSees' (step-by-step reference run);
2. the ratio at equal accuracy: each side at the largest dt whose peaks stay within 1% of a
   dt-converged engine run (dt / 16);
3. batch scaling B = 1 ... 16384 with peak memory (tracemalloc), and memory against the
   number of steps.
Writes benchmarks/results/vs_opensees.json with the machine.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the tests package: tests.reference

GAP, BETA, COR, K_WALL = 0.25, 2.75e10, 0.5, 2.5e9
CONTACT = {"name": "elastic"}
DT = 5e-4
PEAKS = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp", "max_indentation",
         "max_impact_force")


def machine() -> dict:
    import numba

    cpu = platform.processor()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    import openseespy

    return {"cpu": cpu, "logical_cores": os.cpu_count(),
            "affinity": sorted(os.sched_getaffinity(0)), "python": platform.python_version(),
            "numpy": np.__version__, "numba": numba.__version__,
            "openseespy": getattr(openseespy, "__version__", "?"),
            "platform": platform.platform()}


def median_time(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def opensees_time(accel, accel_dt, dt) -> tuple[float, int]:
    """Seconds for one model build and one analyze call over the record, and its steps."""
    import openseespy.opensees as ops

    from tests.reference.opensees_reference import build_model

    n_steps = int(np.floor((len(accel) - 1) * accel_dt / dt + 1e-9))
    start = time.perf_counter()
    build_model(accel, accel_dt, CONTACT["name"], GAP, K_WALL, BETA, COR, 320e3)
    status = ops.analyze(n_steps, dt)
    elapsed = time.perf_counter() - start
    ops.wipe()
    if status != 0:
        raise RuntimeError(f"OpenSees analyze failed at dt {dt}")
    return elapsed, n_steps


def engine_run(accel, accel_dt, size, dt, backend):
    import engine

    return engine.simulate(accel, accel_dt, wall(size), dt=dt, backend=backend)


def wall(size):
    import engine

    if CONTACT["name"] == "elastic":
        return engine.Contact.linear(np.full(size, GAP), k=K_WALL, cor=1.0)
    return engine.Contact.jankowski(np.full(size, GAP), beta=BETA, cor=COR)


def opensees_reference(accel, accel_dt, dt) -> dict:
    """OpenSees' peaks, from the step-by-step reference run of
    tests/reference/opensees_reference.py."""
    from tests.reference.opensees_reference import opensees_peaks

    if CONTACT["name"] == "elastic":
        return opensees_peaks(accel, accel_dt, contact="elastic", gap=GAP, k=K_WALL, dt=dt)
    return opensees_peaks(accel, accel_dt, contact="jankowski", gap=GAP, beta=BETA, cor=COR,
                          dt=dt)


def worst_deviation(peaks: dict, reference: dict) -> float:
    return max(float(np.max(np.abs(np.asarray(peaks[n]) / np.asarray(reference[n]) - 1)))
               for n in PEAKS)


def member_peaks(result, i=0) -> dict:
    return {n: getattr(result, n)[i] for n in PEAKS}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--max-batch", type=int, default=16384)
    p.add_argument("--quick", action="store_true", help="fewer batch sizes, 1 repeat")
    p.add_argument("--core", type=int, default=0, help="the core to pin to")
    p.add_argument("--contact", choices=("elastic", "jankowski"), default="elastic")
    args = p.parse_args(argv)
    repeats = 1 if args.quick else args.repeats
    CONTACT["name"] = args.contact

    os.sched_setaffinity(0, {args.core})
    import numba

    numba.set_num_threads(1)
    import engine
    from pipeline.records import paper_record

    record = paper_record("sylmar_converter")
    accel, accel_dt = np.asarray(record.accel, dtype=float), record.dt
    engine_run(accel[:100], accel_dt, 2, DT, "numba")  # compile or load the kernel
    engine_run(accel[:100], accel_dt, 1, DT, "numba")
    out = {"machine": machine(), "record": record.name, "dt": DT,
           "model": f"paper building, {args.contact} wall at gap {GAP} m", "repeats": repeats}

    # 1. Throughput, side by side.
    os_time = median_time(lambda: opensees_time(accel, accel_dt, DT), repeats)
    _, os_steps = opensees_time(accel, accel_dt, DT)
    os_rate = os_steps / os_time
    n_steps = engine.scheme.checked_record(accel, accel_dt, DT)[1]
    sizes = [1, 16, 256, 1024, 4096] if not args.quick else [1, 1024]
    rows = []
    print(f"{args.contact} wall; Sylmar Converter, {n_steps} steps of {DT * 1e3:g} ms, one core "
          f"({out['machine']['cpu']})")
    print(f"OpenSeesPy: {os_time:.3f} s per run, {os_rate:.3g} sim-steps/s\n")
    print(f"{'B':>6} {'backend':>8} {'s/run':>9} {'sim-steps/s':>12} {'x OpenSees':>11}")
    for size in sizes:
        for backend in ("numba", "numpy"):
            if backend == "numpy" and size > 1024:
                continue
            # NumPy's cost per step does not depend on the record: time a 5 s slice of it.
            part = accel if backend == "numba" else accel[: int(5.0 / accel_dt) + 1]
            steps = engine.scheme.checked_record(part, accel_dt, DT)[1]
            seconds = median_time(lambda p=part, s=size, b=backend:
                                  engine_run(p, accel_dt, s, DT, b), repeats)
            rate = size * steps / seconds
            rows.append({"B": size, "backend": backend, "seconds": seconds, "steps": steps,
                         "sim_steps_per_s": rate, "ratio": rate / os_rate})
            print(f"{size:>6} {backend:>8} {seconds:>9.4f} {rate:>12.3g} {rate / os_rate:>11.1f}")
    out["opensees"] = {"seconds": os_time, "steps": os_steps, "sim_steps_per_s": os_rate}
    out["throughput"] = rows

    from tests.reference.opensees_reference import AGREEMENT

    reference = opensees_reference(accel, accel_dt, DT)
    tolerance = AGREEMENT[CONTACT["name"]]  # what tests/engine/test_simulate_opensees.py asserts
    agreement = {}
    for backend in ("numba", "numpy"):
        res = engine_run(accel, accel_dt, 1, DT, backend)
        agreement[backend] = worst_deviation(member_peaks(res), reference)
        assert res.n_impacts[0] == reference["n_impacts"]
    print(f"\npeaks vs OpenSees (worst relative deviation): numba {agreement['numba']:.2%}, "
          f"numpy {agreement['numpy']:.2%} (tolerance {tolerance:.1%}); "
          f"impacts {reference['n_impacts']} on both")
    out["peak_agreement"] = {**agreement, "tolerance": tolerance,
                             "n_impacts": reference["n_impacts"]}

    # 2. Equal accuracy: the largest dt within 1% of a converged engine run.
    converged = member_peaks(engine_run(accel, accel_dt, 1, DT / 16, "numba"))
    candidates = [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4]
    limit = engine.stable_dt(wall(1))[0]
    accuracy = {}
    for side in ("engine", "opensees"):
        for dt in candidates:
            if side == "engine":
                if dt >= limit:
                    continue
                peaks = member_peaks(engine_run(accel, accel_dt, 1, dt, "numba"))
            else:
                try:
                    peaks = opensees_reference(accel, accel_dt, dt)
                except RuntimeError:
                    continue
            deviation = worst_deviation(peaks, converged)
            if deviation <= 0.01:
                accuracy[side] = {"dt": dt, "deviation": deviation}
                break
    if len(accuracy) == 2:
        dt_e, dt_o = accuracy["engine"]["dt"], accuracy["opensees"]["dt"]
        t_e = median_time(lambda: engine_run(accel, accel_dt, 1, dt_e, "numba"), repeats)
        t_o = median_time(lambda: opensees_time(accel, accel_dt, dt_o), repeats)
        accuracy["ratio_B1"] = t_o / t_e
        big = 1024
        t_big = median_time(lambda: engine_run(accel, accel_dt, big, dt_e, "numba"), 1)
        accuracy["ratio_B1024"] = t_o * big / t_big
        print(f"\nequal accuracy (peaks within 1% of dt {DT / 16:g} s): engine dt {dt_e:g} s "
              f"({accuracy['engine']['deviation']:.2%}), OpenSees dt {dt_o:g} s "
              f"({accuracy['opensees']['deviation']:.2%}): {t_e:.4f} s vs {t_o:.3f} s per "
              f"simulation, {accuracy['ratio_B1']:.0f}x at B = 1, "
              f"{accuracy['ratio_B1024']:.0f}x at B = {big}")
    else:
        print(f"\nequal accuracy: no dt within 1% found for {sorted(set(accuracy))}")
    out["equal_accuracy"] = accuracy

    # 3. Batch scaling and memory.
    print(f"\n{'B':>6} {'s/run':>9} {'sim-steps/s':>12} {'x OpenSees':>11} {'peak MB':>9} "
          f"{'KB/member':>10}")
    scaling = []
    size = 1
    scale_sizes = [1, 16, 256, 1024, 4096, 16384] if not args.quick else [1, 256, 4096]
    for size in [s for s in scale_sizes if s <= args.max_batch]:
        tracemalloc.start()
        start = time.perf_counter()
        engine_run(accel, accel_dt, size, DT, "numba")
        seconds = time.perf_counter() - start
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        rate = size * n_steps / seconds
        scaling.append({"B": size, "seconds": seconds, "sim_steps_per_s": rate,
                        "ratio": rate / os_rate, "peak_bytes": peak})
        print(f"{size:>6} {seconds:>9.3f} {rate:>12.3g} {rate / os_rate:>11.1f} "
              f"{peak / 1e6:>9.2f} {peak / size / 1e3:>10.2f}")
    memory_vs_steps = []
    for fraction in (0.25, 1.0):
        part = accel[: int(fraction * (accel.size - 1)) + 1]
        tracemalloc.start()
        engine_run(part, accel_dt, 256, DT, "numba")
        memory_vs_steps.append({"fraction_of_record": fraction,
                                "peak_bytes": tracemalloc.get_traced_memory()[1]})
        tracemalloc.stop()
    print("memory at B = 256 for 1/4 and all of the record: "
          + ", ".join(f"{m['peak_bytes'] / 1e6:.2f} MB" for m in memory_vs_steps)
          + " (the (N,) ground motion is the only array that grows with the steps)")
    out["scaling"] = scaling
    out["memory_vs_steps"] = memory_vs_steps

    results = ROOT / "benchmarks" / "results"
    results.mkdir(exist_ok=True)
    (results / "vs_opensees.json").write_text(json.dumps(out, indent=2))
    ok = all(r["ratio"] >= 200 for r in rows
             if r["backend"] == "numba" and (r["B"] == 1 or r["B"] >= 1024))
    print(f"\n>= 200x per core at B = 1 and B >= 1024: {'met' if ok else 'NOT met'}; "
          f"written {results / 'vs_opensees.json'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
