"""What a member of a sweep carries: one declaration, one row per number (COLUMNS: its name,
what it belongs to, its declaration where one holds for every member), from which the
parameter names a sweep takes (the wall's, the isolator's, the excitation's), the archive's
dimension order and the member record (MEMBER_DTYPE) are read; and the excitation's rule,
which parameters excite a member and when they are carried, for grids and listed tables
alike.

Which parameters a law takes, in which unit, with which default and valid range, is declared
once in the law's module (engine.impact.LAWS[law].PARAMETERS, the isolator laws' alike; each
parameter's `sweep` name says which of the sweep's parameters it is): the rows of the wall
and the isolator are read from there.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.impact import LAWS, M_EFF
from engine.isolators import LAWS as ISOLATOR_LAWS
from engine.parameters import Parameter
from engine.plan import PLAN_PARAMETERS
from engine.torsion_fields import ACCIDENTAL_ECCENTRICITY

from .errors import SweepError

IMPACT_LAWS = ("bumper", *(law for law in LAWS if law != "bumper"))
"""The wall laws a sweep can run, the default (the paper's bumpers) first."""

LEVEL = Parameter("level", "1", "intensity level: the factor multiplying every record's "
                  "ground acceleration (times the record's own factor when the sweep is given "
                  "factors, e.g. a code suite's MCE_R factors)", 1.0, "(0, inf)",
                  sweep="level", plausible="(0, 50]")
"""A member's intensity (engine.simulate's scale, divided by its record's factor): swept like
the angle, the baseline and unconstrained blocks repeated per level. Members carry it only
when the sweep is given levels or record factors (NaN otherwise: the record as it is)."""


@dataclass(frozen=True)
class Column:
    """One number a member carries (a field of MEMBER_DTYPE, SI units; NaN: not set).

    name: the field's name (a sweep parameter's name, for those a sweep takes); part: what it
    belongs to, one of PARTS; declaration: its engine.parameters.Parameter where one
    declaration holds for every member (the excitation's, m_eff), None where it is each law's
    own (a wall's parameter: `declarations(name)` gives them).
    """

    name: str
    part: str
    declaration: Parameter | None = None


PARTS = {
    "wall": "the wall's sweep parameters, every impact law's declared `sweep` names in "
            "declaration order, the default law's first (gap, thickness, cavity, strain, "
            "n_bumpers, wall_k, cor); NaN where the member's law does not use one",
    "mass": "the effective impact mass m_eff, kg",
    "isolator": "the building's isolator parameters a sweep can vary, every isolator law's "
                "declared `sweep` names (k1, k2, fy_ratio, radius, mu_slow, mu_fast, rate, "
                "yield_disp, L1, L2, L3, d1, d2, d3, mu1, mu2, mu3), replacing the building's "
                "own (NaN: the building's)",
    "plan": "the parameters of runs in plan only: the record pair's incidence angle "
            "(degrees) and the slab-wall friction mu_wall (engine.plan.PLAN_PARAMETERS; NaN: "
            "a planar run)",
    "level": "the intensity level (LEVEL; NaN: the record as it is)",
    "listed": "the wall laws' parameters a grid keeps at their defaults and a table of "
              "listed members (pipeline.listed) may set, by their names in the laws (area, "
              "k_r, n, alpha: a bumper of its own area, say, in a design search; NaN: the "
              "law's default)",
    "torsion": "the parameters of a building that twists (its plan_size; runs in plan): its "
               "accidental eccentricity, a fraction of the plan (engine.torsion.shifted; NaN: "
               "the building's own)",
}
"""What a member's numbers belong to, in the order a member stores them."""
EXCITATION = ("level", "plan", "torsion")
"""The parts that excite a member beside its record, in the archive's dimension order: the
intensity level (any run), the incidence angle and the wall friction (runs in plan), the
accidental eccentricity (a building that twists)."""

COLUMNS = (
    *(Column(name, "wall") for name in dict.fromkeys(
        name for law in IMPACT_LAWS for name in LAWS[law].PARAMETERS.swept())),
    Column("m_eff", "mass", M_EFF),
    *(Column(name, "isolator") for name in dict.fromkeys(
        name for law in ISOLATOR_LAWS.values() for name in law.PARAMETERS.swept())),
    *(Column(name, "plan", param) for name, param in PLAN_PARAMETERS.items()),
    Column("level", "level", LEVEL),
    *(Column(name, "listed") for name in dict.fromkeys(
        p.name for law in IMPACT_LAWS for p in LAWS[law].PARAMETERS.numeric.values()
        if p.sweep is None and p.name != "m_eff" and isinstance(p.default, float))),
    Column(ACCIDENTAL_ECCENTRICITY.sweep, "torsion", ACCIDENTAL_ECCENTRICITY),
)
"""Every number a member carries, one row each, in the order a member stores them (after its
law's name): the one declaration the names below and MEMBER_DTYPE are read from."""


def names(*parts: str) -> tuple[str, ...]:
    """The names of the COLUMNS of `parts` (PARTS keys), part by part in the order given."""
    unknown = [part for part in parts if part not in PARTS]
    if unknown:
        raise KeyError(f"no such part of a member: {unknown[0]!r}; the parts are {tuple(PARTS)}")
    return tuple(c.name for part in parts for c in COLUMNS if c.part == part)


PARAMS = names("wall")
"""The sweep's wall parameters (PARTS["wall"]); also the archive's dimension order of the
wall's swept parameters."""
ISOLATOR_PARAMS = names("isolator")
"""The building's isolator parameters a sweep can vary (PARTS["isolator"]). Each applies when
the building's isolator is of a law that declares it, and replaces the building's own value;
in the archive they follow the wall's parameters."""
assert not set(ISOLATOR_PARAMS) & set(PARAMS), "isolator and wall parameters share a name"
PLAN_PARAMS = names("plan")
"""The parameters of runs in plan only (PARTS["plan"])."""
TORSION_PARAMS = names("torsion")
"""The parameters of a building that twists (PARTS["torsion"])."""
EXCITATION_PARAMETERS = {c.name: c.declaration for part in EXCITATION for c in COLUMNS
                         if c.part == part}
"""What excites a member beside its record, by sweep name -> its declaration (EXCITATION)."""
EXCITATION_PARAMS = names(*EXCITATION)
DIMENSIONS = names(*EXCITATION, "wall", "isolator")
"""Every sweep parameter, in the archive's dimension order (after record): the excitation's,
the wall's, the isolator's."""
LISTED_PARAMS = names("listed")
"""The wall laws' parameters a listed table may set (PARTS["listed"])."""


def declarations(name: str) -> dict:
    """Law -> its declaration (engine.parameters.Parameter) of sweep parameter `name`, for
    every law that takes it: the impact laws (IMPACT_LAWS order) for a wall parameter, the
    isolator laws for an isolator parameter; {"plan": its declaration} for a parameter of runs
    in plan (angle, mu_wall); {"excitation": its declaration} for the level."""
    if name in EXCITATION_PARAMS:
        return {"plan" if name in PLAN_PARAMS else "excitation": EXCITATION_PARAMETERS[name]}
    laws = ISOLATOR_LAWS if name in ISOLATOR_PARAMS else {law: LAWS[law] for law in IMPACT_LAWS}
    return {law: module.PARAMETERS.swept()[name] for law, module in laws.items()
            if name in module.PARAMETERS.swept()}


def excitation_carried(name: str, given: bool, *, plan: bool, intensity: bool) -> bool:
    """The excitation's rule, for grids and listed tables alike: whether members carry the
    excitation parameter `name` (EXCITATION_PARAMS), its default where not given. A parameter
    of runs in plan (or of a building that twists) is refused by a planar run (SweepError) and
    left out of it; in plan the angle and wall friction are always carried; the level when
    given or when the records have intensity factors (`intensity`); the eccentricity when
    given (else the building's own)."""
    if name in (*PLAN_PARAMS, *TORSION_PARAMS) and not plan:
        if given:
            raise SweepError(f"{name} applies to runs in plan, under record pairs (moat="
                             "'rectangular' or 'circular')")
        return False
    return given or not (name == "level" and not intensity or name in TORSION_PARAMS)



MEMBER_DTYPE = np.dtype([("law", "U16"), *((c.name, "f8") for c in COLUMNS)])
"""One member: its wall law's name, then every number of COLUMNS (f8, SI; NaN: not set, see
PARTS for what each part's NaN means)."""
