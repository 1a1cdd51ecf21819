"""What the engine returns, declared once: every peak and every time history, with its shape,
unit and meaning (in the manner of xclim's indicators, which declare `units` and `long_name`
once and generate the metadata from them).

Both time loops fill their outputs by these names, the pipeline's executor sizes its arrays
from them, the archives take `units` and `long_name` from them, and figures label axes with
them: a new result, or a changed unit, is one line here.

Shapes are given per member: `along` None is one value, "floor" one per level (level 0 is the
isolation slab), "story" one per story (story i joins level i-1 to level i).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .layout import columns


@dataclass(frozen=True)
class Quantity:
    """One output of the engine.

    name: its name in Result, in the archives and in code; units: UDUNITS string of its SI
    unit; long_name: one line (the archives' long_name); along: None, "floor" or "story" (see
    the module docstring); dtype: float64, or int64 for counts; wall: True for a quantity of
    the moat-wall contact (zero where there is no wall); flags: for a code, the meaning of
    each of its values 0, 1, ... (the archives' CF flag_values and flag_meanings).
    """

    name: str
    units: str
    long_name: str
    along: str | None = None
    dtype: type = np.float64
    wall: bool = False
    direction: bool = False
    flags: tuple[str, ...] = ()

    def trailing_shape(self, n_levels: int, n_walls: int = 1,
                       n_points: int = 1) -> tuple[int, ...]:
        """The member's shape of this quantity for a building of n_levels levels (and a moat
        of n_walls walls, for a quantity along "wall"; of n_points contact points, along
        "point"); a per-direction quantity adds a last axis of 2 (x, y)."""
        lengths = {None: (), "floor": (n_levels,), "story": (n_levels - 1,), "wall": (n_walls,),
                   "point": (n_points,)}
        return lengths[self.along] + ((len(DIRECTIONS),) if self.direction else ())


PEAKS: tuple[Quantity, ...] = (
    Quantity("peak_total_accel", "m s-2", "peak total (absolute) floor acceleration",
             "floor"),
    Quantity("peak_interstory_drift", "m", "peak interstory deflection", "story"),
    Quantity("peak_isolator_disp", "m", "peak isolator displacement"),
    Quantity("max_indentation", "m", "maximum indentation at the moat wall", wall=True),
    Quantity("max_impact_force", "N", "maximum impact force on the moat wall", wall=True),
    Quantity("n_impacts", "1", "number of impacts on the moat wall", dtype=np.int64,
             wall=True),
    Quantity("impact_energy", "J", "energy dissipated by the moat-wall contacts", wall=True),
    Quantity("peak_isolator_force", "N", "peak force of the isolators' law, hysteretic or "
             "frictional (the isolation system's shear V_b of ASCE 7-22 17.5.4.1, the "
             "isolation dashpot's share not included)"),
    Quantity("peak_story_shear", "N", "peak shear force of each story's law, its stiffness "
             "and strength (its dashpot's and P-Delta's shares not included; story 1: the "
             "superstructure's base shear V_s of ASCE 7-22 17.5.4.2)", "story"),
    Quantity("peak_floor_velocity", "m s-1", "peak velocity of each level relative to the "
             "ground", "floor"),
)
"""The peaks of every member, over every step of the run, in Result's order."""

RESIDUALS: tuple[Quantity, ...] = (
    Quantity("residual_isolator_disp", "m", "isolator displacement at the end of the run "
             "(the record's end, no free vibration added; NaN: the run collapsed)"),
    Quantity("residual_interstory_drift", "m", "interstory deflection of each story at the "
             "end of the run (the record's end, no free vibration added; NaN: the run "
             "collapsed)", "story"),
)
"""What stays of the run at its end: magnitudes (resultants in plan; at the plan's centre in
a building that twists), from the loops' last displacements (`residuals`)."""

COLLAPSE_MODES = ("none", "story_drift", "isolator_capacity", "numerical_instability")
"""How a run can end in collapse, by code: 0 it did not; 1 a story's drift past its collapse
drift; 2 the isolator's displacement (a bearing's, in a building that twists) past its
capacity; 3 a state no longer finite. At a step where several are met, the highest code."""
MODE = columns("CollapseMode", *COLLAPSE_MODES)
"""The codes by name (MODE.isolator_capacity == 2), as the loops write them."""

