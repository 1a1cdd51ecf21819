"""Records no earthquake produced, most likely a unit slip: :func:`check_plausible`.

A record's peak ground acceleration (PGA), peak ground velocity (PGV) and duration are checked
against what recorded earthquakes have produced (the bounds below, each a stated choice with
its source). A PGA outside them, or a weak one (under :data:`ORDINARY_PGA_G`, 0.01 g) that the
same numbers in another unit make an ordinary record, is refused with the unit that brings it
in: ``a PGA of 488 g is implausible (outside [0.0001, 5] g): the values look like cm/s^2
(0.497 g)``, then how to give that unit (where two units fit, the one making a strong
motion: :data:`STRONG_PGA_G`); a PGA that is one sample far above the rest of the record is
refused as a spike, a bad sample, not a unit (:data:`SPIKE_RATIO`). The checks apply where
records are loaded for a run (:func:`pipeline.records.load_record` with ``check=True``, which
``pipeline.sweep`` and the commands use for AT2 and text files, and
:meth:`Record.from_array`); a record or pair given scaled (``kobe*1.5``) has its PGA checked
after the factor (:func:`check_scaled`, always: the refusal names the factors that run);
``Record(...)`` itself and the readers ``read_at2``/``read_text`` take any finite samples, so
a laboratory or synthetic motion can still be built and simulated.

PGV: the trapezoidal integral of the acceleration minus its mean (a constant-offset baseline
correction, nothing else), so that a record with an uncorrected offset is not refused for a
velocity drift it does not really have.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .basics import ACCEL_UNITS, G, RecordError, to_si

PGA_BOUNDS_G = (1e-4, 5.0)
"""PGA, g: the largest recorded is 4.36 g (vector sum of three components; 4022 cm/s^2 = 4.1 g
in one component), KiK-net IWTH25, 2008 Iwate-Miyagi Nairiku earthquake (NIED, the Guinness
record); 5 g leaves it room. The lower bound, 1e-4 g (0.1 cm/s^2), is about the weakest
motion strong-motion networks keep as a record."""

ORDINARY_PGA_G = 0.01
"""PGA, g, under which a record is weak: it is accepted unless the same numbers in another
unit give an ordinary record (PGA within [0.01 g, 2 g]), the AT2 slip of a 'CM/S/S' header over
values in g (0.83 g read as 0.00085 g). A stated choice: a record this weak hardly moves an
isolation system, let alone into its moat (the FEMA P695 far-field set took records above
0.2 g and 15 cm/s); 2 g is above every horizontal PGA but a handful (Tohoku 2011 MYG004,
2.7 g)."""

ORDINARY_MAX_PGA_G = 2.0
"""The upper end of an ordinary record's PGA, g (see :data:`ORDINARY_PGA_G`)."""

PGV_BOUNDS = (1e-4, 5.0)
"""PGV, m/s: the largest recorded is 3.18 m/s (Chi-Chi 1999, TCU068; Anderson, BSSA 100(1),
2010, the 100 largest PGAs and PGVs recorded to 2007); 5 m/s leaves it room; 1e-4 m/s
(0.01 cm/s) goes with the lower PGA bound."""

DURATION_BOUNDS = (1.0, 600.0)
"""Duration npts*dt, s: strong-motion records last tens of seconds; the longest, of great
subduction earthquakes (Tohoku 2011 at K-NET), about 300 s; 600 s leaves them room. A record
under 1 s holds no earthquake (a step given in ms as s, or a fragment)."""

SLIP_UNITS = ("g", "cm/s^2", "m/s^2")
"""The units a slip is looked for among (g vs cm/s^2: 981; g vs m/s^2: 9.81; m/s^2 vs cm/s^2:
100), and mm/s^2 when it is the unit given; in this order, the order in which records are most
often distributed (PEER: g; K-NET, COSMOS: cm/s^2), where two units fit as well."""

STRONG_PGA_G = 0.05
"""PGA, g, from which a record is a strong motion, as records run for pounding are (a stated
choice). Where the values are plausible in more than one unit (a record of 1.2 g in m/s^2
under a 'UNITS OF G' header reads as 0.012 g in cm/s^2 or 1.2 g in m/s^2), a unit that makes
it a strong motion is named as the fix before one that makes it a weak one, so that the
advice followed runs the record intended."""

