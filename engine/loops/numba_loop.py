"""The compiled time loop (numba): the default backend of engine.simulate and engine.two_body.

The scheme is engine/scheme.py's, member by member: members outer, steps inner, every piece of
a member's state in local scalars. The physics is not written here: the impact laws'
`force_terms`, the isolator's return mapping, `implicit_force` and `onset_weight` are the very
functions the NumPy loop calls on arrays, compiled here for scalars; the laws come from the
registry, chained into one dispatch on the member's law code (`_law_dispatch`).

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

from ..impact.contact import LAW_ARGUMENTS
from ..results import PEAKS
from ..scheme import banded_operators, step_operators
from ..stories.registry import MAX_FIELDS, MAX_STATE
from . import compiled
from .compiled import (
    JIT,
    LINK,
    PHYSICS_FILES,
    implicit_force,
    isolator_force,
    law_terms,
    onset_weight,
    plastic_spring,
    slip_limit,
    story_force,
)
from .numba_support import (
    data_pointer,
    history_rows,
    install_cache_locator,
    run_members,
    stack_doubles,
)

# Cached kernels go stale when any physics source they compile changes, not only this file.
install_cache_locator(Path(__file__), [compiled.__file__, *PHYSICS_FILES])



# Columns of the per-member scalar parameters.
(_COMPLIANCE, _K_ELASTIC, _K_SLIP, _F_LIMIT, _SLOW_DROP, _RATE, _STORIES_NONLINEAR, _GAP,
 _SCALE, _LAW_ARGS) = range(10)
_N_PAR = _LAW_ARGS + len(LAW_ARGUMENTS)
# Columns of the per-member scalar state carried between chunks of steps (the displacements
# and velocities of every level are arrays of their own).
_FP, _V_IMP, _DELTA_PREV, _IN_CONTACT, _COLLAPSED, _COLLAPSE_TIME = range(6)
_N_STATE = 6
# The peaks: per level (peak_total_accel), per story (peak_interstory_drift), the scalar
# float peaks in PEAKS order in one matrix, the integer count (n_impacts) in its own array.
_SCALAR_PEAKS = tuple(q.name for q in PEAKS if q.along is None and q.dtype is not np.int64)
_P_ISO, _P_INDENT, _P_FORCE, _P_ENERGY = (_SCALAR_PEAKS.index(name) for name in (
    "peak_isolator_disp", "max_indentation", "max_impact_force", "impact_energy"))


@njit(**LINK)
def _solve_banded(bd, r, v, out, n_levels, dt):
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


@njit(**JIT)
def _member(levels, law_tag, b, s0, s1, ag, dt, op, bands, wall, mass, story, law, par, u_all,
            v_all, story_fields, story_state, state, peak_level, peak_story, peak_scalar, n_impacts,
            hist_row, every, h_u, h_acc, h_f, h_d):
    """Steps s0 <= step < s1 of member b: the NumPy loop's step, on scalars and the member's
    own small arrays (L levels, L - 1 stories; `levels` is a tuple of L zeros, so that L is a
    compile-time constant; `law_tag` a tuple of (story law code + 1) zeros, so that the
    member's story law is one too and its force is the only one compiled into this kernel:
    one compilation per number of levels and story law). Sums run in the order of the scalar
    kernel this loop replaced, and a member's result never depends on the batch. A member
    that has collapsed stops."""
    st = state[b]
    if st[_COLLAPSED] != 0.0:
        return
    n_levels = len(levels)
    ot = op[b]
    bd = bands[b]
    banded = bd.shape[1] > 0
    w = wall[b]
    m = mass[b]
    k_story, gravity, collapse_drift = story[b, 0], story[b, 1], story[b, 2]
    # The story law's constants and state as views of a shape known when the kernel compiles.
    s_fields = carray(data_pointer(story_fields[b]), (n_levels - 1, MAX_FIELDS))
    s_state = carray(data_pointer(story_state[b]), (n_levels - 1, MAX_STATE))
    p = par[b]
    comp = p[_COMPLIANCE]
    k_el, k_slip, f_limit, gap = p[_K_ELASTIC], p[_K_SLIP], p[_F_LIMIT], p[_GAP]
    slow_drop, rate = p[_SLOW_DROP], p[_RATE]
    nonlinear = p[_STORIES_NONLINEAR] != 0.0
    story_law = len(law_tag) - 1
    scale = p[_SCALE]
    q = _LAW_ARGS
    k, n, m_eff, delta_u, k_w = p[q], p[q + 1], p[q + 2], p[q + 3], p[q + 4]
    dashpot, xi, chi, c_coef, c_exp = p[q + 5], p[q + 6], p[q + 7], p[q + 8], p[q + 9]
    code = law[b]
    hrow = hist_row[b]

    fp, v_imp, delta_prev = st[_FP], st[_V_IMP], st[_DELTA_PREV]
    in_contact = st[_IN_CONTACT] != 0.0
    pk = peak_scalar[b]
    p_iso, p_indent, p_force, energy = pk[_P_ISO], pk[_P_INDENT], pk[_P_FORCE], pk[_P_ENERGY]
    n_imp = n_impacts[b]
    half_dt = 0.5 * dt

    # The member's working arrays on the stack: of a size known when it compiles, registers.
    u = carray(stack_doubles(levels), (n_levels,))
    v = carray(stack_doubles(levels), (n_levels,))
    pa = carray(stack_doubles(levels), (n_levels,))
    pd = carray(stack_doubles(levels), (n_levels - 1,))
    for i in range(n_levels):
        u[i], v[i], pa[i] = u_all[b, i], v_all[b, i], peak_level[b, i]
    for i in range(n_levels - 1):
        pd[i] = peak_story[b, i]
    chain = carray(stack_doubles(levels), (n_levels,))  # isolator, stories 1..N
    drift = carray(stack_doubles(levels), (n_levels - 1,))
    r = carray(stack_doubles(levels), (n_levels,))
    nxt = carray(stack_doubles(levels), (n_levels,))
    fallen = False
    for step in range(s0, s1):
        a = ag[step] * scale  # x 1.0 is exact: unscaled members are unchanged
        # Structure without wall force: p - f(u_n), then the free velocities v_{n+1/2}.
        chain[0] = isolator_force(u[0], fp, k_el)
        for i in range(n_levels - 1):
            drift[i] = u[i + 1] - u[i]
            # A story past its collapse drift, or a state no longer finite (NaN fails the
            # comparison), ends the member's run below: its peaks are the steps' before.
            if not abs(drift[i]) <= collapse_drift[i]:
                fallen = True
            if nonlinear:  # the story law's force, less what P-Delta takes
                chain[i + 1] = story_force(story_law, drift[i], s_state[i], s_fields[i]) \
                    - gravity[i] * drift[i]
            else:
                chain[i + 1] = k_story[i] * drift[i]
        if fallen:
            st[_COLLAPSED] = 1.0
            st[_COLLAPSE_TIME] = step * dt
            break
        for i in range(n_levels - 1):
            r[i] = (chain[i + 1] - chain[i]) - m[i] * a
        r[n_levels - 1] = (0.0 - chain[n_levels - 1]) - m[n_levels - 1] * a  # the free roof
        if banded:
            _solve_banded(bd, r, v, nxt, n_levels, dt)
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
            elastic, dashpot_now = law_terms(code, delta, rate_free, v_imp, k, n, m_eff,
                                              delta_u, k_w, dashpot, xi, chi, c_coef, c_exp)
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
            if keep:
                h_acc[hrow, step // every, i] = total
        for i in range(n_levels - 1):
            pd[i] = max(pd[i], abs(drift[i]))
        p_iso = max(p_iso, abs(u0))
        p_indent = max(p_indent, delta)
        p_force = max(p_force, force)
        energy += force * side * (v[0] + nxt[0]) * half_dt

        if keep:
            t = step // every
            h_u[hrow, t] = u0
            h_f[hrow, t] = force
            h_d[hrow, t] = max(delta, 0.0)

        # Advance: the isolator's slip element sees this step's displacement increment, its
        # limit at this step's sliding speed (exactly f_limit without speed dependence: the
        # branch only spares the bilinear law an exp).
        limit = f_limit if slow_drop == 0.0 else slip_limit(f_limit, slow_drop, rate, nxt[0])
        fp = plastic_spring(fp, dt * nxt[0], k_slip, limit)
        for i in range(n_levels):
            v[i] = nxt[i]
            u[i] = u[i] + dt * nxt[i]

    for i in range(n_levels):
        u_all[b, i], v_all[b, i], peak_level[b, i] = u[i], v[i], pa[i]
    for i in range(n_levels - 1):
        peak_story[b, i] = pd[i]
    st[_FP], st[_V_IMP], st[_DELTA_PREV] = fp, v_imp, delta_prev
    st[_IN_CONTACT] = 1.0 if in_contact else 0.0
    pk[_P_ISO], pk[_P_INDENT], pk[_P_FORCE], pk[_P_ENERGY] = p_iso, p_indent, p_force, energy
    n_impacts[b] = n_imp


@njit(**JIT)
def _run(levels, law_tag, members, s0, s1, ag, dt, op, bands, wall, mass, story, law, par, u, v,
         story_fields, story_state, state, peak_level, peak_story, peak_scalar, n_impacts,
         hist_row, every, h_u, h_acc, h_f, h_d):
    """Steps s0 <= step < s1 of the members in `members` (indices), one after the other. One
    compilation per number of levels (the length of `levels` is part of its type): loops of
    known length, the member's arrays on the stack. It releases the GIL: run_simulation hands
    batches of members to threads (numba_support.run_members)."""
    for b in members:
        _member(levels, law_tag, b, s0, s1, ag, dt, op, bands, wall, mass, story, law, par, u, v,
                story_fields, story_state, state, peak_level, peak_story, peak_scalar,
                n_impacts, hist_row, every, h_u, h_acc, h_f, h_d)


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


def member_parameters(arrays, contact, compliance, scale) -> np.ndarray:
    """(B, _N_PAR) float matrix of every per-member scalar the step reads."""
    par = np.empty((len(contact), _N_PAR))
    par[:, _COMPLIANCE] = compliance
    par[:, _K_ELASTIC] = arrays.k_elastic
    par[:, _K_SLIP] = arrays.k_slip
    par[:, _F_LIMIT] = arrays.f_limit
    par[:, _SLOW_DROP] = arrays.slow_drop
    par[:, _RATE] = arrays.rate
    par[:, _STORIES_NONLINEAR] = ~arrays.story_linear
    par[:, _GAP] = contact.clear_gap
    par[:, _SCALE] = scale
    for i, name in enumerate(LAW_ARGUMENTS):
        par[:, _LAW_ARGS + i] = getattr(contact, name)
    return par


def run_simulation(ag, dt, arrays, contact, history, progress, scale=1.0):
    """engine.simulate's time loop on the kernel: (peaks dict, history dict or None).

    ag (N,) on the step grid; arrays: BuildingArrays and contact: Contact, both of B members in
    batch order; history: engine.History or None; progress: callable(step, n_steps) or None.
    With progress the run goes in chunks of about 1% of the steps, the state kept in arrays
    between chunks (the same arithmetic, so the same bits); without, in one call.
    """
    size = len(contact)
    n_levels = arrays.masses.shape[1]
    levels = (0,) * n_levels  # its length, part of its type, specialises the kernel
    n_steps = ag.size
    op, wall_response, compliance = step_operators(arrays, dt)
    bands = banded_operators(arrays, dt)
    if bands is None:
        bands = np.zeros((size, 5, 0))
    par = member_parameters(arrays, contact, compliance, scale)
    law = np.ascontiguousarray(contact.law, dtype=np.int64)
    u, v = np.zeros((size, n_levels)), np.zeros((size, n_levels))
    # Per story: the linear stiffness (P-Delta folded in), P-Delta's stiffness (subtracted
    # from a nonlinear law's force), the collapse drift; the story law's constants and state.
    story = np.ascontiguousarray(np.stack([arrays.story_k, arrays.story_gravity,
                                           arrays.collapse_drift], axis=1))
    story_fields = np.ascontiguousarray(arrays.story_fields, dtype=np.float64)
    story_state = np.array(arrays.story_state, dtype=np.float64, order="C")
    state = np.zeros((size, _N_STATE))
    state[:, _V_IMP] = 1.0
    peak_level, peak_story = np.zeros((size, n_levels)), np.zeros((size, n_levels - 1))
    peak_scalar = np.zeros((size, len(_SCALAR_PEAKS)))
    n_impacts = np.zeros(size, dtype=np.int64)
    ag = np.ascontiguousarray(ag, dtype=np.float64)

    hist_row, every, rows, inverse = history_rows(history, size)
    n_out = 0 if history is None else (n_steps - 1) // every + 1
    h_u, h_f, h_d = (np.zeros((rows, n_out)) for _ in range(3))
    h_acc = np.zeros((rows, n_out, n_levels))

    args = (ag, float(dt), np.ascontiguousarray(op.transpose(0, 2, 1)), bands,
            np.ascontiguousarray(wall_response), np.ascontiguousarray(arrays.masses), story,
            law, par, u, v, story_fields, story_state, state, peak_level, peak_story,
            peak_scalar, n_impacts, hist_row, every, h_u, h_acc, h_f, h_d)
    codes = arrays.story_code

    def steps(members, s0, s1):
        # One kernel per story law (law_tag): each member runs the one its stories follow.
        for code in np.unique(codes[members]):
            _run(levels, (0,) * (int(code) + 1), members[codes[members] == code], s0, s1,
                 *args)
    run_members(size, n_steps, progress, steps)

    by_name = {"peak_total_accel": peak_level, "peak_interstory_drift": peak_story,
               "n_impacts": n_impacts,
               **{name: peak_scalar[:, i].copy() for i, name in enumerate(_SCALAR_PEAKS)}}
    result = {q.name: by_name[q.name] for q in PEAKS}
    result["collapsed"] = state[:, _COLLAPSED] != 0.0
    result["collapse_time"] = np.where(result["collapsed"], state[:, _COLLAPSE_TIME], np.nan)
    hist = None
    if history is not None:
        hist = {"time": np.arange(n_out) * every * dt, "isolator_disp": h_u[inverse],
                "total_accel": h_acc[inverse], "impact_force": h_f[inverse],
                "indentation": h_d[inverse],
                "members": np.asarray(history.members, dtype=int)}
    return result, hist


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
                elastic, dashpot = law_terms(code, delta, v_half, v_imp, p[0], p[1], p[2],
                                              p[3], p[4], p[5], p[6], p[7], p[8], p[9])
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
    par = np.ascontiguousarray(np.column_stack([getattr(contact, f) for f in LAW_ARGUMENTS]))
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

