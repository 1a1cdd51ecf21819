"""The model's range (pipeline.assess.validity). (The counting of comparisons,
pipeline.assess.outcomes: test_outcomes.py.)"""
import numpy as np
import pytest

from engine.impact.laws import rubber_bumper
from engine.units import G
from pipeline.assess import outcomes, validity


def test_rubber_limit_is_the_calibration_tests_stress_and_crushed_bumpers_exceed_it():
    # Kajita et al. 2006: 0.2 kN/mm^2.65 x (8 mm)^2.65 = 49.5 kN on 40 x 40 mm
    assert validity.RUBBER_STRESS_LIMIT == pytest.approx(49.48e3 / 1.6e-3, rel=1e-3)
    # at the crush strain the paper's bumper carries alpha K_r 0.8^n whatever its size
    for side, t in ((0.150, 0.05), (0.3, 0.10)):
        area = side * side
        k = rubber_bumper.impact_stiffness(area, t)
        stress = validity.bumper_stress(k * (0.8 * t) ** 2.65, 1, area)
        assert stress == pytest.approx(2.25 * 55_835e3 * 0.8 ** 2.65, rel=1e-6)
        assert stress == pytest.approx(69.5e6, rel=2e-3) and stress > validity.RUBBER_STRESS_LIMIT
    assert validity.shape_factor(0.15 ** 2, 0.05) == pytest.approx(0.75)


def test_flags():
    limits = validity.Limits(story_shear=10e6, wall_force=50e6)
    accel = np.array([[1.0, 2.0], [1.0, 6 * G], [0.0, 0.0]])
    drift = np.array([[0.01], [0.02], [0.0]])
    force = np.array([0.0, 4 * 0.0225 * 40e6, 60e6])
    got = validity.flags(accel, drift, force, [600e6], limits, n_bumpers=4, area=0.0225)
    assert got["invalid_floor_accel"].tolist() == [False, True, False]
    assert got["invalid_bumper_stress"].tolist() == [False, True, True]
    assert got["invalid_story_shear"].tolist() == [False, True, False]  # 6 and 12 MN
    assert got["invalid_wall_force"].tolist() == [False, False, True]
    assert validity.any_flag(got).tolist() == [False, True, True]
    bare = validity.flags(accel, drift, force, [600e6], validity.Limits(), stories_yield=True)
    assert not bare["invalid_bumper_stress"].any() and not bare["invalid_story_shear"].any()
    assert "not checked" in validity.Limits().describe()


def test_flags_of_takes_the_peaks_as_the_engine_names_them():
    import engine

    building = engine.Building()
    limits = validity.Limits(story_shear=1e6)
    peaks = {"peak_total_accel": np.array([[1.0] * building.n_levels, [6 * G] * 5]),
             "peak_interstory_drift": np.array([[1e-4] * building.n_stories, [0.1] * 4]),
             "max_impact_force": np.array([0.0, 4 * 0.0225 * 40e6])}
    got = validity.flags_of(peaks, building, limits, n_bumpers=4, area=0.0225)
    expected = validity.flags(peaks["peak_total_accel"], peaks["peak_interstory_drift"],
                              peaks["max_impact_force"], building.story_stiffness, limits,
                              n_bumpers=4, area=0.0225)
    assert {k: v.tolist() for k, v in got.items()} == {k: v.tolist()
                                                       for k, v in expected.items()}
    # stress, strain (no thickness given: not checked), floor acceleration, story, wall,
    # collapse (a building without a criterion: none)
    assert [v.tolist() for v in got.values()] == [[False, True], [False, False], [False, True],
                                                  [False, True], [False, False], [False, False]]
    # a collapsed run is flagged as such
    fell = validity.flags_of({**peaks, "collapsed": np.array([False, True])}, building, limits)
    assert fell["invalid_collapse"].tolist() == [False, True]
    # stories with a yield force bound their own shear: not checked
    yielding = engine.Building(story_yield_force=[1e6] * building.n_stories)
    assert not validity.flags_of(peaks, yielding, limits)["invalid_story_shear"].any()


def test_a_collapse_is_the_collapses_effect_never_an_amplification():
    effects = np.array([outcomes.NEUTRAL, outcomes.HELPED, outcomes.HURT, outcomes.HELPED])
    with_bumpers = np.array([True, True, False, True])
    bare = np.array([False, False, True, True])
    got = outcomes.with_collapse(effects, with_bumpers, bare)
    assert got.tolist() == [outcomes.HURT, outcomes.HURT, outcomes.HELPED, outcomes.NEUTRAL]
    untouched = outcomes.with_collapse(effects, np.zeros(4, bool), np.zeros(4, bool))
    assert untouched.tolist() == effects.tolist()
