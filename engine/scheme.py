"""The integration scheme both time loops run, and what they share: the default step, the
per-member step operators, the stability limit, the exact contact solve and the onset
weighting of a new contact.

Equation of motion of member b (levels 0..N, relative to the ground):
    M a + C v + f_story(u) + f_iso(u0, history) + f_wall = -M 1 a_g(t)
Central differences with all damping on the central velocity, written on half-step
velocities v_{n+1/2} = (u_{n+1} - u_n) / dt:
    (M/dt^2 + C/(2dt)) dt v_{n+1/2} = p_n - f(u_n) + (M/dt - C/2) v_{n-1/2}.
The isolator and the wall's elastic force are explicit in u_n. The wall's dashpot also acts on
the central velocity: every impact law is affine in the indentation rate, so a step first
computes the velocities without contact force, then solves the one scalar equation for the
force exactly (`implicit_force`) and adds its effect. A dashpot on a lagged velocity instead
makes peaks jitter by ~1% with dt. The matrices that multiply p - f and v_{n-1/2} are inverted
once per member before the loop (`step_operators`), so a step is a fixed number of operations.

`implicit_force` and `onset_weight` are written once for scalars and arrays alike: the NumPy
loop (loops/numpy_loop.py) calls them on arrays, the compiled loop (loops/numba_loop.py)
compiles them for scalars.
"""
from __future__ import annotations

import numpy as np

from .building import BuildingArrays, distinct_members
from .errors import EngineError
from .impact import Contact

# s: the coarsest step at which halving dt moves every peak of the paper's practical example
# by less than 0.5% (0.35% at most; 1 ms moves them up to 0.9%):
# tests/engine/test_scheme_convergence.py.
DEFAULT_DT = 5e-4
# Indentation assumed reachable by laws without a crush limit (Jankowski, Hertzdamp) when
# bounding their tangent stiffness for the stability limit.
INDENTATION_BOUND = 0.10  # m


def stability_limit(arrays: BuildingArrays, contact: Contact,
                    indentation_bound: float = INDENTATION_BOUND) -> np.ndarray:
    """(B,) central-difference stability limit (s) at the stiffest state each member can reach.

    2 / omega_max, omega_max the highest frequency of M^-1 K with the isolator at k1 and the
    contact's largest tangent stiffness added at level 0. Dashpots act on central velocities
    and do not lower the limit.
    """
    tangent = np.broadcast_to(contact.max_tangent_stiffness(indentation_bound), len(contact))
    # once per distinct building and wall stiffness (a sweep's million members: a few)
    _, stiffness = distinct_members(tangent)
    first, inverse = distinct_members(arrays.distinct * (stiffness.max() + 1) + stiffness)
    k = arrays.stiffness[first].copy()
    k[:, 0, 0] += tangent[first]
    m_isqrt = 1 / np.sqrt(arrays.masses[first])
    omega_max = np.sqrt(np.linalg.eigvalsh(m_isqrt[:, :, None] * k * m_isqrt[:, None, :])[:, -1])
    return (2 / omega_max)[inverse]


def step_operators(b: BuildingArrays, dt: float):
    """Per-member operators of the scheme: the (B, L, 2L) step operator mapping
    [p - f(u_n), v_{n-1/2}] to v_{n+1/2} (L levels); the (B, L) wall response, the velocity
    change of every level per newton pushing level 0 back; and its level-0 entry, the (B,)
    compliance (m/s/N)."""
    first, which = distinct_members(b.distinct)  # once per distinct building
    step_op = distinct_step_operators(b, dt, first)[which]
    wall_response = step_op[:, :, 0].copy()
    return step_op, wall_response, wall_response[:, 0].copy()


def distinct_step_operators(b: BuildingArrays, dt: float, first: np.ndarray) -> np.ndarray:
    """The (D, L, 2L) step operators (step_operators') of the members `first` ((D,) ints: one
    member of each distinct building, building.distinct_members'): a batch's operators once
    per building, member b's the one of its building."""
    return full_step_operator(b.masses[first, :, None] * np.eye(b.masses.shape[1]),
                              b.damping[first], dt)


def full_step_operator(mass: np.ndarray, damping: np.ndarray, dt: float) -> np.ndarray:
    """(B, n, 2n) the step operator of mass and damping matrices (B, n, n): v_{n+1/2} =
    [(M/dt^2 + C/(2dt))^-1 / dt, (M/dt^2 + C/(2dt))^-1 (M/dt - C/2) / dt] [p - f(u_n),
    v_{n-1/2}]."""
    lhs_inv = np.linalg.inv(mass / dt**2 + damping / (2 * dt))
    carry = mass / dt - damping / 2
    return np.concatenate([lhs_inv / dt, lhs_inv @ carry / dt], axis=2)


