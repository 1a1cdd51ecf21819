"""The compiled time loop in plan (numba): numpy_plan.py's step, member by member.

The building moves in x and y (state arrays with a last axis of directions), its operator
shared by both directions (isotropic stories); the isolator's and the yielding stories' slip
elements return radially (isolators/hysteresis.radial_return, the same function the NumPy loop
calls); the moat is two wall directions (rectangular: x and y, each wall on the side the slab
moves towards) or one (circular: along the slab's radius), every impact law along the wall's
normal through the laws' own `force_terms` (the planar kernel's dispatch). The dense step
operator serves every height here (the planar kernel's banded solve above 12 levels is not
used in plan yet). Agrees with the NumPy plan loop to round-off; like the planar kernel, a
member's result never depends on its batch or on threads.
"""
from __future__ import annotations

import math
from pathlib import Path

import numba
import numpy as np
from numba import njit, prange

from .. import scheme
from ..impact import registry
from ..impact.contact import LAW_ARGUMENTS
from ..isolators import hysteresis
from ..results import DIRECTIONS, PEAKS, PLAN_PEAKS, WALLS
from ..scheme import step_operators
from .numba_loop import _JIT, _LINK, _implicit_force, _law_terms, _onset_weight, _slip_limit
from .numba_support import install_cache_locator

install_cache_locator(Path(__file__), [m.__file__ for m in (
    hysteresis, scheme, registry, *registry.LAWS.values())])

_radial_return = njit(**_LINK)(hysteresis.radial_return)

# Per-member scalars, and per wall direction: the clear gap, then the law's arguments.
(_COMPLIANCE, _K_ELASTIC, _K_SLIP, _F_LIMIT, _SLOW_DROP, _RATE, _STORIES_YIELD, _COS, _SIN,
 _N_PAR) = range(10)
_GAP, _LAW_ARGS = 0, 1
_N_WALL_PAR = _LAW_ARGS + len(LAW_ARGUMENTS)
# State carried between chunks: the isolator's slip force (x, y), then per wall direction its
# impact velocity, previous indentation and contact flag.
_FPX, _FPY, _WALL_STATE = 0, 1, 2
# Scalar float peaks: resultant isolator displacement, indentation, force, energy.
_P_ISO, _P_INDENT, _P_FORCE, _P_ENERGY = range(4)


@njit(**_LINK)
def _wall_force(code, wp, distance, rate_before, rate_free, comp, st, j):
    """One wall direction's contact for one member: (force N >= 0, indentation m, new
    contact); st[j:j+3] its state (impact velocity, previous indentation, in contact)."""
    delta = max(distance - wp[_GAP], -1.0)
    touching = delta > 0.0
    new = touching and st[j + 2] == 0.0
    if new:
        st[j] = rate_before
    st[j + 2] = 1.0 if touching else 0.0
    force = 0.0
    if touching:
        q = _LAW_ARGS
        elastic, dashpot = _law_terms(code, delta, rate_free, st[j], wp[q], wp[q + 1],
                                      wp[q + 2], wp[q + 3], wp[q + 4], wp[q + 5], wp[q + 6],
                                      wp[q + 7], wp[q + 8], wp[q + 9])
        if new:
            dashpot = dashpot * _onset_weight(delta, st[j + 1])
        force = _implicit_force(elastic, dashpot, rate_free, comp)
    st[j + 1] = delta
    return force, delta, new


