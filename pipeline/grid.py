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
every number pipeline.members declares, one row each: the sweep parameters in SI units and
m_eff; NaN where the law does not use a parameter), the same members for every record; the
engine's Contact is built from them (`contact_for`), so a member fully describes its wall and
is what resumable runs key on.

The building's isolator parameters can be swept too (ISOLATOR_PARAMS, declared by the isolator
laws the same way: k1, k2, fy_ratio for the bilinear law; radius, mu_slow, mu_fast, rate,
yield_disp for the friction pendulum; L1, L2, L3, d1, d2, d3, mu1, mu2, mu3, yield_disp for the
triple friction pendulum). A member then carries the values that replace the
building's own (NaN: the building's), and `buildings_for` makes each member's engine Building.

Blocks of members, each run for every record:
- "" (main): the chosen impact law over the full grid, C-order over the swept dimensions;
- "baseline_": the paper's bare wall without bumpers, the linear law at its declared defaults
  (k = 2500 kN/mm, COR 0.5, SPEC decision) at the full gap, once per gap and isolator;
- "unconstrained_": no wall at all, once per record and isolator.
"""
from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass

import numpy as np

import engine
from engine.impact import LAWS, M_EFF, NO_WALL
from engine.isolators import LAWS as ISOLATOR_LAWS
from engine.torsion import shifted

from .checks import checked_values, fits_the_wall, plausible
from .errors import PlausibilityWarning, SweepError
from .members import (
    COLUMNS,
    DIMENSIONS,
    EXCITATION,
    EXCITATION_PARAMETERS,
    EXCITATION_PARAMS,
    IMPACT_LAWS,
    ISOLATOR_PARAMS,
    LISTED_PARAMS,
    MEMBER_DTYPE,
    PARAMS,
    TORSION_PARAMS,
    declarations,
    excitation_carried,
    names,
)

CHECK_SLICE = 65_536  # members checked at once by check_dt

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

    impact: the law of the main block; coords: swept parameter -> (n,) values, in DIMENSIONS
    order; fixed: fixed parameter -> scalar; blocks: main first, then baseline and
    unconstrained when asked for; m_eff kg; isolator: the law of the building's isolator,
    whose parameters in coords and fixed replace the building's. A grid of members listed
    one by one (pipeline.listed) has one block along `member`, `listed` its columns for the
    archive, and `table` (R, M) when each record runs members of its own; its impact names
    every law it runs, space-separated.
    """

    impact: str
    coords: dict[str, np.ndarray]
    fixed: dict[str, float]
    blocks: tuple[Block, ...]
    m_eff: float
    isolator: str = "bilinear"
    plan: bool = False
    listed: dict | None = None
    table: np.ndarray | None = None

    @functools.cached_property
    def members(self) -> np.ndarray:
        """(M,) MEMBER_DTYPE: every member run per record, the blocks one after the other
        (a grid whose records run members of their own: the first record's)."""
        if self.table is not None:
            return self.table[0]
        if len(self.blocks) == 1:  # not copied: a million members are 344 MB
            return self.blocks[0].members
        return np.concatenate([b.members for b in self.blocks])

    def members_of(self, record: int) -> np.ndarray:
        """(M,) MEMBER_DTYPE: the members record `record` runs."""
        return self.members if self.table is None else self.table[record]

    @property
    def every_member(self) -> np.ndarray:
        """MEMBER_DTYPE: every member of every record (each once when records share them)."""
        return self.members if self.table is None else self.table.ravel()

    @property
    def n_members(self) -> int:
        """Simulations per record."""
        return sum(b.size for b in self.blocks)

    def block(self, prefix: str) -> Block | None:
        return next((b for b in self.blocks if b.prefix == prefix), None)


def swept_parameter(law: str, name: str):
    """The declaration (engine.impact.parameters.Parameter) behind sweep parameter `name`."""
    return LAWS[law].PARAMETERS.swept()[name]


