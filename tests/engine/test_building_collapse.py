"""P-Delta and collapse in the engine, against closed forms and between the loops: P-Delta on
linear stories is a story of stiffness k - P/h (bit for bit, planar and in plan); a collapsed
member stops with its peaks, in both loops, at the same step; the building's checks.
(OpenSeesPy cross-checks with a leaning column: tests/reference/test_opensees_pdelta.py.)"""
from __future__ import annotations

import numpy as np
import pytest

import engine
from engine import Building, Contact, History, Isolator, Stories, Torsion
from engine.results import MODE

T = np.arange(0.0, 6.0, 0.01)
AG = 3.0 * np.sin(2 * np.pi * 0.7 * T) * np.exp(-0.05 * T)
AG_XY = np.column_stack([AG, 0.6 * np.cos(2 * np.pi * 0.5 * T)])
HEIGHTS = (4.0, 3.5, 3.5, 3.5)


def test_gravity_stiffness_is_the_weight_above_over_the_height():
    b = Building(story_height=HEIGHTS, p_delta=True)
    masses = np.asarray(b.masses)
    expected = [b.g * masses[i:].sum() / HEIGHTS[i - 1] for i in range(1, 5)]
    np.testing.assert_allclose(b.gravity_stiffness, expected, rtol=1e-15)
    assert np.all(Building(story_height=HEIGHTS).gravity_stiffness == 0)


# On the compiled loop: the NumPy loop gives its numbers with P-Delta, in a plane and in plan
# (test_collapse_ends_the_run_at_the_same_step_in_both_loops below).
@pytest.mark.parametrize("backend", ["numba"])
@pytest.mark.parametrize("plan", [False, True])
def test_p_delta_on_linear_stories_is_a_softer_story(backend, plan):
    """With no story dashpots (their rule reads the elastic stiffness), P-Delta on linear
    stories k is the linear story k - P/h, bit for bit, in a plane and in plan; but the
    story's own shear is k times its drift in the first, (k - P/h) times it in the second."""
    pd = Building(zeta_sup=0.0, story_height=HEIGHTS, p_delta=True)
    soft = Building(zeta_sup=0.0, story_stiffness=tuple(np.asarray(pd.story_stiffness)
                                                        - pd.gravity_stiffness))
    contact = Contact.bumper(np.array([0.08, 5.0]))
    ag = (AG_XY if plan else AG)[:300]  # 3 s: contact and yielding-free drifts within it
    a = engine.simulate(ag, 0.01, contact, pd, backend=backend, scale=[1.0, 1.3])
    b = engine.simulate(ag, 0.01, contact, soft, backend=backend, scale=[1.0, 1.3])
    for name, value in a.peaks().items():
        if name != "peak_story_shear":
            assert np.array_equal(value, getattr(b, name)), name
    for building, run in ((pd, a), (soft, b)):
        np.testing.assert_allclose(run.peak_story_shear, np.asarray(building.story_stiffness)
                                   * run.peak_interstory_drift, rtol=1e-12)
    assert not a.collapsed.any() and np.all(np.isnan(a.collapse_time))
    # And it is not the building without P-Delta.
    c = engine.simulate(ag, 0.01, contact, Building(zeta_sup=0.0), backend=backend,
                        scale=[1.0, 1.3])
    assert not np.array_equal(a.peak_interstory_drift, c.peak_interstory_drift)


def _falling(ratio=0.05):
    """Elastic-perfectly-plastic weak stories under their own weight: past yield the story's
    stiffness is -P/h, and a strong enough shake runs it away."""
    return Building(stories=Stories.bilinear(yield_force=1.0e6, post_yield_ratio=0.0),
                    story_height=HEIGHTS, p_delta=True, collapse_drift_ratio=ratio)