@njit(**_JIT)
def _member(levels, circular, b, s0, s1, ag, dt, op, wall, mass, story, law, par, wall_par,
            u_all, v_all, f_story_all, state, peak_level, peak_level_xy, peak_story,
            peak_story_xy, peak_iso_xy, peak_scalar, n_impacts, peak_wall):
    """Steps s0 <= step < s1 of member b (see the module docstring)."""
    n_levels = len(levels)
    ot = op[b]
    w = wall[b]
    m = mass[b]
    p = par[b]
    comp = p[_COMPLIANCE]
    k_el, k_slip, f_limit = p[_K_ELASTIC], p[_K_SLIP], p[_F_LIMIT]
    slow_drop, rate = p[_SLOW_DROP], p[_RATE]
    stories_yield = p[_STORIES_YIELD] != 0.0
    cs, sn = p[_COS], p[_SIN]
    st = state[b]
    pk = peak_scalar[b]
    half_dt = 0.5 * dt

    u = u_all[b]          # (L, 2), updated in place
    v = v_all[b]
    f_story = f_story_all[b]
    nxt = np.empty((n_levels, 2))
    drift = np.empty((n_levels - 1, 2))
    chain = np.empty(n_levels)
    r = np.empty(n_levels)
    a = np.empty(2)
    wf = np.empty(2)
    for step in range(s0, s1):
        a[0] = cs * ag[step, 0] - sn * ag[step, 1]
        a[1] = sn * ag[step, 0] + cs * ag[step, 1]
        for d in range(2):
            chain[0] = k_el * u[0, d] + st[_FPX + d]
            for i in range(n_levels - 1):
                drift[i, d] = u[i + 1, d] - u[i, d]
                if stories_yield:
                    chain[i + 1] = story[b, 1, i] * drift[i, d] + f_story[i, d]
                else:
                    chain[i + 1] = story[b, 0, i] * drift[i, d]
            for i in range(n_levels - 1):
                r[i] = (chain[i + 1] - chain[i]) - m[i] * a[d]
            r[n_levels - 1] = (0.0 - chain[n_levels - 1]) - m[n_levels - 1] * a[d]
            for i in range(n_levels):
                nxt[i, d] = ot[0, i] * r[0]
            for j in range(1, n_levels):
                for i in range(n_levels):
                    nxt[i, d] += ot[j, i] * r[j]
            for j in range(n_levels):
                for i in range(n_levels):
                    nxt[i, d] += ot[n_levels + j, i] * v[j, d]

        if circular:
            radius = math.hypot(u[0, 0], u[0, 1])
            nx, ny = 1.0, 0.0
            if radius > 0.0:
                nx, ny = u[0, 0] / max(radius, 1e-300), u[0, 1] / max(radius, 1e-300)
            before = nx * v[0, 0] + ny * v[0, 1]
            free = nx * (0.5 * (v[0, 0] + nxt[0, 0])) + ny * (0.5 * (v[0, 1] + nxt[0, 1]))
            force, delta, new = _wall_force(law[b, 0], wall_par[b, 0], radius, before, free,
                                            comp, st, _WALL_STATE)
            wf[0], wf[1] = -nx * force, -ny * force
            _raise_wall(pk, n_impacts, peak_wall, b, force, delta, new, 0)
        else:
            for d in range(2):
                side = np.sign(u[0, d])
                force, delta, new = _wall_force(
                    law[b, d], wall_par[b, d], abs(u[0, d]), side * v[0, d],
                    side * 0.5 * (v[0, d] + nxt[0, d]), comp, st, _WALL_STATE + 3 * d)
                wf[d] = -side * force
                _raise_wall(pk, n_impacts, peak_wall, b, force, delta, new,
                            2 * d if side > 0 else 2 * d + 1)
        for d in range(2):
            for i in range(n_levels):
                nxt[i, d] += w[i] * wf[d]
        pk[_P_ENERGY] -= (wf[0] * (v[0, 0] + nxt[0, 0]) + wf[1] * (v[0, 1] + nxt[0, 1])) \
            * half_dt

        for i in range(n_levels):
            tx = (nxt[i, 0] - v[i, 0]) / dt + a[0]
            ty = (nxt[i, 1] - v[i, 1]) / dt + a[1]
            peak_level[b, i] = max(peak_level[b, i], math.sqrt(tx * tx + ty * ty))
            peak_level_xy[b, i, 0] = max(peak_level_xy[b, i, 0], abs(tx))
            peak_level_xy[b, i, 1] = max(peak_level_xy[b, i, 1], abs(ty))
        for i in range(n_levels - 1):
            dx, dy = drift[i, 0], drift[i, 1]
            peak_story[b, i] = max(peak_story[b, i], math.sqrt(dx * dx + dy * dy))
            peak_story_xy[b, i, 0] = max(peak_story_xy[b, i, 0], abs(dx))
            peak_story_xy[b, i, 1] = max(peak_story_xy[b, i, 1], abs(dy))
        ux, uy = u[0, 0], u[0, 1]
        pk[_P_ISO] = max(pk[_P_ISO], math.sqrt(ux * ux + uy * uy))
        peak_iso_xy[b, 0] = max(peak_iso_xy[b, 0], abs(ux))
        peak_iso_xy[b, 1] = max(peak_iso_xy[b, 1], abs(uy))

        # Advance: the slip elements see this step's increments, the isolator's limit at this
        # step's sliding speed |v|.
        limit = f_limit if slow_drop == 0.0 else _slip_limit(
            f_limit, slow_drop, rate, math.hypot(nxt[0, 0], nxt[0, 1]))
        st[_FPX], st[_FPY] = _radial_return(st[_FPX], st[_FPY], dt * nxt[0, 0],
                                            dt * nxt[0, 1], k_slip, limit)
        if stories_yield:
            for i in range(n_levels - 1):
                f_story[i, 0], f_story[i, 1] = _radial_return(
                    f_story[i, 0], f_story[i, 1], dt * (nxt[i + 1, 0] - nxt[i, 0]),
                    dt * (nxt[i + 1, 1] - nxt[i, 1]), story[b, 2, i], story[b, 3, i])
        for i in range(n_levels):
            for d in range(2):
                v[i, d] = nxt[i, d]
                u[i, d] = u[i, d] + dt * nxt[i, d]


