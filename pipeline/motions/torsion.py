"""The code's allowance for torsion of the isolation system: the total maximum displacement
D_TM of ASCE 7-22 section 17.5.3.3 (Eqs. 17.5-3 and 17.5-4 as ASCE 7-16 numbers them; the
clause and the equations not checked against the 2022 text), which the moat's clear gap must
accommodate at the corners. Pure functions.

    D_TM = D_M [1 + (y / P_T^2) (12 e / (b^2 + d^2))],   D_TM >= 1.15 D_M,
    P_T = (1 / r_I) sqrt(sum_i (x_i^2 + y_i^2) / N),     r_I = sqrt((b^2 + d^2) / 12),

for loading along one plan axis: y the distance from the isolation system's centre of rigidity
to the element of interest, perpendicular to the loading (the slab's far corner: half the plan
dimension perpendicular to it, plus the centre of rigidity's offset from the plan's centre);
e the actual eccentricity of the mass above the isolation interface from that centre of
rigidity, perpendicular to the loading, plus the accidental eccentricity, 5% of the plan
dimension perpendicular to the loading; b and d the shortest and longest plan dimensions;
(x_i, y_i) the N isolators' positions from the isolation system's centre (of rigidity, for
identical bearings), P_T the ratio of the translational to the torsional period of the
isolation system, which the code lets be taken as 1.0 where smaller.

Units: m. Plan dimensions (b_x, b_y) along x and y; positions (n, 2) from the plan's centre
(grid_positions: engine.torsion's default layout, the engine's bearings).
"""
from __future__ import annotations

import math

import numpy as np

from engine.torsion import grid_positions, plan_dimensions

from .target import TORSION_FACTOR

ACCIDENTAL = 0.05
"""The accidental eccentricity as a share of the plan dimension perpendicular to the loading
(ASCE 7-22 section 17.5.3.3; also section 12.8.4.2's 5%)."""


def period_ratio(plan_size, positions) -> float:
    """P_T of Eq. 17.5-4 for identical bearings at `positions` (n, 2) m under a rectangular
    plan (the radius of gyration of its area), before the code's floor of 1.0."""
    b_x, b_y = plan_dimensions(plan_size)
    xy = np.asarray(positions, float)
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 1 or not np.all(np.isfinite(xy)):
        raise ValueError(f"positions must be (n, 2) finite metres, got shape {xy.shape}")
    centre = xy.mean(axis=0)  # identical bearings: the centre of rigidity
    r_i = math.sqrt((b_x**2 + b_y**2) / 12)
    return math.sqrt(float(np.mean(np.sum((xy - centre) ** 2, axis=1)))) / r_i


def total_maximum_displacement(d_m: float, plan_size, mass_offset=(0.0, 0.0),
                               positions=None, accidental: float = ACCIDENTAL) -> dict:
    """ASCE 7-22's D_TM (m) of the slab's worst corner from D_M (m), for a rectangular plan
    plan_size (b_x, b_y) m, the mass centre's actual eccentricity, its offset mass_offset
    (e_x, e_y) m from the plan's centre, identical bearings at `positions` (n, 2) m
    (default: grid_positions) and the accidental eccentricity's share of the plan dimension.

    Returns d_tm (the larger over loading along x and along y, at least 1.15 D_M), its ratio
    to D_M, the formula's value for each loading direction (`along_x`, `along_y`, before the
    floor), p_t (after the code's floor of 1.0) and whether the floor governs."""
    b_x, b_y = plan_dimensions(plan_size)
    if not (math.isfinite(d_m) and d_m > 0):
        raise ValueError(f"d_m must be a positive length (m), got {d_m!r}")
    e = np.asarray(mass_offset, float)
    if e.shape != (2,) or not np.all(np.isfinite(e)):
        raise ValueError(f"mass_offset must be (e_x, e_y) in metres, got {mass_offset!r}")
    if not (math.isfinite(accidental) and 0 <= accidental < 0.5):
        raise ValueError(f"accidental must be a share of the plan dimension in [0, 0.5), got "
                         f"{accidental!r}")
    xy = grid_positions((b_x, b_y)) if positions is None else np.asarray(positions, float)
    p_t = max(period_ratio((b_x, b_y), xy), 1.0)
    centre = xy.mean(axis=0)  # the centre of rigidity of identical bearings
    short, long = min(b_x, b_y), max(b_x, b_y)
    factors = {}
    # loading along x: the perpendicular is y (and conversely)
    for name, axis in (("along_x", 1), ("along_y", 0)):
        width = (b_y, b_x)[1 - axis]
        y = width / 2 + abs(centre[axis])
        ecc = abs(e[axis] - centre[axis]) + accidental * width
        factors[name] = 1 + (y / p_t**2) * (12 * ecc / (short**2 + long**2))
    ratio = max(factors.values())
    return {"d_tm": max(ratio, TORSION_FACTOR) * d_m, "ratio": max(ratio, TORSION_FACTOR),
            **{k: v * d_m for k, v in factors.items()}, "p_t": p_t,
            "floor_governs": ratio < TORSION_FACTOR}

