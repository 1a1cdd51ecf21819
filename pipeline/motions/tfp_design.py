"""A triple friction pendulum designed for a target effective period T_M at the maximum
displacement D_M and for the total maximum displacement D_TM (ASCE 7-22 section 17.5.3): the
radii L_i, displacement limits d_i and friction mu_i of engine.Isolator.triple_friction_pendulum
(OpenSees' meanings: L1 the two inner surfaces, L2 the lower and L3 the upper outer one), the
bearing not yet stiffened at D_TM. Pure functions; SI units.

    design_triple_friction_pendulum   the procedure (its docstring states it, step by step)
    TripleFrictionPendulumDesign      what it gives: the parameters, the isolator, and its
                                      period, damping, regime and capacity from the law itself
    effective_friction, regime_iv_start, regime
                                      regime III's mu_e, where regime IV starts, the regime
                                      of the law's backbone at a displacement

The procedure is the configuration with equal outer surfaces (L2 = L3, d2 = d3, mu2 <= mu3, a
small inner radius L1), whose regime III (every surface sliding) has the stiffness W / (L2 + L3)
and the characteristic strength mu_e W (Fenz & Constantinou 2008, EESD 37(2), the regimes;
Constantinou et al. 2011, MCEER-11-0004, and Sarlis & Constantinou 2013, MCEER-13-0010, for
the design of such a bearing on those two numbers). The relations used are derived here from
the regimes of the series model the law implements (engine/isolators/laws/
triple_friction_pendulum.py), not copied from the reports (not checked against their text),
and every number the design reports is the law's own (its backbone, effective_stiffness,
energy_per_cycle and displacement_capacity).

The design is at nominal properties: give it the D_TM of the bound that governs displacements
(the lower, pipeline.motions.bounds), and check the designed building's T_M and D_M at every
bound there (engine.Building(isolator=design.isolator())).
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import engine
from engine.isolators import LAWS
from engine.units import G

from .target import TORSION_FACTOR

LAW = "triple_friction_pendulum"
"""The isolator law the design is for (engine.isolators.LAWS)."""
FRICTION = (0.012, 0.052, 0.052)
"""(mu1, mu2, mu3): the inner surfaces' and the lower outer surface's friction of Dao et al.'s
(2013) check case (L1 = 0.36, L2 = L3 = 1.25 m; mu 0.012 / 0.052 / 0.14; d 0.1 / 0.2 / 0.2 m,
the law's test case), the upper outer surface's made equal to the lower one's: the
configuration with equal outer surfaces. Not a catalogue value: give a project's own friction
from its prototype tests."""
INNER_RADIUS_RATIO = 0.36 / 1.25
"""L1 / L2 (-): the inner surfaces' effective radius over the outer ones', Dao et al.'s check
case's proportion (a choice here, not from a design procedure)."""
INNER_LIMIT_RATIO = 0.1 / 0.2
"""d1 / d2 (-): the inner surfaces' displacement limit over the outer ones', Dao et al.'s check
case's proportion (a choice here, not from a design procedure)."""
STIFFENING_MARGIN = 0.10
"""The share by which the bearing's stiffening (regime IV, an outer slider at its restrainer)
starts beyond D_TM: regime IV from (1 + margin) D_TM on. A choice made here, not a value of
ASCE 7-22, which asks more of a displacement restraint that limits the displacement to less than
D_TM (section 17.2.4.5 as ASCE 7-10 and 7-16 number it; the clause not checked against the 2022
text)."""
REGIMES = ("I", "II", "III", "IV", "V")
"""Fenz & Constantinou's (2008) regimes, in OpenSees' numbering with mu1 <= mu2 <= mu3: I the
inner surfaces slide (stiffness W / (2 L1)), II and the lower outer one (W / (L1 + L2)), III
every surface (W / (L2 + L3)), IV the lower outer slider at its restrainer (W / (L1 + L3)), V
both outer sliders at theirs (W / (2 L1)), up to the ultimate displacement."""
BEYOND = "beyond the ultimate"
"""The regime past the ultimate displacement (the bearing has failed: the law's stops)."""
_MASS = 1.0
"""kg: the mass the law's functions are evaluated at; every force of the law is proportional
to the weight, so the periods, damping and displacements do not depend on it."""


def _parameter(name: str) -> property:
    """A read-only attribute of the design: the law's parameter `name` of its isolator."""
    meaning = LAWS[LAW].PARAMETERS[name].help_text()
    return property(lambda self: self.bearing.values[name], doc=f"{name}: {meaning}")


@dataclass(frozen=True)
class TripleFrictionPendulumDesign:
    """A triple friction pendulum designed by design_triple_friction_pendulum.

    bearing: the engine.Isolator designed (also `isolator()`), whose parameters read as
    attributes, OpenSees' meanings (engine.Isolator.triple_friction_pendulum): L1, L2, L3 the
    effective radii (m), d1, d2, d3 the displacement limits (m), mu1, mu2, mu3 the friction
    (-), yield_disp the pre-slip displacement (m). target_period: T_M (s);
    design_displacement: D_M (m); total_displacement: D_TM (m); margin: the stiffening margin
    it was designed with (-); g: the acceleration of gravity it was designed under (m/s^2).

    Every quantity below is the law's own (engine/isolators/laws/triple_friction_pendulum.py):
    effective_period and effective_damping at any displacement, regime, capacity (its
    displacement_capacity), and at D_M and D_TM the period and damping.
    """

    bearing: engine.Isolator
    target_period: float
    design_displacement: float
    total_displacement: float
    margin: float
    g: float = G

    L1 = _parameter("L1")
    L2 = _parameter("L2")
    L3 = _parameter("L3")
    d1 = _parameter("d1")
    d2 = _parameter("d2")
    d3 = _parameter("d3")
    mu1 = _parameter("mu1")
    mu2 = _parameter("mu2")
    mu3 = _parameter("mu3")
    yield_disp = _parameter("yield_disp")

    @property
    def values(self) -> dict[str, float]:
        """The law's parameters by name (engine.Isolator.triple_friction_pendulum's keywords)."""
        return self.bearing.values

    def isolator(self) -> engine.Isolator:
        """The engine.Isolator of the design (built by the law's constructor, its checks
        applied)."""
        return self.bearing

    def effective_period(self, displacement: float) -> float:
        """2 pi sqrt(M / k_eff) (s) at a displacement amplitude (m): k_eff the law's
        effective_stiffness, F(D) / D on its backbone (ASCE 7-22 chapter 17's effective
        stiffness, section 17.2; T_M at D_M, section 17.5.3)."""
        stiffness = float(self.bearing.effective_stiffness(_MASS, self.g, displacement))
        return 2.0 * math.pi * math.sqrt(_MASS / stiffness)

    def effective_damping(self, displacement: float) -> float:
        """E / (2 pi k_eff D^2) (ratio of critical) at a displacement amplitude D (m): E the
        law's energy_per_cycle and k_eff its effective_stiffness (ASCE 7-22 chapter 17's
        effective damping, section 17.2; beta_M at D_M, section 17.5.3)."""
        iso = self.bearing
        stiffness = float(iso.effective_stiffness(_MASS, self.g, displacement))
        energy = iso.energy_per_cycle(_MASS, self.g, displacement)
        return energy / (2.0 * math.pi * stiffness * displacement**2)

    def regime(self, displacement: float) -> str:
        """The regime (REGIMES, or BEYOND) of the law's backbone pushed to a displacement (m,
        > 0): the module's `regime` of the design's bearing."""
        return regime(self.values, displacement, self.g)

    @property
    def capacity(self) -> float:
        """The bearing's displacement capacity (m): the law's ultimate displacement
        2 d1 + d2 + d3 + L1 d3 / L3 - L1 d2 / L2."""
        return self.bearing.displacement_capacity(_MASS, self.g)

    @property
    def capacity_margin(self) -> float:
        """capacity / D_TM - 1 (-): how far beyond D_TM the bearing fails."""
        return self.capacity / self.total_displacement - 1.0

    @property
    def stiffening_displacement(self) -> float:
        """Where regime IV starts (m): (1 + margin) D_TM by construction."""
        return regime_iv_start(self.values)

    @property
    def sliding_period(self) -> float:
        """2 pi sqrt((L2 + L3) / g) (s): the period of regime III's stiffness W / (L2 + L3)
        alone (Fenz & Constantinou 2008), longer than any effective period."""
        return 2.0 * math.pi * math.sqrt((self.L2 + self.L3) / self.g)

    @property
    def period_at_dm(self) -> float:
        """T_M (s): the effective period at D_M (the target, to round-off)."""
        return self.effective_period(self.design_displacement)

    @property
    def damping_at_dm(self) -> float:
        """beta_M: the effective damping at D_M."""
        return self.effective_damping(self.design_displacement)

    @property
    def period_at_dtm(self) -> float:
        """The effective period (s) at D_TM."""
        return self.effective_period(self.total_displacement)

    @property
    def damping_at_dtm(self) -> float:
        """The effective damping at D_TM."""
        return self.effective_damping(self.total_displacement)

    def describe(self) -> str:
        """One line: the geometry, the friction, T_M and beta_M at D_M, the capacity."""
        return (f"L1 {self.L1:.3g} m, L2 = L3 {self.L2:.3g} m, d1 {self.d1:.3g} m, d2 = d3 "
                f"{self.d2:.3g} m, mu {self.mu1:g} / {self.mu2:g} / {self.mu3:g}: T_M "
                f"{self.period_at_dm:.3g} s, beta_M {self.damping_at_dm:.3g} at D_M "
                f"{self.design_displacement:.3g} m; stiffening from "
                f"{self.stiffening_displacement:.3g} m, capacity {self.capacity:.3g} m "
                f"(D_TM {self.total_displacement:.3g} m + {100 * self.capacity_margin:.0f}%)")


def effective_friction(values) -> float:
    """mu_e (-): regime III's force at zero displacement over W, (2 L1 mu1 + (L2 - L1) mu2 +
    (L3 - L1) mu3) / (L2 + L3), of the law's parameters `values` (by name): in regime III
    F = W (D / (L2 + L3) + mu_e) (Fenz & Constantinou 2008's regime III, re-derived for the
    series model; mu_e W the characteristic strength Q_d of Constantinou et al. 2011)."""
    l1, l2, l3 = values["L1"], values["L2"], values["L3"]
    return (2.0 * l1 * values["mu1"] + (l2 - l1) * values["mu2"]
            + (l3 - l1) * values["mu3"]) / (l2 + l3)


def regime_iv_start(values) -> float:
    """The displacement (m) where the first outer slider meets its restrainer (regime IV), at
    the force W min(mu2 + d2 / L2, mu3 + d3 / L3), on regime III's line (effective_friction);
    meaningful where regime III comes before it."""
    force = min(values["mu2"] + values["d2"] / values["L2"],
                values["mu3"] + values["d3"] / values["L3"])
    return (force - effective_friction(values)) * (values["L2"] + values["L3"])


def regime(values, displacement: float, g: float = G) -> str:
    """The regime (REGIMES, or BEYOND) of the law's backbone with parameters `values` (by
    name) pushed to a displacement (m, > 0): read from its force F(D) / W against the regimes'
    corner forces mu2, mu3, the outer sliders' restrainers mu2 + d2 / L2 and mu3 + d3 / L3
    (the lower one first where it is the smaller) and the inner ones' mu1 + d3 / L3 + d1 / L1
    (Fenz & Constantinou 2008; a force on a corner counts in the regime before it; the law's
    assumptions, mu1 <= mu2 <= mu3, and an inner slider that stops last)."""
    force = float(LAWS[LAW].backbone(_MASS, g, displacement, **values))
    ratio = force / (_MASS * g)
    stops = sorted((values["mu2"] + values["d2"] / values["L2"],
                    values["mu3"] + values["d3"] / values["L3"]))
    corners = (values["mu2"], values["mu3"], *stops,
               values["mu1"] + values["d3"] / values["L3"] + values["d1"] / values["L1"])
    for name, corner in zip(REGIMES, corners, strict=True):
        if ratio <= corner * (1.0 + 1e-12):
            return name
    return BEYOND


def design_triple_friction_pendulum(target_period: float, design_displacement: float,
                                    total_displacement: float | None = None, *,
                                    friction=FRICTION,
                                    inner_radius_ratio: float = INNER_RADIUS_RATIO,
                                    inner_limit_ratio: float = INNER_LIMIT_RATIO,
                                    margin: float = STIFFENING_MARGIN,
                                    yield_disp: float | None = None,
                                    g: float = G) -> TripleFrictionPendulumDesign:
    """The triple friction pendulum with effective period target_period T_M (s) at
    design_displacement D_M (m) that has not stiffened at total_displacement D_TM (m, >= D_M;
    default TORSION_FACTOR D_M, ASCE 7-22 section 17.5.3.3's lower bound, as
    pipeline.motions.target.isolation_design): the configuration with equal outer surfaces.

    1. Geometry and friction: L2 = L3 = L, d2 = d3 = d, friction (mu1, mu2, mu3) as given
       (default FRICTION; mu1 <= mu2 <= mu3, equal outer friction the common choice),
       L1 = inner_radius_ratio L, d1 = inner_limit_ratio d (defaults: Dao et al.'s check
       case's proportions, INNER_RADIUS_RATIO and INNER_LIMIT_RATIO).
    2. The radius from the period: at D_M in regime III (Fenz & Constantinou 2008, EESD 37)
       F = W (D / (2 L) + mu_e), mu_e = r mu1 + (1 - r) (mu2 + mu3) / 2 (effective_friction,
       r = L1 / L: independent of L), so T_M = 2 pi sqrt(M / k_M) with k_M = F / D_M (ASCE
       7-22 section 17.5.3) gives 1 / (2 L) = 4 pi^2 / (g T_M^2) - mu_e / D_M. The sliding
       period 2 pi sqrt(2 L / g) is then longer than T_M.
    3. The displacement limits from D_TM: the lower outer slider meets its restrainer at
       F = W (mu2 + d / L) (mu2 <= mu3: before the upper one), so regime IV starts at
       2 L (mu2 - mu_e) + 2 d; d is set so that this is (1 + margin) D_TM (default
       STIFFENING_MARGIN). The ultimate displacement, the law's displacement_capacity, is then
       2 d1 + 2 d (L2 = L3, d2 = d3), beyond regime IV's start by regime IV and V's travel.

    The procedure follows the design of such a bearing on K_d = W / (L2 + L3) and Q_d = mu_e W
    (Constantinou et al. 2011, MCEER-11-0004; Sarlis & Constantinou 2013, MCEER-13-0010):
    the relations are derived here from the regimes, not taken from the reports' text. The
    radii are derived from the target period, not chosen from a manufacturer's catalogue (none
    is cited here). The design is at nominal properties (the module's docstring says how the
    bounds come in). The weight does not enter (every force of the law is proportional to it).
    yield_disp: the law's pre-slip displacement (m; default the law's, 5e-4); g: the
    acceleration of gravity (m/s^2).

    ValueError, in one line saying what to change, where the target cannot be met: the
    friction alone too stiff for T_M at D_M, a radius or a limit outside the law's plausible
    range (its declaration), D_M before regime III (the upper outer surface would not slide),
    or an inner slider that would stop before the outer ones.
    """
    declaration = LAWS[LAW].PARAMETERS
    _positive(target_period=target_period, design_displacement=design_displacement, g=g)
    d_tm = TORSION_FACTOR * design_displacement if total_displacement is None \
        else total_displacement
    _positive(total_displacement=d_tm)
    if d_tm < design_displacement:
        raise ValueError(f"total_displacement D_TM = {d_tm:g} m must be at least "
                         f"design_displacement D_M = {design_displacement:g} m")
    mu1, mu2, mu3 = _friction(friction)
    for name, value in (("inner_radius_ratio", inner_radius_ratio),
                        ("inner_limit_ratio", inner_limit_ratio)):
        if not (_number(value) and 0 < value < 1):
            raise ValueError(f"{name} must be in (0, 1), got {value!r}")
    if not (_number(margin) and margin >= 0):
        raise ValueError(f"margin must be >= 0, got {margin!r}")
    yield_disp = declaration["yield_disp"].default if yield_disp is None else yield_disp

    # 2. the radius from the period (regime III at D_M)
    r = inner_radius_ratio
    mu_e = effective_friction(dict(L1=r, L2=1.0, L3=1.0, mu1=mu1, mu2=mu2, mu3=mu3))  # any L
    excess = 4.0 * math.pi**2 / (g * target_period**2) - mu_e / design_displacement
    if excess <= 0:
        longest = 2.0 * math.pi * math.sqrt(design_displacement / (mu_e * g))
        raise ValueError(f"T_M = {target_period:g} s cannot be reached at D_M = "
                         f"{design_displacement:g} m: the friction alone (mu_e = {mu_e:.4g}) "
                         f"allows at most {longest:.3g} s there; target a shorter period, a "
                         f"larger D_M or lower friction")
    radius = 1.0 / (2.0 * excess)
    # 3. the displacement limits from D_TM (regime IV from (1 + margin) D_TM on)
    limit = (1.0 + margin) * d_tm / 2.0 - radius * (mu2 - mu_e)
    values = dict(L1=r * radius, L2=radius, L3=radius, d1=inner_limit_ratio * limit, d2=limit,
                  d3=limit, mu1=mu1, mu2=mu2, mu3=mu3, yield_disp=yield_disp)
    _plausible(declaration, values, target_period, design_displacement, d_tm)
    regime_iii = 2.0 * values["L1"] * (mu3 - mu1) + (radius - values["L1"]) * (mu3 - mu2)
    if design_displacement <= regime_iii:
        raise ValueError(f"D_M = {design_displacement:g} m comes before regime III (from "
                         f"{regime_iii:.3g} m: the upper outer surface would not slide); "
                         f"lower mu3 toward mu2 or target a larger D_M")
    if values["d1"] <= values["L1"] * (mu3 - mu1):
        raise ValueError(f"d1 = {values['d1']:.3g} m would stop the inner slider before the "
                         f"outer ones (d1 <= L1 (mu3 - mu1) = "
                         f"{values['L1'] * (mu3 - mu1):.3g} m); raise inner_limit_ratio")
    bearing = engine.Isolator.triple_friction_pendulum(**values)
    return TripleFrictionPendulumDesign(bearing, target_period=float(target_period),
                                        design_displacement=float(design_displacement),
                                        total_displacement=float(d_tm), margin=float(margin),
                                        g=float(g))


def _plausible(declaration, values, target_period, design_displacement, d_tm) -> None:
    """ValueError, saying what to change, for a radius or a limit outside the law's plausible
    range (its declaration's `plausible`)."""
    for name, change in (("L2", "a shorter period or a larger D_M (or lower friction)"),
                         ("L1", "a longer period or a larger inner_radius_ratio"),
                         ("d2", "a smaller margin or D_TM"),
                         ("d1", "a larger inner_limit_ratio")):
        parameter = declaration[name]
        if parameter.implausible(values[name]).size:
            raise ValueError(f"T_M = {target_period:g} s at D_M = {design_displacement:g} m "
                             f"(D_TM {d_tm:g} m) needs {name} = {values[name]:.3g} m, outside "
                             f"the plausible {parameter.plausible} m: target {change}")


def _friction(friction) -> tuple[float, float, float]:
    """(mu1, mu2, mu3) checked: three numbers in (0, 1), mu1 <= mu2 <= mu3."""
    try:
        mu1, mu2, mu3 = (float(mu) for mu in friction)
    except (TypeError, ValueError):
        raise ValueError(f"friction must be three numbers (mu1, mu2, mu3), got "
                         f"{friction!r}") from None
    if not all(math.isfinite(mu) and 0 < mu < 1 for mu in (mu1, mu2, mu3)):
        raise ValueError(f"friction coefficients must be in (0, 1), got {friction!r}")
    if not mu1 <= mu2 <= mu3:
        raise ValueError(f"friction must have mu1 <= mu2 <= mu3 (the inner surfaces slide "
                         f"first), got {friction!r}")
    return mu1, mu2, mu3


def _number(value) -> bool:
    """Whether `value` is one finite real number (NumPy's included, a bool not)."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool) \
        and math.isfinite(value)


def _positive(**values) -> None:
    """ValueError unless every value is a positive finite number."""
    for name, value in values.items():
        if not (_number(value) and value > 0):
            raise ValueError(f"{name} must be a positive number, got {value!r}")
