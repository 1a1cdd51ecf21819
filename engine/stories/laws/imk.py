"""The modified Ibarra-Medina-Krawinkler (IMK) deteriorating story: a bilinear hysteresis
bounded by a backbone that hardens to a capping point, then softens to a residual strength and
drops to zero at an ultimate drift, the backbone and the unloading stiffness shrinking with the
hysteretic energy the story has dissipated.

Sources: Ibarra, Medina & Krawinkler (2005), "Hysteretic models that incorporate strength and
stiffness deterioration", Earthquake Engng Struct. Dyn. 34:1489-1511 (the model and its energy
rule); Lignos & Krawinkler (2011), "Deterioration modeling of steel components in support of
collapse prediction of steel moment frames under earthquake loading", J. Struct. Eng.
137(11):1291-1302 (the modified backbone, E_t = Lambda F_y, and the typical values used as
defaults here). It reproduces OpenSees's uniaxial material IMKBilin in its Nov. 2022 version
("IMK with Bilinear Response - Code by AE_KI (Nov22)", as openseespy 3.7.1.2 runs it), step
for step, but where that material contradicts the model (below).

Units: SI. Drift (the story's deformation) and every deformation parameter in m, forces in N,
energies in J. The elastic stiffness K_e is the building's story stiffness (N/m), not a
parameter of the law.

Backbone (monotonic push, either sign): K_e d up to the yield drift d_y = F_y / K_e; then the
hardening line to the capping point (d_y + theta_p, F_c), F_c = capping_ratio F_y; then the
post-capping line of slope -F_c / theta_pc (theta_pc: drift from the capping point to zero
strength), floored at the residual strength F_r = residual_ratio F_y; zero from the ultimate
drift theta_u on (or where the post-capping line reaches zero, F_r = 0), for good in that
direction, the other direction then keeping only F_r.

Hysteresis (bilinear, kinematic): unloading and reloading run along the unloading stiffness
K_u (K_e at first) until they meet the current backbone of the direction of motion, which
bounds the force from above in that direction only and never below F_r (a reloading branch
can reach F_r before crossing zero drift).

Cyclic deterioration (Lignos & Krawinkler 2011, after Ibarra et al. 2005): each time the force
crosses zero while off the backbone, a new excursion starts and the backbone of its direction
shrinks by beta_i = (E_i / (E_t - sum_{j<=i} E_j))^c, E_i the energy of the excursion just
ended, sum E_j all the energy dissipated so far: the yield strength and hardening slope by
beta_s (E_t = lambda_s F_y theta_p), the post-capping line's intercept by beta_c (E_t =
lambda_c F_y theta_p); each reversal from the backbone shrinks K_u by beta_k (E_t = lambda_k
F_y theta_p, energies net of the elastic energy stored at the reversal). The lambdas here are
therefore dimensionless: Lignos & Krawinkler's Lambda (a cumulative plastic deformation)
divided by theta_p, so that they do not depend on the story's size (OpenSees's Lamda =
lambda theta_p). A beta above 1 is complete deterioration: the story loses its strength in both
directions for good. Once the residual branch has been reached in either direction, IMKBilin
unloads along K_e / 2 from every later reversal (even where the deteriorated K_u was smaller),
and so does this law.

Assumptions: symmetric properties (OpenSees's positive set used for both directions, and one
deterioration factor D = D_pos = D_neg, 1 by default), although each direction's backbone
deteriorates on its own excursions. Each call of `force` is one trial state committed at once
(OpenSees's setTrialStrain then commitState): the law is path dependent and, like OpenSees,
mildly step dependent (the excursion energies are trapezoidal sums over the steps), so the same
steps give OpenSees's forces.

Where it differs from IMKBilin, deliberately: the ratio's denominator E_t - sum E_j at or below
zero (the capacity exhausted, which one large excursion reaches without any earlier beta
exceeding 1) fails the story, as Ibarra et al. (2005) prescribe (beta outside (0, 1]: the
energy capacity is exhausted); IMKBilin takes the negative ratio to the power c and clips the
result to [0, 1], so that with c = 1 its story stops deteriorating for good and keeps its
current strength (a non-integer c gives NaN there). A negative numerator (an unloading-stiffness
excursion whose energy is less than the elastic energy stored) deteriorates nothing here, as
in IMKBilin for c = 1, whereas IMKBilin deteriorates on it for an even c (c = 2 squares the
negative ratio) and gives NaN for a non-integer c. With c = 1 and the capacity not exhausted
the two agree to rounding.
"""
import math

