"""bumpers engine: a batched simulator of isolated buildings pounding on a moat wall.

Arrays in, arrays out; SI units (units.py converts the paper's cm, g, kN); a leading batch
axis B on every state array. building.py holds the structure, isolator.py the bilinear law,
impact/ one module per wall law, each declaring its parameters once (impact/parameters.py),
kernel.py the compiled time loop (the default), integrate.py the vectorised NumPy one (the
readable reference; both call the same law functions), two_body.py section 3's impacts. The
contract is in API.md.
"""
from . import units
from .building import Building
from .errors import EngineError, UnstableTimeStep
from .impact import Contact
from .integrate import DEFAULT_DT, History, Result, simulate, stable_dt
from .two_body import TwoBodyResult, two_body

__all__ = ["Building", "Contact", "DEFAULT_DT", "EngineError", "History", "Result",
           "TwoBodyResult", "UnstableTimeStep", "simulate", "stable_dt", "two_body", "units"]
