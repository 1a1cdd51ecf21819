"""Records at a common intensity: the factor that brings each record to a design displacement.

A suite of records is comparable record by record only at a common intensity. Here the
intensity is the response the moat wall cares about: each record is scaled so that the
building without wall reaches a chosen peak isolator displacement D (default
DEFAULT_DISPLACEMENT, 0.30 m: the paper's gaps of 15-45 cm are then 0.5-1.5 D; factors within
DEFAULT_LIMITS, 0.2-5). The bilinear isolator makes the peak a nonlinear function of the
factor, so the factor is found by search, batched in the engine: every pass is one
`engine.simulate` call per record whose members are the trial factors (`scale=`), first a
geometric grid over the allowed range, then finer grids inside the bracket of the first
crossing. The smallest factor that reaches D is chosen: the peak need not grow monotonically
with the factor (yielding can shift the response), and the smallest is the intensity at which
the building first needs the gap D. Factors are rounded to 6 significant digits, and each
scaled record (accel x factor, the record the sweeps run) is run once more to check that it
reaches D within the tolerance. Records that would need a factor outside the limits, or never
reach D, are listed in `excluded` with the reason, never silently kept.

Pairs in plan are scaled to the code's D_M by another search, pipeline.motions.rules.displacement
(the resultant peak in plan, an unrounded bracket end, every pair kept; its docstring says why
this one cannot serve there).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..progress import Progress

FIRST_PASS = 33  # geometric grid over the limits: neighbours ~10% apart for limits 0.2-5
REFINE = 17  # trial factors per refining pass, inside the current bracket
BRACKET = 1e-5  # stop refining when the bracket is this narrow (relative)
MAX_PASSES = 12
# The defaults, declared once (pipeline.scale_to_displacement and the studies read them here).
DEFAULT_DISPLACEMENT = 0.30  # m: design displacement D (the paper's gaps 15-45 cm = 0.5-1.5 D)
DEFAULT_LIMITS = (0.2, 5.0)  # allowed scale factors (lowest, highest)


@dataclass(frozen=True)
class ScaledSuite:
    """Records scaled to a design displacement.

    records: the kept scaled Record objects; names: their archive names; factors (R,) -;
    reached (R,) m: the peak isolator displacement each scaled record reaches without wall;
    excluded: (name, factor needed or None, reason) for every record left out;
    displacement (m) and limits (-): what was asked.
    """

    records: list
    names: list[str]
    factors: np.ndarray
    reached: np.ndarray
    excluded: list[tuple[str, float | None, str]]
    displacement: float
    limits: tuple[float, float]


def scale_to_displacement(records, displacement: float = DEFAULT_DISPLACEMENT,
                          limits: tuple[float, float] = DEFAULT_LIMITS, *,
                          dt: float | None = None,
                          building=None, records_dir=None, tolerance: float = 1e-3,
                          quiet: bool = True) -> ScaledSuite:
    """Scale every record so that the building without wall reaches `displacement` (m).

    records: as for pipeline.sweep (names, paths, Record objects; unscaled); limits: the
    allowed factors (lowest, highest); dt: integration step (s, default engine.DEFAULT_DT);
    building: engine.Building (default the paper's); tolerance: largest |reached / D - 1|
    accepted for the rounded factor. Raises SweepError for bad arguments.
    """
    import engine

    from ..errors import SweepError
    from ..records import RecordError, resolve_records

    if not (isinstance(displacement, (int, float)) and math.isfinite(displacement)
            and displacement > 0):
        raise SweepError(f"displacement must be a positive length in m, got {displacement!r}")
    try:
        low, high = (float(x) for x in limits)
    except (TypeError, ValueError):
        raise SweepError(f"limits must be two factors (low, high), got {limits!r}") from None
    if not (0 < low < high and math.isfinite(high)):
        raise SweepError(f"limits must satisfy 0 < low < high, got {limits!r}")
    building = engine.Building() if building is None else building
    dt = engine.DEFAULT_DT if dt is None else float(dt)
    try:
        recs, names = resolve_records(records, records_dir)
    except RecordError as err:
        raise SweepError(str(err)) from err

    kept, kept_names, factors, reached, excluded = [], [], [], [], []
    progress = Progress(len(recs), quiet=quiet, label="scaling",
                        unit=f"records scaled to {displacement:g} m")
    for rec, name in zip(recs, names, strict=True):
        factor, reason = _search(rec, displacement, low, high, dt, building)
        progress.advance(1)
        if reason is not None:
            excluded.append((name, factor, reason))
            continue
        factor = float(f"{factor:.6g}")
        scaled = rec.scaled(factor)
        peak = _peaks(scaled, np.ones(1), dt, building)[0]
        if abs(peak / displacement - 1) > tolerance:
            excluded.append((name, factor, f"the rounded factor reaches {peak:.4g} m, not "
                                           f"{displacement:g} m within {tolerance:g}"))
            continue
        kept.append(scaled)
        kept_names.append(_scaled_name(name, factor))
        factors.append(factor)
        reached.append(peak)
    progress.close()
    return ScaledSuite(kept, kept_names, np.array(factors), np.array(reached), excluded,
                       float(displacement), (low, high))


def _scaled_name(name: str, factor: float) -> str:
    """The archive name of a record scaled by factor: as Record.scaled names it."""
    return f"{name}*{factor!r}"


def _peaks(rec, factors: np.ndarray, dt: float, building) -> np.ndarray:
    """(F,) peak isolator displacements (m) of the building without wall, one per factor."""
    import engine

    result = engine.simulate(rec.accel, rec.dt, engine.Contact.none(factors.size),
                             building=building, dt=dt, scale=factors)
    return np.asarray(result.peak_isolator_disp)


def _search(rec, target: float, low: float, high: float, dt: float, building):
    """(factor, None) reaching `target` (m), or (estimate or None, reason) when out of range."""
    trial = np.geomspace(low, high, FIRST_PASS)
    peaks = _peaks(rec, trial, dt, building)
    above = np.flatnonzero(peaks >= target)
    if above.size == 0:
        estimate = float(high * target / peaks[-1]) if peaks[-1] > 0 else None
        return estimate, (f"reaches only {peaks[-1]:.4g} m at the highest factor {high:g}: "
                          f"needs about {estimate:.3g}" if estimate else "does not move")
    first = above[0]
    if first == 0:
        estimate = float(low * target / peaks[0])
        return estimate, (f"reaches {peaks[0]:.4g} m already at the lowest factor {low:g}: "
                          f"needs about {estimate:.3g}")
    lo, hi, p_lo, p_hi = trial[first - 1], trial[first], peaks[first - 1], peaks[first]
    for _ in range(MAX_PASSES):
        if (hi - lo) / hi < BRACKET:
            break
        trial = np.linspace(lo, hi, REFINE)[1:-1]
        peaks = _peaks(rec, trial, dt, building)
        above = np.flatnonzero(peaks >= target)
        if above.size:
            k = above[0]
            hi, p_hi = trial[k], peaks[k]
            if k > 0:
                lo, p_lo = trial[k - 1], peaks[k - 1]
        else:
            lo, p_lo = trial[-1], peaks[-1]
    # Inside a bracket this narrow the peak is linear in the factor to far below tolerance.
    factor = lo + (target - p_lo) * (hi - lo) / (p_hi - p_lo) if p_hi > p_lo else hi
    return float(factor), None