import numpy as np

from ...parameters import REQUIRED, Declaration, Parameter

NAME = "imk"
"""The law's name in building files and archives."""
ORDER = 3
"""Its place in listings (linear 1, bilinear 2)."""

_LK2011 = "Lignos & Krawinkler 2011"

PARAMETERS = Declaration(
    Parameter("yield_force", "N", "story yield strength F_y (effective yield)", REQUIRED,
              "(0, inf)", equation="Ibarra et al. 2005", plausible="[1e3, 1e10]"),
    Parameter("capping_ratio", "1", "capping (peak) to yield strength ratio F_c/F_y: 1.11, "
              "bare other-than-RBS steel beams (" + _LK2011 + ")", 1.11, "[1, inf)",
              equation=_LK2011, plausible="[1, 2]"),
    Parameter("plastic_deformation", "m", "pre-capping plastic drift theta_p, from yield to "
              "the capping point", REQUIRED, "(0, inf)", equation=_LK2011,
              plausible="[1e-4, 1]"),
    Parameter("post_capping_deformation", "m", "post-capping drift theta_pc, from the "
              "capping point to zero strength (inf: no softening)", REQUIRED, "(0, inf]",
              equation=_LK2011, plausible="[1e-3, inf]"),
    Parameter("ultimate_deformation", "m", "ultimate drift theta_u, where the strength "
              "drops to zero for good (inf: none)", math.inf, "(0, inf]", equation=_LK2011),
    Parameter("residual_ratio", "1", "residual to yield strength ratio F_r/F_y: 0.4, steel "
              "beams (" + _LK2011 + ")", 0.4, "[0, 1)", equation=_LK2011),
    Parameter("lambda_s", "1", "yield-strength deterioration capacity E_t/(F_y theta_p): "
              "about 50 (Lambda/theta_p of the " + _LK2011 + " beam regressions; for a story "
              "unverified); inf: none", 50.0, "(0, inf]",
              equation="Ibarra et al. 2005, beta_i = (E_i/(E_t - sum E_j))^c",
              plausible="[5, inf]"),
    Parameter("lambda_c", "1", "post-capping-strength deterioration capacity E_t/(F_y "
              "theta_p): as lambda_s (" + _LK2011 + "; unverified); inf: none", 50.0,
              "(0, inf]", equation="Ibarra et al. 2005", plausible="[5, inf]"),
    Parameter("lambda_k", "1", "unloading-stiffness deterioration capacity E_t/(F_y "
              "theta_p): as lambda_s (" + _LK2011 + "; unverified); inf: none", 50.0,
              "(0, inf]", equation="Ibarra et al. 2005", plausible="[5, inf]"),
    Parameter("c_s", "1", "exponent c of the yield-strength deterioration: 1 ("
              + _LK2011 + ")", 1.0, "(0, inf)", equation="Ibarra et al. 2005",
              plausible="[1, 2]"),
    Parameter("c_c", "1", "exponent c of the post-capping deterioration: 1 (" + _LK2011
              + ")", 1.0, "(0, inf)", equation="Ibarra et al. 2005", plausible="[1, 2]"),
    Parameter("c_k", "1", "exponent c of the unloading-stiffness deterioration: 1 ("
              + _LK2011 + ")", 1.0, "(0, inf)", equation="Ibarra et al. 2005",
              plausible="[1, 2]"),
    Parameter("deterioration_factor", "1", "share D of each cyclic deterioration applied, "
              "both directions (OpenSees D_pos = D_neg)", 1.0, "[0, 1]",
              equation="Lignos & Krawinkler 2011"),
)

# The per-story constants the step reads (fields' columns).
KE, FY0, FRES, KP0, KPC0, UCAP0, FCAP0, UU, EREF_S, EREF_C, EREF_K, C_S, C_C, C_K, D = range(15)
N_FIELDS = 15

