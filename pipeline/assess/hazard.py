"""What a site's seismic hazard makes of conditional results: the hazard curve (the annual rate
at which the spectral acceleration at the isolated period is exceeded) and the mean annual
frequency of an event, or the expected annual value of a loss, from their values at a few
intensity stripes (FEMA P-58-1, 2018, chapter 8, the time-based assessment: the conditional
results at intensities spanning the hazard, weighted by the hazard's rate of each interval).
Pure functions of arrays.

Units: spectral accelerations in m/s^2, annual rates in 1/yr.
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from engine.units import G

MCE_R_RATE = 1.0 / 2475.0
"""The annual rate at which the default curve is exceeded at S_MT: 2% in 50 years (the
uniform-hazard definition that ASCE 7-22 section 21.2 risk-targets; the risk-targeted MCE_R
is not a fixed return period, so anchoring it there is a stated approximation)."""
PEER_RETURN_PERIODS = (43.0, 144.0, 289.0, 475.0, 949.0, 1485.0, 2475.0, 3899.0, 7462.0,
                       10000.0)
PEER_SA_G = (0.04, 0.10, 0.17, 0.24, 0.35, 0.42, 0.50, 0.57, 0.69, 0.75)
"""A site's uniform-hazard Sa(2.99 s), g, at PEER_RETURN_PERIODS (years): the hazard that
Kitayama & Cilsalar (2021, Bull. Earthquake Eng., doi 10.1007/s10518-021-01274-y) assess
isolated buildings at (their data repository's stripes, the period nearest the default
T_M of 3.07 s). Only its shape is used (`fit_second_order`); not checked against the USGS
source."""


def fit_second_order(sa, rate, anchor_sa: float, anchor_rate: float) -> tuple[float, float]:
    """(k1, k2) of the second-order hazard form through (anchor_sa, anchor_rate), fitted by
    least squares in ln(rate) to the points (sa, rate) (any one unit of Sa):
    ln(lambda / anchor_rate) = -k1 x - k2 x^2, x = ln(Sa / anchor_sa) (Vamvatsikos 2013,
    Earthquake Eng. Struct. Dyn. 42(8), the second-order approximation of a hazard curve in
    log-log). k1 is the curve's log-log slope at the anchor; k2 > 0 flattens it towards low
    intensities."""
    x = np.log(np.asarray(sa, float) / anchor_sa)
    y = np.log(np.asarray(rate, float) / anchor_rate)
    (k1, k2), *_ = np.linalg.lstsq(np.column_stack([-x, -x * x]), y, rcond=None)
    return float(k1), float(k2)


SLOPE, CURVATURE = fit_second_order(
    PEER_SA_G, 1.0 / np.array(PEER_RETURN_PERIODS),
    anchor_sa=PEER_SA_G[PEER_RETURN_PERIODS.index(2475.0)], anchor_rate=MCE_R_RATE)
"""The default curve's k1 (2.59: its log-log slope at S_MT) and k2 (0.413): the second-order
form (fit_second_order) fitted to PEER_SA_G's return periods with its 2475-year intensity at
1/2475 per year, which the default puts at S_MT. Its log-log slope k1 + 2 k2 x is 3.2 at
twice S_MT and 1.3 at a fifth of it (the peer's points: 3.4-3.5 between 1 and 1.5 times their
2475-year intensity, 1.3 between a tenth and a fifth of it); a power law of slope 3 (this
module's earlier default) puts 5.6 times the rate above 0.2 S_MT. Cornell et al. (2002, J.
Struct. Eng. 128(4)) take a local slope of 1 to 4."""
GRID = 400
"""Points of the default curve's table, log-spaced from its flat top (the vertex of the
quadratic, 0.043 S_MT) to 100 S_MT, S_MT one of them: log-log interpolation between them is
within 1e-4 of the form."""
POINTS = 4000
"""Integration points (log-spaced) of a lognormal fragility over the hazard curve, from 8
dispersions below its median to 8 above."""


@dataclass(frozen=True)
class Hazard:
    """A hazard curve: spectral accelerations sa (n,) m/s^2, increasing, and their annual
    rates of exceedance rate (n,) 1/yr, decreasing; log-log interpolation, power-law
    extrapolation beyond the ends. `source` says where it comes from."""

    sa: np.ndarray
    rate: np.ndarray
    source: str

    def __post_init__(self):
        sa, rate = np.asarray(self.sa, float), np.asarray(self.rate, float)
        if sa.ndim != 1 or sa.size < 2 or sa.shape != rate.shape:
            raise ValueError("a hazard curve needs at least two points: sa and rate of one "
                             "length")
        if np.any(sa <= 0) or np.any(rate <= 0) or not (np.all(np.isfinite(sa))
                                                         and np.all(np.isfinite(rate))):
            raise ValueError("hazard curve: spectral accelerations and annual rates must be "
                             "positive and finite")
        if np.any(np.diff(sa) <= 0) or np.any(np.diff(rate) >= 0):
            raise ValueError("hazard curve: the rates must decrease as the spectral "
                             "acceleration increases")
        object.__setattr__(self, "sa", sa)
        object.__setattr__(self, "rate", rate)

    def rate_at(self, sa) -> np.ndarray:
        """Annual rate of exceedance (1/yr) at sa (m/s^2), any shape."""
        x, y = np.log(self.sa), np.log(self.rate)
        ls = np.log(np.asarray(sa, float))
        inside = np.interp(ls, x, y)
        low = y[0] + (ls - x[0]) * (y[1] - y[0]) / (x[1] - x[0])
        high = y[-1] + (ls - x[-1]) * (y[-1] - y[-2]) / (x[-1] - x[-2])
        return np.exp(np.where(ls < x[0], low, np.where(ls > x[-1], high, inside)))


def default(s_mt: float) -> Hazard:
    """The documented default curve for a site whose MCE_R spectral acceleration at the
    isolated period is s_mt (m/s^2): the second-order form through MCE_R_RATE at s_mt with the
    peer's shape (SLOPE, CURVATURE), tabulated from its vertex (where its slope is zero) to 100
    S_MT. Below the vertex (0.043 S_MT) the rate grows by under 1% per halving of Sa (the
    table's first interval extrapolated), about flat: no stripe's interval reaches there."""
    return second_order(s_mt, SLOPE, CURVATURE)


def second_order(s_mt: float, slope: float, curvature: float) -> Hazard:
    """lambda(Sa) = MCE_R_RATE exp(-slope x - curvature x^2), x = ln(Sa / s_mt) (m/s^2), as a
    table of GRID points from the vertex x = -slope / (2 curvature) (or 0.01 s_mt, if nearer;
    curvature 0: a power law of that slope) to 100 s_mt; its `source` names the form."""
    if slope <= 0 or curvature < 0:
        raise ValueError("a hazard curve's slope must be positive and its curvature not "
                         "negative")
    low = max(-slope / (2 * curvature), math.log(0.01)) if curvature > 0 else math.log(0.01)
    below = round(GRID * -low / (math.log(100.0) - low))  # S_MT itself a point of the table
    x = np.concatenate([np.linspace(low, 0.0, below + 1)[:-1],
                        np.linspace(0.0, math.log(100.0), GRID - below)])
    rate = MCE_R_RATE * np.exp(-slope * x - curvature * x * x)
    if curvature == 0:
        form = f"(Sa / S_MT)^-{slope:.3g} (a power law"
    else:
        form = (f"exp(-{slope:.3g} x - {curvature:.3g} x^2), x = ln(Sa / S_MT) (Vamvatsikos "
                "2013's second-order form")
    return Hazard(s_mt * np.exp(x), rate,
                  f"lambda(Sa) = {MCE_R_RATE:.3g}/yr {form}, S_MT {s_mt / G:.3g} g at T_M): "
                  "the documented default's form, not this site's hazard")


def from_table(path) -> Hazard:
    """A hazard curve from a CSV table with the columns sa_g (spectral acceleration at the
    isolated period, g) and annual_rate (1/yr), a header line, one point a row."""
    path = Path(path)
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        sa = np.array([float(r["sa_g"]) for r in rows]) * G
        rate = np.array([float(r["annual_rate"]) for r in rows])
    except (OSError, KeyError, ValueError, TypeError) as e:
        raise ValueError(f"hazard table {path}: needs the columns sa_g and annual_rate, one "
                         f"number each a row ({e})") from None
    order = np.argsort(sa)
    return Hazard(sa[order], rate[order], f"table {path.name}")


def interval_rates(levels_sa, hazard: Hazard) -> np.ndarray:
    """(L,) the annual rate of the intensity interval each stripe stands for (FEMA P-58-1
    section 8: the stripes are the intervals' midpoints): edges at the geometric means of
    neighbouring stripes, the lowest interval as wide below its stripe as above it (in ln Sa),
    the highest open above. Intensities below the lowest edge count for nothing: the lowest
    stripe is to be chosen where the losses and events are negligible below it."""
    sa = np.asarray(levels_sa, float)
    if sa.ndim != 1 or sa.size < 2 or np.any(np.diff(sa) <= 0) or np.any(sa <= 0):
        raise ValueError("levels_sa: at least two positive stripes, increasing")
    inner = np.sqrt(sa[1:] * sa[:-1])
    edges = np.concatenate([[sa[0] ** 2 / inner[0]], inner])
    rate = hazard.rate_at(edges)
    return rate - np.append(rate[1:], 0.0)


def mean_annual(levels_sa, conditional, hazard: Hazard) -> np.ndarray:
    """The mean annual value of a quantity known at stripes: the sum over the stripes of its
    conditional mean times the annual rate of the stripe's interval (interval_rates; FEMA
    P-58-1 section 8). levels_sa (L,) m/s^2 increasing; conditional (L, ...): a probability
    gives a mean annual frequency (1/yr), a loss its expected annual value. Returns (...); NaN
    where a stripe's value is NaN."""
    x = np.asarray(conditional, float)
    weight = interval_rates(levels_sa, hazard)
    if x.shape[:1] != weight.shape:
        raise ValueError("conditional: one row per stripe")
    return np.tensordot(weight, x, axes=(0, 0))


def lognormal_annual(median_sa, beta, hazard: Hazard) -> np.ndarray:
    """The mean annual frequency of an event of lognormal fragility (median_sa m/s^2, beta),
    any broadcastable shapes: integral of Phi(ln(Sa / median) / beta) |d lambda|."""
    from scipy.stats import norm

    median = np.asarray(median_sa, float)
    b = np.asarray(beta, float)
    lo = float(np.nanmin(median)) * math.exp(-8 * float(np.nanmax(b)))
    hi = float(np.nanmax(median)) * math.exp(8 * float(np.nanmax(b)))
    grid = np.geomspace(lo, hi, POINTS)
    edges = np.concatenate([[grid[0]], np.sqrt(grid[1:] * grid[:-1]), [grid[-1]]])
    weight = -np.diff(hazard.rate_at(edges))
    p = norm.cdf(np.log(grid[(...,) + (None,) * median.ndim] / median) / b)
    # the tail above the grid: every intensity there collapses
    return np.tensordot(weight, p, axes=(0, 0)) + hazard.rate_at(grid[-1])
