"""The isolation system a designer would give a building at a site: triple friction pendulums
(pipeline.motions.tfp_design) or lead-rubber bearings (pipeline.motions.lrb_design) designed
for a target effective period T_M (DESIGNS), their D_M and D_TM the code's at the bounds
(pipeline.motions.bounds: ASCE 7-22 sections 17.2.8.4 and 17.5.3), the bearing's restrainers or
capacity set beyond the lower bound's D_TM, the bound that governs displacements (section
17.2.8.5; the clause numbers as the issue tracker and SPEC cite them, not checked against the
2022 text).

The design and the code's displacements depend on each other: the bearing is designed at
nominal properties for T_M at the nominal D_M, and its stiffening or capacity from
(1 + margin) times the lower bound's D_TM, while D_M and D_TM follow from the bearing's own
effective stiffness and damping at each bound. `designed_isolation` iterates the two to a
fixed point. Pure functions; SI units.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from engine.units import G

from .bounds import PropertyFactors, design_basis
from .lrb_design import CAPACITY_MARGIN, design_lead_rubber
from .target import TORSION_FACTOR, damping_coefficient
from .tfp_design import STIFFENING_MARGIN, design_triple_friction_pendulum


@dataclass(frozen=True)
class IsolatorDesign:
    """A kind of isolator designed for a target period: what it is called, the margin beyond
    D_TM its default design leaves, and design(target_period s, D_M m, D_TM m, weight N,
    margin) -> a design with .isolator() and .describe()."""

    title: str
    margin: float
    design: object


DESIGNS = {
    "designed-tfp": IsolatorDesign(
        "triple friction pendulums", STIFFENING_MARGIN,
        lambda t, d_m, d_tm, weight, margin: design_triple_friction_pendulum(
            t, d_m, d_tm, margin=margin)),
    "designed-lrb": IsolatorDesign(
        "lead-rubber bearings", CAPACITY_MARGIN,
        lambda t, d_m, d_tm, weight, margin: design_lead_rubber(t, d_m, d_tm, weight,
                                                                margin=margin)),
}
"""The isolators a study can design for the site (--isolators), by name."""
DEFAULT_DESIGN = "designed-tfp"
TARGET_PERIOD = 3.0
"""s: the default target T_M at nominal properties: a stated choice within the 2.5-4 s of the
peers' triple friction pendulum buildings (Pham's open database; Kitayama & Constantinou 2018),
the long period US practice gives a TFP-isolated building at a high-seismicity site."""
ROUNDS = 20
"""At most this many rounds of design and code displacements."""
TOLERANCE = 1e-6
"""The relative change of D_M and D_TM between rounds at which the design is taken as settled."""
FIRST_DAMPING = 0.15
"""The effective damping (ratio of critical) the first round's D_M assumes: a typical
triple friction pendulum's at D_M (the rounds then replace it with the bearing's own)."""


@dataclass(frozen=True)
class DesignedIsolation:
    """A building on a designed isolation system: the design (at nominal properties:
    tfp_design.TripleFrictionPendulumDesign, lrb_design.LeadRubberDesign), the building on it
    (engine.Building), the design basis (bounds.DesignBasis) the design was settled with, the
    target T_M (s), the rounds it took, and what the isolators are (DESIGNS' title)."""

    design: object
    building: object
    basis: object
    target_period: float
    rounds: int
    title: str = DESIGNS[DEFAULT_DESIGN].title

    def describe(self) -> str:
        """One line: the bearing and the code's displacements at the lower bound."""
        lower = self.basis.designs["lower"]
        return (f"{self.title} designed for T_M {self.target_period:g} s "
                f"(nominal): {self.design.describe()}; lower bound T_M {lower.t_m:.3g} s, "
                f"D_M {100 * lower.d_m:.3g} cm, D_TM {100 * lower.d_tm:.3g} cm")


def designed_isolation(s_m1: float, building, target_period: float = TARGET_PERIOD,
                       factors: PropertyFactors | None = None, *, kind: str = DEFAULT_DESIGN,
                       margin: float | None = None,
                       torsion_factor: float = TORSION_FACTOR) -> DesignedIsolation:
    """`building` (engine.Building: its masses and stories; its isolator replaced) on the
    isolators DESIGNS[kind] designed at the site of S_M1 = s_m1 g for the nominal effective
    period target_period (s) at the nominal D_M, their stiffening (a triple friction
    pendulum's regime IV) or capacity (a lead-rubber bearing's) from (1 + margin) times the
    lower bound's D_TM (default the design's own margin; factors: the bounds'
    PropertyFactors; torsion_factor: D_TM / D_M, section 17.5.3.3's lower bound), the two
    settled by rounds (the module docstring). ValueError, in one line, for an unknown kind,
    where the design cannot be met (the design's) or does not settle."""
    if kind not in DESIGNS:
        raise ValueError(f"an isolator design is one of {', '.join(DESIGNS)}, got {kind!r}")
    chosen = DESIGNS[kind]
    margin = chosen.margin if margin is None else margin
    weight = building.g * building.total_mass
    d_m = G * s_m1 * target_period / (4.0 * math.pi**2 * float(damping_coefficient(FIRST_DAMPING)))
    d_tm = torsion_factor * d_m
    for rounds in range(1, ROUNDS + 1):
        design = chosen.design(target_period, d_m, d_tm, weight, margin)
        on_it = dataclasses.replace(building, isolator=design.isolator())
        basis = design_basis(s_m1, on_it, "lower", factors, torsion_factor=torsion_factor)
        new_d_m, new_d_tm = basis.designs["nominal"].d_m, basis.designs["lower"].d_tm
        settled = abs(new_d_m - d_m) <= TOLERANCE * d_m and \
            abs(new_d_tm - d_tm) <= TOLERANCE * d_tm
        d_m, d_tm = new_d_m, max(new_d_tm, new_d_m)
        if settled:
            return DesignedIsolation(design, on_it, basis, float(target_period), rounds,
                                     chosen.title)
    raise ValueError(f"the {chosen.title} for T_M {target_period:g} s did not settle "
                     f"in {ROUNDS} rounds (D_M {d_m:.4g} m, D_TM {d_tm:.4g} m): target another "
                     "period")