# The committed state: the last drift and force, the unloading stiffness, the energies, the
# flags, then each direction's current backbone. The negative direction's is stored mirrored
# (drift and force of opposite sign, so every number is as for a push), so that one code path
# serves both directions.
U, F, K_UNLOAD, ENERGY, ENERGY_START, FAILURE, ON_BACKBONE = range(7)
POSITIVE, NEGATIVE = 7, 12
# Offsets in a direction's block: yield strength, hardening slope, post-capping slope (its
# magnitude), capping drift, capping strength.
B_FY, B_KP, B_KPC, B_UCAP, B_FCAP = range(5)
# Then the drifts (m) between which a step is common (`_elastic_range`), set wherever the rest
# of the state changes.
LOW, HIGH, N_STATE = 17, 18, 19
ELASTIC_MARGIN = 1e-9
"""How far (a share of the virgin capping strength, N/N) that range keeps the force from each
limit: far beyond the rounding of the steps along the line, so that every step it admits is
one the exact tests would find common, with the same bits."""

# FAILURE: 0 elastic so far, 1 yielded, 2 residual branch reached (unloading along K_e/2 from
# then on), 3 strength lost pushing positive, 4 lost pushing negative, 5 lost both ways.


def check(**values):
    """The law's own consistency (ValueError otherwise) from its values (PARAMETERS, by
    name): the ultimate drift, a total drift, beyond the plastic drift theta_p (it has to
    leave room for the hardening branch). The ranges already keep F_r < F_y <= F_c."""
    ultimate_deformation = values["ultimate_deformation"]
    plastic_deformation = values["plastic_deformation"]
    if np.any(np.asarray(ultimate_deformation) <= np.asarray(plastic_deformation)):
        raise ValueError(f"ultimate_deformation is a total drift beyond the capping point: it "
                         f"must exceed plastic_deformation, got {ultimate_deformation} <= "
                         f"{plastic_deformation}")


def fields(stiffness, **values):
    """(N, N_FIELDS) per-story constants from the story stiffnesses K_e (N/m) and the law's
    values (PARAMETERS by name), each (N,): the virgin backbone's corners and slopes and the
    reference energies E_t = lambda F_y theta_p (J), so that the step computes none of them."""
    ke = np.asarray(stiffness, dtype=float)
    fy = np.asarray(values["yield_force"], dtype=float)
    theta_p = np.asarray(values["plastic_deformation"], dtype=float)
    f_cap = values["capping_ratio"] * fy
    out = np.empty((ke.size, N_FIELDS))
    out[:, KE] = ke
    out[:, FY0] = fy
    out[:, FRES] = values["residual_ratio"] * fy
    out[:, KP0] = (f_cap - fy) / theta_p
    out[:, KPC0] = f_cap / values["post_capping_deformation"]  # 0 when theta_pc is inf
    out[:, UCAP0] = fy / ke + theta_p
    out[:, FCAP0] = f_cap
    out[:, UU] = values["ultimate_deformation"]
    for column, factor in ((EREF_S, "lambda_s"), (EREF_C, "lambda_c"), (EREF_K, "lambda_k")):
        out[:, column] = values[factor] * fy * theta_p
    for column, name in ((C_S, "c_s"), (C_C, "c_c"), (C_K, "c_k"), (D, "deterioration_factor")):
        out[:, column] = values[name]
    return out


def strength(stiffness, **values):
    """(N,) the largest force each story carries (N): the virgin capping strength
    capping_ratio F_y (deterioration only lowers it)."""
    return np.asarray(values["capping_ratio"] * np.asarray(values["yield_force"], dtype=float),
                      dtype=float) * np.ones(len(stiffness))


def initial_state(par):
    """(N_STATE,) state of a virgin story (field row `par`): at rest, unloading along K_e,
    both backbones the monotonic one."""
    state = np.zeros(N_STATE)
    state[K_UNLOAD] = par[KE]
    for block in (POSITIVE, NEGATIVE):
        state[block + B_FY] = par[FY0]
        state[block + B_KP] = par[KP0]
        state[block + B_KPC] = par[KPC0]
        state[block + B_UCAP] = par[UCAP0]
        state[block + B_FCAP] = par[FCAP0]
    _elastic_range(state, par)
    return state


def backbone(deformation, par):
    """Monotonic backbone force (N) at drift(s) `deformation` (m) of a virgin story (field row
    `par`): elastic, hardening to the capping point, post-capping down to the residual
    strength, zero from the ultimate drift on; odd in the drift."""
    d = np.asarray(deformation, dtype=float)
    a = np.abs(d)
    slope = np.where(a < par[UCAP0], par[KP0], -par[KPC0])
    bound = np.maximum(par[FCAP0] + (a - par[UCAP0]) * slope, par[FRES])
    f = np.where(a >= par[UU], 0.0, np.minimum(par[KE] * a, bound))
    return np.sign(d) * f


