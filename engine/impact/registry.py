"""The impact laws, derived from the modules in engine/impact/laws/ (in the manner of pygmm's
registry: a hand-written list could drift from the modules it lists). Every module of that
folder is a law (see its package docstring for what a law module holds); engine/registry.py
imports each and checks that it is complete; here the laws are numbered: 0 is "no wall", then
1, 2, ... in the laws' ORDER. The numbers are the `Contact.law` codes the time loops dispatch
on; they are never stored (archives and work folders name laws by NAME).
"""
from __future__ import annotations

from types import ModuleType

from ..registry import discover
from . import laws as _laws_package

NONE = 0
"""Law code of a member without moat wall."""
NO_WALL = "none"
"""Its name."""
LAW_INTERFACE = ("NAME", "ORDER", "PARAMETERS", "ROW", "contact_fields", "force_terms",
                 "max_tangent_stiffness")

LAWS: dict[str, ModuleType] = discover(_laws_package, LAW_INTERFACE, reserved=(NO_WALL,))
"""Law name -> its module (PARAMETERS, contact_fields, force_terms, ...), in ORDER."""
LAW_CODES: dict[str, int] = {NO_WALL: NONE, **{name: code for code, name in
                                               enumerate(LAWS, start=1)}}
LAW_NAMES: dict[int, str] = {code: name for name, code in LAW_CODES.items()}
LAW_MODULES: dict[int, ModuleType] = {LAW_CODES[name]: module for name, module in LAWS.items()}
"""Law code -> its module, for the time loops."""
ROW_WIDTH = max(len(module.ROW) for module in LAWS.values())
"""The widest law's packed row (its ROW): the compiled loops' per-member law rows are this
wide, each law's constants first, the rest unused."""
