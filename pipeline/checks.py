"""The input checks every part of the pipeline shares, each raising one SweepError that names
the input: whole numbers, values no real structure has (most likely a unit slip, with the
conversion), a law's declared range, and records and pairs resolved by name. Imports no other
module of the pipeline's but its errors (and the records, when resolving them)."""
from __future__ import annotations

import operator

import numpy as np

import engine

from .errors import SweepError

# Units in which a value is most likely meant when it is implausible in SI: (unit, its value
# in SI, the suffix of the command-line option taking it).
UNIT_SLIPS = {"m": ("cm", 1e-2, "cm"), "N m-1": ("kN/mm", 1e6, "kn-mm"),
              "kg": ("t", 1e3, "t")}


def check_count(name: str, value, minimum: int) -> int:
    """`value` as an int >= minimum, or SweepError naming it."""
    try:
        count = operator.index(value)
    except TypeError:
        raise SweepError(f"{name} must be a whole number, got {value!r}") from None
    if count < minimum:
        raise SweepError(f"{name} must be >= {minimum}, got {count}")
    return count


def resolve_pairs(pairs, records_dir=None) -> tuple[list, list[str]]:
    """pipeline.records.resolve_pairs, its RecordError raised as SweepError."""
    from .records import RecordError
    from .records import resolve_pairs as resolve

    try:
        return resolve(pairs, records_dir)
    except RecordError as err:
        raise SweepError(str(err)) from err


def resolve_records(records, records_dir=None) -> tuple[list, list[str]]:
    """pipeline.records.resolve_records, its RecordError raised as SweepError."""
    from .records import RecordError
    from .records import resolve_records as resolve

    try:
        return resolve(records, records_dir)
    except RecordError as err:
        raise SweepError(str(err)) from err


def plausible(name: str, param, array: np.ndarray, option: bool = True) -> np.ndarray:
    """Refuse values outside the declaration's `plausible` range (a real moat, bumper, slab or
    isolator has none): most likely a value in the paper's units given as SI. The message
    gives the conversion and, when `option`, the command-line option in the paper's unit."""
    bad = param.implausible(array)
    if bad.size == 0:
        return array
    worst = float(bad[0])
    unit = "" if param.units == "1" else f" {param.units}"  # a ratio: no unit to say
    text = f"{name} {worst:g}{unit} is implausible (outside {param.plausible}{unit})"
    if param.units in UNIT_SLIPS:
        unit, factor, suffix = UNIT_SLIPS[param.units]
        text += f": give {param.units} ({worst:g} {unit} is {worst * factor:g} {param.units})"
        if option:
            text += f", or --{name.replace('_', '-')}-{suffix} {worst:g} on the command line"
    raise SweepError(text)


def fits_the_wall(law: str, values) -> None:
    """SweepError, one line, where the wall of `law` cannot hold the members' parameters
    (values: name -> array; a law's optional `crowded`, e.g. more bumpers than a wall holds):
    for a grid and a listed table alike."""
    crowded = getattr(engine.impact.LAWS[law], "crowded", None)
    problem = None if crowded is None else crowded(values)
    if problem is not None:
        raise SweepError(problem)


def checked_values(param, array: np.ndarray, name: str) -> np.ndarray:
    """The declaration's range check, in the sweep's vocabulary; a ratio given in percent
    (strain 80) is said to be one."""
    try:
        return param.check(array, name=name)
    except engine.EngineError as err:
        text = str(err)
        if param.units == "1" and not param.integer:
            values = np.atleast_1d(np.asarray(array, dtype=float))
            worst = float(values[np.argmax(np.abs(values))])
            try:
                param.check(values / 100, name=name)
            except engine.EngineError:
                pass
            else:
                text += f": a ratio, not a percentage ({worst:g}% is {worst / 100:g})"
        raise SweepError(text) from None
