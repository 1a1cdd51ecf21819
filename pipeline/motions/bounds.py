"""The isolation design basis: the code's T_M, D_M and D_TM at upper-bound, nominal and
lower-bound isolator properties (ASCE 7-22 section 17.2.8.4), from the isolators' own
hysteresis, and the building a code-based study runs: damping counted once.

Damping counted once (DAMPING_TEXT): the code's effective damping beta_M is the isolators'
hysteresis or friction, what a prototype test measures (ASCE 7-22 17.8), plus the dampers the
building declares. So the building a study runs has what its design counts: no isolation
dashpot (zeta_iso 0) unless the building declares one (an explicit zeta_iso > 0 under
damping="paper": a viscous damper at the isolation level), which the design then counts in
beta_M (pipeline.motions.target.isolation_design(dashpot=True)). The paper's isolation
dashpot (the bilinear law's default zeta_iso 0.05 on k1, 13% of critical at T_M) belongs to the
paper's recipes; here it is shown beside (`with_dashpot`: D_M had it been counted), never run.
The superstructure keeps its own damping, stiffness-proportional on the stories (damping=
"paper": 2 zeta_sup k / omega_1 of the fixed-base superstructure), which acts on the stories'
deformation only.

    PropertyFactors     lambda_max, lambda_min on the isolators' characteristic strength Q_d
                        and post-yield stiffness K_d (user-set; defaults UNVERIFIED, see
                        FACTORS_SOURCE)
    bounded_building    the building on its isolator at a bound's properties
    design_basis        DesignBasis: the building and pipeline.motions.target.IsolationDesign at
                        each bound, the bound a study runs, the scaling's period range
                        (0.75 T_M upper to 1.25 T_M lower) and the archive attributes

Which bound governs what (ASCE 7-22 section 17.2.8.5 and 17.5.3; wording UNVERIFIED against the
standard's text): lower-bound properties give the longest T_M and the largest D_M, D_TM, so they
govern displacements, the moat's clearance and contact (the pounding studies' default); upper-
bound properties give the shortest T_M and the largest base shear V_b = k_M D_M, so they govern
forces and accelerations.

How a law's parameters take the factors each law declares (its `bounded`,
engine/isolators/laws/): bilinear: Q_d and K_d = k2 scaled, the
yield displacement u_y kept (the lead core's elastic stiffness goes with the bearing: k1 =
Q_d / u_y + K_d), so that k1, k2 and fy_ratio all scale by lambda when both factors are equal;
friction pendulum: mu_slow and mu_fast scaled by the Q_d factor (friction is its characteristic
strength), the radius (K_d = W / R, geometry) and the pre-slip displacement kept; triple
friction pendulum: mu1, mu2 and mu3 scaled by the Q_d factor, the radii, the displacement
limits and the pre-slip displacement kept.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .target import TORSION_FACTOR, isolation_design

BOUND_NAMES = ("lower", "nominal", "upper")
"""The isolator properties a design quantity or a run is taken at."""
DEFAULT_BOUND = "lower"
"""The bound the pounding studies run unless told: displacements, gaps and contact."""
BOUND_TEXT = {
    "lower": "lower-bound isolator properties (lambda_min): the longest T_M and the largest "
             "D_M, governing displacements, gaps and contact",
    "nominal": "nominal isolator properties (the building as given, lambda 1)",
    "upper": "upper-bound isolator properties (lambda_max): the shortest T_M and the largest "
             "base shear, governing forces and accelerations",
}
"""What each bound is and what it governs (the --bound help, the archives' isolator_bound_text)."""
LAMBDA_MAX = 1.8
"""Default upper-bound property modification factor on Q_d and K_d (UNVERIFIED: FACTORS_SOURCE)."""
LAMBDA_MIN = 0.8
"""Default lower-bound property modification factor on Q_d and K_d (UNVERIFIED: FACTORS_SOURCE)."""
PLAUSIBLE_FACTORS = (3.0, 0.3)
"""The largest lambda_max and the smallest lambda_min a study takes (a stated choice, not the
standard's: 2.5 and 3.5 times the defaults' distance from 1): a factor outside them is most
likely a slip (15 for 1.5, typed without its point)."""
FACTORS_SOURCE = (
    "ASCE 7-22 section 17.2.8.4 (property modification factors lambda_max = (1 + 0.75 "
    "(lambda_ae,max - 1)) lambda_test,max lambda_spec,max and lambda_min likewise, eqs. 17.2-1 "
    "and 17.2-2) and commentary C17.2.8.4 (default factors for lead-rubber bearings without "
    "qualified test data, after McVitty and Constantinou 2015, MCEER-15-0005). UNVERIFIED "
    "against the standard's text: the defaults 1.8 and 0.8 are the values believed in use for "
    "Q_d and K_d of lead-rubber bearings without test data (eq. 17.2-1 is believed to floor "
    "lambda_max at 1.8 and eq. 17.2-2 to cap lambda_min at 0.6 in that case, which would make "
    "the lower bound softer than 0.8); give the project's own factors (--lambda-max, "
    "--lambda-min)")
"""Where the default factors come from, and what is not checked."""


@dataclass(frozen=True)
class PropertyFactors:
    """Property modification factors (-): q_max, q_min on the characteristic strength Q_d (a
    friction pendulum's friction), k_max, k_min on the post-yield stiffness K_d. max >= 1 >=
    min > 0. `of(bound)` gives (lambda on Q_d, lambda on K_d) at a bound of BOUND_NAMES."""

    q_max: float = LAMBDA_MAX
    q_min: float = LAMBDA_MIN
    k_max: float = LAMBDA_MAX
    k_min: float = LAMBDA_MIN

    def __post_init__(self):
        for name in ("q_max", "k_max"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 1):
                raise ValueError(f"the upper-bound factor {name} must be >= 1, got {value!r}")
        for name in ("q_min", "k_min"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value)
                    and 0 < value <= 1):
                raise ValueError(f"the lower-bound factor {name} must be in (0, 1], got "
                                 f"{value!r}")

    @classmethod
    def uniform(cls, lambda_max: float = LAMBDA_MAX,
                lambda_min: float = LAMBDA_MIN) -> PropertyFactors:
        """The same factors on Q_d and K_d."""
        return cls(lambda_max, lambda_min, lambda_max, lambda_min)

    def of(self, bound: str) -> tuple[float, float]:
        """(lambda on Q_d, lambda on K_d) at `bound` (one of BOUND_NAMES)."""
        if bound not in BOUND_NAMES:
            raise ValueError(f"the bound must be one of {BOUND_NAMES}, got {bound!r}")
        return {"lower": (self.q_min, self.k_min), "nominal": (1.0, 1.0),
                "upper": (self.q_max, self.k_max)}[bound]

    def describe(self) -> str:
        """'lambda_max 1.8, lambda_min 0.8 on Q_d and K_d' (each named when they differ)."""
        if (self.q_max, self.q_min) == (self.k_max, self.k_min):
            return f"lambda_max {self.q_max:g}, lambda_min {self.q_min:g} on Q_d and K_d"
        return (f"lambda_max {self.q_max:g}, lambda_min {self.q_min:g} on Q_d; lambda_max "
                f"{self.k_max:g}, lambda_min {self.k_min:g} on K_d")


