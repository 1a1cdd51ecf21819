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
- `weighted_quantiles`: quantiles over the records weighted per earthquake; QUANTILES, the
  ones the studies report.
"""
from __future__ import annotations

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
    """Counts (weighted if given: e.g. pipeline.assess.fragility.event_weights per record) of
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
    """Whether a claim with `quantifier` (QUANTIFIERS) holds at `held` of `counted` points;
    None where nothing was counted."""
    if quantifier not in QUANTIFIERS:
        raise ValueError(f"quantifier must be one of {tuple(QUANTIFIERS)}, got {quantifier!r}")
    if not counted:
        return None
    return {"every": held == counted, "some": held > 0, "most": held > counted / 2,
            "almost every": held >= ALMOST_EVERY * counted}[quantifier]


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
