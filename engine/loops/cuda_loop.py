"""The device time loop (numba's CUDA target): numba_loop.py's step, one GPU thread per member.

The scheme is engine/scheme.py's and its arithmetic numba_loop._member's, in the same order:
a member's state in registers and local memory, members never interacting (no shared memory,
no synchronisation). The physics is not written here: the impact laws' `force_terms`, the
story and isolator laws, `implicit_force`, `onset_weight` and the collapse rule are the
functions the CPU kernels compile, compiled for the device by cuda_physics. The arrays are
numba_loop.planar_run's, copied to the device once a run (the record with them), and the
results come back in one copy. One kernel per number of levels, story law and isolator law
(compiled when first met, as the CPU kernel is); the impact law is dispatched per member.

The device contracts a * b + c into one fused multiply-add (NVVM's default, which numba does
not switch off): a member's peaks agree with the CPU kernel's to about 1e-14 relative, not bit
for bit (tests/engine/loops/test_cuda_loop.py asks 1e-12).
"""
from __future__ import annotations

import functools

import numpy as np
from numba import cuda, float64

from ..impact.registry import ROW_WIDTH
from ..results import MODE
from . import cuda_physics as device
from .layout import (
    PLANAR,
    PLANAR_PEAK_COLUMNS,
    PLANAR_STATE,
    PLANAR_STORY,
)
from .numba_loop import (  # noqa: F401  (ground_motion, run_two_body: the CPU kernel's)
    ground_motion,
    planar_outcome,
    planar_run,
    run_two_body,
    solve_banded,
)
from .numba_support import by_law, chunk_bounds

__all__ = ["ground_motion", "run_simulation", "run_two_body"]
"""ground_motion and run_two_body are the CPU kernel's: a record's interpolation and two free
bodies are too small a work for the device."""


