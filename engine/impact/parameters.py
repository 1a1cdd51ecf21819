"""The parameters every impact law takes, declared once (engine/parameters.py says how a law
declares a parameter)."""
from ..parameters import REQUIRED, Parameter

GAP = Parameter("gap", "m", "seismic gap: clearance between base slab and moat wall on either "
                "side, before any bumper", REQUIRED, "(0, inf)", sweep="gap", plausible="(0, 2]")
# plausible: no lower bound, since studies compute gaps (a fraction of a weak record's peak
# can be millimetres: studies.plan); wider than 2 m, no moat (the largest isolator
# displacements are about 1.5 m).
M_EFF = Parameter("m_eff", "kg", "effective impact mass m1 m2 / (m1 + m2): the base slab "
                  "against an immovable wall (SPEC decision)", 320e3, "(0, inf)",
                  equation="Eq. 2", plausible="[1e3, 1e9]")
