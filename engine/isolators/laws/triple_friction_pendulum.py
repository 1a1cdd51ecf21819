"""The triple friction pendulum bearing (TFP): the series model of Fenz & Constantinou (2008)
as OpenSees' element TripleFrictionPendulum implements it (Dao et al. 2013).

Sources: Fenz & Constantinou (2008), "Modeling triple friction pendulum bearings for
response-history analysis", Earthquake Spectra 24(4) (the series model), and "Spherical
sliding isolation bearings with adaptive behavior: Theory", EESD 37 (the regimes); Dao, Ryan,
Sato & Sasaki (2013), EESD 42(11) (the element); OpenSees'
SRC/element/special/frictionBearing/TripleFrictionPendulum.cpp, read for this module: its
meanings, its pre-slip and stop stiffnesses (not its code).

Parameters, OpenSees' meanings: L_i the effective radii (m), d_i the surfaces' displacement
limits (m), mu1 the friction of the two inner surfaces, mu2 the lower outer surface's and mu3
the upper outer one's (mu1 <= mu2 <= mu3, L1 < L2, L1 < L3: the regimes assume them), under
the building's weight W = g M (constant: no vertical motion).

Three elements in series (W the weight, all forces in N):
    inner        friction mu1 W, pendulum W / (2 L1),     gap 2 (L1 d3 / L3 + d1)
    lower outer  friction mu2 W, pendulum W / (L2 - L1),  gap d2 (1 - L1 / L2)
    upper outer  friction mu3 W, pendulum W / (L3 - L1),  gap d3 (1 - L1 / L3)
Each is the pendulum spring in parallel with an elastic-perfectly-plastic slip element, so
that before sliding it has the pre-slip stiffness E = 3 mu1 W / yield_disp and slides at a
force of its friction mu_i W (OpenSees' bidirectional element with kinematic hardening H = E
E_p / (E - E_p) is exactly this: slip stiffness E - E_p, slip limit mu_i W (1 - E_p / E)), and
in parallel with a stop: past its gap (|deformation| > gap, on a circle in plan) a spring of
stiffness E on the excess, as OpenSees' CircularElasticGap. OpenSees gives all three elements,
and their stops, the same E = 3 mu1 W / uy (not mu_i W / uy each), so that the series' initial
stiffness is mu1 W / yield_disp and the inner surfaces slide from u = yield_disp on; so does
this law, whose forces are then OpenSees' along any path. In the rigid-plastic limit
(yield_disp -> 0) these are regimes I-V of the bearing: the inner surfaces slide (slope
1 / (2 L1)), then the lower outer one, then the upper one (1 / (L2 + L3)), the lower one stops
at its gap, the upper one, and the inner ones stop at the ultimate displacement; unloading and
reloading are the series model's. The ultimate displacement is the bearing's displacement
capacity (displacement_capacity): a run passing it ends as an isolator-capacity collapse (the
series would stiffen to the stops' E / 3 past it, as OpenSees' element does, where the real
bearing is rigid and fails).

The step (engine/isolators/series.py): the time loops give the displacement increment; the
elements' increments that carry one force are found exactly along one axis (the elements are
piecewise linear: event to event) and in plan by Newton's method on the force, each element's
deformation at a force exact (OpenSees iterates alike, in its TFPElement and Segment), to
round-off. Friction does not depend on the speed here (OpenSees' Coulomb friction model).
"""
import numpy as np

from ...layout import columns
from ...parameters import REQUIRED, Declaration, Parameter
from .. import series
from ..series import elements, step_along, step_in_plan

NAME = "triple_friction_pendulum"
"""The law's name in Isolator.of, building files and archives."""
ORDER = 3
"""Its place in listings."""
DEFAULT_ZETA = 0.0
"""No viscous isolation damping unless one is given: friction is the damping."""
DASHPOT_TEXT = "2 zeta_iso sqrt(k_0 M_tot), k_0 = mu1 W / yield_disp the isolator's initial " \
               "stiffness"
"""The isolation dashpot of damping="paper" in this law's symbols (the archives' provenance)."""

