"""ASCE 7-22 chapter 17 (section 17.3.3; pairs and maximum-direction spectra as in section
16.2.3): every pair scaled by one factor, so that the suite's mean RotD100 spectrum is not below
the stated fraction of the MCE_R target over the stated period range around T_M
(pipeline.motions.code_scaling.asce7_isolated with ASCE7_22_ISOLATED, which holds the numbers and
the clause; pairs whose factor falls outside its limits are left out and listed there).

The range runs from 0.75 T_M with upper-bound to 1.25 T_M with lower-bound isolator properties
(the design basis' t_m_bounds, pipeline.motions.bounds), whichever bound the study runs.
"""
from __future__ import annotations

from ..code_scaling import ASCE7_22_ISOLATED, asce7_isolated

NAME = "asce7"
"""The rule's name in --rule and the archives."""
ORDER = 1
"""Its place in listings: the default rule first."""
TEXT = ("ASCE 7-22 chapter 17 (section 17.3.3): the suite's mean maximum-direction (RotD100) "
        "spectrum not below the stated fraction of the target over the stated period range "
        "around T_M")
"""What it does, in one line."""
CLAUSE = ASCE7_22_ISOLATED.clause
"""The clause it implements (pipeline.motions.code_scaling.ASCE7_22_ISOLATED)."""


def factors(pairs, target, design, building, dt):
    """(chosen, factors (K,), ScaledPairs): the pairs scaled to the target over 0.75 T_M
    (upper bound) to 1.25 T_M (lower bound), (T_M upper, T_M lower) = design.t_m_bounds (s; see
    the package's docstring); building and dt are not needed."""
    scaled = asce7_isolated(pairs, target, design.t_m_bounds)
    chosen, kept = scaled.factors_of(pairs)
    return chosen, kept, scaled