DENSE_LEVELS = 12
"""Up to this many levels the compiled loop multiplies by the dense step operator (the
paper's building: its numbers bit for bit); above, with chain damping, it solves the
tridiagonal system (banded_operators), whose cost grows linearly with the levels."""


def banded_operators(b: BuildingArrays, dt: float) -> np.ndarray | None:
    """(B, 5, L) float: the scheme's operators as bands for the Thomas algorithm, or None when
    the building is small (L <= DENSE_LEVELS) or a member's damping is not a chain (modal).

    A = M/dt^2 + C/(2dt) and K = M/dt - C/2 are tridiagonal when C is (the paper's rule:
    dashpots between neighbouring levels). Rows: 1 / pivot of A's LU factorisation (L),
    A's off-diagonal (L - 1), the factor's eliminated off-diagonal (L - 1), K's diagonal (L)
    and off-diagonal (L - 1); shorter rows padded with 0. v_{n+1/2} = A^-1 (p - f + K v) / dt.
    """
    size, n_levels = b.masses.shape
    damping = b.damping
    band = np.abs(np.arange(n_levels)[:, None] - np.arange(n_levels)[None, :]) <= 1
    if n_levels <= DENSE_LEVELS or np.any(damping[:, ~band] != 0):
        return None
    diag = b.masses / dt**2 + np.diagonal(damping, axis1=1, axis2=2) / (2 * dt)
    off = np.diagonal(damping, offset=1, axis1=1, axis2=2) / (2 * dt)
    out = np.zeros((size, 5, n_levels))
    pivot = diag[:, 0].copy()
    out[:, 0, 0] = 1 / pivot
    for i in range(1, n_levels):
        eliminated = off[:, i - 1] / pivot  # A's upper entry over the previous pivot
        out[:, 2, i - 1] = eliminated
        pivot = diag[:, i] - off[:, i - 1] * eliminated
        out[:, 0, i] = 1 / pivot
    out[:, 1, :-1] = off
    out[:, 3] = b.masses / dt - np.diagonal(damping, axis1=1, axis2=2) / 2
    out[:, 4, :-1] = -np.diagonal(damping, offset=1, axis1=1, axis2=2) / 2
    return out


def checked_record(accel, accel_dt: float, dt: float) -> tuple[np.ndarray, int]:
    """The record as a float array, and the number of steps of dt it spans. Always writable:
    the compiled loop types a read-only array apart and would compile once more for it."""
    accel = np.require(accel, dtype=float, requirements=["C", "W"])
    if accel.ndim != 1 or accel.size < 2:
        raise EngineError(f"accel must be a 1-D record with at least 2 samples, got {accel.shape}")
    if not np.all(np.isfinite(accel)):
        raise EngineError("accel contains NaN or inf")
    if not accel_dt > 0:
        raise EngineError(f"accel_dt must be positive, got {accel_dt}")
    duration = (accel.size - 1) * accel_dt
    return accel, int(np.floor(duration / dt + 1e-9)) + 1


def checked_scale(scale, size: int) -> np.ndarray:
    """(B,) ground-motion factors: ones for None, a scalar broadcast, else checked."""
    if scale is None:
        return np.ones(size)
    try:
        factors = np.broadcast_to(np.asarray(scale, dtype=float), (size,)).copy()
    except (TypeError, ValueError):
        raise EngineError(f"scale must be a number or {size} numbers (one per member), "
                          f"got {np.shape(scale)}") from None
    if not np.all(np.isfinite(factors) & (factors > 0)):
        raise EngineError(f"scale must be positive and finite, got {factors.tolist()[:8]}")
    return factors


def onset_weight(delta, delta_prev):
    """Part of the step [t_n - dt/2, t_n + dt/2] after first touch, located by linear
    interpolation of the indentation from delta_prev (m, previous step) to delta (m, > 0).

    A dashpot that is already loaded at first touch (Kelvin-Voigt) would otherwise push for the
    whole step, and peaks would jitter with dt. Scalars or arrays alike.
    """
    travel = np.maximum(delta - np.minimum(delta_prev, 0.0), 1e-300)
    return np.minimum(delta / travel + 0.5, 1.0)


def implicit_force(elastic, dashpot, delta_dot_free, compliance):
    """Contact force (N, >= 0) with the dashpot on the central velocity, solved exactly.

    delta_dot_free: the central indentation rate if no contact force acted this step (m/s);
    compliance: how much one newton of contact force lowers the next half-step velocity, hence
    twice what it lowers the central rate (m/s/N). Because the
    force is affine in the rate, F = (elastic + dashpot * delta_dot_free) /
    (1 + dashpot * compliance / 2) keeps the sign of the explicit estimate, so clipping at
    zero (no tension) stays consistent.
    """
    trial = elastic + dashpot * delta_dot_free
    return np.maximum(trial / (1 + 0.5 * dashpot * compliance), 0.0)
