"""The device loop's member-steps per second against the batch size, paired with the compiled CPU
kernel in the same run, and a sweep of 10^6 members of a 20 s record end to end.

    python benchmarks/bench_gpu.py [--exponents 10 12 ... 22] [--quick]

The paper's building on its bilinear isolators, every impact law in turn along the batch
(linear, Jankowski, Hertzdamp, bumper, none), under the first 20 s of the Kobe record at dt
0.5 ms (40,000 steps); planar, and in plan under a synthetic pair (Kobe along x, a copy delayed
by 1.7 s along y) in a square moat. For each B = 2^k the device runs the record's first half and
then the whole of it: the extra half's member-steps over its extra time are the device's
throughput (the kernel's, without the per-call work on the host: packing, copies, the
stability limit), and B x steps / time of the whole record its throughput end to end. The CPU
kernel (numba, every core, then one) runs 2,048 members of the same batch, 2 s of the record,
in the same run. Then each other law at B = 2^20 (friction pendulums, IMK stories with P-Delta)
and a 10^6-member sweep (pipeline.sweep, the linear wall, 1000 gaps x 1000 stiffnesses, the
archive written) timed whole, records in, archive out.

One run of each (a GPU's timings vary by a few percent; --repeats N takes medians);
--sections picks some of planar, plan, laws, cpu and sweep. Prints a table, writes
benchmarks/results/bench_gpu.json after each section (a run cut short keeps what it
measured). Needs a GPU (or NUMBA_ENABLE_CUDASIM=1 with --quick, which checks the script, not
the speed).
"""
from __future__ import annotations

import argparse
import json
import platform
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DT = 5e-4
SECONDS = 20.0
DELAY = 1.7  # s: the y component, Kobe delayed (a pair without a second record file)
SECTIONS = ("planar", "plan", "laws", "cpu", "sweep")


def batch(size: int):
    """The batch of `size` members: each impact law in turn, the gaps spread over 5-30 cm."""
    import engine

    gaps = np.linspace(0.05, 0.30, size)
    parts = np.array_split(np.arange(size), 5)
    return engine.Contact.concat([
        engine.Contact.linear(gaps[parts[0]]),
        engine.Contact.jankowski(gaps[parts[1]], beta=2.75e9),
        engine.Contact.hertzdamp(gaps[parts[2]], k=2.75e9),
        engine.Contact.bumper(gaps[parts[3]] + 0.05, thickness=0.05),
        engine.Contact.none(len(parts[4]))])


def timed(run, repeats: int) -> float:
    """Median wall time of run() (s)."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def throughput(accel, accel_dt, size, repeats, backend="cuda", **model) -> dict:
    """Member-steps/s of engine.simulate on `size` members: marginal (the record's second
    half) and end to end (the whole record)."""
    import engine

    contact = batch(size)
    building = model.pop("building", engine.Building())
    half = len(accel) // 2

    def run(samples):
        engine.simulate(accel[:samples], accel_dt, contact, building, dt=DT, backend=backend,
                        **model)

    steps = [int(np.floor((n - 1) * accel_dt / DT + 1e-9)) + 1 for n in (half, len(accel))]
    t_half, t_whole = timed(lambda: run(half), repeats), timed(lambda: run(len(accel)), repeats)
    return {"B": size, "steps": steps[1], "seconds": t_whole,
            "kernel_member_steps_per_s": size * (steps[1] - steps[0]) / (t_whole - t_half),
            "end_to_end_member_steps_per_s": size * steps[1] / t_whole}


def cpu_rate(accel, accel_dt, threads: int, size: int = 2048) -> float:
    """The compiled CPU kernel's member-steps/s on `threads` threads, 2 s of the record."""
    import numba

    import engine

    numba.set_num_threads(threads)
    n = int(2.0 / accel_dt) + 1
    contact = batch(size)
    engine.simulate(accel[:n], accel_dt, contact, dt=DT, backend="numba")  # compile or load
    start = time.perf_counter()
    engine.simulate(accel[:n], accel_dt, contact, dt=DT, backend="numba")
    steps = int(np.floor((n - 1) * accel_dt / DT + 1e-9)) + 1
    return size * steps / (time.perf_counter() - start)


