"""The compiled time loop of buildings that twist (numba): numpy_torsion.py's step, member by
member (engine/torsion.py: the model).

The structure is numba_plan.py's: a per-member kernel whose state lives on the stack while it
runs, members on threads of this process (the kernel releases the GIL;
numba_support.run_members), the cache keyed on the physics it compiles. What differs:
- the state is the 3L degrees of freedom (x, y, theta per level), padded to an even count and
  held as pairs, so that the dense step operator (3L x 6L, the columns of the transposed
  operator side by side) runs two rows per instruction (numba_support.add2 and kin);
- the isolation is n bearings, each the isolator law in plan at its own displacement and
  velocity with its share of the weight, and its moment (numba_bearings.py);
- the moat is P contact points (torsion.ContactPoints), each its wall's law times its share
  (the same Contact.part arguments the NumPy loop builds, through compiled.law_terms): the
  points touching at a step are solved together, (I + D G / 2) F = E + D r on the points that
  push (Gaussian elimination with partial pivoting on the member's small dense system), a
  point that would pull dropped and the rest solved again, exactly as
  numpy_torsion.solve_contacts; friction along the walls point by point in order.
Peaks of displacements and accelerations are kept squared while running and rooted at the
end (sqrt is monotone: the same numbers). Agrees with the NumPy loop to round-off.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numba import carray, njit

from ..results import (
    MODE,
    TORSION_HISTORIES,
    empty_peaks,
    empty_plan_history,
    residuals,
)
from ..scheme import full_step_operator
from ..torsion import CORNERS
from . import compiled, layout, numba_bearings, numba_contacts
from .compiled import (
    JIT,
    LINK,
    PHYSICS_FILES,
    failed,
    law_terms,
    onset_weight,
)
from .layout import (
    CONTACT,
    ISOLATOR_FIELDS,
    ISOLATOR_STATE_XY,
    TORSION,
    TORSION_PEAK_COLUMNS,
    TORSION_STATE,
    contact_state,
    finish_peaks,
    isolator_rows,
    packed,
)
from .numba_bearings import bearing_forces, bearings_advance, bearings_past
from .numba_contacts import point_arrays, solve_contacts
from .numba_support import (
    add2,
    by_law,
    data_pointer,
    history_rows,
    install_cache_locator,
    kernel_arrays,
    law_groups,
    load_pair,
    mul2,
    run_members,
    stack_doubles,
    store_pair,
)

install_cache_locator(Path(__file__), [compiled.__file__, layout.__file__,
                                       numba_bearings.__file__, numba_contacts.__file__,
                                       *PHYSICS_FILES])

# The kernel's packed arrays (layout.py): per member its floats (TORSION) and state (
# TORSION_STATE), per contact point its law row (contact.law_rows) and CONTACT state, the
# scalar float peaks (TORSION_PEAK_COLUMNS; displacements squared while running).
POINT_SLOTS = 8
"""The contact points' stack arrays come in multiples of this many (the kernel compiles once per
multiple): the slab's corners, or two pads a wall, are 8."""

