"""pipeline.assess.fragility on synthetic lognormal data: recovery of known (theta, beta), the
stripes
MLE against a brute-force grid of the same likelihood written independently, censored IDA
against the naive fit, degenerate data, record weights and non-monotonic outcomes."""
from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from pipeline.assess.fragility import BETA_BOUNDS, Fragility, fit_ida, fit_stripes
from pipeline.assess.fragility_outcomes import event_weights, fit_outcomes

THETA, BETA = 1.3, 0.4
"""The synthetic fragility: median 1.3 (IM units, e.g. m/s^2), log standard deviation 0.4."""
LEVELS = np.geomspace(0.4, 4.0, 10)
"""Ten stripes around the median: P from 0.002 to 0.998."""


def true_probability(x):
    return stats.norm.cdf(np.log(np.asarray(x) / THETA) / BETA)


def synthetic_capacities(n, seed):
    """(n,) lognormal capacities with the synthetic median and dispersion."""
    rng = np.random.default_rng(seed)
    return THETA * np.exp(BETA * rng.standard_normal(n))


# ---------------------------------------------------------------------------------------------
# Recovery of known parameters
# ---------------------------------------------------------------------------------------------


def test_ida_recovers_a_lognormal_and_is_the_moment_estimate():
    """2000 capacities: theta and beta within 3 %; the estimate is the mean and the population
    standard deviation (1/n) of ln capacity, the lognormal MLE (Baker's eq. 5 uses n - 1)."""
    c = synthetic_capacities(2000, seed=1)
    fit = fit_ida(c)
    assert fit.theta == pytest.approx(THETA, rel=0.03)
    assert fit.beta == pytest.approx(BETA, rel=0.03)
    assert fit.theta == pytest.approx(np.exp(np.mean(np.log(c))), rel=1e-12)
    assert fit.beta == pytest.approx(np.std(np.log(c), ddof=0), rel=1e-12)
    assert fit.log_likelihood == pytest.approx(
        np.sum(stats.norm.logpdf(np.log(c), np.log(fit.theta), fit.beta)), rel=1e-12)
    assert (fit.status, fit.identifiable, fit.method) == ("ok", True, "ida")
    assert (fit.n_records, fit.n_censored) == (2000.0, 0)


def test_stripes_recover_with_many_records_per_level():
    """10 levels, 2000 records each: theta and beta within 3 %."""
    rng = np.random.default_rng(2)
    z = rng.binomial(2000, true_probability(LEVELS))
    fit = fit_stripes(LEVELS, z, 2000)
    assert fit.theta == pytest.approx(THETA, rel=0.03)
    assert fit.beta == pytest.approx(BETA, rel=0.03)
    assert (fit.status, fit.identifiable, fit.method) == ("ok", True, "stripes")
    assert (fit.n_records, fit.n_levels) == (2000.0, 10)


def test_stripes_with_few_records_are_median_unbiased_for_theta():
    """20 records per level, 200 seeds: the median of the estimated theta is within 3 % of the
    true one, and nearly every fit is identifiable."""
    rng = np.random.default_rng(3)
    counts = rng.binomial(20, true_probability(LEVELS), size=(200, LEVELS.size))
    fits = [fit_stripes(LEVELS, z, 20) for z in counts]
    assert np.median([f.theta for f in fits]) == pytest.approx(THETA, rel=0.03)
    assert np.median([f.beta for f in fits]) == pytest.approx(BETA, rel=0.15)
    assert np.mean([f.identifiable for f in fits]) > 0.95


def test_probability_is_the_lognormal_cdf():
    fit = Fragility(theta=THETA, beta=BETA, method="ida", n_records=1.0, n_levels=1,
                    log_likelihood=0.0, status="ok", identifiable=True)
    assert fit.probability(THETA) == pytest.approx(0.5)
    assert fit.probability(THETA * np.exp(BETA)) == pytest.approx(stats.norm.cdf(1.0))
    x = np.array([[0.0, 0.5], [1.3, 9.0]])
    np.testing.assert_allclose(fit.probability(x), [[0.0, true_probability(0.5)],
                                                    [0.5, true_probability(9.0)]], rtol=1e-12)
    assert isinstance(fit.probability(1.0), float)


