"""Every pair scaled so that the building without wall reaches the code's D_M in plan: not a
code rule, kept as an explicit option and labelled as removing the record-to-record scatter (by
construction every pair then gives the same unconstrained peak).

Why not pipeline.motions.scaling.scale_to_displacement, which also scales to a displacement: it
cannot give these factors. It scales planar records (one component, the building along one axis) to
a chosen displacement, by a geometric grid within its limits refined linearly, interpolates
inside the last bracket, rounds to 6 digits, checks the rounded factor by one more run and
leaves out the records it cannot bring there. Here a pair moves the building in plan (both
components, a circular moat, the resultant peak isolator displacement), and the factor is the
upper end of a log bisection (4 passes of 16 trial factors over 0.05-20): at least D_M, never
interpolated nor rounded, and every pair kept (one that cannot reach D_M gets 20).
"""
from __future__ import annotations

import numpy as np

NAME = "displacement"
"""The rule's name in --rule and the archives."""
ORDER = 3
"""Its place in listings: the code's rules first."""
TEXT = ("each pair scaled so that the building without wall reaches D_M in plan: REMOVES the "
        "record-to-record scatter by construction (not a code rule)")
"""What it does, in one line."""
CLAUSE = ("none: not a code rule; the building's unconstrained resultant peak isolator "
          "displacement in plan brought to the code's D_M (ASCE 7-22 section 17.5.3)")
"""What it implements instead of a clause."""


def factors(pairs, target, design, building, dt):
    """(every index, factors (R,), None): each pair's factor to D_M = design.d_m (m, at the
    bound run) on the building (at that bound's properties) at step dt (s, None for
    engine.DEFAULT_DT); the target is not needed."""
    chosen = list(range(len(pairs)))
    kept = np.array([to_displacement(p, design.d_m, building, dt) for p in pairs])
    return chosen, kept, None


def to_displacement(pair, displacement: float, building, dt) -> float:
    """The factor bringing the pair's resultant peak isolator displacement without wall, in
    plan, to `displacement` (m): bisection in log over [0.05, 20] on batched engine runs."""
    import engine

    dt = engine.DEFAULT_DT if dt is None else dt
    low, high = np.log(0.05), np.log(20.0)
    for _ in range(4):  # 4 passes of 16 trial factors: a bracket 16^-4 of the range wide
        trial = np.exp(np.linspace(low, high, 16))
        peaks = engine.simulate(pair.accel, pair.dt, engine.Contact.none(trial.size),
                                building, dt, scale=trial, moat="circular").peak_isolator_disp
        above = np.flatnonzero(peaks >= displacement)
        if above.size == 0:
            return float(trial[-1])
        k = max(int(above[0]), 1)
        low, high = np.log(trial[k - 1]), np.log(trial[k])
    return float(np.exp(high))
