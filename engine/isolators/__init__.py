"""The isolation system: its laws, one module each in laws/ (bilinear, friction_pendulum,
triple_friction_pendulum; a new law, its state and physics included, is a new module there),
the registry that finds them and numbers them for the time loops, the `Isolator` a building
holds, the slip element the bilinear and friction pendulum laws are made of (hysteresis.py: an
elastic spring in parallel with an elastic-perfectly-plastic one) and the three elements in
series the triple friction pendulum is (series.py: a step's solve along one axis and in
plan), the physics both time loops call."""
from .isolator import Isolator
from .registry import LAWS

__all__ = ["LAWS", "Isolator"]
