"""The isolator laws' physics, written once: on a NumPy batch (numpy_isolators.IsolatorBatch,
every law's members at once) and compiled for one member at a time (the law's functions as a
kernel compiles them, compiled.compiled_isolator) the same numbers, bit for bit, along a random
path through yield and back, along one axis and in plan, per member and per bearing; and the
state each law keeps is the one it declares."""
from __future__ import annotations

import functools

import numpy as np
import pytest

from engine import Building, Isolator
from engine.building import building_arrays
from engine.isolators.registry import LAWS
from engine.loops import compiled
from engine.loops.layout import isolator_rows
from engine.loops.numpy_isolators import IsolatorBatch

TFP = dict(L1=0.3, L2=1.5, L3=1.6, d1=0.05, d2=0.15, d3=0.15, mu1=0.01, mu2=0.02, mu3=0.03)
ISOLATORS = (Isolator.bilinear(),
             Isolator.friction_pendulum(radius=2.0, mu_slow=0.05, mu_fast=0.10, rate=30.0),
             Isolator.triple_friction_pendulum(**TFP),
             Isolator.friction_pendulum(radius=3.0, mu_slow=0.07, mu_fast=0.07, rate=10.0),
             Isolator.bilinear(k1=1e8, k2=1e7, fy_ratio=0.06),
             # stops close: the path meets them (a bearing pushed past its capacity)
             Isolator.triple_friction_pendulum(**{**TFP, "d1": 0.01, "d2": 0.02, "d3": 0.025},
                                               yield_disp=2e-3))
DT = 0.005  # s
STEPS = 300


def _batch():
    """Members of mixed laws, and a path (STEPS, members, 2) of velocities (m/s) whose
    displacements pass 0.1 m: every member slips and unloads in both directions (the
    triple friction pendulums: every element slides, and the second one's elements pass their
    stops)."""
    arrays = building_arrays([Building(isolator=iso) for iso in ISOLATORS], len(ISOLATORS))
    rng = np.random.default_rng(7)
    t = np.arange(STEPS)[:, None, None] * DT
    velocity = 0.6 * np.sin(2 * np.pi * t / 0.7 + rng.uniform(0, 6, (1, len(ISOLATORS), 2))) \
        + rng.normal(0.0, 0.05, (STEPS, len(ISOLATORS), 2))
    return arrays, velocity


@pytest.mark.parametrize("bearings", [None, 3], ids=["one", "bearings"])
def test_the_numpy_batch_and_the_compiled_law_agree_bit_for_bit_in_plan(bearings):
    arrays, velocity = _batch()
    batch = IsolatorBatch(arrays, plan=True, bearings=bearings)
    codes, rows = arrays.isolator_code, isolator_rows(arrays, bearings or 1)
    n = bearings or 1
    # each bearing its own path: the member's, turned a little (a slab that twists)
    spin = 1.0 + 0.1 * np.arange(n)
    vx = velocity[..., 0][..., None] * spin
    vy = velocity[..., 1][..., None] / spin
    states = np.zeros((len(ISOLATORS), n, max(len(law.STATE_XY) for law in LAWS.values())))
    ux, uy = np.zeros((len(ISOLATORS), n)), np.zeros((len(ISOLATORS), n))
    largest = 0.0
    for step in range(STEPS):
        shape = (len(ISOLATORS),) if bearings is None else (len(ISOLATORS), n)
        fx, fy = batch.force_xy(ux.reshape(shape), uy.reshape(shape))
        for m in range(len(ISOLATORS)):
            for k in range(n):
                sx, sy = compiled.compiled_isolator(codes[m], "force_xy")(
                    ux[m, k], uy[m, k], states[m, k], rows[m])
                assert (np.reshape(fx, (-1, n))[m, k], np.reshape(fy, (-1, n))[m, k]) == (sx, sy)
                compiled.compiled_isolator(codes[m], "advance_xy")(
                    states[m, k], vx[step, m, k], vy[step, m, k], DT, rows[m])
        batch.advance_xy(vx[step].reshape(shape), vy[step].reshape(shape), DT)
        ux, uy = ux + DT * vx[step], uy + DT * vy[step]
        largest = max(largest, np.abs(ux).max())
    assert largest > 0.1  # the path goes well past every law's yield


def _slip_limits(isolator, width):
    """(width,) the lowest limit each of the law's STATE columns reaches when it is a slip
    element's force (inf for the others)."""
    building = Building()
    fields = isolator.fields(building.total_mass, building.g)
    law = LAWS[isolator.law]
    out = np.full(width, np.inf)
    for name in law.STATE._fields:
        if name == "slip_force":  # one slip element, its limit at the lowest speed
            out[law.STATE.slip_force] = fields["f_limit"] * (1 - fields.get("slow_drop", 0.0))
        elif name.startswith("slip_"):  # an element of the series: slip_inner, ...
            out[getattr(law.STATE, name)] = fields[name.replace("slip_", "limit_")]
    return out


def test_the_numpy_batch_and_the_compiled_law_agree_bit_for_bit_along_one_axis():
    arrays, velocity = _batch()
    batch = IsolatorBatch(arrays)
    codes, rows = arrays.isolator_code, isolator_rows(arrays)
    states = np.zeros((len(ISOLATORS), max(len(law.STATE) for law in LAWS.values())))
    u = np.zeros(len(ISOLATORS))
    limits = np.array([_slip_limits(iso, states.shape[1]) for iso in ISOLATORS])
    slipped = np.zeros_like(states)
    for step in range(STEPS):
        force = batch.force(u)
        for m in range(len(ISOLATORS)):
            law = functools.partial(compiled.compiled_isolator, codes[m])
            assert force[m] == law("force")(u[m], states[m], rows[m])
            law("advance")(states[m], velocity[step, m, 0], DT, rows[m])
        batch.advance(velocity[step, :, 0], DT)
        u = u + DT * velocity[step, :, 0]
        slipped = np.maximum(slipped, np.abs(states) / limits)
    # every slip element reached its limit (the friction's at least its slow value)
    assert (slipped[limits < np.inf] >= 1 - 1e-12).all()


def test_a_collapsed_member_is_set_back_at_rest():
    arrays, velocity = _batch()
    batch = IsolatorBatch(arrays, plan=True)
    for step in range(50):
        batch.advance_xy(velocity[step, :, 0], velocity[step, :, 1], DT)
    zero = np.zeros(len(ISOLATORS))
    before = batch.force_xy(zero, zero)
    batch.reset(np.arange(len(ISOLATORS)) == 1)
    after = batch.force_xy(zero, zero)
    assert after[0][1] == after[1][1] == 0.0
    assert after[0][0] == before[0][0] and after[0][2] == before[0][2] != 0.0
