"""Where a result leaves the model's range: the bumpers' contact stress, strain and shape
factor, floor accelerations a shear building with rigid floors cannot carry, a linear story's
shear above its capacity, the wall's force above its capacity. Pure functions of peaks
(engine.results.PEAKS, SI) and of the bumper and building parameters (the largest floor
acceleration and the bumpers' stress as pipeline.assess.derived declares them); `flags_of`
takes the peaks as the engine names them with the building. The studies store the flags per
member in their archives (variables `invalid_*`, 1 where the member is outside the range) and
count them in every summary.

The limits are stated defaults, each replaceable by the user:
- RUBBER_STRESS_LIMIT, 30.9 MPa: the largest compressive stress of the rubber tests the bumper
  law is calibrated on (Kajita et al. 2006, the paper's section 3.4: a 40 x 40 x 10 mm pad,
  static fit 0.2 kN/mm^2.65 delta^2.65, at its crush strain 0.8, delta = 8 mm: 49.5 kN on
  1600 mm^2). Beyond it the law is extrapolated. At the crush limit every bumper of that rubber
  reaches alpha K_r 0.8^n = 69.5 MPa whatever its size (the stress does not depend on the
  thickness), so a crushed bumper is always beyond it; with the pad's shape (the law's
  shape_k), alpha K_r 0.8^n (1 + 2 k S^2) / (1 + 2 k S_cal^2).
- RUBBER_STRAIN_LIMIT, 0.8: the largest compressive strain of the same tests, the test rubber's
  ultimate strain (the static fit up to delta = 8 mm of the 10 mm pad, as above; the paper's
  section 3.5: 75-80% of the thickness by Kawashima et al. 2002 and Kajita et al. 2006).
  Flagged on the peak strain max_indentation / thickness: past it the law is the rubber's
  power law extrapolated, or the wall k_w behind the crushed rubber (Eq. 14). With the
  default crush strain, a bumper flagged here is crushed too (delta_u = min(0.8 t, t - c_d) <=
  0.8 t); with a cavity it is crushed, at t - c_d, before it is flagged. The flag tells a
  larger crush strain (the law's `strain` up to 1) from the rubber that was tested.
- ACCEL_LIMIT, 5 g: floor accelerations above it come from the impact spikes of a lumped-mass
  model with rigid floors; real floors, walls and the slab's local deformation cut them off.
- A linear story's shear k_i x peak drift above a capacity the caller gives (N): the studies
  take the code's superstructure design shear (`code_story_capacity`).
- The wall's force above a capacity the caller gives (N); none by default (not checked, and
  said so).
- A run that ended in collapse (engine.results.COLLAPSE, a building with a collapse
  criterion): its peaks are those of the steps before, so it is a collapse, never a response;
  the studies count it as such (never as a large amplification) and say how many.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.impact.laws import rubber_bumper
from engine.units import G

from .derived import bumper_stress, largest_floor_accel, peaks_of

_RUBBER = rubber_bumper.PARAMETERS
RUBBER_STRESS_LIMIT = _RUBBER["k_r"].default * _RUBBER["strain"].default ** _RUBBER["n"].default
"""Pa: the calibration test's static stress at its crush strain, K_r 0.8^n (the bumper law's
declared rubber; see the module docstring), 30.9 MPa."""
RUBBER_STRAIN_LIMIT = _RUBBER["strain"].default
"""-: the calibration test's largest strain, its rubber's crush strain 0.8 (the bumper law's
declared default; see the module docstring)."""
ACCEL_LIMIT = 5.0 * G
"""m/s^2: the largest floor acceleration the rigid-floor shear building represents."""


def shape_factor(area, thickness) -> np.ndarray:
    """Shape factor (-) of a square rubber pad: loaded area over the area free to bulge,
    A / (4 sqrt(A) t) = side / (4 t) (the bumper law's, rubber_bumper.shape_factor). Below
    about 1 a pad bulges freely and its stiffness and strength fall well below a confined
    pad's (the paper's 150 x 150 x 50 mm bumper: 0.75; the 40 x 40 x 10 mm test pads: 1.0)."""
    return rubber_bumper.shape_factor(area, thickness)


def code_story_capacity(design, building, r_i: float = 2.0, overstrength: float = 2.0) -> float:
    """A linear superstructure's story shear capacity (N) from the code's design of it: the
    base shear at the isolation system's design displacement V_b = k_M D_M (ASCE 7-22 eq.
    17.5-7), the superstructure's share V_st = V_b (W_s / W)^(1 - 2.5 beta_M) (eq. 17.5-8),
    reduced by R_I (at most 2, section 17.5.4.2) and raised by an overstrength factor for the
    strength a designed structure has beyond its design force. design: a
    pipeline.motions.target.IsolationDesign (k_m N/m, d_m m, beta_m); building: engine.Building.
    Applied to every story (the first carries the most)."""
    from pipeline.motions.superstructure import superstructure_share

    v_b = design.k_m * design.d_m
    return float(overstrength * v_b * superstructure_share(building, design.beta_m) / r_i)


@dataclass(frozen=True)
class Limits:
    """The limits a result is checked against (SI): bumper stress Pa, floor acceleration
    m/s^2, story shear N (None: stories not checked), wall force N (None: not checked),
    bumper strain (-)."""

    bumper_stress: float = RUBBER_STRESS_LIMIT
    floor_accel: float = ACCEL_LIMIT
    story_shear: float | None = None
    wall_force: float | None = None
    bumper_strain: float = RUBBER_STRAIN_LIMIT

    def describe(self) -> str:
        """One line for an archive's attributes and a summary's header."""
        parts = [f"bumper contact stress {self.bumper_stress / 1e6:.3g} MPa",
                 f"bumper strain {self.bumper_strain:.3g}",
                 f"floor acceleration {self.floor_accel / G:.3g} g"]
        parts.append("story shear not checked" if self.story_shear is None else
                     f"story shear {self.story_shear / 1e3:.4g} kN")
        parts.append("wall force not checked" if self.wall_force is None else
                     f"wall force {self.wall_force / 1e3:.4g} kN")
        return "; ".join(parts)


def floor_accel_exceeds(largest_floor_accel, limit: float = ACCEL_LIMIT):
    """The rule of invalid_floor_accel: the largest floor acceleration (m/s^2, any shape;
    derived.largest_floor_accel) above the rigid-floor model's limit (m/s^2)."""
    return largest_floor_accel > limit


