"""Orthogonal parameter grids: validation, and flattening into engine members; the checks of
the other sweep inputs (dt, records, output path, counts) live here too, so that every bad
input fails before any compute.

A sweep runs every combination of the swept parameters for every record. A parameter given as
a sequence is swept and becomes a dimension of the archive; a scalar is held fixed and becomes
a scalar coordinate. Every member of a sweep is one row of a (M, 8) float table
(`MEMBER_COLUMNS`), the same table for every record; the engine's Contact is built from rows
(`contact_for`), so a row fully describes a member's wall and is what resumable runs key on.

Blocks of members, each run for every record:
- "" (main): the chosen impact law over the full grid, C-order over the swept dimensions;
- "baseline_": the paper's bare wall without bumpers (linear viscoelastic, k = 2500 kN/mm,
  COR 0.5, SPEC decision) at the full gap, once per gap;
- "unconstrained_": no wall at all, once per record.

How the sweep parameters map onto each law (SI units; thickness, strain and n_bumpers apply to
bumpers only and are refused for the other laws):

- bumper (default): gap is the clearance before bumpers (the engine uses gap - thickness),
  wall_k is k_w, the wall behind the crushed rubber (N/m, Eq. 14), cor is the bumper COR
  (Eq. 9). Defaults: thickness 0.05 m, strain 0.8, 4 bumpers, wall_k 1.5e9 N/m, cor 0.45.
- linear: wall_k is k (N/m, Eq. 1-3). Defaults: wall_k 2.5e9 N/m, cor 0.5.
- jankowski: wall_k is beta (N/m^1.5), required. Default cor 0.5.
- hertzdamp: wall_k is k (N/m^1.5, exponent 1.5), required. Default cor 0.5.
"""
from __future__ import annotations

import math
import operator
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import engine


class SweepError(ValueError):
    """Invalid sweep input; the message names the offending parameter."""


MEMBER_COLUMNS = ("law", "gap", "thickness", "strain", "n_bumpers", "wall_k", "cor", "m_eff")
_COL = {name: i for i, name in enumerate(MEMBER_COLUMNS)}
LAW_CODES = {"none": 0, "linear": 1, "jankowski": 2, "hertzdamp": 3, "bumper": 4}
LAW_NAMES = {code: name for name, code in LAW_CODES.items()}
IMPACT_LAWS = ("bumper", "linear", "jankowski", "hertzdamp")

# Dimension order of the archive: record first, then the swept parameters in this order.
PARAMS = ("gap", "thickness", "strain", "n_bumpers", "wall_k", "cor")

# Per law: default of each parameter it uses (None: the user must give it).
LAW_DEFAULTS: dict[str, dict[str, Any]] = {
    "bumper": {"thickness": 0.05, "strain": 0.8, "n_bumpers": 4, "wall_k": 1.5e9, "cor": 0.45},
    "linear": {"wall_k": 2.5e9, "cor": 0.5},
    "jankowski": {"wall_k": None, "cor": 0.5},
    "hertzdamp": {"wall_k": None, "cor": 0.5},
}
WALL_K_MEANING = {
    "bumper": ("N/m", "moat wall stiffness k_w past the crushed bumper (Eq. 14)"),
    "linear": ("N/m", "moat wall contact stiffness k (Eq. 1-3)"),
    "jankowski": ("N/m^1.5", "moat wall impact stiffness beta (Jankowski 2005)"),
    "hertzdamp": ("N/m^1.5", "moat wall Hertz stiffness k, exponent 1.5 (Hertzdamp)"),
}
HERTZDAMP_EXPONENT = 1.5

# The paper's bare wall, the reference of the amplification ratios (SPEC section 2 decision).
BASELINE_K = 2.5e9  # N/m (2500 kN/mm)
BASELINE_COR = 0.5
DEFAULT_M_EFF = 320e3  # kg: the base slab against an immovable wall (SPEC decision)