SPIKE_RATIO = 5.0
"""A PGA more than this many times the record's largest acceleration outside 0.1 s of it is a
spike, one bad sample (or a few), not a unit: the refusal says so instead of naming a unit
that would scale the whole record. Real records' ratio is 1.1-1.3 (Kobe KJM 000, Sylmar
Converter 142, Pacoima Dam 164, measured); a stated choice well above it."""
SPIKE_WINDOW = 0.1
"""s: the half-width of the window around the peak left out when the record's next largest
acceleration is looked for (a strong pulse's neighbouring cycles are not a spike)."""


def record_peaks(accel_si: np.ndarray, dt: float) -> tuple[float, float, float]:
    """PGA (m/s^2), PGV (m/s) and duration npts*dt (s) of samples in m/s^2 at step dt s.

    PGV integrates ``accel - mean(accel)`` by the trapezoid rule from v(0) = 0."""
    a = np.asarray(accel_si, dtype=np.float64)
    pga = float(np.max(np.abs(a))) if a.size else 0.0
    if a.size > 1:
        a0 = a - a.mean()
        velocity = np.concatenate([[0.0], np.cumsum((a0[1:] + a0[:-1]) * (0.5 * dt))])
        pgv = float(np.max(np.abs(velocity)))
    else:
        pgv = 0.0
    return pga, pgv, a.size * dt


def _inside(value: float, bounds: tuple[float, float]) -> bool:
    return bounds[0] <= value <= bounds[1]


def _candidates(raw_pga: float, raw_pgv: float, units: str, ordinary: bool) -> list[tuple]:
    """(unit, PGA in g) of the other units in which the raw peaks are plausible (ordinary:
    a PGA within [ORDINARY_PGA_G, ORDINARY_MAX_PGA_G]), in the order of SLIP_UNITS."""
    found = []
    for other in (*SLIP_UNITS, *(("mm/s^2",) if units == "mm/s^2" else ())):
        if other == units:
            continue
        pga_g = float(to_si(np.float64(raw_pga), other)) / G
        pgv = float(to_si(np.float64(raw_pgv), other))
        band = (ORDINARY_PGA_G, ORDINARY_MAX_PGA_G) if ordinary else PGA_BOUNDS_G
        if _inside(pga_g, band) and _inside(pgv, PGV_BOUNDS):
            found.append((other, pga_g))
    # the likeliest first: a strong motion before a weak one, then SLIP_UNITS' order (stable)
    return sorted(found, key=lambda c: c[1] < STRONG_PGA_G)


def spike(accel_si: np.ndarray, dt: float) -> tuple[float, float] | None:
    """(time s, ratio) of a spike in samples (m/s^2, step dt s): a peak SPIKE_RATIO times or
    more the largest acceleration outside SPIKE_WINDOW of it; None when there is none."""
    a = np.abs(np.asarray(accel_si, dtype=np.float64))
    if a.size < 3:
        return None
    k, w = int(np.argmax(a)), max(1, int(round(SPIKE_WINDOW / dt)))
    rest = np.concatenate([a[:max(0, k - w)], a[k + w + 1:]])
    if rest.size == 0 or not np.isfinite(a[k]):
        return None
    ratio = a[k] / rest.max() if rest.max() > 0 else np.inf
    return (k * dt, float(ratio)) if ratio >= SPIKE_RATIO else None