def sweep_end_to_end(record, per_axis: int, out: Path) -> dict:
    """A sweep of per_axis^2 members (gap x wall stiffness, the linear wall) of one record on
    the device, records in and the archive written: wall time (s) and the archive's size."""
    import pipeline

    start = time.perf_counter()
    pipeline.sweep([record], gap=list(np.linspace(0.05, 0.50, per_axis)),
                   wall_k=list(np.geomspace(1e9, 1e10, per_axis)), impact="linear", dt=DT,
                   out=out, backend="cuda", quiet=True, force=True)
    seconds = time.perf_counter() - start
    return {"members": per_axis**2, "seconds": seconds, "archive_bytes": out.stat().st_size}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--exponents", type=int, nargs="+", default=[10, 12, 14, 16, 18, 20, 22],
                   help="B = 2^k for each k (default: 10 to 22 every 2)")
    p.add_argument("--plan-exponents", type=int, nargs="+", default=[10, 16, 20, 22])
    p.add_argument("--repeats", type=int, default=1)
    p.add_argument("--sweep-axis", type=int, default=1000,
                   help="the sweep's members per axis (default 1000: 10^6 members)")
    p.add_argument("--quick", action="store_true",
                   help="tiny sizes and 0.2 s of record: checks the script (the simulator)")
    p.add_argument("--sections", nargs="+", choices=SECTIONS, default=list(SECTIONS),
                   help="what to measure (default: all)")
    p.add_argument("--law-models", nargs="+", choices=("planar", "plan"),
                   default=["planar", "plan"], help="laws: the models each law runs in")
    p.add_argument("--json", type=Path, default=ROOT / "benchmarks/results/bench_gpu.json")
    args = p.parse_args(argv)

    import numba
    from numba import cuda

    import engine
    from pipeline.histories import segment
    from pipeline.records import paper_record

    seconds = 0.2 if args.quick else SECONDS
    exponents = [4, 6] if args.quick else args.exponents
    plan_exponents = [4] if args.quick else args.plan_exponents
    record = segment(paper_record("kobe"), seconds)
    accel, accel_dt = record.accel, record.dt
    shift = int(round(DELAY / accel_dt))
    pair = np.column_stack([accel, np.roll(accel, shift) * (np.arange(len(accel)) >= shift)])
    from engine.loops.cuda_physics import simulated

    device = "CUDA simulator" if simulated() else cuda.get_current_device().name
    device = device.decode() if isinstance(device, bytes) else device
    cores = numba.config.NUMBA_NUM_THREADS
    result = {"device": str(device), "cpu": platform.processor() or platform.machine(),
              "cpu_threads": cores, "record": f"kobe, first {seconds:g} s", "dt": DT,
              "repeats": args.repeats, "planar": [], "plan": [], "laws": []}

    args.json.parent.mkdir(parents=True, exist_ok=True)

    def save():
        args.json.write_text(json.dumps(result, indent=1))

    if "planar" in args.sections or "cpu" in args.sections:
        throughput(accel, accel_dt, 64, 1)  # compile the kernels this run meets first
    if "plan" in args.sections:
        throughput(pair, accel_dt, 64, 1, moat="rectangular")
    for k in exponents if "planar" in args.sections else ():
        row = throughput(accel, accel_dt, 2**k, args.repeats)
        result["planar"].append(row)
        print(f"planar B=2^{k:<2} {row['kernel_member_steps_per_s']:10.3g} member-steps/s "
              f"(kernel), {row['end_to_end_member_steps_per_s']:10.3g} end to end, "
              f"{row['seconds']:7.2f} s", flush=True)
    save()
    for k in plan_exponents if "plan" in args.sections else ():
        row = throughput(pair, accel_dt, 2**k, args.repeats, moat="rectangular")
        result["plan"].append(row)
        print(f"plan   B=2^{k:<2} {row['kernel_member_steps_per_s']:10.3g} member-steps/s "
              f"(kernel), {row['end_to_end_member_steps_per_s']:10.3g} end to end, "
              f"{row['seconds']:7.2f} s", flush=True)
    save()

    size = 2**6 if args.quick else 2**20
    others = {
        "friction_pendulum": engine.Building(isolator=engine.Isolator.friction_pendulum(
            radius=2.0, mu_slow=0.04, mu_fast=0.09, rate=30.0)),
        "triple_friction_pendulum": engine.Building(
            isolator=engine.Isolator.triple_friction_pendulum(
                L1=0.3, L2=1.5, L3=1.6, d1=0.05, d2=0.15, d3=0.15, mu1=0.01, mu2=0.02,
                mu3=0.03)),
        "imk_stories_p_delta": engine.Building(
            stories=engine.Stories.imk(yield_force=(2.5e6, 2.2e6, 1.7e6, 1.0e6),
                                       plastic_deformation=0.03,
                                       post_capping_deformation=0.3),
            story_height=(4.0, 3.5, 3.5, 3.5), p_delta=True, collapse_drift_ratio=0.05)}
    for name, building in others.items() if "laws" in args.sections else ():
        for model, ground in (("planar", accel), ("plan", pair)):
            if model not in args.law_models:
                continue
            extra = {"moat": "rectangular"} if model == "plan" else {}
            throughput(ground[:50], accel_dt, 64, 1, building=building, **extra)  # compile
            row = throughput(ground, accel_dt, size, args.repeats, building=building, **extra)
            result["laws"].append({"law": name, "model": model, **row})
            print(f"{name:>25} {model:>6} B={size}: "
                  f"{row['kernel_member_steps_per_s']:10.3g} member-steps/s (kernel)",
                  flush=True)
            save()

    if "cpu" in args.sections and not args.quick:
        result["cpu_member_steps_per_s"] = {"threads": cores,
                                            "all": cpu_rate(accel, accel_dt, cores),
                                            "one": cpu_rate(accel, accel_dt, 1, 512)}
        # the device at its largest batch: the marginal rate of a small one is a difference
        # of two short times, the noisiest of the table
        largest = max(result["planar"], key=lambda r: r["B"], default=None)
        if largest is not None:
            rate = largest["kernel_member_steps_per_s"]
            result["device_over_cpu"] = {
                "node": rate / result["cpu_member_steps_per_s"]["all"],
                "core": rate / result["cpu_member_steps_per_s"]["one"]}
        ratios = result.get("device_over_cpu")
        print(f"CPU kernel: {result['cpu_member_steps_per_s']['all']:.3g} member-steps/s on "
              f"{cores} threads, {result['cpu_member_steps_per_s']['one']:.3g} on one"
              + (f"; device / node {ratios['node']:.0f}x, device / core {ratios['core']:.0f}x"
                 if ratios else ""), flush=True)
        save()

    if "sweep" in args.sections:
        axis = 4 if args.quick else args.sweep_axis
        with tempfile.TemporaryDirectory() as folder:
            sweep_end_to_end(record, 8, Path(folder) / "warm.nc")  # the sweep's kernel compiled
            row = sweep_end_to_end(record, axis, Path(folder) / "sweep.nc")
        result["sweep"] = row
        print(f"sweep of {row['members']} members, {seconds:g} s record, archive written: "
              f"{row['seconds']:.2f} s ({row['archive_bytes'] / 1e6:.1f} MB)", flush=True)
    save()
    print(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
