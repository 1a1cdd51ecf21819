"""The linear story (the paper's, SPEC section 1): force k drift, k the building's
story_stiffness. No state, no parameter of its own."""
import numpy as np

from ...parameters import Declaration

NAME = "linear"
"""The law's name in Stories.of, building files and archives."""
ORDER = 1
"""Its place in listings."""
LINEAR = True
"""The loops multiply the drift by the stiffness directly (the paper's building: its numbers
and its speed), never calling `force`."""
PARAMETERS = Declaration()
N_FIELDS = 1
N_STATE = 0


def check():
    """Nothing to check: the stiffness is the building's."""


def fields(stiffness):
    """(N, 1): each story's stiffness k (N/m)."""
    return np.asarray(stiffness, float)[:, None]


def initial_state(row):
    return np.zeros(0)


def force(drift, state, row):
    """k drift (N)."""
    return row[0] * drift


def strength(stiffness):
    """(N,) the largest force each story can carry (N): unbounded."""
    return np.full(len(stiffness), np.inf)


def plan_fields(stiffness):
    """The stories in plan as an elastic spring plus a slip element with a circular yield
    surface (engine/isolators/hysteresis.radial_return): (k_elastic, k_slip, f_limit), (N,)
    each; linear: k, 0, inf."""
    k = np.asarray(stiffness, float)
    return k, np.zeros_like(k), np.full_like(k, np.inf)


def code_values(strength, height, **backbone):
    """The law's values for stories of a designed strength (N,) N and height (N,) m: none,
    a linear story has no strength of its own (nor backbone: its drift ratios do not
    apply)."""
    return {}


def yield_strength(stiffness):
    """(N,) the force at which each story starts to yield (N): never."""
    return np.full(len(stiffness), np.inf)
