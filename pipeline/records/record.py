"""The :class:`Record` type and what every reader of records shares.

The units and errors of the record layer (pipeline/records/basics.py, read from here too), the
spelling of component labels, the low-level reading of a record file (lines,
numbers, the RSN in a file name) and the user's records directory (``$BUMPERS_RECORDS_DIR``).
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .basics import (  # noqa: F401 - the record layer's names, read from here too
    ACCEL_UNITS,
    UNITS_HELP,
    G,
    RecordError,
    StandInWarning,
    canonical_units,
    to_si,
)

RECORDS_DIR_ENV = "BUMPERS_RECORDS_DIR"
FOUND_IN = ("records_dir", "built-in", "library", "stand-in")

NUMBER_RE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[Ee][+-]?\d+)?", re.ASCII)
"""One number as record files write it (``-.1416764E-03``, ``12``, ``0.005``)."""


def norm_component(comp: str) -> str:
    """'0' -> '000', '90' -> '090', 'e' -> 'E': one spelling per component label."""
    comp = comp.strip().upper()
    return comp.zfill(3) if comp.isdigit() else comp


def normalize(text: str) -> str:
    """Lower-case letters and digits only: 'Sylmar - Converter Sta' -> 'sylmarconvertersta'."""
    return re.sub(r"[^a-z0-9]", "", text.lower())


def spells_non_finite(token: str) -> bool:
    """Whether a token that is not a number spells NaN or infinity ('nan', '-Inf', 'INFINITY')."""
    return normalize(token) in {"nan", "inf", "infinity"}


def read_lines(path: Path) -> list[str]:
    """A record file's lines (UTF-8, else Latin-1); RecordError if it cannot be read."""
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


def rsn_from_name(path: Path) -> int | None:
    """The record sequence number of an ``RSN<n>`` file name, else None."""
    m = re.search(r"RSN(\d+)", path.name, re.IGNORECASE)
    return int(m.group(1)) if m else None


def records_directory(records_dir: str | os.PathLike | None) -> Path | None:
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


def scale_factor(factor, what: str) -> float:
    """A record's scale factor as a float, or RecordError."""
    try:
        value = float(factor)
    except (TypeError, ValueError):
        raise RecordError(f"{what}: scale factor must be a number, got {factor!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise RecordError(f"{what}: scale factor must be positive and finite, got {factor!r}")
    return value


@dataclass(frozen=True, eq=False)
class Record:
    """One horizontal ground-acceleration component, sampled at a constant step.

    ``accel`` is in m/s^2 (read-only float64 array, sample i at t = i*dt), ``dt`` in s,
    ``pga`` in m/s^2. ``found_in``/``note``/``paper_key`` are set only for the paper's
    records (see :func:`paper_record`). ``scale`` (-) is the factor the original record was
    multiplied by (1 unscaled; see :meth:`scaled`), ``unscaled_pga`` its PGA before (m/s^2).
    ``label`` is what the user called it where that is not its paper key or name (a library
    selector such as RSN1106:000: resolve_records), the name an archive gives it.
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
    label: str | None = None
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

    @classmethod
    def from_array(cls, accel, dt: float, *, units: str, name: str = "array",
                   source: str | None = None) -> Record:
        """A record from samples: ``accel`` (1-D, sample i at t = i*dt) in ``units``
        (required: ``"g"``, ``"m/s^2"`` or ``"cm/s^2"``, also spelt ``"m/s2"``, ``"cm/s2"``,
        ``"gal"``, or ``"mm/s^2"``), converted to the m/s^2 the engine takes; ``dt`` in s.

        The record is checked (:func:`pipeline.records.plausible.check_plausible`): a PGA,
        PGV or duration no earthquake produced is refused (RecordError), with the units (or
        step in s) that would fit, e.g. ``a PGA of 488 g ...: the values look like cm/s^2
        (0.497 g); give units='cm/s^2'``. ``Record(...)`` itself takes any finite samples in
        m/s^2, unchecked.
        """
        from .plausible import check_plausible

        where = source or name
        label = canonical_units(units) if isinstance(units, str) else None
        if label is None:
            raise RecordError(f"{where}: units {units!r} not understood; give the "
                              f"acceleration's units as {UNITS_HELP}")
        try:
            values = np.array(accel, dtype=np.float64)
        except (TypeError, ValueError):
            raise RecordError(f"{where}: accel must be an array of numbers") from None
        try:
            dt = float(dt)
        except (TypeError, ValueError):
            raise RecordError(f"{where}: dt must be a number of s, got {dt!r}") from None
        record = cls(name=name, rsn=None, event="", station="", component="", dt=dt,
                     accel=to_si(values, label), source=where)
        check_plausible(record.accel, record.dt, label, where,
                        fix_units=lambda unit: f"give units={unit!r}",
                        fix_dt=lambda s: f"give dt={s:g} (s)")
        return record

    def scaled(self, factor: float) -> Record:
        """This record times `factor` (-): accel * factor, named ``<name>*<factor>`` (the
        factor as given, shortest form), with ``scale`` and ``unscaled_pga`` kept, so that
        two scales of one record are two archive coordinates. Raises RecordError for a
        factor that is not a positive finite number."""
        factor = scale_factor(factor, self.name)
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


def samples_digest(values: np.ndarray):
    """A sha256 hash object fed with samples as little-endian float64 bytes: the one way the
    project hashes record samples (the built-in data's checksum, the archives' record hashes,
    the resume keys); callers add what else identifies them (e.g. the step)."""
    return hashlib.sha256(np.ascontiguousarray(values, dtype="<f8").tobytes())
