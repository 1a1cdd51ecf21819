"""PEER AT2 files: :func:`read_at2` reads one into a :class:`Record`, :func:`parse_at2` gives
the samples as written with the header's units (:class:`At2File`)."""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import NoReturn

import numpy as np

from .record import (
    NUMBER_RE,
    UNITS_HELP,
    Record,
    RecordError,
    canonical_units,
    norm_component,
    read_lines,
    rsn_from_name,
    spells_non_finite,
    to_si,
)

# The NPTS/DT line is line 4 in every known layout; a little slack for hand-edited headers.
_MAX_HEADER_LINES = 10
_NUMBER = NUMBER_RE.pattern
# Whitespace-separated numbers only: glued values such as "1.5E-02-3.1E-02" are an error.
_DATA_RE = re.compile(rf"\s*(?:{_NUMBER}(?:\s+{_NUMBER})*)?\s*", re.ASCII)
_NPTS_RE = re.compile(r"\bNPTS\s*=?\s*([^\s,]+)", re.IGNORECASE)
_DT_RE = re.compile(r"\bDT\s*=?\s*([^\s,]+)", re.IGNORECASE)
_NUMBERS_FIRST_RE = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,?\s*DT\b", re.IGNORECASE)
_DATE_RE = re.compile(r"\d+/\d+/\d+")
# "UNITS OF G.", "UNITS OF CM/S/S", "UNITS OF CM/SEC^2,", "UNITS OF M/S**2": the token ends at
# the first character that cannot be part of a units spelling (space, '.', ',', ';', ')').
_UNITS_RE = re.compile(r"\bUNITS?\s+OF\s+([A-Za-z][A-Za-z0-9/^*\-]*)", re.IGNORECASE)


@dataclass(frozen=True, eq=False)
class At2File:
    """An AT2 file as parsed: ``values`` as written (in ``units``, a key of ACCEL_UNITS)."""

    path: Path
    values: np.ndarray
    units: str
    dt: float
    event: str
    station: str
    component: str
    rsn: int | None


_HEADER_SPELLING = {"g": "G", "m/s^2": "M/S/S", "cm/s^2": "CM/S/S", "mm/s^2": "MM/S/S"}


def read_at2(path: str | os.PathLike, *, check: bool = False) -> Record:
    """Read a PEER AT2 file into a :class:`Record` (m/s^2, s).

    Accepts the NGA-West2 and older PEER layouts: ``NPTS=  8000, DT= .00500 SEC``,
    ``NPTS =   7500 , DT =   .020 SEC ,``, ``NPTS=   4172  DT=   .0100 SEC,``, the oldest
    ``4164 0.0100 NPTS, DT``, LF or CRLF line ends, trailing spaces, any count per line.
    Values are in g unless a header line says ``UNITS OF`` cm/s^2 (``CM/S/S``, ``CM/SEC/SEC``,
    ``CM/S^2``, ``CM/S2``, ``GAL``), m/s^2 or mm/s^2 (see :data:`ACCEL_UNITS`); g is converted
    with :data:`G`. Velocity and displacement files and other units are refused.
    Event, station and component come from header line 2, the RSN from an ``RSN<n>`` file name.
    Raises :class:`RecordError` (file name and line number in the message) on anything odd.

    check: also refuse a record no earthquake produced (:func:`check_plausible`: PGA, PGV,
    duration), above all values in other units than the header says (a 'CM/S/S' header over
    values in g), naming the units that fit; what ``pipeline.sweep`` and the commands read.
    """
    at2 = parse_at2(Path(path))
    if check:
        from .plausible import check_plausible

        check_plausible(to_si(at2.values, at2.units), at2.dt, at2.units,
                        str(at2.path), units_note="the header's units",
                        fix_units=lambda unit: f"correct the file's header to say 'UNITS OF "
                                               f"{_HEADER_SPELLING[unit]}' (an AT2 file "
                                               "states its own units)")
    return Record(name=at2.path.stem, rsn=at2.rsn, event=at2.event, station=at2.station,
                  component=at2.component, dt=at2.dt, accel=to_si(at2.values, at2.units),
                  source=str(at2.path))


def parse_at2(path: Path) -> At2File:
    """An AT2 file's samples as written, with their units and the header's fields; the checks
    and errors of :func:`read_at2`, which converts the samples to m/s^2."""
    lines = read_lines(path)
    if not any(line.strip() for line in lines):
        raise RecordError(f"{path}: file is empty")
    h = _find_count_line(lines, path)
    units = _header_units(lines[:h], path)
    npts, dt = _parse_count_line(lines[h], f"{path}, line {h + 1}")
    body = lines[h + 1:]
    text = "\n".join(body)
    tokens = text.split()
    if not _DATA_RE.fullmatch(text):
        _raise_bad_token(path, body, h + 2)
    if len(tokens) != npts:
        raise RecordError(f"{path}: {len(tokens)} values after the header but NPTS = {npts} "
                          f"(line {h + 1})")
    values = np.array(tokens, dtype=np.float64)
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        counts = np.cumsum([len(line.split()) for line in body])
        lineno = h + 2 + int(np.searchsorted(counts, bad[0], side="right"))
        raise RecordError(f"{path}, line {lineno}: value {tokens[bad[0]]!r} is not finite")
    event, station, component = _split_header_line2(lines[1]) if h >= 2 else ("", "", "")
    return At2File(path=path, values=values, units=units, dt=dt, event=event, station=station,
                   component=component, rsn=rsn_from_name(path))


