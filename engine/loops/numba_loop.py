"""The compiled time loop (numba): the default backend of engine.simulate and engine.two_body.

The scheme is engine/scheme.py's, member by member: members outer, steps inner, every piece of
a member's state in local scalars. The physics is not written here: the impact laws'
`force_terms`, the isolator's return mapping, `implicit_force` and `onset_weight` are the very
functions the NumPy loop calls on arrays, compiled here for scalars; the laws come from the
registry, chained into one dispatch on the member's law code (`compiled.law_dispatch`).

No fastmath: the kernel agrees with the NumPy loop to round-off. Members never interact, so
the result of a member does not depend on its batch, its position in it, or on threads.
Compilation is cached on disk (cache=True; 5-7 s cold, well under a second from the cache).
The cache is keyed on the source of this file *and* of the physics modules it compiles
(numba alone would only watch this file), see numba_support.install_cache_locator.
"""
from __future__ import annotations

from pathlib import Path

import numba
import numpy as np
from numba import carray, njit
from numba.np.unsafe.ndarray import to_fixed_tuple

from ..impact.contact import law_rows
from ..impact.registry import ROW_WIDTH
from ..results import MODE, empty_peaks, residuals
from ..scheme import banded_operators
from ..stories.registry import MAX_FIELDS
from . import compiled, layout
from .compiled import (
    JIT,
    LINK,
    PHYSICS_FILES,
    failed,
    implicit_force,
    isolator_advance,
    isolator_force,
    law_terms,
    onset_weight,
    story_force,
)
from .layout import (
    ISOLATOR_FIELDS,
    ISOLATOR_SLOTS,
    ISOLATOR_STATE,
    PLANAR,
    PLANAR_PEAK_COLUMNS,
    PLANAR_STATE,
    PLANAR_STORY,
    finish_peaks,
    isolator_rows,
    linear_story_shear,
    packed,
    per_building,
    story_states,
)
from .numba_support import (
    by_law,
    data_pointer,
    history_rows,
    install_cache_locator,
    kernel_arrays,
    law_groups,
    run_members,
    stack_doubles,
)

# Cached kernels go stale when any physics source they compile changes, not only this file.
install_cache_locator(Path(__file__), [compiled.__file__, layout.__file__, *PHYSICS_FILES])

# The kernel's packed arrays (layout.py): per member its floats (PLANAR), its impact law's
# row (contact.law_rows), its isolator law's row (isolator_fields), its state between chunks of
# steps (PLANAR_STATE; the displacements and velocities of every level and the isolator law's
# state are arrays of their own), per story PLANAR_STORY; the peaks per
# level (peak_total_accel), per story (peak_interstory_drift), the scalar float peaks
# (PLANAR_PEAK_COLUMNS, named as in engine/results.py) in one matrix, the count (n_impacts) apart.


@njit(**LINK)
def solve_banded(bd, r, v, out, n_levels, dt):
    """out = A^-1 (r + C v) / dt for tridiagonal A = M/dt^2 + C/(2dt) and C = M/dt - C/2 (the
    scheme's operators when the damping is a chain, as the paper's rule makes it): a product
    with C and the Thomas algorithm, O(L) instead of the dense operator's O(L^2). bd rows
    (scheme.banded_operators): 1 / pivots, A's off-diagonal, the eliminated off-diagonal,
    C's diagonal and off-diagonal."""
    last = n_levels - 1
    for i in range(n_levels):
        rhs = r[i] + bd[3, i] * v[i]
        if i > 0:
            rhs += bd[4, i - 1] * v[i - 1]
        if i < last:
            rhs += bd[4, i] * v[i + 1]
        if i > 0:
            rhs -= bd[1, i - 1] * out[i - 1]
        out[i] = rhs * bd[0, i]
    for i in range(last - 1, -1, -1):
        out[i] -= bd[2, i] * out[i + 1]
    for i in range(n_levels):
        out[i] = out[i] / dt


