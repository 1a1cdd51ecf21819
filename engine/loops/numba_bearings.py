"""The isolation of a building that twists, compiled for one member (numba_torsion.py): its
bearings, each the isolator law in plan at its own position (X, Y) from the plan's centre, with
its own displacement (u_x - theta Y, u_y + theta X) and velocity, and its share of the weight
(layout.isolator_rows); numpy_torsion.py writes the same on a batch."""
from __future__ import annotations

import numpy as np
from numba import njit

from ..results import MODE
from .compiled import LINK, failed, isolator_advance_xy, isolator_force_xy


@njit(**LINK)
def bearing_forces(tag, row, state, bearings, ux, uy, theta):
    """The bearings' force on the slab (N, x and y) and moment about the plan's centre (N m)
    at the slab's displacement (ux, uy) m and rotation theta rad; state (n, STATE_XY) each
    bearing's, bearings (n, 2) their positions (m)."""
    sx, sy, sm = 0.0, 0.0, 0.0
    for k in range(bearings.shape[0]):
        bx, by = bearings[k, 0], bearings[k, 1]
        fbx, fby = isolator_force_xy(tag, ux - theta * by, uy + theta * bx, state[k], row)
        sx += fbx
        sy += fby
        sm += bx * fby - by * fbx
    return sx, sy, sm


@njit(**LINK)
def bearings_advance(tag, row, state, bearings, velocity, dt):
    """Each bearing's state after a step of dt (s) at the slab's velocity (vx, vy, omega)."""
    vx, vy, omega = velocity
    for k in range(bearings.shape[0]):
        bx, by = bearings[k, 0], bearings[k, 1]
        isolator_advance_xy(tag, state[k], vx - omega * by, vy + omega * bx, dt, row)


@njit(**LINK)
def bearings_past(mode, bearings, ux, uy, theta, capacity_square):
    """The collapse mode (results.MODE) once a bearing's displacement is past its capacity
    (capacity_square m^2), `mode` otherwise (without a capacity no bearing is checked: a state
    no longer finite, the drifts say so)."""
    if capacity_square < np.inf:
        for k in range(bearings.shape[0]):
            bx = ux - theta * bearings[k, 1]
            by = uy + theta * bearings[k, 0]
            square = bx * bx + by * by
            if not square <= capacity_square:
                mode = failed(mode, square, MODE.isolator_capacity)
    return mode
