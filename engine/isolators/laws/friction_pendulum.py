"""The single friction pendulum bearing (SPEC section 7): a concave sliding surface of radius
R under the weight W of the building (constant: no vertical motion), i.e. a restoring spring
W / R in parallel with Coulomb friction mu(|v|) W, with the velocity dependence of Constantinou
et al. (1990): mu(v) = mu_fast - (mu_fast - mu_slow) exp(-rate |v|). Before sliding the bearing
is elastic with the constant pre-slip stiffness k_0 = mu_fast W / yield_disp (as OpenSees'
bearings keep theirs), which the stability limit accounts for. Friction is the isolation's
damping: no viscous isolation damping unless a zeta_iso is given (then on k_0 + W / R).
Exact return mapping (engine/isolators/hysteresis.py), the friction limit at the step's
sliding speed.
"""
import numpy as np

from ...layout import columns
from ...parameters import REQUIRED, Declaration, Parameter
from ..hysteresis import (
    isolator_force,
    isolator_force_xy,
    plastic_spring_force,
    radial_return,
    slip_limit,
)

NAME = "friction_pendulum"
"""The law's name in Isolator.of, building files and archives."""
ORDER = 2
"""Its place in listings."""
DEFAULT_ZETA = 0.0
"""No viscous isolation damping unless one is given: friction is the damping."""
DASHPOT_TEXT = "2 zeta_iso sqrt(k_0 M_tot), k_0 the isolator's initial stiffness"
"""The isolation dashpot of damping="paper" in this law's symbols (the archives' provenance)."""

PARAMETERS = Declaration(
    Parameter("radius", "m", "radius R of the concave sliding surface", REQUIRED, "(0, inf)",
              equation="SPEC section 7", sweep="radius", plausible="[0.2, 20]"),
    Parameter("mu_slow", "1", "friction coefficient at low sliding speed", REQUIRED, "(0, 1)",
              equation="Constantinou et al. 1990", sweep="mu_slow"),
    Parameter("mu_fast", "1", "friction coefficient at high sliding speed", REQUIRED, "(0, 1)",
              equation="Constantinou et al. 1990", sweep="mu_fast"),
    Parameter("rate", "s m-1", "rate of the change from mu_slow to mu_fast with the sliding "
              "speed", REQUIRED, "[0, inf)", equation="Constantinou et al. 1990", sweep="rate"),
    Parameter("yield_disp", "m", "sliding displacement at which the pre-slip spring reaches "
              "mu_fast W (sets k_0 = mu_fast W / yield_disp)", 5e-4, "(0, inf)",
              equation="SPEC section 7", sweep="yield_disp", plausible="[1e-5, 0.05]"),
    Parameter("capacity", "m", "displacement capacity: where the bearing meets its restrainer "
              "or fails, a run passing it ends as a collapse (unset: none)", None, "(0, inf)",
              plausible="[0.02, 5]"),
)


def check(radius, mu_slow, mu_fast, rate, yield_disp, capacity=None):
    """mu_slow <= mu_fast (ValueError otherwise): friction rises with the sliding speed."""
    if not mu_slow <= mu_fast:
        raise ValueError(f"friction needs mu_slow <= mu_fast, got mu_slow={mu_slow}, "
                         f"mu_fast={mu_fast}")


def displacement_capacity(mass, g, radius, mu_slow, mu_fast, rate, yield_disp, capacity=None):
    """The displacement capacity (m): the `capacity` given, inf unset."""
    return float("inf") if capacity is None else capacity


def yield_displacement(mass, g, radius, mu_slow, mu_fast, rate, yield_disp, capacity=None):
    """yield_disp (m): where the pre-slip spring reaches the fast friction force."""
    return yield_disp


def initial_stiffness(mass, g, radius, mu_slow, mu_fast, rate, yield_disp, capacity=None):
    """k_0 + W / R (N/m), W = g M: pre-slip spring and pendulum together."""
    weight = g * mass
    return mu_fast * weight / yield_disp + weight / radius


def effective_stiffness(mass, g, displacement, radius, mu_slow, mu_fast, rate, yield_disp,
                        capacity=None):
    """Secant stiffness (N/m) at displacement D (m, past yield_disp): W / R + mu_fast W / D
    (the friction at the speeds of a design-level motion; ASCE 7 chapter 17's k_eff)."""
    weight = g * mass
    return weight / radius + mu_fast * weight / displacement