@pytest.mark.parametrize("plan", [False, True])
def test_collapse_ends_the_run_at_the_same_step_in_both_loops(plan):
    ag = AG_XY if plan else AG
    contact = Contact.none(4)
    scale = [0.1, 0.8, 1.5, 3.0]
    runs = {be: engine.simulate(ag, 0.01, contact, _falling(), backend=be, scale=scale)
            for be in ("numba", "numpy")}
    a, b = runs["numba"], runs["numpy"]
    assert a.collapsed.tolist() == b.collapsed.tolist() == [False, True, True, True]
    np.testing.assert_array_equal(a.collapse_time, b.collapse_time)
    assert a.collapse_mode.tolist() == b.collapse_mode.tolist() == [0] + [MODE.story_drift] * 3
    assert np.isnan(a.collapse_time[0]) and np.all(np.diff(a.collapse_time[1:]) < 0)
    # The peaks stop at the step before: no drift beyond the collapse drift is reported.
    limit = 0.05 * np.asarray(HEIGHTS)
    assert np.all(a.peak_interstory_drift <= limit + 1e-12)
    for name, value in a.peaks().items():
        np.testing.assert_allclose(value, getattr(b, name), rtol=1e-9, atol=1e-12,
                                   err_msg=name)


@pytest.mark.parametrize("plan", [False, True])
def test_both_loops_agree_on_deteriorating_stories_through_collapse(plan):
    """IMK stories with P-Delta, an intensity sweep from standing to collapse: the NumPy loop
    gives the compiled loop's peaks (to 1e-9), collapse flags, modes and times (the OpenSees
    cross-checks of tests/reference/test_opensees_imk.py then run on the compiled loop)."""
    building = Building(stories=Stories.imk(yield_force=(2.5e6, 2.2e6, 1.7e6, 1.0e6),
                                            plastic_deformation=0.03,
                                            post_capping_deformation=0.3),
                        story_height=HEIGHTS, p_delta=True, collapse_drift_ratio=0.05)
    scale = [0.5, 1.5, 3.0, 6.0]
    ag = AG_XY if plan else AG
    a, b = (engine.simulate(ag, 0.01, Contact.none(4), building, backend=be, scale=scale)
            for be in ("numba", "numpy"))
    assert a.collapsed.tolist() == b.collapsed.tolist()
    assert 0 < a.collapsed.sum() < 4  # some stand, some collapse
    assert a.collapse_mode.tolist() == b.collapse_mode.tolist()
    np.testing.assert_array_equal(a.collapse_time, b.collapse_time)
    assert (a.peak_interstory_drift[~a.collapsed] > building.story_yield_drift).any()  # yields
    for name, value in a.peaks().items():
        np.testing.assert_allclose(value, getattr(b, name), rtol=1e-9, atol=1e-12,
                                   err_msg=name)


def test_a_collapsed_member_is_the_same_in_any_batch():
    alone = engine.simulate(AG, 0.01, Contact.none(1), _falling(), scale=[1.5])
    batch = engine.simulate(AG, 0.01, Contact.none(3), _falling(), scale=[0.1, 1.5, 3.0],
                            progress=lambda step, n: None)  # in chunks of steps
    assert alone.collapse_time[0] == batch.collapse_time[1]
    assert np.array_equal(alone.peak_interstory_drift[0], batch.peak_interstory_drift[1])


def test_without_a_criterion_the_weak_building_runs_on():
    b = Building(stories=Stories.bilinear(yield_force=1.0e6, post_yield_ratio=0.0),
                 story_height=HEIGHTS, p_delta=True)
    r = engine.simulate(AG, 0.01, Contact.none(1), b, scale=[1.5])
    assert not r.collapsed[0]
    assert r.peak_interstory_drift.max() > 0.05 * 4.0  # it went past the 5% above


def _capped(capacity=None, torsion=None):
    """The paper's building on bilinear isolators with a displacement capacity (m)."""
    return Building(isolator=Isolator.bilinear(capacity=capacity), torsion=torsion)


