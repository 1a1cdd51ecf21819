"""Cost of one engine member-step against the batch size B, on both backends.

The compiled kernel (numba) costs a few tens of nanoseconds per member-step at every B; the
NumPy loop a fixed cost per step (Python and NumPy call overhead) plus a small part per member,
so it gains with B. Run: python benchmarks/bench_engine.py [--threads N]
"""
import argparse
import time

import numpy as np

import engine
from engine import Contact

STEPS = 4000


def step_cost(size: int, backend: str, steps: int = STEPS) -> float:
    """Microseconds per time step for a batch of `size` mixed members (all five laws)."""
    gaps = np.linspace(0.05, 0.2, size)
    parts = np.array_split(np.arange(size), 5)
    contact = Contact.concat([
        Contact.none(len(parts[0])), Contact.linear(gaps[parts[1]]),
        Contact.jankowski(gaps[parts[2]], beta=2.75e10),
        Contact.hertzdamp(gaps[parts[3]], k=2.75e10),
        Contact.bumper(gaps[parts[4]] + 0.05)])
    dt = engine.DEFAULT_DT
    t = np.arange(steps) * dt
    accel = 8.0 * np.sin(2 * np.pi * 0.6 * t)  # m/s^2: strong enough to pound
    start = time.perf_counter()
    engine.simulate(accel, dt, contact, dt=dt, backend=backend)
    return (time.perf_counter() - start) / steps * 1e6


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--threads", type=int, default=None, help="numba threads (default: all)")
    args = p.parse_args()
    if args.threads:
        import numba

        numba.set_num_threads(args.threads)
    step_cost(5, "numba", 10)  # compile or load from the cache
    print(f"{'backend':>8} {'B':>6} {'us/step':>9} {'ns/member-step':>15} {'member-steps/s':>15}")
    for backend in ("numba", "numpy"):
        for size in (5, 10, 50, 100, 500, 1000, 2000, 8000):
            if backend == "numpy" and size > 2000:
                continue
            steps = STEPS if backend == "numpy" else 40_000
            cost = step_cost(size, backend, steps)
            print(f"{backend:>8} {size:>6} {cost:>9.2f} {cost / size * 1e3:>15.1f} "
                  f"{size / cost * 1e6:>15.3g}")
