"""The isolator laws, derived from the modules in engine/isolators/laws/ (engine/registry.py)."""
from __future__ import annotations

from types import ModuleType

from ..registry import discover
from . import laws as _laws_package

LAW_INTERFACE = ("NAME", "ORDER", "PARAMETERS", "DEFAULT_ZETA", "check", "fields",
                 "initial_stiffness", "yield_displacement", "effective_stiffness")

LAWS: dict[str, ModuleType] = discover(_laws_package, LAW_INTERFACE)
"""Isolator law name -> its module, in ORDER."""
