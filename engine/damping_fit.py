"""Re-deriving the impact damping coefficient of the rubber-bumper law, Eq. 9 (section 3.2).

The paper's procedure: in restitution the bumper force is F = k_imp delta^n (1 + C_imp
delta_dot) (Eq. 6), with C_imp = a1 (1 - COR^2) (Eq. 8). For each (COR, m_eff, v_imp), a1 is
varied until the hysteresis area A_h of a two-body impact equals the kinetic energy loss
Delta E = 1/2 m_eff (1 - COR^2) v_imp^2 (Eq. 5). A power law
C_imp = c0 (1 - COR^2) / (COR^p1 m_eff^p2 v_imp^p3) fitted to the a1 found gives Eq. 9
(paper: c0 = 1.55, p1 = 0.7076, p2 = 0.0025, p3 = 0.9755; SI units, C_imp in s/m).

Pure functions over (P,) arrays of grid points: no I/O. `find_a1` runs `engine.two_body` on the
whole grid at once in every bisection step. With a pure power law (no crushing) the realised
COR depends only on C_imp v_imp and n (scale delta by (m_eff v^2/k)^(1/(n+1))), so the fit
should find p2 = 0 and p3 = 1: the bumper passed in must not be crushed (checked: see
`EquilibriumResult.crushed`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import EngineError
from .impact import Contact
from .simulate import two_body

# Bracket of the dimensionless damping number C_imp v_imp searched: 1e-3 realises COR ~ 1, 20
# about 0.05. Far larger values make the restitution a slow creep at delta_dot ~ -1/C_imp that
# two_body would have to follow for many contact times.
DEFAULT_BRACKET = (1e-3, 20.0)


@dataclass
class EquilibriumResult:
    """Per grid point (P,): a1 s/m (Eq. 8) and what the impact with C_imp = a1 (1 - COR^2)
    gives: c_imp s/m, hysteresis_area J (A_h), energy_loss J (Delta E of Eq. 5 with the target
    COR), cor_realised (-v_out / v_imp), peak_indentation m, peak_force N, delta_u m (the
    bumper's crush indentation), crushed bool (peak_indentation >= delta_u: the law is no
    longer a pure power law); iterations: bisection steps run (scalar)."""

    a1: np.ndarray
    c_imp: np.ndarray
    hysteresis_area: np.ndarray
    energy_loss: np.ndarray
    cor_realised: np.ndarray
    peak_indentation: np.ndarray
    peak_force: np.ndarray
    delta_u: np.ndarray
    crushed: np.ndarray
    iterations: int


@dataclass
class PowerLaw:
    """C_imp = c0 (1 - COR^2) / (COR^p1 m_eff^p2 v_imp^p3), SI (C_imp s/m, m_eff kg, v m/s);
    rms_log_error: root-mean-square of ln(fitted / data) over the points fitted."""

    c0: float
    p1: float
    p2: float
    p3: float
    rms_log_error: float

    def c_imp(self, cor, m_eff, v):
        """C_imp (s/m) of this law at (COR, m_eff kg, v m/s), broadcast."""
        return power_law_c_imp(cor, m_eff, v, self.c0, self.p1, self.p2, self.p3)


def power_law_c_imp(cor, m_eff, v, c0, p1, p2, p3):
    """Eq. 9 with free constants: c0 (1 - COR^2) / (COR^p1 m_eff^p2 v^p3), s/m, broadcast."""
    cor, m_eff, v = (np.asarray(x, dtype=float) for x in (cor, m_eff, v))
    return c0 * (1 - cor**2) / (cor**p1 * m_eff**p2 * v**p3)


def bumper_impacts(cor, m_eff, c_imp, bumper: dict) -> Contact:
    """(P,) bumper contacts with a fixed C_imp (s/m) per point, for `engine.two_body`.

    bumper: keywords of `Contact.bumper` (thickness, area, strain, n_bumpers, k_w, k_r, n,
    alpha, cavity); the gap is irrelevant between two free bodies and is set just wide
    enough to be valid."""
    thickness = np.asarray(bumper.get("thickness", 0.05), dtype=float)
    return Contact.bumper(2 * np.max(thickness) + 1.0, cor=cor, m_eff=m_eff, c_imp=c_imp,
                          **bumper)


def impact(cor, m_eff, v, c_imp, bumper: dict, steps_per_contact=None, backend=None):
    """One two-body impact per point (two equal bodies of 2 m_eff each, relative velocity v
    m/s) through the bumper with C_imp = c_imp (s/m): (`engine.TwoBodyResult`, the (P,)
    `Contact` used)."""
    cor, m_eff, v, c_imp = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float))
                                                 for x in (cor, m_eff, v, c_imp)))
    contact = bumper_impacts(cor, m_eff, c_imp, bumper)
    options = {} if steps_per_contact is None else {"steps_per_contact": steps_per_contact}
    return two_body(2 * m_eff, 2 * m_eff, v, contact, backend=backend, **options), contact


def find_a1(cor, m_eff, v, bumper: dict, bracket=DEFAULT_BRACKET, rtol=1e-6,
            max_iter=100, steps_per_contact=None, backend=None) -> EquilibriumResult:
    """Energy equilibrium of section 3.2: a1 (s/m) such that the hysteresis area of the impact
    with C_imp = a1 (1 - COR^2) (Eq. 8) equals Delta E of Eq. 5, for every grid point at once.

    cor (1), m_eff (kg), v (m/s impact velocity): (P,) arrays (broadcast), COR < 1.
    bumper: `Contact.bumper` keywords (see `bumper_impacts`). The area grows monotonically with
    a1, so a batched bisection in log(a1) runs until every point's bracket is narrower than
    rtol (relative). `bracket` (lower, upper) bounds the dimensionless C_imp v_imp, i.e.
    a1 in bracket / ((1 - COR^2) v); EngineError if it does not enclose the equilibrium.
    backend: engine.two_body's (None: the compiled kernel when numba is importable).
    """
    cor, m_eff, v = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float))
                                          for x in (cor, m_eff, v)))
    if np.any(~((cor > 0) & (cor < 1))):
        raise EngineError(f"cor must be in (0, 1) for the energy equilibrium, got {cor}")
    damping = 1 - cor**2
    energy_loss = 0.5 * m_eff * damping * v**2

    def excess(a1):  # A_h - Delta E, J: < 0 with too little damping
        res, _ = impact(cor, m_eff, v, a1 * damping, bumper, steps_per_contact, backend)
        return res.hysteresis_area - energy_loss

    lower = float(bracket[0]) / (damping * v)
    upper = float(bracket[1]) / (damping * v)
    if np.any(excess(lower) > 0) or np.any(excess(upper) < 0):
        raise EngineError(f"find_a1: the bracket {bracket} of C_imp v_imp does not enclose "
                          "the energy equilibrium at every grid point; widen it")
    iterations = 0
    while np.any(upper / lower - 1 > rtol):
        if iterations == max_iter:
            raise EngineError(f"find_a1: no convergence to rtol {rtol} in {max_iter} steps")
        middle = np.sqrt(lower * upper)
        too_much = excess(middle) > 0
        upper = np.where(too_much, middle, upper)
        lower = np.where(too_much, lower, middle)
        iterations += 1
    a1 = np.sqrt(lower * upper)
    res, contact = impact(cor, m_eff, v, a1 * damping, bumper, steps_per_contact, backend)
    return EquilibriumResult(
        a1=a1, c_imp=a1 * damping, hysteresis_area=res.hysteresis_area,
        energy_loss=energy_loss, cor_realised=res.cor, peak_indentation=res.peak_indentation,
        peak_force=res.peak_force, delta_u=contact.delta_u,
        crushed=res.peak_indentation >= contact.delta_u, iterations=iterations)


def fit_power_law(cor, m_eff, v, c_imp) -> PowerLaw:
    """Least-squares fit of Eq. 9's form in log space over (P,) points:
    ln(C_imp / (1 - COR^2)) = ln c0 - p1 ln COR - p2 ln m_eff - p3 ln v.

    cor (1), m_eff (kg), v (m/s), c_imp (s/m): (P,) arrays, P >= 4 with COR, m_eff and v each
    taking at least two values (else the exponents are not determined: EngineError)."""
    cor, m_eff, v, c_imp = (np.ravel(np.asarray(x, dtype=float)) for x in (cor, m_eff, v, c_imp))
    design = np.column_stack([np.ones_like(cor), -np.log(cor), -np.log(m_eff), -np.log(v)])
    if np.linalg.matrix_rank(design) < 4:
        raise EngineError("fit_power_law needs at least two values each of COR, m_eff and v")
    target = np.log(c_imp / (1 - cor**2))
    coeffs, *_ = np.linalg.lstsq(design, target, rcond=None)
    rms = float(np.sqrt(np.mean((design @ coeffs - target) ** 2)))
    return PowerLaw(c0=float(np.exp(coeffs[0])), p1=float(coeffs[1]), p2=float(coeffs[2]),
                    p3=float(coeffs[3]), rms_log_error=rms)
