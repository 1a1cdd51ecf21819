"""What a run in plan takes beyond a planar one, declared once: the moats and the incidence
angle of a record pair (engine.simulate with accel (N, 2); the loops are loops/numpy_plan.py
and loops/numba_plan.py, what they return results.PLAN_PEAKS and PLAN_HISTORIES)."""
from .parameters import Parameter
from .results import WALLS

MOATS = tuple(WALLS)
"""The moat shapes: "rectangular" (walls normal to x and to y), "circular"."""

ANGLE = Parameter("angle", "degree", "incidence angle: the record pair rotated "
                  "counterclockwise, x towards y, before it excites the building", 0.0,
                  "[-360, 360]", sweep="angle")
"""A member's incidence angle (engine.simulate's angle; pipeline.sweep's angle)."""
