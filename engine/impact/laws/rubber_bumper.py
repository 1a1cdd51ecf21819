"""The paper's nonlinear hysteretic rubber-bumper impact law (Eq. 4, 6, 9, 11, 12, 14).

Approach (delta_dot > 0), Eq. 4 and 14:
    F_A = k_imp delta^n                                 for delta < delta_u
    F_A = k_imp delta_u^n + k_w (delta - delta_u)       beyond (crushed rubber on the wall)
Restitution (delta_dot <= 0), Eq. 6:  F = F_A(delta) (1 + C_imp delta_dot), floored at 0.
Eq. 9 (SI, s/m): C_imp = 1.55 (1 - COR^2) / (COR^0.7076 m_eff^0.0025 v_imp^0.9755).
Alternative "calibrated" rule: C_imp = chi / v_imp with chi solved so that the pure power law
realises the target COR exactly (calibration.py). Either way C_imp = c_imp_coef /
v_imp^c_imp_exponent, the two constants a Contact holds.

Bumper stiffness, Eq. 11-12: k_st = A K_r / t^n, k_imp = alpha k_st, and bumpers on one side
act in parallel. With the paper's material (K_r = 55,835 kN/m^2, n = 2.65, alpha = 2.25) one
150 x 150 x 50 mm bumper gives 0.089 kN/mm^2.65.

Geometry (SPEC section 2): bumpers of thickness t are fixed to the wall, set into a cavity of
depth c_d (0 by default), so they protrude t - c_d and the clear gap is gap - (t - c_d); they
are crushed at delta_u = min(strain t, t - c_d), past which the slab bears on the wall (k_w).

Decisions where the paper is silent (each checked against an independent solution in
tests/engine/test_model_edges.py):
- Past the crush limit, restitution damps the whole F_A, the wall term k_w (delta - delta_u)
  included: Eq. 6 multiplies F_A, and Eq. 14 defines F_A past delta_u. The realised COR then
  does not depend on crushing or k_w at all (a closed-form solve of the restitution phase
  gives the same 0.4381 for COR 0.45 at k_w 1500 and 200 kN/mm); damping the rubber term only
  would give 0.73 and 0.63.
- A contact lasts while delta > 0, not while F > 0. The law is continuous in the rate: as
  delta_dot -> 0- the restitution force tends to F_A(delta). So a slab whose restitution force
  was floored at zero (fast separation) and that turns back before delta reaches 0 reloads
  continuously through F_A (1 + C_imp delta_dot), with the same v_imp; the engine converges
  on such an event as dt shrinks.
- Grazing contacts (v_imp -> 0): C_imp grows without bound, but the restitution factor
  (1 + C_imp delta_dot) is clipped to [0, 1], so the force stays between 0 and F_A(delta):
  bounded, and dt-convergent (a 0.1 mm graze at v_imp 0.036 m/s). No floor on v_imp is needed.
"""
import numpy as np

from ...errors import EngineError
from ...parameters import Declaration, Option, Parameter
from ..calibration import hunt_crossley_chi
from ..parameters import GAP, M_EFF

C_IMP_RULES = ("eq9", "calibrated")
EQ9_COEFFICIENT = 1.55
EQ9_COR_EXPONENT = 0.7076
EQ9_MASS_EXPONENT = 0.0025
EQ9_VELOCITY_EXPONENT = 0.9755

NAME = "bumper"
"""The law's name in Contact.of, sweeps and archives."""
ORDER = 4
"""Its place among the laws of the paper's section 2 (listings follow it)."""

PARAMETERS = Declaration(
    GAP,
    # plausible: a rubber pad thinner than 5 mm is a sheet, not a bumper (the paper's test pad
    # is 10 mm); thicker than 2 m, a block.
    Parameter("thickness", "m", "bumper thickness t", 0.05, "(0, inf)", equation="Eq. 11",
              sweep="thickness", plausible="[0.005, 2]"),
    Parameter("cavity", "m", "depth c_d of the wall cavity holding each bumper", 0.0,
              "[0, inf)", equation="section 5.3", sweep="cavity", plausible="[0, 2]"),
    Parameter("strain", "1", "ultimate compressive strain of the bumper rubber", 0.8,
              "(0, 1]", equation="Eq. 14", sweep="strain"),
    Parameter("n_bumpers", "1", "number of bumpers on each side, acting in parallel", 4,
              "[1, inf)", integer=True, equation="Eq. 12", sweep="n_bumpers"),
    Parameter("k_w", "N m-1", "moat wall stiffness k_w behind the crushed bumpers", 1.5e9,
              "(0, inf)", equation="Eq. 14", sweep="wall_k", plausible="[1e6, 1e13]"),
    # 0.45: the paper's rubber, section 3.4 (SPEC decision).
    Parameter("cor", "1", "coefficient of restitution of the bumper impacts", 0.45, "(0, 1]",
              equation="Eq. 9", sweep="cor"),
    M_EFF,
    Parameter("area", "m2", "contact area A of one bumper (150 x 150 mm)", 0.150 * 0.150,
              "(0, inf)", equation="Eq. 11"),
    Parameter("k_r", "Pa", "rubber stiffness K_r (55,835 kN/m^2, Kajita et al. static test)",
              55_835e3, "(0, inf)", equation="Eq. 11"),
    Parameter("n", "1", "exponent n of the rubber's power law", 2.65, "[1, inf)",
              equation="Eq. 4"),
    Parameter("alpha", "1", "impact-to-static stiffness ratio alpha", 2.25, "(0, inf)",
              equation="Eq. 12"),
    Option("c_imp_rule", C_IMP_RULES, "eq9",
           "impact damping coefficient C_imp: the paper's Eq. 9, or calibrated to realise "
           "the COR exactly"),
    Parameter("c_imp", "s m-1", "a fixed C_imp instead of the rule's, the same at every "
              "impact velocity (to re-derive Eq. 9, section 3.2)", None, "(0, inf)",
              equation="Eq. 8"),
)


