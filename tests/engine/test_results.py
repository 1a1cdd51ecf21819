"""The responses beyond the paper's peaks (engine.results: peak_isolator_force, peak_story_shear,
peak_floor_velocity, the RESIDUALS and the isolator_force history), checked against what they
must be whatever the loop: the equations of motion summed over the levels (the stories' forces
cancel, what is left is the isolators' force against the floors' inertia), the bilinear law's
envelope, the scheme's own kinematics (u_{n+1} = u_n + dt v_{n+1/2}) and a building at rest
after a free-vibration tail. Both loops' agreement on them: tests/engine/loops/."""
from __future__ import annotations

import numpy as np
import pytest

import engine
from engine import Building, Contact, History, Isolator, Torsion
from engine.results import RESIDUALS

DT = 0.005
T = np.arange(0.0, 12.0, DT)
AG = 5.0 * np.sin(2 * np.pi * T / 1.4) * np.exp(-(((T - 4.0) / 2.5) ** 2))  # m/s^2
AG_XY = np.column_stack([AG, 0.6 * np.roll(AG, 90)])
# No isolation dashpot and no story dashpots: the chain's forces are the springs' alone.
UNDAMPED = dict(zeta_iso=0.0, zeta_sup=0.0)
FRICTION = Isolator.friction_pendulum(radius=2.0, mu_slow=0.04, mu_fast=0.08, rate=30.0)


def _inertia(building: Building, total_accel: np.ndarray) -> np.ndarray:
    """sum over the levels j >= i of m_j a_j(t), per story i = 0 (the isolators) .. N:
    (T, L) from total accelerations (T, L), or (T, L, 2) from (T, L, 2)."""
    m = np.asarray(building.masses, float)
    m = m[:, None] if total_accel.ndim == 3 else m
    return np.flip(np.cumsum(np.flip(m * total_accel, axis=1), axis=1), axis=1)


# Linear stories' peak shear is k times their peak drift, the others' kept step by step
# (engine.loops.layout.linear_story_shear): both ways are checked, yielding stories included.
@pytest.mark.parametrize(("isolator", "yield_force"), [(Isolator.bilinear(), None),
                                                       (FRICTION, None), (FRICTION, 4e6)],
                         ids=["bilinear", "fp", "fp-yielding-stories"])
def test_the_springs_carry_the_floors_inertia_in_a_plane(isolator, yield_force):
    """Undamped, without a wall: at every step the isolators' force is minus the floors'
    inertia above them, and each story's shear minus that of the floors above it."""
    building = Building(isolator=isolator, story_yield_force=yield_force and (yield_force,) * 4,
                        **UNDAMPED)
    res = engine.simulate(AG, DT, Contact.none(1), building, dt=DT, history=History([0]))
    inertia = _inertia(building, res.history["total_accel"][0])
    scale = np.abs(inertia).max()
    np.testing.assert_allclose(res.history["isolator_force"][0], -inertia[:, 0], rtol=0,
                               atol=1e-9 * scale)
    np.testing.assert_allclose(res.peak_isolator_force[0], np.abs(inertia[:, 0]).max(),
                               rtol=1e-9)
    np.testing.assert_allclose(res.peak_story_shear[0], np.abs(inertia[:, 1:]).max(axis=0),
                               rtol=1e-9)
    assert res.peak_isolator_force[0] > 0.05 * building.g * building.total_mass  # it slid


@pytest.mark.parametrize("building", [Building(**UNDAMPED),
                                      Building(story_stiffness_y=(5e8, 5e8, 4e8, 3e8),
                                               **UNDAMPED)], ids=["alike", "stiffer-along-x"])
def test_the_springs_carry_the_floors_inertia_in_plan(building):
    res = engine.simulate(AG_XY, DT, Contact.none(1), building, dt=DT, moat="rectangular",
                          angle=[30.0], history=History([0]))
    inertia = _inertia(building, res.history["total_accel"][0])  # (T, L, 2)
    scale = np.abs(inertia).max()
    np.testing.assert_allclose(res.history["isolator_force"][0], -inertia[:, 0], rtol=0,
                               atol=1e-9 * scale)
    np.testing.assert_allclose(res.peak_story_shear[0],
                               np.hypot(inertia[:, 1:, 0], inertia[:, 1:, 1]).max(axis=0),
                               rtol=1e-9)


