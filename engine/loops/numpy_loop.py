"""The NumPy time loop: the scheme of engine/scheme.py vectorised over the batch, the readable
reference of the compiled loop (numba_loop.py), needing no compiler.

Every step is a fixed number of array operations over all members. Members are sorted by
impact law first, so that each law's `force_terms` runs on a contiguous block; the results
come back in batch order. The physics is not written here: the laws' `force_terms`, the
isolator's return mapping, `implicit_force` and `onset_weight` are called as they are.
"""
from __future__ import annotations

import numpy as np

from ..building import BuildingArrays
from ..impact.contact import fill_force_terms, law_blocks
from ..results import MODE, empty_collapse, empty_peaks, residuals
from ..scheme import implicit_force, onset_weight, step_operators
from ..stories.registry import BY_CODE as STORY_LAWS_BY_CODE
from .layout import linear_story_shear
from .numpy_isolators import IsolatorBatch


def ground_motion(accel, accel_dt: float, dt: float, n_steps: int) -> np.ndarray:
    """The record (m/s^2 every accel_dt s) linearly interpolated onto n_steps steps of dt."""
    return np.interp(np.arange(n_steps) * dt, np.arange(accel.size) * accel_dt, accel)


def run_simulation(ag, dt, arrays: BuildingArrays, contact, history, progress, scale):
    """engine.simulate's time loop: (peaks dict, history dict or None), in batch order.

    ag (N,) m/s^2 on the step grid; arrays and contact: B members in batch order; history:
    engine.History or None; progress: callable(step, n_steps) or None; scale (B,).
    """
    order, blocks = law_blocks(contact)
    inverse = np.argsort(order)
    contact, arrays, scale = contact[order], arrays.take(order), scale[order]
    hist_members = None if history is None else inverse[np.asarray(history.members, dtype=int)]
    peaks, hist = _time_loop(ag, dt, arrays, contact.clear_gap, blocks, hist_members,
                             None if history is None else history.every, progress, scale)
    peaks = {name: value[inverse] for name, value in peaks.items()}
    if hist is not None:
        hist["members"] = np.asarray(history.members, dtype=int)
    return peaks, hist


