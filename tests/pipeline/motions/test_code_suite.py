"""pipeline.motions.code_suite beyond its scaling (tested with the rules and bounds): a suite
run in both orientations (FEMA P695's two runs of each pair of a three-dimensional model)."""
from __future__ import annotations

import numpy as np

import engine
from pipeline.motions.code_suite import ORIENTATIONS, SWAPPED, both_orientations, code_suite
from pipeline.records import resolve_pairs
from pipeline.suite_labels import archive_variables

RECORDS = ["RSN953", "RSN960", "RSN1602"]  # two earthquakes: Northridge twice, Duzce


def test_both_orientations_swap_each_pair_and_share_its_weight():
    pairs, names = resolve_pairs(RECORDS)
    suite = code_suite(pairs, names, engine.Building(), rule="p695")
    both = both_orientations(suite)
    n = len(suite.pairs)
    assert both.names == [*suite.names, *(name + SWAPPED for name in suite.names)]
    for pair, swapped in zip(both.pairs[:n], both.pairs[n:], strict=True):
        np.testing.assert_array_equal(swapped.accel, pair.accel[:, ::-1])
        assert swapped.dt == pair.dt and swapped.event == pair.event
    np.testing.assert_array_equal(both.factors, np.tile(suite.factors, 2))
    assert both.orientations == (ORIENTATIONS[0],) * n + (ORIENTATIONS[1],) * n
    # each orientation half its pair's weight, the earthquakes weighing as before
    np.testing.assert_allclose(both.weights, np.tile(suite.weights, 2), rtol=1e-12)
    coords = archive_variables(both)[1]
    assert list(coords["record_orientation"].values) == list(both.orientations)
    assert "record_orientation" not in archive_variables(suite)[1]


def test_a_building_stiffer_along_y_tells_the_orientations_apart_an_isotropic_one_not():
    """Run in plan in a square moat, a pair and its swapped pair: the same peaks bit for bit
    on an isotropic building (the exchange of x and y is a symmetry of it), other peaks on
    one whose stories are twice as stiff along y."""
    (pair,), _ = resolve_pairs(RECORDS[:1])
    accel = pair.accel[: int(15.0 / pair.dt)]
    wall = engine.Contact.linear([0.15, 0.15])
    for building, same in ((engine.Building(), True),
                           (engine.Building(story_stiffness_y=(1.2e9,) * 4), False)):
        runs = [engine.simulate(a, pair.dt, wall, building, scale=[2.0, 2.0])
                for a in (accel, accel[:, ::-1])]
        equal = [np.array_equal(getattr(runs[0], name), getattr(runs[1], name))
                 for name in ("peak_isolator_disp", "max_impact_force", "peak_interstory_drift")]
        assert all(equal) if same else not any(equal)
