"""The physics the device loops (cuda_loop.py, cuda_plan.py) call, compiled for an NVIDIA GPU
from the very source the CPU kernels compile (compiled.py): the impact laws' `force_terms`
chained on a member's law code, the story and isolator laws, the scheme's contact solve and
onset weight, the collapse rule and the banded solve. Nothing is written twice: a law's
functions are compiled with numba's CUDA target (device functions) by compiled.compiled_for,
with `np` replaced by SCALAR_NUMPY, NumPy's functions on scalars as the device has them
(math's, or a few lines here where math has none), and in a CPU kernel's helper compiled.py's
physics by its device twins (DEVICE). The CPU kernels keep NumPy's own, so their bits do not
change.

NumPy's ufuncs on scalars are what numba's CUDA target lacks (`np.sqrt` of a float fails to
type there); the laws keep calling them, since the NumPy loops call the same functions on
arrays.

numba-cuda (the `cuda` extra) and an NVIDIA driver are needed to run; numba's CUDA simulator
(NUMBA_ENABLE_CUDASIM=1) runs the same kernels in Python without either (the tests).
`unavailable()` says in one line why the backend cannot run, or None.
"""
from __future__ import annotations

import functools
import math
import os
import types

import numpy as np

if not hasattr(np, "row_stack"):  # numba-cuda 0.2x-0.30 registers np.row_stack (NumPy < 2.5)
    setattr(np, "row_stack", np.vstack)  # noqa: B010  (ruff NPY201 would rename it)

from numba import cuda  # noqa: E402  (after the guard above)

from ..isolators import registry as isolator_registry  # noqa: E402
from ..stories import registry as story_registry  # noqa: E402
from . import compiled  # noqa: E402

DEVICE_OPTIONS = {"device": True}
"""How a law is compiled: a device function (FP64, no fast math: numba's default)."""


def simulated() -> bool:
    """Whether numba's CUDA simulator runs the kernels (NUMBA_ENABLE_CUDASIM=1)."""
    return os.environ.get("NUMBA_ENABLE_CUDASIM", "0") not in ("", "0")


def _device(function):
    """`function` as a device function; under the simulator the Python function itself (the
    physics uses nothing of the device: the simulator's wrapper, which swaps its `cuda` module
    at every call, would make a member-step cost 0.1 ms)."""
    return function if simulated() else cuda.jit(**DEVICE_OPTIONS)(function)


@_device
def _maximum(a, b):
    # np.maximum: the NaN of either side wins
    return a if (a >= b or a != a) else b


@_device
def _minimum(a, b):
    return a if (a <= b or a != a) else b


@_device
def _sign(x):
    if x > 0.0:
        return 1.0
    if x < 0.0:
        return -1.0
    return x  # 0.0, -0.0 or NaN, as np.sign gives them


@_device
def _clip(x, low, high):
    return _minimum(_maximum(x, low), high)


@_device
def _where(condition, a, b):
    return a if condition else b


@_device
def _same(x):
    # np.all / np.any of one boolean: itself
    return x


SCALAR_NUMPY = types.ModuleType("scalar_numpy")
"""NumPy's functions the laws call, on scalars, for the device (the `np` a law sees there)."""
for _name, _value in {"sqrt": math.sqrt, "exp": math.exp, "log": math.log, "abs": abs,
                      "hypot": math.hypot, "arctan": math.atan, "isfinite": math.isfinite,
                      "maximum": _maximum, "minimum": _minimum, "sign": _sign, "clip": _clip,
                      "where": _where, "all": _same, "any": _same, "inf": math.inf,
                      "pi": math.pi}.items():
    setattr(SCALAR_NUMPY, _name, _value)

SCALARS = compiled.Target("cuda", _device, (("np", SCALAR_NUMPY),))
"""The device target of compiled.compiled_for: NumPy's functions on scalars."""


def _on_device(target, function):
    return compiled.compiled_for(getattr(function, "py_func", function), target)


law_terms = compiled.law_dispatch(_device, lambda module: _on_device(SCALARS,
                                                                     module.force_terms))
"""law_terms(code, delta, rate, v_imp, row) on the device: compiled.law_terms' twin."""
implicit_force = _on_device(SCALARS, compiled.implicit_force)
onset_weight = _on_device(SCALARS, compiled.onset_weight)
failed = _on_device(SCALARS, compiled.failed)
radial_return = _on_device(SCALARS, compiled.radial_return)

DEVICE = compiled.Target("cuda", _device, (*SCALARS.replaced, *{
    "law_terms": law_terms, "implicit_force": implicit_force, "onset_weight": onset_weight,
    "failed": failed, "radial_return": radial_return}.items()))
"""The device target for a CPU kernel's helper (numba_plan.wall_contact, say): the device's NumPy
of scalars, and compiled.py's physics by its names replaced by their device twins above."""


def device_function(function):
    """A function of the physics (a plain one, or a CPU kernel's @njit one: its py_func)
    compiled for the device, with its module's helpers (compiled.compiled_for, DEVICE)."""
    return _on_device(DEVICE, function)


def story_law(code: int, name: str = "force"):
    """The story law `code`'s function `name`, on the device."""
    return device_function(getattr(tuple(story_registry.LAWS.values())[code], name))


def story_widths(code: int) -> tuple[int, int]:
    """(constants, state) per story of story law `code` (its N_FIELDS and N_STATE, at least 1:
    a local array's shape): what a kernel of that law holds of a member's (B, N, MAX_FIELDS)
    and (B, N, MAX_STATE) rows."""
    law = tuple(story_registry.LAWS.values())[code]
    return max(law.N_FIELDS, 1), max(law.N_STATE, 1)


def isolator_widths(code: int, state: str) -> tuple[int, int]:
    """(constants, state) of isolator law `code` (len(ROW) and len of its `state`, STATE or
    STATE_XY, at least 1): what a kernel of that law holds of a member's isolator rows."""
    law = isolator_registry.BY_CODE[code]
    return max(len(law.ROW), 1), max(len(getattr(law, state)), 1)


def isolator_law(code: int, name: str):
    """The isolator law `code`'s function `name` (force, advance, force_xy, advance_xy), on the
    device."""
    return device_function(getattr(isolator_registry.BY_CODE[code], name))


@functools.cache
def unavailable() -> str | None:
    """Why the device backend cannot run here, in one line, or None when it can."""
    if simulated():
        return None
    try:
        if cuda.is_available():
            return None
        reason = "no NVIDIA GPU or driver was found"
    except Exception as err:  # a driver that fails to load says so in many ways
        reason = f"the CUDA driver failed to load ({str(err).splitlines()[0]})"
    return (f"backend 'cuda' needs an NVIDIA GPU, its driver and numba-cuda "
            f"(pip install -e \".[cuda]\"): {reason}; run backend 'numba' instead")


LAUNCH_THREADS = 128
"""Threads per block: each thread runs one member (its state in registers and local memory),
so a block needs no shared memory; 128 keeps enough warps resident on every multiprocessor."""


def launch(kernel, size: int, *args) -> None:
    """kernel over `size` members, one thread each."""
    if size:
        kernel[(size + LAUNCH_THREADS - 1) // LAUNCH_THREADS, LAUNCH_THREADS](*args)
