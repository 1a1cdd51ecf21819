"""The isolation system: its laws, one module each in laws/ (bilinear, friction_pendulum; a new
law is a new module there), the registry that finds them, the `Isolator` a building holds, and
the hysteresis every law reduces to (hysteresis.py: an elastic spring in parallel with a slip
element, the physics both time loops call)."""
from .isolator import Isolator
from .registry import LAWS

__all__ = ["LAWS", "Isolator"]
