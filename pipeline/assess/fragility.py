"""Lognormal fragility curves from incremental dynamic or multiple-stripe analyses.

A fragility curve is the probability of an event (contact with the moat wall, bumpers crushed,
a floor acceleration above a threshold, ...) given the ground-motion intensity IM = x:

    P(event | IM = x) = Phi(ln(x / theta) / beta)

theta the median (units of the IM: Sa(T_M) in m/s^2, or a dimensionless factor on a target
spectrum), beta the logarithmic standard deviation (dimensionless). Pure functions of numbers
already computed (numpy + scipy only):

    fit_stripes    multiple-stripe analysis: event counts per intensity level, binomial MLE
    fit_ida        incremental dynamic analysis: each record's intensity at the event,
                   lognormal MLE, right-censored records that never reach it
    (fit_outcomes and event_weights, from per-record outcomes: pipeline.assess.fragility_outcomes)

Each returns a frozen :class:`Fragility`; degenerate data (the event never or always happens,
beta not identifiable, a median outside the tested levels) are said in its `status` and
`identifiable`, never hidden in a number.

Reference: Baker, J. W. (2015). Efficient analytical fragility function fitting using dynamic
structural analysis. Earthquake Spectra 31(1), 579-599. doi:10.1193/021113EQS025M.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize, special

BETA_BOUNDS = (0.01, 3.0)
"""Bounds (dimensionless) on beta in every fit. An MLE on a bound means the data do not
identify beta: 0.01 a (quasi-)step, the data separate; 3 an outcome hardly varying with x."""

_AT_BOUND = 1e-4
"""How close (in ln beta) an estimate must be to a bound to count as on it."""

_LN_SQRT_2PI = 0.5 * np.log(2.0 * np.pi)

# Truncated Newton (scipy's C TNC) rather than L-BFGS-B: the latter calls threaded LAPACK on
# 2 x 2 matrices, ten times slower for these tiny problems on a busy machine.
# The objectives are per unit record weight, so that these tolerances do not depend on the
# number of records; ftol ~ 0 keeps TNC from stopping on a flat f before the gradient is small.
_TNC_OPTIONS = {"xtol": 1e-10, "gtol": 1e-8, "ftol": 1e-300, "maxfun": 1000}


@dataclass(frozen=True)
class Fragility:
    """A fitted lognormal fragility curve P(event | IM = x) = Phi(ln(x / theta) / beta).

    theta: median, units of the IM (nan when the data place it outside every level).
    beta: logarithmic standard deviation, dimensionless (nan with theta nan).
    method: "stripes" (binomial MLE over levels) or "ida" (lognormal MLE of capacities).
    n_records: total record weight (R for unit weights); for stripes the largest count at any
        level (the same records usually run at every level).
    n_levels: intensity levels with records (stripes; IDA from outcomes: levels analysed;
        fit_ida on capacities: distinct capacities and censoring points).
    log_likelihood: at the estimate, without constants of theta and beta (stripes: no
        binomial coefficient; IDA: the density of ln x); a pseudo-likelihood with weights.
    status: "ok", or "; "-separated findings, each starting with one of
        "no data: ..." (no level or record with weight; theta nan),
        "never observed: median above <highest level>" (theta nan),
        "always observed: median below <lowest level>" (theta nan),
        "beta not identifiable: ..." (a single level, separated outcomes, or beta on a
        bound of BETA_BOUNDS: the MLE is returned, beta being the bound),
        "extrapolated: median <theta> outside the tested levels [<lo>, <hi>]",
        "optimiser: <message>" (the optimiser did not report convergence).
    identifiable: False when theta or beta is not determined by the data (nan, or beta on a
        bound of BETA_BOUNDS); an extrapolated median is still identifiable, only flagged.
    beta_at_bound: beta is the bound it was clipped to, not an interior maximum.
    extrapolated: theta lies outside the intensities tested.
    n_censored: IDA records that never had the event within their levels (0 for stripes).
    n_nonmonotonic: records whose event occurs at a level and not at a higher one (counted by
        fit_outcomes; 0 when the fit was given counts or capacities).
    """

    theta: float
    beta: float
    method: str
    n_records: float
    n_levels: int
    log_likelihood: float
    status: str
    identifiable: bool
    beta_at_bound: bool = False
    extrapolated: bool = False
    n_censored: int = 0
    n_nonmonotonic: int = 0

    def probability(self, x):
        """P(event | IM = x): x scalar or array (any shape), units of theta; 0 for x <= 0.

        Returns a float for a scalar x, else an array of x's shape; nan where theta is nan
        (never / always observed: the data do not give the curve, only its side)."""
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            p = special.ndtr(np.log(x / self.theta) / self.beta)
        p = np.where(x <= 0, 0.0, p) if np.isfinite(self.theta) else np.full(x.shape, np.nan)
        return float(p) if p.ndim == 0 else p


# ---------------------------------------------------------------------------------------------
# Multiple-stripe analysis: binomial maximum likelihood
# ---------------------------------------------------------------------------------------------


def fit_stripes(levels, n_events, n_records, weights=None) -> Fragility:
    """Fragility from a multiple-stripe analysis by maximum likelihood (Baker 2015, eq. 11).

    At level x_j (IM units) z_j of n_j records had the event; (theta, beta) maximise

        l(theta, beta) = sum_j w_j [ z_j ln p_j + (n_j - z_j) ln(1 - p_j) ],
        p_j = Phi(ln(x_j / theta) / beta)

    (the binomial log-likelihood without its coefficient, constant in theta and beta).

    levels: (L,) intensities x_j > 0 (any order; repeated levels have their counts added).
    n_events: (L,) z_j, 0 <= z_j <= n_j. n_records: (L,) or scalar n_j >= 0; levels with
        n_j = 0 carry no information and are left out.
    weights: (L,) w_j >= 0 on each level's term (default 1).

    Counts may be non-integer "effective counts": with record weights u_i (e.g.
    :func:`event_weights`), z_j = sum of u_i over the records with the event at x_j, n_j =
    sum of u_i over the records run at x_j. The objective is then a weighted
    pseudo-likelihood: its maximum is a consistent estimate, but its curvature and
    likelihood-ratio tests are not those of a true likelihood (no standard errors from it).

    The search is over (ln theta, ln beta), beta in BETA_BOUNDS, from a probit regression;
    ln p and ln(1 - p) come from scipy.special.log_ndtr, finite for every finite argument, so
    no probability is clipped and log(0) never occurs. Data that separate (no level, or one
    level, with mixed outcomes between all-no and all-yes) have no finite MLE: beta runs to
    its lower bound and the result says so.
    """
    x, z, n, n_run = _stripe_arrays(levels, n_events, n_records, weights)
    base = dict(method="stripes", n_records=float(np.max(n_run, initial=0.0)),
                n_levels=int(x.size))
    degenerate = _degenerate_stripes(x, z, n)
    if degenerate is not None:
        return Fragility(theta=np.nan, beta=np.nan, log_likelihood=np.nan, status=degenerate,
                         identifiable=False, **base)
    lx = np.log(x)
    start = _probit_start(lx, z, n)
    separated = x.size > 1 and _separated(x, z, n)
    # separated data: the supremum is at beta -> 0, where the likelihood flattens out
    # exponentially and the optimiser would stop anywhere; beta is held on the bound and only
    # theta is placed
    beta_bounds = (_LN_BETA_BOUNDS[0],) * 2 if separated else _LN_BETA_BOUNDS
    start[1] = np.clip(start[1], *beta_bounds)
    scale = float(np.sum(n))  # per record: tolerances independent of the sample size
    res = optimize.minimize(_stripes_nll, start, args=(lx, z, n, scale), jac=True,
                            method="TNC", bounds=[(None, None), beta_bounds],
                            options=_TNC_OPTIONS)
    theta, beta = float(np.exp(res.x[0])), float(np.exp(res.x[1]))
    log_lik = -scale * float(res.fun)
    notes = []
    if x.size == 1:
        notes.append(f"beta not identifiable: a single level {x[0]:g} gives only "
                     f"P({x[0]:g}) = {np.sum(z) / np.sum(n):.3g}, not theta and beta apart")
    elif separated:
        notes.append(_separation_note(x, z, n))
    return _finish(theta, beta, log_lik, float(x.min()), float(x.max()), notes, res, base)


_LN_BETA_BOUNDS = (float(np.log(BETA_BOUNDS[0])), float(np.log(BETA_BOUNDS[1])))


def _stripe_arrays(levels, n_events, n_records, weights):
    """Validated float arrays (x, z, n, n_run), each (L',): the distinct levels with records,
    increasing; the level weights folded into the counts z and n (the log-likelihood is linear
    in them), repeated levels added up; n_run the unweighted counts."""
    x = np.atleast_1d(np.asarray(levels, dtype=float))
    z = np.broadcast_to(np.asarray(n_events, dtype=float), x.shape)
    n = np.broadcast_to(np.asarray(n_records, dtype=float), x.shape)
    w = np.ones_like(x) if weights is None else np.broadcast_to(
        np.asarray(weights, dtype=float), x.shape)
    if x.ndim != 1:
        raise ValueError(f"levels must be 1-D, got shape {x.shape}")
    if not np.all(np.isfinite(x) & (x > 0)):
        raise ValueError("levels must be finite and > 0")
    if not np.all(np.isfinite(n) & (n >= 0) & np.isfinite(z) & (z >= 0)):
        raise ValueError("n_events and n_records must be finite and >= 0")
    # effective counts are sums of float weights: allow their rounding
    if np.any(z > n * (1 + 1e-12)):
        raise ValueError("n_events exceeds n_records at some level")
    if not np.all(np.isfinite(w) & (w >= 0)):
        raise ValueError("weights must be finite and >= 0")
    keep = (n > 0) & (w > 0)
    levels, where = np.unique(x[keep], return_inverse=True)
    z, n, n_run = (np.bincount(where, v, levels.size)
                   for v in (w[keep] * z[keep], w[keep] * n[keep], n[keep]))
    return levels, np.minimum(z, n), n, n_run


def _degenerate_stripes(x, z, n):
    """Status when the counts cannot place theta at all, else None. x, z, n: (L,)."""
    if x.size == 0:
        return "no data: no level has records"
    if np.all(_none(z, n)):
        return f"never observed: median above {x.max():g}"
    if np.all(_all(z, n)):
        return f"always observed: median below {x.min():g}"
    return None


def _none(z, n):
    """(L,) bool: no event at the level (to the rounding of weighted counts)."""
    return z <= 1e-12 * n


def _all(z, n):
    """(L,) bool: the event for every record at the level."""
    return z >= n * (1 - 1e-12)


def _separated(x, z, n) -> bool:
    """Whether the stripes separate (Albert & Anderson 1984, for probit on ln x): a cut in x
    with no event below it and only events above it, at most the level at the cut mixed. Then
    the likelihood rises without bound as beta -> 0. x, z, n: (L,)."""
    order = np.argsort(x, kind="stable")
    z, n = z[order], n[order]
    with_event = np.flatnonzero(~_none(z, n))
    without_event = np.flatnonzero(~_all(z, n))
    # every level without events at or below the first with events; every level after it full
    return bool(without_event[-1] <= with_event[0])


def _separation_note(x, z, n) -> str:
    """The status of separated stripes (x, z, n: (L,)): where the step is."""
    mixed = ~_none(z, n) & ~_all(z, n)
    if np.any(mixed):
        where = (f"a single transition level {x[mixed][0]:g} (fraction "
                 f"{z[mixed][0] / n[mixed][0]:.3g}) between levels with no event and levels "
                 "with only events")
    else:
        where = (f"a step between {x[_none(z, n)].max():g} (no event) and "
                 f"{x[_all(z, n)].min():g} (only events), no level in between")
    return f"beta not identifiable: {where}; no finite MLE, beta -> 0"


def _probit_start(lx, z, n):
    """(ln theta, ln beta) start: a weighted least-squares probit line Phi^-1(p_j) = a + b ln x_j
    through the empirical fractions, (z + 1/2) / (n + 1) so that 0 and 1 stay finite; theta
    where the line crosses 1/2, beta = 1 / b. When the line does not rise (b <= 0, one level),
    the level with the fraction nearest 1/2 and beta = 0.5. lx, z, n: (L,), lx distinct."""
    y = special.ndtri((z + 0.5) / (n + 1.0))
    slope = 0.0
    if lx.size > 1:
        mx, my = np.average(lx, weights=n), np.average(y, weights=n)
        slope = np.sum(n * (lx - mx) * (y - my)) / np.sum(n * (lx - mx) ** 2)
    if slope > 0:
        ln_theta, ln_beta = mx - my / slope, -np.log(slope)
    else:
        ln_theta, ln_beta = lx[np.argmin(np.abs(z / n - 0.5))], np.log(0.5)
    # a wild start (near-flat fractions) is pulled back to the tested range
    ln_theta = np.clip(ln_theta, lx.min() - 1.0, lx.max() + 1.0)
    return np.array([ln_theta, np.clip(ln_beta, *_LN_BETA_BOUNDS)])


def _stripes_nll(params, lx, z, n, scale):
    """Negative binomial log-likelihood divided by scale, and its gradient, in
    params = (ln theta, ln beta). lx, z, n: (L,)."""
    ln_theta, ln_beta = params
    beta = np.exp(ln_beta)
    u = (lx - ln_theta) / beta
    log_p, log_q = special.log_ndtr(u), special.log_ndtr(-u)
    log_phi = -0.5 * u * u - _LN_SQRT_2PI
    # d/du of z ln Phi(u) + (n - z) ln Phi(-u), the ratios phi/Phi taken in logs (no 0/0)
    dl_du = z * np.exp(log_phi - log_p) - (n - z) * np.exp(log_phi - log_q)
    nll = -np.sum(z * log_p + (n - z) * log_q) / scale
    grad = np.array([np.sum(dl_du) / beta, np.sum(dl_du * u)]) / scale
    return nll, grad


# ---------------------------------------------------------------------------------------------
# Incremental dynamic analysis: lognormal capacities, right-censored
# ---------------------------------------------------------------------------------------------


def fit_ida(capacities, weights=None, censored=None, max_level=None,
            min_level=None) -> Fragility:
    """Fragility from IDA capacities: each record's intensity at its first event (IM units).

    The capacities are taken as lognormal. With every record observed the MLE is the
    (weighted) mean and standard deviation of ln capacity (Baker 2015, eq. 4-5; the method of
    moments is the MLE here). The MLE standard deviation divides by the total weight (the
    population form); Baker's eq. 5 divides by n - 1 (the sample form), larger by
    sqrt(n / (n - 1)): 2.6 % at 20 records, 0.25 % at 200. The population form is kept so that
    the censored and uncensored fits are the same estimator and duplicated, reweighted
    records change nothing.

    A record that never had the event within the levels analysed is right-censored at the
    highest of them, m_i: its capacity is only known to exceed m_i. Then (theta, beta) maximise

        l = sum_observed w_i [ ln phi(u_i) - ln beta ] + sum_censored w_i ln(1 - Phi(u_i)),
        u_i = ln(c_i / theta) / beta  (c_i = m_i when censored)

    over (ln theta, ln beta), beta in BETA_BOUNDS (Baker's truncated-IDA fit); dropping the
    censored records, or counting them at m_i, would bias theta and beta low.

    capacities: (R,) c_i > 0; inf or nan where the event never occurred.
    weights: (R,) w_i >= 0 (default 1); a weighted pseudo-likelihood (see fit_stripes).
    censored: (R,) bool; default: capacities not finite, or above max_level.
    max_level: scalar or (R,), the censoring point m_i of censored records (IM units); default
        their capacities entry (which must then be finite).
    min_level: the lowest level analysed (IM units), if any: a record with capacity <= it had
        the event at the first level, its capacity is only known to be at most that. If
        every record did, the result is "always observed" with theta nan.
    """
    c, w, cens = _ida_arrays(capacities, weights, censored, max_level)
    lc = np.log(c)
    n_levels = int(np.unique(c).size)
    base = dict(method="ida", n_records=float(np.sum(w)), n_levels=n_levels,
                n_censored=int(np.count_nonzero(cens)))
    degenerate = _degenerate_ida(c, cens, min_level)
    if degenerate is not None:
        return Fragility(theta=np.nan, beta=np.nan, log_likelihood=np.nan, status=degenerate,
                         identifiable=False, **base)
    if not np.any(cens):
        ln_theta, ln_beta, res = *_weighted_moments(lc, w), None
        ln_beta = float(np.clip(ln_beta, *_LN_BETA_BOUNDS))
    else:
        start = np.array([*_weighted_moments(lc, w)])
        start[1] = np.clip(start[1], *_LN_BETA_BOUNDS)
        scale = float(np.sum(w))
        res = optimize.minimize(_ida_nll, start, args=(lc, w, cens, scale), jac=True,
                                method="TNC", bounds=[(None, None), _LN_BETA_BOUNDS],
                                options=_TNC_OPTIONS)
        ln_theta, ln_beta = res.x
    log_lik = -float(_ida_nll([ln_theta, ln_beta], lc, w, cens, 1.0)[0])
    lo = min(float(c.min()), np.inf if min_level is None else float(min_level))
    return _finish(float(np.exp(ln_theta)), float(np.exp(ln_beta)), log_lik, lo,
                   float(c.max()), [], res, base)


def _ida_arrays(capacities, weights, censored, max_level):
    """Validated (c, w, cens), each (R',): capacities or censoring points (> 0, finite),
    weights, censored flags; records of zero weight left out."""
    c = np.atleast_1d(np.asarray(capacities, dtype=float))
    if c.ndim != 1:
        raise ValueError(f"capacities must be 1-D, got shape {c.shape}")
    w = np.ones_like(c) if weights is None else np.broadcast_to(
        np.asarray(weights, dtype=float), c.shape)
    if not np.all(np.isfinite(w) & (w >= 0)):
        raise ValueError("weights must be finite and >= 0")
    top = None if max_level is None else np.broadcast_to(np.asarray(max_level, float), c.shape)
    if censored is None:
        cens = ~np.isfinite(c)
        if top is not None:
            with np.errstate(invalid="ignore"):
                cens |= c > top
    else:
        cens = np.broadcast_to(np.asarray(censored, dtype=bool), c.shape)
    # a censored record's point is where its analysis stopped without the event
    c = np.where(cens, c if top is None else top, c)
    if not np.all(np.isfinite(c) & (c > 0)):
        raise ValueError("capacities (censoring points for censored records, max_level if "
                         "given) must be finite and > 0")
    keep = w > 0
    return c[keep], w[keep], np.asarray(cens)[keep]


def _degenerate_ida(c, cens, min_level):
    """Status when the capacities cannot place theta at all, else None. c, cens: (R,)."""
    if c.size == 0:
        return "no data: no record with weight"
    if np.all(cens):
        return f"never observed: median above {c.max():g}"
    if min_level is not None and not np.any(cens) and np.all(c <= min_level):
        return f"always observed: median below {float(min_level):g}"
    return None


def _weighted_moments(lc, w):
    """(mean, ln std) of ln capacities lc (R,) with weights w (R,): the population form (the
    MLE); ln std = -inf when all are equal (clipped to the lower bound by the caller)."""
    mean = float(np.average(lc, weights=w))
    var = float(np.average((lc - mean) ** 2, weights=w))
    with np.errstate(divide="ignore"):
        return mean, 0.5 * float(np.log(var))


def _ida_nll(params, lc, w, cens, scale):
    """Negative censored lognormal log-likelihood per unit weight (of the density of ln c)
    and its gradient in params = (ln theta, ln beta). lc, w, cens: (R,)."""
    ln_theta, ln_beta = params
    beta = np.exp(ln_beta)
    u = (lc - ln_theta) / beta
    obs = ~cens
    log_surv = special.log_ndtr(-u[cens])
    nll = -(np.sum(w[obs] * (-0.5 * u[obs] ** 2 - ln_beta - _LN_SQRT_2PI))
            + np.sum(w[cens] * log_surv)) / scale
    # observed: d/du = -u, plus -1 per unit weight from -ln beta; censored: -phi/(1 - Phi)
    mills = np.exp(-0.5 * u[cens] ** 2 - _LN_SQRT_2PI - log_surv)
    d_theta = np.sum(w[obs] * u[obs]) / beta + np.sum(w[cens] * mills) / beta
    d_beta = np.sum(w[obs] * (u[obs] ** 2 - 1.0)) + np.sum(w[cens] * mills * u[cens])
    return nll, -np.array([d_theta, d_beta]) / scale


# ---------------------------------------------------------------------------------------------
# Shared: a fit's flags
# ---------------------------------------------------------------------------------------------


def _finish(theta, beta, log_lik, lo, hi, notes, res, base) -> Fragility:
    """The Fragility of an MLE (theta, beta) with its flags. lo, hi: the range of intensities
    tested (IM units); notes: findings already made; res: the optimiser's result or None."""
    notes = list(notes)
    ln_beta = np.log(beta)
    at_lower = ln_beta <= _LN_BETA_BOUNDS[0] + _AT_BOUND
    at_upper = ln_beta >= _LN_BETA_BOUNDS[1] - _AT_BOUND
    if at_lower and not any(s.startswith("beta not identifiable") for s in notes):
        notes.append(f"beta not identifiable: at lower bound {BETA_BOUNDS[0]:g} "
                     "(a step: the data separate)")
    elif at_lower:
        notes[-1] += f"; beta at lower bound {BETA_BOUNDS[0]:g}"
    if at_upper:
        notes.append(f"beta not identifiable: at upper bound {BETA_BOUNDS[1]:g} (the "
                     "outcome hardly varies with intensity)")
    extrapolated = not lo <= theta <= hi
    if extrapolated:
        notes.append(f"extrapolated: median {theta:.4g} outside the tested levels "
                     f"[{lo:g}, {hi:g}]")
    if res is not None and not res.success:
        notes.append(f"optimiser: {res.message}")
    identifiable = not any(s.startswith("beta not identifiable") for s in notes)
    return Fragility(theta=theta, beta=beta, log_likelihood=log_lik,
                     status="; ".join(notes) if notes else "ok", identifiable=identifiable,
                     beta_at_bound=bool(at_lower or at_upper), extrapolated=extrapolated,
                     **base)