@dataclass(frozen=True)
class Block:
    """A family of members run for every record.

    prefix: name prefix of its archive variables; dims: its swept dimensions; shape: their
    lengths; table: (prod(shape), 8) member rows, C-order over dims.
    """

    prefix: str
    dims: tuple[str, ...]
    shape: tuple[int, ...]
    table: np.ndarray

    @property
    def size(self) -> int:
        return self.table.shape[0]


@dataclass(frozen=True)
class Grid:
    """A validated sweep: which parameters vary, which are fixed, and the member blocks.

    impact: the law of the main block; coords: swept parameter -> (n,) values, in PARAMS
    order; fixed: fixed parameter -> scalar; blocks: main first, then baseline and
    unconstrained when asked for; m_eff kg.
    """

    impact: str
    coords: dict[str, np.ndarray]
    fixed: dict[str, float]
    blocks: tuple[Block, ...]
    m_eff: float

    @property
    def table(self) -> np.ndarray:
        """(M, 8) rows of every member run per record: the blocks one after the other."""
        return np.concatenate([b.table for b in self.blocks])

    @property
    def n_members(self) -> int:
        """Simulations per record."""
        return sum(b.size for b in self.blocks)

    def block(self, prefix: str) -> Block | None:
        return next((b for b in self.blocks if b.prefix == prefix), None)


def make_grid(gap, thickness=None, strain=None, n_bumpers=None, wall_k=None, cor=None,
              impact: str = "bumper", m_eff: float = DEFAULT_M_EFF, baseline: bool = False,
              unconstrained: bool = False) -> Grid:
    """Validate the parameters and build the member blocks (see module docstring).

    Each parameter is a scalar (fixed) or a 1-D sequence (swept); None takes the law's default.
    gap, thickness m; strain, n_bumpers, cor dimensionless; wall_k N/m (N/m^1.5 for jankowski
    and hertzdamp); m_eff kg. gap=None with unconstrained=True builds only the no-wall block.
    Raises SweepError naming the parameter.
    """
    if impact not in IMPACT_LAWS:
        raise SweepError(f"impact: unknown impact law {impact!r}; choose one of {IMPACT_LAWS}")
    m_eff = _scalar("m_eff", m_eff)
    if not m_eff > 0:
        raise SweepError(f"m_eff must be positive (kg), got {m_eff}")
    given = {"gap": gap, "thickness": thickness, "strain": strain, "n_bumpers": n_bumpers,
             "wall_k": wall_k, "cor": cor}
    if gap is None:
        if not unconstrained or any(given[p] is not None for p in PARAMS) or baseline:
            raise SweepError("gap is required (m); only an unconstrained-only run may omit it")
        blocks = (_unconstrained_block(m_eff),)
        return Grid(impact="none", coords={}, fixed={}, blocks=blocks, m_eff=m_eff)

    defaults = LAW_DEFAULTS[impact]
    values: dict[str, np.ndarray] = {}
    swept: list[str] = []
    for name in PARAMS:
        value = given[name]
        if name != "gap" and name not in defaults:
            if value is not None:
                raise SweepError(f"{name} applies to impact='bumper' only, not {impact!r}")
            continue
        if value is None:
            value = defaults.get(name)
            if value is None:
                unit = WALL_K_MEANING[impact][0]
                raise SweepError(f"{name} is required with impact={impact!r} ({unit})")
        array, is_swept = _values(name, value)
        values[name] = array
        if is_swept:
            swept.append(name)
    _check_ranges(values)
    if baseline and impact != "bumper":
        raise SweepError(f"baseline compares bumpers with the bare wall: it needs "
                         f"impact='bumper', not {impact!r}")

    dims = tuple(swept)
    shape = tuple(values[d].size for d in dims)
    mesh = np.meshgrid(*(values[p] for p in values), indexing="ij")
    table = np.full((mesh[0].size, len(MEMBER_COLUMNS)), np.nan)
    table[:, _COL["law"]] = LAW_CODES[impact]
    table[:, _COL["m_eff"]] = m_eff
    for name, column in zip(values, mesh, strict=True):
        table[:, _COL[name]] = column.ravel()
    blocks = [Block("", dims, shape, table)]
    if baseline:
        gaps = values["gap"]
        base = np.full((gaps.size, len(MEMBER_COLUMNS)), np.nan)
        base[:, _COL["law"]] = LAW_CODES["linear"]
        base[:, _COL["gap"]] = gaps
        base[:, _COL["wall_k"]] = BASELINE_K
        base[:, _COL["cor"]] = BASELINE_COR
        base[:, _COL["m_eff"]] = m_eff
        gap_dims = ("gap",) if "gap" in dims else ()
        blocks.append(Block("baseline_", gap_dims, (gaps.size,) if gap_dims else (), base))
    if unconstrained:
        blocks.append(_unconstrained_block(m_eff))
    coords = {d: values[d] for d in dims}
    fixed = {p: values[p].item() for p in values if p not in dims}
    return Grid(impact=impact, coords=coords, fixed=fixed, blocks=tuple(blocks), m_eff=m_eff)


