"""The isolator laws on a NumPy batch: the members of each law in the batch, the law's ROW and
its state, and its physics (force, advance, force_xy, advance_xy, engine/isolators/laws/)
called on each law's members at once, as written. The compiled loops' twin is
compiled.isolator_force and its kin, one member at a time, on the same rows
(layout.isolator_rows).
"""
from __future__ import annotations

import numpy as np

from ..isolators.registry import BY_CODE
from .layout import isolator_rows


class IsolatorBatch:
    """The isolators of a batch of B members (one bearing each, or `bearings` of a building
    that twists): per law present, (module, members, row, state), with row the law's ROW
    columns (F, B_law[, 1]) and state its STATE (planar) or STATE_XY (`plan`) columns
    (S, B_law[, bearings]), zero at rest. Displacements and velocities are (B,) or, with
    bearings, (B, bearings)."""

    def __init__(self, arrays, plan: bool = False, bearings: int | None = None):
        codes, rows = np.asarray(arrays.isolator_code), isolator_rows(arrays, bearings or 1)
        size = codes.size
        trailing = () if bearings is None else (bearings,)
        self.blocks = []
        for code in np.unique(codes):
            law = BY_CODE[code]
            members = np.flatnonzero(codes == code)
            if members.size == size:  # one law: the whole batch, no copies
                members = slice(None)
            row = rows[members, :len(law.ROW)].T
            if bearings is not None:
                row = row[..., None]
            width = len(law.STATE_XY if plan else law.STATE)
            state = np.zeros((width, row.shape[1], *trailing))
            self.blocks.append((law, members, row, state))

    def force(self, u: np.ndarray) -> np.ndarray:
        """Each member's isolator force (N) at displacement u (m)."""
        out = np.empty_like(u)
        for law, members, row, state in self.blocks:
            out[members] = law.force(u[members], state, row)
        return out

    def advance(self, velocity: np.ndarray, dt: float) -> None:
        """Each member's state after a step of dt (s) at `velocity` (m/s)."""
        for law, members, row, state in self.blocks:
            law.advance(state, velocity[members], dt, row)

    def force_xy(self, ux: np.ndarray, uy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """In plan: each member's (or bearing's) force along x and y (N)."""
        fx, fy = np.empty_like(ux), np.empty_like(uy)
        for law, members, row, state in self.blocks:
            fx[members], fy[members] = law.force_xy(ux[members], uy[members], state, row)
        return fx, fy

    def advance_xy(self, vx: np.ndarray, vy: np.ndarray, dt: float) -> None:
        """In plan: each member's (or bearing's) state after a step at velocity (vx, vy)."""
        for law, members, row, state in self.blocks:
            law.advance_xy(state, vx[members], vy[members], dt, row)

    def reset(self, fallen: np.ndarray) -> None:
        """The state of the members `fallen` ((B,) bool) back at rest (a collapsed member)."""
        for _, members, _, state in self.blocks:
            state[:, fallen[members]] = 0.0
