"""The compiled time loop in plan (numba): numpy_plan.py's step, member by member.

The building moves in x and y (state arrays with a last axis of directions, the two directions'
identical arithmetic on pairs, both in one vector register: numba_support.add2 and kin, the
same bits as two scalar operations), with its step operator along x and along y (the same
arrays for isotropic stories); the isolator law in plan (compiled.isolator_force_xy and
isolator_advance_xy, the law's own functions the NumPy loop calls) and the yielding stories'
slip elements (isolators/hysteresis.radial_return, as the NumPy loop); the moat
is two wall directions (rectangular: x and y, each wall on the side the slab moves towards) or
one (circular: along the slab's radius), every impact law along the wall's normal through the
laws' own `force_terms` (the planar kernel's dispatch), and the slab-wall friction along the
wall, solved as numpy_plan._friction solves it. The dense step operator serves every height
here (the planar kernel's banded solve above 12 levels is not used in plan yet). Agrees with
the NumPy plan loop to round-off; like the planar kernel, a member's result never depends on
its batch or on threads. Members run on threads of this process (the kernel releases the GIL;
numba_support.run_members), as the planar kernel's.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numba import carray, njit

from ..impact.contact import law_rows
from ..results import (
    DIRECTIONS,
    MODE,
    PLAN_HISTORIES,
    empty_peaks,
    empty_plan_history,
    residuals,
)
from ..scheme import distinct_step_operators
from ..stories.registry import MAX_FIELDS
from . import compiled, layout
from .compiled import (
    JIT,
    LINK,
    PHYSICS_FILES,
    failed,
    implicit_force,
    isolator_advance_xy,
    isolator_force_xy,
    law_terms,
    onset_weight,
    radial_return,
    story_force,
)
from .layout import (
    CONTACT,
    ISOLATOR_FIELDS,
    ISOLATOR_SLOTS_XY,
    ISOLATOR_STATE_XY,
    PLAN,
    PLAN_PEAK_COLUMNS,
    PLAN_STATE,
    PLAN_STORY,
    contact_state,
    finish_peaks,
    isolator_rows,
    linear_story_shear,
    packed,
    per_building,
    story_states,
)
from .numba_support import (
    add2,
    by_law,
    data_pointer,
    div2,
    history_rows,
    install_cache_locator,
    kernel_arrays,
    law_groups,
    load_pair,
    max2,
    mul2,
    run_members,
    stack_doubles,
    store_pair,
    sub2,
)

install_cache_locator(Path(__file__), [compiled.__file__, layout.__file__, *PHYSICS_FILES])

# The kernel's packed arrays (layout.py): per member its floats (PLAN) and state between
# chunks (PLAN_STATE), per wall direction its clear gap, its law's row (contact.law_rows) and
# its CONTACT state, per story PLAN_STORY, the scalar float peaks (PLAN_PEAK_COLUMNS: the
# displacement's squared while running, as every displacement and acceleration peak:
# layout.finish_peaks roots them).


@njit(**LINK)
def wall_contact(code, row, delta, new, v_imp, delta_prev, rate_free, comp):
    """One wall direction's contact force (N, >= 0) at indentation delta > 0 (m): the law's
    terms along the wall's normal (row: its law row), the dashpot weighted at a new contact,
    solved exactly."""
    elastic, dashpot = law_terms(code, delta, rate_free, v_imp, row)
    if new:
        dashpot = dashpot * onset_weight(delta, delta_prev)
    return implicit_force(elastic, dashpot, rate_free, comp)


@njit(**LINK)
def wall_friction(nx, w, comp, comp_y, limit, nrm_x, nrm_y):
    """numpy_plan._friction for one member: the friction force (fx, fy) N of a wall pushing
    with unit normal (nrm_x, nrm_y), limit = mu_wall N, added to the velocities nx (L, 2) in
    place through the wall responses w (L, 2)."""
    t_x, t_y = -nrm_y, nrm_x
    slip = t_x * nx[0, 0] + t_y * nx[0, 1]
    stick = -slip / (comp * (t_x * t_x) + comp_y * (t_y * t_y))
    force = min(max(stick, -limit), limit)
    fx, fy = t_x * force, t_y * force
    for i in range(nx.shape[0]):
        nx[i, 0] += w[i, 0] * fx
        nx[i, 1] += w[i, 1] * fy
    return fx, fy


@njit(**LINK)
def _member(shape, b, s0, s1, model, memory, peaks, hist):
    """Steps s0 <= step < s1 of member b (see the module docstring). shape = (levels, pairs,
    circular, law_tag, isolator_tag); model = (ag, dt, op, which, story_k, mass, story, law, par,
    gaps, law_par, story_fields, isolator), what the run reads, its building's at which[b]
    (layout.per_building; isolator: the isolator law's rows);
    memory = (u, v, f_story, story_state, state, wall_state, isolator_state), what it carries
    between chunks; peaks = (peak_level, peak_level_xy, peak_story, peak_story_xy, peak_iso_xy,
    peak_scalar, n_impacts, peak_wall, peak_velocity, peak_shear); hist = (hist_row, every, h_u,
    h_acc, h_f, h_d, h_fi) (run_plan builds them). Like the planar kernel, the member's state lives
    in scalars and arrays on the stack while it runs, each level's x and y side by side (a last axis
    of 2, as the operators: op (2L, L, 2), the operator along x and along y transposed, wall (L, 2),
    story_k (L - 1, 2)), and the two directions' identical arithmetic done on pairs, both lanes at
    once (numba_support.add2 and kin). Peaks are kept squared, per direction and resultant: the
    square root of the largest square is the largest magnitude, bit for bit (sqrt(x * x) == |x| in
    binary floating point), and run_plan roots them at the end. Stories of a uniaxial law (one
    without plan_fields, engine/stories/) act along x and y each on their own (two springs of the
    law per story, uncoupled), its force compiled in for the member's law only (law_tag, as the
    planar kernel's), and so is its isolator law's (isolator_tag). A member that has collapsed
    stops."""
    levels, pairs, circular, law_tag, isolator_tag = shape
    (ag, dt, op, which, story_k, mass, story, law, par, gaps_all, law_par, story_fields,
     isolator) = model
    u_all, v_all, f_story_all, story_state, state, wall_state, isolator_state = memory
    (peak_level, peak_level_xy, peak_story, peak_story_xy, peak_iso_xy, peak_scalar, n_impacts,
     peak_wall, peak_velocity, peak_shear) = peaks
    hist_row, every, h_u, h_acc, h_f, h_d, h_fi = hist
    st = state[b]
    if st[PLAN_STATE.collapsed] != 0.0:
        return
    n_levels = len(levels)
    n_st = n_levels - 1
    own = which[b]  # the member's building
    ot = carray(data_pointer(op[own]), (2 * n_levels, n_levels, 2))
    w = ot[0]  # the wall responses: the operators' first columns (transposed: row)
    ks = story_k[own]
    m = mass[own]
    p = par[b]
    comp, comp_y = w[0, 0], w[0, 1]  # the compliances: the wall responses at the slab
    anisotropic = p[PLAN.anisotropic] != 0.0
    mu_wall = p[PLAN.mu_wall]
    iso_row = carray(data_pointer(isolator[own]), (ISOLATOR_FIELDS,))
    stories_yield = p[PLAN.stories_yield] != 0.0
    cs, sn = p[PLAN.cos], p[PLAN.sin]
    rows = story[own]
    k_post, k_slip_story = rows[PLAN_STORY.story_k_post], rows[PLAN_STORY.story_k_slip]
    f_limit_story, gravity = rows[PLAN_STORY.story_f_limit], rows[PLAN_STORY.story_gravity]
    collapse_square = rows[PLAN_STORY.collapse_square]  # no root per step
    uniaxial = p[PLAN.stories_uniaxial] != 0.0
    s_fields = carray(data_pointer(story_fields[own]), (n_levels - 1, MAX_FIELDS))
    s_state = carray(data_pointer(story_state[b]), (n_levels - 1, 2, story_state.shape[3]))
    n_walls = law.shape[1]
    codes = law[b]
    half_dt = 0.5 * dt

    iso_state = carray(stack_doubles(ISOLATOR_SLOTS_XY), (ISOLATOR_STATE_XY,))
    for j in range(ISOLATOR_STATE_XY):
        iso_state[j] = isolator_state[b, j]
    # per wall direction: impact velocity, previous indentation, in contact (1.0), clear gap
    v_imp = carray(stack_doubles(levels), (2,))
    delta_prev = carray(stack_doubles(levels), (2,))
    inside = carray(stack_doubles(levels), (2,))
    gaps = carray(stack_doubles(levels), (2,))
    # per wall direction this step: its normal force and unit normal (for the friction)
    f_n = carray(stack_doubles(levels), (2,))
    n_x = carray(stack_doubles(levels), (2,))
    n_y = carray(stack_doubles(levels), (2,))
    ws = wall_state[b]
    for d in range(n_walls):
        v_imp[d], delta_prev[d] = ws[d, CONTACT.v_imp], ws[d, CONTACT.delta_prev]
        inside[d] = ws[d, CONTACT.in_contact]
        gaps[d] = gaps_all[b, d]
    pk = peak_scalar[b]
    p_iso2 = pk[PLAN_PEAK_COLUMNS.peak_isolator_disp]
    p_indent = pk[PLAN_PEAK_COLUMNS.max_indentation]
    p_force, energy = pk[PLAN_PEAK_COLUMNS.max_impact_force], pk[PLAN_PEAK_COLUMNS.impact_energy]
    p_iso_x, p_iso_y = peak_iso_xy[b, 0], peak_iso_xy[b, 1]
    p_fiso2 = pk[PLAN_PEAK_COLUMNS.peak_isolator_force]
    n_imp = n_impacts[b]
    pw = peak_wall[b]
    hrow = hist_row[b]

    u = carray(stack_doubles(pairs), (n_levels, 2))
    v = carray(stack_doubles(pairs), (n_levels, 2))
    nx = carray(stack_doubles(pairs), (n_levels, 2))  # v_{n+1/2}
    r = carray(stack_doubles(pairs), (n_levels, 2))
    c = carray(stack_doubles(pairs), (n_levels, 2))
    pa2 = carray(stack_doubles(levels), (n_levels,))
    pa = carray(stack_doubles(pairs), (n_levels, 2))
    dr = carray(stack_doubles(pairs), (n_levels, 2))  # the stories' drifts (first n_st rows)
    fs = carray(stack_doubles(pairs), (n_levels, 2))
    pd2 = carray(stack_doubles(levels), (n_levels,))
    pd = carray(stack_doubles(pairs), (n_levels, 2))
    pv2 = carray(stack_doubles(levels), (n_levels,))
    ps2 = carray(stack_doubles(levels), (n_levels,))
    for i in range(n_levels):
        for e in range(2):
            u[i, e], v[i, e] = u_all[b, i, e], v_all[b, i, e]
            pa[i, e] = peak_level_xy[b, i, e]
        pa2[i], pv2[i] = peak_level[b, i], peak_velocity[b, i]
    for i in range(n_st):
        for e in range(2):
            fs[i, e] = f_story_all[b, i, e]
            pd[i, e] = peak_story_xy[b, i, e]
        pd2[i], ps2[i] = peak_story[b, i], peak_shear[b, i]

    capacity_square = p[PLAN.capacity_square]
    for step in range(s0, s1):
        # The isolator or a story's drift vector past its limit, or a state no longer finite,
        # ends the member's run (numba_loop.py's rule, on the vectors' magnitudes).
        mode = 0
        square = u[0, 0] * u[0, 0] + u[0, 1] * u[0, 1]
        if not square <= capacity_square:
            mode = failed(mode, square, MODE.isolator_capacity)
        for i in range(n_st):
            drift = sub2(load_pair(u, i + 1), load_pair(u, i))
            store_pair(dr, i, drift)
            square = drift[0] * drift[0] + drift[1] * drift[1]
            if not square <= collapse_square[i]:
                mode = failed(mode, square, MODE.story_drift)
        if mode > 0:
            st[PLAN_STATE.collapsed] = 1.0
            st[PLAN_STATE.collapse_time] = step * dt
            st[PLAN_STATE.collapse_mode] = mode
            break
        acc = (cs * ag[step, 0] - sn * ag[step, 1], sn * ag[step, 0] + cs * ag[step, 1])
        c[0, 0], c[0, 1] = isolator_force_xy(isolator_tag, u[0, 0], u[0, 1], iso_state, iso_row)
        for i in range(n_st):
            drift = load_pair(dr, i)
            if uniaxial:  # the law along x and along y, less what P-Delta takes
                c[i + 1, 0] = story_force(law_tag, drift[0], s_state[i, 0], s_fields[i]) \
                    - gravity[i] * drift[0]
                c[i + 1, 1] = story_force(law_tag, drift[1], s_state[i, 1], s_fields[i]) \
                    - gravity[i] * drift[1]
            elif stories_yield:
                store_pair(c, i + 1, add2(mul2((k_post[i], k_post[i]), drift),
                                          load_pair(fs, i)))
            else:
                store_pair(c, i + 1, mul2(load_pair(ks, i), drift))
        for i in range(n_st):
            store_pair(r, i, sub2(sub2(load_pair(c, i + 1), load_pair(c, i)),
                                  mul2((m[i], m[i]), acc)))
        store_pair(r, n_st, sub2(sub2((0.0, 0.0), load_pair(c, n_st)),
                                 mul2((m[n_st], m[n_st]), acc)))  # the free roof
        # Both directions through their transposed operators, in the planar kernel's order.
        for i in range(n_levels):
            store_pair(nx, i, mul2(load_pair(ot[0], i), load_pair(r, 0)))
        for j in range(1, n_levels):
            for i in range(n_levels):
                store_pair(nx, i, add2(load_pair(nx, i),
                                       mul2(load_pair(ot[j], i), load_pair(r, j))))
        for j in range(n_levels):
            for i in range(n_levels):
                store_pair(nx, i, add2(load_pair(nx, i),
                                       mul2(load_pair(ot[n_levels + j], i), load_pair(v, j))))

        # The moat: the force on the slab (wfx, wfy), towards the centre; one wall direction
        # (the circle's radius) or two (x, then y), each the same code, the law's once.
        wfx, wfy = 0.0, 0.0
        deepest = -1.0
        radius = math.hypot(u[0, 0], u[0, 1]) if circular else 0.0
        for d in range(n_walls):
            # the distance to the wall first: the rest only where the slab touches it
            distance = radius if circular else abs(u[0, d])
            delta = max(distance - gaps[d], -1.0)
            touching = delta > 0.0
            f_n[d] = 0.0
            if touching:
                if circular:
                    nrm_x, nrm_y = 1.0, 0.0
                    if radius > 0.0:
                        nrm_x, nrm_y = u[0, 0] / radius, u[0, 1] / radius
                    before = nrm_x * v[0, 0] + nrm_y * v[0, 1]
                    free = nrm_x * (0.5 * (v[0, 0] + nx[0, 0])) + nrm_y * (0.5 * (v[0, 1]
                                                                                   + nx[0, 1]))
                    which = 0
                    along = comp if not anisotropic else \
                        comp * (nrm_x * nrm_x) + comp_y * (nrm_y * nrm_y)
                else:
                    u0d, v0d, n0d = u[0, d], v[0, d], nx[0, d]
                    side = np.sign(u0d)
                    nrm_x, nrm_y = (side, 0.0) if d == 0 else (0.0, side)
                    before = side * v0d
                    free = side * 0.5 * (v0d + n0d)
                    which = 2 * d if side > 0 else 2 * d + 1
                    along = comp if d == 0 else comp_y
                new = inside[d] == 0.0
                if new:
                    n_imp += 1
                    v_imp[d] = before
                force = wall_contact(codes[d], law_par[b, d], delta, new, v_imp[d],
                                 delta_prev[d], free, along)
                wfx -= nrm_x * force
                wfy -= nrm_y * force
                p_force = max(p_force, force)
                pw[which] = max(pw[which], force)
                f_n[d], n_x[d], n_y[d] = force, nrm_x, nrm_y
            inside[d] = 1.0 if touching else 0.0
            delta_prev[d] = delta
            p_indent = max(p_indent, delta)
            deepest = max(deepest, delta)
        if wfx != 0.0 or wfy != 0.0:
            for i in range(n_levels):
                nx[i, 0] += w[i, 0] * wfx
                nx[i, 1] += w[i, 1] * wfy
            if mu_wall > 0.0:
                for d in range(n_walls):
                    if f_n[d] > 0.0:
                        fx, fy = wall_friction(nx, w, comp, comp_y, mu_wall * f_n[d], n_x[d],
                                           n_y[d])
                        wfx += fx
                        wfy += fy
            energy -= (wfx * (v[0, 0] + nx[0, 0]) + wfy * (v[0, 1] + nx[0, 1])) * half_dt

        keep = hrow >= 0 and step % every == 0  # this step goes into the histories
        if keep:
            t = step // every
            h_u[hrow, t, 0], h_u[hrow, t, 1] = u[0, 0], u[0, 1]
            h_f[hrow, t] = math.hypot(wfx, wfy)
            h_d[hrow, t] = max(deepest, 0.0)
            h_fi[hrow, t, 0], h_fi[hrow, t, 1] = c[0, 0], c[0, 1]
        for i in range(n_levels):
            total = add2(div2(sub2(load_pair(nx, i), load_pair(v, i)), (dt, dt)), acc)
            if keep:
                h_acc[hrow, step // every, i, 0], h_acc[hrow, step // every, i, 1] = total
            square = mul2(total, total)
            store_pair(pa, i, max2(load_pair(pa, i), square))
            pa2[i] = max(pa2[i], square[0] + square[1])
            square = mul2(load_pair(nx, i), load_pair(nx, i))
            pv2[i] = max(pv2[i], square[0] + square[1])
        for i in range(n_st):
            square = mul2(load_pair(dr, i), load_pair(dr, i))
            store_pair(pd, i, max2(load_pair(pd, i), square))
            pd2[i] = max(pd2[i], square[0] + square[1])
            if uniaxial or stories_yield or anisotropic:  # the law's shear (else at the end)
                shear = add2(load_pair(c, i + 1), mul2((gravity[i], gravity[i]), load_pair(dr, i)))
                square = mul2(shear, shear)
                ps2[i] = max(ps2[i], square[0] + square[1])
        square = mul2(load_pair(c, 0), load_pair(c, 0))
        p_fiso2 = max(p_fiso2, square[0] + square[1])
        square = mul2(load_pair(u, 0), load_pair(u, 0))
        p_iso2 = max(p_iso2, square[0] + square[1])
        p_iso_x = max(p_iso_x, square[0])
        p_iso_y = max(p_iso_y, square[1])

        # Advance: the isolator law's state after this step, at its velocity; the stories'
        # slip elements see this step's increments.
        isolator_advance_xy(isolator_tag, iso_state, nx[0, 0], nx[0, 1], dt, iso_row)
        if stories_yield:
            for i in range(n_st):
                fs[i, 0], fs[i, 1] = radial_return(
                    fs[i, 0], fs[i, 1], dt * (nx[i + 1, 0] - nx[i, 0]),
                    dt * (nx[i + 1, 1] - nx[i, 1]), k_slip_story[i], f_limit_story[i])
        for i in range(n_levels):
            store_pair(v, i, load_pair(nx, i))
            store_pair(u, i, add2(load_pair(u, i), mul2((dt, dt), load_pair(nx, i))))

    for i in range(n_levels):
        for e in range(2):
            u_all[b, i, e], v_all[b, i, e] = u[i, e], v[i, e]
            peak_level_xy[b, i, e] = pa[i, e]
        peak_level[b, i], peak_velocity[b, i] = pa2[i], pv2[i]
    for i in range(n_st):
        for e in range(2):
            f_story_all[b, i, e] = fs[i, e]
            peak_story_xy[b, i, e] = pd[i, e]
        peak_story[b, i], peak_shear[b, i] = pd2[i], ps2[i]
    for j in range(ISOLATOR_STATE_XY):
        isolator_state[b, j] = iso_state[j]
    for d in range(n_walls):
        ws[d, CONTACT.v_imp], ws[d, CONTACT.delta_prev] = v_imp[d], delta_prev[d]
        ws[d, CONTACT.in_contact] = inside[d]
    pk[PLAN_PEAK_COLUMNS.peak_isolator_disp] = p_iso2
    pk[PLAN_PEAK_COLUMNS.max_indentation] = p_indent
    pk[PLAN_PEAK_COLUMNS.max_impact_force] = p_force
    pk[PLAN_PEAK_COLUMNS.impact_energy] = energy
    pk[PLAN_PEAK_COLUMNS.peak_isolator_force] = p_fiso2
    peak_iso_xy[b, 0], peak_iso_xy[b, 1] = p_iso_x, p_iso_y
    n_impacts[b] = n_imp


@njit(**JIT)
def _run(shape, members, s0, s1, model, memory, peaks, hist):
    """Steps s0 <= step < s1 of the members in `members`, one after the other (the other
    arguments: _member's), the GIL released: run_plan's threads run batches of members at once
    (numba's parallel loops' parallelism at a third of their compile time)."""
    for b in members:
        _member(shape, b, s0, s1, model, memory, peaks, hist)


def plan_run(ag, dt, arrays, contacts, moat: str, scale, angle, history=None, arrays_y=None,
             mu_wall=None) -> dict:
    """The packed arrays of a run in plan, shared by this loop and the device's (cuda_plan):
    model, memory, kept (the peaks), written (the histories), as _member takes them, groups
    (law_groups), levels and pairs (tuples of L and 2L zeros), circular, and what
    `plan_outcome` reads back. The arguments: run_plan's."""
    size, n_levels = arrays.masses.shape
    levels = (0,) * n_levels
    pairs = (0,) * (2 * n_levels)  # x and y of every level, side by side on the stack
    # a Building is both its directions: the x arrays' distinct members key y's too
    first, which, building, op = per_building(arrays, dt)
    op_y, story_y = (op, building.story_k) if arrays_y is None else (  # isotropic: x's serve y
        distinct_step_operators(arrays_y, dt, first), arrays_y.story_k[first])
    # x and y side by side: operators transposed (D, 2L, L, 2), story stiffnesses (D, L - 1, 2)
    op_xy = np.ascontiguousarray(np.stack([op.transpose(0, 2, 1), op_y.transpose(0, 2, 1)],
                                          axis=-1))
    story_xy = np.ascontiguousarray(np.stack([building.story_k, story_y], axis=-1))
    # cos and sin times the scale, as the NumPy loop forms them (the same bits)
    par = packed(PLAN, arrays, size, anisotropic=arrays_y is not None,
                 mu_wall=0.0 if mu_wall is None else mu_wall,
                 stories_yield=arrays.story_yields, stories_uniaxial=arrays.story_uniaxial,
                 cos=np.cos(angle) * scale, sin=np.sin(angle) * scale,
                 capacity_square=arrays.isolator_capacity**2)
    n_dir = len(contacts)
    law = np.ascontiguousarray(np.stack([c.law for c in contacts], axis=1), dtype=np.int64)
    gaps = np.ascontiguousarray(np.stack([c.clear_gap for c in contacts], axis=1),
                                dtype=np.float64)
    law_par = np.ascontiguousarray(np.stack([law_rows(c) for c in contacts], axis=1))
    story = packed(PLAN_STORY, building, collapse_square=building.collapse_drift**2)
    story_fields = np.ascontiguousarray(building.story_fields, dtype=np.float64)
    n_dirs = len(DIRECTIONS)
    story_state = story_states(arrays, first, n_dirs)  # each story's law along x and y
    u, v = np.zeros((size, n_levels, n_dirs)), np.zeros((size, n_levels, n_dirs))
    f_story = np.zeros((size, n_levels - 1, n_dirs))
    state = np.zeros((size, len(PLAN_STATE)))
    wall_state = contact_state(size, n_dir)
    peaks = empty_peaks(size, n_levels, moat)
    scalar = np.zeros((size, len(PLAN_PEAK_COLUMNS)))
    n_steps = ag.shape[0]
    hist_row, every, rows, inverse = history_rows(history, size)
    hist = empty_plan_history(rows, n_steps, every, dt, n_levels)
    model = (np.ascontiguousarray(ag, dtype=np.float64), float(dt), op_xy,
             np.ascontiguousarray(which, dtype=np.int64), story_xy,
             np.ascontiguousarray(building.masses), story, law, par, gaps, law_par,
             story_fields, isolator_rows(building))
    model = kernel_arrays(model)
    isolator_state = np.zeros((size, ISOLATOR_STATE_XY))  # every law's state is zero at rest
    memory = (u, v, f_story, story_state, state, wall_state, isolator_state)
    kept = (peaks["peak_total_accel"], peaks["peak_total_accel_xy"],
            peaks["peak_interstory_drift"], peaks["peak_interstory_drift_xy"],
            peaks["peak_isolator_disp_xy"], scalar, peaks["n_impacts"],
            peaks["max_impact_force_wall"], peaks["peak_floor_velocity"],
            peaks["peak_story_shear"])
    written = (hist_row, every, hist["isolator_disp"], hist["total_accel"],
               hist["impact_force"], hist["indentation"], hist["isolator_force"])
    return {"model": model, "memory": memory, "kept": kept, "written": written,
            "groups": law_groups(arrays.story_code, arrays.isolator_code), "levels": levels,
            "pairs": pairs, "circular": moat == "circular", "peaks": peaks, "scalar": scalar,
            "hist": hist, "inverse": inverse, "n_steps": n_steps,
            "stories": (arrays, arrays_y is None)}


def plan_outcome(run: dict, history) -> tuple[dict, dict | None]:
    """(peaks, history) of a run in plan (plan_run) once its kernel ran."""
    state = run["memory"][4]
    peaks = linear_story_shear(finish_peaks(run["peaks"], run["scalar"], PLAN_PEAK_COLUMNS,
                                            state, rooted=True), *run["stories"])
    peaks.update(residuals(run["memory"][0], peaks["collapsed"]))
    if history is None:
        return peaks, None
    hist, inverse = run["hist"], run["inverse"]
    return peaks, {"time": hist["time"],
                   **{q.name: hist[q.name][inverse] for q in PLAN_HISTORIES},
                   "members": np.asarray(history.members, dtype=int)}


def run_plan(ag, dt, arrays, contacts, moat: str, progress, scale, angle, history=None,
             arrays_y=None, mu_wall=None):
    """numpy_plan.run_plan on the kernel: the same arguments, the same (peaks, history)."""
    run = plan_run(ag, dt, arrays, contacts, moat, scale, angle, history, arrays_y, mu_wall)
    args = (run["model"], run["memory"], run["kept"], run["written"])
    levels, pairs, circular, groups = run["levels"], run["pairs"], run["circular"], run["groups"]
    # One kernel per story law and isolator law, as the planar loop.
    run_members(len(contacts[0]), run["n_steps"], progress,
                lambda members, s0, s1: [
                    _run((levels, pairs, circular, *tags), chosen, s0, s1, *args)
                    for tags, chosen in by_law(members, groups)])
    return plan_outcome(run, history)
