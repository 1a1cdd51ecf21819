"""Parallel efficiency of the local execution modes on this machine, for a recipe-sized sweep.

    python benchmarks/bench_parallel.py [--repeats 3] [--quick]

The sweep is Figs. 14-15's (studies.gap_size: the paper's four records, gaps 15-45 cm every
1 cm, four 5 cm bumpers, the bare wall and the free building: 252 simulations). Each mode runs
in its own process (thread counts are fixed at import), `--repeats` times; the table gives the
median wall time of the `pipeline.sweep` call and the parallel efficiency

    efficiency = T(one core) / (cores x T(mode)),

where T(one core) is the in-process run with the compiled kernel on one thread, each timed after
a warm-up sweep in the same process (kernel loaded, record library indexed: one-off costs of
about 1.5 s per process, not parallel work). The modes:
"1 process, 1 thread" (the reference), "1 process, all threads" (the default, workers=1) and
"N dask workers" (workers=N, one thread each). The default should stay above 80%; the issue
that asked for this measurement chose the default from it. JSON goes to
benchmarks/results/parallel.json.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"

CHILD = """
import json, sys, time
import pipeline
from studies.common.peaks_vs_gap import gaps
quick, workers = sys.argv[1] == "1", int(sys.argv[2])
kwargs = dict(gap=gaps(quick), thickness=0.05, n_bumpers=4, baseline=True, unconstrained=True,
              workers=workers, quiet=True)
records = ["kobe", "sylmar_converter", "olive_view", "pacoima"]
# Warm-up: the kernel from its cache, the record library's index (read once per process)
pipeline.sweep(records, **{**kwargs, "gap": kwargs["gap"][:2], "workers": 1})
start = time.perf_counter()
ds = pipeline.sweep(records, **kwargs)
wall = time.perf_counter() - start
n = sum(v.size for name, v in ds.data_vars.items() if name.endswith("peak_isolator_disp"))
print(json.dumps({"wall": wall, "simulations": int(n)}))
"""


def run_mode(threads: int, workers: int, quick: bool) -> dict:
    env = {**os.environ, "NUMBA_NUM_THREADS": str(threads), "OMP_NUM_THREADS": "1"}
    out = subprocess.run([sys.executable, "-c", CHILD, "1" if quick else "0", str(workers)],
                         env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=3, help="runs per mode (median quoted)")
    p.add_argument("--quick", action="store_true", help="the --quick gap grid (10 cm steps)")
    args = p.parse_args(argv)

    cores = os.cpu_count() or 1
    modes = [("1 process, 1 thread", 1, 1), (f"1 process, {cores} threads (default)", cores, 1),
             (f"{cores} dask workers, 1 thread each", 1, cores)]
    # Round robin over the modes, so that a noisy spell of the shared machine hits all alike.
    runs = {label: [] for label, _, _ in modes}
    for _ in range(args.repeats):
        for label, threads, workers in modes:
            runs[label].append(run_mode(threads, workers, args.quick))
    rows = []
    for label, threads, workers in modes:
        walls = [r["wall"] for r in runs[label]]
        rows.append({"mode": label, "threads": threads, "workers": workers,
                     "simulations": runs[label][0]["simulations"],
                     "median_s": statistics.median(walls), "min_s": min(walls),
                     "max_s": max(walls)})
    reference = rows[0]["median_s"]
    print(f"{rows[0]['simulations']} simulations, {cores} cores, medians of {args.repeats}")
    print(f"{'mode':40s} {'median s':>9s} {'min':>7s} {'max':>7s} {'speed-up':>9s} "
          f"{'efficiency':>10s}")
    for row in rows:
        cores_used = max(row["threads"], row["workers"])
        row["speedup"] = reference / row["median_s"]
        row["efficiency"] = row["speedup"] / cores_used
        print(f"{row['mode']:40s} {row['median_s']:9.2f} {row['min_s']:7.2f} "
              f"{row['max_s']:7.2f} {row['speedup']:9.2f} {100 * row['efficiency']:9.0f}%")
    RESULTS.mkdir(exist_ok=True)
    path = RESULTS / "parallel.json"
    path.write_text(json.dumps({"cores": cores, "repeats": args.repeats, "quick": args.quick,
                                "rows": rows}, indent=2))
    print("wrote", path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