COLLAPSE: tuple[Quantity, ...] = (
    Quantity("collapsed", "1", "the run ended in collapse: a story's drift ratio past the "
             "building's collapse_drift_ratio, the isolator past its displacement capacity, "
             "or a numerical instability", dtype=np.bool_),
    Quantity("collapse_time", "s", "time at which the run ended in collapse (NaN: it did "
             "not)"),
    Quantity("collapse_mode", "1", "how the run ended: " + ", ".join(
        f"{code} {mode.replace('_', ' ')}" for code, mode in enumerate(COLLAPSE_MODES)),
        dtype=np.int8, flags=COLLAPSE_MODES),
)
"""How each member's run ended, beside its peaks (which stop at the step before a collapse:
a collapsed run is a collapse, its peaks no amplification)."""

HISTORIES: tuple[Quantity, ...] = (
    Quantity("isolator_disp", "m",
             "isolator displacement (isolation level relative to the ground)"),
    Quantity("total_accel", "m s-2", "total (absolute) floor acceleration", "floor"),
    Quantity("impact_force", "N", "impact force on the moat wall (0 out of contact)",
             wall=True),
    Quantity("indentation", "m", "indentation at the moat wall (0 out of contact)",
             wall=True),
    Quantity("isolator_force", "N", "force of the isolators' law (against isolator_disp: its "
             "hysteresis loop)"),
)
"""The time histories kept for the members an engine.History asks for, against time."""

DIRECTIONS = ("x", "y")
"""The horizontal directions of a run in plan, the last axis of its per-direction results."""
WALLS = {"rectangular": ("+x", "-x", "+y", "-y"), "circular": ("all",)}
"""The walls of each moat in plan: the rectangular moat's four, each named by its outward
normal; the circular moat's one."""

PLAN_PEAKS: tuple[Quantity, ...] = (
    Quantity("peak_total_accel_xy", "m s-2", "peak total floor acceleration in each "
             "direction", "floor", direction=True),
    Quantity("peak_interstory_drift_xy", "m", "peak interstory deflection in each direction",
             "story", direction=True),
    Quantity("peak_isolator_disp_xy", "m", "peak isolator displacement in each direction",
             direction=True),
    Quantity("max_impact_force_wall", "N", "maximum impact force on each wall of the moat",
             "wall", wall=True),
)
"""What a run in plan returns besides PEAKS, whose quantities it gives as resultants (vector
magnitudes: the peak of |u_0(t)|, of |a(t)| per level, of the drift vector per story)."""

PLAN_HISTORIES: tuple[Quantity, ...] = (
    Quantity("isolator_disp", "m", "isolator displacement in each direction (the orbit)",
             direction=True),
    Quantity("total_accel", "m s-2", "total (absolute) floor acceleration in each direction",
             "floor", direction=True),
    Quantity("impact_force", "N", "magnitude of the moat's force on the slab (0 out of "
             "contact)", wall=True),
    Quantity("indentation", "m", "deepest indentation into a wall (0 out of contact)",
             wall=True),
    Quantity("isolator_force", "N", "force of the isolators' law in each direction (against "
             "isolator_disp: its hysteresis loops)", direction=True),
)
"""The time histories of a run in plan: HISTORIES with a last axis of directions where a
quantity has one."""


TORSION_PEAKS: tuple[Quantity, ...] = (
    Quantity("peak_corner_disp", "m", "peak isolator displacement at the slab's worst corner "
             "(resultant)"),
    Quantity("peak_rotation", "rad", "peak rotation of the isolation slab about the vertical"),
    Quantity("max_point_force", "N", "maximum force on each contact point of the moat (a "
             "corner against a bare wall, a bumper)", "point", wall=True),
    Quantity("max_point_indentation", "m", "maximum indentation at each contact point of the "
             "moat", "point", wall=True),
)
"""What a run of a building that twists returns besides PEAKS (at the plan's centre) and
PLAN_PEAKS (max_impact_force_wall: the peak of the sum of a wall's points' forces;
max_impact_force the largest of them)."""

TORSION_HISTORIES: tuple[Quantity, ...] = (
    *PLAN_HISTORIES,
    Quantity("floor_disp", "m", "displacement of each level's plan centre in each direction",
             "floor", direction=True),
    Quantity("floor_rotation", "rad", "rotation of each level about the vertical", "floor"),
)
"""The time histories of a building that twists: the plan's (at the plan's centre) and every
level's displacement and rotation (the corners' orbits follow: engine.torsion.corner_orbits)."""