@pytest.mark.parametrize("plan", [False, True])
def test_an_isolator_past_its_capacity_ends_the_run_at_that_step(plan):
    """The run without capacity says when the isolator first passes 60% of its peak: with
    that capacity the run stops at that very step, as an isolator-capacity collapse, in both
    loops, its peaks those of the steps before; the paper's building (no capacity) cannot
    collapse."""
    ag = AG_XY if plan else AG
    assert not _capped().can_collapse and _capped(1.0).can_collapse
    for backend in ("numba", "numpy"):  # each loop against itself: the same bits
        free = engine.simulate(ag, 0.01, Contact.none(1), _capped(), dt=2e-3,
                               history=History(members=(0,)), backend=backend)
        disp = free.history["isolator_disp"][0]
        size = np.hypot(disp[:, 0], disp[:, 1]) if plan else np.abs(disp)
        capacity = 0.6 * free.peak_isolator_disp[0]
        stop = int(np.argmax(size > capacity))
        r = engine.simulate(ag, 0.01, Contact.none(1), _capped(capacity), dt=2e-3,
                            backend=backend)
        assert r.collapsed[0] and r.collapse_mode[0] == MODE.isolator_capacity
        assert r.collapse_time[0] == stop * 2e-3
        assert r.peak_isolator_disp[0] == size[:stop].max() <= capacity


def test_a_bearing_of_a_twisting_building_past_its_capacity_ends_the_run():
    """Each bearing is checked at its own displacement: a slab that turns loses its corner
    bearings no later than its centre would pass the capacity, in both loops alike."""
    torsion = Torsion(plan_size=(30.0, 20.0), mass_offset=(3.0, 2.0))
    free = engine.simulate(AG_XY, 0.01, Contact.none(1), _capped(torsion=torsion), dt=2e-3,
                           history=History(members=(0,)))
    disp = free.history["isolator_disp"][0]
    capacity = 0.6 * free.peak_isolator_disp[0]
    centre_stop = int(np.argmax(np.hypot(disp[:, 0], disp[:, 1]) > capacity)) * 2e-3
    runs = [engine.simulate(AG_XY, 0.01, Contact.none(1), _capped(capacity, torsion),
                            dt=2e-3, backend=backend) for backend in ("numba", "numpy")]
    for r in runs:
        assert r.collapse_mode[0] == MODE.isolator_capacity
        assert r.collapse_time[0] <= centre_stop
    assert runs[0].collapse_time[0] == runs[1].collapse_time[0]


def test_a_state_no_longer_finite_is_a_numerical_instability():
    """A record scaled past what floats hold makes the state infinite, then NaN: the run ends
    as a numerical instability (not as a story's or the isolator's failure), in both loops."""
    for backend in ("numba", "numpy"):
        r = engine.simulate(AG, 0.01, Contact.none(1), Building(), scale=[1e306],
                            backend=backend)
        assert r.collapsed[0] and r.collapse_mode[0] == MODE.numerical_instability


def test_the_building_says_what_is_wrong():
    with pytest.raises(engine.EngineError, match="need story_height"):
        Building(p_delta=True)
    with pytest.raises(engine.EngineError, match="need story_height"):
        Building(collapse_drift_ratio=0.1)
    with pytest.raises(engine.EngineError, match="story_height must be 4 positive"):
        Building(story_height=(3.0, 3.0))
    with pytest.raises(engine.EngineError, match=r"in \(0, 1\]"):
        Building(story_height=HEIGHTS, collapse_drift_ratio=10)
    with pytest.raises(engine.EngineError, match="either as stories= or by story_yield"):
        Building(stories=Stories.linear(), story_yield_force=(1e6,) * 4)
    with pytest.raises(engine.EngineError, match="one number or 4"):
        Building(stories=Stories.bilinear(yield_force=(1e6, 2e6)))
    with pytest.raises(engine.EngineError, match="unknown story law"):
        Stories.of("elastoplastic")


def test_the_shorthand_is_the_bilinear_law():
    short = Building(story_yield_force=(2e6,) * 4, story_post_yield_ratio=0.05)
    law = Building(stories=Stories.bilinear(yield_force=2e6, post_yield_ratio=0.05))
    a = engine.simulate(AG, 0.01, Contact.none(1), short)
    b = engine.simulate(AG, 0.01, Contact.none(1), law)
    assert np.array_equal(a.peak_interstory_drift, b.peak_interstory_drift)
    assert short.story_law.describe() == "bilinear(yield_force = (2e+06, 2e+06, 2e+06, " \
        "2e+06) N, post_yield_ratio = 0.05)"
