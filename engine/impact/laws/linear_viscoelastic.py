"""Linear viscoelastic (Kelvin-Voigt) impact law, paper Eq. 1-3 (Anagnostopoulos 1988).

F = k * delta + c * delta_dot,  c = 2 * xi * sqrt(k * m_eff),  clipped at zero (no tension).

Two rules give xi from the coefficient of restitution:
- "eq3": xi = -ln(COR) / sqrt(pi^2 + ln^2(COR)), the paper's Eq. 3. It is exact only if the
  contact may pull at the end of restitution; with the no-tension rule the bodies separate
  when F reaches zero, earlier and faster, so the realised COR is higher (0.55 for 0.5).
- "no_tension" (default): the xi for which the *clipped* law realises the target COR. The
  clipped oscillator separates when its acceleration vanishes, which gives in closed form
  COR = exp(-r * (pi - 2 * atan(r))), r = xi / sqrt(1 - xi^2); it is inverted here.

The paper's bare moat wall (the no-bumper reference of every figure) is this law at its
defaults: k = 2500 kN/mm, COR 0.5 (SPEC decision).
"""
import numpy as np

from ...layout import columns
from ...parameters import Declaration, Option, Parameter
from ..parameters import GAP, M_EFF

XI_RULES = ("no_tension", "eq3")

NAME = "linear"
"""The law's name in Contact.of, sweeps and archives."""
ORDER = 1
"""Its place among the laws of the paper's section 2 (listings follow it)."""

PARAMETERS = Declaration(
    GAP,
    Parameter("k", "N m-1", "moat wall contact stiffness k", 2.5e9, "(0, inf)",
              equation="Eq. 1", sweep="wall_k", plausible="[1e6, 1e13]"),
    Parameter("cor", "1", "coefficient of restitution of the wall impacts", 0.5, "(0, 1]",
              equation="Eq. 3", sweep="cor"),
    M_EFF,
    Option("xi_rule", XI_RULES, "no_tension",
           "damping ratio from the COR: exact for the no-tension contact, or Eq. 3"),
)

ROW = columns("LinearViscoelasticRow", "k", "dashpot")
"""The Contact fields force_terms reads, packed in this order into one row per member
(contact.law_rows; the NumPy loops pass a tuple of (B,) arrays, the compiled ones a row of
floats): a new constant of this law is a new name here."""


def xi_eq3(cor):
    """Paper Eq. 3 damping ratio, (B,)."""
    log = np.log(cor)
    return -log / np.sqrt(np.pi**2 + log**2)


def cor_no_tension(xi):
    """COR realised by the clipped Kelvin-Voigt contact with damping ratio xi (< 1)."""
    r = xi / np.sqrt(1 - xi**2)
    return np.exp(-r * (np.pi - 2 * np.arctan(r)))


def xi_no_tension(cor):
    """Damping ratio for which the clipped contact realises `cor` exactly, (B,)."""
    from scipy.optimize import brentq  # here: scipy takes 0.6 s to import, rarely needed

    cor = np.atleast_1d(np.asarray(cor, dtype=float))
    values, inverse = np.unique(cor, return_inverse=True)  # a sweep's million members: a few
    xi = np.zeros_like(values)
    for i, c in enumerate(values):  # setup only, never inside the time loop
        if c < 1:
            xi[i] = brentq(lambda x, c=c: cor_no_tension(x) - c, 0.0, 1 - 1e-12, xtol=1e-15)
    return xi[inverse.reshape(cor.shape)]


def damping_coefficient(k, cor, m_eff, xi_rule="no_tension"):
    """Impact dashpot c (N*s/m), Eq. 2, with xi from `xi_rule`."""
    xi = xi_no_tension(cor) if xi_rule == "no_tension" else xi_eq3(cor)
    return 2 * xi * np.sqrt(k * m_eff)


def contact_fields(gap, k, cor, m_eff, xi_rule):
    """The Contact fields of this law from its checked, broadcast (B,) parameters."""
    return {"clear_gap": gap, "k": k, "n": 1.0,
            "dashpot": damping_coefficient(k, cor, m_eff, xi_rule)}


def force_terms(delta, delta_dot, v_imp, row):
    """(elastic force N, dashpot N*s/m): F = k delta + c delta_dot; k N/m, dashpot c N*s/m.

    row: ROW; scalars or (B,) arrays alike (a row of floats or a tuple of arrays), compiled as
    is by the kernel.
    """
    return row[ROW.k] * delta, row[ROW.dashpot]


def max_tangent_stiffness(p, indentation_bound):
    """Largest contact stiffness the member can reach (N/m), for the stability limit."""
    return p.k