def empty_plan_history(rows: int, n_steps: int, every: int, dt: float,
                       n_levels: int, torsion: bool = False) -> dict[str, np.ndarray]:
    """Zeroed histories in plan (of a building that twists: `torsion`) for `rows` members,
    every `every`-th of n_steps steps, with their time (T,) s."""
    n_out = (n_steps - 1) // every + 1
    return {"time": np.arange(n_out) * every * dt,
            **{q.name: np.zeros((rows, n_out, *q.trailing_shape(n_levels)))
               for q in (TORSION_HISTORIES if torsion else PLAN_HISTORIES)}}


PEAK_NAMES = tuple(q.name for q in PEAKS)
HISTORY_NAMES = tuple(q.name for q in HISTORIES)


def quantity(name: str) -> Quantity:
    """The declaration of a peak or history by name."""
    for q in (*PEAKS, *HISTORIES):
        if q.name == name:
            return q
    raise KeyError(name)


def level_axes(n_levels: int) -> dict[str, tuple[np.ndarray, str, str]]:
    """The trailing axes of the results, for labelling: "floor" and "story" -> (values,
    units, long_name), for a building of n_levels levels."""
    top = n_levels - 1
    return {"floor": (np.arange(n_levels), "1",
                      f"level (0 = isolation level, {top} = roof)"),
            "story": (np.arange(1, n_levels), "1",
                      "story (story i joins level i-1 to level i)")}


def run_quantities(moat: str | None = None, collapse: bool = False,
                   torsion: bool = False) -> tuple[Quantity, ...]:
    """What a run returns and an archive keeps of it: PEAKS, then PLAN_PEAKS for a run in
    plan (`moat`), then TORSION_PEAKS for a building that twists, then COLLAPSE for a
    building with a collapse criterion (so that a building without one, the paper's, keeps
    the archive it had)."""
    return (*PEAKS, *(PLAN_PEAKS if moat is not None else ()),
            *(TORSION_PEAKS if torsion else ()), *RESIDUALS, *(COLLAPSE if collapse else ()))


def residuals(disp: np.ndarray, collapsed: np.ndarray) -> dict[str, np.ndarray]:
    """RESIDUALS from the last displacements `disp` (B, L) m of each level relative to the
    ground ((B, L, 2) in plan: magnitudes of the vectors), NaN where `collapsed` (B,)."""
    disp = np.asarray(disp, dtype=np.float64)
    drift = np.diff(disp, axis=1)
    if disp.ndim == 3:
        base, drift = np.hypot(disp[:, 0, 0], disp[:, 0, 1]), np.hypot(drift[..., 0],
                                                                         drift[..., 1])
    else:
        base, drift = np.abs(disp[:, 0]), np.abs(drift)
    fallen = np.asarray(collapsed, dtype=bool)
    return {"residual_isolator_disp": np.where(fallen, np.nan, base),
            "residual_interstory_drift": np.where(fallen[:, None], np.nan, drift)}


def empty_collapse(size: int) -> dict[str, np.ndarray]:
    """No member collapsed yet: collapsed (size,) False, collapse_time (size,) NaN,
    collapse_mode (size,) 0."""
    return {"collapsed": np.zeros(size, dtype=bool), "collapse_time": np.full(size, np.nan),
            "collapse_mode": np.zeros(size, dtype=np.int8)}


def empty_peaks(size: int, n_levels: int, moat: str | None = None,
                collapse: bool = False, n_points: int | None = None) -> dict[str, np.ndarray]:
    """(size, ...) arrays of every quantity of run_quantities(moat, collapse, torsion), zeroed
    (no member collapsed, collapse_time NaN), for a building of n_levels levels; n_points:
    None, or the contact points of a building that twists (TORSION_PEAKS)."""
    walls = 1 if moat is None else len(WALLS[moat])
    out = {q.name: np.zeros((size, *q.trailing_shape(n_levels, walls, n_points or 1)),
                            dtype=q.dtype)
           for q in run_quantities(moat, collapse, n_points is not None)}
    if collapse:
        out["collapse_time"][:] = np.nan
    return out


@dataclass(frozen=True)
class History:
    """Ask for time histories of some members: batch indices and every how many steps."""

    members: Sequence[int]
    every: int = 1