@njit(**LINK)
def _member(shape, b, s0, s1, model, memory, peaks, hist):
    """Steps s0 <= step < s1 of member b (the module docstring). shape = (levels, padded, slots,
    isolator_tag); model = (ag, dt, op, respond, load, story_k, story_centre, collapse_square, par,
    bearings, point_wall, point_axis, codes, gaps, point_par, direction, tangent, coupling,
    tangent_compliance, corners, isolator), what the run reads (isolator: the isolator law's rows, a
    bearing's share); memory = (u, v, isolator_state, state, point_state), what it carries between
    chunks (isolator_state: per bearing); peaks = (peak_level, peak_level_xy, peak_story,
    peak_story_xy, peak_iso_xy, scalar, n_impacts, peak_wall, peak_point_force, peak_point_indent,
    peak_velocity, peak_shear); hist = (hist_row, every, h_u, h_acc, h_f, h_d, h_floor, h_floor_rot,
    h_fi) (run_torsion builds them). The state's 3L degrees of freedom sit on the stack as Q pairs
    (Q = len(padded) / 2, the last lane of an odd 3L unused, its operator rows 0): op (B, 6L, Q, 2)
    the transposed step operator, respond (B, 3, Q, 2) its first three columns transposed; the P
    contact points' state and this step's values too, on POINT_SLOTS-sized stack arrays (len(slots)
    of them: the kernel compiles once per number of levels and multiple of POINT_SLOTS, P =
    len(point_wall) at run time, and per isolator law: the bearings' law, numba_support.law_tag). A
    member that has collapsed stops."""
    levels, padded, slots, isolator_tag = shape
    (ag, dt, op, respond, load, story_k, story_centre, collapse_square, par, bearings,
     point_wall, point_axis, codes, gaps_all, point_par, direction, tangent, coupling,
     tangent_compliance, corners, isolator) = model
    u_all, v_all, isolator_state, state, point_state = memory
    (peak_level, peak_level_xy, peak_story, peak_story_xy, peak_iso_xy, scalar, n_impacts,
     peak_wall, peak_point_force, peak_point_indent, peak_velocity, peak_shear) = peaks
    hist_row, every, h_u, h_acc, h_f, h_d, h_floor, h_floor_rot, h_fi = hist
    st = state[b]
    if st[TORSION_STATE.collapsed] != 0.0:
        return
    n_levels = len(levels)
    n_dofs = 3 * n_levels
    n_pad = len(padded)
    n_pairs = n_pad // 2
    n_st = n_levels - 1
    ot = carray(data_pointer(op[b]), (2 * n_dofs, n_pairs, 2))
    wr = carray(data_pointer(respond[b]), (3, n_pairs, 2))
    ld = carray(data_pointer(load[b]), (n_dofs, 2))
    ks = carray(data_pointer(story_k[b]), (n_st, 3))
    sc = carray(data_pointer(story_centre[b]), (n_st, 2))
    cq = collapse_square[b]
    p = par[b]
    cs, sn = p[TORSION.cos], p[TORSION.sin]
    iso_row = carray(data_pointer(isolator[b]), (ISOLATOR_FIELDS,))
    mu_wall = p[TORSION.mu_wall]
    bear = bearings[b]
    fp = isolator_state[b]
    code = codes[b]
    pp = point_par[b]
    pg = gaps_all[b]
    g = direction[b]
    tg = tangent[b]
    cg = coupling[b]
    tc = tangent_compliance[b]
    ps = point_state[b]
    n_points = point_wall.shape[0]
    cn = corners[b]
    pk = scalar[b]
    pw = peak_wall[b]
    ppf = peak_point_force[b]
    ppi = peak_point_indent[b]
    hrow = hist_row[b]
    half_dt = 0.5 * dt

    # The member's state: displacements, half-step velocities, the next ones, the right-hand
    # side, each 3L degrees of freedom as pairs (flat views beside them).
    pu, pv = stack_doubles(padded), stack_doubles(padded)
    pn, pr = stack_doubles(padded), stack_doubles(padded)
    u, v = carray(pu, (n_pad,)), carray(pv, (n_pad,))
    nx, r = carray(pn, (n_pad,)), carray(pr, (n_pad,))
    u2 = carray(pu, (n_pairs, 2))
    v2 = carray(pv, (n_pairs, 2))
    nx2 = carray(pn, (n_pairs, 2))
    dr = carray(stack_doubles(padded), (n_pad,))  # the stories' drifts (3 per story)
    pa2 = carray(stack_doubles(levels), (n_levels,))
    pa = carray(stack_doubles(padded), (n_pad,))  # per level x and y, squared
    pd2 = carray(stack_doubles(levels), (n_levels,))
    pv2 = carray(stack_doubles(levels), (n_levels,))
    ps2 = carray(stack_doubles(levels), (n_levels,))
    pd = carray(stack_doubles(padded), (n_pad,))
    for i in range(n_pad):
        u[i], v[i], r[i] = 0.0, 0.0, 0.0
    for i in range(n_levels):
        for d in range(3):
            u[3 * i + d], v[i * 3 + d] = u_all[b, i, d], v_all[b, i, d]
        for e in range(2):
            pa[2 * i + e] = peak_level_xy[b, i, e]
        pa2[i], pv2[i] = peak_level[b, i], peak_velocity[b, i]
    for i in range(n_st):
        for e in range(2):
            pd[2 * i + e] = peak_story_xy[b, i, e]
        pd2[i], ps2[i] = peak_story[b, i], peak_shear[b, i]
    p_iso2 = pk[TORSION_PEAK_COLUMNS.peak_isolator_disp]
    p_iso_x, p_iso_y = peak_iso_xy[b, 0], peak_iso_xy[b, 1]
    p_indent = pk[TORSION_PEAK_COLUMNS.max_indentation]
    p_force = pk[TORSION_PEAK_COLUMNS.max_impact_force]
    energy = pk[TORSION_PEAK_COLUMNS.impact_energy]
    p_corner = pk[TORSION_PEAK_COLUMNS.peak_corner_disp]
    p_rot = pk[TORSION_PEAK_COLUMNS.peak_rotation]
    p_fiso2 = pk[TORSION_PEAK_COLUMNS.peak_isolator_force]
    n_imp = n_impacts[b]
    touch_x = st[TORSION_STATE.touch_x] != 0.0
    touch_y = st[TORSION_STATE.touch_y] != 0.0

    # The contact points on the stack (POINT_SLOTS at a time; P at run time): their
    # directions, gaps and state, and this step's indentations, law terms and forces.
    gx_ = carray(stack_doubles(slots), (n_points,))
    gy_ = carray(stack_doubles(slots), (n_points,))
    gt_ = carray(stack_doubles(slots), (n_points,))
    gap = carray(stack_doubles(slots), (n_points,))
    v_imp = carray(stack_doubles(slots), (n_points,))
    delta_prev = carray(stack_doubles(slots), (n_points,))
    inside = carray(stack_doubles(slots), (n_points,))
    p_point = carray(stack_doubles(slots), (n_points,))  # max_point_indentation
    delta = carray(stack_doubles(slots), (n_points,))
    elastic = carray(stack_doubles(slots), (n_points,))
    dashpot = carray(stack_doubles(slots), (n_points,))
    rate_free = carray(stack_doubles(slots), (n_points,))
    touching = carray(stack_doubles(slots), (n_points,))
    force = carray(stack_doubles(slots), (n_points,))
    active = carray(stack_doubles(slots), (n_points,))
    for q in range(n_points):
        gx_[q], gy_[q], gt_[q] = g[q, 0], g[q, 1], g[q, 2]
        gap[q] = pg[q]
        v_imp[q], delta_prev[q] = ps[q, CONTACT.v_imp], ps[q, CONTACT.delta_prev]
        inside[q] = ps[q, CONTACT.in_contact]
        p_point[q] = ppi[q]
    index = np.empty(n_points, dtype=np.int64)
    a = np.empty((n_points, n_points))
    rhs = np.empty(n_points)
    x = np.empty(n_points)
    per_wall = np.empty(4)

    capacity_square = p[TORSION.capacity_square]
    for step in range(s0, s1):
        # numpy_torsion's collapse rule, on each bearing's displacement and the drift of the
        # plan's centre.
        mode = 0
        mode = bearings_past(mode, bear, u[0], u[1], u[2], capacity_square)
        for i in range(n_st):
            for d in range(3):
                dr[3 * i + d] = u[3 * i + 3 + d] - u[3 * i + d]
            dx, dy = dr[3 * i], dr[3 * i + 1]
            square = dx * dx + dy * dy
            if not square <= cq[i]:
                mode = failed(mode, square, MODE.story_drift)
        if mode > 0:
            st[TORSION_STATE.collapsed] = 1.0
            st[TORSION_STATE.collapse_time] = step * dt
            st[TORSION_STATE.collapse_mode] = mode
            break
        a0 = cs * ag[step, 0] - sn * ag[step, 1]
        a1 = sn * ag[step, 0] + cs * ag[step, 1]
        u0x, u0y, th = u[0], u[1], u[2]
        # The bearings at their own displacements, their forces and moments on the slab.
        sx, sy, sm = bearing_forces(isolator_tag, iso_row, fp, bear, u0x, u0y, th)
        # The right-hand side: the chain of forces, less the ground's load.
        prev_x, prev_y, prev_t = sx, sy, sm
        for i in range(n_levels):
            if i < n_st:  # numpy_torsion.story_forces: the springs at their centres
                cx = ks[i, 0] * (dr[3 * i] - dr[3 * i + 2] * sc[i, 1])
                cy = ks[i, 1] * (dr[3 * i + 1] + dr[3 * i + 2] * sc[i, 0])
                ct = ks[i, 2] * dr[3 * i + 2] + sc[i, 0] * cy - sc[i, 1] * cx
                ps2[i] = max(ps2[i], cx * cx + cy * cy)
            else:
                cx, cy, ct = 0.0, 0.0, 0.0
            j = 3 * i
            r[j] = (cx - prev_x) - (ld[j, 0] * a0 + ld[j, 1] * a1)
            r[j + 1] = (cy - prev_y) - (ld[j + 1, 0] * a0 + ld[j + 1, 1] * a1)
            r[j + 2] = (ct - prev_t) - (ld[j + 2, 0] * a0 + ld[j + 2, 1] * a1)
            prev_x, prev_y, prev_t = cx, cy, ct
        # v_{n+1/2} = op [rhs, v_{n-1/2}], two rows at a time.
        rj = r[0]
        for i in range(n_pairs):
            store_pair(nx2, i, mul2(load_pair(ot[0], i), (rj, rj)))
        for j in range(1, n_dofs):
            rj = r[j]
            for i in range(n_pairs):
                store_pair(nx2, i, add2(load_pair(nx2, i), mul2(load_pair(ot[j], i), (rj, rj))))
        for j in range(n_dofs):
            vj = v[j]
            for i in range(n_pairs):
                store_pair(nx2, i, add2(load_pair(nx2, i),
                                        mul2(load_pair(ot[n_dofs + j], i), (vj, vj))))

        # The moat: every point's indentation, the touching ones solved together.
        v0x, v0y, v0t = v[0], v[1], v[2]
        mx, my, mt = 0.5 * (v0x + nx[0]), 0.5 * (v0y + nx[1]), 0.5 * (v0t + nx[2])
        any_on = False
        on_x, on_y = False, False
        deepest = -1.0
        for q in range(n_points):
            gx, gy, gt = gx_[q], gy_[q], gt_[q]
            dq = max(gx * u0x + gy * u0y + gt * th - gap[q], -1.0)
            delta[q] = dq
            deepest = max(deepest, dq)
            p_point[q] = max(p_point[q], dq)
            on = dq > 0.0
            touching[q] = 1.0 if on else 0.0
            if on:
                any_on = True
                if point_axis[q] == 0:
                    on_x = True
                else:
                    on_y = True
                fresh = inside[q] == 0.0
                if fresh:
                    v_imp[q] = gx * v0x + gy * v0y + gt * v0t
                rf = gx * mx + gy * my + gt * mt
                rate_free[q] = rf
                el, dp = law_terms(code[q], dq, rf, v_imp[q], pp[q])
                if fresh:
                    dp = dp * onset_weight(dq, delta_prev[q])
                elastic[q], dashpot[q] = el, dp
            inside[q] = touching[q]
            delta_prev[q] = dq
        if on_x and not touch_x:
            n_imp += 1
        if on_y and not touch_y:
            n_imp += 1
        touch_x, touch_y = on_x, on_y
        p_indent = max(p_indent, deepest)
        px, py, pm = 0.0, 0.0, 0.0
        if any_on:
            solve_contacts(n_points, touching, elastic, dashpot, rate_free, cg, force, active,
                            index, a, rhs, x)
            for q in range(n_points):
                fq = force[q]
                px += fq * gx_[q]
                py += fq * gy_[q]
                pm += fq * gt_[q]
            px, py, pm = -px, -py, -pm
            for i in range(n_pairs):
                store_pair(nx2, i, add2(load_pair(nx2, i), add2(add2(
                    mul2(load_pair(wr[0], i), (px, px)), mul2(load_pair(wr[1], i), (py, py))),
                    mul2(load_pair(wr[2], i), (pm, pm)))))
            if mu_wall > 0.0:
                for q in range(n_points):
                    limit = mu_wall * force[q]
                    if limit > 0.0:
                        tx, ty, tt = tg[q, 0], tg[q, 1], tg[q, 2]
                        slip = tx * nx[0] + ty * nx[1] + tt * nx[2]
                        fr = min(max(-slip / tc[q], -limit), limit)
                        fx, fy, ft = fr * tx, fr * ty, fr * tt
                        for i in range(n_pairs):
                            store_pair(nx2, i, add2(load_pair(nx2, i), add2(add2(
                                mul2(load_pair(wr[0], i), (fx, fx)),
                                mul2(load_pair(wr[1], i), (fy, fy))),
                                mul2(load_pair(wr[2], i), (ft, ft)))))
                        px += fx
                        py += fy
                        pm += ft
            energy -= (px * (v0x + nx[0]) + py * (v0y + nx[1]) + pm * (v0t + nx[2])) * half_dt
            for w_ in range(4):
                per_wall[w_] = 0.0
            for q in range(n_points):
                fq = force[q]
                ppf[q] = max(ppf[q], fq)
                per_wall[point_wall[q]] += fq
            for w_ in range(4):
                pw[w_] = max(pw[w_], per_wall[w_])
                p_force = max(p_force, per_wall[w_])

        keep = hrow >= 0 and step % every == 0  # this step goes into the histories
        t = step // every if keep else 0
        if keep:
            h_u[hrow, t, 0], h_u[hrow, t, 1] = u0x, u0y
            h_f[hrow, t] = math.hypot(px, py)
            h_d[hrow, t] = max(deepest, 0.0)
            h_fi[hrow, t, 0], h_fi[hrow, t, 1] = sx, sy
            for i in range(n_levels):
                h_floor[hrow, t, i, 0] = u[3 * i]
                h_floor[hrow, t, i, 1] = u[3 * i + 1]
                h_floor_rot[hrow, t, i] = u[3 * i + 2]
        for i in range(n_levels):
            tx_ = (nx[3 * i] - v[3 * i]) / dt + a0
            ty_ = (nx[3 * i + 1] - v[3 * i + 1]) / dt + a1
            if keep:
                h_acc[hrow, t, i, 0], h_acc[hrow, t, i, 1] = tx_, ty_
            sqx, sqy = tx_ * tx_, ty_ * ty_
            pa[2 * i] = max(pa[2 * i], sqx)
            pa[2 * i + 1] = max(pa[2 * i + 1], sqy)
            pa2[i] = max(pa2[i], sqx + sqy)
            pv2[i] = max(pv2[i], nx[3 * i] * nx[3 * i] + nx[3 * i + 1] * nx[3 * i + 1])
        for i in range(n_st):
            sqx, sqy = dr[3 * i] * dr[3 * i], dr[3 * i + 1] * dr[3 * i + 1]
            pd[2 * i] = max(pd[2 * i], sqx)
            pd[2 * i + 1] = max(pd[2 * i + 1], sqy)
            pd2[i] = max(pd2[i], sqx + sqy)
        p_fiso2 = max(p_fiso2, sx * sx + sy * sy)
        sqx, sqy = u0x * u0x, u0y * u0y
        p_iso2 = max(p_iso2, sqx + sqy)
        p_iso_x = max(p_iso_x, sqx)
        p_iso_y = max(p_iso_y, sqy)
        for c in range(4):
            cx = u0x + th * (-cn[c, 1])
            cy = u0y + th * cn[c, 0]
            p_corner = max(p_corner, cx * cx + cy * cy)
        p_rot = max(p_rot, abs(th))

        # Advance: each bearing's isolator law with its own velocity.
        bearings_advance(isolator_tag, iso_row, fp, bear, (nx[0], nx[1], nx[2]), dt)
        for i in range(n_pairs):
            w_pair = load_pair(nx2, i)
            store_pair(v2, i, w_pair)
            store_pair(u2, i, add2(load_pair(u2, i), mul2((dt, dt), w_pair)))

    for i in range(n_levels):
        for d in range(3):
            u_all[b, i, d], v_all[b, i, d] = u[3 * i + d], v[3 * i + d]
        for e in range(2):
            peak_level_xy[b, i, e] = pa[2 * i + e]
        peak_level[b, i], peak_velocity[b, i] = pa2[i], pv2[i]
    for i in range(n_st):
        for e in range(2):
            peak_story_xy[b, i, e] = pd[2 * i + e]
        peak_story[b, i], peak_shear[b, i] = pd2[i], ps2[i]
    pk[TORSION_PEAK_COLUMNS.peak_isolator_disp] = p_iso2
    peak_iso_xy[b, 0], peak_iso_xy[b, 1] = p_iso_x, p_iso_y
    pk[TORSION_PEAK_COLUMNS.max_indentation] = p_indent
    pk[TORSION_PEAK_COLUMNS.max_impact_force] = p_force
    pk[TORSION_PEAK_COLUMNS.impact_energy] = energy
    pk[TORSION_PEAK_COLUMNS.peak_corner_disp] = p_corner
    pk[TORSION_PEAK_COLUMNS.peak_rotation] = p_rot
    pk[TORSION_PEAK_COLUMNS.peak_isolator_force] = p_fiso2
    n_impacts[b] = n_imp
    for q in range(n_points):
        ps[q, CONTACT.v_imp], ps[q, CONTACT.delta_prev] = v_imp[q], delta_prev[q]
        ps[q, CONTACT.in_contact] = inside[q]
        ppi[q] = p_point[q]
    st[TORSION_STATE.touch_x] = 1.0 if touch_x else 0.0
    st[TORSION_STATE.touch_y] = 1.0 if touch_y else 0.0