def _backbone(state, block, u_local):
    """The current backbone of a direction (its state block) at the drift u_local (m, in the
    direction's frame) before the residual floor: the hardening line up to the capping drift,
    the post-capping line past it (N)."""
    ucap = state[block + B_UCAP]
    if u_local < ucap:
        slope = state[block + B_KP]
    else:
        slope = -state[block + B_KPC]
    return state[block + B_FCAP] + (u_local - ucap) * slope


def _on_residual(state, drift, f, fres):
    """Whether the story is on or past the residual branch in either direction at drift (m)
    and force f (N): past the drift where a direction's post-capping line meets the residual
    strength fres (N), or, for a backbone without post-capping slope, at that strength."""
    residual = False
    for side in (POSITIVE, NEGATIVE):
        sign = 1.0 if side == POSITIVE else -1.0
        kpc = state[side + B_KPC]
        if kpc == 0.0:
            residual = residual or sign * f == fres
        else:
            u_res = state[side + B_UCAP] + (state[side + B_FCAP] - fres) / kpc
            residual = residual or sign * drift >= u_res
    return residual


def _limit(low, high, gap, slope, margin):
    """The offsets (low, high) from the committed drift (m) narrowed to where gap + slope x (N,
    x the offset, slope N/m) stays above margin (N); empty (inf, -inf) if not at x = 0."""
    if not gap > margin:
        return math.inf, -math.inf
    if slope > 0.0:
        low = max(low, (margin - gap) / slope)
    elif slope < 0.0:
        high = min(high, (margin - gap) / slope)
    return low, high


def _elastic_range(state, par):
    """Set state[LOW], state[HIGH], the open interval of drifts (m) where a step along the
    unloading/reloading line (K_u from the committed drift and force) is common: off the
    backbone, before the residual branch; under both backbones (the lower of each one's two
    lines, never above it), these above F_r; short of the ultimate drift and, once yielded, of
    zero force and of the residual branch (as `_on_residual` finds it). Else (inf, -inf)."""
    low, high = math.inf, -math.inf
    f0 = state[F]
    k = state[K_UNLOAD]
    failure = state[FAILURE]
    if state[ON_BACKBONE] == 0.0 and failure < 2.0 and k > 0.0 and (failure == 0.0 or f0 != 0.0):
        u0 = state[U]
        fres = par[FRES]
        margin = ELASTIC_MARGIN * par[FCAP0]
        low, high = -math.inf, math.inf  # offsets from u0 (the force's limits)
        floor, ceiling = -par[UU], par[UU]  # drifts (the exact limits)
        if failure != 0.0:  # the force keeps its sign
            low, high = _limit(low, high, abs(f0), math.copysign(k, f0), margin)
        for block in (POSITIVE, NEGATIVE):
            s = 1.0 if block == POSITIVE else -1.0  # to the block's frame
            kp = state[block + B_KP]
            kpc = state[block + B_KPC]
            x = s * u0 - state[block + B_UCAP]
            hard = state[block + B_FCAP] + x * kp
            soft = state[block + B_FCAP] - x * kpc
            low, high = _limit(low, high, hard - fres, s * kp, margin)
            low, high = _limit(low, high, soft - fres, -s * kpc, margin)
            low, high = _limit(low, high, hard - s * f0, s * (kp - k), margin)
            low, high = _limit(low, high, soft - s * f0, -s * (kpc + k), margin)
            if failure != 0.0 and kpc == 0.0:
                gap = s * f0 - fres
                low, high = _limit(low, high, abs(gap), s * math.copysign(k, gap), margin)
            elif failure != 0.0:
                u_res = state[block + B_UCAP] + (state[block + B_FCAP] - fres) / kpc
                if block == POSITIVE:
                    ceiling = min(ceiling, u_res)
                else:
                    floor = max(floor, -u_res)
        low = max(u0 + low, floor)
        high = min(u0 + high, ceiling)
    state[LOW], state[HIGH] = low, high


