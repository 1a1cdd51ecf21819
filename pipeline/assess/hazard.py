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
SLOPE = 3.0
"""The default curve's log-log slope k, lambda(Sa) = lambda(S_MT) (Sa / S_MT)^-k: 3, a stated
choice for a high-seismicity site at a long period (Cornell et al. 2002, J. Struct. Eng.
128(4), take k from 1 to 4 locally; not checked against a site's hazard). Give the site's own
curve with a table (`from_table`)."""
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
    isolated period is s_mt (m/s^2): a power law through MCE_R_RATE at s_mt with slope SLOPE."""
    sa = s_mt * np.array([0.01, 1.0, 100.0])
    return Hazard(sa, MCE_R_RATE * (sa / s_mt) ** -SLOPE,
                  f"power law lambda(Sa) = {MCE_R_RATE:.3g}/yr (Sa / S_MT)^-{SLOPE:g} "
                  f"(S_MT {s_mt / G:.3g} g at T_M): the documented default, not a site's "
                  "hazard")


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