def read_at2_header(path: Path) -> tuple[str, str, str] | None:
    """Event, station, component from header line 2, reading only the first lines."""
    try:
        with open(path, encoding="latin-1", newline=None) as f:
            head = [f.readline() for _ in range(4)]
    except OSError:
        return None
    return _split_header_line2(head[1]) if head[1].strip() else None


def _split_header_line2(line: str) -> tuple[str, str, str]:
    """'Kobe Japan, 1/16/1995, KJMA, 0' -> ('Kobe Japan', 'KJMA', '000')."""
    parts = [p.strip() for p in line.split(",")]
    if len(parts) < 3:
        return line.strip(), "", ""
    middle = parts[1:-1]
    while len(middle) > 1 and _DATE_RE.search(middle[0]):
        middle = middle[1:]
    last = parts[-1].split()
    return parts[0], ", ".join(middle), norm_component(last[0]) if last else ""


def _parse_count_line(line: str, where: str) -> tuple[int, float]:
    m = _NUMBERS_FIRST_RE.match(line)
    if m:
        npts_tok, dt_tok = m.groups()
    else:
        m_n, m_d = _NPTS_RE.search(line), _DT_RE.search(line)
        if not m_n:
            raise RecordError(f"{where}: cannot read NPTS from {line.strip()!r}")
        if not m_d:
            raise RecordError(f"{where}: no DT in {line.strip()!r}")
        npts_tok, dt_tok = m_n.group(1), m_d.group(1)
    dt_tok = re.sub(r"(?i)(sec|s)$", "", dt_tok)
    if not npts_tok.isdigit() or int(npts_tok) == 0:
        raise RecordError(f"{where}: NPTS must be a positive integer, got {npts_tok!r}")
    if not NUMBER_RE.fullmatch(dt_tok):
        raise RecordError(f"{where}: cannot read DT from {dt_tok!r}")
    dt = float(dt_tok)
    if not (math.isfinite(dt) and dt > 0):
        raise RecordError(f"{where}: DT must be > 0 s, got {dt_tok!r}")
    return int(npts_tok), dt


def _find_count_line(lines: list[str], path: Path) -> int:
    head = lines[:_MAX_HEADER_LINES]
    for i, line in enumerate(head):
        if "NPTS" in line.upper():
            return i
    for i, line in enumerate(head):
        if re.search(r"\bDT\b", line, re.IGNORECASE):
            raise RecordError(f"{path}, line {i + 1}: no NPTS in {line.strip()!r}")
    raise RecordError(f"{path}: no NPTS/DT header line in lines 1-{_MAX_HEADER_LINES} "
                      "(expected on line 4, e.g. 'NPTS=  4172, DT=   .0100 SEC,')")


def _header_units(header: list[str], path: Path) -> str:
    """The values' units stated in the header (a key of ACCEL_UNITS); g when none is stated.

    Refuses velocity/displacement files and units it does not know: they would parse silently.
    """
    found: tuple[str, int] | None = None
    for i, line in enumerate(header):
        upper = line.upper()
        if re.search(r"\b(VELOCITY|DISPLACEMENT)\b", upper) and "ACCELERATION" not in upper:
            raise RecordError(f"{path}, line {i + 1}: not an acceleration record "
                              f"({line.strip()!r})")
        m = _UNITS_RE.search(re.sub(r"\s*/\s*", "/", line))
        if not m:
            continue
        units = canonical_units(m.group(1))
        if units is None:
            raise RecordError(f"{path}, line {i + 1}: units {m.group(1)!r} not understood; "
                              f"expected an acceleration in {UNITS_HELP}")
        if found is not None and found[0] != units:
            raise RecordError(f"{path}, line {i + 1}: units {m.group(1)!r} contradict line "
                              f"{found[1]} ({found[0]})")
        found = (units, i + 1)
    return found[0] if found else "g"


def _raise_bad_token(path: Path, body: list[str], first_lineno: int) -> NoReturn:
    for offset, line in enumerate(body):
        for tok in line.split():
            if not NUMBER_RE.fullmatch(tok):
                what = "is not finite" if spells_non_finite(tok) else \
                    "is not a number"
                raise RecordError(f"{path}, line {first_lineno + offset}: value {tok!r} {what}")
    raise RecordError(f"{path}: unreadable data")  # unreachable unless the regexes disagree
