"""The NumPy time loop of buildings that twist: every level a rigid diaphragm with (u_x, u_y,
theta) at its plan's centre, on bearings where they stand, against the rectangular moat at its
contact points (engine/torsion.py: the model).

The scheme is the planar one (engine/scheme.py) on the 3L degrees of freedom: the mass matrix
couples a level's translations and rotation where its mass centre is eccentric, the step
operator is inverted once per member (scheme.step_operators' rule on full matrices). What
the step adds to numpy_plan.py's:
- the isolation's force is the sum of its bearings', each the isolator law in plan with its
  share of the weight (numpy_isolators.IsolatorBatch) at the bearing's own displacement
  (u_x - theta Y, u_y + theta X) and velocity, with its moment about the plan's centre;
- the moat is P contact points (torsion.ContactPoints), each its wall's law times its share;
  the points touching at a step are solved together, exactly: their forces F >= 0 satisfy
  (I + D G / 2) F = E + D r_free on the points that push (E, D the laws' elastic force and
  dashpot, r_free the central indentation rates without contact force, G_pq = g_p' R g_q the
  level-0 response of point p's rate to point q's force), a point whose force would pull
  dropped and the rest solved again: one point alone is scheme.implicit_force exactly, and two
  corners of a slab that does not turn sum to the plan's one wall;
- friction along the walls (mu_wall > 0) is numpy_plan's implicit Coulomb solve point by point,
  in the points' order, each with its own normal force and the compliance along its tangent.
Peaks are those of a run in plan at the plan's centre, with the corners', the slab's rotation
and each point's force and indentation (results.TORSION_PEAKS).
"""
from __future__ import annotations

import numpy as np

from ..building import BuildingArrays
from ..impact.contact import fill_force_terms, law_blocks
from ..results import (
    PEAKS,
    PLAN_PEAKS,
    TORSION_PEAKS,
    WALLS,
    empty_collapse,
    empty_plan_history,
    residuals,
)
from ..scheme import full_step_operator, onset_weight
from ..torsion import CORNERS, ContactPoints, TorsionArrays, corner_orbits, point_laws
from .numpy_isolators import IsolatorBatch
from .numpy_loop import collapse_modes
from .numpy_plan import raise_peak


def step_operators(t: TorsionArrays, dt: float):
    """The scheme's (B, 3L, 6L) step operator on the full matrices, and its first three
    columns, the (B, 3L, 3) wall response: the velocity change of every degree of freedom per
    unit generalised force on the slab (N along x and y, N m about z)."""
    step_op = full_step_operator(t.mass, t.damping, dt)
    return step_op, step_op[:, :, :3].copy()


class _Points:
    """The contact state of the points of one axis' walls (x or y) for the batch: their laws
    (the wall's Contact times each point's share, flattened member by member) sorted into
    law blocks, gaps, impact velocities, previous indentations and contact flags (B, Pa)."""

    def __init__(self, columns, contact, flat):
        self.columns = columns
        size, n = len(contact), columns.size
        self.order, self.blocks = law_blocks(flat)
        self.inverse = np.argsort(self.order)
        self.gap = np.repeat(contact.clear_gap, n).reshape(size, n)
        self.shape = (size, n)
        self.v_imp = np.ones(self.shape)
        self.delta_prev = np.zeros(self.shape)
        self.in_contact = np.zeros(self.shape, dtype=bool)

    def terms(self, delta, rate_free, new):
        """(elastic N, dashpot N s/m) of every point (B, Pa), the dashpot weighted at a new
        contact (scheme.onset_weight)."""
        o, i = self.order, self.inverse
        elastic, dashpot = np.zeros(delta.size), np.zeros(delta.size)
        fill_force_terms(self.blocks, delta.ravel()[o], rate_free.ravel()[o],
                         self.v_imp.ravel()[o], elastic, dashpot)
        elastic, dashpot = elastic[i].reshape(self.shape), dashpot[i].reshape(self.shape)
        return elastic, np.where(new, dashpot * onset_weight(delta, self.delta_prev), dashpot)