# ---------------------------------------------------------------------------------------------
# The stripes MLE against a brute-force grid
# ---------------------------------------------------------------------------------------------


def grid_log_likelihood(ln_theta, ln_beta, x, z, n):
    """The binomial log-likelihood (no coefficient) on a grid of (ln theta, ln beta), written
    from scipy.stats with clipped probabilities: (G1, G2) from (G1, 1) and (1, G2)."""
    p = stats.norm.cdf((np.log(x) - ln_theta[..., None]) / np.exp(ln_beta[..., None]))
    p = np.clip(p, 1e-300, 1.0 - 1e-16)
    return np.sum(z * np.log(p) + (n - z) * np.log1p(-p), axis=-1)


def grid_maximum(x, z, n):
    """(theta, beta, max log-likelihood) by a coarse grid and then a finer one around its best
    point (steps 0.01 then 5e-5 in ln theta and ln beta)."""
    ln_t = np.linspace(np.log(0.2), np.log(5.0), 323)
    ln_b = np.linspace(np.log(0.05), np.log(2.0), 369)
    for _ in range(2):
        ll = grid_log_likelihood(ln_t[:, None], ln_b[None, :], x, z, n)
        i, j = np.unravel_index(np.argmax(ll), ll.shape)
        step_t, step_b = ln_t[1] - ln_t[0], ln_b[1] - ln_b[0]
        best_t, best_b, best = ln_t[i], ln_b[j], ll[i, j]
        ln_t = np.linspace(best_t - 2 * step_t, best_t + 2 * step_t, 401)
        ln_b = np.linspace(best_b - 2 * step_b, best_b + 2 * step_b, 401)
    return np.exp(best_t), np.exp(best_b), best


@pytest.mark.parametrize("n", [
    np.array([15, 15, 20, 20, 12, 10], dtype=float),
    # effective counts from record weights: non-integer
    np.array([14.5, 13.25, 17.75, 18.0, 11.5, 9.5]),
])
def test_stripes_mle_matches_a_grid_maximisation(n):
    x = np.array([0.3, 0.6, 0.9, 1.2, 1.8, 2.7])
    z = np.round(n * np.array([0.0, 0.15, 0.3, 0.55, 0.8, 0.9]) * 4) / 4
    fit = fit_stripes(x, z, n)
    theta, beta, best = grid_maximum(x, z, n)
    assert fit.identifiable and fit.status == "ok"
    assert fit.theta == pytest.approx(theta, rel=2e-4)
    assert fit.beta == pytest.approx(beta, rel=2e-4)
    # the optimiser's maximum is at least the grid's, to rounding
    assert fit.log_likelihood >= best - 1e-9
    assert fit.log_likelihood == pytest.approx(best, abs=1e-6)


def test_repeated_levels_add_up_and_level_weights_scale_the_counts():
    merged = fit_stripes([1.0, 2.0, 3.0], [5, 12, 18], [40, 20, 20])
    repeated = fit_stripes([1.0, 3.0, 2.0, 1.0], [5, 18, 12, 0], [20, 20, 20, 20])
    assert (repeated.theta, repeated.beta) == pytest.approx((merged.theta, merged.beta),
                                                            rel=1e-7)
    assert repeated.n_levels == 3
    doubled = fit_stripes([1.0, 2.0, 3.0], [5, 12, 18], [40, 20, 20], weights=2.0)
    assert (doubled.theta, doubled.beta) == pytest.approx((merged.theta, merged.beta),
                                                          rel=1e-7)
    assert doubled.log_likelihood == pytest.approx(2 * merged.log_likelihood, rel=1e-9)


