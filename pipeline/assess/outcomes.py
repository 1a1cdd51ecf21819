"""How a comparison of two configurations is counted, and how a claim's quantifier is judged
(SPEC section 6, "Statistics"): pure functions over arrays.

- `effect`: with bumpers against without, per point, as HURT (+1), NEUTRAL (0) or HELPED
  (-1) with a stated relative tolerance: amplification = with / without below 1 - tol helps,
  above 1 + tol hurts, within is neutral (an exact tie is neutral, never "not helped").
- `where_contact`: a point counts only where contact occurs in at least one of the two
  configurations; elsewhere both runs are the same unconstrained run and the amplification is
  1 by construction, not a finding.
- `judged`: a claim with the paper's quantifier ("every", "almost every", "most", "some")
  held at `held` of `counted` points; None when nothing was counted (not tested).
- `count` (-> `Count`): THE counting rule every study's verdicts use (SPEC section 6): the
  quantifier as the paper's sentence states it; ties (within the tolerance) and cases where
  what the claim speaks of does not happen (no contact) outside the denominator and reported
  beside it; each pair carries its earthquake's weight once, however many angles, levels or
  gaps it runs at (see `count` for the rule).
- `weighted_quantiles`: quantiles over the records weighted per earthquake; QUANTILES, the
  ones the studies report.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

TOLERANCE = 0.02
"""Relative change below which bumpers neither help nor hurt (2%: well above the engine's
convergence error, 0.5% at the default step, and below what an engineer would act on)."""
HELPED, NEUTRAL, HURT = -1, 0, 1
NAMES = {HELPED: "helped", NEUTRAL: "neutral", HURT: "hurt"}
ALMOST_EVERY = 0.9
"""The paper's "almost all": held at this fraction of the counted points at least (a stated
reading: the paper gives no number)."""
QUANTIFIERS = {"every": "at every counted point",
               "almost every": f"at {ALMOST_EVERY:.0%} at least of the counted points",
               "most": "at more than half the counted points",
               "some": "at one counted point at least"}
ALIASES = {"all": "every", "almost all": "almost every", "may": "some", "can": "some",
           "could": "some"}
"""The paper's wordings of the four quantifiers: "may" / "can" assert that it happens at
least once ("some"); "almost all" is "almost every"."""
COUNT_TEXT = {"every": "every counted pair holds at every counted case",
              "almost every": f"held weight >= {ALMOST_EVERY:.0%} of the counted weight",
              "most": "held weight > half the counted weight",
              "some": "one counted case at least holds"}
"""The verdict rule of each quantifier over `count`'s weights (ties and cases not counted
outside the denominator)."""


def canonical(quantifier: str) -> str:
    """The quantifier among QUANTIFIERS for the paper's wording (ALIASES); ValueError else."""
    q = ALIASES.get(quantifier, quantifier)
    if q not in QUANTIFIERS:
        raise ValueError(f"quantifier must be one of {tuple(QUANTIFIERS) + tuple(ALIASES)}, "
                         f"got {quantifier!r}")
    return q


