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
from .backends import loop_of, resolve_backend, time_loop
from .building import Building, building_arrays
from .errors import EngineError, UnstableTimeStep
from .impact import NONE, Contact
from .model import PLANAR, TWISTING, model_of
from .plan import ANGLE, MU_WALL, Moat
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
              indentation_bound: float = INDENTATION_BOUND,
              moat: Moat | None = None) -> np.ndarray:
    """(B,) central-difference stability limit (s) at the stiffest state each member can reach
    (scheme.stability_limit): isolator at k1, the contact's largest tangent stiffness. For
    buildings that twist, their torsional limit with `contact` as every wall and its points
    where `moat` puts them (its bumper_positions; the slab's corners without a moat)."""
    size = len(contact)
    if _twisting(building):
        twist = torsion_arrays(_members(building), size)
        positions = None if moat is None else moat.bumper_positions
        return torsion.stability_limit(twist, contact_points(twist.plan, positions),
                                       (contact, contact), indentation_bound)
    return stability_limit(building_arrays(building, size), contact, indentation_bound)


def simulate(accel, accel_dt: float, contact: Contact,
             building: Building | Sequence[Building] = Building(), dt: float = DEFAULT_DT,
             history: History | None = None,
             progress: Callable[[int, int], None] | None = None,
             backend: str | None = None, scale=None, *, moat: str | Moat | None = None,
             angle=None) -> Result:
    """Integrate B isolated buildings under one ground motion, pounding on their moat walls.

    The run's model (engine/model.py) follows from the inputs, once: accel (N,), one
    component along x, is the planar model (a Result); accel (N, 2), a record pair's x and y
    components, runs in plan (a PlanResult), or twisting when the buildings have a torsion
    component (a TorsionResult). What each model takes is engine.model.SUPPORTS; anything
    else is refused quoting it.

    accel: the ground acceleration in m/s^2 every accel_dt s, linearly interpolated onto dt;
    contact: a Contact of B members (in plan: the x walls, and every wall unless the moat
    gives contact_y); building: one Building or a sequence of B of them (one model);
    dt: integration step (s), refused above the stability limit;
    history: record time histories for some members every `every` steps (the model's
    histories: results.HISTORIES, PLAN_HISTORIES, TORSION_HISTORIES);
    progress: called as progress(step, n_steps) about every 1% of the run;
    backend: "numba" (the compiled kernel), "numpy" (the vectorised reference loop), "cuda"
    (the device loop on an NVIDIA GPU: the planar and plan models, numba-cuda needed) or None:
    numba when it can be imported, else numpy with a one-line notice;
    scale: None or (B,) positive factors (-) multiplying the ground acceleration member by
    member, so that one call runs one record at several intensities. None is 1 for every
    member, and a factor of 1 leaves a member's result bit for bit unchanged;
    moat (in plan): None ("rectangular"), a shape's name ("rectangular", "circular") or an
    engine.Moat (its shape, the y walls' contact_y, the wall friction mu_wall, the bumpers'
    positions along the walls of a building that twists);
    angle (in plan): None or (B,) incidence angles in degrees rotating each member's pair
    counterclockwise (one call runs a pair at many angles).
    Returns the model's result: the peaks of model.peaks, (B, ...) in batch order (in plan
    the PEAKS as resultants, vector magnitudes), and its history.
    """
    model = model_of(np.shape(accel)[1] if np.ndim(accel) == 2 else 1, _twisting(building))
    if not model.in_plan:
        if moat is not None or angle is not None:
            raise model.refuse("moat" if moat is not None else "angle")
        return _simulate_planar(accel, accel_dt, contact, building, dt, history, progress,
                                backend, scale)
    return _simulate_plan(model, accel, accel_dt, contact, building, dt,
                          (history, progress, backend, scale),
                          (Moat.of("rectangular" if moat is None else moat), angle))


def _simulate_planar(accel, accel_dt, contact, building, dt, history, progress, backend,
                     scale) -> Result:
    """simulate for one component (N,): the planar loop (see simulate)."""
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

    loop = loop_of(PLANAR, backend)
    ag = loop.ground_motion(accel, float(accel_dt), float(dt), n_steps)
    peaks, hist = loop.run_simulation(ag, dt, arrays, contact, history, progress, scale)
    return Result(**peaks, dt=dt, history=hist)


def _members(building) -> list:
    """The batch's buildings: [one] broadcast, or the sequence's."""
    return [building] if isinstance(building, Building) else list(building)


def _twisting(building) -> bool:
    """Whether the members twist (a torsion component); EngineError when only some do."""
    twists = {getattr(b, "twists", False) for b in _members(building)}
    if len(twists) > 1:
        raise EngineError("building: the members of one batch either all twist (a torsion "
                          "component) or none does")
    return twists == {True}


def _simulate_plan(model, accel, accel_dt, contact, building, dt, run, walls) -> PlanResult:
    """simulate for a record pair (N, 2) (see simulate): run = (history, progress, backend,
    scale), walls = (the Moat, angle)."""
    history, progress, backend, scale = run
    moat, angle = walls
    model.check("moat", moat.shape)
    model.check("bumper_positions", moat.bumper_positions is not None)
    contact_y = moat.contact_y
    if not isinstance(contact, Contact) or (contact_y is not None
                                            and not isinstance(contact_y, Contact)):
        raise EngineError("contact (and contact_y) must be an engine.Contact")
    size = len(contact)
    if size == 0:
        raise EngineError("contact: empty batch")
    if contact_y is not None and (moat.shape != "rectangular" or len(contact_y) != size):
        raise EngineError(f"contact_y: the y walls of a rectangular moat, one per member "
                          f"({size}), got {len(contact_y)} for a {moat.shape} moat")
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
        if moat.shape == "rectangular" else (contact,)
    directions = (arrays,) if arrays_y is None else (arrays, arrays_y)
    if model is TWISTING:
        twist = torsion_arrays(_members(building), size)
        points = contact_points(twist.plan, moat.bumper_positions)
        limit = torsion.stability_limit(twist, points, contacts, INDENTATION_BOUND)
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
    mu_wall = moat.mu_wall
    friction = None if mu_wall is None else _checked_member_values(MU_WALL, mu_wall, size)
    if friction is not None and not np.any(friction > 0):
        friction = None  # frictionless walls: the loops skip the tangential solve
    from .loops import numpy_plan

    ag = numpy_plan.ground_motion(accel, float(accel_dt), float(dt), n_steps)
    loop = loop_of(model, backend)
    if model is TWISTING:
        peaks, hist = loop.run_torsion(ag, dt, arrays, twist, contacts, points, progress, scale,
                                       np.radians(angle), history, friction)
        return TorsionResult(**peaks, dt=dt, history=hist, moat=moat.shape, points=points)
    peaks, hist = loop.run_plan(ag, dt, arrays, contacts, moat.shape, progress, scale,
                                np.radians(angle), history, arrays_y, friction)
    return PlanResult(**peaks, dt=dt, history=hist, moat=moat.shape)


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
    members = _members(building)
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
