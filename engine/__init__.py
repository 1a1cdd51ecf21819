"""bumpers engine: a batched simulator of isolated buildings pounding on a moat wall.

Arrays in, arrays out; SI units (units.py converts the paper's cm, g, kN); a leading batch
axis B on every state array. Where things live:

    building.py   the shear building: any number of stories on a story law, P-Delta,
                  collapse, damping; torsion.py: a building that twists in plan (its plan,
                  eccentric masses, bearings where they stand, the moat's contact points)
    stories/      the story laws, one module each in stories/laws/ (linear, bilinear, imk),
                  and the Stories a building's stories follow
    isolators/    the isolator laws, one module each in isolators/laws/ (bilinear, friction
                  pendulum), the Isolator a building stands on, and the hysteresis they share
    impact/       the moat-wall impact laws, one module each in impact/laws/ (each declares
                  its parameters once), the registry that finds them, and Contact
    parameters.py how a law declares its parameters; registry.py how laws are found
    scheme.py     the integration scheme: default dt, step operators, stability limit, the
                  exact contact solve and onset weighting, shared by both loops
    results.py    what the engine returns, declared once (every peak and history: shape, unit,
                  long name), and the Result / History / TwoBodyResult types
    simulate.py   the entry points simulate(), two_body(), stable_dt(); backends.py picks the loop
    loops/        the NumPy time loop (the readable reference) and the compiled one (numba,
                  the default): both import only the scheme, the laws and the results
    damping_fit.py  Eq. 9 re-derived by energy equilibrium; units.py, errors.py

Nothing here imports pipeline/ or studies/. The contract is in API.md.
"""
from . import units
from .building import Building
from .errors import EngineError, UnstableTimeStep
from .impact import Contact
from .isolators import Isolator
from .results import History, PlanResult, Result, TorsionResult, TwoBodyResult
from .scheme import DEFAULT_DT
from .simulate import simulate, stable_dt, two_body
from .stories import Stories

__all__ = ["Building", "Contact", "DEFAULT_DT", "EngineError", "History", "Isolator",
           "PlanResult", "Result", "Stories", "TorsionResult", "TwoBodyResult",
           "UnstableTimeStep", "simulate", "stable_dt", "two_body", "units"]
