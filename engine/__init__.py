"""bumpers engine: a vectorised NumPy simulator of isolated buildings pounding on a moat wall.

Arrays in, arrays out; SI units; a leading batch axis B on every state array. See API.md.
"""
from .building import Building
from .errors import EngineError, UnstableTimeStep
from .impact import Contact
from .integrate import DEFAULT_DT, History, Result, simulate, stable_dt
from .two_body import TwoBodyResult, two_body

__all__ = ["Building", "Contact", "DEFAULT_DT", "EngineError", "History", "Result",
           "TwoBodyResult", "UnstableTimeStep", "simulate", "stable_dt", "two_body"]