def solve_contacts(elastic, dashpot, rate_free, touching, coupling):
    """(B, P) contact forces (N, >= 0) of the points touching: (I + D G / 2) F = E + D r on
    the points that push, the others at 0 (module docstring); coupling G (B, P, P) m/s/N."""
    size, n = elastic.shape
    active = touching.copy()
    eye = np.eye(n)
    force = np.zeros_like(elastic)
    for _ in range(n):
        a = np.where(active[:, :, None], eye + 0.5 * dashpot[:, :, None] * coupling, eye)
        a = np.where(active[:, None, :] | eye.astype(bool), a, 0.0)
        rhs = np.where(active, elastic + dashpot * rate_free, 0.0)
        force = np.linalg.solve(a, rhs[:, :, None])[:, :, 0]
        pulling = active & (force < 0)
        if not pulling.any():
            break
        active &= ~pulling
    return np.where(active, np.maximum(force, 0.0), 0.0)


def run_torsion(ag, dt, b: BuildingArrays, t: TorsionArrays, contacts, points: ContactPoints,
                progress, scale, angle, history=None, mu_wall=None):
    """engine.simulate's loop for buildings that twist: (peaks: PEAKS at the plan's centre,
    PLAN_PEAKS, TORSION_PEAKS; history dict or None).

    ag (N, 2) m/s^2 on the step grid; b, t: the members' arrays (B members, L levels);
    contacts (x walls, y walls); points: the moat's contact points; scale (B,); angle (B,)
    rad; history: engine.History or None (results.TORSION_HISTORIES); mu_wall: None or (B,).
    """
    size, n_levels = b.masses.shape
    n_points = points.wall.size
    step_op, respond = step_operators(t, dt)
    r0 = respond[:, :3, :]  # the slab's own response (B, 3, 3)
    g, tangent = points.direction, points.tangent
    coupling = np.einsum("bpi,bij,bqj->bpq", g, r0, g)
    tangent_compliance = np.einsum("bpi,bij,bpj->bp", tangent, r0, tangent)
    walls = [_Points(*laws) for laws in point_laws(contacts, points)]
    wall_columns = [np.flatnonzero(points.wall == w) for w in range(len(WALLS["rectangular"]))]
    bearing_x, bearing_y = t.bearings[..., 0], t.bearings[..., 1]
    n_bearings = bearing_x.shape[1]
    isolators = IsolatorBatch(b, plan=True, bearings=n_bearings)  # each bearing its share
    corners = np.array(CORNERS) * t.plan[:, None, :] / 2  # (B, 4, 2)
    cos, sin = np.cos(angle) * scale, np.sin(angle) * scale

    u = np.zeros((size, n_levels, 3))
    v_half = np.zeros((size, n_levels, 3))
    chain = np.zeros((size, n_levels + 1, 3))
    collapse = empty_collapse(size)
    peaks = {q.name: np.zeros((size, *q.trailing_shape(n_levels, len(WALLS["rectangular"]),
                                                       n_points)), dtype=q.dtype)
             for q in (*PEAKS, *PLAN_PEAKS, *TORSION_PEAKS)}
    touching_axis = np.zeros((size, 2), dtype=bool)
    n_steps = ag.shape[0]
    hist, rows = None, None
    if history is not None:
        rows = np.asarray(history.members, dtype=int) % size
        hist = empty_plan_history(rows.size, n_steps, history.every, dt, n_levels, torsion=True)
    report_every = max(n_steps // 100, 1)
    # the limits squared once: the step compares squared magnitudes (no root per step)
    capacity_square, collapse_square = b.isolator_capacity**2, b.collapse_drift**2
    for step in range(n_steps):
        drift = np.diff(u, axis=1)
        # numpy_plan.py's rule, on each bearing's displacement and the drift of the plan's
        # centre
        ux = u[:, :1, 0] - u[:, :1, 2] * bearing_y
        uy = u[:, :1, 1] + u[:, :1, 2] * bearing_x
        mode = collapse_modes(ux * ux + uy * uy, capacity_square,
                              drift[..., 0] * drift[..., 0] + drift[..., 1] * drift[..., 1],
                              collapse_square)
        fallen = (mode > 0) & ~collapse["collapsed"]
        if fallen.any():
            collapse["collapsed"] |= fallen
            collapse["collapse_time"][fallen] = step * dt
            collapse["collapse_mode"][fallen] = mode[fallen]
            cos, sin = (np.where(collapse["collapsed"], 0.0, x) for x in (cos, sin))
            for array in (u, v_half):
                array[fallen] = 0.0
            isolators.reset(fallen)
            drift = np.diff(u, axis=1)
        a = np.column_stack([cos * ag[step, 0] - sin * ag[step, 1],
                             sin * ag[step, 0] + cos * ag[step, 1]])
        u0 = u[:, 0]
        # The bearings at their own displacements, their forces and moments on the slab.
        f_bx, f_by = isolators.force_xy(u0[:, :1] - u0[:, 2:] * bearing_y,
                                        u0[:, 1:2] + u0[:, 2:] * bearing_x)
        chain[:, 0] = np.column_stack([f_bx.sum(axis=1), f_by.sum(axis=1),
                                       (bearing_x * f_by - bearing_y * f_bx).sum(axis=1)])
        chain[:, 1:n_levels] = story_forces(t.story_k, t.story_centre, drift)
        rhs = (chain[:, 1:] - chain[:, :-1]).reshape(size, -1) - np.einsum("bid,bd->bi",
                                                                           t.load, a)
        v_next = np.einsum("bij,bj->bi", step_op,
                           np.concatenate([rhs, v_half.reshape(size, -1)], axis=1))

        # The moat: every point's indentation, the touching ones solved together.
        v_prev0, v_free0 = v_half[:, 0], v_next[:, :3]
        distance = np.einsum("bpi,bi->bp", g, u0)
        rate_before = np.einsum("bpi,bi->bp", g, v_prev0)
        rate_free = np.einsum("bpi,bi->bp", g, 0.5 * (v_prev0 + v_free0))
        delta = np.zeros((size, n_points))
        elastic, dashpot = np.zeros((size, n_points)), np.zeros((size, n_points))
        touching = np.zeros((size, n_points), dtype=bool)
        new = np.zeros((size, n_points), dtype=bool)
        for wall in walls:
            axis = int(points.axis[wall.columns[0]])
            c = wall.columns
            d = np.maximum(distance[:, c] - wall.gap, -1.0)
            on = d > 0
            fresh = on & ~wall.in_contact
            wall.v_imp = np.where(fresh, rate_before[:, c], wall.v_imp)
            if on.any():  # most steps nobody touches: the laws need not run
                elastic[:, c], dashpot[:, c] = wall.terms(d, rate_free[:, c], fresh)
            wall.in_contact, wall.delta_prev = on, d
            delta[:, c], touching[:, c], new[:, c] = d, on, fresh
            axis_on = on.any(axis=1)
            peaks["n_impacts"] += axis_on & ~touching_axis[:, axis]
            touching_axis[:, axis] = axis_on
        force = np.zeros((size, n_points))
        if touching.any():
            force = solve_contacts(elastic, dashpot, rate_free, touching, coupling)
        push = -np.einsum("bp,bpi->bi", force, g)  # the walls' generalised force on the slab
        if touching.any():
            v_next += np.einsum("bij,bj->bi", respond, push)
            if mu_wall is not None:
                for p in range(n_points):
                    slip = np.einsum("bi,bi->b", tangent[:, p], v_next[:, :3])
                    limit = mu_wall * force[:, p]
                    friction = np.clip(-slip / tangent_compliance[:, p], -limit, limit)
                    along = friction[:, None] * tangent[:, p]
                    v_next += np.einsum("bij,bj->bi", respond, along)
                    push += along
        peaks["impact_energy"] -= np.sum(push * (v_prev0 + v_next[:, :3]), axis=1) * (0.5 * dt)
        _contact_peaks(peaks, wall_columns, force, delta)

        v_next = v_next.reshape(size, n_levels, 3)
        total_accel = (v_next[..., :2] - v_half[..., :2]) / dt + a[:, None, :]
        corner = corner_orbits(u0[:, None, :2], u0[:, None, 2], corners)
        if hist is not None and step % history.every == 0:
            k = step // history.every
            hist["isolator_disp"][:, k] = u0[rows, :2]
            hist["total_accel"][:, k] = total_accel[rows]
            hist["impact_force"][:, k] = np.hypot(push[rows, 0], push[rows, 1])
            hist["indentation"][:, k] = np.maximum(delta[rows].max(axis=1, initial=-1.0), 0.0)
            hist["floor_disp"][:, k] = u[rows, :, :2]
            hist["floor_rotation"][:, k] = u[rows, :, 2]
            hist["isolator_force"][:, k] = chain[rows, 0, :2]
        raise_peak(peaks, "peak_total_accel", total_accel)
        raise_peak(peaks, "peak_floor_velocity", v_next[..., :2], directions=False)
        raise_peak(peaks, "peak_isolator_force", chain[:, 0, :2], directions=False)
        raise_peak(peaks, "peak_story_shear", chain[:, 1:n_levels, :2], directions=False)
        raise_peak(peaks, "peak_interstory_drift", drift[..., :2])
        raise_peak(peaks, "peak_isolator_disp", u0[:, :2])
        np.maximum(peaks["peak_corner_disp"], np.sqrt(np.sum(corner * corner, axis=-1)).max(
            axis=1), out=peaks["peak_corner_disp"])
        np.maximum(peaks["peak_rotation"], np.abs(u0[:, 2]), out=peaks["peak_rotation"])

        # Advance: each bearing's isolator law with its own velocity.
        v0 = v_next[:, 0]
        isolators.advance_xy(v0[:, :1] - v0[:, 2:] * bearing_y,
                             v0[:, 1:2] + v0[:, 2:] * bearing_x, dt)
        v_half = v_next
        u = u + dt * v_next
        if progress is not None and step % report_every == 0:
            progress(step, n_steps)
    if progress is not None:
        progress(n_steps, n_steps)
    if hist is not None:
        hist["members"] = np.asarray(history.members, dtype=int)
    return {**peaks, **collapse, **residuals(u[..., :2], collapse["collapsed"])}, hist


def story_forces(story_k, centre, drift):
    """(B, L - 1, 3) the stories' forces and moments about the plans' centres (N, N m) at
    drifts (B, L - 1, 3) (m, m, rad): the springs at their centres of stiffness (B, L - 1, 2)
    m (engine/torsion.py); a centre at the plan's adds exact zeros (the same bits)."""
    x_s, y_s = centre[..., 0], centre[..., 1]
    f_x = story_k[..., 0] * (drift[..., 0] - drift[..., 2] * y_s)
    f_y = story_k[..., 1] * (drift[..., 1] + drift[..., 2] * x_s)
    moment = story_k[..., 2] * drift[..., 2] + x_s * f_y - y_s * f_x
    return np.stack([f_x, f_y, moment], axis=-1)


def _contact_peaks(peaks, wall_columns, force, delta):
    """Raise the moat's peaks with this step's point forces and indentations (B, P): each
    point's, each wall's sum (wall_columns: each wall's points), the largest wall sum and the
    deepest indentation."""
    np.maximum(peaks["max_point_force"], force, out=peaks["max_point_force"])
    np.maximum(peaks["max_point_indentation"], delta, out=peaks["max_point_indentation"])
    np.maximum(peaks["max_indentation"], delta.max(axis=1), out=peaks["max_indentation"])
    per_wall = np.stack([force[:, columns].sum(axis=1) for columns in wall_columns], axis=1)
    np.maximum(peaks["max_impact_force_wall"], per_wall, out=peaks["max_impact_force_wall"])
    np.maximum(peaks["max_impact_force"], per_wall.max(axis=1), out=peaks["max_impact_force"])