@functools.cache
def _kernel(n_levels: int, story_code: int, isolator_code: int, banded: bool):
    """The kernel of buildings of n_levels levels on story law `story_code` and isolator law
    `isolator_code` (banded: the tridiagonal solve of a tall building with chain damping):
    kernel(members, s0, s1, model, memory, peaks, hist), numba_loop._member's arguments but
    `members` (the members a thread each) in place of `shape` and `b`."""
    levels = n_levels
    stories = max(n_levels - 1, 1)
    operator_rows = 0 if banded else 2 * n_levels
    operator_size = max(operator_rows, 1)  # a local array's shape: constants only
    story_force = device.story_law(story_code)
    # the member's law constants and state, as wide as its own laws' (the kernel's story and
    # isolator laws): a wider local array only holds registers the laws never read
    n_fields, n_state = device.story_widths(story_code)
    n_row, n_iso_state = device.isolator_widths(isolator_code, "STATE")
    isolator_force = device.isolator_law(isolator_code, "force")
    isolator_advance = device.isolator_law(isolator_code, "advance")
    law_terms, implicit_force, onset_weight, failed = (
        device.law_terms, device.implicit_force, device.onset_weight, device.failed)
    banded_solve = device.device_function(solve_banded)
    sign = device.SCALAR_NUMPY.sign

    def kernel(members, s0, s1, model, memory, peaks, hist):
        t = cuda.grid(1)
        if t >= members.size:
            return
        b = members[t]
        ag, dt, op, which, bands, mass, story, law, par, law_par, story_fields, isolator = model
        u_all, v_all, story_state, state, isolator_state = memory
        peak_level, peak_story, peak_velocity, peak_shear, peak_scalar, n_impacts = peaks
        hist_row, every, h_u, h_acc, h_f, h_d, h_fi = hist
        st = state[b]
        if st[PLANAR_STATE.collapsed] != 0.0:
            return
        n_levels = levels
        # The member's constants and state in local arrays (registers where they fit); its
        # building's (op, bands, mass, story, story_fields, isolator) at which[b]: the
        # members of a sweep share a few, so a warp's reads of one are one broadcast.
        own = which[b]
        ot = cuda.local.array((operator_size, levels), float64)
        for j in range(operator_rows):
            for i in range(levels):
                ot[j, i] = op[own, j, i]
        bd = bands[own]
        w = cuda.local.array(levels, float64)
        m = cuda.local.array(levels, float64)
        u = cuda.local.array(levels, float64)
        v = cuda.local.array(levels, float64)
        pa = cuda.local.array(levels, float64)
        pv = cuda.local.array(levels, float64)
        for i in range(levels):
            w[i], m[i] = op[own, 0, i], mass[own, i]  # w: the operator's first row
            u[i], v[i], pa[i] = u_all[b, i], v_all[b, i], peak_level[b, i]
            pv[i] = peak_velocity[b, i]
        k_story = cuda.local.array(stories, float64)
        gravity = cuda.local.array(stories, float64)
        collapse_drift = cuda.local.array(stories, float64)
        pd = cuda.local.array(stories, float64)
        ps = cuda.local.array(stories, float64)
        s_fields = cuda.local.array((stories, n_fields), float64)
        s_state = cuda.local.array((stories, n_state), float64)
        for i in range(n_levels - 1):
            k_story[i] = story[own, PLANAR_STORY.story_k, i]
            gravity[i] = story[own, PLANAR_STORY.story_gravity, i]
            collapse_drift[i] = story[own, PLANAR_STORY.collapse_drift, i]
            pd[i], ps[i] = peak_story[b, i], peak_shear[b, i]
            for j in range(n_fields):
                s_fields[i, j] = story_fields[own, i, j]
            for j in range(n_state):
                s_state[i, j] = story_state[b, i, j]
        iso_row = cuda.local.array(n_row, float64)
        for j in range(n_row):
            iso_row[j] = isolator[own, j]
        iso_state = cuda.local.array(n_iso_state, float64)
        for j in range(n_iso_state):
            iso_state[j] = isolator_state[b, j]
        law_row = cuda.local.array(ROW_WIDTH, float64)
        for j in range(ROW_WIDTH):
            law_row[j] = law_par[b, j]
        comp = w[0]  # the compliance: the wall response at the slab
        gap = par[b, PLANAR.gap]
        nonlinear = par[b, PLANAR.stories_nonlinear] != 0.0
        scale = par[b, PLANAR.scale]
        capacity = par[b, PLANAR.capacity]
        code = law[b]
        hrow = hist_row[b]

        v_imp = st[PLANAR_STATE.v_imp]
        delta_prev = st[PLANAR_STATE.delta_prev]
        in_contact = st[PLANAR_STATE.in_contact] != 0.0
        p_iso = peak_scalar[b, PLANAR_PEAK_COLUMNS.peak_isolator_disp]
        p_indent = peak_scalar[b, PLANAR_PEAK_COLUMNS.max_indentation]
        p_force = peak_scalar[b, PLANAR_PEAK_COLUMNS.max_impact_force]
        energy = peak_scalar[b, PLANAR_PEAK_COLUMNS.impact_energy]
        p_fiso = peak_scalar[b, PLANAR_PEAK_COLUMNS.peak_isolator_force]
        n_imp = n_impacts[b]
        half_dt = 0.5 * dt

        chain = cuda.local.array(levels, float64)  # isolator, stories 1..N
        drift = cuda.local.array(stories, float64)
        r = cuda.local.array(levels, float64)
        nxt = cuda.local.array(levels, float64)
        mode = 0
        for step in range(s0, s1):
            a = ag[step] * scale
            chain[0] = isolator_force(u[0], iso_state, iso_row)
            if not abs(u[0]) <= capacity:
                mode = failed(mode, u[0], MODE.isolator_capacity)
            for i in range(n_levels - 1):
                drift[i] = u[i + 1] - u[i]
                if not abs(drift[i]) <= collapse_drift[i]:
                    mode = failed(mode, drift[i], MODE.story_drift)
                if nonlinear:
                    chain[i + 1] = story_force(drift[i], s_state[i], s_fields[i]) \
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
            r[n_levels - 1] = (0.0 - chain[n_levels - 1]) - m[n_levels - 1] * a
            if banded:
                banded_solve(bd, r, v, nxt, n_levels, dt)
            else:
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

            u0 = u[0]
            side = sign(u0)
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

            keep = hrow >= 0 and step % every == 0
            for i in range(n_levels):
                total = (nxt[i] - v[i]) / dt + a
                pa[i] = max(pa[i], abs(total))
                pv[i] = max(pv[i], abs(nxt[i]))
                if keep:
                    h_acc[hrow, step // every, i] = total
            for i in range(n_levels - 1):
                pd[i] = max(pd[i], abs(drift[i]))
                if nonlinear:
                    ps[i] = max(ps[i], abs(chain[i + 1] + gravity[i] * drift[i]))
            p_iso = max(p_iso, abs(u0))
            p_fiso = max(p_fiso, abs(chain[0]))
            p_indent = max(p_indent, delta)
            p_force = max(p_force, force)
            energy += force * side * (v[0] + nxt[0]) * half_dt
            if keep:
                k = step // every
                h_u[hrow, k] = u0
                h_f[hrow, k] = force
                h_d[hrow, k] = max(delta, 0.0)
                h_fi[hrow, k] = chain[0]

            isolator_advance(iso_state, nxt[0], dt, iso_row)
            for i in range(n_levels):
                v[i] = nxt[i]
                u[i] = u[i] + dt * nxt[i]

        for i in range(n_levels):
            u_all[b, i], v_all[b, i], peak_level[b, i] = u[i], v[i], pa[i]
            peak_velocity[b, i] = pv[i]
        for i in range(n_levels - 1):
            peak_story[b, i], peak_shear[b, i] = pd[i], ps[i]
            for j in range(n_state):
                story_state[b, i, j] = s_state[i, j]
        for j in range(n_iso_state):
            isolator_state[b, j] = iso_state[j]
        st[PLANAR_STATE.v_imp] = v_imp
        st[PLANAR_STATE.delta_prev] = delta_prev
        st[PLANAR_STATE.in_contact] = 1.0 if in_contact else 0.0
        peak_scalar[b, PLANAR_PEAK_COLUMNS.peak_isolator_disp] = p_iso
        peak_scalar[b, PLANAR_PEAK_COLUMNS.max_indentation] = p_indent
        peak_scalar[b, PLANAR_PEAK_COLUMNS.max_impact_force] = p_force
        peak_scalar[b, PLANAR_PEAK_COLUMNS.impact_energy] = energy
        peak_scalar[b, PLANAR_PEAK_COLUMNS.peak_isolator_force] = p_fiso
        n_impacts[b] = n_imp

    return cuda.jit(kernel)


def to_device(arrays):
    """A tuple of host arrays and numbers as the kernel takes it: arrays copied to the device
    (nested tuples likewise), numbers as they are."""
    if isinstance(arrays, tuple):
        return tuple(to_device(a) for a in arrays)
    if not isinstance(arrays, np.ndarray):
        return arrays
    if arrays.size == 0:  # no histories, no bands: a placeholder the kernel never reads (an
        # empty device allocation is one thing fewer for a driver to get right)
        return cuda.to_device(np.zeros(tuple(max(n, 1) for n in arrays.shape), arrays.dtype))
    return cuda.to_device(arrays)


def to_host(device_arrays, host_arrays) -> None:
    """Copy the device arrays back into the host arrays they came from (to_device)."""
    if isinstance(host_arrays, tuple):
        for d, h in zip(device_arrays, host_arrays, strict=True):
            to_host(d, h)
    elif isinstance(host_arrays, np.ndarray) and host_arrays.size:
        device_arrays.copy_to_host(host_arrays)


def run_on_device(host: tuple, groups, n_steps: int, progress, kernel_of) -> None:
    """Run a packed run on the device: host = (model, memory, kept, hist), the host arrays
    (numba_loop.planar_run's, numba_plan.plan_run's) copied to the device once, memory, kept
    and hist copied back into them at the end; groups: law_groups' of the batch, one launch
    per law combination, kernel_of(story_code, isolator_code) its kernel; with progress, the
    steps in chunks (numba_support.chunk_bounds), the state kept on the device between them."""
    model, memory, kept, hist = to_device(host)
    size = len(groups[1])
    launches = [(kernel_of(*(len(tag) - 1 for tag in tags)), cuda.to_device(chosen))
                for tags, chosen in by_law(np.arange(size), groups)]
    for s0, s1 in chunk_bounds(size, n_steps, progress):
        for kernel, chosen in launches:
            device.launch(kernel, chosen.size, chosen, s0, s1, model, memory, kept, hist)
    cuda.synchronize()
    to_host((memory, kept, hist), host[1:])


def run_simulation(ag, dt, arrays, contact, history, progress, scale=1.0):
    """engine.simulate's time loop on the device: (peaks dict, history dict or None), as
    numba_loop.run_simulation (the same arguments and packed arrays; run_on_device)."""
    run = planar_run(ag, dt, arrays, contact, history, scale)
    n_levels, banded = len(run["levels"]), run["model"][4].shape[2] > 0  # bands
    run_on_device((run["model"], run["memory"], run["kept"], run["hist"]), run["groups"],
                  ag.size, progress,
                  lambda story, isolator: _kernel(n_levels, story, isolator, banded))
    return planar_outcome(run, dt, history)
