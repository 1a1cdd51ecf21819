"""Fragility fits from what the runs say: per-record boolean outcomes over intensity levels
(`fit_outcomes`, stripes or IDA, through pipeline.assess.fragility's fits), weighted by the
records' weights that keep one earthquake from dominating them (`event_weights`, declared in
pipeline.motions.weights with the suites that carry them). Pure functions of arrays."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from pipeline.motions.weights import event_weights

from .fragility import Fragility, fit_ida, fit_stripes

__all__ = ["bootstrap", "event_weights", "fit_outcomes"]


def fit_outcomes(levels, outcomes, weights=None, method: str = "stripes") -> Fragility:
    """Fragility from per-record outcomes at each intensity level.

    levels: (L,) intensities x_j > 0, distinct (IM units; any order, sorted here).
    outcomes: (R, L) bool, outcomes[i, j] whether record i had the event at level j; or float
        with nan where record i was not run at level j (an IDA stopped early, a failed run).
    weights: (R,) record weights >= 0 (default 1; see :func:`event_weights`).
    method: "stripes": weighted counts per level into :func:`fit_stripes`. "ida": each
        record's capacity is the first level with the event into :func:`fit_ida`, censored at
        its highest level run when it never has it.

    A record whose event occurs at a level but not at a higher one ("resurrection", common in
    pounding: a stronger record can move the building so that it misses the wall) is
    non-monotonic. Stripes use every outcome as it is; IDA takes the first occurrence. Either
    way the result counts such records in n_nonmonotonic.

    The IDA capacity is the first level with the event, an upper bound: the event occurred
    somewhere between the previous level and it. With levels a ratio r apart this biases theta
    up by a factor up to r (about sqrt(r) on average); use fine levels or the stripes.
    """
    x, y, w = _outcome_arrays(levels, outcomes, weights)
    ran = ~np.isnan(y)
    hit = ran & (y > 0.5)
    n_nonmono = int(np.count_nonzero(_nonmonotonic(hit, ran)))
    if method == "stripes":
        fit = fit_stripes(x, w @ hit, w @ ran)
    elif method == "ida":
        fit = _fit_outcomes_ida(x, hit, ran, w)
    else:
        raise ValueError(f"method must be 'stripes' or 'ida', got {method!r}")
    return replace(fit, n_nonmonotonic=n_nonmono)


def _outcome_arrays(levels, outcomes, weights):
    """Validated (x (L,), y (R, L) float with nan = not run, w (R,)), levels increasing."""
    x = np.atleast_1d(np.asarray(levels, dtype=float))
    y = np.asarray(outcomes, dtype=float)
    if y.ndim != 2 or y.shape[1] != x.size:
        raise ValueError(f"outcomes must be (R, {x.size}), got shape {y.shape}")
    if x.ndim != 1 or not np.all(np.isfinite(x) & (x > 0)):
        raise ValueError("levels must be 1-D, finite and > 0")
    if np.unique(x).size != x.size:
        raise ValueError("levels must be distinct")
    w = np.ones(y.shape[0]) if weights is None else np.asarray(weights, dtype=float)
    if w.shape != (y.shape[0],) or not np.all(np.isfinite(w) & (w >= 0)):
        raise ValueError(f"weights must be ({y.shape[0]},), finite and >= 0")
    order = np.argsort(x)
    return x[order], y[:, order], w


def _nonmonotonic(hit, ran):
    """(R,) bool: records with the event at some level and, run, without it at a higher one.
    hit, ran: (R, L) bool, levels increasing."""
    seen = np.cumsum(hit, axis=1) > 0
    return np.any(seen & ran & ~hit, axis=1)


def _fit_outcomes_ida(x, hit, ran, w) -> Fragility:
    """fit_ida on the first level with the event of each record (x (L,), hit and ran (R, L)),
    censored at the highest level run; records never run are left out."""
    any_run = np.any(ran, axis=1)
    first = np.argmax(hit, axis=1)
    last_run = x.size - 1 - np.argmax(ran[:, ::-1], axis=1)
    cens = ~np.any(hit, axis=1)
    cap = np.where(cens, x[last_run], x[first])
    fit = fit_ida(cap[any_run], w[any_run], censored=cens[any_run], min_level=x[0])
    return replace(fit, n_levels=int(x.size))


BOOTSTRAP_QUANTILES = (0.05, 0.95)
"""The bootstrap interval of a fragility's parameters: 5% to 95%."""


def bootstrap(levels, outcomes, weights=None, method: str = "stripes", n: int = 200,
              seed: int = 0, q=BOOTSTRAP_QUANTILES) -> dict:
    """Percentile bootstrap intervals of a fragility fit (Efron & Tibshirani 1993): the records
    (rows of outcomes, each with its weight) resampled with replacement n times and refitted
    (fit_outcomes). Returns theta (len(q),) and beta (len(q),) quantiles over the resamples
    whose fit is identifiable (NaN when fewer than half are), and identifiable, the share of
    the resamples that are."""
    x = np.asarray(levels, dtype=float)
    y = np.asarray(outcomes, dtype=float)
    w = np.ones(y.shape[0]) if weights is None else np.asarray(weights, dtype=float)
    rng = np.random.default_rng(seed)
    thetas, betas = np.full(n, np.nan), np.full(n, np.nan)
    for k in range(n):
        pick = rng.integers(0, y.shape[0], y.shape[0])
        fit = fit_outcomes(x, y[pick], w[pick], method=method)
        if fit.identifiable:
            thetas[k], betas[k] = fit.theta, fit.beta
    share = float(np.mean(np.isfinite(thetas)))
    if share < 0.5:
        return {"theta": np.full(len(q), np.nan), "beta": np.full(len(q), np.nan),
                "identifiable": share}
    return {"theta": np.nanquantile(thetas, q), "beta": np.nanquantile(betas, q),
            "identifiable": share}
