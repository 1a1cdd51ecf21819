"""Nonlinear viscoelastic impact law (Jankowski 2005; paper Fig. 4a).

Approach (delta_dot > 0): F = beta * delta^1.5 + c * delta_dot,
    c = 2 xi sqrt(beta sqrt(delta) m_eff)
Restitution (delta_dot <= 0): F = beta * delta^1.5
xi = 9 sqrt(5) (1 - COR^2) / (2 COR (COR (9 pi - 16) + 16))  (Jankowski 2006).
"""
import numpy as np

from ...layout import columns
from ...parameters import REQUIRED, Declaration, Parameter
from ...units import power_law_units
from ..parameters import GAP, M_EFF

EXPONENT = 1.5

NAME = "jankowski"
"""The law's name in Contact.of, sweeps and archives."""
ORDER = 2
"""Its place among the laws of the paper's section 2 (listings follow it)."""

PARAMETERS = Declaration(
    GAP,
    Parameter("beta", power_law_units(EXPONENT), "moat wall impact stiffness beta, "
              f"{power_law_units(EXPONENT)}", REQUIRED, "(0, inf)",
              equation="Jankowski 2005", sweep="wall_k", plausible="[1e6, 1e14]"),
    Parameter("cor", "1", "coefficient of restitution of the wall impacts", 0.5, "(0, 1]",
              equation="Jankowski 2006", sweep="cor"),
    M_EFF,
)

ROW = columns("JankowskiRow", "k", "m_eff", "damping_ratio")
"""The Contact fields force_terms reads, packed in this order into one row per member
(contact.law_rows; the NumPy loops pass a tuple of (B,) arrays, the compiled ones a row of
floats): a new constant of this law is a new name here."""


def damping_ratio(cor):
    """Jankowski's damping ratio for a target COR, (B,)."""
    return 9 * np.sqrt(5) * (1 - cor**2) / (2 * cor * (cor * (9 * np.pi - 16) + 16))


def contact_fields(gap, beta, cor, m_eff):
    """The Contact fields of this law from its checked, broadcast (B,) parameters."""
    return {"clear_gap": gap, "k": beta, "n": EXPONENT, "damping_ratio": damping_ratio(cor)}


def force_terms(delta, delta_dot, v_imp, row):
    """(elastic force N, dashpot N*s/m); the dashpot acts on approach only.

    row: ROW, k = beta (N/m^1.5), damping_ratio = xi, m_eff (kg); scalars or (B,) arrays
    alike (a row of floats or a tuple of arrays), compiled as is by the kernel.
    """
    k, m_eff, xi = row[ROW.k], row[ROW.m_eff], row[ROW.damping_ratio]
    d = np.maximum(delta, 0.0)
    dashpot = 2 * xi * np.sqrt(k * np.sqrt(d) * m_eff)
    return k * d**EXPONENT, (delta_dot > 0) * dashpot


def max_tangent_stiffness(p, indentation_bound):
    """Tangent 1.5 beta delta^0.5 at the indentation bound (m): the law itself has no cap."""
    return EXPONENT * p.k * np.sqrt(indentation_bound)
