"""The slab-wall friction (mu_wall) and the stories' stiffness along y (story_stiffness_y) of
runs in plan, on both backends.

Friction is checked by the building's momentum, exactly as the scheme keeps it: with an elastic
isolator (no yield, no isolation dashpot) the floors' total accelerations weighted by their
masses equal the isolator's force -k1 u0 plus the moat's force on the slab, step by step, so
the moat's force can be read off the histories and split into its normal and tangential parts:
- while the slab slides along a wall, the tangential part is mu_wall times the normal one, and
  opposes the sliding;
- while it sticks, its tangential displacement does not change;
- with mu_wall = 0 the run is the frictionless one, bit for bit.
Per-direction stiffness: one component along x or along y gives the planar run of the building
with that direction's stories. The compiled loop is checked against these; the NumPy loop
against the compiled one (friction and stiffer x than y included), and on the sliding case.
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

import engine
from engine import Building, Contact, Moat

BACKENDS = ("numba", "numpy")
K1 = 10e6  # N/m: an isolator that stays elastic here (yield force 0.9 W at 1.35 m)
ELASTIC = Building(k1=K1, k2=1e6, fy_ratio=0.9, zeta_iso=0.0)
MASS = np.asarray(ELASTIC.masses)


@functools.cache
def pair(seconds: float = 4.0):
    from pipeline.records import paper_record

    rec = paper_record("pacoima")
    accel = rec.accel[: int(seconds / rec.dt) + 1]
    return np.column_stack([accel, 0.8 * accel[::-1]]), rec.dt


def moat_force(result, member: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """The moat's force on the slab (T, 2) N, from the momentum of the building, and the
    isolator's displacement (T, 2) m, of a history member."""
    row = list(result.history["members"]).index(member)
    accel = result.history["total_accel"][row]  # (T, levels, 2)
    u0 = result.history["isolator_disp"][row]
    assert np.hypot(u0[:, 0], u0[:, 1]).max() < ELASTIC.yield_displacement
    return np.einsum("l,tld->td", MASS, accel) + K1 * u0, u0


def run(mu, moat="rectangular", backend="numba", contact_y=None):
    accel, dt = pair()
    return engine.simulate(accel, dt, Contact.linear([0.10] * np.size(mu)), ELASTIC,
                           moat=Moat(moat, contact_y=contact_y, mu_wall=mu), backend=backend,
                           history=engine.History(list(range(np.size(mu))), every=1))


# On the compiled loop: the NumPy loop gives its numbers to 1e-9 with friction
# (test_no_friction_is_the_frictionless_run_and_the_loops_agree, below).
@pytest.mark.parametrize("backend", ["numba"])
def test_sliding_along_a_wall_costs_mu_times_the_normal_force(backend):
    """x walls only (the y walls out of reach): normal along x, friction along y."""
    far = Contact.linear([5.0])
    result = run([0.3], contact_y=far, backend=backend)
    force, u0 = moat_force(result)
    normal, tangential = np.abs(force[:, 0]), force[:, 1]
    pushing = normal > 1e3  # N
    sliding = np.zeros_like(pushing)
    sliding[:-1] = np.diff(u0[:, 1]) != 0.0
    slide, stick = pushing & sliding, pushing & ~sliding
    assert slide.sum() > 50 and result.n_impacts[0] >= 2
    np.testing.assert_allclose(np.abs(tangential[slide]), 0.3 * normal[slide], rtol=1e-6)
    # against the sliding: the force's y part opposes the next step's y displacement
    step_y = np.diff(u0[:, 1])
    assert np.all(tangential[:-1][slide[:-1]] * step_y[slide[:-1]] < 0)
    assert np.all(np.abs(tangential[stick]) <= 0.3 * normal[stick] * (1 + 1e-6))
    # the walls' work now includes the friction's: more than without it
    frictionless = run([0.0], contact_y=far, backend=backend)
    assert result.impact_energy[0] > frictionless.impact_energy[0]


def test_a_slab_that_sticks_does_not_slide(backend="numba"):
    """mu_wall = 10: inside the friction cone the slab's tangential position holds; it slides
    only as a contact begins, while the normal force is still small."""
    far = Contact.linear([5.0])
    result = run([10.0], contact_y=far, backend=backend)
    force, u0 = moat_force(result)
    normal, tangential = np.abs(force[:-1, 0]), np.abs(force[:-1, 1])
    inside = (normal > 1e3) & (tangential < 10.0 * normal * (1 - 1e-9))
    assert inside.sum() > 0.9 * (normal > 1e3).sum() > 50
    np.testing.assert_array_equal(np.diff(u0[:, 1])[inside], 0.0)


