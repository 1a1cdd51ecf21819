"""The building that twists, as a component beside Isolator and Stories: its plan, where its
masses sit, their polar inertia, its bearings where they stand, and its stories' torsional
stiffness and centre, each field declared once (engine/declared.py).

    engine.Building(torsion=engine.Torsion(plan_size=(30.0, 20.0), mass_offset=(1.5, 0.0)))

A Building with a `torsion` component runs the twisting model (engine/model.py; the physics in
engine/torsion.py). The accidental eccentricity of ASCE 7-22 17.5.3.3, a fraction of the plan
by which a sweep moves every level's mass (`ACCIDENTAL_ECCENTRICITY`, `Torsion.shifted`), is a
parameter of its own, distinct from `mass_offset`, the mass centre's offset in metres.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .declared import checked, declared, fields_of
from .errors import EngineError
from .parameters import Parameter

ACCIDENTAL_ECCENTRICITY = Parameter(
    "accidental_eccentricity", "1", "accidental eccentricity: every level's mass centre moved "
    "by this fraction of each plan dimension (e_x + e b_x, e_y + e b_y) from the building's "
    "own", 0.0, "[0, 0.5)", equation="ASCE 7-22 17.5.3.3 (5%)",
    sweep="accidental_eccentricity", plausible="[0, 0.2]")
"""A member's accidental eccentricity (pipeline.sweep's accidental_eccentricity;
Torsion.shifted): the mass moved along the plan's diagonal, which loads both directions'
torsion at once."""


@dataclass(frozen=True)
class Torsion:
    """What a building that twists has beyond a building in plan (SI; see engine/torsion.py
    for the model). Values are checked on construction (the plan, the pairs within it, the
    bearings under the slab); their counts per level and per story when the Building that
    holds them is made (`for_building`)."""

    plan_size: tuple = declared(
        None, "m", "the rectangular plan (b_x, b_y) of every level", per="pair",
        valid="(0, inf)", plausible="[2, 500]")
    mass_offset: tuple = declared(
        (0.0, 0.0), "m", "each level's mass centre from its plan's centre (e_x, e_y): one "
        "pair, or one per level", per="pair", pairs_per="level")
    mass_inertia: tuple | None = declared(
        None, "kg m2", "the polar moment of each level's mass about its own centre (None: "
        "uniform slabs, m (b_x^2 + b_y^2) / 12)", per="level", valid="(0, inf)", optional=True)
    isolator_positions: tuple | None = declared(
        None, "m", "the bearings' positions (X, Y) from the plan's centre, each carrying 1/n "
        "of the isolator (None: a 4 x 4 grid, the outer bearings at the slab's edges)",
        per="point", optional=True)
    story_torsional_stiffness: tuple | None = declared(
        None, "N m rad-1", "each story's torsional stiffness about its centre of stiffness "
        "(None: a perimeter frame's, k_y (b_x/2)^2 + k (b_y/2)^2)", per="story",
        valid="(0, inf)", optional=True)
    story_stiffness_centre: tuple | None = declared(
        None, "m", "where each story's stiffness acts (x_s, y_s) from the plan's centre: one "
        "pair, or one per story (None: the plan's centre)", per="pair", pairs_per="story",
        optional=True)

    def __post_init__(self):
        b_x, b_y = plan_dimensions(self.plan_size)
        object.__setattr__(self, "plan_size", (b_x, b_y))
        half = np.array([b_x, b_y]) / 2
        for name in ("mass_offset", "story_stiffness_centre"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, _pairs(name, getattr(self, name), half))
        for name in ("mass_inertia", "story_torsional_stiffness"):
            values = getattr(self, name)
            if values is not None:  # their count is the building's (for_building)
                count = np.size(values) if np.ndim(values) == 1 else 1
                object.__setattr__(self, name, checked(name, FIELDS[name], values, count))
        if self.isolator_positions is not None:
            object.__setattr__(self, "isolator_positions",
                               _bearings(self.isolator_positions, half))

    def for_building(self, n_levels: int, n_stories: int) -> Torsion:
        """This component checked against a building of n_levels levels and n_stories stories:
        one value (or pair) per level or per story where more than one is given; EngineError
        naming the field otherwise."""
        counts = {"level": n_levels, "story": n_stories}
        for name, spec in FIELDS.items():
            value = getattr(self, name)
            per = spec.pairs_per or spec.per
            if value is None or per not in counts:
                continue
            if spec.per == "pair":
                if np.shape(value) != (2,) and np.shape(value) != (counts[per], 2):
                    raise EngineError(f"{name} must be (x, y) in metres, or one pair per {per} "
                                      f"({counts[per]}), within the plan, got {value!r}")
            else:
                checked(name, spec, value, counts[per])
        return self

    def shifted(self, fraction: float) -> Torsion:
        """This component with every level's mass centre moved by fraction (b_x, b_y)
        (ACCIDENTAL_ECCENTRICITY), itself at 0."""
        fraction = float(ACCIDENTAL_ECCENTRICITY.check(np.asarray(fraction, float)))
        if fraction == 0:
            return self
        moved = np.asarray(self.mass_offset, float) + fraction * np.asarray(self.plan_size)
        return dataclasses.replace(self, mass_offset=tuple(map(tuple, moved.tolist()))
                                   if moved.ndim == 2 else tuple(moved.tolist()))


FIELDS = fields_of(Torsion)
"""name -> Field of every field of a Torsion, in order (plan_size first)."""


def plan_dimensions(plan_size) -> tuple[float, float]:
    """(b_x, b_y) m, checked positive and finite."""
    size = np.asarray(plan_size, float) if plan_size is not None else np.zeros(0)
    if size.shape != (2,) or not np.all(np.isfinite(size) & (size > 0)):
        raise EngineError(f"plan_size must be (b_x, b_y), positive metres, got {plan_size!r}")
    return float(size[0]), float(size[1])


def _pairs(name: str, given, half: np.ndarray) -> tuple:
    """Field `name`: one (x, y) pair (m) or several, within the plan (half its dimensions,
    half), as a tuple of floats or of pairs (EngineError otherwise)."""
    try:
        pairs = np.asarray(given, float)
    except (TypeError, ValueError):
        pairs = np.zeros((0, 0))
    if pairs.shape[-1:] != (2,) or pairs.ndim not in (1, 2) or not np.all(np.isfinite(pairs)) \
            or np.any(np.abs(pairs) > half):
        raise EngineError(f"{name} must be (x, y) in metres, or one pair per "
                          f"{FIELDS[name].pairs_per}, within the plan, got {given!r}")
    return tuple(pairs.tolist()) if pairs.ndim == 1 else tuple(map(tuple, pairs.tolist()))


def _bearings(given, half: np.ndarray) -> tuple:
    """isolator_positions as a tuple of pairs: (n, 2) m, n >= 2, under the slab, not all at
    one point (EngineError otherwise)."""
    xy = np.asarray(given, float)
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 2 or not np.all(np.isfinite(xy)) \
            or np.any(np.abs(xy) > half * (1 + 1e-12)):
        raise EngineError(f"isolator_positions must be (n, 2) metres from the plan's "
                          f"centre, n >= 2, under the slab, got shape {xy.shape}")
    if np.ptp(xy[:, 0]) == 0 and np.ptp(xy[:, 1]) == 0:
        raise EngineError("isolator_positions: the bearings stand at one point, the slab "
                          "would have no torsional stiffness")
    return tuple(map(tuple, xy.tolist()))
