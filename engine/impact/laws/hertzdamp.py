"""Hertzdamp impact law (Muthukumar & DesRoches 2006; paper Fig. 4b).

F = k delta^n (1 + chi * delta_dot / v_imp), clipped at zero; n = 1.5 by default.

Two rules give chi from the coefficient of restitution:
- "lankarani" (default, as published): chi = 3 (1 - COR^2) / 4 (Lankarani & Nikravesh). It is an
  approximation for COR near 1; for low COR the realised COR is far higher (0.68 for 0.3, n 1.5).
- "calibrated": chi solved so that the law realises the target COR (see calibration.py).

Grazing contacts (v_imp -> 0): the dashpot k delta^n chi / v_imp grows without bound; the
engine solves it implicitly on the central velocity, so the force stays finite (at most what
stops the approach within one step) and, in the tested 0.1 mm graze at v_imp 0.036 m/s,
below k delta^n (1 + chi) and dt-convergent (tests/engine/impact/test_contact.py). Unlike the bumper
law it has no intrinsic bound: a slab pushed faster into the wall than it touched it meets a
dashpot of k delta^n chi / v_imp.
"""
import numpy as np

from ...layout import columns
from ...parameters import REQUIRED, Declaration, Option, Parameter
from ...units import power_law_units
from ..calibration import hunt_crossley_chi
from ..parameters import GAP, M_EFF

CHI_RULES = ("lankarani", "calibrated")

NAME = "hertzdamp"
"""The law's name in Contact.of, sweeps and archives."""
ORDER = 3
"""Its place among the laws of the paper's section 2 (listings follow it)."""

PARAMETERS = Declaration(
    GAP,
    # The unit is N/m^n; the string is that of the default exponent, which sweeps keep. UDUNITS
    # has no fractional powers: power_law_units gives a string it refuses, and long_name says it.
    Parameter("k", power_law_units(1.5), "moat wall Hertz stiffness k, N/m^n: "
              f"{power_law_units(1.5)} at the default n", REQUIRED, "(0, inf)",
              equation="Muthukumar & DesRoches 2006", sweep="wall_k",
              plausible="[1e6, 1e14]"),
    Parameter("n", "1", "Hertz exponent n", 1.5, "[1, inf)"),
    Parameter("cor", "1", "coefficient of restitution of the wall impacts", 0.5, "(0, 1]",
              sweep="cor"),
    M_EFF,
    Option("chi_rule", CHI_RULES, "lankarani",
           "damping factor chi from the COR: 3 (1 - COR^2) / 4 as published, or calibrated "
           "to realise the COR"),
)

ROW = columns("HertzdampRow", "k", "n", "chi")
"""The Contact fields force_terms reads, packed in this order into one row per member
(contact.law_rows; the NumPy loops pass a tuple of (B,) arrays, the compiled ones a row of
floats): a new constant of this law is a new name here."""


def chi(cor, n, rule="lankarani"):
    """Dimensionless damping factor chi, (B,)."""
    if rule == "lankarani":
        return 0.75 * (1 - np.asarray(cor, dtype=float) ** 2)
    return hunt_crossley_chi(cor, n, restitution_only=False)


def contact_fields(gap, k, n, cor, m_eff, chi_rule):
    """The Contact fields of this law from its checked, broadcast (B,) parameters."""
    return {"clear_gap": gap, "k": k, "n": n, "chi": chi(cor, n, chi_rule)}


def force_terms(delta, delta_dot, v_imp, row):
    """(elastic force N, dashpot N*s/m): F = k delta^n + (k delta^n chi / v_imp) delta_dot.

    row: ROW, k (N/m^n), n, chi; v_imp (m/s) > 0; scalars or (B,) arrays alike (a row of
    floats or a tuple of arrays), compiled as is by the kernel.
    """
    k, n, chi = row[ROW.k], row[ROW.n], row[ROW.chi]
    elastic = k * np.maximum(delta, 0.0) ** n
    return elastic, elastic * chi / v_imp


def max_tangent_stiffness(p, indentation_bound):
    """Tangent n k delta^(n-1) at the indentation bound (m): the law itself has no cap."""
    return p.n * p.k * indentation_bound ** (p.n - 1)