def bumper_stress_exceeds(stress, limit: float = RUBBER_STRESS_LIMIT):
    """The rule of invalid_bumper_stress: the bumpers' (or a pad's) mean contact stress (Pa,
    any shape; derived.bumper_stress) above the rubber's limit (Pa)."""
    return stress > limit


def bumper_strain_exceeds(max_indentation, thickness, limit: float = RUBBER_STRAIN_LIMIT):
    """The rule of invalid_bumper_strain: the peak indentation (m) beyond `limit` (-) times
    the bumpers' thickness (m), as `crushed` compares with delta_u = strain t (broadcast;
    thickness inf where a member has no bumpers)."""
    return max_indentation > limit * thickness


FLAGS = {
    "invalid_bumper_stress": "the bumpers' contact stress exceeds the rubber's limit",
    "invalid_bumper_strain": "the bumpers' peak strain exceeds the rubber's calibration",
    "invalid_floor_accel": "a floor acceleration exceeds what the rigid-floor model represents",
    "invalid_story_shear": "a linear story's shear exceeds its capacity",
    "invalid_wall_force": "the wall's force exceeds its capacity",
    "invalid_collapse": "the run ended in collapse (its peaks stop there: a collapse, not a "
                        "response)",
}
"""The flags `flags` returns and what each says (the archives' long_name)."""


