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
(numba alone would only watch this file), see _PhysicsCacheLocator.
"""
from __future__ import annotations

import hashlib
from pathlib import Path

import numba
import numpy as np
from numba import njit, prange

from .. import isolator, scheme
from ..building import N_LEVELS
from ..impact import registry
from ..impact.contact import LAW_ARGUMENTS
from ..results import PEAKS
from ..scheme import step_operators

_HERE = Path(__file__).resolve()
_PHYSICS_SOURCES = [_HERE, *(Path(m.__file__).resolve() for m in (
    isolator, scheme, registry, *registry.LAWS.values()))]


def _install_cache_locator() -> None:
    """Make numba's on-disk cache of this file's kernels stale when any physics source
    changes, not only this file. Private numba API: without it caching still works, keyed on
    this file alone."""
    try:
        from numba.core.caching import CacheImpl, InTreeCacheLocator
    except ImportError:  # pragma: no cover - other numba versions
        return

    class _PhysicsCacheLocator(InTreeCacheLocator):
        @classmethod
        def from_function(cls, py_func, py_file):
            if Path(py_file).resolve() != _HERE:
                return None
            return super().from_function(py_func, py_file)

        def get_source_stamp(self):
            digest = hashlib.sha256()
            for path in _PHYSICS_SOURCES:
                digest.update(path.read_bytes())
            return digest.hexdigest()

    if not any(c.__name__ == "_PhysicsCacheLocator" for c in CacheImpl._locator_classes):
        CacheImpl._locator_classes.insert(0, _PhysicsCacheLocator)


_install_cache_locator()

_JIT = {"cache": True, "nogil": True, "error_model": "numpy"}
_LINK = {"nogil": True, "error_model": "numpy"}  # compiled into the cached kernels that call it

# The physics, written once in its own modules, compiled for scalars.
_isolator_force = njit(isolator.isolator_force)
_plastic_spring = njit(isolator.plastic_spring_force)
_implicit_force = njit(scheme.implicit_force)
_onset_weight = njit(scheme.onset_weight)


def _no_wall(code, delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot, damping_ratio, chi,
             c_imp_coef, c_imp_exponent):
    return 0.0, 0.0


def _link(code, force_terms, otherwise):
    """A dispatch that runs force_terms for members of law `code`, else `otherwise`."""
    def dispatch(law, delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot, damping_ratio,
                 chi, c_imp_coef, c_imp_exponent):
        if law == code:
            return force_terms(delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot,
                               damping_ratio, chi, c_imp_coef, c_imp_exponent)
        return otherwise(law, delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot,
                         damping_ratio, chi, c_imp_coef, c_imp_exponent)
    return njit(**_LINK)(dispatch)


def _law_dispatch():
    """(elastic, dashpot) of the member's law, dispatched on its code: every law of the
    registry, chained; (0, 0) for a member without wall."""
    dispatch = njit(**_LINK)(_no_wall)
    for code, module in registry.LAW_MODULES.items():
        dispatch = _link(code, njit(**_LINK)(module.force_terms), dispatch)
    return dispatch


_law_terms = _law_dispatch()

# Columns of the per-member parameter matrix.
_WALL, _COMPLIANCE, _MASS, _STORY_K = 0, 5, 6, 11
_K2, _K_PLASTIC, _F_YIELD, _GAP, _SCALE, _LAW_ARGS = 15, 16, 17, 18, 19, 20
_N_PAR = _LAW_ARGS + len(LAW_ARGUMENTS)
# Columns of the per-member state carried between chunks of steps.
_U, _V, _FP, _V_IMP, _DELTA_PREV, _IN_CONTACT = 0, 5, 10, 11, 12, 13
_N_STATE = 14


def _peak_columns(n_levels: int) -> dict[str, slice]:
    """Columns of the float peaks in the kernel's (B, columns) matrix, in PEAKS order; the
    integer counts (n_impacts) are kept in their own (B,) array."""
    columns, start = {}, 0
    for q in PEAKS:
        if q.dtype is np.int64:
            continue
        width = int(np.prod(q.trailing_shape(n_levels), dtype=int))
        columns[q.name] = slice(start, start + width)
        start += width
    return columns


_PEAK_COLUMNS = _peak_columns(N_LEVELS)
_P_ACCEL = _PEAK_COLUMNS["peak_total_accel"].start
_P_DRIFT = _PEAK_COLUMNS["peak_interstory_drift"].start
_P_ISO = _PEAK_COLUMNS["peak_isolator_disp"].start
_P_INDENT = _PEAK_COLUMNS["max_indentation"].start
_P_FORCE = _PEAK_COLUMNS["max_impact_force"].start
_P_ENERGY = _PEAK_COLUMNS["impact_energy"].start
_N_PEAKS = max(c.stop for c in _PEAK_COLUMNS.values())


@njit(**_JIT)
def _member(b, s0, s1, ag, dt, op, law, par, state, peaks, n_impacts, hist_row, every,
            h_u, h_acc, h_f, h_d):
    """Steps s0 <= step < s1 of member b: the NumPy loop's step, on scalars."""
    o = op[b]
    # The step operator's 50 coefficients as locals: registers or the stack, never reloaded.
    o00, o01, o02, o03, o04 = o[0, 0], o[0, 1], o[0, 2], o[0, 3], o[0, 4]
    o05, o06, o07, o08, o09 = o[0, 5], o[0, 6], o[0, 7], o[0, 8], o[0, 9]
    o10, o11, o12, o13, o14 = o[1, 0], o[1, 1], o[1, 2], o[1, 3], o[1, 4]
    o15, o16, o17, o18, o19 = o[1, 5], o[1, 6], o[1, 7], o[1, 8], o[1, 9]
    o20, o21, o22, o23, o24 = o[2, 0], o[2, 1], o[2, 2], o[2, 3], o[2, 4]
    o25, o26, o27, o28, o29 = o[2, 5], o[2, 6], o[2, 7], o[2, 8], o[2, 9]
    o30, o31, o32, o33, o34 = o[3, 0], o[3, 1], o[3, 2], o[3, 3], o[3, 4]
    o35, o36, o37, o38, o39 = o[3, 5], o[3, 6], o[3, 7], o[3, 8], o[3, 9]
    o40, o41, o42, o43, o44 = o[4, 0], o[4, 1], o[4, 2], o[4, 3], o[4, 4]
    o45, o46, o47, o48, o49 = o[4, 5], o[4, 6], o[4, 7], o[4, 8], o[4, 9]
    p = par[b]
    w0, w1, w2, w3, w4 = p[_WALL], p[_WALL + 1], p[_WALL + 2], p[_WALL + 3], p[_WALL + 4]
    comp = p[_COMPLIANCE]
    m0, m1, m2, m3, m4 = p[_MASS], p[_MASS + 1], p[_MASS + 2], p[_MASS + 3], p[_MASS + 4]
    sk1, sk2, sk3, sk4 = p[_STORY_K], p[_STORY_K + 1], p[_STORY_K + 2], p[_STORY_K + 3]
    k2, kp, fy, gap = p[_K2], p[_K_PLASTIC], p[_F_YIELD], p[_GAP]
    scale = p[_SCALE]
    q = _LAW_ARGS
    k, n, m_eff, delta_u, k_w = p[q], p[q + 1], p[q + 2], p[q + 3], p[q + 4]
    dashpot, xi, chi, c_coef, c_exp = p[q + 5], p[q + 6], p[q + 7], p[q + 8], p[q + 9]
    code = law[b]
    hrow = hist_row[b]

    st = state[b]
    u0, u1, u2, u3, u4 = st[_U], st[_U + 1], st[_U + 2], st[_U + 3], st[_U + 4]
    v0, v1, v2, v3, v4 = st[_V], st[_V + 1], st[_V + 2], st[_V + 3], st[_V + 4]
    fp, v_imp, delta_prev = st[_FP], st[_V_IMP], st[_DELTA_PREV]
    in_contact = st[_IN_CONTACT] != 0.0

    pk = peaks[b]
    pa0, pa1, pa2 = pk[_P_ACCEL], pk[_P_ACCEL + 1], pk[_P_ACCEL + 2]
    pa3, pa4 = pk[_P_ACCEL + 3], pk[_P_ACCEL + 4]
    pd1, pd2, pd3, pd4 = pk[_P_DRIFT], pk[_P_DRIFT + 1], pk[_P_DRIFT + 2], pk[_P_DRIFT + 3]
    p_iso, p_indent, p_force, energy = pk[_P_ISO], pk[_P_INDENT], pk[_P_FORCE], pk[_P_ENERGY]
    n_imp = n_impacts[b]
    half_dt = 0.5 * dt

    for step in range(s0, s1):
        a = ag[step] * scale  # x 1.0 is exact: unscaled members are unchanged
        # Structure without wall force: p - f(u_n), then the free velocities v_{n+1/2}.
        c0 = _isolator_force(u0, fp, k2)
        d1 = u1 - u0
        d2 = u2 - u1
        d3 = u3 - u2
        d4 = u4 - u3
        c1 = sk1 * d1
        c2 = sk2 * d2
        c3 = sk3 * d3
        c4 = sk4 * d4
        r0 = (c1 - c0) - m0 * a
        r1 = (c2 - c1) - m1 * a
        r2 = (c3 - c2) - m2 * a
        r3 = (c4 - c3) - m3 * a
        r4 = (0.0 - c4) - m4 * a
        n0 = (o00 * r0 + o01 * r1 + o02 * r2 + o03 * r3 + o04 * r4
              + o05 * v0 + o06 * v1 + o07 * v2 + o08 * v3 + o09 * v4)
        n1 = (o10 * r0 + o11 * r1 + o12 * r2 + o13 * r3 + o14 * r4
              + o15 * v0 + o16 * v1 + o17 * v2 + o18 * v3 + o19 * v4)
        n2 = (o20 * r0 + o21 * r1 + o22 * r2 + o23 * r3 + o24 * r4
              + o25 * v0 + o26 * v1 + o27 * v2 + o28 * v3 + o29 * v4)
        n3 = (o30 * r0 + o31 * r1 + o32 * r2 + o33 * r3 + o34 * r4
              + o35 * v0 + o36 * v1 + o37 * v2 + o38 * v3 + o39 * v4)
        n4 = (o40 * r0 + o41 * r1 + o42 * r2 + o43 * r3 + o44 * r4
              + o45 * v0 + o46 * v1 + o47 * v2 + o48 * v3 + o49 * v4)

        # Wall contact on the side the slab moves towards (clamped as in the NumPy loop).
        side = np.sign(u0)
        delta = max(abs(u0) - gap, -1.0)
        touching = delta > 0.0
        new = touching and not in_contact
        if new:
            n_imp += 1
            v_imp = side * v0
        in_contact = touching
        force = 0.0
        if touching:
            rate_free = side * 0.5 * (v0 + n0)
            elastic, dashpot_now = _law_terms(code, delta, rate_free, v_imp, k, n, m_eff,
                                              delta_u, k_w, dashpot, xi, chi, c_coef, c_exp)
            if new:
                dashpot_now = dashpot_now * _onset_weight(delta, delta_prev)
            force = _implicit_force(elastic, dashpot_now, rate_free, comp)
            push = side * force
            n0 = n0 - w0 * push
            n1 = n1 - w1 * push
            n2 = n2 - w2 * push
            n3 = n3 - w3 * push
            n4 = n4 - w4 * push
        delta_prev = delta

        a0 = (n0 - v0) / dt + a
        a1 = (n1 - v1) / dt + a
        a2 = (n2 - v2) / dt + a
        a3 = (n3 - v3) / dt + a
        a4 = (n4 - v4) / dt + a
        pa0 = max(pa0, abs(a0))
        pa1 = max(pa1, abs(a1))
        pa2 = max(pa2, abs(a2))
        pa3 = max(pa3, abs(a3))
        pa4 = max(pa4, abs(a4))
        pd1 = max(pd1, abs(d1))
        pd2 = max(pd2, abs(d2))
        pd3 = max(pd3, abs(d3))
        pd4 = max(pd4, abs(d4))
        p_iso = max(p_iso, abs(u0))
        p_indent = max(p_indent, delta)
        p_force = max(p_force, force)
        energy += force * side * (v0 + n0) * half_dt

        if hrow >= 0 and step % every == 0:
            t = step // every
            h_u[hrow, t] = u0
            h_acc[hrow, t, 0] = a0
            h_acc[hrow, t, 1] = a1
            h_acc[hrow, t, 2] = a2
            h_acc[hrow, t, 3] = a3
            h_acc[hrow, t, 4] = a4
            h_f[hrow, t] = force
            h_d[hrow, t] = max(delta, 0.0)

        # Advance: the isolator's plastic spring sees this step's displacement increment.
        fp = _plastic_spring(fp, dt * n0, kp, fy)
        v0, v1, v2, v3, v4 = n0, n1, n2, n3, n4
        u0 = u0 + dt * n0
        u1 = u1 + dt * n1
        u2 = u2 + dt * n2
        u3 = u3 + dt * n3
        u4 = u4 + dt * n4

    st[_U], st[_U + 1], st[_U + 2], st[_U + 3], st[_U + 4] = u0, u1, u2, u3, u4
    st[_V], st[_V + 1], st[_V + 2], st[_V + 3], st[_V + 4] = v0, v1, v2, v3, v4
    st[_FP], st[_V_IMP], st[_DELTA_PREV] = fp, v_imp, delta_prev
    st[_IN_CONTACT] = 1.0 if in_contact else 0.0
    pk[_P_ACCEL], pk[_P_ACCEL + 1], pk[_P_ACCEL + 2] = pa0, pa1, pa2
    pk[_P_ACCEL + 3], pk[_P_ACCEL + 4] = pa3, pa4
    pk[_P_DRIFT], pk[_P_DRIFT + 1], pk[_P_DRIFT + 2], pk[_P_DRIFT + 3] = pd1, pd2, pd3, pd4
    pk[_P_ISO], pk[_P_INDENT], pk[_P_FORCE], pk[_P_ENERGY] = p_iso, p_indent, p_force, energy
    n_impacts[b] = n_imp


