"""The batched time loop: explicit central differences over B buildings at once.

Equation of motion of member b (5 DOFs, relative to the ground):
    M a + C v + f_story(u) + f_iso(u0, history) + f_wall = -M 1 a_g(t)
Central differences with all damping on the central velocity, written on half-step
velocities v_{n+1/2} = (u_{n+1} - u_n) / dt:
    (M/dt^2 + C/(2dt)) dt v_{n+1/2} = p_n - f(u_n) + (M/dt - C/2) v_{n-1/2}.
The isolator and the wall's elastic force are explicit in u_n. The wall's dashpot also acts on
the central velocity: every impact law is affine in the indentation rate, so the step first
computes the velocities without contact force, then solves the one scalar equation for the
force exactly (impact.implicit_force) and adds its effect. A dashpot on a lagged velocity
instead makes peaks jitter by ~1% with dt. The matrices that multiply p - f and v_{n-1/2} are
inverted once per member before the loop, so a step is a fixed number of array operations.

Two backends run this scheme: the compiled kernel (kernel.py, numba; the default) and the
vectorised NumPy loop below (`backend="numpy"`), the readable reference that needs no
compiler. Both call the same physics functions (impact laws, isolator, implicit_force) and
agree to round-off; each is bitwise independent of the batch a member runs in.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from .backends import resolve_backend
from .building import N_LEVELS, Building, BuildingArrays, building_arrays
from .errors import EngineError, UnstableTimeStep
from .impact import Contact, fill_force_terms, implicit_force, law_blocks, onset_weight
from .isolator import isolator_force, plastic_spring_force

# s: the coarsest step at which halving dt moves every peak of the paper's practical example
# by less than 0.5% (0.35% at most; 1 ms moves them up to 0.9%): tests/test_convergence.py.
DEFAULT_DT = 5e-4
# Indentation assumed reachable by laws without a crush limit (Jankowski, Hertzdamp) when
# bounding their tangent stiffness for the stability limit.
INDENTATION_BOUND = 0.10  # m


@dataclass(frozen=True)
class History:
    """Ask for time histories of some members: batch indices and every how many steps."""

    members: Sequence[int]
    every: int = 1


@dataclass
class Result:
    """Peaks per member, in batch order (SI units), and optional histories.

    peak_total_accel (B, 5) m/s^2, peak_interstory_drift (B, 4) m, peak_isolator_disp (B,) m,
    max_indentation (B,) m, max_impact_force (B,) N, n_impacts (B,), impact_energy (B,) J:
    work done on the wall contacts, i.e. energy dissipated by impacts once contacts close;
    dt: the integration step (s); history: dict of arrays or None (see `simulate`).
    """

    peak_total_accel: np.ndarray
    peak_interstory_drift: np.ndarray
    peak_isolator_disp: np.ndarray
    max_indentation: np.ndarray
    max_impact_force: np.ndarray
    n_impacts: np.ndarray
    impact_energy: np.ndarray
    dt: float
    history: dict | None = None

    PEAK_FIELDS = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
                   "max_indentation", "max_impact_force", "n_impacts", "impact_energy")

    def peaks(self) -> dict[str, np.ndarray]:
        return {name: getattr(self, name) for name in self.PEAK_FIELDS}


def stable_dt(contact: Contact, building: Building | Sequence[Building] = Building(),
              indentation_bound: float = INDENTATION_BOUND) -> np.ndarray:
    """(B,) central-difference stability limit (s) at the stiffest state each member can reach.

    2 / omega_max, omega_max the highest frequency of M^-1 K with the isolator at k1 and the
    contact's largest tangent stiffness added at level 0. Dashpots act on central velocities
    and do not lower the limit.
    """
    arrays = building_arrays(building, len(contact))
    return _stable_dt(arrays, contact, indentation_bound)


def _stable_dt(arrays: BuildingArrays, contact: Contact, indentation_bound: float) -> np.ndarray:
    k = arrays.stiffness.copy()
    k[:, 0, 0] += contact.max_tangent_stiffness(indentation_bound)
    m_isqrt = 1 / np.sqrt(arrays.masses)
    omega_max = np.sqrt(np.linalg.eigvalsh(m_isqrt[:, :, None] * k * m_isqrt[:, None, :])[:, -1])
    return 2 / omega_max


def ground_motion_on_grid(accel, accel_dt: float, dt: float) -> np.ndarray:
    """Linearly interpolate a record (m/s^2 every accel_dt s) onto the step dt, (N,)."""
    accel, n_steps = _checked_record(accel, accel_dt, dt)
    return np.interp(np.arange(n_steps) * dt, np.arange(accel.size) * accel_dt, accel)


def _checked_record(accel, accel_dt: float, dt: float) -> tuple[np.ndarray, int]:
    """The record as a float array, and the number of steps of dt it spans."""
    accel = np.ascontiguousarray(accel, dtype=float)
    if accel.ndim != 1 or accel.size < 2:
        raise EngineError(f"accel must be a 1-D record with at least 2 samples, got {accel.shape}")
    if not np.all(np.isfinite(accel)):
        raise EngineError("accel contains NaN or inf")
    if not accel_dt > 0:
        raise EngineError(f"accel_dt must be positive, got {accel_dt}")
    duration = (accel.size - 1) * accel_dt
    return accel, int(np.floor(duration / dt + 1e-9)) + 1


def simulate(accel, accel_dt: float, contact: Contact,
             building: Building | Sequence[Building] = Building(), dt: float = DEFAULT_DT,
             history: History | None = None,
             progress: Callable[[int, int], None] | None = None,
             backend: str | None = None, scale=None) -> Result:
    """Integrate B isolated buildings under one ground motion, pounding on their moat walls.

    accel: (N,) ground acceleration in m/s^2 every accel_dt s, linearly interpolated onto dt;
    contact: a Contact of B members; building: one Building or a sequence of B of them;
    dt: integration step (s), refused above the stability limit;
    history: record time histories for some members every `every` steps: the result's history
    dict holds time (T,) s, members (M,), isolator_disp (M, T) m, total_accel (M, T, 5) m/s^2,
    impact_force (M, T) N, indentation (M, T) m;
    progress: called as progress(step, n_steps) about every 1% of the run;
    backend: "numba" (the compiled kernel), "numpy" (the vectorised reference loop) or None:
    numba when it can be imported, else numpy with a one-line notice;
    scale: None or (B,) positive factors (-) multiplying the ground acceleration member by
    member, so that one call runs one record at several intensities (e.g. the search for the
    factor that brings a record to a design displacement). None is 1 for every member, and a
    factor of 1 leaves a member's result bit for bit unchanged.
    """
    if not isinstance(contact, Contact):
        raise EngineError("contact must be an engine.Contact")
    size = len(contact)
    if size == 0:
        raise EngineError("contact: empty batch")
    if not dt > 0:
        raise EngineError(f"dt must be positive, got {dt}")
    arrays = building_arrays(building, size)
    limit = _stable_dt(arrays, contact, INDENTATION_BOUND)
    worst = int(np.argmin(limit))
    if dt >= limit[worst]:
        raise UnstableTimeStep(
            f"dt = {dt:g} s is unstable: the central-difference limit is {limit[worst]:.4g} s "
            f"(member {worst}, {contact.law_names[worst]} contact); use dt < {limit[worst]:.4g} s")
    accel, n_steps = _checked_record(accel, accel_dt, dt)
    scale = _checked_scale(scale, size)
    if history is not None:
        members = np.asarray(history.members, dtype=int)
        if members.ndim != 1 or np.any((members < -size) | (members >= size)):
            raise EngineError(f"history.members must index the batch of {size}, got "
                              f"{history.members!r}")
        if not (isinstance(history.every, (int, np.integer)) and history.every >= 1):
            raise EngineError(f"history.every must be a positive integer, got {history.every!r}")

    if resolve_backend(backend) == "numba":
        from .kernel import ground_motion, run_simulation
        ag = ground_motion(accel, float(accel_dt), float(dt), n_steps)  # == np.interp's
        peaks, hist = run_simulation(ag, dt, arrays, contact, history, progress, scale)
        return Result(**peaks, dt=dt, history=hist)
    ag = np.interp(np.arange(n_steps) * dt, np.arange(accel.size) * accel_dt, accel)

    order, blocks = law_blocks(contact)
    inverse = np.argsort(order)
    contact, arrays, scale = contact[order], arrays.take(order), scale[order]
    hist_members = None if history is None else inverse[np.asarray(history.members, dtype=int)]
    peaks, hist = _time_loop(ag, dt, arrays, contact.clear_gap, blocks, hist_members,
                             None if history is None else history.every, progress, scale)
    peaks = {name: value[inverse] for name, value in peaks.items()}
    if hist is not None:
        hist["members"] = np.asarray(history.members, dtype=int)
    return Result(**peaks, dt=dt, history=hist)


def _checked_scale(scale, size: int) -> np.ndarray:
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


def step_operators(b: BuildingArrays, dt: float):
    """Per-member operators of the scheme, shared by both backends: the (B, 5, 10) step
    operator mapping [p - f(u_n), v_{n-1/2}] to v_{n+1/2}; the (B, 5) wall response, the
    velocity change of every level per newton pushing level 0 back; and its level-0 entry,
    the (B,) compliance (m/s/N)."""
    mass = b.masses
    lhs = mass[:, :, None] * np.eye(N_LEVELS) / dt**2 + b.damping / (2 * dt)
    lhs_inv = np.linalg.inv(lhs)
    carry = mass[:, :, None] * np.eye(N_LEVELS) / dt - b.damping / 2
    step_op = np.concatenate([lhs_inv / dt, lhs_inv @ carry / dt], axis=2)
    wall_response = step_op[:, :, 0].copy()
    return step_op, wall_response, wall_response[:, 0].copy()


def _time_loop(ag, dt, b: BuildingArrays, gap, blocks, hist_members, hist_every, progress,
               scale):
    """The NumPy reference: every step is a fixed number of array operations over the batch."""
    size = b.masses.shape[0]
    mass = b.masses
    step_op, wall_response, compliance = step_operators(b, dt)

    u = np.zeros((size, N_LEVELS))
    v_half = np.zeros((size, N_LEVELS))
    rhs = np.zeros((size, 2 * N_LEVELS))  # [p - f(u_n), v_{n-1/2}]
    chain = np.zeros((size, N_LEVELS + 1))  # forces in isolator, stories 1..4, free end
    f_plastic = np.zeros(size)
    elastic = np.zeros(size)
    dashpot = np.zeros(size)
    v_imp = np.ones(size)
    delta_prev = np.zeros(size)
    in_contact = np.zeros(size, dtype=bool)

    peak_accel = np.zeros((size, N_LEVELS))
    peak_drift = np.zeros((size, N_LEVELS - 1))
    peak_iso = np.zeros(size)
    max_indent = np.zeros(size)
    max_force = np.zeros(size)
    n_impacts = np.zeros(size, dtype=np.int64)
    energy = np.zeros(size)

    n_steps = ag.size
    hist = None
    if hist_members is not None:
        n_out = (n_steps - 1) // hist_every + 1
        m_out = hist_members.size
        hist = {"time": np.arange(n_out) * hist_every * dt,
                "isolator_disp": np.zeros((m_out, n_out)),
                "total_accel": np.zeros((m_out, n_out, N_LEVELS)),
                "impact_force": np.zeros((m_out, n_out)),
                "indentation": np.zeros((m_out, n_out))}
    report_every = max(n_steps // 100, 1)

    for step in range(n_steps):
        a = ag[step] * scale  # (B,): x 1.0 is exact, unscaled members are unchanged
        u0 = u[:, 0]
        # Structure without wall force this step: p - f and the free velocities.
        chain[:, 0] = isolator_force(u0, f_plastic, b.k2)
        drift = np.diff(u, axis=1)
        np.multiply(b.story_k, drift, out=chain[:, 1:N_LEVELS])
        np.subtract(chain[:, 1:], chain[:, :-1], out=rhs[:, :N_LEVELS])
        rhs[:, :N_LEVELS] -= mass * a[:, None]
        rhs[:, N_LEVELS:] = v_half
        v_next = np.einsum("bij,bj->bi", step_op, rhs)

        # Wall contact on the side the slab moves towards.
        side = np.sign(u0)
        # Separations beyond 1 m never matter; the clamp keeps wall-less members (infinite
        # gap) finite in the arithmetic below.
        delta = np.maximum(np.abs(u0) - gap, -1.0)
        touching = delta > 0
        new = touching & ~in_contact
        n_impacts += new
        # The impact velocity is the approach rate just before the contact force acts.
        v_imp = np.where(new, side * v_half[:, 0], v_imp)
        in_contact = touching
        rate_free = side * 0.5 * (v_half[:, 0] + v_next[:, 0])
        fill_force_terms(blocks, delta, rate_free, v_imp, elastic, dashpot)
        # A dashpot that is already loaded at first touch (Kelvin-Voigt) would push for the
        # whole step; weight it by the part after the touch (impact.onset_weight).
        np.multiply(dashpot, onset_weight(delta, delta_prev), out=dashpot, where=new)
        delta_prev = delta
        force = np.where(touching, implicit_force(elastic, dashpot, rate_free, compliance), 0.0)
        v_next -= wall_response * (side * force)[:, None]

        total_accel = (v_next - v_half) / dt + a[:, None]
        np.maximum(peak_accel, np.abs(total_accel), out=peak_accel)
        np.maximum(peak_drift, np.abs(drift), out=peak_drift)
        np.maximum(peak_iso, np.abs(u0), out=peak_iso)
        np.maximum(max_indent, delta, out=max_indent)
        np.maximum(max_force, force, out=max_force)
        # Work on the wall over this step, with the central velocity of level 0.
        energy += force * side * (v_half[:, 0] + v_next[:, 0]) * (0.5 * dt)

        if hist is not None and step % hist_every == 0:
            k = step // hist_every
            hist["isolator_disp"][:, k] = u0[hist_members]
            hist["total_accel"][:, k] = total_accel[hist_members]
            hist["impact_force"][:, k] = force[hist_members]
            hist["indentation"][:, k] = np.maximum(delta[hist_members], 0.0)

        # Advance: the isolator's plastic spring sees this step's displacement increment.
        f_plastic = plastic_spring_force(f_plastic, dt * v_next[:, 0], b.k_plastic,
                                         b.f_plastic_yield)
        v_half = v_next
        u = u + dt * v_next
        if progress is not None and step % report_every == 0:
            progress(step, n_steps)
    if progress is not None:
        progress(n_steps, n_steps)

    peaks = {"peak_total_accel": peak_accel, "peak_interstory_drift": peak_drift,
             "peak_isolator_disp": peak_iso, "max_indentation": max_indent,
             "max_impact_force": max_force, "n_impacts": n_impacts, "impact_energy": energy}
    return peaks, hist
