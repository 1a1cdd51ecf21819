"""Orthogonal parameter grids: validation against the laws' declarations, and flattening into
engine members.

A sweep runs every combination of the swept parameters for every record. A parameter given as
a sequence is swept and becomes a dimension of the archive; a scalar is held fixed and becomes
a scalar coordinate. Which parameters a law takes, in which unit, with which default and valid
range, is declared once in the law's module (`engine.impact.LAWS[law].PARAMETERS`; each
parameter's `sweep` name says which of the sweep's parameters it is). In particular the
sweep's `wall_k` is, per law: the bumpers' k_w behind the crushed rubber (N/m, Eq. 14), the
linear wall's k (N/m, Eq. 1), Jankowski's beta (N/m^1.5), Hertzdamp's k (N/m^1.5).

Every member of a sweep is one element of a structured array of `MEMBER_DTYPE` (law name, then
the sweep parameters in SI units and m_eff; NaN where the law does not use a parameter), the
same members for every record; the engine's Contact is built from them (`contact_for`), so a
member fully describes its wall and is what resumable runs key on.

Blocks of members, each run for every record:
- "" (main): the chosen impact law over the full grid, C-order over the swept dimensions;
- "baseline_": the paper's bare wall without bumpers, the linear law at its declared defaults
  (k = 2500 kN/mm, COR 0.5, SPEC decision) at the full gap, once per gap;
- "unconstrained_": no wall at all, once per record.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

import engine
from engine.impact import LAWS, M_EFF, NO_WALL

from .errors import SweepError

IMPACT_LAWS = ("bumper", *(law for law in LAWS if law != "bumper"))
"""The wall laws a sweep can run, the default (the paper's bumpers) first."""
PARAMS = tuple(dict.fromkeys(name for law in IMPACT_LAWS
                             for name in LAWS[law].PARAMETERS.swept()))
"""The sweep's parameters: every law's declared `sweep` names, in declaration order, the
default law's first (gap, thickness, cavity, strain, n_bumpers, wall_k, cor). Also the
archive's dimension order: record first, then the swept parameters in this order."""


def declarations(name: str) -> dict:
    """Law -> its declaration (engine.impact.parameters.Parameter) of sweep parameter `name`,
    for every law that takes it, IMPACT_LAWS order."""
    return {law: LAWS[law].PARAMETERS.swept()[name] for law in IMPACT_LAWS
            if name in LAWS[law].PARAMETERS.swept()}


# Lengths of the sweep (m) and the largest plausible one: seismic gaps and bumpers are tens of
# cm; a value above 2 m is almost surely centimetres given as metres.
LENGTHS = tuple(name for name in PARAMS
                if all(p.units == "m" for p in declarations(name).values()))
CHECK_SLICE = 65_536  # members checked at once by check_dt
PLAUSIBLE_LENGTH = 2.0

MEMBER_DTYPE = np.dtype([("law", "U16"), *((name, "f8") for name in (*PARAMS, "m_eff"))])
"""One member: its law's name, the sweep parameters (SI; NaN: unused by the law), m_eff kg."""

# The paper's bare wall, the reference of the amplification ratios (SPEC section 2 decision).
BASELINE_LAW = "linear"
BASELINE = {sweep: p.default for sweep, p in LAWS[BASELINE_LAW].PARAMETERS.swept().items()
            if sweep != "gap"}
"""Sweep parameters of the bare wall: the linear law's declared defaults (wall_k N/m, cor)."""


@dataclass(frozen=True)
class Block:
    """A family of members run for every record.

    prefix: name prefix of its archive variables; dims: its swept dimensions; shape: their
    lengths; members: (prod(shape),) of MEMBER_DTYPE, C-order over dims.
    """

    prefix: str
    dims: tuple[str, ...]
    shape: tuple[int, ...]
    members: np.ndarray

    @property
    def size(self) -> int:
        return self.members.size


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

    @functools.cached_property
    def members(self) -> np.ndarray:
        """(M,) MEMBER_DTYPE: every member run per record, the blocks one after the other."""
        return np.concatenate([b.members for b in self.blocks])

    @property
    def n_members(self) -> int:
        """Simulations per record."""
        return sum(b.size for b in self.blocks)

    def block(self, prefix: str) -> Block | None:
        return next((b for b in self.blocks if b.prefix == prefix), None)


def swept_parameter(law: str, name: str):
    """The declaration (engine.impact.parameters.Parameter) behind sweep parameter `name`."""
    return LAWS[law].PARAMETERS.swept()[name]


def make_grid(gap=None, *, impact: str = "bumper", m_eff: float | None = None,
              baseline: bool = False, unconstrained: bool = False, **parameters) -> Grid:
    """Validate the parameters and build the member blocks (see module docstring).

    gap and the other sweep parameters (PARAMS: thickness, cavity, strain, n_bumpers, wall_k,
    cor), by name: each a scalar (fixed) or a 1-D sequence (swept); None takes the law's
    declared default. SI units: gap, thickness, cavity m; strain, n_bumpers, cor
    dimensionless; wall_k as the module docstring says per law; m_eff kg (None: the declared
    default). gap=None with unconstrained=True builds only the no-wall block. Raises
    SweepError naming the parameter (an unknown name too).
    """
    given = sweep_parameters({"gap": gap, **parameters})
    if impact not in IMPACT_LAWS:
        raise SweepError(f"impact: unknown impact law {impact!r}; choose one of {IMPACT_LAWS}")
    m_eff = M_EFF.default if m_eff is None else _scalar("m_eff", m_eff)
    _checked(M_EFF, np.asarray(m_eff), "m_eff")
    if gap is None:
        if not unconstrained or any(given[p] is not None for p in PARAMS) or baseline:
            raise SweepError("gap is required (m); only an unconstrained-only run may omit it")
        blocks = (_members_block("unconstrained_", NO_WALL, {}, m_eff),)
        return Grid(impact=NO_WALL, coords={}, fixed={}, blocks=blocks, m_eff=m_eff)

    declared = LAWS[impact].PARAMETERS.swept()
    values: dict[str, np.ndarray] = {}
    swept: list[str] = []
    for name in PARAMS:
        value = given[name]
        if name not in declared:
            if value is not None:
                takes = [law for law in IMPACT_LAWS if name in LAWS[law].PARAMETERS.swept()]
                raise SweepError(f"{name} applies to impact={' or '.join(map(repr, takes))} "
                                 f"only, not {impact!r}")
            continue
        param = declared[name]
        if value is None:
            if param.required:
                raise SweepError(f"{name} is required with impact={impact!r} ({param.units})")
            value = param.default
        array, is_swept = _values(name, value)
        values[name] = _plausible(name, _checked(param, array, name))
        if is_swept:
            swept.append(name)
    if baseline and impact != "bumper":
        raise SweepError(f"baseline compares bumpers with the bare wall: it needs "
                         f"impact='bumper', not {impact!r}")

    dims = tuple(swept)
    shape = tuple(values[d].size for d in dims)
    mesh = np.meshgrid(*values.values(), indexing="ij")
    blocks = [_members_block("", impact, dict(zip(values, (m.ravel() for m in mesh),
                                                      strict=True)), m_eff, dims, shape)]
    if baseline:
        gaps = values["gap"]
        gap_dims = ("gap",) if "gap" in dims else ()
        blocks.append(_members_block("baseline_", BASELINE_LAW, {"gap": gaps, **BASELINE},
                                     m_eff, gap_dims, (gaps.size,) if gap_dims else ()))
    if unconstrained:
        blocks.append(_members_block("unconstrained_", NO_WALL, {}, m_eff))
    coords = {d: values[d] for d in dims}
    fixed = {p: values[p].item() for p in values if p not in dims}
    return Grid(impact=impact, coords=coords, fixed=fixed, blocks=tuple(blocks), m_eff=m_eff)


def sweep_parameters(given: dict) -> dict:
    """Every sweep parameter (PARAMS order) -> its given value or None; SweepError for a name
    that is none of them."""
    unknown = [name for name in given if name not in PARAMS]
    if unknown:
        raise SweepError(f"{unknown[0]}: no such sweep parameter; the parameters are "
                         f"{', '.join(PARAMS)}")
    return {name: given.get(name) for name in PARAMS}


def baseline_text() -> str:
    """The bare wall's parameters as text: 'k = 2.5e+09 N m-1, cor = 0.5'."""
    return ", ".join(swept_parameter(BASELINE_LAW, name).value_text(value)
                     for name, value in BASELINE.items())


def _members_block(prefix: str, law: str, columns: dict, m_eff: float, dims=(),
                   shape=()) -> Block:
    size = math.prod(shape)
    members = np.zeros(size, dtype=MEMBER_DTYPE)
    for name in PARAMS:
        members[name] = columns.get(name, np.nan)
    members["law"] = law
    members["m_eff"] = m_eff
    return Block(prefix, tuple(dims), tuple(shape), members)


def _plausible(name: str, array: np.ndarray) -> np.ndarray:
    """Refuse lengths no moat or bumper has: most likely centimetres given as metres."""
    if name in LENGTHS and np.any(array > PLAUSIBLE_LENGTH):
        worst = float(array.max())
        raise SweepError(f"{name} {worst:g} m is implausible (> {PLAUSIBLE_LENGTH:g} m): give "
                         f"metres (e.g. {worst / 100:g} for {worst:g} cm), or "
                         f"--{name.replace('_', '-')}-cm {worst:g} on the command line")
    return array


def _checked(param, array: np.ndarray, name: str) -> np.ndarray:
    """The declaration's range check, in the sweep's vocabulary."""
    try:
        return param.check(array, name=name)
    except engine.EngineError as err:
        raise SweepError(str(err)) from None


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


def contact_for(members: np.ndarray) -> engine.Contact:
    """The engine Contact of (B,) MEMBER_DTYPE members, in their order."""
    parts, where = [], []
    for law in np.unique(members["law"]):
        idx = np.flatnonzero(members["law"] == law)
        rows = members[idx]
        if law == NO_WALL:
            parts.append(engine.Contact.none(idx.size))
        else:
            params = {p.name: rows[sweep] for sweep, p in LAWS[law].PARAMETERS.swept().items()}
            parts.append(engine.Contact.of(str(law), m_eff=rows["m_eff"], **params))
        where.append(idx)
    contact = engine.Contact.concat(parts)
    # Back to member order: part members sit in the order of the concatenated indices.
    return contact[np.argsort(np.concatenate(where), kind="stable")]


def check_dt(grid: Grid, dt: float, building: engine.Building) -> float:
    """Refuse a step at or above the engine's stability limit for any member (s); the
    engine's own checks of every member's parameters run here too, before any compute."""
    dt = _scalar("dt", dt)
    if not (dt > 0 and math.isfinite(dt)):
        raise SweepError(f"dt must be positive (s), got {dt}")
    members = grid.members
    worst, limit = 0, math.inf
    # In slices: a million members' contacts and operators at once would take gigabytes.
    for start in range(0, members.size, CHECK_SLICE):
        part = members[start:start + CHECK_SLICE]
        try:
            limits = engine.stable_dt(contact_for(part), building)
        except engine.EngineError as err:
            raise SweepError(str(err)) from err
        i = int(np.argmin(limits))
        if limits[i] < limit:
            worst, limit = start + i, float(limits[i])
    if dt >= limit:
        raise SweepError(f"dt = {dt:g} s is unstable: the stability limit is "
                         f"{limit:.4g} s for member {describe_member(members[worst])}")
    return dt


def describe_member(member) -> str:
    """One member's parameters as text, e.g. 'bumper(gap=0.2, thickness=0.05, ...)'."""
    params = ", ".join(f"{name}={member[name]:g}" for name in (*PARAMS, "m_eff")
                       if not np.isnan(member[name]))
    return f"{member['law']}({params})"