def _unconstrained_block(m_eff: float) -> Block:
    row = np.full((1, len(MEMBER_COLUMNS)), np.nan)
    row[0, _COL["law"]] = LAW_CODES["none"]
    row[0, _COL["m_eff"]] = m_eff
    return Block("unconstrained_", (), (), row)


def _scalar(name: str, value) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise SweepError(f"{name} must be a number, got {value!r}") from None


def _values(name: str, value) -> tuple[np.ndarray, bool]:
    """(n,) float values of one parameter, and whether it is swept (given as a sequence)."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SweepError(f"{name} must be a number or a sequence of numbers, "
                         f"got {value!r}") from None
    if array.ndim > 1:
        raise SweepError(f"{name} must be a scalar or a 1-D sequence, got shape {array.shape}")
    swept = array.ndim == 1
    array = np.atleast_1d(array)
    if array.size == 0:
        raise SweepError(f"{name} is empty")
    if not np.all(np.isfinite(array)):
        raise SweepError(f"{name} must be finite, got {array.tolist()}")
    if np.unique(array).size != array.size:
        raise SweepError(f"{name} has repeated values {array.tolist()}: a coordinate must be "
                         "unique")
    return array, swept


def _check_ranges(values: dict[str, np.ndarray]) -> None:
    def bad(name, mask, rule):
        if np.any(mask):
            raise SweepError(f"{name} must be {rule}, got {values[name][mask].tolist()}")

    gap = values["gap"]
    bad("gap", gap <= 0, "positive (m)")
    if "thickness" in values:
        t = values["thickness"]
        bad("thickness", t <= 0, "positive (m)")
        # Orthogonal grid: every thickness meets every gap.
        if t.max() >= gap.min():
            raise SweepError(f"thickness must be smaller than every gap: thickness {t.max():g} m "
                             f">= gap {gap.min():g} m leaves no clearance")
    if "strain" in values:
        bad("strain", (values["strain"] <= 0) | (values["strain"] > 1), "in (0, 1]")
    if "n_bumpers" in values:
        n = values["n_bumpers"]
        bad("n_bumpers", (n < 1) | (n != np.round(n)), "a whole number >= 1")
    bad("wall_k", values["wall_k"] <= 0, "positive")
    bad("cor", (values["cor"] <= 0) | (values["cor"] > 1), "in (0, 1]")


def contact_for(table: np.ndarray) -> engine.Contact:
    """The engine Contact of a (B, 8) member table, in row order."""
    table = np.asarray(table, dtype=float)
    codes = table[:, _COL["law"]].astype(int)
    parts, where = [], []
    for code in np.unique(codes):
        idx = np.flatnonzero(codes == code)
        parts.append(_law_contact(LAW_NAMES[int(code)], table[idx]))
        where.append(idx)
    contact = engine.Contact.concat(parts)
    # Back to row order: part members sit in the order of the concatenated indices.
    return contact[np.argsort(np.concatenate(where), kind="stable")]


def _law_contact(law: str, rows: np.ndarray) -> engine.Contact:
    col = {name: rows[:, i] for i, name in enumerate(MEMBER_COLUMNS)}
    if law == "none":
        return engine.Contact.none(len(rows))
    common = {"cor": col["cor"], "m_eff": col["m_eff"]}
    if law == "linear":
        return engine.Contact.linear(col["gap"], k=col["wall_k"], **common)
    if law == "jankowski":
        return engine.Contact.jankowski(col["gap"], beta=col["wall_k"], **common)
    if law == "hertzdamp":
        return engine.Contact.hertzdamp(col["gap"], k=col["wall_k"], n=HERTZDAMP_EXPONENT,
                                        **common)
    return engine.Contact.bumper(col["gap"], thickness=col["thickness"], strain=col["strain"],
                                 n_bumpers=col["n_bumpers"], k_w=col["wall_k"], **common)


def check_dt(grid: Grid, dt: float, building: engine.Building) -> float:
    """Refuse a step at or above the engine's stability limit for any member (s)."""
    dt = _scalar("dt", dt)
    if not (dt > 0 and math.isfinite(dt)):
        raise SweepError(f"dt must be positive (s), got {dt}")
    try:
        limits = engine.stable_dt(contact_for(grid.table), building)
    except engine.EngineError as err:
        raise SweepError(str(err)) from err
    worst = int(np.argmin(limits))
    if dt >= limits[worst]:
        raise SweepError(f"dt = {dt:g} s is unstable: the stability limit is "
                         f"{limits[worst]:.4g} s for member {describe_row(grid.table[worst])}")
    return dt


