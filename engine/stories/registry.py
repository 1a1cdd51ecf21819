"""The story laws, derived from the modules in engine/stories/laws/ (engine/registry.py), with
the integer code each law has in the time loops' dispatch."""
from __future__ import annotations

from types import ModuleType

from ..registry import discover
from . import laws as _laws_package

LAW_INTERFACE = ("NAME", "ORDER", "PARAMETERS", "N_FIELDS", "N_STATE", "check", "fields",
                 "initial_state", "force", "strength", "yield_strength", "code_values")

LAWS: dict[str, ModuleType] = discover(_laws_package, LAW_INTERFACE)
"""Story law name -> its module, in ORDER."""
LAW_CODES: dict[str, int] = {name: code for code, name in enumerate(LAWS)}
"""Story law name -> its code in the time loops (0 the first law: linear)."""
BY_CODE: tuple[ModuleType, ...] = tuple(LAWS.values())
"""Story law code -> its module."""
MAX_FIELDS = max(module.N_FIELDS for module in LAWS.values())
"""The widest law's constants per story: the loops' (B, N, MAX_FIELDS) arrays are this wide."""
MAX_STATE = max(module.N_STATE for module in LAWS.values())
"""The widest law's state per story: the loops' (B, N, MAX_STATE) arrays are this wide."""
