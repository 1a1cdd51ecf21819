"""FEMA P695 (2009) appendix A, section A.8: each pair normalised by its PGV to the set's median
PGV, then one factor anchoring the set's median spectrum at T = T_M on the target
(pipeline.motions.code_scaling.fema_p695 with FEMA_P695, which holds the clause).
"""
from __future__ import annotations

from ..code_scaling import FEMA_P695, fema_p695

NAME = "p695"
"""The rule's name in --rule and the archives."""
ORDER = 2
"""Its place in listings."""
TEXT = ("FEMA P695 (appendix A.8): each pair normalised by its PGV to the set's median, then "
        "one factor anchoring the set's median spectrum at T_M")
"""What it does, in one line."""
CLAUSE = FEMA_P695.clause
"""The clause it implements (pipeline.motions.code_scaling.FEMA_P695)."""


def factors(pairs, target, design, building, dt):
    """(chosen, factors (K,), ScaledPairs): the pairs normalised and anchored at
    T = design.t_m (s: T_M at the bound run) on the target (see the package's docstring);
    every pair is kept; building and dt are not needed."""
    scaled = fema_p695(pairs, target, design.t_m)
    chosen, kept = scaled.factors_of(pairs)
    return chosen, kept, scaled