def bounded_building(building, bound: str, factors: PropertyFactors | None = None):
    """The engine.Building on its isolator at `bound`'s properties (BOUND_NAMES): `building`
    itself at "nominal" (the very object: its runs unchanged, bit for bit), else the same
    building with its isolator's parameters modified by the factors (default PropertyFactors())
    as its law declares (the law's `bounded`, engine/isolators/laws/). ValueError names a law
    without the declaration or a modified parameter its law refuses."""
    import engine
    from engine.isolators.registry import law_function

    factors = PropertyFactors() if factors is None else factors
    lambda_q, lambda_k = factors.of(bound)
    if bound == "nominal":
        return building
    try:
        modified = law_function(building.isolation.law, "bounded")
    except engine.EngineError as err:
        raise ValueError(f"{err}: it has no upper- and lower-bound properties; run --bound "
                         "nominal") from None
    values = modified(building.isolation.values, lambda_q, lambda_k)
    try:
        return building.with_isolator(**values)
    except engine.EngineError as err:
        raise ValueError(f"the {bound}-bound isolator ({factors.describe()}): {err}") from None


@dataclass(frozen=True)
class DesignBasis:
    """The code's isolation design at each bound. bound: the one a study runs (BOUND_NAMES);
    factors: PropertyFactors; buildings: bound -> the engine.Building run (damping counted
    once: its isolation dashpot the declared damper's, else none); designs: bound ->
    pipeline.motions.target.IsolationDesign from the isolators' hysteresis plus the declared
    damper and the supplemental damping given; with_dashpot: the design had the paper's
    isolation dashpot been counted (shown beside, never run), None where the building declares
    its damper or has no isolation dashpot (damping="modal"); damper: the declared isolation
    damper's zeta_iso (0: none)."""

    bound: str
    factors: PropertyFactors
    buildings: dict
    designs: dict
    with_dashpot: dict | None
    damper: float = 0.0

    @property
    def building(self):
        """The engine.Building the study runs: at its bound's properties."""
        return self.buildings[self.bound]

    @property
    def design(self):
        """The IsolationDesign at the bound the study runs."""
        return self.designs[self.bound]

    @property
    def t_m(self) -> float:
        """T_M (s) at the bound run."""
        return self.design.t_m

    @property
    def d_m(self) -> float:
        """D_M (m) at the bound run."""
        return self.design.d_m

    @property
    def d_tm(self) -> float:
        """D_TM (m) at the bound run."""
        return self.design.d_tm

    @property
    def t_m_bounds(self) -> tuple[float, float]:
        """(T_M with upper-bound, T_M with lower-bound properties), s: the scaling's period
        range is 0.75 the first to 1.25 the second (ASCE 7-22 section 17.3.3,
        pipeline.motions.code_scaling.ASCE7_22_ISOLATED)."""
        return self.designs["upper"].t_m, self.designs["lower"].t_m

    @property
    def force_design(self):
        """The IsolationDesign of the largest base shear V_b = k_M D_M over the bounds (in
        practice the upper bound): the one the superstructure's design forces come from
        (ASCE 7-22 section 17.5.4)."""
        return max(self.designs.values(), key=lambda d: d.k_m * d.d_m)

    def attributes(self) -> dict:
        """The archive's attributes: design_basis (the describe line, which a recipe prints),
        the bound run and its text, the factors and their source,
        T_M, D_M, D_TM and beta_M at every bound (T_M_lower, ...), the same with the model's
        dashpot counted at the bound run (D_M_with_dashpot, ...; "none" without a dashpot) and
        what the design's damping counts."""
        attrs = {"design_basis": self.describe(),
                 "isolator_bound": self.bound, "isolator_bound_text": BOUND_TEXT[self.bound],
                 "property_factors": self.factors.describe(),
                 "property_factors_source": FACTORS_SOURCE,
                 "design_damping": DAMPING_TEXT, "isolation_damper_zeta": self.damper}
        for bound in BOUND_NAMES:
            d = self.designs[bound]
            attrs.update({f"T_M_{bound}": d.t_m, f"D_M_{bound}": d.d_m,
                          f"D_TM_{bound}": d.d_tm, f"beta_M_{bound}": d.beta_m})
        for name in ("T_M", "D_M", "D_TM", "beta_M"):
            attrs[f"{name}_with_dashpot"] = "none" if self.with_dashpot is None else \
                getattr(self.with_dashpot[self.bound], _FIELD[name])
        return attrs

    def describe(self) -> str:
        """One line: the bound run, T_M / D_M / D_TM at it and at the others, and D_M with the
        model's dashpot counted beside."""
        def at(bound):
            d = self.designs[bound]
            return (f"T_M {d.t_m:.3g} s, D_M {d.d_m * 100:.3g} cm, D_TM {d.d_tm * 100:.3g} "
                    f"cm")

        others = "; ".join(f"{b}: {at(b)}" for b in BOUND_NAMES if b != self.bound)
        source = "the isolators' hysteresis" + (
            f" and the declared isolation damper (zeta_iso {self.damper:g}, run and counted)"
            if self.damper else " (no isolation dashpot run)")
        dashpot = "" if self.with_dashpot is None else (
            f"; had the paper's isolation dashpot been counted (it is not run): D_M "
            f"{self.with_dashpot[self.bound].d_m * 100:.3g} cm, D_TM "
            f"{self.with_dashpot[self.bound].d_tm * 100:.3g} cm")
        return (f"{self.bound} bound ({self.factors.describe()}): {at(self.bound)} from "
                f"{source}; {others}{dashpot}")