# ---------------------------------------------------------------------------------------------
# Censored IDA
# ---------------------------------------------------------------------------------------------


def test_censored_ida_recovers_while_the_naive_fit_is_biased_low():
    """Capacities above 1.5 unknown (36 % of records never have the event): the censored MLE
    stays within 3 %; taking them at 1.5, or dropping them, biases theta and beta low."""
    c = synthetic_capacities(2000, seed=4)
    top = 1.5
    fit = fit_ida(c, max_level=top)
    assert fit.n_censored == np.count_nonzero(c > top) > 600
    assert fit.theta == pytest.approx(THETA, rel=0.03)
    assert fit.beta == pytest.approx(BETA, rel=0.03)
    assert fit.identifiable and fit.status == "ok"
    # the same through explicit flags, censored records given as inf
    flagged = fit_ida(np.where(c > top, np.inf, c), max_level=top)
    assert flagged.theta == pytest.approx(fit.theta, rel=1e-9)
    at_top = fit_ida(np.minimum(c, top))
    dropped = fit_ida(c[c <= top])
    for naive in (at_top, dropped):
        assert naive.theta < 0.95 * THETA and naive.beta < 0.85 * BETA


def test_mostly_censored_ida_is_flagged_extrapolated():
    """With the analyses stopped at 1.0 (a quarter of the records reach the event) the median
    is above every level analysed: the estimate stands, flagged."""
    c = synthetic_capacities(2000, seed=5)
    fit = fit_ida(c, max_level=1.0)
    assert fit.extrapolated and fit.identifiable and fit.theta > 1.0
    assert fit.status.startswith("extrapolated: median")
    assert fit.theta == pytest.approx(THETA, rel=0.05)


def test_ida_from_outcomes_censors_at_the_highest_level_run():
    """Per-record outcomes of an IDA: capacities the first level with the event, censored at
    the last level run (nan: not run) when the event never occurs."""
    x = np.array([0.5, 1.0, 2.0, 4.0])
    nan = np.nan
    outcomes = np.array([[0, 1, nan, nan],    # capacity 1.0, the IDA stopped at the event
                         [0, 0, 0, 1],        # 4.0
                         [0, 0, 1, nan],      # 2.0
                         [0, 0, 0, nan],      # never, run up to 2.0: censored at 2.0
                         [0, 0, 0, 0],        # never: censored at 4.0
                         [1, 1, 1, 1]])       # 0.5, at the first level
    fit = fit_outcomes(x, outcomes, method="ida")
    expected = fit_ida([1.0, 4.0, 2.0, 2.0, 4.0, 0.5],
                       censored=[False, False, False, True, True, False])
    assert (fit.theta, fit.beta) == pytest.approx((expected.theta, expected.beta), rel=1e-9)
    assert (fit.n_censored, fit.n_levels, fit.n_records) == (2, 4, 6.0)


# ---------------------------------------------------------------------------------------------
# Degenerate data
# ---------------------------------------------------------------------------------------------


def test_never_observed_gives_nan_and_says_where():
    x = [0.5, 1.0, 2.0, 4.0]
    fits = [fit_stripes(x, 0, 20),
            fit_ida([np.inf] * 5, max_level=4.0),
            fit_outcomes(x, np.zeros((5, 4), bool)),
            fit_outcomes(x, np.zeros((5, 4), bool), method="ida")]
    for fit in fits:
        assert np.isnan(fit.theta) and np.isnan(fit.beta) and not fit.identifiable
        assert fit.status == "never observed: median above 4"
        assert np.isnan(fit.probability(1.0))


def test_always_observed_gives_nan_and_says_where():
    x = [0.5, 1.0, 2.0, 4.0]
    fits = [fit_stripes(x, 20, 20),
            fit_ida([0.5] * 5, min_level=0.5),
            fit_outcomes(x, np.ones((5, 4), bool)),
            fit_outcomes(x, np.ones((5, 4), bool), method="ida")]
    for fit in fits:
        assert np.isnan(fit.theta) and np.isnan(fit.beta) and not fit.identifiable
        assert fit.status == "always observed: median below 0.5"