@njit(**LINK)
def _member(shape, b, s0, s1, model, memory, peaks, hist):
    """Steps s0 <= step < s1 of member b: the NumPy loop's step, on scalars and the member's own
    small arrays (L levels, L - 1 stories). shape = (levels, law_tag, isolator_tag): `levels` a
    tuple of L zeros, so that L is a compile-time constant; `law_tag` and `isolator_tag` the
    member's story law and isolator law (numba_support.law_tag), so that they are constants too and
    their physics alone is compiled into this kernel: one compilation per number of levels, story
    law and isolator law. model = (ag, dt, op, which, bands, mass, story, law, par, law_par,
    story_fields, isolator), what the run reads, its building's at which[b] (layout.per_building;
    isolator: the isolator law's rows); memory = (u, v, story_state, state, isolator_state),
    what it carries between chunks; peaks = (peak_level,
    peak_story, peak_velocity, peak_shear, peak_scalar, n_impacts); hist = (hist_row, every,
    h_u, h_acc, h_f, h_d, h_fi)
    (run_simulation builds them; layout.py names their columns). Sums run in the order of the scalar
    kernel this loop replaced, and a member's result never depends on the batch. A member that has
    collapsed stops."""
    levels, law_tag, isolator_tag = shape
    ag, dt, op, which, bands, mass, story, law, par, law_par, story_fields, isolator = model
    u_all, v_all, story_state, state, isolator_state = memory
    peak_level, peak_story, peak_velocity, peak_shear, peak_scalar, n_impacts = peaks
    hist_row, every, h_u, h_acc, h_f, h_d, h_fi = hist
    st = state[b]
    if st[PLANAR_STATE.collapsed] != 0.0:
        return
    n_levels = len(levels)
    own = which[b]  # the member's building
    ot = op[own]
    bd = bands[own]
    banded = bd.shape[1] > 0
    w = ot[0]  # the wall response: the operator's first column (transposed: row)
    m = mass[own]
    k_story, gravity = story[own, PLANAR_STORY.story_k], story[own, PLANAR_STORY.story_gravity]
    collapse_drift = story[own, PLANAR_STORY.collapse_drift]
    # The story law's constants and state as views: the constants' width known when the kernel
    # compiles, the state's the batch's widest law's (layout.story_states).
    s_fields = carray(data_pointer(story_fields[own]), (n_levels - 1, MAX_FIELDS))
    s_state = carray(data_pointer(story_state[b]), (n_levels - 1, story_state.shape[2]))
    p = par[b]
    comp = w[0]  # the compliance: the wall response at the slab
    gap = p[PLANAR.gap]
    iso_row = carray(data_pointer(isolator[own]), (ISOLATOR_FIELDS,))
    nonlinear = p[PLANAR.stories_nonlinear] != 0.0
    scale = p[PLANAR.scale]
    law_row = to_fixed_tuple(law_par[b], ROW_WIDTH)  # in registers, as scalars
    code = law[b]
    hrow = hist_row[b]

    v_imp = st[PLANAR_STATE.v_imp]
    delta_prev = st[PLANAR_STATE.delta_prev]
    in_contact = st[PLANAR_STATE.in_contact] != 0.0
    pk = peak_scalar[b]
    p_iso = pk[PLANAR_PEAK_COLUMNS.peak_isolator_disp]
    p_indent = pk[PLANAR_PEAK_COLUMNS.max_indentation]
    p_force = pk[PLANAR_PEAK_COLUMNS.max_impact_force]
    energy = pk[PLANAR_PEAK_COLUMNS.impact_energy]
    p_fiso = pk[PLANAR_PEAK_COLUMNS.peak_isolator_force]
    n_imp = n_impacts[b]
    half_dt = 0.5 * dt

    # The member's working arrays on the stack: of a size known when it compiles, registers.
    u = carray(stack_doubles(levels), (n_levels,))
    v = carray(stack_doubles(levels), (n_levels,))
    pa = carray(stack_doubles(levels), (n_levels,))
    pd = carray(stack_doubles(levels), (n_levels - 1,))
    pv = carray(stack_doubles(levels), (n_levels,))
    ps = carray(stack_doubles(levels), (n_levels - 1,))
    for i in range(n_levels):
        u[i], v[i], pa[i], pv[i] = u_all[b, i], v_all[b, i], peak_level[b, i], peak_velocity[b, i]
    for i in range(n_levels - 1):
        pd[i], ps[i] = peak_story[b, i], peak_shear[b, i]
    chain = carray(stack_doubles(levels), (n_levels,))  # isolator, stories 1..N
    drift = carray(stack_doubles(levels), (n_levels - 1,))
    r = carray(stack_doubles(levels), (n_levels,))
    nxt = carray(stack_doubles(levels), (n_levels,))
    iso_state = carray(stack_doubles(ISOLATOR_SLOTS), (ISOLATOR_STATE,))
    for j in range(ISOLATOR_STATE):
        iso_state[j] = isolator_state[b, j]
    capacity = p[PLANAR.capacity]
    mode = 0
    for step in range(s0, s1):
        a = ag[step] * scale  # x 1.0 is exact: unscaled members are unchanged
        # Structure without wall force: p - f(u_n), then the free velocities v_{n+1/2}.
        chain[0] = isolator_force(isolator_tag, u[0], iso_state, iso_row)
        # The isolator past its capacity, a story past its collapse drift, or a state no
        # longer finite ends the member's run below: its peaks are the steps' before.
        if not abs(u[0]) <= capacity:
            mode = failed(mode, u[0], MODE.isolator_capacity)
        for i in range(n_levels - 1):
            drift[i] = u[i + 1] - u[i]
            if not abs(drift[i]) <= collapse_drift[i]:
                mode = failed(mode, drift[i], MODE.story_drift)
            if nonlinear:  # the story law's force, less what P-Delta takes
                chain[i + 1] = story_force(law_tag, drift[i], s_state[i], s_fields[i]) \
                    - gravity[i] * drift[i]
            else:
                chain[i + 1] = k_story[i] * drift[i]
        if mode > 0:
            st[PLANAR_STATE.collapsed] = 1.0
            st[PLANAR_STATE.collapse_time] = step * dt
            st[PLANAR_STATE.collapse_mode] = mode
            break
        for i in range(n_levels - 1):
            r[i] = (chain[i + 1] - chain[i]) - m[i] * a
        r[n_levels - 1] = (0.0 - chain[n_levels - 1]) - m[n_levels - 1] * a  # the free roof
        if banded:
            solve_banded(bd, r, v, nxt, n_levels, dt)
        else:
            # nxt = op @ [r, v], each row summed in column order (the order of the unrolled
            # sums this loop replaced, bit for bit). Rows are independent: the inner loop
            # over them keeps their sums in flight at once (ot: the operator transposed).
            for i in range(n_levels):
                nxt[i] = ot[0, i] * r[0]
            for j in range(1, n_levels):
                rj = r[j]
                for i in range(n_levels):
                    nxt[i] += ot[j, i] * rj
            for j in range(n_levels):
                vj = v[j]
                for i in range(n_levels):
                    nxt[i] += ot[n_levels + j, i] * vj

        # Wall contact on the side the slab moves towards (clamped as in the NumPy loop).
        u0 = u[0]
        side = np.sign(u0)
        delta = max(abs(u0) - gap, -1.0)
        touching = delta > 0.0
        new = touching and not in_contact
        if new:
            n_imp += 1
            v_imp = side * v[0]
        in_contact = touching
        force = 0.0
        if touching:
            rate_free = side * 0.5 * (v[0] + nxt[0])
            elastic, dashpot_now = law_terms(code, delta, rate_free, v_imp, law_row)
            if new:
                dashpot_now = dashpot_now * onset_weight(delta, delta_prev)
            force = implicit_force(elastic, dashpot_now, rate_free, comp)
            push = side * force
            for i in range(n_levels):
                nxt[i] = nxt[i] - w[i] * push
        delta_prev = delta

        keep = hrow >= 0 and step % every == 0  # this step goes into the histories
        for i in range(n_levels):
            total = (nxt[i] - v[i]) / dt + a
            pa[i] = max(pa[i], abs(total))
            pv[i] = max(pv[i], abs(nxt[i]))
            if keep:
                h_acc[hrow, step // every, i] = total
        for i in range(n_levels - 1):
            pd[i] = max(pd[i], abs(drift[i]))
            if nonlinear:  # the law's shear, P-Delta's share given back (linear: at the end)
                ps[i] = max(ps[i], abs(chain[i + 1] + gravity[i] * drift[i]))
        p_iso = max(p_iso, abs(u0))
        p_fiso = max(p_fiso, abs(chain[0]))
        p_indent = max(p_indent, delta)
        p_force = max(p_force, force)
        energy += force * side * (v[0] + nxt[0]) * half_dt

        if keep:
            t = step // every
            h_u[hrow, t] = u0
            h_f[hrow, t] = force
            h_d[hrow, t] = max(delta, 0.0)
            h_fi[hrow, t] = chain[0]

        # Advance: the isolator law's state after this step, at its velocity.
        isolator_advance(isolator_tag, iso_state, nxt[0], dt, iso_row)
        for i in range(n_levels):
            v[i] = nxt[i]
            u[i] = u[i] + dt * nxt[i]

    for i in range(n_levels):
        u_all[b, i], v_all[b, i], peak_level[b, i], peak_velocity[b, i] = u[i], v[i], pa[i], pv[i]
    for i in range(n_levels - 1):
        peak_story[b, i], peak_shear[b, i] = pd[i], ps[i]
    for j in range(ISOLATOR_STATE):
        isolator_state[b, j] = iso_state[j]
    st[PLANAR_STATE.v_imp] = v_imp
    st[PLANAR_STATE.delta_prev] = delta_prev
    st[PLANAR_STATE.in_contact] = 1.0 if in_contact else 0.0
    pk[PLANAR_PEAK_COLUMNS.peak_isolator_disp] = p_iso
    pk[PLANAR_PEAK_COLUMNS.max_indentation] = p_indent
    pk[PLANAR_PEAK_COLUMNS.max_impact_force] = p_force
    pk[PLANAR_PEAK_COLUMNS.impact_energy] = energy
    pk[PLANAR_PEAK_COLUMNS.peak_isolator_force] = p_fiso
    n_impacts[b] = n_imp


@njit(**JIT)
def _run(shape, members, s0, s1, model, memory, peaks, hist):
    """Steps s0 <= step < s1 of the members in `members` (indices), one after the other (the other
    arguments: _member's). One compilation per number of levels and laws (`shape`'s type): loops of
    known length, the member's arrays on the stack. The cached kernel: _member is compiled into it,
    not cached on its own (one entry to write and load a variant, a second in every process saved).
    It releases the GIL: run_simulation hands batches of members to threads
    (numba_support.run_members)."""
    for b in members:
        _member(shape, b, s0, s1, model, memory, peaks, hist)


@njit(**JIT)
def ground_motion(accel, accel_dt, dt, n_steps):
    """np.interp(arange(n_steps) * dt, arange(accel.size) * accel_dt, accel), bit for bit
    (the same formula and edge rules), without searching: the record's grid is uniform."""
    out = np.empty(n_steps)
    last = accel.size - 1
    x_last = last * accel_dt
    slopes = np.empty(max(last, 1))
    for j in range(last):
        slopes[j] = (accel[j + 1] - accel[j]) / ((j + 1) * accel_dt - j * accel_dt)
    j = 0  # x grows with i: the interval index only moves forward
    for i in range(n_steps):
        x = i * dt
        if x >= x_last:
            out[i] = accel[last]
            continue
        while j < last - 1 and (j + 1) * accel_dt <= x:
            j += 1
        x_j = j * accel_dt
        if x_j == x:
            out[i] = accel[j]
        else:
            out[i] = slopes[j] * (x - x_j) + accel[j]
    return out


def threads() -> int:
    """Threads the kernel runs members on (numba's setting, e.g. NUMBA_NUM_THREADS)."""
    return numba.get_num_threads()


def member_parameters(arrays, contact, scale) -> np.ndarray:
    """(B, len(PLANAR)) float matrix of every per-member scalar the step reads."""
    return packed(PLANAR, arrays, len(contact),
                  stories_nonlinear=~arrays.story_linear, gap=contact.clear_gap, scale=scale,
                  capacity=arrays.isolator_capacity)


def planar_run(ag, dt, arrays, contact, history, scale) -> dict:
    """The packed arrays of a planar run, shared by this loop and the device's (cuda_loop):
    model, memory, kept (the peaks), hist (as _member takes them), groups (law_groups), levels
    (a tuple of L zeros), and what `planar_outcome` reads back."""
    size = len(contact)
    n_levels = arrays.masses.shape[1]
    n_steps = ag.size
    first, which, building, op = per_building(arrays, dt)
    bands = banded_operators(building, dt)
    if bands is None:
        bands = np.zeros((first.size, 5, 0))
    par = member_parameters(arrays, contact, scale)
    law = np.ascontiguousarray(contact.law, dtype=np.int64)
    u, v = np.zeros((size, n_levels)), np.zeros((size, n_levels))
    # Per story PLANAR_STORY; the story law's constants and state.
    story = packed(PLANAR_STORY, building)
    story_fields = np.ascontiguousarray(building.story_fields, dtype=np.float64)
    story_state = story_states(arrays, first)
    state = np.zeros((size, len(PLANAR_STATE)))
    state[:, PLANAR_STATE.v_imp] = 1.0
    isolator_state = np.zeros((size, ISOLATOR_STATE))  # every law's state is zero at rest
    peaks = empty_peaks(size, n_levels)
    peak_scalar = np.zeros((size, len(PLANAR_PEAK_COLUMNS)))
    ag = np.ascontiguousarray(ag, dtype=np.float64)

    hist_row, every, rows, inverse = history_rows(history, size)
    n_out = 0 if history is None else (n_steps - 1) // every + 1
    h_u, h_f, h_d, h_fi = (np.zeros((rows, n_out)) for _ in range(4))
    h_acc = np.zeros((rows, n_out, n_levels))

    model = (ag, float(dt), np.ascontiguousarray(op.transpose(0, 2, 1)),
             np.ascontiguousarray(which, dtype=np.int64), bands,
             np.ascontiguousarray(building.masses), story, law, par, law_rows(contact),
             story_fields, isolator_rows(building))
    model = kernel_arrays(model)
    return {"model": model, "memory": (u, v, story_state, state, isolator_state),
            "kept": (peaks["peak_total_accel"], peaks["peak_interstory_drift"],
                     peaks["peak_floor_velocity"], peaks["peak_story_shear"], peak_scalar,
                     peaks["n_impacts"]),
            "hist": (hist_row, every, h_u, h_acc, h_f, h_d, h_fi),
            "groups": law_groups(arrays.story_code, arrays.isolator_code),
            "levels": (0,) * n_levels,  # its length, part of its type, specialises the kernel
            "peaks": peaks, "inverse": inverse, "n_out": n_out, "arrays": arrays}


def planar_outcome(run: dict, dt: float, history) -> tuple[dict, dict | None]:
    """(peaks dict, history dict or None) of a planar run (planar_run) once its kernel ran."""
    state = run["memory"][3]
    result = finish_peaks(run["peaks"], run["kept"][4], PLANAR_PEAK_COLUMNS, state)
    result.update(residuals(run["memory"][0], result["collapsed"]))
    linear_story_shear(result, run["arrays"])
    if history is None:
        return result, None
    _, every, h_u, h_acc, h_f, h_d, h_fi = run["hist"]
    inverse = run["inverse"]
    return result, {"time": np.arange(run["n_out"]) * every * dt, "isolator_disp": h_u[inverse],
                    "total_accel": h_acc[inverse], "impact_force": h_f[inverse],
                    "indentation": h_d[inverse], "isolator_force": h_fi[inverse],
                    "members": np.asarray(history.members, dtype=int)}


def run_simulation(ag, dt, arrays, contact, history, progress, scale=1.0):
    """engine.simulate's time loop on the kernel: (peaks dict, history dict or None).

    ag (N,) on the step grid; arrays: BuildingArrays and contact: Contact, both of B members in
    batch order; history: engine.History or None; progress: callable(step, n_steps) or None.
    With progress the run goes in chunks of about 1% of the steps, the state kept in arrays
    between chunks (the same arithmetic, so the same bits); without, in one call.
    """
    run = planar_run(ag, dt, arrays, contact, history, scale)
    args = (run["model"], run["memory"], run["kept"], run["hist"])
    groups, levels = run["groups"], run["levels"]

    def steps(members, s0, s1):
        # One kernel per story law and isolator law: each member runs the one of its laws.
        for tags, chosen in by_law(members, groups):
            _run((levels, *tags), chosen, s0, s1, *args)
    run_members(len(contact), ag.size, progress, steps)
    return planar_outcome(run, dt, history)


# --- two free bodies (engine.two_body) ---------------------------------------------------

@njit(**JIT)
def _two_body(law, par, v, dt, m_eff, n_iter, deltas, forces, out, stops):
    """Each member from first touch: n_iter steps (n_iter < 0: until it separates, at most
    -n_iter steps). Records indentation and force per step when deltas has columns; out[b] =
    (hysteresis area J, final half-step velocity m/s, peak force N, peak indentation m);
    stops[b]: the step after which the member had separated for good (-1: not yet)."""
    record = deltas.shape[1] > 0
    limit = n_iter if n_iter >= 0 else -n_iter
    for b in range(law.size):
        p = par[b]
        code = law[b]
        h = dt[b]
        m = m_eff[b]
        v_imp = v[b]
        compliance = h / m
        delta = 0.0
        v_half = v_imp
        area = 0.0
        peak_force = 0.0
        peak_delta = 0.0
        stop = -1
        done = 0
        for i in range(limit):
            force = 0.0
            if delta > 0.0:
                # No other force acts, so the free central rate is v_{n-1/2} itself.
                elastic, dashpot = law_terms(code, delta, v_half, v_imp, p)
                force = implicit_force(elastic, dashpot, v_half, compliance)
            if record:
                deltas[b, i] = delta
                forces[b, i] = force
            peak_delta = max(peak_delta, delta)
            peak_force = max(peak_force, force)
            v_next = v_half - h * force / m
            area += force * 0.5 * (v_half + v_next) * h
            delta = delta + h * v_next
            v_half = v_next
            done = i + 1
            if stop < 0 and v_half < 0 and (delta <= 0 or force == 0):
                stop = i
                if n_iter < 0:
                    break
        if record:
            deltas[b, done] = delta
            forces[b, done] = 0.0
        out[b, 0] = area
        out[b, 1] = v_half
        out[b, 2] = peak_force
        out[b, 3] = max(peak_delta, delta)
        stops[b] = stop


def run_two_body(contact, v, dt, m_eff, max_steps):
    """two_body's loop on the kernel. Every member runs as many steps as the slowest needs,
    as in the NumPy loop (which steps the whole batch until all have separated), so the
    histories are the same (B, T). Returns (stop step or None if some member did not
    separate within max_steps, out (B, 4), indentation (B, T), force (B, T))."""
    size = len(contact)
    law = np.ascontiguousarray(contact.law, dtype=np.int64)
    par = law_rows(contact)
    # writable copies: a read-only array is another type to numba, another compilation
    v, dt, m_eff = (np.require(x, dtype=np.float64, requirements=["C", "W"])
                    for x in (v, dt, m_eff))
    out = np.zeros((size, 4))
    stops = np.zeros(size, dtype=np.int64)
    _two_body(law, par, v, dt, m_eff, -max_steps, np.zeros((size, 0)), np.zeros((size, 0)),
              out, stops)
    if np.any(stops < 0):
        return None, out, None, None
    n_iter = int(stops.max()) + 1
    deltas, forces = np.zeros((size, n_iter + 1)), np.zeros((size, n_iter + 1))
    _two_body(law, par, v, dt, m_eff, n_iter, deltas, forces, out, stops)
    return n_iter, out, deltas, forces

