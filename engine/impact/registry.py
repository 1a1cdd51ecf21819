"""The impact laws, derived from the modules in engine/impact/laws/ (in the manner of pygmm's
registry: a hand-written list could drift from the modules it lists).

Every module of that folder is a law (see its package docstring for what a law module holds);
the registry imports each, checks that it is complete, and numbers the laws: 0 is "no wall",
then 1, 2, ... in the laws' ORDER. The numbers are the `Contact.law` codes the time loops
dispatch on; they are never stored (archives and work folders name laws by NAME).
"""
from __future__ import annotations

import importlib
import pkgutil
from types import ModuleType

from . import laws as _laws_package

NONE = 0
"""Law code of a member without moat wall."""
NO_WALL = "none"
"""Its name."""
LAW_INTERFACE = ("NAME", "ORDER", "PARAMETERS", "contact_fields", "force_terms",
                 "max_tangent_stiffness")


def _discover() -> dict[str, ModuleType]:
    modules = []
    for info in pkgutil.iter_modules(_laws_package.__path__):
        module = importlib.import_module(f"{_laws_package.__name__}.{info.name}")
        missing = [name for name in LAW_INTERFACE if not hasattr(module, name)]
        if missing:
            raise ImportError(f"{module.__name__} is in engine/impact/laws/ but is not an "
                              f"impact law: it lacks {', '.join(missing)}")
        modules.append(module)
    modules.sort(key=lambda m: (m.ORDER, m.NAME))
    names = [m.NAME for m in modules]
    if len(set(names)) != len(names) or NO_WALL in names:
        raise ImportError(f"impact law names must be unique and not {NO_WALL!r}: {names}")
    return {m.NAME: m for m in modules}


LAWS: dict[str, ModuleType] = _discover()
"""Law name -> its module (PARAMETERS, contact_fields, force_terms, ...), in ORDER."""
LAW_CODES: dict[str, int] = {NO_WALL: NONE, **{name: code for code, name in
                                               enumerate(LAWS, start=1)}}
LAW_NAMES: dict[int, str] = {code: name for name, code in LAW_CODES.items()}
LAW_MODULES: dict[int, ModuleType] = {LAW_CODES[name]: module for name, module in LAWS.items()}
"""Law code -> its module, for the time loops."""
