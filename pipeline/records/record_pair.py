"""A record pair as one excitation of a sweep in plan (pipeline.sweep(..., moat=...)):
:class:`RecordPair`, a pair named and aligned, answering what the pipeline asks of a record,
and :func:`resolve_pairs`, the pairs of a sweep from what the user gave. Loading a pair is
:mod:`pair`'s job."""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass

import numpy as np

from .pair import align_pair, load_pair
from .record import Record, RecordError


@dataclass(frozen=True)
class RecordPair:
    """A record pair as one excitation of a sweep in plan: its name in the archive's record
    coordinate and its two aligned components x, y (Records). Answers what the pipeline asks of
    a record: accel (N, 2) m/s^2 (x, y), dt s, pga (the larger component's, m/s^2), scale,
    source, found_in, note."""

    name: str
    x: Record
    y: Record

    @functools.cached_property
    def accel(self) -> np.ndarray:
        return np.column_stack([self.x.accel, self.y.accel])

    @property
    def dt(self) -> float:
        return self.x.dt

    @property
    def npts(self) -> int:
        return self.x.npts

    @property
    def pga(self) -> float:
        return max(self.x.pga, self.y.pga)

    @property
    def unscaled_pga(self) -> float:
        return max(self.x.unscaled_pga, self.y.unscaled_pga)

    @property
    def scale(self) -> float:
        return self.x.scale

    @property
    def rsn(self):
        return self.x.rsn

    @property
    def event(self) -> str:
        return self.x.event

    @property
    def station(self) -> str:
        return self.x.station

    @property
    def component(self) -> str:
        return f"{self.x.component}+{self.y.component}"

    @property
    def source(self) -> str:
        return f"x: {self.x.source}; y: {self.y.source}"

    @property
    def found_in(self) -> str:
        found = dict.fromkeys(f for f in (self.x.found_in, self.y.found_in) if f)
        return "+".join(found) or "given"

    @property
    def note(self) -> str:
        return " ".join(n for n in (self.x.note, self.y.note) if n)


def resolve_pairs(pairs, records_dir=None) -> tuple[list[RecordPair], list[str]]:
    """Record pairs given by name (anything load_pair takes), as RecordPair objects or as
    (x, y) Records, and their names in an archive's record coordinate: the name as given
    (a paper key, `RSN953`, `A+B`), or `x.name+y.name` for a tuple. RecordError (message
    starting "records:") for an empty list, a pair that cannot be loaded, one given twice."""
    if isinstance(pairs, (str, os.PathLike, int, RecordPair)) or (
            isinstance(pairs, tuple) and len(pairs) == 2
            and all(isinstance(p, Record) for p in pairs)):
        pairs = [pairs]
    if isinstance(pairs, np.ndarray) or (
            isinstance(pairs, (list, tuple)) and any(isinstance(p, np.ndarray) for p in pairs)):
        raise RecordError("records: a NumPy array is not a record pair (its step and units "
                          "are unknown): give a pair of Records, (Record.from_array(ax, dt, "
                          "units=...), Record.from_array(ay, dt, units=...)) (dt in s; units "
                          "'g', 'm/s^2' or 'cm/s^2')")
    pairs = list(pairs)
    if not pairs:
        raise RecordError("records: no record pair given")
    loaded = []
    for item in pairs:
        if isinstance(item, RecordPair):
            loaded.append(item)
            continue
        try:
            x, y = load_pair(item, records_dir)
        except RecordError as err:
            raise RecordError(f"records: {err}") from err
        name = str(item) if not isinstance(item, (tuple, list)) else f"{x.name}+{y.name}"
        loaded.append(RecordPair(name, *align_pair(x, y)))
    names = [p.name for p in loaded]
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise RecordError(f"records: each pair must appear once, repeated {repeated}")
    return loaded, names
