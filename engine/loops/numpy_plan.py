"""The NumPy time loop in plan: the building moving in both horizontal directions under a pair
of record components, on coupled isolators, against a rectangular or circular moat.

The scheme is the planar one (engine/scheme.py) applied to each direction: the state carries a
last axis of directions (x, y; room for a rotation later). The building has its step operator
along x and, when its stories differ along y (Building.story_stiffness_y), another along y;
either way a force along x moves nothing along y. What couples the directions:
- the isolator law in plan (its force_xy and advance_xy: the bilinear and friction pendulum
  laws' slip element with a circular yield surface and the exact radial return, the friction
  pendulum's limit at the sliding speed |v|) and the yielding stories' slip elements, with
  isolators/hysteresis.radial_return;
- the moat: a rectangular one is two walls per axis, at +-clear gap along x (contact) and
  along y (contact_y), a corner loading both; a circular one pushes along the slab's radial
  direction n = u0 / |u0| with the radial indentation |u0| - clear gap. Every impact law acts
  along the wall's normal as in the planar loop, with the same implicit solve: the operator's
  response along n to a force along n is the compliance along n (c_x n_x^2 + c_y n_y^2, the
  planar compliance for an isotropic building);
- friction between slab and wall (mu_wall > 0): while a wall pushes with normal force N, a
  tangential force T along the wall, |T| <= mu_wall N, solved implicitly like the normal one
  (backward Euler on Coulomb's law): the force that stops the slab's tangential velocity at the
  end of the step if it is within the cone (stick), else mu_wall N against that velocity
  (slide). It cannot reverse the sliding, so it never chatters. At a corner the x wall's
  friction acts along y after the y wall's normal force, and conversely.
A motion along x alone gives the planar loop's numbers to rounding.
"""
from __future__ import annotations

import numpy as np

from ..building import BuildingArrays
from ..impact.contact import fill_force_terms, law_blocks
from ..isolators.hysteresis import radial_return
from ..results import (
    DIRECTIONS,
    PEAKS,
    PLAN_PEAKS,
    WALLS,
    empty_collapse,
    empty_plan_history,
    residuals,
)
from ..scheme import implicit_force, onset_weight, step_operators
from ..stories.registry import BY_CODE as STORY_LAWS_BY_CODE
from .layout import linear_story_shear
from .numpy_isolators import IsolatorBatch
from .numpy_loop import collapse_modes


def ground_motion(accel, accel_dt: float, dt: float, n_steps: int) -> np.ndarray:
    """(n_steps, 2) m/s^2: both components linearly interpolated onto the step grid."""
    t, t_rec = np.arange(n_steps) * dt, np.arange(accel.shape[0]) * accel_dt
    return np.column_stack([np.interp(t, t_rec, accel[:, d]) for d in range(accel.shape[1])])


class _Wall:
    """The contact state of one wall direction (an axis of the rectangular moat, or the
    circular moat's radial direction) for the sorted batch."""

    def __init__(self, contact, size: int):
        self.order, self.blocks = law_blocks(contact)
        self.inverse = np.argsort(self.order)
        self.gap = contact.clear_gap[self.order]
        self.elastic, self.dashpot = np.zeros(size), np.zeros(size)
        self.v_imp = np.ones(size)
        self.delta_prev = np.zeros(size)
        self.in_contact = np.zeros(size, dtype=bool)

    def force(self, distance, rate_before, rate_free, compliance):
        """Contact force (N, >= 0) for the members at `distance` from the centre (m, >= 0),
        approaching at rate_before (the half-step velocity towards the wall, m/s) and at the
        free central rate rate_free; also (indentation m, new contact bool). Arrays in batch
        order."""
        o = self.order
        # Separations beyond 1 m never matter; the clamp keeps wall-less members finite.
        delta = np.maximum(distance[o] - self.gap, -1.0)
        touching = delta > 0
        new = touching & ~self.in_contact
        self.v_imp = np.where(new, rate_before[o], self.v_imp)
        self.in_contact = touching
        force = np.zeros_like(delta)
        if touching.any():  # most steps nobody touches: the laws need not run
            fill_force_terms(self.blocks, delta, rate_free[o], self.v_imp, self.elastic,
                             self.dashpot)
            np.multiply(self.dashpot, onset_weight(delta, self.delta_prev), out=self.dashpot,
                        where=new)
            force = np.where(touching, implicit_force(self.elastic, self.dashpot,
                                                      rate_free[o], compliance[o]), 0.0)
        self.delta_prev = delta
        i = self.inverse
        return force[i], delta[i], new[i]