def force(drift, state, par):
    """Story force (N) at drift `drift` (m) from the committed state `state` (N_STATE,
    updated in place to the new committed state) of a story of field row `par` (`_step`'s,
    which says how). A drift within the cached elastic range (`_elastic_range`) is a common
    step: `_step` would find no reversal from the backbone, start no excursion, not reach the
    backbone and change no flag, so its few operations are done here, the same ones in the
    same order, and `_step` (large) runs only for the rest."""
    if state[LOW] < drift < state[HIGH]:
        f_prev = state[F]
        du = drift - state[U]
        f = f_prev + state[K_UNLOAD] * du
        state[U] = drift
        state[ENERGY] += 0.5 * (f + f_prev) * du  # trapezoidal, as OpenSees
        state[F] = f
        return f
    return _step(drift, state, par)


def _step(drift, state, par):
    """Story force (N) at drift `drift` (m) from the committed state `state` (N_STATE,
    updated in place to the new committed state) of a story of field row `par`. One
    self-contained function, so that it runs as plain Python and compiles with numba.njit as
    is.

    Every deterioration is Ibarra et al. (2005)'s beta = (E_i / (E_t - sum E_j))^c: a
    denominator at or below zero means the energy capacity is exhausted, i.e. complete
    deterioration (where OpenSees clips the negative ratio to 0, see the module's docstring);
    a negative numerator (an excursion's energy net of the stored elastic energy) deteriorates
    nothing."""
    u_prev = state[U]
    f_prev = state[F]
    du = drift - u_prev
    state[U] = drift
    failure = state[FAILURE]
    if failure == 5.0:  # strength lost both ways: nothing left
        state[F] = 0.0
        return 0.0
    if du == 0.0:
        return f_prev

    ke = par[KE]
    fres = par[FRES]
    on_backbone = state[ON_BACKBONE] == 1.0
    exhausted = False

    # A reversal from the backbone ends a half cycle: the unloading stiffness shrinks with the
    # energy dissipated since the last excursion began, net of the elastic energy still stored
    # (Lignos & Krawinkler 2011).
    if on_backbone and (f_prev * du < 0.0 or (f_prev == 0.0 and u_prev * du <= 0.0)):
        on_backbone = False
        k_unload = state[K_UNLOAD]
        stored = 0.5 * f_prev * f_prev / k_unload
        capacity = par[EREF_K] - (state[ENERGY] - stored)
        beta_k = 1.0
        if capacity > 0.0:
            beta_k = math.pow(max(state[ENERGY] - state[ENERGY_START] - stored, 0.0)
                              / capacity, par[C_K])
        if capacity <= 0.0 or beta_k > 1.0:
            exhausted = True
            beta_k = 1.0
        k_unload *= 1.0 - beta_k
        if failure > 1.0:  # past the residual branch, OpenSees unloads along K_e / 2
            k_unload = 0.5 * ke
        state[K_UNLOAD] = k_unload
    f = f_prev + state[K_UNLOAD] * du

    # The direction of motion and its backbone; the negative one is worked in its mirror
    # frame (s times drift and force), so that both use the same lines.
    if du > 0.0:
        s = 1.0
        block = POSITIVE
        lost_own = 3.0
        lost_other = 4.0
    else:
        s = -1.0
        block = NEGATIVE
        lost_own = 4.0
        lost_other = 3.0

    # Crossing zero force off the backbone starts a new excursion (once yielded): the backbone
    # of its direction shrinks with the energy of the excursion just ended, its yield strength
    # and hardening slope by beta_s, its post-capping line by beta_c.
    if not on_backbone and f_prev * f <= 0.0 and failure > 0.0:
        energy = state[ENERGY]
        excursion = max(0.0, energy - state[ENERGY_START])
        state[ENERGY_START] = energy
        beta_s = 1.0
        beta_c = 1.0
        if par[EREF_S] - energy <= 0.0 or par[EREF_C] - energy <= 0.0:
            exhausted = True
        else:
            beta_s = math.pow(excursion / (par[EREF_S] - energy), par[C_S])
            beta_c = math.pow(excursion / (par[EREF_C] - energy), par[C_C])
            if beta_s > 1.0 or beta_c > 1.0:
                exhausted = True
            beta_s = min(beta_s, 1.0)
            beta_c = min(beta_c, 1.0)
        shrink_s = 1.0 - beta_s * par[D]
        kp = state[block + B_KP] * shrink_s
        fy = state[block + B_FY] * shrink_s
        # The post-capping line's value at zero drift shrinks by 1 - beta_c.
        intercept = (state[block + B_FCAP] + state[block + B_KPC] * state[block + B_UCAP]) \
            * (1.0 - beta_c * par[D])
        # The post-capping slope scales with the strength above the residual, so that the
        # branch still ends at the residual strength; nothing to soften once below it.
        if fy < fres:
            kpc = 0.0
        else:
            kpc = par[KPC0] * (fy - fres) / (par[FY0] - fres)
        # The new capping point: where the shrunk hardening line meets the post-capping one.
        fy_intercept = fy - kp * (fy / ke)
        if kp + kpc <= 0.0:
            ucap = 0.0
        else:
            ucap = (intercept - fy_intercept) / (kp + kpc)
        fcap = fy_intercept + kp * ucap
        if fcap < fres:
            # The whole backbone under the residual strength: it is the residual plateau.
            fy = fres
            fcap = fres
            kp = 0.0
            kpc = 0.0
            ucap = 0.0
        else:
            # Reloading along K_u meets the residual strength at u_res; a hardening line
            # steeper than the one from there to the capping point would put the backbone
            # under the residual strength on the way: it is flattened to that line (as
            # IMKBilin does).
            u_res = s * u_prev + (fres - s * f_prev) / state[K_UNLOAD]
            if ucap > u_res and fcap > fres:
                kp = min(kp, (fcap - fres) / (ucap - u_res))
        state[block + B_FY] = fy
        state[block + B_KP] = kp
        state[block + B_KPC] = kpc
        state[block + B_UCAP] = ucap
        state[block + B_FCAP] = fcap

    # The backbone bounds the force in the direction of motion.
    u_local = s * drift
    bound = _backbone(state, block, u_local)
    if bound < fres or failure == lost_other:
        bound = fres  # the residual floor; the only strength left once the other way is lost
    if failure == lost_own:
        bound = 0.0
    if s * f > bound:
        f = s * bound
        on_backbone = True

    # Where the story stands: on or past the residual branch in either direction (a backbone
    # without post-capping slope is on it when at its strength; asked only while it matters,
    # once yielded and before the residual branch: a story that never reached its backbone
    # is within its elastic range, far from it) ...
    residual = False
    if not (failure >= 2.0 or (failure == 0.0 and not on_backbone)):
        residual = _on_residual(state, drift, f, fres)
    # ... and failure: energy capacity exhausted (both ways), or the ultimate drift or zero
    # strength on the backbone in the direction of motion (that way only).
    if exhausted:
        f = 0.0
        failure = 5.0
    elif u_local >= par[UU] or (on_backbone and s * f <= 0.0):
        f = 0.0
        failure = 5.0 if failure == lost_other else lost_own
    elif failure < 2.0 and residual:
        failure = 2.0
    elif failure == 0.0 and on_backbone:
        failure = 1.0

    state[ENERGY] += 0.5 * (f + f_prev) * du  # trapezoidal, as OpenSees
    state[F] = f
    state[FAILURE] = failure
    state[ON_BACKBONE] = 1.0 if on_backbone else 0.0
    _elastic_range(state, par)
    return f


