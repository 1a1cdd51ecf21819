"""The engine's entry points: `simulate` (B isolated buildings under one record, pounding on
their moat walls) and `two_body` (B two-body impacts, paper sections 3.2 and 3.4), and the
public stability limit `stable_dt`.

They check the input, pick the time loop (engine/backends.py: the compiled kernel by default,
the NumPy reference on request) and hand it arrays; the scheme itself is in scheme.py, the
loops in loops/, what they return is declared in results.py.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from . import torsion
from .backends import plan_loop, resolve_backend, time_loop, torsion_loop
from .building import Building, building_arrays
from .errors import EngineError, UnstableTimeStep
from .impact import NONE, Contact
from .plan import ANGLE, MOATS, MU_WALL
from .results import History, PlanResult, Result, TorsionResult, TwoBodyResult
from .scheme import (
    DEFAULT_DT,
    INDENTATION_BOUND,
    checked_record,
    checked_scale,
    stability_limit,
)
from .torsion import contact_points, torsion_arrays

DEFAULT_STEPS_PER_CONTACT = 4000


def stable_dt(contact: Contact, building: Building | Sequence[Building] = Building(),
              indentation_bound: float = INDENTATION_BOUND) -> np.ndarray:
    """(B,) central-difference stability limit (s) at the stiffest state each member can reach
    (scheme.stability_limit): isolator at k1, the contact's largest tangent stiffness. For
    buildings that twist, their torsional limit with `contact` as every wall and the slab's
    corners as its points (bumpers stand within the sides: their limit is no lower)."""
    size = len(contact)
    if _twisting(building):
        twist = torsion_arrays([building] if isinstance(building, Building) else building, size)
        tangent = contact.max_tangent_stiffness(indentation_bound)
        return torsion.stability_limit(twist, contact_points(twist.plan), [tangent, tangent])
    return stability_limit(building_arrays(building, size), contact, indentation_bound)


def simulate(accel, accel_dt: float, contact: Contact,
             building: Building | Sequence[Building] = Building(), dt: float = DEFAULT_DT,
             history: History | None = None,
             progress: Callable[[int, int], None] | None = None,
             backend: str | None = None, scale=None, *, moat: str | None = None,
             contact_y: Contact | None = None, angle=None, mu_wall=None,
             bumper_positions=None) -> Result:
    """Integrate B isolated buildings under one ground motion, pounding on their moat walls.

    accel: (N,) ground acceleration in m/s^2 every accel_dt s, linearly interpolated onto dt;
    or (N, 2), the two horizontal components (x, y) of a record pair: the run is in plan (see
    below) and returns a PlanResult;
    contact: a Contact of B members; building: one Building or a sequence of B of them;
    dt: integration step (s), refused above the stability limit;
    history: record time histories for some members every `every` steps: the result's history
    dict holds time (T,) s, members (M,), isolator_disp (M, T) m, total_accel (M, T, levels)
    m/s^2, impact_force (M, T) N, indentation (M, T) m (results.HISTORIES);
    progress: called as progress(step, n_steps) about every 1% of the run;
    backend: "numba" (the compiled kernel), "numpy" (the vectorised reference loop) or None:
    numba when it can be imported, else numpy with a one-line notice;
    scale: None or (B,) positive factors (-) multiplying the ground acceleration member by
    member, so that one call runs one record at several intensities (e.g. the search for the
    factor that brings a record to a design displacement). None is 1 for every member, and a
    factor of 1 leaves a member's result bit for bit unchanged.
    Returns a Result: the peaks of results.PEAKS, (B, ...) in batch order.

    In plan ((N, 2) accel): the building moves in x and y on coupled isolators (circular yield
    surface, exact radial return; loops/numpy_plan.py), its stories isotropic. moat:
    "rectangular" (default: walls normal to x at +- the clear gap of `contact`, normal to y at
    +- that of contact_y, default the same walls; a corner loads both) or "circular" (one wall
    at the clear gap of `contact`, pushing along the radius). angle: None or (B,) incidence
    angles in degrees rotating each member's pair counterclockwise (one call runs a pair at
    many angles). mu_wall: None (0) or (B,) Coulomb friction coefficients between slab and
    wall (-): a slab pressing on a wall with normal force N slides along it against mu_wall N
    or sticks. The building's story_stiffness_y (if any) sets its stories along y.
    A building with a plan_size twists (engine/torsion.py; rectangular moat only): it returns
    a TorsionResult, the peaks at the plan's centre with the corners', the rotation and each
    contact point's (results.TORSION_PEAKS); bumper_positions: None (the slab's corners meet
    bare walls) or (along the x walls, along the y walls), the bumpers' positions in metres
    from the plan's centre, each carrying its share of the wall's law.
    Returns a PlanResult: the PEAKS as resultants (vector magnitudes), the
    per-direction peaks and the largest force on each wall (loops/numba_plan.py compiled, or
    loops/numpy_plan.py); its history (results.PLAN_HISTORIES) has the isolator's orbit
    (M, T, 2) m, the floor accelerations (M, T, levels, 2) m/s^2, the moat's force |F| (M, T)
    N and the deepest indentation (M, T) m.
    """
    if np.ndim(accel) == 2:
        return _simulate_plan(accel, accel_dt, contact, building, dt, history, progress,
                              backend, scale, moat, contact_y, angle, mu_wall,
                              bumper_positions)
    if moat is not None or contact_y is not None or angle is not None or mu_wall is not None \
            or bumper_positions is not None or _twisting(building):
        raise EngineError("moat, contact_y, angle, mu_wall, bumper_positions and a building's "
                          "plan_size apply to a run in plan: give accel as (N, 2), the record "
                          "pair's x and y components")
    if not isinstance(contact, Contact):
        raise EngineError("contact must be an engine.Contact")
    size = len(contact)
    if size == 0:
        raise EngineError("contact: empty batch")
    if not dt > 0:
        raise EngineError(f"dt must be positive, got {dt}")
    arrays = building_arrays(building, size)
    limit = stability_limit(arrays, contact)
    worst = int(np.argmin(limit))
    if dt >= limit[worst]:
        raise UnstableTimeStep(
            f"dt = {dt:g} s is unstable: the central-difference limit is {limit[worst]:.4g} s "
            f"(member {worst}, {contact.law_names[worst]} contact); use dt < {limit[worst]:.4g} s")
    accel, n_steps = checked_record(accel, accel_dt, dt)
    scale = checked_scale(scale, size)
    if history is not None:
        _check_history(history, size)

    loop = time_loop(resolve_backend(backend))
    ag = loop.ground_motion(accel, float(accel_dt), float(dt), n_steps)
    peaks, hist = loop.run_simulation(ag, dt, arrays, contact, history, progress, scale)
    return Result(**peaks, dt=dt, history=hist)


def _twisting(building) -> bool:
    """Whether the members twist (plan_size given); EngineError when only some do."""
    members = [building] if isinstance(building, Building) else list(building)
    twists = {getattr(b, "plan_size", None) is not None for b in members}
    if len(twists) > 1:
        raise EngineError("building: the members of one batch either all twist (plan_size "
                          "given) or none does")
    return twists == {True}


def _simulate_plan(accel, accel_dt, contact, building, dt, history, progress, backend, scale,
                   moat, contact_y, angle, mu_wall, bumper_positions) -> PlanResult:
    """simulate for a record pair (N, 2): the plan loop (see simulate)."""
    moat = "rectangular" if moat is None else moat
    if moat not in MOATS:
        raise EngineError(f"moat must be one of {MOATS}, got {moat!r}")
    twisting = _twisting(building)
    if bumper_positions is not None and not twisting:
        raise EngineError("bumper_positions place bumpers along the walls of a building that "
                          "twists: give the building its plan_size")
    if twisting and moat != "rectangular":
        raise EngineError("a building that twists (plan_size) needs the rectangular moat")
    if not isinstance(contact, Contact) or (contact_y is not None
                                            and not isinstance(contact_y, Contact)):
        raise EngineError("contact (and contact_y) must be an engine.Contact")
    size = len(contact)
    if size == 0:
        raise EngineError("contact: empty batch")
    if contact_y is not None and (moat != "rectangular" or len(contact_y) != size):
        raise EngineError(f"contact_y: the y walls of a rectangular moat, one per member "
                          f"({size}), got {len(contact_y)} for a {moat} moat")
    if history is not None:
        _check_history(history, size)
    accel = np.asarray(accel, dtype=float)
    if accel.ndim != 2 or accel.shape[1] != 2:
        raise EngineError(f"accel in plan must be (N, 2): x and y components, got "
                          f"{accel.shape}")
    if not dt > 0:
        raise EngineError(f"dt must be positive, got {dt}")
    arrays = building_arrays(building, size)
    arrays_y = _arrays_along_y(building, size)
    contacts = (contact, contact if contact_y is None else contact_y) \
        if moat == "rectangular" else (contact,)
    directions = (arrays,) if arrays_y is None else (arrays, arrays_y)
    if twisting:
        twist = torsion_arrays([building] if isinstance(building, Building) else building, size)
        points = contact_points(twist.plan, bumper_positions)
        limit = torsion.stability_limit(twist, points, [c.max_tangent_stiffness(
            INDENTATION_BOUND) for c in contacts])  # bumpers' points: a limit of their own
    else:
        limit = np.min([stability_limit(a, c) for c in contacts for a in directions], axis=0)
    worst = int(np.argmin(limit))
    if dt >= limit[worst]:
        raise UnstableTimeStep(f"dt = {dt:g} s is unstable: the central-difference limit is "
                               f"{limit[worst]:.4g} s (member {worst}); use dt < "
                               f"{limit[worst]:.4g} s")
    _, n_steps = checked_record(accel[:, 0], accel_dt, dt)
    checked_record(accel[:, 1], accel_dt, dt)
    scale = checked_scale(scale, size)
    angle = np.zeros(size) if angle is None else checked_angle(angle, size)
    friction = None if mu_wall is None else _checked_member_values(MU_WALL, mu_wall, size)
    if friction is not None and not np.any(friction > 0):
        friction = None  # frictionless walls: the loops skip the tangential solve
    from .loops import numpy_plan

    ag = numpy_plan.ground_motion(accel, float(accel_dt), float(dt), n_steps)
    if twisting:
        loop = torsion_loop(resolve_backend(backend))
        peaks, hist = loop.run_torsion(ag, dt, arrays, twist, contacts, points, progress, scale,
                                       np.radians(angle), history, friction)
        return TorsionResult(**peaks, dt=dt, history=hist, moat=moat, points=points)
    loop = plan_loop(resolve_backend(backend))
    peaks, hist = loop.run_plan(ag, dt, arrays, contacts, moat, progress, scale,
                                np.radians(angle), history, arrays_y, friction)
    return PlanResult(**peaks, dt=dt, history=hist, moat=moat)


def _check_history(history: History, size: int) -> None:
    members = np.asarray(history.members, dtype=int)
    if members.ndim != 1 or np.any((members < -size) | (members >= size)):
        raise EngineError(f"history.members must index the batch of {size}, got "
                          f"{history.members!r}")
    if not (isinstance(history.every, (int, np.integer)) and history.every >= 1):
        raise EngineError(f"history.every must be a positive integer, got {history.every!r}")


def _arrays_along_y(building, size: int):
    """The batch's arrays along y when a member's stories differ along y, else None (the
    loops then use the x arrays both ways, bit for bit as an isotropic building)."""
    members = [building] if isinstance(building, Building) else list(building)
    if all(b.isotropic for b in members):
        return None
    along_y = members[0].along_y() if len(members) == 1 else [b.along_y() for b in members]
    return building_arrays(along_y, size)


def checked_angle(angle, size: int) -> np.ndarray:
    """(B,) incidence angles in degrees, in the declared range (plan.ANGLE)."""
    return _checked_member_values(ANGLE, angle, size)


def _checked_member_values(param, values, size: int) -> np.ndarray:
    """(B,) values of a per-member parameter of runs in plan, in its declared range."""
    try:
        out = np.broadcast_to(np.asarray(values, dtype=float), (size,)).copy()
    except (TypeError, ValueError):
        raise EngineError(f"{param.name} must be a number or {size} numbers ({param.units}), "
                          f"got {np.shape(values)}") from None
    return param.check(out)


def contact_time_scale(m_eff, v, k, n):
    """Peak indentation (m) of an undamped power-law contact, times 3 / v: > the contact time."""
    delta_max = ((n + 1) * m_eff * v**2 / (2 * k)) ** (1 / (n + 1))
    return 3 * delta_max / v


def two_body(m1, m2, v, contact: Contact, steps_per_contact: int = DEFAULT_STEPS_PER_CONTACT,
             max_contacts: float = 20.0, backend: str | None = None) -> TwoBodyResult:
    """Collide B pairs of free rigid bodies through their impact laws (paper 3.2, 3.4).

    Body 1 (m1) approaches body 2 (m2) at relative velocity v. Only the relative coordinate
    matters: m_eff delta'' = -F(delta, delta'), m_eff = m1 m2 / (m1 + m2), delta(0) = 0,
    delta'(0) = v. It is integrated with the same central differences as the building (the
    dashpot on the central rate, solved exactly), with a step per member sized to its own
    contact duration, so members of very different stiffness finish in about the same number
    of steps.

    m1, m2 kg and v m/s broadcast to (B,); contact: B members whose gap is ignored (the bodies
    touch at t = 0) and whose m_eff must equal m1 m2 / (m1 + m2), since the laws' damping
    constants were built with it. backend: as in `simulate`.
    """
    m1, m2, v = (np.asarray(x, dtype=float) for x in (m1, m2, v))
    m1, m2, v = (np.broadcast_to(x, (len(contact),)) for x in (m1, m2, v))
    for name, x in (("m1", m1), ("m2", m2), ("v", v)):
        if np.any(~(x > 0)):
            raise EngineError(f"{name} must be positive, got {x}")
    if np.any(contact.law == NONE):
        raise EngineError("two_body needs an impact law for every member, got 'none'")
    m_eff = m1 * m2 / (m1 + m2)
    if not np.allclose(contact.m_eff, m_eff, rtol=1e-12):
        raise EngineError("contact.m_eff must equal m1 m2 / (m1 + m2) for each member")

    # The crush limit of a bumper only shortens the contact; the power law bounds its time.
    dt = contact_time_scale(m_eff, v, contact.k, contact.n) / steps_per_contact
    max_steps = int(max_contacts * steps_per_contact)
    expected_loss = 0.5 * m_eff * (1 - contact.cor**2) * v**2
    loop = time_loop(resolve_backend(backend))
    steps, out, deltas, forces = loop.run_two_body(contact, v, dt, m_eff, max_steps)
    if steps is None:
        raise EngineError(f"two_body: contact did not end within {max_steps} steps")
    v_out = -out[:, 1]
    return TwoBodyResult(
        peak_force=out[:, 2], peak_indentation=out[:, 3], cor=v_out / v,
        dissipated_energy=0.5 * m_eff * (v**2 - v_out**2), hysteresis_area=out[:, 0],
        expected_energy_loss=expected_loss, dt=dt, indentation=deltas, force=forces)
