"""Cost of one engine time step against the batch size B.

The time loop does a fixed number of array operations per step, so the cost is a constant
(Python and NumPy call overhead) plus a small part per member: simulations per second grow
almost linearly with B until the arrays outgrow the cache. Run: python benchmarks/bench_engine.py
"""
import time

import numpy as np

import engine
from engine import Contact

STEPS = 4000


def step_cost(size: int) -> float:
    """Microseconds per time step for a batch of `size` mixed members (all five laws)."""
    gaps = np.linspace(0.05, 0.2, size)
    parts = np.array_split(np.arange(size), 5)
    contact = Contact.concat([
        Contact.none(len(parts[0])), Contact.linear(gaps[parts[1]]),
        Contact.jankowski(gaps[parts[2]], beta=2.75e10),
        Contact.hertzdamp(gaps[parts[3]], k=2.75e10),
        Contact.bumper(gaps[parts[4]] + 0.05)])
    dt = engine.DEFAULT_DT
    t = np.arange(STEPS) * dt
    accel = 8.0 * np.sin(2 * np.pi * 0.6 * t)  # m/s^2: strong enough to pound
    start = time.perf_counter()
    engine.simulate(accel, dt, contact, dt=dt)
    return (time.perf_counter() - start) / STEPS * 1e6


if __name__ == "__main__":
    print(f"{'B':>6} {'us/step':>9} {'us/step/member':>15} {'member-steps/s':>15}")
    for size in (5, 10, 50, 100, 500, 1000, 2000):
        cost = step_cost(size)
        print(f"{size:>6} {cost:>9.1f} {cost / size:>15.3f} {size / cost * 1e6:>15.3g}")
