"""The paper's nonlinear hysteretic rubber-bumper impact law (Eq. 4, 6, 9, 11, 12, 14).

Approach (delta_dot > 0), Eq. 4 and 14:
    F_A = k_imp delta^n                                 for delta < delta_u
    F_A = k_imp delta_u^n + k_w (delta - delta_u)       beyond (crushed rubber on the wall)
Restitution (delta_dot <= 0), Eq. 6:  F = F_A(delta) (1 + C_imp delta_dot), floored at 0.
Eq. 9 (SI, s/m): C_imp = 1.55 (1 - COR^2) / (COR^0.7076 m_eff^0.0025 v_imp^0.9755).
Alternative "calibrated" rule: C_imp = chi / v_imp with chi solved so that the pure power law
realises the target COR exactly (calibration.py).

Bumper stiffness, Eq. 11-12: k_st = A K_r / t^n, k_imp = alpha k_st, and bumpers on one side
act in parallel. With the paper's material (K_r = 55,835 kN/m^2, n = 2.65, alpha = 2.25) one
150 x 150 x 50 mm bumper gives 0.089 kN/mm^2.65.
"""
import numpy as np

from .calibration import hunt_crossley_chi

C_IMP_RULES = ("eq9", "calibrated")
EQ9_COEFFICIENT = 1.55
EQ9_COR_EXPONENT = 0.7076
EQ9_MASS_EXPONENT = 0.0025
EQ9_VELOCITY_EXPONENT = 0.9755

# The paper's rubber (section 3.4, from the Kajita et al. static test): SI units.
K_R = 55_835e3  # Pa (55,835 kN/m^2)
EXPONENT = 2.65
ALPHA = 2.25
BUMPER_AREA = 0.150 * 0.150  # m^2


def kn_mm_to_si(k, n):
    """Convert a stiffness from kN/mm^n to N/m^n."""
    return np.asarray(k, dtype=float) * 1e3 * 1e3**n


def si_to_kn_mm(k, n):
    """Convert a stiffness from N/m^n to kN/mm^n."""
    return np.asarray(k, dtype=float) / (1e3 * 1e3**n)


def static_stiffness(area, thickness, k_r=K_R, n=EXPONENT):
    """Eq. 11: k_st = A K_r / t^n in N/m^n (area m^2, thickness m, k_r Pa)."""
    return area * k_r / np.asarray(thickness, dtype=float) ** n


def impact_stiffness(area, thickness, k_r=K_R, n=EXPONENT, alpha=ALPHA, count=1):
    """Eq. 12 for `count` identical bumpers acting in parallel: alpha * count * k_st (N/m^n)."""
    return alpha * count * static_stiffness(area, thickness, k_r, n)


def damping_prefactor(cor, m_eff):
    """The part of Eq. 9 that does not depend on v_imp: C_imp * v_imp^0.9755."""
    return EQ9_COEFFICIENT * (1 - cor**2) / (cor**EQ9_COR_EXPONENT * m_eff**EQ9_MASS_EXPONENT)


def damping_constants(cor, m_eff, n, rule="eq9"):
    """(coef, vexp) with C_imp = coef / v_imp^vexp for the chosen rule, (B,) each."""
    cor = np.asarray(cor, dtype=float)
    if rule == "eq9":
        return damping_prefactor(cor, m_eff), np.full(cor.shape, EQ9_VELOCITY_EXPONENT)
    return hunt_crossley_chi(cor, n, restitution_only=True), np.ones(cor.shape)


def approach_force(delta, p):
    """F_A of Eq. 4 and 14 (N), (B,); p.k = k_imp (N/m^n), p.delta_u (m), p.k_w (N/m)."""
    d = np.maximum(delta, 0.0)
    rubber = p.k * np.minimum(d, p.delta_u) ** p.n
    return rubber + p.k_w * np.maximum(d - p.delta_u, 0.0)


def force_terms(delta, delta_dot, v_imp, p):
    """(elastic force N, dashpot N*s/m), (B,) each: F_A on approach, F_A (1 + C_imp
    delta_dot) in restitution, i.e. a dashpot F_A C_imp that acts in restitution only."""
    elastic = approach_force(delta, p)
    c_imp = p.coef / v_imp**p.vexp
    return elastic, np.where(delta_dot > 0, 0.0, elastic * c_imp)


def max_tangent_stiffness(p, indentation_bound):
    """The stiffer of the rubber's tangent at delta_u and the wall k_w (N/m)."""
    return np.maximum(p.n * p.k * p.delta_u ** (p.n - 1), p.k_w)