def post_yield_stiffness(mass, g, radius, mu_slow, mu_fast, rate, yield_disp, capacity=None):
    """W / R (N/m), W = g M: the pendulum's stiffness, which the secant stiffness tends to at
    large displacements."""
    weight = g * mass
    return weight / radius


def energy_per_cycle(mass, g, displacement, radius, mu_slow, mu_fast, rate, yield_disp,
                     capacity=None):
    """Energy (J) dissipated per cycle at displacement amplitude D (m): 4 mu W D with
    mu = mu_fast, W = g M (the friction effective_stiffness uses; the pre-slip displacement
    neglected, as there: ASCE 7 chapter 17's E_M of a sliding isolator)."""
    weight = g * mass
    return 4 * mu_fast * weight * displacement


ROW = columns("FrictionPendulumRow", "k_elastic", "k_slip", "f_limit", "slow_drop", "rate")
"""The constants the time loops read: the pendulum's stiffness W / R (N/m), the pre-slip
stiffness k_0 (N/m), the fast friction force mu_fast W (N), its drop at low speed
(mu_fast - mu_slow) / mu_fast and the rate of the change (s/m)."""
CARRIED = ("k_elastic", "k_slip", "f_limit")
"""The constants proportional to the weight the bearing carries."""
STATE = columns("FrictionPendulumState", "slip_force")
"""Along one axis: the friction force (N)."""
STATE_XY = columns("FrictionPendulumStateXY", "slip_force_x", "slip_force_y")
"""In plan: the friction force along x and y (N)."""


def fields(mass, g, radius, mu_slow, mu_fast, rate, yield_disp, capacity=None):
    """ROW by name: W / R elastic; k_0 slipping at mu(|v|) W = mu_fast W (1 - slow_drop
    exp(-rate |v|))."""
    weight = g * mass
    return {"k_elastic": weight / radius, "k_slip": mu_fast * weight / yield_disp,
            "f_limit": mu_fast * weight, "slow_drop": (mu_fast - mu_slow) / mu_fast,
            "rate": rate}


def force(u, state, row):
    """The bearing's force (N) at displacement u (m): the pendulum's plus the friction."""
    return isolator_force(u, state[STATE.slip_force], row[ROW.k_elastic])


def advance(state, velocity, dt, row):
    """The friction after a step of dt (s) at `velocity` (m/s): return-mapped, its limit at
    this speed (exactly mu_fast W where mu_slow = mu_fast)."""
    limit = slip_limit(row[ROW.f_limit], row[ROW.slow_drop], row[ROW.rate], velocity)
    state[STATE.slip_force] = plastic_spring_force(state[STATE.slip_force], dt * velocity,
                                                   row[ROW.k_slip], limit)


def force_xy(ux, uy, state, row):
    """In plan: the force (N, x and y) at displacement (ux, uy) (m)."""
    return isolator_force_xy(ux, uy, state[STATE_XY.slip_force_x],
                             state[STATE_XY.slip_force_y], row[ROW.k_elastic])


def advance_xy(state, vx, vy, dt, row):
    """In plan: the friction after a step of dt (s) at velocity (vx, vy) (m/s), return-mapped
    onto its circle, whose radius is the limit at the sliding speed |v|."""
    limit = slip_limit(row[ROW.f_limit], row[ROW.slow_drop], row[ROW.rate], np.hypot(vx, vy))
    state[STATE_XY.slip_force_x], state[STATE_XY.slip_force_y] = radial_return(
        state[STATE_XY.slip_force_x], state[STATE_XY.slip_force_y], dt * vx, dt * vy,
        row[ROW.k_slip], limit)


def bounded(values, lambda_q, lambda_k):
    """The parameters at property modification factors lambda_q on the characteristic strength
    (the friction, mu W: mu_slow and mu_fast scaled) and lambda_k on the post-yield stiffness
    K_d = W / R (ASCE 7-22 17.2.8.4): the radius is geometry, kept (lambda_k unused), as the
    pre-slip displacement."""
    return {**values, "mu_slow": lambda_q * values["mu_slow"],
            "mu_fast": lambda_q * values["mu_fast"]}
