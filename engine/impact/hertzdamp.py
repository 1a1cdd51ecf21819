"""Hertzdamp impact law (Muthukumar & DesRoches 2006; paper Fig. 4b).

F = k delta^n (1 + chi * delta_dot / v_imp), clipped at zero; n = 1.5 by default.

Two rules give chi from the coefficient of restitution:
- "lankarani" (default, as published): chi = 3 (1 - COR^2) / 4 (Lankarani & Nikravesh). It is an
  approximation for COR near 1; for low COR the realised COR is far higher (0.68 for 0.3, n 1.5).
- "calibrated": chi solved so that the law realises the target COR (see calibration.py).
"""
import numpy as np

from .calibration import hunt_crossley_chi

CHI_RULES = ("lankarani", "calibrated")


def chi(cor, n, rule="lankarani"):
    """Dimensionless damping factor chi, (B,)."""
    if rule == "lankarani":
        return 0.75 * (1 - np.asarray(cor, dtype=float) ** 2)
    return hunt_crossley_chi(cor, n, restitution_only=False)


def force_terms(delta, delta_dot, v_imp, p):
    """(elastic force N, dashpot N*s/m), (B,) each: F = k delta^n + (k delta^n chi / v_imp)
    delta_dot. p.k (N/m^n), p.n, p.coef = chi; v_imp (m/s) > 0."""
    elastic = p.k * np.maximum(delta, 0.0) ** p.n
    return elastic, elastic * p.coef / v_imp


def max_tangent_stiffness(p, indentation_bound):
    """Tangent n k delta^(n-1) at the indentation bound (m): the law itself has no cap."""
    return p.n * p.k * indentation_bound ** (p.n - 1)

