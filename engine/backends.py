"""Which time loop runs: the compiled kernel (numba) or the vectorised NumPy reference.

`resolve_backend(None)` picks "numba" when engine.kernel can be imported, else "numpy" and says
so once per process, in one line on stderr (through `warnings`, category BackendNotice).
"""
from __future__ import annotations

import importlib
import warnings

from .errors import EngineError

BACKENDS = ("numba", "numpy")


class BackendNotice(RuntimeWarning):
    """The compiled kernel is unavailable; the NumPy time loop runs instead."""


_notice_given = False


def load_kernel():
    """The engine.kernel module (compiles nothing yet); ImportError without numba."""
    return importlib.import_module(".kernel", __package__)


def kernel_available() -> bool:
    try:
        load_kernel()
    except ImportError:
        return False
    return True


def resolve_backend(backend: str | None) -> str:
    """"numba" or "numpy" for a requested backend (None: numba if importable)."""
    global _notice_given
    if backend is None:
        try:
            load_kernel()
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
            load_kernel()
        except ImportError as err:
            raise EngineError(f"backend 'numba' needs numba: {err}") from None
    return backend