_SOURCE = "Fenz & Constantinou 2008; Dao et al. 2013"
_PLAUSIBLE_RADIUS = "[0.05, 20]"
PARAMETERS = Declaration(
    Parameter("L1", "m", "effective radius L1 of the two inner sliding surfaces", REQUIRED,
              "(0, inf)", equation=_SOURCE, sweep="L1", plausible=_PLAUSIBLE_RADIUS),
    Parameter("L2", "m", "effective radius L2 of the lower outer sliding surface", REQUIRED,
              "(0, inf)", equation=_SOURCE, sweep="L2", plausible=_PLAUSIBLE_RADIUS),
    Parameter("L3", "m", "effective radius L3 of the upper outer sliding surface", REQUIRED,
              "(0, inf)", equation=_SOURCE, sweep="L3", plausible=_PLAUSIBLE_RADIUS),
    Parameter("d1", "m", "displacement limit d1 of each inner sliding surface", REQUIRED,
              "(0, inf)", equation=_SOURCE, sweep="d1", plausible="[0.001, 2]"),
    Parameter("d2", "m", "displacement limit d2 of the lower outer sliding surface", REQUIRED,
              "(0, inf)", equation=_SOURCE, sweep="d2", plausible="[0.001, 2]"),
    Parameter("d3", "m", "displacement limit d3 of the upper outer sliding surface", REQUIRED,
              "(0, inf)", equation=_SOURCE, sweep="d3", plausible="[0.001, 2]"),
    Parameter("mu1", "1", "friction coefficient of the inner sliding surfaces", REQUIRED,
              "(0, 1)", equation=_SOURCE, sweep="mu1"),
    Parameter("mu2", "1", "friction coefficient of the lower outer sliding surface", REQUIRED,
              "(0, 1)", equation=_SOURCE, sweep="mu2"),
    Parameter("mu3", "1", "friction coefficient of the upper outer sliding surface", REQUIRED,
              "(0, 1)", equation=_SOURCE, sweep="mu3"),
    Parameter("yield_disp", "m", "displacement at which the inner surfaces start to slide "
              "(OpenSees' uy: every element's pre-slip stiffness is 3 mu1 W / yield_disp)",
              5e-4, "(0, inf)", equation="Dao et al. 2013", sweep="yield_disp",
              plausible="[1e-5, 0.05]"),
)


def _elements(mass, g, values):
    """((pendulum stiffness N/m, friction force N, gap m) of the inner, lower and upper
    elements, the pre-slip and stop stiffness E N/m) of the law's values (by name)."""
    weight = g * mass
    l1, l2, l3 = values["L1"], values["L2"], values["L3"]
    inner = (weight / (2.0 * l1), values["mu1"] * weight,
             2.0 * (l1 * values["d3"] / l3 + values["d1"]))
    lower = (weight / (l2 - l1), values["mu2"] * weight, values["d2"] * (1.0 - l1 / l2))
    upper = (weight / (l3 - l1), values["mu3"] * weight, values["d3"] * (1.0 - l1 / l3))
    return (inner, lower, upper), 3.0 * values["mu1"] * weight / values["yield_disp"]


def check(**values):
    """The regimes' assumptions (ValueError otherwise): L1 < L2 and L1 < L3 (an outer surface
    flatter than the inner ones), mu1 <= mu2 <= mu3 (the inner surfaces slide first, the upper
    one last), and a pre-slip stiffness 3 mu1 W / yield_disp above every element's pendulum
    stiffness (yield_disp < 6 mu1 L1 and < 3 mu1 (L_j - L1))."""
    l1, l2, l3 = values["L1"], values["L2"], values["L3"]
    mu1, mu2, mu3 = values["mu1"], values["mu2"], values["mu3"]
    if not (l1 < l2 and l1 < l3):
        raise ValueError(f"a triple friction pendulum needs L1 < L2 and L1 < L3 (the inner "
                         f"surfaces the most curved), got L1={l1}, L2={l2}, L3={l3}")
    if not mu1 <= mu2 <= mu3:
        raise ValueError(f"a triple friction pendulum needs mu1 <= mu2 <= mu3 (the inner "
                         f"surfaces slide first, the upper one last), got mu1={mu1}, "
                         f"mu2={mu2}, mu3={mu3}")
    parts, stop = _elements(1.0, 1.0, values)
    if not all(stop > pendulum for pendulum, _, _ in parts):
        raise ValueError(f"yield_disp={values['yield_disp']} is too large: the pre-slip "
                         f"stiffness 3 mu1 W / yield_disp must exceed every element's "
                         f"pendulum stiffness (yield_disp < 6 mu1 L1 and < 3 mu1 (L2 - L1), "
                         f"3 mu1 (L3 - L1))")


def displacement_capacity(mass, g, **values):
    """The ultimate displacement (m), where the sliders meet the restrainers:
    2 d1 + d2 + d3 + L1 d3 / L3 - L1 d2 / L2 (the three elements' gaps; 0.600 m in Dao et
    al.'s check case)."""
    return sum(gap for _, _, gap in _elements(1.0, 1.0, values)[0])


def yield_displacement(mass, g, **values):
    """yield_disp (m): where the inner surfaces start to slide (the series reaches mu1 W)."""
    return values["yield_disp"]


def initial_stiffness(mass, g, **values):
    """mu1 W / yield_disp (N/m), W = g M: the three elements' pre-slip stiffness E in series
    (OpenSees' initial stiffness). Unloading past a stop is stiffer, up to 2 E / 3 with every
    element past its gap."""
    return values["mu1"] * g * mass / values["yield_disp"]