def check_plausible(accel_si: np.ndarray, dt: float, units: str, where: str,
                    fix_units: Callable[[str], str] | None = None,
                    fix_dt: Callable[[float], str] | None = None,
                    units_note: str = "") -> None:
    """Refuse samples (m/s^2, step dt s, read in `units`, a key of ACCEL_UNITS) whose PGA, PGV
    or duration no earthquake record has: RecordError, starting with `where` (the file), with
    the unit (or step) that would make them plausible when one does.

    fix_units(unit) says how to give that unit ("give units='cm/s^2' ..."; default: "give
    units=..."); fix_dt(dt_s) how to give a step in s (None: the step is the file's own);
    units_note, where the units come from ("the header's"), said after them.
    """
    if units not in ACCEL_UNITS:
        raise ValueError(f"units must be a key of ACCEL_UNITS, got {units!r}")
    fix_units = fix_units or (lambda unit: f"give units={unit!r}")
    pga, pgv, duration = record_peaks(accel_si, dt)
    multiplier, divisor = ACCEL_UNITS[units]
    raw_pga, raw_pgv = pga * divisor / multiplier, pgv * divisor / multiplier
    pga_g = pga / G

    def slip(what: str, ordinary: bool) -> None:
        text = f"{where}: {what}"
        lone = None if ordinary else spike(accel_si, dt)
        if lone is not None:  # one bad sample: a unit would scale the whole record wrongly
            t, ratio = lone
            raise RecordError(f"{text}: it is a spike, one sample at t = {t:.4g} s, {ratio:.3g} "
                              f"times the record's largest acceleration {SPIKE_WINDOW:g} s and "
                              "more away from it: a bad sample, not a unit; remove it from the "
                              "file (or give the record without it)")
        found = _candidates(raw_pga, raw_pgv, units, True) \
            or ([] if ordinary else _candidates(raw_pga, raw_pgv, units, False))
        if found:
            looks = " or ".join(f"{u} ({p:.3g} g)" for u, p in found)
            text += f": the values look like {looks}; {fix_units(found[0][0])}"
        raise RecordError(text)

    if not _inside(duration, DURATION_BOUNDS):
        text = (f"{where}: a duration of {duration:.4g} s ({np.size(accel_si)} samples at "
                f"{dt:g} s) is implausible (outside [{DURATION_BOUNDS[0]:g}, "
                f"{DURATION_BOUNDS[1]:g}] s)")
        if fix_dt is not None and _inside(duration / 1000, DURATION_BOUNDS):
            text += f": is the step in ms? {dt:g} ms is {dt / 1000:g} s; {fix_dt(dt / 1000)}"
        raise RecordError(text)
    unit_note = "" if units == "g" else f" ({raw_pga:.4g} {units})"
    in_units = f"values in {units}" + (f" ({units_note})" if units_note else "")
    if not _inside(pga_g, PGA_BOUNDS_G):
        slip(f"a PGA of {pga_g:.3g} g{unit_note} is implausible (outside "
             f"[{PGA_BOUNDS_G[0]:g}, {PGA_BOUNDS_G[1]:g}] g) for {in_units}",
             ordinary=False)
    if pga_g < ORDINARY_PGA_G and _candidates(raw_pga, raw_pgv, units, True):
        slip(f"a PGA of {pga_g:.3g} g{unit_note} is weak (under {ORDINARY_PGA_G:g} g) for "
             f"{in_units}", ordinary=True)
    if not _inside(pgv, PGV_BOUNDS):
        slip(f"a PGV of {pgv:.3g} m/s is implausible (outside [{PGV_BOUNDS[0]:g}, "
             f"{PGV_BOUNDS[1]:g}] m/s) for {in_units} (PGV: the trapezoidal integral "
             "of the acceleration minus its mean)", ordinary=False)


def check_scaled(unscaled_pga: float, factor: float, where: str) -> None:
    """Refuse a record given scaled (``name*factor``) whose PGA after the factor no earthquake
    record has (PGA_BOUNDS_G): RecordError, starting with `where` (the name as given), naming
    the factors that keep it inside (rounded inward, so that the advice followed runs).
    unscaled_pga: the record's PGA before the factor, m/s^2 (the larger component's, for a
    pair)."""
    pga_g = unscaled_pga * factor / G
    if _inside(pga_g, PGA_BOUNDS_G) or unscaled_pga <= 0.0:
        return
    low, high = (bound * G / unscaled_pga for bound in PGA_BOUNDS_G)
    raise RecordError(f"{where}: a PGA of {pga_g:.3g} g after the factor {factor:g} is "
                      f"implausible (outside [{PGA_BOUNDS_G[0]:g}, {PGA_BOUNDS_G[1]:g}] g, what "
                      f"earthquakes have recorded); give a factor between {_rounded(low, 1)} "
                      f"and {_rounded(high, -1)}")


def check_level(pga: float, level: float, where: str) -> None:
    """Refuse an intensity level (a sweep's `level`, on a record run as it is) that takes the
    record's PGA (m/s^2, as run) beyond what earthquakes have recorded (PGA_BOUNDS_G's top):
    RecordError, starting with `where` (the record's name), naming the largest level that
    keeps it inside (rounded down, so that the advice followed runs)."""
    pga_g = pga * level / G
    if pga_g <= PGA_BOUNDS_G[1] or pga <= 0.0:
        return
    raise RecordError(f"{where}: level {level:g} takes its PGA to {pga_g:.3g} g, implausible "
                      f"(above {PGA_BOUNDS_G[1]:g} g, the most earthquakes have recorded); give "
                      f"levels up to {_rounded(PGA_BOUNDS_G[1] * G / pga, -1)}")


def _rounded(value: float, direction: int) -> str:
    """`value` to 3 significant digits, rounded up (direction 1) or down (-1)."""
    step = 10.0 ** (np.floor(np.log10(value)) - 2)
    return f"{(np.ceil if direction > 0 else np.floor)(value / step) * step:.3g}"