def flags(peak_total_accel, peak_interstory_drift, max_impact_force, story_k, limits: Limits,
          n_bumpers=None, area=None, stories_yield: bool = False, max_indentation=None,
          thickness=None, collapsed=None) -> dict[str, np.ndarray]:
    """Per member, whether it left the model's range: name (FLAGS) -> bool array (...,).

    peak_total_accel (..., levels) m/s^2; peak_interstory_drift (..., stories) m; story_k
    (stories,) N/m; max_impact_force (...,) N; n_bumpers, area: the bumpers (None: a bare wall,
    no bumper stress; n_bumpers inf where a member has no bumpers); stories_yield: the stories
    follow their own yield law (their shear is bounded by the model: not checked);
    max_indentation (...,) m and thickness m: the bumpers' strain (either None: not checked;
    members without bumpers, n_bumpers None or inf, never flagged); collapsed (...,) bool
    (engine.results.COLLAPSE; None: a building that cannot collapse).
    """
    accel = np.asarray(peak_total_accel, float)
    force = np.asarray(max_impact_force, float)
    out = {"invalid_floor_accel": floor_accel_exceeds(largest_floor_accel(accel),
                                                      limits.floor_accel)}
    if n_bumpers is None:
        out["invalid_bumper_stress"] = np.zeros(force.shape, dtype=bool)
    else:
        out["invalid_bumper_stress"] = bumper_stress_exceeds(
            bumper_stress(force, n_bumpers, area), limits.bumper_stress)
    if n_bumpers is None or max_indentation is None or thickness is None:
        out["invalid_bumper_strain"] = np.zeros(force.shape, dtype=bool)
    else:
        strained = bumper_strain_exceeds(np.asarray(max_indentation, float),
                                         np.asarray(thickness, float), limits.bumper_strain)
        out["invalid_bumper_strain"] = np.broadcast_to(
            strained & np.isfinite(np.asarray(n_bumpers, float)), force.shape).copy()
    shear = np.asarray(peak_interstory_drift, float) * np.asarray(story_k, float)
    out["invalid_story_shear"] = np.zeros(force.shape, dtype=bool) \
        if limits.story_shear is None or stories_yield \
        else shear.max(axis=-1) > limits.story_shear
    out["invalid_wall_force"] = np.zeros(force.shape, dtype=bool) \
        if limits.wall_force is None else force > limits.wall_force
    out["invalid_collapse"] = np.zeros(force.shape, dtype=bool) if collapsed is None \
        else np.broadcast_to(np.asarray(collapsed, bool), force.shape).copy()
    return {name: out[name] for name in FLAGS}


def flags_of(peaks, building, limits: Limits, n_bumpers=None, area=None,
             thickness=None) -> dict[str, np.ndarray]:
    """`flags` of the engine's peaks for a building: peaks, an engine Result or a dict with
    peak_total_accel (..., levels), peak_interstory_drift (..., stories), max_impact_force
    (...,) and, for the bumpers' strain, max_indentation (...,) as engine.results.PEAKS names
    them (a sweep's blocks: their peaks without the prefix); building: the engine.Building run
    (its story stiffness; stories with a yield force bound their own shear); n_bumpers, area,
    thickness: the bumpers (None: a bare wall; thickness None: strain not checked)."""
    found = peaks_of(peaks)
    indentation = found["max_indentation"] if thickness is not None else None
    return flags(found["peak_total_accel"], found["peak_interstory_drift"],
                 found["max_impact_force"], building.story_stiffness, limits,
                 n_bumpers=n_bumpers, area=area,
                 stories_yield=not building.story_law.is_linear,
                 max_indentation=indentation, thickness=thickness,
                 collapsed=peaks.get("collapsed") if isinstance(peaks, dict)
                 else getattr(peaks, "collapsed", None))


def any_flag(flagged: dict[str, np.ndarray]) -> np.ndarray:
    """(...,) bool: the member left the model's range in any way."""
    return np.any(np.stack(list(flagged.values())), axis=0)
