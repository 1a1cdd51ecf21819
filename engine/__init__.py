"""bumpers engine: a batched simulator of isolated buildings pounding on a moat wall.

Arrays in, arrays out; SI units (units.py converts the paper's cm, g, kN); a leading batch
axis B on every state array. Where things live:

    model.py      the run's model named once (planar, plan, twisting) and SUPPORTS, the one
                  table of what each model takes
    building.py   the shear building, its fields declared once (declared.py): any number of
                  stories on a story law, P-Delta, collapse, damping; torsion_fields.py its
                  Torsion component (a building that twists: its plan, the masses' offsets,
                  bearings where they stand), torsion.py that model's matrices and the moat's
                  contact points; plan.py the Moat and what a run in plan takes
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
    loops/        each model's NumPy time loop (the readable reference) and compiled one
                  (numba, the default): numpy_loop / numba_loop (planar), numpy_plan /
                  numba_plan, numpy_torsion / numba_torsion
    damping_fit.py  Eq. 9 re-derived by energy equilibrium; units.py, errors.py

Nothing here imports pipeline/ or studies/. The contract is in API.md.
"""
from . import units
from .building import Building
from .errors import EngineError, UnstableTimeStep
from .impact import Contact
from .isolators import Isolator
from .model import MODELS, Model
from .plan import Moat
from .results import History, PlanResult, Result, TorsionResult, TwoBodyResult
from .scheme import DEFAULT_DT
from .simulate import simulate, stable_dt, two_body
from .stories import Stories
from .torsion_fields import Torsion

__all__ = ["Building", "Contact", "DEFAULT_DT", "EngineError", "History", "Isolator",
           "MODELS", "Model", "Moat", "PlanResult", "Result", "Stories", "Torsion",
           "TorsionResult", "TwoBodyResult", "UnstableTimeStep", "simulate", "stable_dt",
           "two_body", "units"]
