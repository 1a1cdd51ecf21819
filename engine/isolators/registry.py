"""The isolator laws, derived from the modules in engine/isolators/laws/ (engine/registry.py)."""
from __future__ import annotations

from types import ModuleType

from ..errors import EngineError
from ..registry import discover
from . import laws as _laws_package

LAW_INTERFACE = ("NAME", "ORDER", "PARAMETERS", "DEFAULT_ZETA", "DASHPOT_TEXT", "check",
                 "fields", "initial_stiffness", "yield_displacement", "effective_stiffness",
                 "displacement_capacity", "ROW", "CARRIED", "STATE", "STATE_XY", "force",
                 "advance", "force_xy", "advance_xy")
CODE_INTERFACE = ("post_yield_stiffness", "energy_per_cycle", "bounded")
"""What a law gives the code's equivalent-linear design (pipeline.motions.target.isolation_design)
and its property bounds (pipeline.motions.bounds: `bounded(values, lambda_q, lambda_k)`):
optional, so that a law can be run without them; law_function says which is missing."""

LAWS: dict[str, ModuleType] = discover(_laws_package, LAW_INTERFACE)
"""Isolator law name -> its module, in ORDER."""
LAW_CODES: dict[str, int] = {name: code for code, name in enumerate(LAWS)}
"""Isolator law name -> its code in the time loops (0 the first law: bilinear)."""
BY_CODE: tuple[ModuleType, ...] = tuple(LAWS.values())
"""Isolator law code -> its module."""
MAX_FIELDS = max(len(module.ROW) for module in LAWS.values())
"""The widest law's ROW: the loops' (B, MAX_FIELDS) isolator constants are this wide."""
MAX_STATE = max(len(module.STATE) for module in LAWS.values())
"""The widest law's STATE along one axis (the planar loops' state per member)."""
MAX_STATE_XY = max(len(module.STATE_XY) for module in LAWS.values())
"""The widest law's STATE_XY in plan (the loops' state per member, or per bearing)."""


def law_function(law: str, name: str):
    """The function `name` of the isolator law `law` (a name of LAWS). EngineError (a
    ValueError) naming the law and its module when the law does not declare it, e.g. a
    law without CODE_INTERFACE asked for the code's design."""
    module = LAWS[law]
    function = getattr(module, name, None)
    if function is None:
        raise EngineError(f"the {law} isolator law declares no {name} (declare it in "
                          f"{module.__name__} to use the law here)")
    return function