def make_grid(gap=None, *, impact: str = "bumper", isolator: str = "bilinear",
              m_eff: float | None = None, baseline: bool = False, unconstrained: bool = False,
              plan: bool = False, intensity: bool = False, **parameters) -> Grid:
    """Validate the parameters and build the member blocks (see module docstring).

    gap and the other wall parameters (PARAMS: thickness, cavity, strain, n_bumpers, wall_k,
    cor), by name: each a scalar (fixed) or a 1-D sequence (swept); None takes the law's
    declared default. SI units: gap, thickness, cavity m; strain, n_bumpers, cor
    dimensionless; wall_k as the module docstring says per law; m_eff kg (None: the declared
    default). isolator: the law of the building's isolator; its parameters (ISOLATOR_PARAMS
    it declares, SI) given here replace the building's, fixed or swept alike, None keeping the
    building's. plan: the members run in plan, under record pairs; angle (degrees, default 0)
    is then their incidence angle and mu_wall (default 0) the slab-wall friction, each fixed
    or swept, and the baseline and unconstrained blocks repeat per value. level (-, default
    1; any run) is the members' intensity, fixed or swept alike, its blocks repeated per value
    too; it is carried by the members when given or when `intensity` (the records have
    factors), else NaN (the records as they are). gap=None with
    unconstrained=True builds only the no-wall block. Raises SweepError naming the parameter
    (an unknown name too).
    """
    given = sweep_parameters({"gap": gap, **parameters})
    if impact not in IMPACT_LAWS:
        raise SweepError(f"impact: unknown impact law {impact!r}; choose one of {IMPACT_LAWS}")
    m_eff = M_EFF.default if m_eff is None else _scalar("m_eff", m_eff)
    plausible("m_eff", M_EFF, checked_values(M_EFF, np.asarray(m_eff), "m_eff"))
    iso_values, iso_swept = _isolator_values(isolator, given)
    # The excitation's parameters lead the isolator's: the level when given (or when the
    # records carry factors), the angle and friction in plan.
    excitation, excitation_swept = {}, []
    for name, param in EXCITATION_PARAMETERS.items():
        if not excitation_carried(name, given[name] is not None, plan=plan,
                                  intensity=intensity):
            continue
        array, is_swept = _values(name, param.default if given[name] is None
                                  else given[name])
        excitation[name] = plausible(name, param, checked_values(param, array, name))
        excitation_swept += [name] * is_swept
    iso_values, iso_swept = {**excitation, **iso_values}, excitation_swept + iso_swept
    if gap is None:
        if not unconstrained or any(given[p] is not None for p in PARAMS) or baseline:
            raise SweepError("gap is required (m); only an unconstrained-only run may omit it")
        blocks = (_members_block("unconstrained_", NO_WALL, iso_values, iso_swept, m_eff),)
        return Grid(NO_WALL, *_coords(iso_values, iso_swept), blocks, m_eff, isolator, plan)

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
        values[name] = plausible(name, param, checked_values(param, array, name))
        if is_swept:
            swept.append(name)
    fits_the_wall(impact, values)
    if baseline and impact != "bumper":
        raise SweepError(f"baseline compares bumpers with the bare wall: it needs "
                         f"impact='bumper', not {impact!r}")

    blocks = [_members_block("", impact, _excitation_first(values, iso_values),
                             [*swept, *iso_swept], m_eff)]
    if baseline:
        bare = {"gap": values["gap"], **{k: np.array([v]) for k, v in BASELINE.items()}}
        bare_swept = [name for name in swept if name == "gap"]  # its wall is fixed
        blocks.append(_members_block("baseline_", BASELINE_LAW,
                                     _excitation_first(bare, iso_values),
                                     [*bare_swept, *iso_swept], m_eff))
    if unconstrained:
        blocks.append(_members_block("unconstrained_", NO_WALL, iso_values, iso_swept, m_eff))
    return Grid(impact, *_coords({**values, **iso_values}, [*swept, *iso_swept]),
                tuple(blocks), m_eff, isolator, plan)


def _excitation_first(values: dict, extra: dict) -> dict:
    """A block's columns in DIMENSIONS order: the excitation's (level, angle, mu_wall), the
    wall's, the isolator's."""
    return {**{k: v for k, v in extra.items() if k in EXCITATION_PARAMS}, **values,
            **{k: v for k, v in extra.items() if k not in EXCITATION_PARAMS}}