def amplification(with_bumpers, without) -> np.ndarray:
    """with / without (-), NaN where `without` is 0 or either is NaN."""
    a, b = np.asarray(with_bumpers, float), np.asarray(without, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(b > 0, a / np.where(b > 0, b, 1.0), np.nan)


def effect(with_bumpers, without, tol: float = TOLERANCE) -> np.ndarray:
    """int8 array of HELPED / NEUTRAL / HURT (see the module docstring); NEUTRAL where the
    amplification is NaN (nothing to compare)."""
    amp = amplification(with_bumpers, without)
    out = np.zeros(amp.shape, dtype=np.int8)
    out[amp < 1 - tol] = HELPED
    out[amp > 1 + tol] = HURT
    return out


def with_collapse(effects, collapsed_with, collapsed_without) -> np.ndarray:
    """The effects (int8, `effect`'s) where a run collapsed: a collapse is a collapse, never
    a large amplification. HURT where only the run with bumpers collapsed, HELPED where only
    the one without, NEUTRAL where both did (nothing to tell them apart); the others as they
    were. Arrays broadcast."""
    c_with = np.asarray(collapsed_with, bool)
    c_without = np.asarray(collapsed_without, bool)
    out = np.array(np.broadcast_to(effects, np.broadcast_shapes(
        np.shape(effects), c_with.shape, c_without.shape)), dtype=np.int8)
    out[c_with & ~c_without] = HURT
    out[c_without & ~c_with] = HELPED
    out[c_with & c_without] = NEUTRAL
    return out


def where_contact(impacts_with, impacts_without) -> np.ndarray:
    """bool: contact in at least one of the two configurations (n_impacts > 0)."""
    return (np.asarray(impacts_with) > 0) | (np.asarray(impacts_without) > 0)


def tally(effects, counted, weights=None) -> dict:
    """Counts (weighted if given: e.g. pipeline.motions.weights.event_weights per record) of
    helped,
    neutral and hurt among the counted points, with their total and the points not counted
    ("no contact")."""
    e, c = np.asarray(effects), np.asarray(counted, bool)
    w = np.ones(e.shape) if weights is None else np.broadcast_to(np.asarray(weights, float),
                                                                 e.shape)
    out = {NAMES[k]: float(w[c & (e == k)].sum()) for k in (HELPED, NEUTRAL, HURT)}
    out["counted"] = float(w[c].sum())
    out["no_contact"] = float(w[~c].sum())
    return out


def judged(quantifier: str, held: float, counted: float) -> bool | None:
    """Whether a claim with `quantifier` (QUANTIFIERS, or its wording in ALIASES) holds at
    `held` of `counted` points; None where nothing was counted."""
    quantifier = canonical(quantifier)
    if not counted:
        return None
    eps = 1e-12 * abs(counted)  # the rounding of weighted sums, never a case's weight
    return {"every": held >= counted - eps, "some": held > eps,
            "most": held > counted / 2 + eps,
            "almost every": held >= ALMOST_EVERY * counted - eps}[quantifier]


@dataclass(frozen=True)
class Count:
    """A claim counted by `count`. Weights (the pairs', per earthquake): held and counted (the
    denominator), ties (pairs whose only cases where the claim applies are within the
    tolerance) and not_counted (pairs where it never applies: no contact); the four add up to
    the total weight. Cases (ints): held_cases, counted_cases, tie_cases, not_counted_cases,
    failed_cases (counted and not held). pairs, events: the pairs and earthquakes in the
    denominator (events None when no earthquake ids were given). verdict: True / False, None
    when nothing was counted (not tested)."""

    quantifier: str
    wording: str
    held: float
    counted: float
    ties: float
    not_counted: float
    held_cases: int
    counted_cases: int
    tie_cases: int
    not_counted_cases: int
    pairs: int
    events: int | None
    verdict: bool | None

    @property
    def failed_cases(self) -> int:
        return self.counted_cases - self.held_cases

    @property
    def fraction(self) -> float | None:
        """held / counted (weights), None when nothing was counted."""
        return self.held / self.counted if self.counted else None

    def text(self, unit: str = "cases", tol: float = TOLERANCE) -> str:
        """'holds for 67% of the weight of 3 pairs (2 earthquakes; 7 of 12 cases); beside,
        not counted: 2 cases within the 2% tolerance (weight 0.5), 5 cases without contact
        (weight 1)'."""
        if self.events is None and self.pairs + self.ties + self.not_counted <= 1:
            # one set of cases (configurations compared from fits over all the pairs): no
            # weights to state
            head = (f"holds in {self.held_cases} of {self.counted_cases} {unit}"
                    if self.counted else f"nothing counted (0 {unit})")
            return (f"{head}; beside, not counted: {self.tie_cases} within the {tol:.0%} "
                    f"tolerance, {self.not_counted_cases} where it does not apply")
        who = f"{self.pairs} pair{'s' * (self.pairs != 1)}"
        if self.events is not None:
            who += f", {self.events} earthquake{'s' * (self.events != 1)}"
        head = (f"holds for {self.fraction:.0%} of the weight of {who} ({self.held_cases} of "
                f"{self.counted_cases} {unit})" if self.counted else f"nothing counted (0 {unit})")
        return (f"{head}; beside, not counted: {self.tie_cases} {unit} within the {tol:.0%} "
                f"tolerance (pairs with only such: weight {self.ties:.3g}), "
                f"{self.not_counted_cases} where it does not apply (weight "
                f"{self.not_counted:.3g})")

    def numbers(self) -> dict:
        """The count for an archive (JSON-ready)."""
        return {"quantifier": self.quantifier, "wording": self.wording,
                "rule": COUNT_TEXT[self.quantifier], "held_weight": self.held,
                "counted_weight": self.counted, "fraction": self.fraction,
                "tie_weight": self.ties, "not_counted_weight": self.not_counted,
                "held_cases": self.held_cases, "counted_cases": self.counted_cases,
                "failed_cases": self.failed_cases, "tie_cases": self.tie_cases,
                "not_counted_cases": self.not_counted_cases, "pairs_counted": self.pairs,
                "events_counted": self.events,
                "verdict": None if self.verdict is None else bool(self.verdict)}


def count(quantifier: str, holds, applies, changed=None, weights=None, events=None) -> Count:
    """One way to count a claim (SPEC section 6), for every study.

    Cases are arrays (R, ...) over the pairs (axis 0) and whatever else they run at (angles,
    levels, gaps, ...): holds (bool: the claim holds there), applies (bool: what it speaks of
    happens there, e.g. contact in one of the two configurations), changed (bool: the
    quantity changes beyond the tolerance; None for a yes/no claim: no ties). A case is
    COUNTED where it applies and changed; a TIE where it applies and did not change; NOT
    COUNTED where it does not apply. weights (R,): each pair's weight (e.g. a suite's
    record_weight); None: `event_weights(events)` when events (R,) earthquake ids are given
    (the pairs of one earthquake share its weight), else 1 per pair.

    The rule: a pair with counted cases puts its whole weight w in the denominator once,
    however many cases it has, and w x (its held cases / its counted cases) in the held
    weight; a pair with no counted case puts w in `ties` if some of its cases are ties, else in
    `not_counted`. The verdict of the quantifier (QUANTIFIERS or the paper's wording, ALIASES):
    "every": no counted case fails (ties ignored); "almost every": held >= ALMOST_EVERY x
    counted; "most": held > counted / 2; "some" ("may", "can"): one counted case holds; None
    when nothing is counted."""
    wording, quantifier = quantifier, canonical(quantifier)
    applies = np.asarray(applies, bool)
    holds = np.broadcast_to(np.asarray(holds, bool), applies.shape)
    ch = np.ones(applies.shape, bool) if changed is None else np.broadcast_to(
        np.asarray(changed, bool), applies.shape)
    n_pairs = applies.shape[0] if applies.ndim else 1
    flat = lambda a: np.reshape(a, (n_pairs, -1))  # noqa: E731  (pair, case)
    applies, holds, ch = flat(applies), flat(holds), flat(ch)
    if weights is None:
        if events is None:
            weights = np.ones(n_pairs)
        else:
            from pipeline.motions.weights import event_weights

            weights = event_weights(np.asarray(events))
    w = np.broadcast_to(np.asarray(weights, float), (n_pairs,))
    counted, tie = applies & ch, applies & ~ch
    n_c, n_h = counted.sum(axis=1), (counted & holds).sum(axis=1)
    in_count = n_c > 0
    tie_only = ~in_count & tie.any(axis=1)
    outside = ~in_count & ~tie_only
    share = np.where(in_count, n_h / np.maximum(n_c, 1), 0.0)
    held, total = float(np.sum(w[in_count] * share[in_count])), float(np.sum(w[in_count]))
    n_events = None if events is None else int(np.unique(np.asarray(events)[in_count]).size)
    if not in_count.any():
        verdict = None
    elif quantifier == "every":
        verdict = bool(n_h.sum() == n_c.sum())
    elif quantifier == "some":
        verdict = bool(n_h.sum() > 0)
    else:
        verdict = judged(quantifier, held, total)
    return Count(quantifier, wording, held, total, float(w[tie_only].sum()),
                 float(w[outside].sum()), int(n_h.sum()), int(n_c.sum()), int(tie.sum()),
                 int((~applies).sum()), int(in_count.sum()), n_events, verdict)


QUANTILES = (0.16, 0.5, 0.84)
"""The quantiles the studies report over the records: the 16th, 50th and 84th percentiles (a
lognormal's median and one standard deviation either side)."""


def weighted_quantiles(values, weights, qs) -> np.ndarray:
    """(Q, ...) weighted quantiles qs (Q,) over axis 0 of values (R, ...), weights (R,) >= 0
    (e.g. per earthquake): the weighted empirical distribution at the midpoints of its steps,
    linear between (Hazen's (i - 1/2) / R with equal weights); NaN where no weight."""
    v = np.asarray(values, float)
    qs = np.atleast_1d(np.asarray(qs, float))
    w = np.asarray(weights, float)
    if v.size == 0:
        return np.full((qs.size, *v.shape[1:]), np.nan)
    w = np.broadcast_to(w.reshape(w.shape + (1,) * (v.ndim - w.ndim)), v.shape)
    order = np.argsort(v, axis=0)
    ranked, w = np.take_along_axis(v, order, axis=0), np.take_along_axis(w, order, axis=0)
    total = w.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        cdf = (np.cumsum(w, axis=0) - 0.5 * w) / total
    flat_v, flat_p = ranked.reshape(len(v), -1), cdf.reshape(len(v), -1)
    out = np.full((qs.size, flat_v.shape[1]), np.nan)
    for j in np.flatnonzero(total.reshape(-1) > 0):
        out[:, j] = np.interp(qs, flat_p[:, j], flat_v[:, j])
    return out.reshape((qs.size, *v.shape[1:]))
