"""The bilinear story with kinematic hardening: elastic k up to the yield drift F_y / k, then
post_yield_ratio k; an elastic spring post_yield_ratio k in parallel with an
elastic-perfectly-plastic spring (1 - post_yield_ratio) k that slips at
(1 - post_yield_ratio) F_y, return-mapped exactly (the isolator's slip element,
engine/isolators/hysteresis.py, for one story). OpenSees' Steel01 without isotropic hardening
is the same law (tests/reference/opensees_reference.py)."""
import numpy as np

from ...isolators.hysteresis import plastic_spring_force
from ...parameters import REQUIRED, Declaration, Parameter

NAME = "bilinear"
ORDER = 2
LINEAR = False
PARAMETERS = Declaration(
    Parameter("yield_force", "N", "story yield force F_y", REQUIRED, "(0, inf)",
              plausible="[1e3, 1e10]"),
    Parameter("post_yield_ratio", "1", "story post-yield stiffness over its elastic stiffness",
              0.02, "[0, 1)"),
)
N_FIELDS = 3
"""Per story: post-yield stiffness (N/m), slip stiffness (N/m), slip limit (N)."""
N_STATE = 2
"""Per story: the slip element's force (N) and the drift it was last committed at (m)."""


def check(yield_force, post_yield_ratio):
    """Nothing beyond each value's range."""


def fields(stiffness, yield_force, post_yield_ratio):
    """(N, 3): post_yield_ratio k, (1 - post_yield_ratio) k, (1 - post_yield_ratio) F_y."""
    k = np.asarray(stiffness, float)
    ratio = np.asarray(post_yield_ratio, float)
    return np.column_stack([ratio * k, (1 - ratio) * k, (1 - ratio) * np.asarray(yield_force)])


def initial_state(row):
    return np.zeros(N_STATE)


def force(drift, state, row):
    """The post-yield spring's force plus the slip element's, return-mapped over the drift
    increment since the last step (N); commits the slip force and the drift."""
    slip = plastic_spring_force(state[0], drift - state[1], row[1], row[2])
    state[0] = slip
    state[1] = drift
    return row[0] * drift + slip


def strength(stiffness, yield_force, post_yield_ratio):
    """(N,) the yield force (N): hardening has no cap, the yield force is the capacity."""
    return np.asarray(yield_force, float) * np.ones(len(stiffness))


def plan_fields(stiffness, yield_force, post_yield_ratio):
    """In plan (see linear.plan_fields): the same springs, the slip element's yield surface a
    circle of radius (1 - post_yield_ratio) F_y."""
    row = fields(stiffness, yield_force, post_yield_ratio)
    return row[:, 0], row[:, 1], row[:, 2]


def code_values(strength, height, **backbone):
    """The law's values for stories of a designed strength (N,) N and height (N,) m: yielding
    at the strength, the default hardening (a lateral system's backbone drift ratios, for a
    law that caps and deteriorates, do not apply)."""
    return {"yield_force": tuple(map(float, strength))}


def yield_strength(stiffness, yield_force, post_yield_ratio):
    """(N,) the force at which each story starts to yield (N): F_y."""
    return np.asarray(yield_force, float) * np.ones(len(stiffness))
