"""pipeline.assess.annual_loss: the expected annual loss under resamplings of the earthquakes,
each piece against its closed form."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm

from engine.units import G
from pipeline.assess import annual_loss, hazard


def test_weighted_means_count_the_standing_runs_alone():
    values = np.array([[1.0, 10.0], [3.0, np.nan], [5.0, 30.0]])  # (R, config)
    standing = np.array([[True, True], [True, False], [False, True]])
    draws = np.array([[1.0, 0.0], [1.0, 2.0], [1.0, 0.0]])  # (R, D): as is; run 1 twice
    got = annual_loss.weighted_means(values, standing, draws)
    assert got[0].tolist() == pytest.approx([2.0, 20.0])
    assert got[1, 0] == pytest.approx(3.0)
    assert np.isnan(got[1, 1])  # nothing of config 1 stands in that draw
    assert annual_loss.weighted_means(values, standing, np.ones(3)).shape == (1, 2)


def test_the_draws_scale_the_model_by_the_runs_relative_change():
    run_cost = np.array([100.0, 300.0, 500.0])[:, None]
    standing = np.ones((3, 1), bool)
    weights = np.ones(3)
    draws = np.column_stack([weights, [0.0, 0.0, 3.0], [0.0, 0.0, 0.0]])
    got = annual_loss.given_no_collapse(np.array([600.0]), run_cost, standing, weights, draws)
    # as is: the model's own; only the dearest run: 500 / 300 of it; nothing standing: kept
    assert got[:, 0].tolist() == pytest.approx([600.0, 1000.0, 600.0])
    free = annual_loss.given_no_collapse(np.array([50.0]), 0 * run_cost, standing, weights,
                                         draws)
    assert free[:, 0].tolist() == [50.0, 50.0, 50.0]  # runs that cost nothing: no ratio


def test_a_stripes_collapse_is_the_fragility_through_the_drawn_mce_r_value():
    beta = np.array([0.5, 0.6])
    acmr = np.array([[2.0, 1.5], [3.0, 1.2]])  # (D, config)
    mce = norm.cdf(-np.log(acmr) / beta)
    levels = np.array([0.2, 1.0, 1.5])
    got = annual_loss.stripe_collapse(levels, mce, beta)
    assert got.shape == (2, 3, 2)
    exact = norm.cdf(np.log(levels[None, :, None] / acmr[:, None, :]) / beta)
    assert got == pytest.approx(exact, rel=1e-10)
    assert got[:, 1] == pytest.approx(mce, rel=1e-12)


def test_the_annual_loss_is_the_stripes_mean_over_their_intervals():
    curve = hazard.default(0.3 * G)
    levels = np.array([0.2, 0.4, 2 / 3, 1.0, 1.5])
    sa = levels * 0.3 * G
    rates = hazard.interval_rates(sa, curve)
    given = np.full((1, 5, 1), 1000.0)
    # no collapse: 1000 at every stripe happens at their total rate
    none = annual_loss.annual_loss(sa, annual_loss.stripe_means(np.zeros((1, 5, 1)), given,
                                                                1e7), curve)
    assert none[0, 0] == pytest.approx(1000.0 * rates.sum(), rel=1e-12)
    # collapse certain at the top stripe alone: its interval's rate times the replacement
    top = np.zeros((1, 5, 1))
    top[0, -1] = 1.0
    got = annual_loss.annual_loss(sa, annual_loss.stripe_means(top, given, 1e7), curve)
    assert got[0, 0] == pytest.approx(1000.0 * rates[:-1].sum() + 1e7 * rates[-1], rel=1e-12)
    assert math.isfinite(got[0, 0])


def test_the_mixture_of_collapse_and_repair():
    given = np.array([[1.0, 2.0, 3.0, 4.0]])
    mean, q = annual_loss.mixture(given, np.array([0.25]), 100.0, (0.1, 0.5, 0.74, 0.76))
    assert mean[0] == pytest.approx(0.25 * 100 + 0.75 * 2.5)
    # each repair realization weighs 0.75 / 4: cumulative 0.1875, 0.375, 0.5625, 0.75, then 1
    assert q[:, 0].tolist() == [1.0, 3.0, 4.0, 100.0]
    none, _ = annual_loss.mixture(given, np.array([0.0]), 100.0)
    assert none[0] == 2.5


def test_each_runs_value_goes_back_to_its_place():
    standing = np.array([[True, False], [False, True], [True, True]])  # (R 3, groups 2)
    per_group = np.array([[10.0, 30.0], [21.0, 31.0]])  # group 0: runs 0, 2; group 1: 1, 2
    got = annual_loss.runs_in_place(per_group, standing)
    np.testing.assert_array_equal(got, [[10.0, np.nan], [np.nan, 21.0], [30.0, 31.0]])