@njit(**_LINK)
def _raise_wall(pk, n_impacts, peak_wall, b, force, delta, new, which):
    pk[_P_INDENT] = max(pk[_P_INDENT], delta)
    pk[_P_FORCE] = max(pk[_P_FORCE], force)
    if new:
        n_impacts[b] += 1
    peak_wall[b, which] = max(peak_wall[b, which], force)


@njit(parallel=True, **_JIT)
def _run(levels, circular, s0, s1, ag, dt, op, wall, mass, story, law, par, wall_par, u, v,
         f_story, state, peak_level, peak_level_xy, peak_story, peak_story_xy, peak_iso_xy,
         peak_scalar, n_impacts, peak_wall):
    for b in prange(law.shape[0]):
        _member(levels, circular, b, s0, s1, ag, dt, op, wall, mass, story, law, par, wall_par,
                u, v, f_story, state, peak_level, peak_level_xy, peak_story, peak_story_xy,
                peak_iso_xy, peak_scalar, n_impacts, peak_wall)


def run_plan(ag, dt, arrays, contacts, moat: str, progress, scale, angle):
    """numpy_plan.run_plan on the kernel: the same arguments, the same peaks dict."""
    size, n_levels = arrays.masses.shape
    levels = (0,) * n_levels
    op, wall_response, compliance = step_operators(arrays, dt)
    par = np.empty((size, _N_PAR))
    par[:, _COMPLIANCE] = compliance
    par[:, _K_ELASTIC], par[:, _K_SLIP] = arrays.k_elastic, arrays.k_slip
    par[:, _F_LIMIT], par[:, _SLOW_DROP], par[:, _RATE] = (arrays.f_limit, arrays.slow_drop,
                                                           arrays.rate)
    par[:, _STORIES_YIELD] = arrays.story_yields
    # cos and sin times the scale, as the NumPy loop forms them (the same bits)
    par[:, _COS], par[:, _SIN] = np.cos(angle) * scale, np.sin(angle) * scale
    n_dir = len(contacts)
    law = np.ascontiguousarray(np.stack([c.law for c in contacts], axis=1), dtype=np.int64)
    wall_par = np.empty((size, n_dir, _N_WALL_PAR))
    for d, c in enumerate(contacts):
        wall_par[:, d, _GAP] = c.clear_gap
        for i, name in enumerate(LAW_ARGUMENTS):
            wall_par[:, d, _LAW_ARGS + i] = getattr(c, name)
    story = np.ascontiguousarray(np.stack([arrays.story_k, arrays.story_k_post,
                                           arrays.story_k_slip, arrays.story_f_limit], axis=1))
    n_dirs = len(DIRECTIONS)
    u, v = np.zeros((size, n_levels, n_dirs)), np.zeros((size, n_levels, n_dirs))
    f_story = np.zeros((size, n_levels - 1, n_dirs))
    state = np.zeros((size, _WALL_STATE + 3 * n_dir))
    state[:, _WALL_STATE::3] = 1.0  # impact velocities before any impact
    peaks = {q.name: np.zeros((size, *q.trailing_shape(n_levels, len(WALLS[moat]))),
                              dtype=q.dtype) for q in (*PEAKS, *PLAN_PEAKS)}
    scalar = np.zeros((size, 4))
    args = (np.ascontiguousarray(ag, dtype=np.float64), float(dt),
            np.ascontiguousarray(op.transpose(0, 2, 1)), np.ascontiguousarray(wall_response),
            np.ascontiguousarray(arrays.masses), story, law, par, wall_par, u, v, f_story,
            state, peaks["peak_total_accel"], peaks["peak_total_accel_xy"],
            peaks["peak_interstory_drift"], peaks["peak_interstory_drift_xy"],
            peaks["peak_isolator_disp_xy"], scalar, peaks["n_impacts"],
            peaks["max_impact_force_wall"])
    n_steps = ag.shape[0]
    circular = moat == "circular"
    previous = numba.set_parallel_chunksize(1)  # members to whichever thread is free
    try:
        if progress is None:
            _run(levels, circular, 0, n_steps, *args)
        else:
            chunk = max(n_steps // 100, 1)
            for start in range(0, n_steps, chunk):
                progress(start, n_steps)
                _run(levels, circular, start, min(start + chunk, n_steps), *args)
            progress(n_steps, n_steps)
    finally:
        numba.set_parallel_chunksize(previous)
    for i, name in enumerate(("peak_isolator_disp", "max_indentation", "max_impact_force",
                              "impact_energy")):
        peaks[name] = scalar[:, i].copy()
    return peaks