CODE_PLASTIC_DRIFT_RATIO = 0.025
"""theta_p / h of a code-designed story (stated choice, unverified: the story of a steel
moment frame reaching its capping point at about 3% drift)."""
CODE_POST_CAPPING_DRIFT_RATIO = 0.10
"""theta_pc / h of a code-designed story (stated choice, unverified)."""


def code_values(strength, height, plastic_drift_ratio=CODE_PLASTIC_DRIFT_RATIO,
                post_capping_drift_ratio=CODE_POST_CAPPING_DRIFT_RATIO):
    """The law's values for stories of a designed strength (N,) N (their yield strength) and
    height (N,) m: theta_p and theta_pc as plastic_drift_ratio and post_capping_drift_ratio
    of the height (the lateral system's backbone; default CODE_PLASTIC_DRIFT_RATIO and
    CODE_POST_CAPPING_DRIFT_RATIO), the other parameters at their defaults."""
    height = np.asarray(height, float)
    return {"yield_force": tuple(map(float, strength)),
            "plastic_deformation": tuple(map(float, plastic_drift_ratio * height)),
            "post_capping_deformation": tuple(map(float, post_capping_drift_ratio * height))}


def yield_strength(stiffness, **values):
    """(N,) the force at which each story starts to yield (N): the virgin F_y."""
    return np.asarray(values["yield_force"], dtype=float) * np.ones(len(stiffness))
