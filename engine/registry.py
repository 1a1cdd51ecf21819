"""Laws found, not listed: every module of a `laws/` folder is a law (in the manner of pygmm's
registry, since a hand-written list can drift from the modules it lists). The impact laws
(engine/impact/laws/) and the isolator laws (engine/isolators/laws/) are registered so.
"""
from __future__ import annotations

import importlib
import pkgutil
from types import ModuleType


def discover(package: ModuleType, interface: tuple[str, ...],
             reserved: tuple[str, ...] = ()) -> dict[str, ModuleType]:
    """Law NAME -> module for every module of `package`, sorted by (ORDER, NAME).

    Each module must define every name of `interface` (NAME and ORDER among them); ImportError
    for one that does not, for two laws of one NAME, or for a NAME in `reserved`.
    """
    modules = []
    for info in pkgutil.iter_modules(package.__path__):
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        missing = [name for name in interface if not hasattr(module, name)]
        if missing:
            raise ImportError(f"{module.__name__} is in {package.__name__} but is not a law: "
                              f"it lacks {', '.join(missing)}")
        modules.append(module)
    modules.sort(key=lambda m: (m.ORDER, m.NAME))
    names = [m.NAME for m in modules]
    if len(set(names)) != len(names) or set(names) & set(reserved):
        raise ImportError(f"law names in {package.__name__} must be unique and none of "
                          f"{reserved}: {names}")
    return {m.NAME: m for m in modules}
