"""The isolator laws' physics, written once: on a NumPy batch (numpy_isolators.IsolatorBatch,
every law's members at once) and compiled for one member at a time (compiled.isolator_force
and its kin, dispatched on the law's code) the same numbers, bit for bit, along a random path
through yield and back, along one axis and in plan, per member and per bearing; and the
state each law keeps is the one it declares."""
from __future__ import annotations

import numpy as np
import pytest

from engine import Building, Isolator
from engine.building import building_arrays
from engine.isolators.registry import LAWS
from engine.loops import compiled
from engine.loops.layout import isolator_rows
from engine.loops.numpy_isolators import IsolatorBatch

ISOLATORS = (Isolator.bilinear(),
             Isolator.friction_pendulum(radius=2.0, mu_slow=0.05, mu_fast=0.10, rate=30.0),
             Isolator.friction_pendulum(radius=3.0, mu_slow=0.07, mu_fast=0.07, rate=10.0),
             Isolator.bilinear(k1=1e8, k2=1e7, fy_ratio=0.06))
DT = 0.005  # s
STEPS = 300


def _batch():
    """Four members of mixed laws, and a path (STEPS, 4, 2) of velocities (m/s) whose
    displacements reach about 0.3 m: every member slips and unloads in both directions."""
    arrays = building_arrays([Building(isolator=iso) for iso in ISOLATORS], len(ISOLATORS))
    rng = np.random.default_rng(7)
    t = np.arange(STEPS)[:, None, None] * DT
    velocity = 0.6 * np.sin(2 * np.pi * t / 0.7 + rng.uniform(0, 6, (1, 4, 2))) \
        + rng.normal(0.0, 0.05, (STEPS, 4, 2))
    return arrays, velocity


@pytest.mark.parametrize("bearings", [None, 3], ids=["one", "bearings"])
def test_the_numpy_batch_and_the_compiled_dispatch_agree_bit_for_bit_in_plan(bearings):
    arrays, velocity = _batch()
    batch = IsolatorBatch(arrays, plan=True, bearings=bearings)
    codes, rows = isolator_rows(arrays, bearings or 1)
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
                sx, sy = compiled.isolator_force_xy(codes[m], ux[m, k], uy[m, k], states[m, k],
                                                    rows[m])
                assert (np.reshape(fx, (-1, n))[m, k], np.reshape(fy, (-1, n))[m, k]) == (sx, sy)
                compiled.isolator_advance_xy(codes[m], states[m, k], vx[step, m, k],
                                             vy[step, m, k], DT, rows[m])
        batch.advance_xy(vx[step].reshape(shape), vy[step].reshape(shape), DT)
        ux, uy = ux + DT * vx[step], uy + DT * vy[step]
        largest = max(largest, np.abs(ux).max())
    assert largest > 0.1  # the path goes well past every law's yield


def test_the_numpy_batch_and_the_compiled_dispatch_agree_bit_for_bit_along_one_axis():
    arrays, velocity = _batch()
    batch = IsolatorBatch(arrays)
    codes, rows = isolator_rows(arrays)
    states = np.zeros((len(ISOLATORS), max(len(law.STATE) for law in LAWS.values())))
    u = np.zeros(len(ISOLATORS))
    slipped = np.zeros(len(ISOLATORS))
    for step in range(STEPS):
        force = batch.force(u)
        for m in range(len(ISOLATORS)):
            assert force[m] == compiled.isolator_force(codes[m], u[m], states[m], rows[m])
            compiled.isolator_advance(codes[m], states[m], velocity[step, m, 0], DT, rows[m])
        batch.advance(velocity[step, :, 0], DT)
        u = u + DT * velocity[step, :, 0]
        slipped = np.maximum(slipped, np.abs(states[:, 0]))  # both laws: the slip force
    # every member reached its slip limit (the friction's at least its slow value)
    building = Building()
    for m, iso in enumerate(ISOLATORS):
        fields = iso.fields(building.total_mass, building.g)
        assert slipped[m] >= fields["f_limit"] * (1 - fields.get("slow_drop", 0.0)) * (1 - 1e-12)


def test_a_collapsed_member_is_set_back_at_rest():
    arrays, velocity = _batch()
    batch = IsolatorBatch(arrays, plan=True)
    for step in range(50):
        batch.advance_xy(velocity[step, :, 0], velocity[step, :, 1], DT)
    zero = np.zeros(len(ISOLATORS))
    before = batch.force_xy(zero, zero)
    batch.reset(np.array([False, True, False, False]))
    after = batch.force_xy(zero, zero)
    assert after[0][1] == after[1][1] == 0.0
    assert after[0][0] == before[0][0] and after[0][2] == before[0][2] != 0.0
