"""The bilinear isolator (SPEC section 1, the paper's lead-rubber bearings): an elastic K2
spring in parallel with an elastic-perfectly-plastic spring of stiffness K1 - K2 that yields at
(K1 - K2) u_y, u_y = Fy / K1, Fy = fy_ratio g M (M: the mass of the whole building).
Exact return mapping (engine/isolators/hysteresis.py); the limit does not depend on speed.
"""
import numpy as np

from ...layout import columns
from ...parameters import Declaration, Parameter
from ..hysteresis import (
    isolator_force,
    isolator_force_xy,
    plastic_spring_force,
    radial_return,
)

NAME = "bilinear"
"""The law's name in Isolator.of, building files and archives."""
ORDER = 1
"""Its place in listings."""
DEFAULT_ZETA = 0.05
"""Isolation damping ratio on K1 unless one is given (SPEC decision, the paper's 5%)."""
DASHPOT_TEXT = "2 zeta_iso sqrt(k1 M_tot)"
"""The isolation dashpot of damping="paper" in this law's symbols (the archives' provenance)."""

PARAMETERS = Declaration(
    Parameter("k1", "N m-1", "isolator initial stiffness K1", 200e6, "(0, inf)",
              equation="SPEC section 1", sweep="k1", plausible="[1e5, 1e11]"),
    Parameter("k2", "N m-1", "isolator post-yield stiffness K2", 25e6, "(0, inf)",
              equation="SPEC section 1", sweep="k2", plausible="[1e5, 1e11]"),
    Parameter("fy_ratio", "1", "isolator yield force Fy as a fraction of the building's weight",
              0.1, "(0, inf)", equation="SPEC section 1", sweep="fy_ratio"),
    Parameter("capacity", "m", "displacement capacity: where the bearing meets its restrainer "
              "or fails, a run passing it ends as a collapse (unset: none)", None, "(0, inf)",
              plausible="[0.02, 5]"),
)


def check(k1, k2, fy_ratio, capacity=None):
    """The law's own consistency: 0 < K2 < K1 (ValueError otherwise)."""
    if not 0 < k2 < k1:
        raise ValueError(f"isolator stiffness needs 0 < k2 < k1, got k1={k1}, k2={k2}")


def displacement_capacity(mass, g, k1, k2, fy_ratio, capacity=None):
    """The displacement capacity (m): the `capacity` given, inf unset."""
    return float("inf") if capacity is None else capacity


def yield_displacement(mass, g, k1, k2, fy_ratio, capacity=None):
    """u_y = Fy / K1 (m), Fy = fy_ratio g M."""
    return fy_ratio * g * mass / k1


def initial_stiffness(mass, g, k1, k2, fy_ratio, capacity=None):
    """K1 (N/m)."""
    return k1


def effective_stiffness(mass, g, displacement, k1, k2, fy_ratio, capacity=None):
    """Secant stiffness (N/m) at displacement D (m, scalar or array): (K1 min(D, u_y) +
    K2 max(D - u_y, 0)) / D, the equivalent-linear isolator of ASCE 7 chapter 17."""
    u_y = yield_displacement(mass, g, k1, k2, fy_ratio)
    return (k1 * np.minimum(displacement, u_y) + k2 * np.maximum(displacement - u_y, 0.0)) \
        / displacement


def post_yield_stiffness(mass, g, k1, k2, fy_ratio, capacity=None):
    """K2 (N/m): the stiffness the secant stiffness tends to at large displacements."""
    return k2


def energy_per_cycle(mass, g, displacement, k1, k2, fy_ratio, capacity=None):
    """Energy (J) dissipated per cycle at displacement amplitude D (m, one number): the area of
    the loop, 4 Q_d (D - D_y) past yield and 0 before, Q_d = (K1 - K2) D_y the characteristic
    strength (the loop's half-height), D_y = u_y (ASCE 7 chapter 17's E_M of a bilinear
    isolator)."""
    d_y = yield_displacement(mass, g, k1, k2, fy_ratio)
    q_d = (k1 - k2) * d_y  # characteristic strength: the loop's half-height
    return 4 * q_d * max(displacement - d_y, 0.0)


ROW = columns("BilinearRow", "k_elastic", "k_slip", "f_limit")
"""The constants the time loops read: the elastic spring K2 (N/m), the slip element's
stiffness K1 - K2 (N/m) and its limit force (N)."""
CARRIED = ROW._fields
"""Every constant is proportional to the weight the bearing carries."""
STATE = columns("BilinearState", "slip_force")
"""Along one axis: the slip element's force (N)."""
STATE_XY = columns("BilinearStateXY", "slip_force_x", "slip_force_y")
"""In plan: the slip element's force along x and y (N)."""


def fields(mass, g, k1, k2, fy_ratio, capacity=None):
    """ROW by name: K2 elastic; K1 - K2 slipping at (K1 - K2) u_y, whatever the speed."""
    k_slip = k1 - k2
    return {"k_elastic": k2, "k_slip": k_slip,
            "f_limit": k_slip * yield_displacement(mass, g, k1, k2, fy_ratio)}


def force(u, state, row):
    """The isolator's force (N) at displacement u (m): the spring's plus the slip element's."""
    return isolator_force(u, state[STATE.slip_force], row[ROW.k_elastic])


def advance(state, velocity, dt, row):
    """The slip element after a step of dt (s) at `velocity` (m/s), return-mapped."""
    state[STATE.slip_force] = plastic_spring_force(
        state[STATE.slip_force], dt * velocity, row[ROW.k_slip], row[ROW.f_limit])


def force_xy(ux, uy, state, row):
    """In plan: the force (N, x and y) at displacement (ux, uy) (m)."""
    return isolator_force_xy(ux, uy, state[STATE_XY.slip_force_x],
                             state[STATE_XY.slip_force_y], row[ROW.k_elastic])


def advance_xy(state, vx, vy, dt, row):
    """In plan: the slip element after a step of dt (s) at velocity (vx, vy) (m/s),
    return-mapped onto its circle."""
    state[STATE_XY.slip_force_x], state[STATE_XY.slip_force_y] = radial_return(
        state[STATE_XY.slip_force_x], state[STATE_XY.slip_force_y], dt * vx, dt * vy,
        row[ROW.k_slip], row[ROW.f_limit])


def bounded(values, lambda_q, lambda_k):
    """The parameters at property modification factors lambda_q on the characteristic strength
    Q_d = (K1 - K2) u_y and lambda_k on the post-yield stiffness K_d = K2 (ASCE 7-22 17.2.8.4),
    the yield displacement u_y = fy_ratio W / K1 kept (the usual bounding convention: the lead
    core's yield displacement is a property of its geometry): K2 -> lambda_k K2, K1 ->
    lambda_q (K1 - K2) + lambda_k K2, fy_ratio -> fy_ratio K1' / K1."""
    k1, k2 = values["k1"], values["k2"]
    k1_new = lambda_q * (k1 - k2) + lambda_k * k2
    return {**values, "k1": k1_new, "k2": lambda_k * k2,
            "fy_ratio": values["fy_ratio"] * k1_new / k1}