def _time_loop(ag, dt, b: BuildingArrays, gap, blocks, hist_members, hist_every, progress,
               scale):
    """The NumPy reference: every step is a fixed number of array operations over the batch."""
    size = b.masses.shape[0]
    mass = b.masses
    step_op, wall_response, compliance = step_operators(b, dt)

    n_levels = mass.shape[1]
    u = np.zeros((size, n_levels))
    v_half = np.zeros((size, n_levels))
    rhs = np.zeros((size, 2 * n_levels))  # [p - f(u_n), v_{n-1/2}]
    chain = np.zeros((size, n_levels + 1))  # forces in isolator, stories 1..N, free end
    isolators = IsolatorBatch(b)
    # Nonlinear stories: each member's law (its `force`, called story by story: the law's
    # physics as written, for scalars) on its own copy of the initial state.
    state = b.story_state.copy()
    nonlinear = [(m, STORY_LAWS_BY_CODE[b.story_code[m]].force)
                 for m in np.flatnonzero(~b.story_linear)]
    collapse = empty_collapse(size)
    collapsed, collapse_time = collapse["collapsed"], collapse["collapse_time"]
    elastic = np.zeros(size)
    dashpot = np.zeros(size)
    v_imp = np.ones(size)
    delta_prev = np.zeros(size)
    in_contact = np.zeros(size, dtype=bool)
    no_force = np.zeros(size)  # read only

    peaks = empty_peaks(size, n_levels)
    peak_accel, peak_drift = peaks["peak_total_accel"], peaks["peak_interstory_drift"]
    peak_iso, max_indent = peaks["peak_isolator_disp"], peaks["max_indentation"]
    max_force, n_impacts = peaks["max_impact_force"], peaks["n_impacts"]
    energy = peaks["impact_energy"]
    peak_fiso, peak_shear = peaks["peak_isolator_force"], peaks["peak_story_shear"]
    peak_velocity = peaks["peak_floor_velocity"]

    n_steps = ag.size
    hist = None
    if hist_members is not None:
        n_out = (n_steps - 1) // hist_every + 1
        m_out = hist_members.size
        hist = {"time": np.arange(n_out) * hist_every * dt,
                "isolator_disp": np.zeros((m_out, n_out)),
                "total_accel": np.zeros((m_out, n_out, n_levels)),
                "impact_force": np.zeros((m_out, n_out)),
                "indentation": np.zeros((m_out, n_out)),
                "isolator_force": np.zeros((m_out, n_out))}
    report_every = max(n_steps // 100, 1)

    for step in range(n_steps):
        drift = np.diff(u, axis=1)
        # The isolator past its capacity, a story past its collapse drift, or a state no
        # longer finite ends the run: the member is set at rest, unshaken, from this step on,
        # its peaks those of the steps before.
        mode = collapse_modes(np.abs(u[:, :1]), b.isolator_capacity, np.abs(drift),
                              b.collapse_drift)
        fallen = (mode > 0) & ~collapsed
        if fallen.any():
            collapsed |= fallen
            collapse_time[fallen] = step * dt
            collapse["collapse_mode"][fallen] = mode[fallen]
            scale = np.where(collapsed, 0.0, scale)
            for array in (u, v_half):
                array[fallen] = 0.0
            isolators.reset(fallen)
            drift = np.diff(u, axis=1)
        a = ag[step] * scale  # (B,): x 1.0 is exact, unscaled members are unchanged
        u0 = u[:, 0]
        # Structure without wall force this step: p - f and the free velocities.
        chain[:, 0] = isolators.force(u0)
        np.multiply(b.story_k, drift, out=chain[:, 1:n_levels])
        for m, force in nonlinear:  # the law's force, less what P-Delta takes
            if not collapsed[m]:
                for i in range(n_levels - 1):
                    chain[m, i + 1] = force(drift[m, i], state[m, i], b.story_fields[m, i]) \
                        - b.story_gravity[m, i] * drift[m, i]
            else:
                chain[m, 1:n_levels] = 0.0
        np.subtract(chain[:, 1:], chain[:, :-1], out=rhs[:, :n_levels])
        rhs[:, :n_levels] -= mass * a[:, None]
        rhs[:, n_levels:] = v_half
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
        force = no_force  # most steps nobody touches: the laws need not run
        if touching.any():
            rate_free = side * 0.5 * (v_half[:, 0] + v_next[:, 0])
            fill_force_terms(blocks, delta, rate_free, v_imp, elastic, dashpot)
            # A dashpot that is already loaded at first touch (Kelvin-Voigt) would push for
            # the whole step; weight it by the part after the touch (impact.onset_weight).
            np.multiply(dashpot, onset_weight(delta, delta_prev), out=dashpot, where=new)
            force = np.where(touching, implicit_force(elastic, dashpot, rate_free, compliance),
                             0.0)
            v_next -= wall_response * (side * force)[:, None]
        delta_prev = delta

        total_accel = (v_next - v_half) / dt + a[:, None]
        np.maximum(peak_accel, np.abs(total_accel), out=peak_accel)
        np.maximum(peak_drift, np.abs(drift), out=peak_drift)
        np.maximum(peak_velocity, np.abs(v_next), out=peak_velocity)
        if nonlinear:  # the law's shear, P-Delta's share given back (linear: at the end)
            np.maximum(peak_shear, np.abs(chain[:, 1:n_levels] + b.story_gravity * drift),
                       out=peak_shear)
        np.maximum(peak_iso, np.abs(u0), out=peak_iso)
        np.maximum(peak_fiso, np.abs(chain[:, 0]), out=peak_fiso)
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
            hist["isolator_force"][:, k] = chain[hist_members, 0]

        # Advance: the isolator law's state after this step, at its velocity.
        isolators.advance(v_next[:, 0], dt)
        v_half = v_next
        u = u + dt * v_next
        if progress is not None and step % report_every == 0:
            progress(step, n_steps)
    if progress is not None:
        progress(n_steps, n_steps)

    linear_story_shear(peaks, b)  # the linear stories' from their drifts
    return {**peaks, **collapse, **residuals(u, collapsed)}, hist


def collapse_modes(isolator, capacity, story, collapse_drift) -> np.ndarray:
    """(B,) the collapse mode (results.MODE) of each member at this step, 0 where none: the
    highest of isolator capacity where a bearing's displacement `isolator` (B, n) (m, or its
    square) passes `capacity` (B,), story drift where a story's `story` (B, N) passes
    `collapse_drift` (B, N), and numerical instability where a measure that fails is not
    finite (NaN fails every comparison): compiled.failed's rule, member by member."""
    iso_ok, story_ok = isolator <= capacity[:, None], story <= collapse_drift
    if iso_ok.all() and story_ok.all():  # most steps: nobody fails (a third of the loop's time)
        return np.zeros(len(isolator), dtype=np.int8)
    iso_past, story_past = ~iso_ok, ~story_ok
    unstable = np.any(iso_past & ~np.isfinite(isolator), axis=1) \
        | np.any(story_past & ~np.isfinite(story), axis=1)
    mode = np.where(np.any(iso_past, axis=1), MODE.isolator_capacity,
                    np.where(np.any(story_past, axis=1), MODE.story_drift, 0))
    return np.where(unstable, MODE.numerical_instability, mode).astype(np.int8)


def run_two_body(contact, v, dt, m_eff, max_steps):
    """engine.two_body's loop: every member from first touch until all have separated.

    contact, v (m/s), dt (s), m_eff (kg): B members. Returns (steps run, or None if some
    member had not separated after max_steps; out (B, 4): hysteresis area J, final half-step
    velocity m/s, peak force N, peak indentation m; indentation (B, T) m; force (B, T) N).
    """
    order, blocks = law_blocks(contact)
    v_sorted, dt_sorted, m_sorted = v[order], dt[order], m_eff[order]
    size = len(contact)

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
        return None, None, None, None
    deltas.append(delta.copy())
    forces.append(np.zeros(size))

    inverse = np.argsort(order)
    out = np.column_stack([area, v_half, np.max(forces, axis=0), np.max(deltas, axis=0)])
    return (len(deltas) - 1, out[inverse], np.array(deltas).T[inverse],
            np.array(forces).T[inverse])