@njit(**_JIT)
def _run_serial(s0, s1, ag, dt, op, law, par, state, peaks, n_impacts, hist_row, every,
                h_u, h_acc, h_f, h_d):
    for b in range(law.size):
        _member(b, s0, s1, ag, dt, op, law, par, state, peaks, n_impacts, hist_row, every,
                h_u, h_acc, h_f, h_d)


@njit(parallel=True, **_JIT)
def _run_parallel(s0, s1, ag, dt, op, law, par, state, peaks, n_impacts, hist_row, every,
                  h_u, h_acc, h_f, h_d):
    for b in prange(law.size):
        _member(b, s0, s1, ag, dt, op, law, par, state, peaks, n_impacts, hist_row, every,
                h_u, h_acc, h_f, h_d)


@njit(**_JIT)
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


def member_parameters(arrays, contact, wall_response, compliance, scale) -> np.ndarray:
    """(B, _N_PAR) float matrix of every per-member constant the step reads."""
    size = len(contact)
    par = np.empty((size, _N_PAR))
    par[:, _WALL:_WALL + N_LEVELS] = wall_response
    par[:, _COMPLIANCE] = compliance
    par[:, _MASS:_MASS + N_LEVELS] = arrays.masses
    par[:, _STORY_K:_STORY_K + N_LEVELS - 1] = arrays.story_k
    par[:, _K2] = arrays.k2
    par[:, _K_PLASTIC] = arrays.k_plastic
    par[:, _F_YIELD] = arrays.f_plastic_yield
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
    n_steps = ag.size
    op, wall_response, compliance = step_operators(arrays, dt)
    par = member_parameters(arrays, contact, wall_response, compliance, scale)
    law = np.ascontiguousarray(contact.law, dtype=np.int64)
    state = np.zeros((size, _N_STATE))
    state[:, _V_IMP] = 1.0
    peaks = np.zeros((size, _N_PEAKS))
    n_impacts = np.zeros(size, dtype=np.int64)
    ag = np.ascontiguousarray(ag, dtype=np.float64)

    hist_row = np.full(size, -1, dtype=np.int64)
    every, n_out, rows, inverse = 1, 0, 0, None
    if history is not None:
        wanted = np.asarray(history.members, dtype=np.int64) % size
        unique, inverse = np.unique(wanted, return_inverse=True)
        rows = unique.size
        hist_row[unique] = np.arange(rows)
        every = int(history.every)
        n_out = (n_steps - 1) // every + 1
    h_u, h_f, h_d = (np.zeros((rows, n_out)) for _ in range(3))
    h_acc = np.zeros((rows, n_out, N_LEVELS))

    run = _run_parallel if threads() > 1 and size > 1 else _run_serial
    args = (ag, float(dt), op, law, par, state, peaks, n_impacts, hist_row, every,
            h_u, h_acc, h_f, h_d)
    # Members one at a time to whichever thread is free: they cost unequally (a member that
    # pounds does more work), and even halves of the batch would leave one thread waiting
    # (gap_size's batch: 81% -> 88% parallel efficiency on 2 threads). Bitwise the same.
    previous = numba.set_parallel_chunksize(1)
    try:
        if progress is None:
            run(0, n_steps, *args)
        else:
            chunk = max(n_steps // 100, 1)
            for start in range(0, n_steps, chunk):
                progress(start, n_steps)
                run(start, min(start + chunk, n_steps), *args)
            progress(n_steps, n_steps)
    finally:
        numba.set_parallel_chunksize(previous)

    result = {}
    for q in PEAKS:
        if q.name in _PEAK_COLUMNS:
            values = peaks[:, _PEAK_COLUMNS[q.name]]
            result[q.name] = (values if q.along else values[:, 0]).copy()
        else:
            result[q.name] = n_impacts
    hist = None
    if history is not None:
        hist = {"time": np.arange(n_out) * every * dt, "isolator_disp": h_u[inverse],
                "total_accel": h_acc[inverse], "impact_force": h_f[inverse],
                "indentation": h_d[inverse],
                "members": np.asarray(history.members, dtype=int)}
    return result, hist


# --- two free bodies (engine.two_body) ---------------------------------------------------

@njit(**_JIT)
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
                elastic, dashpot = _law_terms(code, delta, v_half, v_imp, p[0], p[1], p[2],
                                              p[3], p[4], p[5], p[6], p[7], p[8], p[9])
                force = _implicit_force(elastic, dashpot, v_half, compliance)
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
    v, dt, m_eff = (np.ascontiguousarray(x, dtype=np.float64) for x in (v, dt, m_eff))
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