@dataclass
class Result:
    """Peaks per member, in batch order (SI units, declared in PEAKS), and optional histories.

    peak_total_accel (B, levels) m/s^2, peak_interstory_drift (B, stories) m,
    peak_isolator_disp (B,) m, max_indentation (B,) m, max_impact_force (B,) N, n_impacts (B,),
    impact_energy (B,) J: work done on the wall contacts, i.e. energy dissipated by impacts
    once contacts close; peak_isolator_force (B,) N, peak_story_shear (B, stories) N,
    peak_floor_velocity (B, levels) m/s; residual_isolator_disp (B,) m and
    residual_interstory_drift (B, stories) m (RESIDUALS); dt: the integration step (s);
    collapsed (B,) bool, collapse_time (B,) s, NaN where none, and collapse_mode (B,) int8
    (COLLAPSE, COLLAPSE_MODES); history: None or a dict of time (T,) s, members (M,) and every
    HISTORIES quantity, (M, T) or (M, T, levels).
    """

    peak_total_accel: np.ndarray
    peak_interstory_drift: np.ndarray
    peak_isolator_disp: np.ndarray
    max_indentation: np.ndarray
    max_impact_force: np.ndarray
    n_impacts: np.ndarray
    impact_energy: np.ndarray
    peak_isolator_force: np.ndarray
    peak_story_shear: np.ndarray
    peak_floor_velocity: np.ndarray
    residual_isolator_disp: np.ndarray
    residual_interstory_drift: np.ndarray
    dt: float
    history: dict | None = None
    collapsed: np.ndarray | None = None
    collapse_time: np.ndarray | None = None
    collapse_mode: np.ndarray | None = None

    def peaks(self) -> dict[str, np.ndarray]:
        """Peak name -> array, in PEAKS order."""
        return {name: getattr(self, name) for name in PEAK_NAMES}

    def residuals(self) -> dict[str, np.ndarray]:
        """RESIDUALS name -> array."""
        return {q.name: getattr(self, q.name) for q in RESIDUALS}


@dataclass
class PlanResult(Result):
    """A run in plan: PEAKS as resultants (see Result), then PLAN_PEAKS: peak_total_accel_xy
    (B, levels, 2) m/s^2, peak_interstory_drift_xy (B, stories, 2) m, peak_isolator_disp_xy
    (B, 2) m, max_impact_force_wall (B, walls) N (WALLS[moat] order); moat: its shape."""

    peak_total_accel_xy: np.ndarray = None
    peak_interstory_drift_xy: np.ndarray = None
    peak_isolator_disp_xy: np.ndarray = None
    max_impact_force_wall: np.ndarray = None
    moat: str = "rectangular"

    def plan_peaks(self) -> dict[str, np.ndarray]:
        """PLAN_PEAKS name -> array."""
        return {q.name: getattr(self, q.name) for q in PLAN_PEAKS}


@dataclass
class TorsionResult(PlanResult):
    """A run of buildings that twist: PlanResult's peaks at the plan's centre, then
    TORSION_PEAKS: peak_corner_disp (B,) m, peak_rotation (B,) rad, max_point_force and
    max_point_indentation (B, P) N and m per contact point; points: the moat's contact points
    (engine.torsion.ContactPoints: each point's wall, position along it, share of its law)."""

    peak_corner_disp: np.ndarray = None
    peak_rotation: np.ndarray = None
    max_point_force: np.ndarray = None
    max_point_indentation: np.ndarray = None
    points: object = None

    def torsion_peaks(self) -> dict[str, np.ndarray]:
        """TORSION_PEAKS name -> array."""
        return {q.name: getattr(self, q.name) for q in TORSION_PEAKS}


@dataclass
class TwoBodyResult:
    """Per member (B,): peak_force N, peak_indentation m, cor (measured, -v_out / v),
    dissipated_energy J (kinetic energy lost, 1/2 m_eff (v^2 - v_out^2)), hysteresis_area J
    (closed integral of F d(delta)), expected_energy_loss J (Eq. 5 with the target COR),
    dt s; histories (B, T): indentation m, force N (zero after separation)."""

    peak_force: np.ndarray
    peak_indentation: np.ndarray
    cor: np.ndarray
    dissipated_energy: np.ndarray
    hysteresis_area: np.ndarray
    expected_energy_loss: np.ndarray
    dt: np.ndarray
    indentation: np.ndarray
    force: np.ndarray