def _isolator_values(isolator: str, given: dict) -> tuple[dict[str, np.ndarray], list[str]]:
    """The isolator parameters given ((n,) values each, ISOLATOR_PARAMS order) and which of
    them are swept; SweepError for a parameter the building's isolator law does not take."""
    if isolator not in ISOLATOR_LAWS:
        raise SweepError(f"isolator: unknown isolator law {isolator!r}; choose one of "
                         f"{tuple(ISOLATOR_LAWS)}")
    declared = ISOLATOR_LAWS[isolator].PARAMETERS.swept()
    values, swept = {}, []
    for name in ISOLATOR_PARAMS:
        if given[name] is None:
            continue
        if name not in declared:
            takes = " or ".join(repr(law) for law in declarations(name))
            raise SweepError(f"{name} is a parameter of the {takes} isolator; the building "
                             f"stands on a {isolator!r} isolator (its parameters: "
                             f"{', '.join(declared)})")
        array, is_swept = _values(name, given[name])
        param = declared[name]
        values[name] = plausible(name, param, checked_values(param, array, name),
                                 option=param.units == "N m-1")
        if is_swept:
            swept.append(name)
    return values, swept


def _coords(values: dict, swept: list[str]) -> tuple[dict, dict]:
    """(coords, fixed) of a grid: the swept values (DIMENSIONS order), the fixed scalars."""
    coords = {d: values[d] for d in DIMENSIONS if d in swept}
    fixed = {p: values[p].item() for p in values if p not in swept}
    return coords, fixed


def sweep_parameters(given: dict) -> dict:
    """Every sweep parameter (DIMENSIONS order) -> its given value or None; SweepError for a
    name that is none of them."""
    unknown = [name for name in given if name not in DIMENSIONS]
    if unknown:
        raise SweepError(f"{unknown[0]}: no such sweep parameter; the wall's are "
                         f"{', '.join(PARAMS)}, the isolator's {', '.join(ISOLATOR_PARAMS)}")
    return {name: given.get(name) for name in DIMENSIONS}


def baseline_text() -> str:
    """The bare wall's parameters as text: 'k = 2.5e+09 N m-1, cor = 0.5'."""
    return ", ".join(swept_parameter(BASELINE_LAW, name).value_text(value)
                     for name, value in BASELINE.items())


def _members_block(prefix: str, law: str, values: dict, swept, m_eff: float) -> Block:
    """Every combination of `values` (name -> (n,) array; fixed ones of length 1), C-order in
    the order given; the `swept` names are the block's dims."""
    mesh = np.meshgrid(*values.values(), indexing="ij")
    dims = tuple(name for name in values if name in swept)
    shape = tuple(values[d].size for d in dims)
    members = np.zeros(math.prod(shape), dtype=MEMBER_DTYPE)
    for column in COLUMNS:  # m_eff set below
        members[column.name] = np.nan
    for name, column in zip(values, mesh, strict=True):
        members[name] = column.ravel()
    members["law"] = law
    members["m_eff"] = m_eff
    return Block(prefix, dims, shape, members)


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
    laws = members["law"]
    if laws.size and np.all(laws == laws[0]):  # one law (a grid's block): no regrouping
        return _law_contact(str(laws[0]), members)
    parts, where = [], []
    for law in np.unique(laws):
        idx = np.flatnonzero(laws == law)
        parts.append(_law_contact(str(law), members[idx]))
        where.append(idx)
    contact = engine.Contact.concat(parts)
    # Back to member order: part members sit in the order of the concatenated indices.
    return contact[np.argsort(np.concatenate(where), kind="stable")]


def _law_contact(law: str, rows: np.ndarray) -> engine.Contact:
    """The engine Contact of (b,) MEMBER_DTYPE members all of impact law `law`."""
    if law == NO_WALL:
        return engine.Contact.none(rows.size)
    declared = LAWS[law].PARAMETERS
    params = {p.name: rows[sweep] for sweep, p in declared.swept().items()}
    for name in LISTED_PARAMS:  # set by listed members only: else the law's default
        if name in declared.numeric and not np.all(np.isnan(rows[name])):
            params[name] = np.where(np.isnan(rows[name]), declared.numeric[name].default,
                                    rows[name])
    return engine.Contact.of(law, m_eff=rows["m_eff"], **params)


