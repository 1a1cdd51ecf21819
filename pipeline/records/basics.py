"""The record layer's units and errors, a leaf every records module may import: the
acceleration units understood (``ACCEL_UNITS``, :func:`canonical_units`, :func:`to_si`) and
the errors and warnings of the record layer."""

from __future__ import annotations

import re

import numpy as np

from engine.units import G  # m/s^2 in 1 g (SPEC: 9.81), the project's one value

ACCEL_UNITS = {"g": (G, 1.0), "m/s^2": (1.0, 1.0), "cm/s^2": (1.0, 100.0),
               "mm/s^2": (1.0, 1000.0)}
"""Acceleration units understood, each as (multiplier, divisor) to m/s^2: a value x in these
units is ``x * multiplier / divisor`` m/s^2 (a division by 100 rounds better than * 0.01).
Spellings such as ``CM/S/S``, ``CM/SEC/SEC``, ``cm/s2``, ``gal`` and ``M/S**2`` are accepted."""

UNITS_HELP = "g, cm/s^2 (gal, CM/S/S), m/s^2 or mm/s^2"
"""The accepted acceleration units, as error messages list them."""


class StandInWarning(UserWarning):
    """A paper record was not found and a stand-in is used: said when the record is resolved,
    before any simulation; silence it with ``warnings.simplefilter("ignore", StandInWarning)``."""


class RecordError(ValueError):
    """A record cannot be read, found or trusted. The message names the file (and line)."""


def canonical_units(text: str) -> str | None:
    """A key of :data:`ACCEL_UNITS` for an acceleration units spelling, else None.

    'G' -> 'g'; 'GAL', 'CM/S/S', 'CM/SEC/SEC', 'cm/s^2', 'CM/S2', 'cm s-2' -> 'cm/s^2'; likewise
    for m and mm. Velocities ('CM/S'), lengths and anything else give None.
    """
    t = re.sub(r"\s+", "", text.lower()).replace("**", "^").replace("sec", "s").replace("^", "")
    if t == "g":
        return "g"
    if t in ("gal", "gals"):
        return "cm/s^2"
    m = re.fullmatch(r"(mm|cm|m)(?:/s2|/s/s|s-2|[.*]s-2|/\(s\*?s\))", t)
    return f"{m.group(1)}/s^2" if m else None


def to_si(values: np.ndarray, units: str) -> np.ndarray:
    """Accelerations in ``units`` (a key of :data:`ACCEL_UNITS`) to m/s^2."""
    multiplier, divisor = ACCEL_UNITS[units]
    accel = values * multiplier
    return accel / divisor if divisor != 1.0 else accel
