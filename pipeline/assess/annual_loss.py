"""A stripe's loss, collapse and repair mixed (FEMA P-58-1 Eq. 7-1: `mixture` of the
realizations, `stripe_means`), and the expected annual loss under resamplings of the
earthquakes: the paired bootstrap of the collapse study (`collapse.resampled_weights`, the
same seed: the same resampled earthquakes) carried through the loss at every stripe, so that
two configurations' EALs are compared on the same draws. Pure functions of arrays.

Each draw changes what a stripe's mean loss is made of:
- P(collapse | stripe): the collapse study's draw of P(collapse | MCE_R) (the fragility of
  dispersion beta_TOT, its median moved: `stripe_collapse`);
- the mean repair cost given no collapse: pelicun's estimate on the fitted demand model (FEMA
  P-58-1 section 5.3), times the ratio of the standing runs' weighted mean cost under the draw's
  weights to the same under the pairs' own (`given_no_collapse`). The runs' costs are each
  run's demands assessed as they are (pipeline.assess.loss, run_repair_cost): refitting the
  demand model and assessing every draw again would take a pelicun assessment per draw, so the
  record-to-record spread of the mean is taken from the runs, relative, and its level from the
  model (a stated approximation);
- the moat inventory's mean cost given no collapse: the standing runs' weighted mean under the
  draw's weights (exact, as the point estimate's).

Units: costs in USD of 2011, rates in 1/yr.
"""
from __future__ import annotations

import numpy as np

from .hazard import Hazard, mean_annual


def weighted_means(values, standing, weights) -> np.ndarray:
    """(D, ...) the standing runs' weighted means of values (R, ...) under the weights (R, D)
    (or (R,), D = 1); NaN where no run stands under a draw. standing (R, ...) bool; values
    where not standing are ignored (NaN allowed there)."""
    w = np.asarray(weights, float)
    w = w[:, None] if w.ndim == 1 else w
    keep = np.asarray(standing, bool)
    x = np.where(keep, np.asarray(values, float), 0.0)
    total = np.tensordot(w, x, axes=(0, 0))
    count = np.tensordot(w, keep.astype(float), axes=(0, 0))
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, total / count, np.nan)


def runs_in_place(per_group, standing) -> np.ndarray:
    """(R, ...) each standing run's value from per_group (G, max runs) (pipeline.assess.loss.losses'
    run_repair_cost), the groups in C order over standing's trailing axes (standing (R, ...)
    bool), each group's runs those standing there in order; NaN where a run does not stand."""
    standing = np.asarray(standing, bool)
    out = np.full(standing.shape, np.nan)
    for k, index in enumerate(np.ndindex(standing.shape[1:])):
        keep = standing[(slice(None), *index)]
        out[(keep, *index)] = per_group[k, :keep.sum()]
    return out


def given_no_collapse(model_mean, run_cost, standing, weights, draws) -> np.ndarray:
    """(D, ...) the mean repair cost given no collapse under each draw: model_mean (...) (the
    fitted demand model's) times the runs' weighted mean of run_cost (R, ...) under the draw's
    weights (R, D) over the same under the pairs' weights (R,). Where either is not a positive
    number (no run standing in the draw, or the runs cost nothing), the draw keeps
    model_mean."""
    base = weighted_means(run_cost, standing, weights)[0]
    drawn = weighted_means(run_cost, standing, draws)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = drawn / base
    ratio = np.where(np.isfinite(ratio) & (base > 0), ratio, 1.0)
    return np.asarray(model_mean, float) * ratio


def stripe_collapse(levels, mce_draws, beta) -> np.ndarray:
    """(D, L, ...) P(collapse | stripe) of the lognormal fragility of dispersion beta (...)
    whose value at the MCE_R is each draw's mce_draws (D, ...): Phi(ln(level) / beta +
    Phi^-1(P_MCE)), levels (L,) x MCE_R."""
    from scipy.stats import norm

    p = np.clip(np.asarray(mce_draws, float), 1e-300, 1.0 - 1e-16)
    z = norm.ppf(p)[:, None]
    x = np.log(np.asarray(levels, float)).reshape((1, -1) + (1,) * (z.ndim - 2))
    return norm.cdf(x / np.asarray(beta, float) + z)


def mixture(given_no_collapse, collapse_probability, replacement: float, quantiles=()):
    """The statistics of a loss that is `replacement` with probability collapse_probability
    (..., ) and else distributed as the realizations given_no_collapse (..., S): (mean (...),
    quantiles (len(quantiles), ...)), the quantiles of the mixture's distribution (the
    realizations weighted (1 - P(C)) / S each, the replacement P(C))."""
    x = np.asarray(given_no_collapse, float)
    p = np.asarray(collapse_probability, float)
    mean = stripe_means(p, x.mean(axis=-1), replacement)
    q = np.asarray(quantiles, float)
    out = np.full((q.size, *x.shape[:-1]), np.nan)
    for index in np.ndindex(x.shape[:-1]):
        if not np.isfinite(p[index]) or np.isnan(x[index]).any():
            continue
        values = np.append(np.sort(x[index]), replacement)
        weight = np.append(np.full(x.shape[-1], (1 - p[index]) / x.shape[-1]), p[index])
        order = np.argsort(values, kind="stable")
        cdf = np.cumsum(weight[order])
        out[(slice(None), *index)] = values[order][
            np.minimum(np.searchsorted(cdf, q - 1e-12), values.size - 1)]
    return mean, out


def stripe_means(collapse, given, replacement: float) -> np.ndarray:
    """(D, L, ...) each stripe's mean loss under each draw: P(C) x the replacement + (1 - P(C))
    x the loss given no collapse (collapse and given (D, L, ...)), FEMA P-58-1 Eq. 7-1."""
    return collapse * replacement + (1.0 - collapse) * given


def annual_loss(levels_sa, means, hazard: Hazard) -> np.ndarray:
    """(D, ...) the expected annual loss of each draw: the stripes' (levels_sa (L,) m/s^2)
    mean losses (D, L, ...) (stripe_means) over the hazard curve's intervals
    (hazard.mean_annual)."""
    return mean_annual(levels_sa, np.moveaxis(np.asarray(means, float), 1, 0), hazard)
