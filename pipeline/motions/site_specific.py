"""A site-specific MCE_R spectrum given as a table (`--target-spectrum CSV`), and the design
parameters the code takes from it (ASCE 7-22 section 21.4).

    read_target_table(path)          the CSV (columns period_s, sa_g; a header line) as a
                                     TargetSpectrum of level MCE_R, RotD100
    site_specific_parameters(target) (S_MS, S_M1) in g from the spectrum, section 21.4

Section 21.4 (as this project reads it; not checked against the printed standard here): S_DS
is 90% of the largest Sa of the site-specific design spectrum at periods 0.2 to 5 s, S_D1 the
largest T Sa at periods 1 to 2 s where v_s30 > 1,200 ft/s and 1 to 5 s elsewhere, and S_MS, S_M1
are 1.5 times them: on the MCE_R spectrum itself (2/3 of which is the design spectrum), S_MS =
0.9 max Sa(0.2-5 s) and S_M1 = max T Sa over the same range. The wider range, 1 to 5 s, is taken
(v_s30 is not asked for): on softer sites it is the rule, on rock it can only give a larger S_M1,
a larger D_M. The floor of 21.4, 80% of the mapped values of section 11.4, is not applied (the
mapped values are not known here): a user's spectrum below it is the user's to answer for.
"""
from __future__ import annotations

import csv
import hashlib
from pathlib import Path

import numpy as np

from engine.units import G

from .target import TargetSpectrum

COLUMNS = ("period_s", "sa_g")
"""The table's columns: the period (s) and the MCE_R spectral acceleration (g, RotD100)."""
SHORT_RANGE = (0.2, 5.0)
"""s: the periods over which 90% of the largest Sa is S_MS (section 21.4)."""
LONG_RANGE = (1.0, 5.0)
"""s: the periods over which the largest T Sa is S_M1 (section 21.4, v_s30 <= 1,200 ft/s)."""
SHORT_FRACTION = 0.9
"""S_MS = 0.9 x the largest Sa over SHORT_RANGE (section 21.4)."""


def read_target_table(path) -> TargetSpectrum:
    """The site-specific MCE_R spectrum of a CSV table (COLUMNS, a header line, one period a
    row, periods increasing), its source naming the file and its sha256. ValueError in one
    line naming what is wrong (a missing column, a number that is not one, the order, a
    value <= 0, a table not covering SHORT_RANGE, the periods the code's parameters need)."""
    path = Path(path)
    try:
        data = path.read_bytes()
        rows = list(csv.DictReader(data.decode("utf-8-sig").splitlines()))
        periods = np.array([float(r[COLUMNS[0]]) for r in rows])
        sa_g = np.array([float(r[COLUMNS[1]]) for r in rows])
    except (OSError, UnicodeDecodeError) as e:
        raise ValueError(f"target spectrum {path}: cannot read it ({e})") from None
    except (KeyError, ValueError, TypeError) as e:
        raise ValueError(f"target spectrum {path}: needs the columns {COLUMNS[0]} (s) and "
                         f"{COLUMNS[1]} (g), a header line and one number each a row ({e})"
                         ) from None
    digest = hashlib.sha256(data).hexdigest()[:16]
    target = TargetSpectrum.from_table(
        periods, sa_g, level="MCE_R", component="RotD100",
        source=f"site-specific MCE_R spectrum, table {path.name} (sha256 {digest}...)")
    low, high = min(SHORT_RANGE[0], LONG_RANGE[0]), max(SHORT_RANGE[1], LONG_RANGE[1])
    if target.periods[0] > low or target.periods[-1] < high:
        raise ValueError(f"target spectrum {path}: covers {target.periods[0]:g} to "
                         f"{target.periods[-1]:g} s; the code's S_MS and S_M1 need {low:g} "
                         f"to {high:g} s at least (ASCE 7-22 section 21.4)")
    return target


def site_specific_parameters(target: TargetSpectrum) -> tuple[float, float]:
    """(S_MS, S_M1) in g of a site-specific MCE_R spectrum (section 21.4, see the module
    docstring): 0.9 x the largest Sa at periods in SHORT_RANGE, the largest T Sa at periods
    in LONG_RANGE; over the table's own periods in the range and the range's ends (the
    spectrum is log-log linear in between, so T Sa's largest value is at one of them)."""
    def within(bounds):
        t = target.periods
        inside = t[(t >= bounds[0]) & (t <= bounds[1])]
        return np.unique(np.concatenate([inside, bounds]))

    short = within(SHORT_RANGE)
    long = within(LONG_RANGE)
    s_ms = SHORT_FRACTION * float(np.max(target.at(short))) / G
    s_m1 = float(np.max(long * target.at(long))) / G
    return s_ms, s_m1