def test_circular_moat_friction_is_tangential_and_bounded(backend="numba"):
    result = run([0.3], moat="circular", backend=backend)
    force, u0 = moat_force(result)
    radius = np.hypot(u0[:, 0], u0[:, 1])
    n = u0 / np.maximum(radius, 1e-300)[:, None]
    normal = -np.sum(force * n, axis=1)
    tangential = force[:, 0] * -n[:, 1] + force[:, 1] * n[:, 0]
    pushing = normal > 1e3
    assert pushing.sum() > 50
    ratio = np.abs(tangential[pushing]) / normal[pushing]
    assert ratio.max() == pytest.approx(0.3, rel=1e-6)
    assert np.all(ratio <= 0.3 * (1 + 1e-6))
    sliding = np.isclose(ratio, 0.3, rtol=1e-6)
    assert sliding.sum() > 100 and (~sliding).sum() > 100  # the slab slides and sticks


@pytest.mark.parametrize("moat", ["rectangular", "circular"])
def test_no_friction_is_the_frictionless_run_and_the_loops_agree(moat):
    accel, dt = pair()
    contact = Contact.concat([Contact.linear([0.08, 0.12]), Contact.bumper([0.10],
                                                                           thickness=0.05)])
    plain = engine.simulate(accel, dt, contact, moat=moat)
    zero = engine.simulate(accel, dt, contact, moat=Moat(moat, mu_wall=0.0))
    for name, value in {**plain.peaks(), **plain.plan_peaks()}.items():
        np.testing.assert_array_equal(getattr(zero, name), value, err_msg=name)
    mixed = [0.0, 0.2, 0.6]
    fast, ref = (engine.simulate(accel, dt, contact, moat=Moat(moat, mu_wall=mixed),
                                 backend=backend) for backend in BACKENDS)
    for name, value in {**ref.peaks(), **ref.plan_peaks()}.items():
        np.testing.assert_allclose(getattr(fast, name), value, rtol=1e-9,
                                   atol=1e-9 * np.abs(value).max(), err_msg=name)
    # the frictionless member of the mixed batch is the frictionless run
    np.testing.assert_allclose(ref.peak_isolator_disp[0], plain.peak_isolator_disp[0],
                               rtol=1e-12)
    # friction works on the bumpers' member: the walls take more energy
    assert ref.impact_energy[2] > 1.003 * plain.impact_energy[2]


def test_friction_is_refused_out_of_range():
    accel, dt = pair()
    with pytest.raises(engine.EngineError, match="mu_wall"):
        engine.simulate(accel, dt, Contact.linear([0.1]),
                        moat=Moat("circular", mu_wall=-0.1))
    refusal = "the planar model takes none.*a record pair \\(accel \\(N, 2\\)"
    with pytest.raises(engine.EngineError, match=refusal):
        engine.simulate(accel[:, 0], dt, Contact.linear([0.1]), moat=Moat(mu_wall=0.2))


SOFT_Y = (300e6, 280e6, 250e6, 200e6)  # N/m per story along y


def test_stories_per_direction(backend="numba"):
    """One component along x is the planar run of the x stories; along y, of the y stories
    (with bumpers, so that the walls see the right compliance)."""
    accel, dt = pair()
    walls = Contact.concat([Contact.none(1), Contact.linear([0.10]),
                            Contact.bumper([0.12], thickness=0.05)])
    building = Building(story_stiffness_y=SOFT_Y)
    for axis, stories in ((0, building.story_stiffness), (1, SOFT_Y)):
        component = np.zeros_like(accel)
        component[:, axis] = accel[:, 0]
        for moat in ("rectangular", "circular"):
            plan = engine.simulate(component, dt, walls, building, moat=moat, backend=backend)
            flat = engine.simulate(accel[:, 0], dt, walls, Building(story_stiffness=stories),
                                   backend=backend)
            for name, value in flat.peaks().items():
                np.testing.assert_allclose(getattr(plan, name), value, rtol=1e-9,
                                           atol=1e-9 * np.abs(value).max(),
                                           err_msg=f"{name} along {'xy'[axis]}, {moat}")
            np.testing.assert_array_equal(plan.peak_isolator_disp_xy[:, 1 - axis], 0.0)


def test_stories_per_direction_on_both_loops_and_refused_with_yielding():
    accel, dt = pair()
    walls = Contact.concat([Contact.linear([0.08]), Contact.bumper([0.10], thickness=0.05)])
    buildings = [Building(story_stiffness_y=SOFT_Y), Building()]
    fast, ref = (engine.simulate(accel, dt, walls, buildings, angle=20.0,
                                 moat=Moat("circular", mu_wall=0.1), backend=backend)
                 for backend in BACKENDS)
    for name, value in {**ref.peaks(), **ref.plan_peaks()}.items():
        np.testing.assert_allclose(getattr(fast, name), value, rtol=1e-9,
                                   atol=1e-9 * np.abs(value).max(), err_msg=name)
    with pytest.raises(engine.EngineError, match="linear stories"):
        Building(story_stiffness_y=SOFT_Y, story_yield_force=(3e6,) * 4)
    with pytest.raises(engine.EngineError, match="story_stiffness_y must be 4"):
        Building(story_stiffness_y=(1e8,) * 3)