DAMPING_TEXT = (
    "damping counted once: beta_M from the isolators' hysteresis (energy per cycle at D_M, ASCE "
    "7-22 section 17.5.3) plus the isolation damper the building declares (an explicit "
    "zeta_iso, run and counted; isolation_damper_zeta) and any supplemental damping; the "
    "building run has no other isolation dashpot (zeta_iso 0); the paper's isolation dashpot "
    "(the bilinear law's default zeta_iso, a damping no prototype test measures) is neither run "
    "nor counted: the *_with_dashpot attributes show the design had it been counted; the "
    "superstructure's damping is stiffness-proportional on the stories")
"""What the design's effective damping counts (the archives' design_damping)."""
_FIELD = {"T_M": "t_m", "D_M": "d_m", "D_TM": "d_tm", "beta_M": "beta_m"}


def design_basis(s_m1: float, building=None, bound: str = DEFAULT_BOUND,
                 factors: PropertyFactors | None = None, *,
                 torsion_factor: float = TORSION_FACTOR,
                 supplemental_damping: float = 0.0) -> DesignBasis:
    """The design basis of `building` (engine.Building, default the paper's) at S_M1 = s_m1 g:
    pipeline.motions.target.isolation_design at each of BOUND_NAMES (bounded_building with
    factors, default PropertyFactors()) of the building run (`run_building`: damping counted
    once), from the isolators' hysteresis plus the declared isolation damper plus
    supplemental_damping (a ratio of critical, for other dampers: none in the building files
    today); the paper's isolation dashpot counted beside where the building has it by default.
    bound: the one the study runs. ValueError for damping="modal" with a declared zeta_iso."""
    import engine

    if bound not in BOUND_NAMES:
        raise ValueError(f"the bound must be one of {BOUND_NAMES}, got {bound!r}")
    building = engine.Building() if building is None else building
    factors = PropertyFactors() if factors is None else factors
    run, damper = run_building(building)
    buildings = {b: bounded_building(run, b, factors) for b in BOUND_NAMES}
    designs = {b: isolation_design(s_m1, buildings[b], torsion_factor=torsion_factor,
                                   supplemental_damping=supplemental_damping,
                                   dashpot=damper > 0)
               for b in BOUND_NAMES}
    with_dashpot = None
    if building.damping == "paper" and not damper and building.isolation_zeta > 0:
        with_dashpot = {b: isolation_design(s_m1, bounded_building(building, b, factors),
                                            torsion_factor=torsion_factor,
                                            supplemental_damping=supplemental_damping,
                                            dashpot=True)
                        for b in BOUND_NAMES}
    return DesignBasis(bound, factors, buildings, designs, with_dashpot, damper)


def run_building(building):
    """(the engine.Building a code-based study runs, the declared isolation damper's zeta_iso):
    the building itself where it declares zeta_iso > 0 (damping="paper": a viscous damper at
    the isolation level, which the design counts), else the building with zeta_iso 0 (the
    isolators' hysteresis alone: the isolator law's default dashpot is the paper's, not the
    design's). ValueError for damping="modal" with a declared zeta_iso > 0: a modal ratio is no
    damper the code's B_M can count."""
    import dataclasses

    declared = building.zeta_iso is not None and building.zeta_iso > 0
    if declared and building.damping != "paper":
        raise ValueError(f"zeta_iso {building.zeta_iso:g} under damping='modal' is a modal "
                         "damping ratio, not a damper the code's B_M can count: declare the "
                         "isolation damper under damping='paper', or leave zeta_iso unset")
    if declared:
        return building, float(building.zeta_iso)
    return dataclasses.replace(building, zeta_iso=0.0), 0.0
