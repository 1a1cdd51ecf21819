"""The superstructure the code would design on an isolation system: ASCE 7-22 sections 17.5.4
(minimum lateral forces) and 17.5.5 (their vertical distribution), each story given the
strength its design shear and an overstrength factor imply, on a story law of the registry
(engine/stories/laws/), with P-Delta and a collapse criterion, so that the studies beyond the
paper run a building that yields and can collapse where a code-designed one would.

What is computed, with the clause it follows (the clause numbers are ASCE 7-22's as the
issue tracker and SPEC cite them; the text of the standard was not at hand to check them, and
the values marked "stated choice" are not the standard's):
- V_b = k_M D_M, the isolation system's force at D_M (eq. 17.5-7), k_M and D_M of the bound
  the caller gives (the upper bound governs forces, section 17.2.8.5);
- V_st = V_b (W_s / W)^(1 - 2.5 beta_M), the superstructure's unreduced share (eq. 17.5-8);
- V_s = V_st / R_I (eq. 17.5-9), R_I = 3/8 R at most 2 (section 17.5.4.2), not less than
  1.5 times the force that fully activates the isolation system (17.5.4.3, item 3: the
  isolator law's yield force); items 1 (a fixed-base building's base shear) and 2 (wind) need
  a chapter 12 design and the wind load: not checked, and said so in the archive;
- F_x = C_vx V_s over levels 1..N, C_vx = w_x h_x^k / sum w_i h_i^k with h_x the height
  above the isolation level and k = 14 beta_M T_fb (eq. 17.5-11), T_fb the fixed-base
  superstructure's first period;
- each story's design shear the sum of F_x above it, its strength the lateral system's
  Omega_0 times that (ASCE 7-22 Table 12.2-1; lateral_systems.py), or a given overstrength;
- its stiffness the building's (the lateral system "given", the default, with
  OVERSTRENGTH: a stated choice), or that strength over the system's yield drift, T_fb and
  the distribution then iterated with the stiffnesses to a fixed point (STIFFNESS_ROUNDS).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from . import lateral_systems
from .lateral_systems import DEFAULT as DEFAULT_SYSTEM

R_I = 2.0
"""The superstructure's response modification R_I: 3/8 R, at most 2 (ASCE 7-22 17.5.4.2);
2 for any system with R >= 16/3 (e.g. steel special moment or concentrically braced frames)."""
OVERSTRENGTH = lateral_systems.SYSTEMS[DEFAULT_SYSTEM].omega_0
"""Story strength over its design shear on the building's own stories (the default lateral
system): 2, a stated choice, the overstrength factor Omega_0 of a steel special concentrically
braced frame (ASCE 7-22 Table 12.2-1). A designed building's actual overstrength depends on
its design (FEMA P695 measures it by pushover)."""
PLAUSIBLE_OVERSTRENGTH = (1.0, 3.0)
"""The overstrength a study takes: at least the design shear, at most 3, the largest Omega_0
of ASCE 7-22 Table 12.2-1 (a stated bound; a pushover's measured overstrength of a real frame
seldom exceeds it)."""
STORY_HEIGHT = 3.5
"""m: the height of every story of a building that states none (the paper's building gives no
heights; stated choice, a typical office story)."""
COLLAPSE_DRIFT_RATIO = 0.10
"""The drift ratio at which a story is taken as collapsed: stated choice, the 10% interstory
drift commonly used as the collapse cap of incremental dynamic analyses (Vamvatsikos &
Cornell 2002); the deteriorating law reaches zero strength on its own before or after it."""
STIFFNESS_ROUNDS = 50
"""At most this many rounds of stiffness -> T_fb -> forces -> strength -> stiffness (each
story's stiffness from its strength and the system's yield drift); they stop once T_fb
repeats to 1e-12 (a few rounds: T_fb moves the distribution's exponent alone)."""
STORY_LAW = "imk"
"""The story law of the code-designed building: the deteriorating law (collapse needs it)."""


@dataclass(frozen=True)
class SuperstructureDesign:
    """The code's superstructure design: v_b, v_st, v_s N; v_s_activation N (1.5 x the
    isolation system's yield force); k_exponent (-) and t_fb s of the vertical distribution;
    level_forces (N,) N on levels 1..N; story_shear (N,) N; strength (N,) N; story_height
    (N,) m; stiffness (N,) N/m; r_i, overstrength; story_law; lateral_system (a
    lateral_systems.LateralSystem); building: the engine.Building it designs."""

    v_b: float
    v_st: float
    v_s: float
    v_s_activation: float
    k_exponent: float
    t_fb: float
    level_forces: np.ndarray
    story_shear: np.ndarray
    strength: np.ndarray
    story_height: np.ndarray
    stiffness: np.ndarray
    r_i: float
    overstrength: float
    story_law: str
    lateral_system: object
    building: object

    def attributes(self) -> dict:
        """The archive's record of what was chosen (SI)."""
        return {"superstructure": self.describe(),
                "superstructure_clauses": "ASCE 7-22 17.5.4 (eqs. 17.5-7 to 17.5-9), 17.5.4.3 "
                                          "item 3, 17.5.5 (eq. 17.5-11); 17.5.4.3 items 1 and 2 "
                                          "not checked",
                "V_b": self.v_b, "V_st": self.v_st, "V_s": self.v_s, "R_I": self.r_i,
                "overstrength": self.overstrength, "T_fb": self.t_fb,
                "vertical_distribution_k": self.k_exponent,
                "story_strength": self.strength.tolist(),
                "story_stiffness": self.stiffness.tolist(),
                "story_height": self.story_height.tolist(),
                "story_law": self.building.story_law.describe(),
                "p_delta": int(self.building.p_delta),
                "collapse_drift_ratio": float(self.building.collapse_drift_ratio or np.nan),
                **self.lateral_system.attributes()}

    def describe(self) -> str:
        stiffness = "" if self.lateral_system.yield_drift_ratio is None else (
            "; stiffnesses " + ", ".join(f"{k / 1e6:.0f}" for k in self.stiffness)
            + f" MN/m (yield drift {100 * self.lateral_system.yield_drift_ratio:g}%)")
        return (f"code-designed ({self.story_law} stories, {self.lateral_system.title}): V_b "
                f"{self.v_b / 1e3:.0f} kN, V_st {self.v_st / 1e3:.0f} kN, V_s "
                f"{self.v_s / 1e3:.0f} kN (R_I {self.r_i:g}), story strengths "
                f"{self.overstrength:g} x design shear: "
                + ", ".join(f"{s / 1e3:.0f}" for s in self.strength) + " kN" + stiffness)


def superstructure_share(building, beta_m: float) -> float:
    """V_st / V_b (-), the superstructure's unreduced share of the base shear:
    (W_s / W)^(1 - 2.5 beta_M), W_s the weight above the isolation level (ASCE 7-22 eq.
    17.5-8); building: engine.Building, beta_m the effective damping (ratio)."""
    masses = np.asarray(building.masses, float)
    return (masses[1:].sum() / masses.sum()) ** (1 - 2.5 * beta_m)


def code_designed_building(design, building, *, r_i: float = R_I,
                           overstrength: float | None = None, story_law: str = STORY_LAW,
                           p_delta: bool = True,
                           collapse_drift_ratio: float | None = COLLAPSE_DRIFT_RATIO,
                           activation_force: float | None = None,
                           lateral_system: str = DEFAULT_SYSTEM) -> SuperstructureDesign:
    """The superstructure the code designs (module docstring) on `building`'s isolators.

    design: a pipeline.motions.target.IsolationDesign (k_m N/m, d_m m, beta_m) at the bound
    that governs forces; building: engine.Building (its masses, story stiffnesses, isolator
    and story heights, STORY_HEIGHT where it has none). story_law: a law of
    engine.stories.LAWS, given the strengths (and the system's backbone) by its code_values.
    lateral_system: a name of lateral_systems.SYSTEMS: its Omega_0 the overstrength unless
    one is given (the default system's: OVERSTRENGTH), its yield drift the stiffnesses (the
    default keeps the building's), its 3/8 R the largest R_I. activation_force: 1.5 times the
    force that fully activates the isolation system (N; default 1.5 x `building`'s isolator
    yield force; the largest over the property bounds is the caller's to give). ValueError
    for a bad argument.
    """
    from engine.building import DEFAULTS as BUILDING_DEFAULTS
    from engine.stories import LAWS, Stories

    system = lateral_systems.system(lateral_system)
    overstrength = system.omega_0 if overstrength is None else overstrength
    if not (math.isfinite(r_i) and 1 <= r_i <= system.r_i):
        raise ValueError(f"R_I must be in [1, {system.r_i:g}] for {system.title} (3/8 R, at "
                         f"most 2: ASCE 7-22 17.5.4.2), got {r_i!r}")
    if not (math.isfinite(overstrength) and overstrength >= 1):
        raise ValueError(f"overstrength must be >= 1, got {overstrength!r}")
    if story_law not in LAWS:
        raise ValueError(f"unknown story law {story_law!r}; choose one of {tuple(LAWS)}")
    masses = np.asarray(building.masses, float)
    heights = np.full(building.n_stories, STORY_HEIGHT) if building.story_height is None \
        else np.asarray(building.story_height, float)
    v_b = design.k_m * design.d_m
    v_st = v_b * superstructure_share(building, design.beta_m)
    activation = 1.5 * building.yield_force if activation_force is None \
        else float(activation_force)
    v_s = max(v_st / r_i, activation)
    elevation = np.cumsum(heights)  # level x's height above the isolation level
    stiff, t_fb = building, math.nan
    for _ in range(STIFFNESS_ROUNDS):
        last, t_fb = t_fb, 2 * math.pi / stiff.fixed_base_omega1()
        k = 14 * design.beta_m * t_fb
        weights = masses[1:] * elevation**k
        forces = v_s * weights / weights.sum()
        shear = np.cumsum(forces[::-1])[::-1]
        strength = overstrength * shear
        if system.yield_drift_ratio is None or abs(t_fb - last) <= 1e-12 * t_fb:
            break
        # the stiffness at which each story yields at the system's drift, both directions
        stiff = dataclasses.replace(building, story_stiffness=tuple(
            map(float, strength / (system.yield_drift_ratio * heights))),
            story_stiffness_y=None)
    values = LAWS[story_law].code_values(
        strength, heights, plastic_drift_ratio=system.plastic_drift_ratio,
        post_capping_drift_ratio=system.post_capping_drift_ratio)
    designed = dataclasses.replace(
        stiff, stories=Stories.of(story_law, **values), story_yield_force=None,
        story_post_yield_ratio=BUILDING_DEFAULTS["story_post_yield_ratio"],
        story_height=tuple(map(float, heights)), p_delta=p_delta,
        collapse_drift_ratio=collapse_drift_ratio)
    return SuperstructureDesign(v_b=v_b, v_st=v_st, v_s=v_s, v_s_activation=activation,
                                k_exponent=k, t_fb=t_fb, level_forces=forces,
                                story_shear=shear, strength=strength, story_height=heights,
                                stiffness=np.asarray(stiff.story_stiffness, float), r_i=r_i,
                                overstrength=overstrength, story_law=story_law,
                                lateral_system=system, building=designed)


def for_basis(basis, story_law: str = STORY_LAW, **options) -> SuperstructureDesign:
    """The superstructure the code designs on a pipeline.motions.bounds.DesignBasis: the
    forces of its force-governing bound, on the building at the bound it runs, the isolation
    system's activation force the largest of its bounds'; options as
    code_designed_building's."""
    activation = 1.5 * max(b.yield_force for b in basis.buildings.values())
    return code_designed_building(basis.force_design, basis.building, story_law=story_law,
                                  activation_force=activation, **options)
