"""Two free rigid bodies colliding through one impact law (paper sections 3.2 and 3.4).

Body 1 (m1) approaches body 2 (m2) at relative velocity v. Only the relative coordinate
matters: m_eff delta'' = -F(delta, delta'), m_eff = m1 m2 / (m1 + m2), delta(0) = 0,
delta'(0) = v. It is integrated with the same central differences as the building engine (the
dashpot on the central rate, solved exactly), with a step per member sized to its own contact
duration, so members of very different stiffness finish in about the same number of steps.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .backends import resolve_backend
from .errors import EngineError
from .impact import NONE, Contact, fill_force_terms, implicit_force, law_blocks

DEFAULT_STEPS_PER_CONTACT = 4000


@dataclass
class TwoBodyResult:
    """Per member (B,): peak_force N, peak_indentation m, cor (measured, -v_out / v),
    dissipated_energy J (kinetic energy lost, 1/2 m_eff (v^2 - v_out^2)), hysteresis_area J
    (closed integral of F d(delta)), expected_energy_loss J (Eq. 5 with the target COR),
    dt s; histories (B, T): indentation m, force N (zero after separation)."""

    peak_force: np.ndarray
    peak_indentation: np.ndarray
    cor: np.ndarray
    dissipated_energy: np.ndarray
    hysteresis_area: np.ndarray
    expected_energy_loss: np.ndarray
    dt: np.ndarray
    indentation: np.ndarray
    force: np.ndarray


def contact_time_scale(m_eff, v, k, n):
    """Peak indentation (m) of an undamped power-law contact, times 3 / v: > the contact time."""
    delta_max = ((n + 1) * m_eff * v**2 / (2 * k)) ** (1 / (n + 1))
    return 3 * delta_max / v


def two_body(m1, m2, v, contact: Contact, steps_per_contact: int = DEFAULT_STEPS_PER_CONTACT,
             max_contacts: float = 20.0, backend: str | None = None) -> TwoBodyResult:
    """Collide B pairs of bodies. m1, m2 kg and v m/s broadcast to (B,); contact: B members
    whose gap is ignored (the bodies touch at t = 0) and whose m_eff must equal
    m1 m2 / (m1 + m2), since the laws' damping constants were built with it.
    backend: "numba" (the compiled kernel), "numpy" or None (numba when importable), as in
    engine.simulate."""
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
    size = len(contact)
    expected_loss = 0.5 * m_eff * (1 - contact.cor**2) * v**2
    if resolve_backend(backend) == "numba":
        from .kernel import run_two_body
        steps, out, deltas, forces = run_two_body(contact, v, dt, m_eff, max_steps)
        if steps is None:
            raise EngineError(f"two_body: contact did not end within {max_steps} steps")
        v_out = -out[:, 1]
        return TwoBodyResult(
            peak_force=out[:, 2], peak_indentation=out[:, 3], cor=v_out / v,
            dissipated_energy=0.5 * m_eff * (v**2 - v_out**2), hysteresis_area=out[:, 0],
            expected_energy_loss=expected_loss, dt=dt, indentation=deltas, force=forces)

    order, blocks = law_blocks(contact)
    v_sorted, dt_sorted, m_sorted = v[order], dt[order], m_eff[order]

    delta = np.zeros(size)
    v_half = v_sorted.copy()
    elastic, dashpot = np.zeros(size), np.zeros(size)
    compliance = dt_sorted / m_sorted
    area = np.zeros(size)
    deltas, forces = [], []
    for _ in range(max_steps):
        # No other force acts, so the free central rate is v_{n-1/2} itself.
        fill_force_terms(blocks, delta, v_half, v_sorted, elastic, dashpot)
        force = np.where(delta > 0, implicit_force(elastic, dashpot, v_half, compliance), 0.0)
        deltas.append(delta.copy())
        forces.append(force.copy())
        v_next = v_half - dt_sorted * force / m_sorted
        area += force * 0.5 * (v_half + v_next) * dt_sorted
        delta = delta + dt_sorted * v_next
        v_half = v_next
        # Separated: out of contact and moving apart (F can no longer act), or restitution
        # force floored at zero for good (the laws' damping factor cannot recover).
        if np.all((v_half < 0) & ((delta <= 0) | (force == 0))):
            break
    else:
        raise EngineError(f"two_body: contact did not end within {max_steps} steps")
    deltas.append(delta.copy())
    forces.append(np.zeros(size))

    inverse = np.argsort(order)
    v_out = -v_half[inverse]
    return TwoBodyResult(
        peak_force=np.max(forces, axis=0)[inverse],
        peak_indentation=np.max(deltas, axis=0)[inverse],
        cor=v_out / v,
        dissipated_energy=0.5 * m_eff * (v**2 - v_out**2),
        hysteresis_area=area[inverse],
        expected_energy_loss=expected_loss,
        dt=dt,
        indentation=np.array(deltas).T[inverse],
        force=np.array(forces).T[inverse],
    )
