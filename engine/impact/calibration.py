"""Damping factors that make Hunt-Crossley-type laws realise a target COR exactly.

For F = k delta^n (1 + chi delta_dot / v_imp) between two free bodies the realised COR depends
only on chi and n: scaling delta by (m v^2 / k)^(1/(n+1)) and time accordingly leaves
y'' = -y^n (1 + chi y'), y(0) = 0, y'(0) = 1. The damping acts in both phases (Hertzdamp) or
in restitution only (rubber bumper). COR(chi) is tabulated once per (n, phases) and inverted.
"""
from functools import lru_cache

import numpy as np

_CHI_GRID = np.concatenate([[0.0], np.geomspace(1e-4, 1e3, 400)])
_STEPS = 20_000


@lru_cache(maxsize=32)
def _cor_table(n: float, restitution_only: bool) -> np.ndarray:
    """Realised COR for each chi of _CHI_GRID (decreasing in chi)."""
    chi = _CHI_GRID
    y_max = ((n + 1) / 2) ** (1 / (n + 1))
    dt = 4 * y_max / _STEPS  # the undamped contact lasts < pi * y_max
    y = np.zeros_like(chi)
    v = np.ones_like(chi)
    for _ in range(3 * _STEPS):
        damping = chi * v
        if restitution_only:
            damping = np.where(v > 0, 0.0, damping)
        f = np.where(y > 0, np.maximum(np.maximum(y, 0) ** n * (1 + damping), 0.0), 0.0)
        # Symplectic Euler, damping on the previous velocity: at 20,000 steps per contact the
        # lag moves the COR far less than the table's interpolation error.
        v = v - dt * f
        y = y + dt * v
        if np.all((y < 0) | ((f == 0) & (v < 0) & (y > 0) & (1 + damping <= 0))):
            break
    return -v


def hunt_crossley_chi(cor, n, restitution_only: bool) -> np.ndarray:
    """chi (B,) realising `cor` (B,) for exponents `n` (B,)."""
    cor = np.atleast_1d(np.asarray(cor, dtype=float))
    n = np.broadcast_to(np.asarray(n, dtype=float), cor.shape)
    chi = np.empty_like(cor)
    for n_value in np.unique(n):
        table = _cor_table(float(n_value), bool(restitution_only))
        sel = n == n_value
        # np.interp needs increasing x: COR falls as chi grows.
        chi[sel] = np.interp(cor[sel], table[::-1], _CHI_GRID[::-1])
    return chi