def describe_row(row: np.ndarray) -> str:
    """One member's parameters as text, e.g. for error messages."""
    law = LAW_NAMES[int(row[_COL["law"]])]
    params = ", ".join(f"{name}={row[i]:g}" for i, name in enumerate(MEMBER_COLUMNS)
                       if name != "law" and not np.isnan(row[i]))
    return f"{law}({params})"


def default_batch_size(n_members: int, n_records: int, workers: int,
                       max_batch: int = 512) -> int:
    """Default members per engine batch.

    A time step costs a fixed ~50 us plus ~0.2 us per member, so batches should be large; but
    a sweep should give every worker something to do, and no batch exceeds max_batch members
    (memory stays small: a few (B, 5, 10) arrays).
    """
    per_record = max(math.ceil(n_members / max_batch), math.ceil(max(workers, 1) / n_records))
    return max(1, min(max_batch, math.ceil(n_members / per_record)))


def resolve_records(records, records_dir=None) -> tuple[list, list[str]]:
    """Record objects and their coordinate names (a paper record is named by its key)."""
    from .records import RecordError, load_record

    if isinstance(records, (str, os.PathLike)) or hasattr(records, "accel"):
        records = [records]
    try:
        records = list(records)
    except TypeError:
        raise SweepError(f"records must be a name, path, Record or a list of them, "
                         f"got {records!r}") from None
    if not records:
        raise SweepError("records is empty")
    loaded = []
    for item in records:
        if hasattr(item, "accel") and hasattr(item, "dt"):
            loaded.append(item)
            continue
        try:
            loaded.append(load_record(item, records_dir))
        except RecordError as err:
            raise SweepError(f"records: {err}") from err
    names = [getattr(rec, "paper_key", None) or str(rec.name) for rec in loaded]
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise SweepError(f"records: each record must appear once, repeated {repeated}")
    return loaded, names


def check_count(name: str, value, minimum: int) -> int:
    try:
        count = operator.index(value)
    except TypeError:
        raise SweepError(f"{name} must be a whole number, got {value!r}") from None
    if count < minimum:
        raise SweepError(f"{name} must be >= {minimum}, got {count}")
    return count


def check_out(out) -> Path | None:
    """Refuse an output path that cannot be written, before any compute."""
    if out is None:
        return None
    out = Path(out)
    if out.is_dir():
        raise SweepError(f"out: {out} is a directory, not a file name")
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=out.parent):
            pass
    except OSError as err:
        raise SweepError(f"out: cannot write to {out.parent} ({err.strerror or err})") from None
    return out


def plain(value):
    """JSON-friendly copy of the arguments (numpy arrays and scalars to lists and floats)."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if hasattr(value, "tolist"):
        return value.tolist()
    return value