@njit(**JIT)
def _run(shape, members, s0, s1, model, memory, peaks, hist):
    """Steps s0 <= step < s1 of the members in `members`, one after the other (the other
    arguments: _member's), the GIL released: run_torsion's threads run batches at once."""
    for b in members:
        _member(shape, b, s0, s1, model, memory, peaks, hist)


def run_torsion(ag, dt, b, t, contacts, points, progress, scale, angle, history=None,
                mu_wall=None):
    """numpy_torsion.run_torsion on the kernel: the same arguments, the same (peaks,
    history)."""
    size, n_levels = b.masses.shape
    n_dofs = 3 * n_levels
    n_pad = n_dofs + n_dofs % 2
    n_points = points.wall.size
    # the points' stack arrays in multiples of POINT_SLOTS: 2 to 8 points, the corners or two
    # pads a wall, share one compiled kernel
    slots = (0,) * (POINT_SLOTS * -(-n_points // POINT_SLOTS))
    levels, padded = (0,) * n_levels, (0,) * n_pad
    step_op = full_step_operator(t.mass, t.damping, dt)  # (B, 3L, 6L), numpy_torsion's
    op = np.zeros((size, 2 * n_dofs, n_pad))
    op[:, :, :n_dofs] = step_op.transpose(0, 2, 1)
    respond = np.zeros((size, 3, n_pad))
    respond[:, :, :n_dofs] = step_op[:, :, :3].transpose(0, 2, 1)
    g, tangent = points.direction, points.tangent
    r0 = step_op[:, :3, :3]
    coupling = np.ascontiguousarray(np.einsum("bpi,bij,bqj->bpq", g, r0, g))
    tangent_compliance = np.ascontiguousarray(np.einsum("bpi,bij,bpj->bp", tangent, r0,
                                                        tangent))
    codes, gaps, point_par = point_arrays(contacts, points, size)
    n_bearings = t.bearings.shape[1]
    # cos and sin times the scale, as the NumPy loop forms them (the same bits)
    par = packed(TORSION, b, size, cos=np.cos(angle) * scale, sin=np.sin(angle) * scale,
                 capacity_square=b.isolator_capacity**2,
                 mu_wall=0.0 if mu_wall is None else mu_wall)
    corners = np.ascontiguousarray(np.array(CORNERS) * t.plan[:, None, :] / 2)
    u, v = np.zeros((size, n_levels, 3)), np.zeros((size, n_levels, 3))
    # per bearing, every law's state zero at rest
    isolator_state = np.zeros((size, n_bearings, ISOLATOR_STATE_XY))
    state = np.zeros((size, len(TORSION_STATE)))
    point_state = contact_state(size, n_points)
    peaks = empty_peaks(size, n_levels, "rectangular", n_points=n_points)
    scalar = np.zeros((size, len(TORSION_PEAK_COLUMNS)))
    n_steps = ag.shape[0]
    hist_row, every, rows, inverse = history_rows(history, size)
    hist = empty_plan_history(rows, n_steps, every, dt, n_levels, torsion=True)
    model = (np.ascontiguousarray(ag, dtype=np.float64), float(dt), op, respond,
             np.ascontiguousarray(t.load, dtype=np.float64),
             np.ascontiguousarray(t.story_k, dtype=np.float64),
             np.ascontiguousarray(t.story_centre, dtype=np.float64),
             np.ascontiguousarray(b.collapse_drift**2, dtype=np.float64), par,
             np.ascontiguousarray(t.bearings, dtype=np.float64),
             np.ascontiguousarray(points.wall, dtype=np.int64),
             np.ascontiguousarray(points.axis, dtype=np.int64), codes, gaps, point_par,
             np.ascontiguousarray(g, dtype=np.float64),
             np.ascontiguousarray(tangent, dtype=np.float64), coupling, tangent_compliance,
             corners, isolator_rows(b, n_bearings))
    model = kernel_arrays(model)
    memory = (u, v, isolator_state, state, point_state)
    kept = (peaks["peak_total_accel"], peaks["peak_total_accel_xy"],
            peaks["peak_interstory_drift"], peaks["peak_interstory_drift_xy"],
            peaks["peak_isolator_disp_xy"], scalar, peaks["n_impacts"],
            peaks["max_impact_force_wall"], peaks["max_point_force"],
            peaks["max_point_indentation"], peaks["peak_floor_velocity"],
            peaks["peak_story_shear"])
    written = (hist_row, every, hist["isolator_disp"], hist["total_accel"],
               hist["impact_force"], hist["indentation"], hist["floor_disp"],
               hist["floor_rotation"], hist["isolator_force"])
    groups = law_groups(b.isolator_code)  # one kernel per isolator law, as the planar loop
    run_members(size, n_steps, progress,
                lambda members, s0, s1: [
                    _run((levels, padded, slots, *tags), chosen, s0, s1, model, memory, kept,
                         written)
                    for tags, chosen in by_law(members, groups)])
    peaks = finish_peaks(peaks, scalar, TORSION_PEAK_COLUMNS, state, rooted=True)
    peaks.update(residuals(u[..., :2], peaks["collapsed"]))
    if history is None:
        return peaks, None
    hist = {"time": hist["time"], **{q.name: hist[q.name][inverse] for q in TORSION_HISTORIES},
            "members": np.asarray(history.members, dtype=int)}
    return peaks, hist
