"""Which time loop runs: the compiled kernel (numba) or the vectorised NumPy reference.

`resolve_backend(None)` picks "numba" when the compiled loop can be imported, else "numpy" and
says so once per process, in one line on stderr (through `warnings`, category BackendNotice).
`time_loop(name)` is the module of that loop (engine/loops/).
"""
from __future__ import annotations

import importlib
import warnings
from types import ModuleType

from .errors import EngineError

BACKENDS = ("numba", "numpy")
_LOOPS = {"numba": "numba_loop", "numpy": "numpy_loop"}
_PLAN_LOOPS = {"numba": "numba_plan", "numpy": "numpy_plan"}
_TORSION_LOOPS = {"numba": "numba_torsion", "numpy": "numpy_torsion"}


class BackendNotice(RuntimeWarning):
    """The compiled kernel is unavailable; the NumPy time loop runs instead."""


_notice_given = False


def time_loop(backend: str) -> ModuleType:
    """The loop module of a backend ("numba" or "numpy"); ImportError for numba without numba.
    Imported on first use: the NumPy loop needs no compiler, and numba takes a second."""
    return importlib.import_module(f"{__package__}.loops.{_LOOPS[backend]}")


def plan_loop(backend: str) -> ModuleType:
    """The loop module of a run in plan (engine/loops/numba_plan.py or numpy_plan.py)."""
    return importlib.import_module(f"{__package__}.loops.{_PLAN_LOOPS[backend]}")


def torsion_loop(backend: str) -> ModuleType:
    """The loop module of buildings that twist (engine/loops/numba_torsion.py or
    numpy_torsion.py)."""
    return importlib.import_module(f"{__package__}.loops.{_TORSION_LOOPS[backend]}")


def resolve_backend(backend: str | None) -> str:
    """"numba" or "numpy" for a requested backend (None: numba if importable)."""
    global _notice_given
    if backend is None:
        try:
            time_loop("numba")
        except ImportError as err:
            if not _notice_given:
                _notice_given = True
                warnings.warn(f"engine: numba unavailable ({err}); running the NumPy time loop",
                              BackendNotice, stacklevel=3)
            return "numpy"
        return "numba"
    if backend not in BACKENDS:
        raise EngineError(f"backend must be one of {BACKENDS} or None, got {backend!r}")
    if backend == "numba":
        try:
            time_loop("numba")
        except ImportError as err:
            raise EngineError(f"backend 'numba' needs numba: {err}") from None
    return backend
