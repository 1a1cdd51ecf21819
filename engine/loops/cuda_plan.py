"""The device time loop in plan (numba's CUDA target): numba_plan.py's step, one GPU thread per
member.

numba_plan._member's arithmetic, in its order, with each pair operation of the CPU kernel
(numba_support.add2 and kin: the same IEEE operation on each lane) written as the two scalar
operations it stands for. The physics is the CPU kernel's, compiled for the device by
cuda_physics: the laws, the wall contact (numba_plan.wall_contact) and the slab-wall friction
(numba_plan.wall_friction). The arrays are numba_plan.plan_run's, copied to the device once a run;
the results come back in one copy (cuda_loop.run_on_device). As on the planar device loop,
the device's fused multiply-adds make the peaks agree with the CPU kernel's to round-off, not
bit for bit.
"""
from __future__ import annotations

import functools
import math

from numba import cuda, float64

from ..results import MODE
from . import cuda_physics as device
from .cuda_loop import run_on_device
from .layout import (
    CONTACT,
    PLAN,
    PLAN_PEAK_COLUMNS,
    PLAN_STATE,
    PLAN_STORY,
)
from .numba_plan import plan_outcome, plan_run, wall_contact, wall_friction


@functools.cache
def _kernel(n_levels: int, circular: bool, walls: int, story_code: int, isolator_code: int):
    """The kernel of buildings of n_levels levels in a circular moat or not, against `walls`
    wall directions (1 or 2), on story law `story_code` and isolator law `isolator_code`:
    kernel(members, s0, s1, model, memory, peaks, hist), numba_plan._member's arguments but
    `members` (a thread each) in place of `shape` and `b`."""
    levels = n_levels
    # `walls`, the wall directions (the run's contacts), a constant of the kernel: the loops
    # over them unroll, so that u[0, d], v[0, d] and nx[0, d] index the state with constants
    # (with a count read at run time, the levels' u, v and nx lived in the thread's local
    # memory: 352 bytes, loaded and stored at every step).
    stories = max(n_levels - 1, 1)
    story_force = device.story_law(story_code)
    # the member's law state, as wide as the kernel's own laws' (a wider local array only
    # holds registers the laws never read)
    n_state = device.story_widths(story_code)[1]
    n_iso_state = device.isolator_widths(isolator_code, "STATE_XY")[1]
    isolator_force_xy = device.isolator_law(isolator_code, "force_xy")
    isolator_advance_xy = device.isolator_law(isolator_code, "advance_xy")
    contact = device.device_function(wall_contact)
    friction = device.device_function(wall_friction)
    failed, radial_return = device.failed, device.radial_return
    sign = device.SCALAR_NUMPY.sign

    def kernel(members, s0, s1, model, memory, peaks, hist):
        t = cuda.grid(1)
        if t >= members.size:
            return
        b = members[t]
        (ag, dt, op, which, story_k, mass, story, law, par, gaps_all, law_par, story_fields,
         isolator) = model
        u_all, v_all, f_story_all, story_state, state, wall_state, isolator_state = memory
        (peak_level, peak_level_xy, peak_story, peak_story_xy, peak_iso_xy, peak_scalar,
         n_impacts, peak_wall, peak_velocity, peak_shear) = peaks
        hist_row, every, h_u, h_acc, h_f, h_d, h_fi = hist
        st = state[b]
        if st[PLAN_STATE.collapsed] != 0.0:
            return
        n_levels = levels
        n_st = n_levels - 1
        # The building's constants read where they lie, not copied: the members of a sweep
        # share a few buildings (which), so a warp's reads of one are one broadcast, cached;
        # copied, the operators' 4 L^2 numbers and the stories' filled the thread's
        # registers and spilled its state to local memory.
        own = which[b]
        ot = op[own]
        w = ot[0]  # the wall responses: the operators' first row (numba_plan.plan_run)
        m = mass[own]
        ks = story_k[own]
        rows = story[own]
        k_post, k_slip_story = rows[PLAN_STORY.story_k_post], rows[PLAN_STORY.story_k_slip]
        f_limit_story, gravity = rows[PLAN_STORY.story_f_limit], rows[PLAN_STORY.story_gravity]
        collapse_square = rows[PLAN_STORY.collapse_square]
        s_fields = story_fields[own]
        s_state = cuda.local.array((stories, 2, n_state), float64)
        for i in range(n_st):
            for e in range(2):
                for j in range(n_state):
                    s_state[i, e, j] = story_state[b, i, e, j]
        comp, comp_y = w[0, 0], w[0, 1]  # the compliances: the wall responses at the slab
        anisotropic = par[b, PLAN.anisotropic] != 0.0
        mu_wall = par[b, PLAN.mu_wall]
        stories_yield = par[b, PLAN.stories_yield] != 0.0
        uniaxial = par[b, PLAN.stories_uniaxial] != 0.0
        cs, sn = par[b, PLAN.cos], par[b, PLAN.sin]
        capacity_square = par[b, PLAN.capacity_square]
        iso_row = isolator[own]
        iso_state = cuda.local.array(n_iso_state, float64)
        for j in range(n_iso_state):
            iso_state[j] = isolator_state[b, j]
        n_walls = walls
        half_dt = 0.5 * dt

        v_imp = cuda.local.array(2, float64)
        delta_prev = cuda.local.array(2, float64)
        inside = cuda.local.array(2, float64)
        gaps = cuda.local.array(2, float64)
        f_n = cuda.local.array(2, float64)
        n_x = cuda.local.array(2, float64)
        n_y = cuda.local.array(2, float64)
        ws = wall_state[b]
        for d in range(n_walls):
            v_imp[d], delta_prev[d] = ws[d, CONTACT.v_imp], ws[d, CONTACT.delta_prev]
            inside[d] = ws[d, CONTACT.in_contact]
            gaps[d] = gaps_all[b, d]
        pk = peak_scalar[b]
        p_iso2 = pk[PLAN_PEAK_COLUMNS.peak_isolator_disp]
        p_indent = pk[PLAN_PEAK_COLUMNS.max_indentation]
        p_force = pk[PLAN_PEAK_COLUMNS.max_impact_force]
        energy = pk[PLAN_PEAK_COLUMNS.impact_energy]
        p_iso_x, p_iso_y = peak_iso_xy[b, 0], peak_iso_xy[b, 1]
        p_fiso2 = pk[PLAN_PEAK_COLUMNS.peak_isolator_force]
        n_imp = n_impacts[b]
        pw = peak_wall[b]
        hrow = hist_row[b]

        u = cuda.local.array((levels, 2), float64)
        v = cuda.local.array((levels, 2), float64)
        nx = cuda.local.array((levels, 2), float64)
        r = cuda.local.array((levels, 2), float64)
        c = cuda.local.array((levels, 2), float64)
        pa2 = cuda.local.array(levels, float64)
        pa = cuda.local.array((levels, 2), float64)
        dr = cuda.local.array((levels, 2), float64)
        fs = cuda.local.array((levels, 2), float64)
        pd2 = cuda.local.array(levels, float64)
        pd = cuda.local.array((levels, 2), float64)
        pv2 = cuda.local.array(levels, float64)
        ps2 = cuda.local.array(levels, float64)
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

        for step in range(s0, s1):
            mode = 0
            square = u[0, 0] * u[0, 0] + u[0, 1] * u[0, 1]
            if not square <= capacity_square:
                mode = failed(mode, square, MODE.isolator_capacity)
            for i in range(n_st):
                dr[i, 0] = u[i + 1, 0] - u[i, 0]
                dr[i, 1] = u[i + 1, 1] - u[i, 1]
                square = dr[i, 0] * dr[i, 0] + dr[i, 1] * dr[i, 1]
                if not square <= collapse_square[i]:
                    mode = failed(mode, square, MODE.story_drift)
            if mode > 0:
                st[PLAN_STATE.collapsed] = 1.0
                st[PLAN_STATE.collapse_time] = step * dt
                st[PLAN_STATE.collapse_mode] = mode
                break
            acc_x = cs * ag[step, 0] - sn * ag[step, 1]
            acc_y = sn * ag[step, 0] + cs * ag[step, 1]
            c[0, 0], c[0, 1] = isolator_force_xy(u[0, 0], u[0, 1], iso_state, iso_row)
            for i in range(n_st):
                if uniaxial:
                    c[i + 1, 0] = story_force(dr[i, 0], s_state[i, 0], s_fields[i]) \
                        - gravity[i] * dr[i, 0]
                    c[i + 1, 1] = story_force(dr[i, 1], s_state[i, 1], s_fields[i]) \
                        - gravity[i] * dr[i, 1]
                elif stories_yield:
                    c[i + 1, 0] = k_post[i] * dr[i, 0] + fs[i, 0]
                    c[i + 1, 1] = k_post[i] * dr[i, 1] + fs[i, 1]
                else:
                    c[i + 1, 0] = ks[i, 0] * dr[i, 0]
                    c[i + 1, 1] = ks[i, 1] * dr[i, 1]
            for i in range(n_st):
                r[i, 0] = (c[i + 1, 0] - c[i, 0]) - m[i] * acc_x
                r[i, 1] = (c[i + 1, 1] - c[i, 1]) - m[i] * acc_y
            r[n_st, 0] = (0.0 - c[n_st, 0]) - m[n_st] * acc_x
            r[n_st, 1] = (0.0 - c[n_st, 1]) - m[n_st] * acc_y
            for i in range(n_levels):
                nx[i, 0] = ot[0, i, 0] * r[0, 0]
                nx[i, 1] = ot[0, i, 1] * r[0, 1]
            for j in range(1, n_levels):
                for i in range(n_levels):
                    nx[i, 0] = nx[i, 0] + ot[j, i, 0] * r[j, 0]
                    nx[i, 1] = nx[i, 1] + ot[j, i, 1] * r[j, 1]
            for j in range(n_levels):
                for i in range(n_levels):
                    nx[i, 0] = nx[i, 0] + ot[n_levels + j, i, 0] * v[j, 0]
                    nx[i, 1] = nx[i, 1] + ot[n_levels + j, i, 1] * v[j, 1]

            wfx, wfy = 0.0, 0.0
            deepest = -1.0
            radius = math.hypot(u[0, 0], u[0, 1]) if circular else 0.0
            for d in range(n_walls):
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
                        free = nrm_x * (0.5 * (v[0, 0] + nx[0, 0])) \
                            + nrm_y * (0.5 * (v[0, 1] + nx[0, 1]))
                        which = 0
                        along = comp if not anisotropic else \
                            comp * (nrm_x * nrm_x) + comp_y * (nrm_y * nrm_y)
                    else:
                        u0d, v0d, n0d = u[0, d], v[0, d], nx[0, d]
                        side = sign(u0d)
                        nrm_x, nrm_y = (side, 0.0) if d == 0 else (0.0, side)
                        before = side * v0d
                        free = side * 0.5 * (v0d + n0d)
                        which = 2 * d if side > 0 else 2 * d + 1
                        along = comp if d == 0 else comp_y
                    new = inside[d] == 0.0
                    if new:
                        n_imp += 1
                        v_imp[d] = before
                    force = contact(law[b, d], law_par[b, d], delta, new, v_imp[d],
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
                            fx, fy = friction(nx, w, comp, comp_y, mu_wall * f_n[d], n_x[d],
                                              n_y[d])
                            wfx += fx
                            wfy += fy
                energy -= (wfx * (v[0, 0] + nx[0, 0]) + wfy * (v[0, 1] + nx[0, 1])) * half_dt

            keep = hrow >= 0 and step % every == 0
            if keep:
                k = step // every
                h_u[hrow, k, 0], h_u[hrow, k, 1] = u[0, 0], u[0, 1]
                h_f[hrow, k] = math.hypot(wfx, wfy)
                h_d[hrow, k] = max(deepest, 0.0)
                h_fi[hrow, k, 0], h_fi[hrow, k, 1] = c[0, 0], c[0, 1]
            for i in range(n_levels):
                total_x = (nx[i, 0] - v[i, 0]) / dt + acc_x
                total_y = (nx[i, 1] - v[i, 1]) / dt + acc_y
                if keep:
                    h_acc[hrow, step // every, i, 0] = total_x
                    h_acc[hrow, step // every, i, 1] = total_y
                square_x, square_y = total_x * total_x, total_y * total_y
                pa[i, 0] = max(pa[i, 0], square_x)
                pa[i, 1] = max(pa[i, 1], square_y)
                pa2[i] = max(pa2[i], square_x + square_y)
                pv2[i] = max(pv2[i], nx[i, 0] * nx[i, 0] + nx[i, 1] * nx[i, 1])
            for i in range(n_st):
                square_x, square_y = dr[i, 0] * dr[i, 0], dr[i, 1] * dr[i, 1]
                pd[i, 0] = max(pd[i, 0], square_x)
                pd[i, 1] = max(pd[i, 1], square_y)
                pd2[i] = max(pd2[i], square_x + square_y)
                if uniaxial or stories_yield or anisotropic:
                    shear_x = c[i + 1, 0] + gravity[i] * dr[i, 0]
                    shear_y = c[i + 1, 1] + gravity[i] * dr[i, 1]
                    ps2[i] = max(ps2[i], shear_x * shear_x + shear_y * shear_y)
            p_fiso2 = max(p_fiso2, c[0, 0] * c[0, 0] + c[0, 1] * c[0, 1])
            square_x, square_y = u[0, 0] * u[0, 0], u[0, 1] * u[0, 1]
            p_iso2 = max(p_iso2, square_x + square_y)
            p_iso_x = max(p_iso_x, square_x)
            p_iso_y = max(p_iso_y, square_y)

            isolator_advance_xy(iso_state, nx[0, 0], nx[0, 1], dt, iso_row)
            if stories_yield:
                for i in range(n_st):
                    fs[i, 0], fs[i, 1] = radial_return(
                        fs[i, 0], fs[i, 1], dt * (nx[i + 1, 0] - nx[i, 0]),
                        dt * (nx[i + 1, 1] - nx[i, 1]), k_slip_story[i], f_limit_story[i])
            for i in range(n_levels):
                v[i, 0], v[i, 1] = nx[i, 0], nx[i, 1]
                u[i, 0] = u[i, 0] + dt * nx[i, 0]
                u[i, 1] = u[i, 1] + dt * nx[i, 1]

        for i in range(n_levels):
            for e in range(2):
                u_all[b, i, e], v_all[b, i, e] = u[i, e], v[i, e]
                peak_level_xy[b, i, e] = pa[i, e]
            peak_level[b, i], peak_velocity[b, i] = pa2[i], pv2[i]
        for i in range(n_st):
            for e in range(2):
                f_story_all[b, i, e] = fs[i, e]
                peak_story_xy[b, i, e] = pd[i, e]
                for j in range(n_state):
                    story_state[b, i, e, j] = s_state[i, e, j]
            peak_story[b, i], peak_shear[b, i] = pd2[i], ps2[i]
        for j in range(n_iso_state):
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

    return cuda.jit(kernel)


def run_plan(ag, dt, arrays, contacts, moat: str, progress, scale, angle, history=None,
             arrays_y=None, mu_wall=None):
    """numba_plan.run_plan on the device: the same arguments, the same (peaks, history)
    (cuda_loop.run_on_device)."""
    run = plan_run(ag, dt, arrays, contacts, moat, scale, angle, history, arrays_y, mu_wall)
    n_levels, circular = len(run["levels"]), run["circular"]
    run_on_device((run["model"], run["memory"], run["kept"], run["written"]), run["groups"],
                  run["n_steps"], progress,
                  lambda story, isolator: _kernel(n_levels, circular, len(contacts), story,
                                                  isolator))
    return plan_outcome(run, history)