def backbone(mass, g, displacement, **values):
    """The force (N) of the rigid-plastic series model (yield_disp -> 0) pushed monotonically
    to displacement D (m, >= 0, scalar or array): D is the sum of the elements' slides
    clip((F - mu_i W) / k_i, 0, gap_i), k_i their pendulum stiffnesses (regimes I-V of Fenz &
    Constantinou 2008), the force at D interpolated between the regimes' corners. Past the
    ultimate displacement (every element at its stop) the slope is the law's, 1 / sum 1 / (k_i
    + E) (OpenSees' stops; the real bearing is rigid there)."""
    parts, stop = _elements(mass, g, values)
    corners = np.unique([force for pendulum, friction, gap in parts
                         for force in (friction, friction + pendulum * gap)])
    slid = sum(np.clip((corners - friction) / pendulum, 0.0, gap)
               for pendulum, friction, gap in parts)
    stiff = 1.0 / sum(1.0 / (pendulum + stop) for pendulum, _, _ in parts)
    d = np.asarray(displacement, dtype=float)
    force = np.where(d > 0.0, np.interp(d, slid, corners), 0.0)  # mu1 W from D = 0+ on
    return force + stiff * np.maximum(d - slid[-1], 0.0)


def _slides(mass, g, displacement, values):
    """Each element's slide (m) on the backbone at displacement D (m, one number)."""
    parts, _ = _elements(mass, g, values)
    force = float(backbone(mass, g, displacement, **values))
    return [(friction, float(np.clip((force - friction) / pendulum, 0.0, gap)))
            for pendulum, friction, gap in parts]


def effective_stiffness(mass, g, displacement, **values):
    """Secant stiffness (N/m) at displacement D (m, scalar or array): F(D) / D on the
    rigid-plastic backbone (`backbone`; ASCE 7-22 chapter 17's k_eff of the series model,
    Fenz & Constantinou 2008; the pre-slip displacement neglected, as for the friction
    pendulum)."""
    return backbone(mass, g, displacement, **values) / displacement


def post_yield_stiffness(mass, g, **values):
    """W / (L2 + L3) (N/m): regime III's stiffness, every surface sliding (the K_d of a TFP,
    Sarlis & Constantinou 2013). The secant stiffness exceeds it at every displacement and
    tends to it while regime III lasts; past it the bearing stiffens."""
    return g * mass / (values["L2"] + values["L3"])


def energy_per_cycle(mass, g, displacement, **values):
    """Energy (J) dissipated per cycle at displacement amplitude D (m, one number): 4 sum mu_i
    W x_i, x_i each element's slide on the backbone at D (each element's loop is its
    friction over twice its slide each way; a stopped element slides no further): the loop of
    the series model (Fenz & Constantinou 2008; ASCE 7-22 chapter 17's E_M; the pre-slip
    displacement neglected)."""
    return 4.0 * sum(friction * slide
                     for friction, slide in _slides(mass, g, displacement, values))


def bounded(values, lambda_q, lambda_k):
    """The parameters at property modification factors lambda_q on the characteristic strength
    (the friction: mu1, mu2 and mu3 scaled, their order kept) and lambda_k on the post-yield
    stiffness (ASCE 7-22 17.2.8.4): the radii and limits are geometry, kept (lambda_k unused),
    as the pre-slip displacement."""
    return {**values, **{name: lambda_q * values[name] for name in ("mu1", "mu2", "mu3")}}


ROW = columns("TripleFrictionPendulumRow", *series.ROW)
"""The constants the time loops read, per element (inner, lower outer, upper outer): its
pendulum stiffness k_i (N/m), its slip element's stiffness E - k_i (N/m) and limit mu_i W (1 -
k_i / E) (N), its gap (m); then the stops' stiffness E (N/m) (engine/isolators/series.py)."""
CARRIED = tuple(name for name in ROW._fields if not name.startswith("gap"))
"""The constants proportional to the weight the bearing carries (the gaps are geometry)."""
STATE = columns("TripleFrictionPendulumState", *series.STATE)
"""Along one axis: each element's deformation (m) and slip element's force (N), and the
bearing's force (N)."""
STATE_XY = columns("TripleFrictionPendulumStateXY", *series.STATE_XY)
"""In plan: the same along x and y, and the series' tangent stiffness (N/m) where the last
step ended (the next step's first Newton step)."""


def fields(mass, g, **values):
    """ROW by name: each element's pendulum, slip stiffness and limit, gap; the stops' E."""
    parts, stop = _elements(mass, g, values)
    out = {}
    for name, (pendulum, friction, gap) in zip(series.ELEMENTS, parts, strict=True):
        out.update({f"pendulum_{name}": pendulum, f"slip_{name}": stop - pendulum,
                    f"limit_{name}": friction * (1.0 - pendulum / stop), f"gap_{name}": gap})
    return {**out, "stop": stop}


def force(u, state, row):
    """The bearing's force (N) at displacement u (m): the force its elements carry after the
    last step (which ended at u)."""
    return state[STATE.bearing_force]


def advance(state, velocity, dt, row):
    """The elements after a step of dt (s) at `velocity` (m/s): the increment dt velocity
    shared among them with one force, event to event (exact: series.step_along)."""
    step_along(state, dt * velocity, elements(row))


def force_xy(ux, uy, state, row):
    """In plan: the force (N, x and y) its elements carry after the last step."""
    return state[STATE_XY.bearing_force_x], state[STATE_XY.bearing_force_y]


def advance_xy(state, vx, vy, dt, row):
    """In plan: the elements after a step of dt (s) at velocity (vx, vy) (m/s), the force
    they carry converged by Newton's method (series.step_in_plan)."""
    step_in_plan(state, dt * vx, dt * vy, elements(row))
