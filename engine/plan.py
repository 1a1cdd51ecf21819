"""What a run in plan takes beyond a planar one, declared once: the moats, the incidence angle
of a record pair and the friction between slab and wall (engine.simulate with accel (N, 2);
the loops are loops/numpy_plan.py and loops/numba_plan.py, what they return
results.PLAN_PEAKS and PLAN_HISTORIES)."""
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
