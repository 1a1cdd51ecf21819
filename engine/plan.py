"""What a run in plan takes beyond a planar one, declared once: the moats, the incidence angle
of a record pair and the friction between slab and wall (engine.simulate with accel (N, 2);
the loops are loops/numpy_plan.py and loops/numba_plan.py, what they return
results.PLAN_PEAKS and PLAN_HISTORIES)."""
from __future__ import annotations

from dataclasses import dataclass

from .errors import EngineError
from .parameters import Parameter
from .results import WALLS

MOATS = tuple(WALLS)
"""The moat shapes: "rectangular" (walls normal to x and to y), "circular"."""

ANGLE = Parameter("angle", "degree", "incidence angle: the record pair rotated "
                  "counterclockwise, x towards y, before it excites the building", 0.0,
                  "[-360, 360]", sweep="angle")
"""A member's incidence angle (engine.simulate's angle; pipeline.sweep's angle)."""

MU_WALL = Parameter("mu_wall", "1", "Coulomb friction coefficient between the slab and the "
                    "moat wall (or its bumpers), along the wall", 0.0, "[0, 10]",
                    sweep="mu_wall", plausible="[0, 1.5]")
"""A member's slab-wall friction (engine.simulate's mu_wall; pipeline.sweep's mu_wall): while
the slab presses on a wall with normal force N it slides along it against mu_wall N, or
sticks (loops/numpy_plan.py: the implicit Coulomb solve)."""

PLAN_PARAMETERS = {p.sweep: p for p in (ANGLE, MU_WALL)}
"""The parameters of runs in plan only, by sweep name (pipeline.grid.PLAN_PARAMS)."""


@dataclass(frozen=True)
class Moat:
    """The moat of a run in plan (engine.simulate's moat): its shape and what stands on its
    walls.

    shape: "rectangular" (walls normal to x at +- the clear gap of simulate's contact, normal
    to y at +- that of contact_y; a corner loads both) or "circular" (one wall at the clear
    gap of `contact`, pushing along the radius); contact_y: None (the y walls as the x walls)
    or a Contact of B members, the y walls of a rectangular moat; mu_wall: None (0) or (B,)
    Coulomb friction coefficients between slab and wall (-), MU_WALL: a slab pressing on a
    wall with normal force N slides along it against mu_wall N or sticks; bumper_positions:
    None (a building that twists meets bare walls with its corners) or (along the x walls,
    along the y walls), the bumpers' positions in metres from the plan's centre (twisting
    model only), each carrying its share of the wall's law.
    """

    shape: str = "rectangular"
    contact_y: object = None
    mu_wall: object = None
    bumper_positions: object = None

    def __post_init__(self):
        if self.shape not in MOATS:
            raise EngineError(f"moat must be one of {MOATS}, got {self.shape!r}")

    @classmethod
    def of(cls, moat) -> Moat:
        """A Moat from engine.simulate's moat argument: a Moat, or a shape's name."""
        return moat if isinstance(moat, Moat) else cls(shape=moat)