def run_plan(ag, dt, b: BuildingArrays, contacts, moat: str, progress, scale, angle,
             history=None, b_y: BuildingArrays | None = None, mu_wall=None):
    """engine.simulate's loop in plan: (peaks: PEAKS as resultants, then PLAN_PEAKS; history
    dict or None).

    ag (N, 2) m/s^2 on the step grid (x, y); b: B members; contacts: (x walls, y walls) for a
    rectangular moat, (radial wall,) for a circular one; scale (B,); angle (B,) rad, rotating
    each member's ground motion counterclockwise; history: engine.History or None (the
    histories in plan: results.plan_history); b_y: the members along y when their stories
    differ along y (None: b both ways); mu_wall: None (frictionless walls) or (B,) slab-wall
    friction coefficients.
    """
    size, n_levels = b.masses.shape
    mass = b.masses
    step_op, wall_response, compliance = step_operators(b, dt)
    if b_y is None:
        story_k = b.story_k[:, :, None]
        respond = wall_response[:, :, None]
        comp_xy = np.column_stack([compliance, compliance])
    else:
        op_y, response_y, compliance_y = step_operators(b_y, dt)
        story_k = np.stack([b.story_k, b_y.story_k], axis=-1)
        respond = np.stack([wall_response, response_y], axis=-1)
        comp_xy = np.column_stack([compliance, compliance_y])
    cos, sin = np.cos(angle) * scale, np.sin(angle) * scale
    walls = [_Wall(c, size) for c in contacts]

    n_dir = len(DIRECTIONS)
    u = np.zeros((size, n_levels, n_dir))
    v_half = np.zeros((size, n_levels, n_dir))
    rhs = np.zeros((size, 2 * n_levels, n_dir))
    chain = np.zeros((size, n_levels + 1, n_dir))
    isolators = IsolatorBatch(b, plan=True)
    f_story = np.zeros((size, n_levels - 1, n_dir))
    yields = b.story_yields
    any_yields = bool(yields.any())
    collapse = empty_collapse(size)
    # Stories of a uniaxial law: the law along x and along y (uncoupled), each with its state.
    state = np.repeat(b.story_state[:, :, None, :], n_dir, axis=2)
    uniaxial = [(m, STORY_LAWS_BY_CODE[b.story_code[m]].force)
                for m in np.flatnonzero(b.story_uniaxial)]
    # Linear stories alike along x and y: their shears from their drifts at the end.
    keep_shear = b_y is not None or not bool(np.all(b.story_linear))

    peaks = {q.name: np.zeros((size, *q.trailing_shape(n_levels, len(WALLS[moat]))),
                              dtype=q.dtype) for q in (*PEAKS, *PLAN_PEAKS)}
    n_steps = ag.shape[0]
    hist, rows = None, None
    if history is not None:
        rows = np.asarray(history.members, dtype=int) % size
        hist = empty_plan_history(rows.size, n_steps, history.every, dt, n_levels)
    report_every = max(n_steps // 100, 1)
    # the limits squared once: the step compares squared magnitudes (no root per step)
    capacity_square, collapse_square = b.isolator_capacity**2, b.collapse_drift**2
    for step in range(n_steps):
        # The member's ground motion: the pair rotated by its angle, times its scale.
        drift = np.diff(u, axis=1)
        # The isolator or a story's drift vector past its limit, or a state no longer finite,
        # ends the run: the member is set at rest, unshaken (numpy_loop.py's rule, squared).
        mode = collapse_modes(u[:, :1, 0] * u[:, :1, 0] + u[:, :1, 1] * u[:, :1, 1],
                              capacity_square,
                              drift[..., 0] * drift[..., 0] + drift[..., 1] * drift[..., 1],
                              collapse_square)
        fallen = (mode > 0) & ~collapse["collapsed"]
        if fallen.any():
            collapse["collapsed"] |= fallen
            collapse["collapse_time"][fallen] = step * dt
            collapse["collapse_mode"][fallen] = mode[fallen]
            cos, sin = (np.where(collapse["collapsed"], 0.0, x) for x in (cos, sin))
            for array in (u, v_half, f_story):
                array[fallen] = 0.0
            isolators.reset(fallen)
            drift = np.diff(u, axis=1)
        a = np.column_stack([cos * ag[step, 0] - sin * ag[step, 1],
                             sin * ag[step, 0] + cos * ag[step, 1]])
        u0 = u[:, 0]
        chain[:, 0, 0], chain[:, 0, 1] = isolators.force_xy(u0[:, 0], u0[:, 1])
        chain[:, 1:n_levels] = story_k * drift
        if any_yields:
            chain[yields, 1:n_levels] = (b.story_k_post[yields][:, :, None] * drift[yields]
                                         + f_story[yields])
        for m, force in uniaxial:  # the law's force, less what P-Delta takes
            for i in range(n_levels - 1):
                for e in range(n_dir):
                    chain[m, i + 1, e] = 0.0 if collapse["collapsed"][m] else \
                        force(drift[m, i, e], state[m, i, e], b.story_fields[m, i]) \
                        - b.story_gravity[m, i] * drift[m, i, e]
        rhs[:, :n_levels] = chain[:, 1:] - chain[:, :-1] - mass[:, :, None] * a[:, None, :]
        rhs[:, n_levels:] = v_half
        if b_y is None:
            v_next = np.einsum("bij,bjd->bid", step_op, rhs)
        else:
            v_next = np.stack([np.einsum("bij,bj->bi", step_op, rhs[..., 0]),
                               np.einsum("bij,bj->bi", op_y, rhs[..., 1])], axis=-1)

        wall_force = np.zeros((size, n_dir))  # on the slab, towards the centre
        step_delta = np.full(size, -1.0)  # the deepest indentation this step
        normals = []  # per wall direction: its normal force (B,) and unit normal (B, 2)
        if moat == "rectangular":
            for d, wall in enumerate(walls):
                side = np.sign(u0[:, d])
                force, delta, new = wall.force(
                    np.abs(u0[:, d]), side * v_half[:, 0, d],
                    side * 0.5 * (v_half[:, 0, d] + v_next[:, 0, d]), comp_xy[:, d])
                wall_force[:, d] = -side * force
                normals.append((force, np.eye(2)[d] * np.where(side < 0, -1.0, 1.0)[:, None]))
                step_delta = np.maximum(step_delta, delta)
                _wall_peaks(peaks, force, delta, new, np.where(side > 0, 2 * d, 2 * d + 1))
        else:
            radius = np.hypot(u0[:, 0], u0[:, 1])
            normal = np.where(radius[:, None] > 0, u0 / np.maximum(radius, 1e-300)[:, None],
                              np.array([1.0, 0.0]))
            central = 0.5 * (v_half[:, 0] + v_next[:, 0])
            along = compliance if b_y is None else np.sum(comp_xy * normal**2, axis=1)
            force, delta, new = walls[0].force(
                radius, np.sum(normal * v_half[:, 0], axis=1), np.sum(normal * central, axis=1),
                along)
            wall_force = -normal * force[:, None]
            step_delta = delta
            normals.append((force, normal))
            _wall_peaks(peaks, force, delta, new, np.zeros(size, dtype=int))
        v_next += respond * wall_force[:, None, :]
        if mu_wall is not None:
            for force, normal in normals:
                wall_force += _friction(v_next, respond, comp_xy, mu_wall * force, normal)
        # Work on the walls over this step, with the central velocity of level 0.
        peaks["impact_energy"] -= np.sum(wall_force * (v_half[:, 0] + v_next[:, 0]),
                                         axis=1) * (0.5 * dt)

        total_accel = (v_next - v_half) / dt + a[:, None, :]
        if hist is not None and step % history.every == 0:
            k = step // history.every
            hist["isolator_disp"][:, k] = u0[rows]
            hist["total_accel"][:, k] = total_accel[rows]
            hist["impact_force"][:, k] = np.hypot(wall_force[rows, 0], wall_force[rows, 1])
            hist["indentation"][:, k] = np.maximum(step_delta[rows], 0.0)
            hist["isolator_force"][:, k] = chain[rows, 0]
        raise_peak(peaks, "peak_total_accel", total_accel)
        raise_peak(peaks, "peak_interstory_drift", drift)
        raise_peak(peaks, "peak_isolator_disp", u0)
        raise_peak(peaks, "peak_floor_velocity", v_next, directions=False)
        raise_peak(peaks, "peak_isolator_force", chain[:, 0], directions=False)
        if keep_shear:  # the law's shear, P-Delta's share given back (linear: at the end)
            raise_peak(peaks, "peak_story_shear", chain[:, 1:n_levels]
                       + b.story_gravity[:, :, None] * drift, directions=False)

        # Advance: the isolator law's state after this step, at its velocity; the stories'
        # slip elements see this step's increments.
        isolators.advance_xy(v_next[:, 0, 0], v_next[:, 0, 1], dt)
        if any_yields:
            inc = dt * np.diff(v_next[yields], axis=1)
            fx, fy = radial_return(f_story[yields][..., 0], f_story[yields][..., 1],
                                   inc[..., 0], inc[..., 1], b.story_k_slip[yields],
                                   b.story_f_limit[yields])
            f_story[yields] = np.stack([fx, fy], axis=-1)
        v_half = v_next
        u = u + dt * v_next
        if progress is not None and step % report_every == 0:
            progress(step, n_steps)
    if progress is not None:
        progress(n_steps, n_steps)
    if hist is not None:
        hist["members"] = np.asarray(history.members, dtype=int)
    linear_story_shear(peaks, b, isotropic=b_y is None)  # linear stories': from their drifts
    return {**peaks, **collapse, **residuals(u, collapse["collapsed"])}, hist


def _friction(v_next, respond, comp_xy, limit, normal):
    """The friction force (B, 2) N of one wall direction on the slab, added to v_next (B, L, 2)
    in place: along the tangent t (normal turned by +90 degrees), the force that brings the
    slab's tangential velocity t . v0 to zero at the end of the step (compliance along t:
    c_x t_x^2 + c_y t_y^2) if its magnitude is within limit = mu_wall N (B,), else limit
    against that velocity; zero where the wall does not push (N = 0)."""
    tangent = np.column_stack([-normal[:, 1], normal[:, 0]])
    slip = np.sum(tangent * v_next[:, 0], axis=1)
    stick = -slip / np.sum(comp_xy * tangent**2, axis=1)
    force = tangent * np.clip(stick, -limit, limit)[:, None]
    v_next += respond * force[:, None, :]
    return force


def raise_peak(peaks, name, vectors, directions=True):
    """Raise the resultant peak `name` and, with `directions`, its per-direction peak
    `name`_xy."""
    np.maximum(peaks[name], np.sqrt(np.sum(vectors * vectors, axis=-1)), out=peaks[name])
    if directions:
        np.maximum(peaks[name + "_xy"], np.abs(vectors), out=peaks[name + "_xy"])


def _wall_peaks(peaks, force, delta, new, wall):
    """Raise the wall peaks with one wall direction's contact: force N, indentation m, new
    contacts, and which wall (WALLS index) each member is against."""
    np.maximum(peaks["max_indentation"], delta, out=peaks["max_indentation"])
    np.maximum(peaks["max_impact_force"], force, out=peaks["max_impact_force"])
    peaks["n_impacts"] += new
    rows = np.arange(force.size)
    per_wall = peaks["max_impact_force_wall"]
    per_wall[rows, wall] = np.maximum(per_wall[rows, wall], force)
