"""Plain text records, one column (acceleration) or two (time in s, acceleration):
:func:`read_text`."""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import numpy as np

from .record import (
    NUMBER_RE,
    UNITS_HELP,
    Record,
    RecordError,
    canonical_units,
    read_lines,
    rsn_from_name,
    spells_non_finite,
    to_si,
)

TIME_STEP_RTOL = 1e-3
"""Relative tolerance on each step of a two-column text file's time column."""

_FIELD_SEP_RE = re.compile(r"\s*,\s*|\s+")


def read_text(path: str | os.PathLike, units: str, dt: float | None = None, *,
              check: bool = False) -> Record:
    """Read a plain text record: one column (acceleration) or two (time in s, acceleration).

    ``units`` is required: the acceleration column's units, ``"g"`` (converted with
    :data:`G`), ``"m/s^2"``, ``"cm/s^2"`` (or ``"gal"``) or ``"mm/s^2"``, in the spellings of
    :data:`ACCEL_UNITS`. ``dt`` in s is required for one column; for two columns it is taken
    from the times, which must step uniformly (each step within :data:`TIME_STEP_RTOL` of the
    mean step), and a ``dt`` given must agree with them. The first time is the record's t = 0
    (times may start anywhere). Values are separated by commas or whitespace; blank lines and
    lines starting with ``#`` are skipped. Anything else raises :class:`RecordError` naming
    the file and line.

    check: also refuse a record no earthquake produced (:func:`check_plausible`: PGA, PGV,
    duration), naming the units (or the step in s) that fit: what ``pipeline.sweep`` and the
    commands read.
    """
    path = Path(path)
    if units is None:
        raise RecordError(f"{path}: units are required: give the acceleration column's units "
                          f"as {UNITS_HELP}")
    label = canonical_units(units) if isinstance(units, str) else None
    if label is None:
        raise RecordError(f"{path}: units {units!r} not understood; give the acceleration "
                          f"column's units as {UNITS_HELP}")
    if dt is not None:
        try:
            dt = float(dt)
        except (TypeError, ValueError):
            raise RecordError(f"{path}: dt must be a number of s, got {dt!r}") from None
        if not (math.isfinite(dt) and dt > 0):
            raise RecordError(f"{path}: dt must be a positive number of s, got {dt!r}")
    rows, linenos = [], []
    for lineno, line in enumerate(read_lines(path), start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        tokens = _FIELD_SEP_RE.split(text)
        for tok in tokens:
            if not NUMBER_RE.fullmatch(tok):
                what = "an empty field" if tok == "" else f"value {tok!r}"
                why = "is not finite" if spells_non_finite(tok) else \
                    "is not a number (comment lines start with '#')"
                raise RecordError(f"{path}, line {lineno}: {what} {why}")
        if len(tokens) > 2 or (rows and len(tokens) != len(rows[0])):
            expected = f"as on line {linenos[0]}" if rows else "time s, acceleration"
            raise RecordError(f"{path}, line {lineno}: {len(tokens)} columns; expected "
                              f"{len(rows[0]) if rows else '1 or 2'} ({expected})")
        rows.append(tokens)
        linenos.append(lineno)
    if not rows:
        raise RecordError(f"{path}: no data (only blank lines and '#' comments)")
    table = np.array(rows, dtype=np.float64)
    bad = np.flatnonzero(~np.all(np.isfinite(table), axis=1))
    if bad.size:
        raise RecordError(f"{path}, line {linenos[bad[0]]}: value "
                          f"{next(t for t in rows[bad[0]] if not math.isfinite(float(t)))!r} "
                          "is not finite")
    if table.shape[1] == 1:
        if dt is None:
            raise RecordError(f"{path}: one column of accelerations needs the time step: "
                              "pass dt (s)")
        values = table[:, 0]
    else:
        dt = _uniform_step(table[:, 0], linenos, dt, path)
        values = table[:, 1]
    accel = to_si(values, label)
    if check:
        from .plausible import check_plausible

        one_column = table.shape[1] == 1
        check_plausible(accel, dt, label, str(path),
                        fix_units=lambda unit: f"give units {unit} (--record-units {unit} "
                                               f"on the command line, units={unit!r} in "
                                               "Python)",
                        fix_dt=(lambda s: f"give dt {s:g} s (--record-dt {s:g} on the "
                                          f"command line, dt={s:g} in Python)")
                        if one_column else None)
    return Record(name=path.stem, rsn=rsn_from_name(path), event="", station="",
                  component="", dt=dt, accel=accel, source=str(path))


def _uniform_step(times: np.ndarray, linenos: list[int], dt: float | None, path: Path) -> float:
    """The time step in s of a two-column file's times; RecordError unless uniform."""
    if times.size < 2:
        raise RecordError(f"{path}, line {linenos[0]}: one row of time and acceleration "
                          "gives no time step; give at least two rows")
    step = (times[-1] - times[0]) / (times.size - 1)
    if not step > 0:
        raise RecordError(f"{path}, line {linenos[-1]}: the times do not increase (from "
                          f"t = {times[0]:g} s on line {linenos[0]} to t = {times[-1]:g} s)")
    steps = np.diff(times)
    bad = np.flatnonzero(~(np.abs(steps - step) <= TIME_STEP_RTOL * step))
    if bad.size:
        i = int(bad[0])
        raise RecordError(f"{path}, line {linenos[i + 1]}: irregular time step: "
                          f"t = {times[i + 1]:g} s follows t = {times[i]:g} s, a step of "
                          f"{steps[i]:g} s against {step:g} s on average (the times must "
                          f"step uniformly, to {TIME_STEP_RTOL:g} relative)")
    if dt is not None:
        if abs(dt - step) > TIME_STEP_RTOL * step:
            raise RecordError(f"{path}: dt = {dt:g} s given, but the times step by "
                              f"{step:g} s")
        return dt
    # The mean of printed times carries rounding noise (0.005000000000000001): keep 12 digits.
    return float(f"{step:.12g}")