def test_the_bearings_carry_the_floors_inertia_when_the_slab_twists():
    """The bearings' forces summed (the isolation system's shear at the plan's centre) against
    the floors' inertia, each level's mass at its plan centre (the default: no offset)."""
    building = Building(torsion=Torsion(plan_size=(30.0, 20.0)), zeta_iso=0.0)
    res = engine.simulate(AG_XY, DT, Contact.none(1), building, dt=DT, angle=[30.0],
                          history=History([0]))
    inertia = _inertia(building, res.history["total_accel"][0])
    np.testing.assert_allclose(res.history["isolator_force"][0], -inertia[:, 0], rtol=0,
                               atol=1e-9 * np.abs(inertia).max())
    # the level velocities are the scheme's displacement increments over dt
    disp = res.history["floor_disp"][0]  # (T, L, 2)
    speed = np.hypot(*np.moveaxis(np.diff(disp, axis=0), -1, 0)) / DT
    np.testing.assert_allclose(np.max(speed, axis=0), res.peak_floor_velocity[0], rtol=1e-9)


def test_the_bilinear_isolator_peaks_on_its_envelope():
    """The bilinear law's largest force is its envelope at the largest displacement:
    F_y + k2 (u_max - u_y), u_y = F_y / k1."""
    building = Building(**UNDAMPED)
    res = engine.simulate(AG, DT, Contact.none(1), building, dt=DT)
    weight = building.g * building.total_mass
    f_y = building.fy_ratio * weight
    u_max = res.peak_isolator_disp[0]
    assert u_max > 3 * f_y / building.k1  # well past yield
    np.testing.assert_allclose(res.peak_isolator_force[0],
                               f_y + building.k2 * (u_max - f_y / building.k1), rtol=1e-9)


def test_floor_velocities_are_the_displacement_increments():
    """u_{n+1} = u_n + dt v_{n+1/2}: the slab's largest increment over dt is its peak velocity
    (the history holds u_n at every step; the last half step's velocity is not in it)."""
    res = engine.simulate(AG, DT, Contact.concat([Contact.none(1), Contact.bumper([0.10])]),
                          dt=DT, history=History([0, 1]))
    steps = np.abs(np.diff(res.history["isolator_disp"], axis=1)).max(axis=1) / DT
    np.testing.assert_allclose(steps, res.peak_floor_velocity[:, 0], rtol=1e-9)
    assert np.all(np.diff(res.peak_floor_velocity[0]) > 0)  # faster up the height
    assert res.n_impacts[1] > 0


def test_a_building_at_rest_keeps_only_its_isolators_offset():
    """After a long free vibration the elastic stories return to zero drift while a hysteretic
    isolator keeps a permanent offset; a run that collapsed has no residual (NaN)."""
    tail = np.concatenate([AG, np.zeros(int(60.0 / DT))])
    buildings = [Building(), Building(stories=engine.Stories.bilinear(
        yield_force=1.0e6, post_yield_ratio=0.0), story_height=(3.5,) * 4, p_delta=True,
        collapse_drift_ratio=0.05)]
    res = engine.simulate(tail, DT, Contact.none(2), buildings, dt=DT)
    assert res.collapsed.tolist() == [False, True]
    assert res.residual_isolator_disp[0] > 1e-3                       # m: the offset
    assert np.all(res.residual_interstory_drift[0] < 1e-6 * res.peak_interstory_drift[0])
    assert np.isnan(res.residual_isolator_disp[1])
    assert np.all(np.isnan(res.residual_interstory_drift[1]))
    assert set(res.residuals()) == {q.name for q in RESIDUALS}


@pytest.mark.parametrize("moat", [None, "rectangular", "circular"])
def test_both_loops_give_the_residuals(moat):
    accel = AG if moat is None else AG_XY
    contact = Contact.concat([Contact.none(1), Contact.bumper([0.10])])
    building = Building(story_yield_force=(3e6,) * 4)
    runs = [engine.simulate(accel, DT, contact, building, dt=DT, moat=moat, backend=backend)
            for backend in ("numba", "numpy")]
    for name in runs[0].residuals():
        np.testing.assert_allclose(getattr(runs[0], name), getattr(runs[1], name), rtol=1e-9,
                                   atol=1e-12, err_msg=name)
