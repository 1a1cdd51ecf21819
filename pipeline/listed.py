"""Members listed one by one: a sweep whose members are not every combination of a few values
but a table, the same for every record or one per record.

    pipeline.sweep(pairs, moat="rectangular", members={
        "law": ["none", "linear", "bumper"],
        "gap": [np.nan, 0.20, 0.20], "thickness": [np.nan, np.nan, 0.05],
        "angle": [0.0, 0.0, 0.0]})

A design search's candidates (bumpers of different thickness, count and wall), or gaps that
depend on each record (the plan study's fractions of each record's own peak), are such tables.
Column "law" names each member's wall law (engine.impact.LAWS, or "none" for no wall); every
other column is a sweep parameter (pipeline.members.DIMENSIONS: the wall's, the excitation's
level, angle and mu_wall), a law's parameter that grids keep at its default
(pipeline.members.LISTED_PARAMS: a bumper's area, say) or m_eff, in SI units. A column is (K,),
the same for every record,
or (R, K), one row per record (the records' order). NaN where a member's law does not take the
parameter; a parameter its law takes and the table leaves out (or NaN) takes the law's
declared default. Every value is checked against its law's declaration, as a sweep's are.

The archive has dims (record, member): the peaks of member k of record r at [r, k], and the
table's columns as coordinates along member (or record and member), labelled with their
declarations' units.
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from engine.impact import LAWS, M_EFF, NO_WALL

from .checks import checked_values, fits_the_wall, plausible
from .errors import SweepError
from .grid import Block, Grid
from .members import (
    EXCITATION,
    EXCITATION_PARAMETERS,
    EXCITATION_PARAMS,
    LISTED_PARAMS,
    MEMBER_DTYPE,
    PARAMS,
    excitation_carried,
    names,
)

TABLE_COLUMNS = ("law", *names(*EXCITATION, "wall", "listed", "mass"))
"""What a table of members may hold: the law's name and the members' numbers
(pipeline.grid.COLUMNS) but the isolator's."""


def listed_grid(table: Mapping, *, isolator: str = "bilinear", plan: bool = False,
                intensity: bool = False) -> Grid:
    """The Grid of the members of `table` (see the module docstring). plan: the members run
    in plan (angle and mu_wall default to 0); intensity: the records carry factors (level
    defaults to 1). SweepError naming the column and member for anything the laws refuse."""
    if not isinstance(table, Mapping) or "law" not in table:
        raise SweepError("members must be a table: a dict of columns with 'law' (the wall law "
                         "of each member) and the parameters by name")
    unknown = [name for name in table if name not in TABLE_COLUMNS]
    if unknown:
        raise SweepError(f"members: {unknown[0]!r} is no member column; the columns are "
                         f"{', '.join(TABLE_COLUMNS)}")
    laws = np.asarray(table["law"], dtype=str)
    if laws.ndim not in (1, 2) or laws.size == 0:
        raise SweepError(f"members: law must be (K,) or (R, K) names, got shape {laws.shape}")
    columns = {name: _column(name, table[name], laws.shape) for name in table if name != "law"}
    shape = np.broadcast_shapes(laws.shape, *(c.shape for c in columns.values()))
    rows = np.zeros(shape, dtype=MEMBER_DTYPE)
    for name in MEMBER_DTYPE.names[1:]:  # every number; the law's name set below
        rows[name] = np.nan
    rows["law"] = np.broadcast_to(laws, shape)
    rows["m_eff"] = M_EFF.default
    for name, values in columns.items():
        rows[name] = np.broadcast_to(values, shape)
    for law in np.unique(rows["law"]):
        _fill(rows, rows["law"] == law, str(law))
    _excitation(rows, plan, intensity)
    per_record = rows.ndim == 2
    k = shape[-1]
    flat = rows.reshape(-1, k)
    block = Block("", ("member",), (k,), flat[0])
    listed = {"law": laws, **columns}
    for name in EXCITATION_PARAMS:  # defaults filled in: the archive says what ran
        if name not in listed and not np.all(np.isnan(rows[name])):
            listed[name] = rows[name][0] if per_record else rows[name]
    # the grid's laws, as they first appear: what the archive and its provenance name
    impact = " ".join(dict.fromkeys(rows["law"].ravel().tolist()))
    return Grid(impact, {}, {}, (block,), float(M_EFF.default), isolator, plan,
                listed=listed, table=flat if per_record else None)


def check_records(grid: Grid, n_records: int) -> None:
    """Refuse a table of members per record whose rows are not one per record."""
    if grid.table is not None and grid.table.shape[0] != n_records:
        raise SweepError(f"members: a table per record needs one row per record "
                         f"({n_records}), got {grid.table.shape[0]}")


def _column(name: str, values, shape: tuple) -> np.ndarray:
    """One numeric column, (K,) or (R, K) matching the laws' (K,) or (R, K)."""
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise SweepError(f"members: {name} must be numbers, got {values!r}") from None
    try:
        np.broadcast_shapes(shape, array.shape)
    except ValueError:
        raise SweepError(f"members: {name} has shape {array.shape}, the laws {shape}") from None
    if array.ndim not in (1, 2) or array.shape[-1] != shape[-1]:
        raise SweepError(f"members: {name} must be (K,) or (R, K) with K = {shape[-1]}, "
                         f"got shape {array.shape}")
    return array


def _fill(rows: np.ndarray, where: np.ndarray, law: str) -> None:
    """Check the members of one law and give the parameters it takes their defaults."""
    if law == NO_WALL:
        declared = {}
    elif law in LAWS:
        declared = LAWS[law].PARAMETERS.swept()
    else:
        raise SweepError(f"members: unknown law {law!r}; choose one of "
                         f"{(NO_WALL, *LAWS)}")
    numeric = {} if law == NO_WALL else LAWS[law].PARAMETERS.numeric
    for name in LISTED_PARAMS:  # left NaN where not given: the law's default (contact_for)
        values = rows[name][where]
        given = ~np.isnan(values)
        if np.any(given) and name not in numeric:
            raise SweepError(f"members: {name} does not apply to the {law!r} members "
                             f"(NaN there)")
        if np.any(given):
            checked_values(numeric[name], values[given], name)
    for name in PARAMS:
        values = rows[name][where]
        given = ~np.isnan(values)
        if name not in declared:
            if np.any(given):
                raise SweepError(f"members: {name} does not apply to the {law!r} members "
                                 f"(NaN there)")
            continue
        param = declared[name]
        if not np.all(given) and param.required:
            raise SweepError(f"members: {name} is required for the {law!r} members "
                             f"({param.units})")
        values = np.where(given, values, param.default)
        plausible(name, param, checked_values(param, values, name))
        column = rows[name]
        column[where] = values
    if law != NO_WALL:
        fits_the_wall(law, {name: rows[name][where] for name in (*declared, *LISTED_PARAMS)})
    plausible("m_eff", M_EFF, checked_values(M_EFF, rows["m_eff"][where], "m_eff"))


def _excitation(rows: np.ndarray, plan: bool, intensity: bool) -> None:
    """The members' level, angle and mu_wall: checked, defaults where the run needs them."""
    for name, param in EXCITATION_PARAMETERS.items():
        values = rows[name]
        given = ~np.isnan(values)
        try:
            if not excitation_carried(name, bool(np.any(given)), plan=plan,
                                      intensity=intensity):
                continue
        except SweepError as err:
            raise SweepError(f"members: {err}") from None
        values = np.where(given, values, param.default)
        plausible(name, param, checked_values(param, values, name))
        rows[name] = values