def test_a_single_transition_level_leaves_beta_on_its_lower_bound():
    """None at 0.5, 7 of 20 at 1.0, all at 2 and 4: the likelihood grows as beta -> 0, the
    median is at the transition level."""
    fit = fit_stripes([0.5, 1.0, 2.0, 4.0], [0, 7, 20, 20], 20)
    assert not fit.identifiable and fit.beta_at_bound
    assert fit.beta == pytest.approx(BETA_BOUNDS[0])
    assert fit.status.startswith("beta not identifiable: a single transition level 1 ")
    assert fit.theta == pytest.approx(1.0, rel=0.01)
    # the same with no level in between: a step somewhere from 1 to 2
    step = fit_stripes([0.5, 1.0, 2.0, 4.0], [0, 0, 20, 20], 20)
    assert not step.identifiable and step.beta == pytest.approx(BETA_BOUNDS[0])
    assert "a step between 1 (no event) and 2 (only events)" in step.status
    assert 1.0 <= step.theta <= 2.0


def test_an_outcome_flat_in_intensity_puts_beta_on_its_upper_bound():
    fit = fit_stripes([0.5, 1.0, 2.0, 4.0], 10, 20)
    assert not fit.identifiable and fit.beta_at_bound
    assert fit.beta == pytest.approx(BETA_BOUNDS[1])
    assert fit.status.startswith("beta not identifiable: at upper bound 3")


def test_a_single_level_does_not_identify_beta():
    fit = fit_stripes([1.0], [7], [20])
    assert not fit.identifiable
    assert fit.status.startswith("beta not identifiable: a single level 1 gives only P(1)")
    assert fit.probability(1.0) == pytest.approx(7 / 20, rel=1e-4)


def test_a_median_beyond_the_levels_is_flagged_extrapolated():
    """Levels 0.1 to 0.5, far below the median 1.3: the expected counts fit a curve whose
    median is beyond the levels; identifiable but flagged."""
    x = np.array([0.1, 0.2, 0.3, 0.4, 0.5])
    z = np.round(1000 * true_probability(x))
    assert z[0] == 0 and z[-1] > 0
    fit = fit_stripes(x, z, 1000)
    assert fit.extrapolated and fit.identifiable and fit.theta > 0.5
    assert fit.status.startswith("extrapolated: median")
    assert "outside the tested levels [0.1, 0.5]" in fit.status


# ---------------------------------------------------------------------------------------------
# Weights, non-monotonic outcomes
# ---------------------------------------------------------------------------------------------


def some_outcomes(seed=6, records=12):
    """(R, L) outcomes of records with lognormal capacities at LEVELS, monotonic."""
    c = synthetic_capacities(records, seed)
    return LEVELS[None, :] >= c[:, None]


@pytest.mark.parametrize("method", ["stripes", "ida"])
def test_a_record_twice_at_half_weight_is_the_record_once(method):
    outcomes = some_outcomes()
    doubled = np.vstack([outcomes, outcomes[:1]])
    weights = np.r_[0.5, np.ones(len(outcomes) - 1), 0.5]
    once = fit_outcomes(LEVELS, outcomes, method=method)
    twice = fit_outcomes(LEVELS, doubled, weights=weights, method=method)
    assert (twice.theta, twice.beta, twice.log_likelihood) == pytest.approx(
        (once.theta, once.beta, once.log_likelihood), rel=1e-9)
    assert twice.n_records == once.n_records