def buildings_for(members: np.ndarray, building: engine.Building):
    """The engine building of (B,) MEMBER_DTYPE members: `building` itself when none of them
    replaces an isolator parameter or moves its mass (an accidental eccentricity), else a list
    of B Buildings (one object per distinct variant, so that the engine builds each one's
    operators once). EngineError for values the isolator law refuses together (e.g. k2 >= k1)
    and for an eccentricity given a building that does not twist."""
    names = [name for name in ISOLATOR_PARAMS if not np.all(np.isnan(members[name]))]
    moved = [name for name in TORSION_PARAMS if not np.all(np.isnan(members[name]))]
    if not names and not moved:
        return building
    own = building.isolation.values
    rows = np.stack([np.where(np.isnan(members[n]), own.get(n, np.nan), members[n])
                     for n in names] + [np.nan_to_num(members[n]) for n in moved], axis=1)
    distinct, which = np.unique(rows, axis=0, return_inverse=True)
    variants = []
    for row in distinct:
        # the row: the isolator's values, then the eccentricity (zip stops at the names)
        variant = building.with_isolator(**dict(zip(names, map(float, row), strict=False))) \
            if names else building
        variants.append(shifted(variant, row[-1]) if moved else variant)
    return [variants[i] for i in which.ravel()]


FINEST_DT = 1e-6
"""s: the finest step a sweep takes, 500 x finer than the converged one (engine.DEFAULT_DT;
a convergence study's finest is some tens of times finer): below it most likely a slip (a
step in ms or us given as s), a run of days."""


def check_dt(grid: Grid, dt: float, building: engine.Building) -> float:
    """Refuse a step at or above the engine's stability limit for any member (s); the
    engine's own checks of every member's parameters (its isolator's too) run here, before
    any compute."""
    dt = _scalar("dt", dt)
    if not (dt > 0 and math.isfinite(dt)):
        raise SweepError(f"dt must be positive (s), got {dt}")
    if dt < FINEST_DT:
        raise SweepError(f"dt = {dt:g} s is implausible (a 40 s record would take "
                         f"{40.0 / dt:.3g} steps): give a step of at least {FINEST_DT:g} s, "
                         f"{engine.DEFAULT_DT / FINEST_DT:g} x finer than the converged "
                         f"{engine.DEFAULT_DT:g} s")
    members = grid.every_member
    worst, limit = 0, math.inf
    # In slices: a million members' contacts and operators at once would take gigabytes.
    for start in range(0, members.size, CHECK_SLICE):
        part = members[start:start + CHECK_SLICE]
        try:
            limits = engine.stable_dt(contact_for(part), buildings_for(part, building))
        except engine.EngineError as err:
            raise SweepError(str(err)) from err
        i = int(np.argmin(limits))
        if limits[i] < limit:
            worst, limit = start + i, float(limits[i])
    if dt >= limit:
        raise SweepError(f"dt = {dt:g} s is unstable: the stability limit is "
                         f"{limit:.4g} s for member {describe_member(members[worst])}")
    if dt > engine.DEFAULT_DT * (1 + 1e-9):
        warnings.warn(PlausibilityWarning(
            f"dt = {dt:g} s is {dt / engine.DEFAULT_DT:.3g} x the converged step "
            f"{engine.DEFAULT_DT:g} s (halving that one moves no peak by 0.5%; "
            "tests/engine/test_scheme_convergence.py): peaks and verdicts may not have converged"),
            stacklevel=2)
    return dt


def describe_member(member) -> str:
    """One member's parameters as text, e.g. 'bumper(gap=0.2, thickness=0.05, ...)'."""
    params = ", ".join(f"{name}={member[name]:g}" for name in
                       names(*EXCITATION, "wall", "mass", "isolator", "listed")
                       if not np.isnan(member[name]))
    return f"{member['law']}({params})"
