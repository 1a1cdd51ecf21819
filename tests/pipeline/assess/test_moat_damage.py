"""The moat inventory (pipeline/assess/moat_damage.py): its quantities for a floor area, each
item's cost in hand-made runs (the triggers written out), the weighted mean over the runs that
stand, and a table that is wrong refused in one line naming its row."""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.assess import moat_damage

DELTA_U = 0.04  # m: the paper's bumper's crush indentation
D_TM = 0.7  # m


def test_the_quantities_of_a_30_m_square_plan():
    """900 m^2: a 120 m perimeter, 5 x 5 bearings under 7.5 m bays, 4 walls of n bumpers."""
    q = moat_damage.quantities(900.0, [0.0, 8.0])
    assert q["perimeter_m"] == 120.0 and q["bearing"] == 25.0 and q["building"] == 1.0
    np.testing.assert_array_equal(q["bumper"], [0.0, 32.0])


def test_each_item_costs_its_quantity_once_its_trigger_holds():
    """Four runs, the default inventory (cover $500/m, wall $25k, bumpers $400 each, bearings
    $20k each, utilities $50k): a contact against the bare wall; a contact crushing one of 8
    bumpers a wall; the isolators past D_TM without contact; nothing. A bare wall's
    indentation past delta_u crushes no bumper."""
    rows = moat_damage.read()
    assert [r["item"] for r in rows] == ["moat_cover", "moat_wall", "bumpers", "bearings",
                                         "utilities"]
    peaks = {"n_impacts": np.array([3, 1, 0, 0]),
             "max_indentation": np.array([0.05, 0.05, 0.0, 0.0]),
             "peak_isolator_disp": np.array([0.6, 0.6, 0.71, 0.3])}
    bumpers = np.array([0.0, 8.0, 8.0, 8.0])
    cost = moat_damage.costs(rows, peaks, d_tm=D_TM, delta_u=DELTA_U, bumpers=bumpers,
                             floor_area=900.0)
    assert cost.shape == (5, 4)
    np.testing.assert_array_equal(cost.sum(axis=0),
                                  [120 * 500 + 25_000,
                                   120 * 500 + 25_000 + 32 * 400,
                                   25 * 20_000 + 50_000,
                                   0.0])


def test_the_mean_weighs_each_standing_run_by_its_share():
    """Runs weighed by their pair's share, the collapsed left out (the replacement holds
    them); 0 where none stands."""
    item_costs = np.array([[[100.0, 0.0], [200.0, 0.0], [900.0, 0.0]]])  # (1 item, 3 runs, 2)
    standing = np.array([[True, False], [True, False], [False, False]])
    share = np.array([0.5, 0.25, 0.25])
    mean = moat_damage.mean_given_no_collapse(item_costs, standing, share)
    np.testing.assert_allclose(mean, [[(0.5 * 100 + 0.25 * 200) / 0.75, 0.0]])


def test_a_wrong_table_is_refused_naming_its_line(tmp_path):
    bad = tmp_path / "moat.csv"
    bad.write_text("item,trigger,per,unit_cost,description\n"
                   "cover,contact,perimeter_m,500,ok\n"
                   "wall,earthquake,building,1,no\n")
    with pytest.raises(ValueError, match=r"line 3: trigger must be one of contact, crushed"):
        moat_damage.read(bad)
    bad.write_text("item,trigger,per,unit_cost,description\ncover,contact,acre,500,no\n")
    with pytest.raises(ValueError, match=r"line 2: per must be one of perimeter_m"):
        moat_damage.read(bad)
    bad.write_text("item,trigger,per,unit_cost,description\ncover,contact,building,-1,no\n")
    with pytest.raises(ValueError, match=r"line 2: unit_cost must be >= 0"):
        moat_damage.read(bad)


def test_the_realizations_draw_whole_runs_by_their_weights():
    """Stratified draws of standing runs: the realizations' mean is the weighted mean to a
    slice of the weights per run, each realization one run's cost, the same realization the
    same slice in another configuration (common random numbers), none where no run stands."""
    run_costs = np.array([[0.0, 10.0, 0.0], [100.0, 10.0, 0.0], [5000.0, 10.0, 0.0]])  # (R, 3)
    standing = np.array([[True, True, False], [True, True, False], [False, True, False]])
    share = np.array([0.5, 0.3, 0.2])
    draws = moat_damage.realizations(run_costs, standing, share, samples=1000)
    assert draws.shape == (3, 1000)
    np.testing.assert_allclose(draws.mean(axis=-1), [0.3 / 0.8 * 100, 10.0, 0.0], atol=0.2)
    assert set(np.unique(draws[0])) == {0.0, 100.0}  # never the collapsed run's 5000
    again = moat_damage.realizations(run_costs[:, :1] * 2, standing[:, :1], share, 1000)
    np.testing.assert_array_equal(again[0] == 200.0, draws[0] == 100.0)