def test_a_duplicated_capacity_at_half_weight_is_the_capacity_once():
    c = synthetic_capacities(30, seed=7)
    for top in (None, 1.6):  # uncensored (closed form) and censored (optimiser)
        once = fit_ida(c, max_level=top)
        twice = fit_ida(np.r_[c, c[:1]], weights=np.r_[0.5, np.ones(29), 0.5], max_level=top)
        assert (twice.theta, twice.beta, twice.log_likelihood) == pytest.approx(
            (once.theta, once.beta, once.log_likelihood), rel=1e-7)


def test_event_weights_give_each_earthquake_the_same_total():
    w = event_weights(["kobe", "kobe", "northridge", "chichi", "chichi", "chichi"])
    np.testing.assert_allclose(w, [1.0, 1.0, 2.0, 2 / 3, 2 / 3, 2 / 3])
    assert w.sum() == pytest.approx(6.0)
    np.testing.assert_allclose(event_weights([3, 1, 2]), 1.0)


def test_event_weights_enter_the_stripe_counts():
    """Records weighted by earthquake: the counts per level are the weight sums."""
    outcomes = some_outcomes(records=6)
    w = event_weights([0, 0, 1, 2, 2, 2])
    fit = fit_outcomes(LEVELS, outcomes, weights=w)
    expected = fit_stripes(LEVELS, w @ outcomes, w.sum())
    assert (fit.theta, fit.beta) == pytest.approx((expected.theta, expected.beta), rel=1e-7)


def test_non_monotonic_records_are_counted_and_ida_takes_the_first_event():
    """Record 0 touches the wall at 1.0, not at 2.0 ("resurrection"), again at 4.0."""
    x = np.array([0.5, 1.0, 2.0, 4.0])
    outcomes = np.array([[0, 1, 0, 1],
                         [0, 0, 1, 1],
                         [0, 1, 1, 1],
                         [0, 0, 0, 1],
                         [0, 0, 1, 0],    # non-monotonic too: event at 2.0, not at 4.0
                         [0, 0, 0, 0]], dtype=bool)
    ida = fit_outcomes(x, outcomes, method="ida")
    assert ida.n_nonmonotonic == 2
    expected = fit_ida([1.0, 2.0, 1.0, 4.0, 2.0, np.inf], max_level=4.0)
    assert (ida.theta, ida.beta) == pytest.approx((expected.theta, expected.beta), rel=1e-9)
    stripes = fit_outcomes(x, outcomes)
    assert stripes.n_nonmonotonic == 2
    expected = fit_stripes(x, [0, 2, 3, 4], 6)
    assert (stripes.theta, stripes.beta) == pytest.approx((expected.theta, expected.beta),
                                                          rel=1e-12)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="exceeds"):
        fit_stripes([1.0, 2.0], [3, 1], 2)
    with pytest.raises(ValueError, match="method"):
        fit_outcomes([1.0, 2.0], np.zeros((3, 2), bool), method="probit")
    with pytest.raises(ValueError, match="finite and > 0"):
        fit_ida([1.0, np.inf])  # a censored record with no censoring point


def test_bootstrap_intervals_cover_the_truth_and_shrink_with_more_records():
    from pipeline.assess.fragility_outcomes import bootstrap

    rng = np.random.default_rng(11)
    levels = np.array([0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5])

    def interval(n):
        capacity = np.exp(rng.normal(0.0, 0.4, n))  # theta 1, beta 0.4
        return bootstrap(levels, levels[None, :] > capacity[:, None], n=100, seed=2)

    few, many = interval(20), interval(200)
    for b in (few, many):
        assert b["identifiable"] > 0.9
        assert b["theta"][0] < 1.0 < b["theta"][1] and b["beta"][0] < 0.4 < b["beta"][1]
    assert np.diff(many["theta"])[0] < 0.6 * np.diff(few["theta"])[0]
    # too few records to identify beta in most resamples: no interval
    none = bootstrap(levels[:2], np.array([[False, True]] * 3), n=20)
    assert np.isnan(none["theta"]).all() and none["identifiable"] < 0.5
