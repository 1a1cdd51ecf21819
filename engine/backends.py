"""Which time loop runs: the compiled kernel (numba), the vectorised NumPy reference, or the
device loop on an NVIDIA GPU (cuda, asked for by name: never a default).

`resolve_backend(None)` picks "numba" when the compiled loop can be imported, else "numpy" and
says so once per process, in one line on stderr (through `warnings`, category BackendNotice).
`model_loop(model, name)` is the module of that loop for a model (engine/model.py: each model
names its loops, engine/loops/<backend>_<model.loop>.py); `time_loop(name)` the planar one.
Which loops run a model is its "backend" row of engine.model.SUPPORTS.
"""
from __future__ import annotations

import importlib
import warnings
from types import ModuleType

from .errors import EngineError
from .model import PLANAR

BACKENDS = ("numba", "numpy", "cuda")


class BackendNotice(RuntimeWarning):
    """The compiled kernel is unavailable; the NumPy time loop runs instead."""


_notice_given = False


def model_loop(model, backend: str) -> ModuleType:
    """The loop module of a model (engine.model.Model) and backend (BACKENDS; loop_of checks
    that the model runs on it): engine/loops/<backend>_<model.loop>.py; ImportError for numba
    without numba. Imported on first use: the NumPy loops need no compiler, and numba takes a
    second."""
    return importlib.import_module(f"{__package__}.loops.{backend}_{model.loop}")


def loop_of(model, backend: str | None) -> ModuleType:
    """The loop module that runs `model` on `backend` (None: the default, resolve_backend):
    EngineError quoting engine.model.SUPPORTS for a backend the model does not run on, before
    asking whether the backend can run here."""
    if backend is not None:
        model.check("backend", backend)
    return model_loop(model, resolve_backend(backend))


def time_loop(backend: str) -> ModuleType:
    """The planar model's loop module of a backend (it also runs two_body)."""
    return model_loop(PLANAR, backend)


def resolve_backend(backend: str | None) -> str:
    """The backend that runs for a requested one (None: numba if importable, else numpy);
    EngineError in one line for one that cannot run here (numba without numba, cuda without
    a GPU)."""
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
    if backend == "cuda":
        _check_device()
    return backend


def _check_device() -> None:
    """EngineError, in one line, unless the device loop can run here."""
    try:
        from .loops.cuda_physics import unavailable
    except ImportError as err:
        raise EngineError(f"backend 'cuda' needs numba-cuda (pip install -e \".[cuda]\"): "
                          f"{err}; run backend 'numba' instead") from None
    reason = unavailable()
    if reason is not None:
        raise EngineError(reason)