_RUBBER = {name: PARAMETERS[name].default for name in ("k_r", "n", "alpha")}


def static_stiffness(area, thickness, k_r=_RUBBER["k_r"], n=_RUBBER["n"]):
    """Eq. 11: k_st = A K_r / t^n in N/m^n (area m^2, thickness m, k_r Pa)."""
    return area * k_r / np.asarray(thickness, dtype=float) ** n


def impact_stiffness(area, thickness, k_r=_RUBBER["k_r"], n=_RUBBER["n"],
                     alpha=_RUBBER["alpha"], count=1):
    """Eq. 12 for `count` identical bumpers acting in parallel: alpha * count * k_st (N/m^n)."""
    return alpha * count * static_stiffness(area, thickness, k_r, n)


def damping_prefactor(cor, m_eff):
    """The part of Eq. 9 that does not depend on v_imp: C_imp * v_imp^0.9755."""
    return EQ9_COEFFICIENT * (1 - cor**2) / (cor**EQ9_COR_EXPONENT * m_eff**EQ9_MASS_EXPONENT)


def damping_constants(cor, m_eff, n, rule="eq9"):
    """(c_imp_coef, c_imp_exponent) with C_imp = c_imp_coef / v_imp^c_imp_exponent for the
    chosen rule, (B,) each."""
    cor = np.asarray(cor, dtype=float)
    if rule == "eq9":
        return damping_prefactor(cor, m_eff), np.full(cor.shape, EQ9_VELOCITY_EXPONENT)
    return hunt_crossley_chi(cor, n, restitution_only=True), np.ones(cor.shape)


def contact_fields(gap, thickness, strain, n_bumpers, k_w, cor, m_eff, cavity, area, k_r, n,
                   alpha, c_imp_rule, c_imp):
    """The Contact fields of this law from its checked, broadcast (B,) parameters."""
    if np.any(cavity >= thickness):
        raise EngineError(f"cavity must be smaller than thickness, got cavity {cavity} m, "
                          f"thickness {thickness} m")
    protrusion = thickness - cavity
    if np.any(protrusion >= gap):
        raise EngineError("thickness - cavity must be smaller than gap: the bumpers would "
                          f"close the gap (gap {gap}, thickness {thickness}, cavity {cavity})")
    if c_imp is None:
        c_imp_coef, c_imp_exponent = damping_constants(cor, m_eff, n, c_imp_rule)
    else:
        c_imp_coef, c_imp_exponent = c_imp, 0.0
    return {"clear_gap": gap - protrusion, "k": impact_stiffness(area, thickness, k_r, n, alpha,
                                                                 n_bumpers),
            "n": n, "delta_u": np.minimum(strain * thickness, protrusion), "k_w": k_w,
            "c_imp_coef": c_imp_coef, "c_imp_exponent": c_imp_exponent}


def force_terms(delta, delta_dot, v_imp, k, n, m_eff, delta_u, k_w, dashpot, damping_ratio, chi,
                c_imp_coef, c_imp_exponent):
    """(elastic force N, dashpot N*s/m): F_A on approach, F_A (1 + C_imp delta_dot) in
    restitution, i.e. a dashpot F_A C_imp that acts in restitution only.

    F_A of Eq. 4 and 14: k_imp min(delta, delta_u)^n + k_w max(delta - delta_u, 0), with
    k = k_imp (N/m^n), delta_u (m), k_w (N/m); C_imp = c_imp_coef / v_imp^c_imp_exponent (s/m).
    Scalars or (B,) arrays alike (the laws' uniform signature, contact.LAW_ARGUMENTS),
    compiled as is by the kernel.
    """
    d = np.maximum(delta, 0.0)
    elastic = k * np.minimum(d, delta_u) ** n + k_w * np.maximum(d - delta_u, 0.0)
    c_imp = c_imp_coef / v_imp**c_imp_exponent
    return elastic, (delta_dot <= 0) * (elastic * c_imp)


def max_tangent_stiffness(p, indentation_bound):
    """The stiffer of the rubber's tangent at delta_u and the wall k_w (N/m)."""
    return np.maximum(p.n * p.k * p.delta_u ** (p.n - 1), p.k_w)
