"""The physics the compiled loops (numba_loop.py, numba_plan.py, numba_torsion.py) call,
compiled for scalars from the modules that write it once: the stories' slip element in plan
(isolators/hysteresis.py), the scheme's contact solve and onset weight (scheme.py), and the
impact laws' force terms, chained into one dispatch on a member's law code (the registry):
law_terms(code, delta, rate, v_imp, row) with the member's packed law row
(impact.contact.law_rows); the story laws' forces and the isolator laws' forces and state,
the members' law resolved when a kernel compiles (story_force(tag, drift, state, row),
isolator_force(tag, u, state, row) and its kin, tag = numba_support.law_tag(code)).

JIT: the options of the cached kernels; LINK: those of the functions compiled into them.
"""
from __future__ import annotations

import functools
import types
from typing import NamedTuple

import numpy as np
from numba import njit
from numba.extending import overload

from .. import layout as columns
from .. import results, scheme
from ..impact import registry
from ..isolators import hysteresis, series
from ..isolators import registry as isolator_registry
from ..results import MODE
from ..stories import registry as story_registry

PHYSICS_FILES = [m.__file__ for m in (hysteresis, series, scheme, columns, results, registry,
                                      *registry.LAWS.values(), story_registry,
                                      *story_registry.LAWS.values(), isolator_registry,
                                      *isolator_registry.LAWS.values())]
"""The sources a cached kernel compiles besides its own file (numba_support's cache key)."""

JIT = {"cache": True, "nogil": True, "error_model": "numpy"}
LINK = {"nogil": True, "error_model": "numpy"}  # compiled into the cached kernels that call it
STORY_LINK = {**LINK, "_nrt": False}
"""The story laws' options: LINK without numba's reference counting of arrays. A law takes
views of arrays its loop owns and allocates nothing (numba refuses to compile one that
would), but with reference counting each call of a law that calls a helper with its arrays
keeps four refcount calls and is never inlined into the story loop: the deteriorating law
then cost 2.4-2.6x the linear building's member-step, 1.3-1.4x without (numba's `_nrt`
option, private but stable since numba 0.2x)."""

radial_return = njit(**LINK)(hysteresis.radial_return)
implicit_force = njit(**LINK)(scheme.implicit_force)


@njit(**LINK)
def failed(mode, measure, code):
    """The collapse mode (results.MODE) once a criterion of mode `code` failed on `measure`:
    `code`, or numerical instability where the measure is not finite (NaN fails every
    comparison); the higher of it and `mode`, the mode of the criteria failed before."""
    return max(mode, code if np.isfinite(measure) else MODE.numerical_instability)
onset_weight = njit(**LINK)(scheme.onset_weight)


def _no_wall(code, delta, rate, v_imp, row):
    return 0.0, 0.0


def _link(code, force_terms, otherwise, compile):
    """A dispatch that runs force_terms for members of law `code`, else `otherwise`."""
    def dispatch(law, delta, rate, v_imp, row):
        if law == code:
            return force_terms(delta, rate, v_imp, row)
        return otherwise(law, delta, rate, v_imp, row)
    return compile(dispatch)


_CPU_LINK = njit(**LINK)


def law_dispatch(compile=_CPU_LINK, terms=lambda module: _CPU_LINK(module.force_terms)):
    """(elastic, dashpot) of the member's law, dispatched on its code: every law of the
    registry, chained; (0, 0) for a member without wall. law_terms(code, delta, rate, v_imp,
    row): row the member's law row (contact.law_rows), of floats. compile: how the chain is
    compiled, terms(module): a law's force_terms compiled (the CPU's by default; the device's
    in cuda_physics)."""
    dispatch = compile(_no_wall)
    for code, module in registry.LAW_MODULES.items():
        dispatch = _link(code, terms(module), dispatch, compile)
    return dispatch


law_terms = law_dispatch()


SHARED_PHYSICS = (hysteresis.__name__, series.__name__)
"""Modules whose physics a law may call (the slip element of isolators/hysteresis.py, the
elements in series of isolators/series.py): compiled with the law like its own helpers."""


class Target(NamedTuple):
    """What a law's scalar source is compiled for: `compile` (a decorator) turns a function
    into a compiled one, `replaced` the globals it sees in place of its module's (name ->
    value pairs: the device's NumPy of scalars for np)."""

    name: str
    compile: object
    replaced: tuple = ()


CPU = Target("cpu", njit(**STORY_LINK))
"""The compiled loops' target: numba's CPU compiler with STORY_LINK, the globals as written."""


@functools.cache
def compiled_for(function, target: Target):
    """`function` (a law's physics) compiled for `target`, with the plain functions of its
    own module (and of SHARED_PHYSICS) that it calls compiled alongside (a law may write its
    physics as several small functions; numba would otherwise refuse them as untyped
    globals), and the target's `replaced` globals in its scope. The module itself is left as
    it is. Once per function and target: a helper several functions call (the series solve's)
    is compiled once for all of them."""
    module_name = function.__module__
    scope = dict(function.__globals__)
    scope.update(target.replaced)
    for name in function.__code__.co_names:
        value = scope.get(name)
        if isinstance(value, types.FunctionType) and (
                value.__module__ == module_name or value.__module__ in SHARED_PHYSICS):
            scope[name] = compiled_for(value, target)
    rebuilt = types.FunctionType(function.__code__, scope, function.__name__,
                                 function.__defaults__, function.__closure__)
    return target.compile(rebuilt)


def compiled_in_module(function):
    """`function` (a story law's force) compiled for scalars with STORY_LINK (compiled_for on
    the CPU)."""
    return compiled_for(function, CPU)


def compiled_law(laws, code: int, name: str):
    """The function `name` of law `code` of `laws` (a registry's laws in code order), compiled
    for scalars (compiled_in_module)."""
    return compiled_in_module(getattr(laws[code], name))


def compiled_isolator(code: int, name: str):
    """The isolator law `code`'s function `name` (force, advance, force_xy, advance_xy)."""
    return compiled_law(isolator_registry.BY_CODE, code, name)


def _by_tag(laws, name, called):
    """The laws' function `name`, called as `called`(tag, *args) in a kernel: that of the law
    of code len(tag) - 1 (numba_support.law_tag), resolved when the kernel compiles, so that a
    kernel holds its members' law alone (laws: a registry's, in code order). A chain of every
    law dispatching on the code compiled each law into every kernel: with the triple friction
    pendulum, a bilinear building's kernel took 40% longer to compile (twice as long in plan)
    and its twisting step ran 9-11% slower."""
    def by_tag(tag, *args):
        raise TypeError(f"{called} is called inside a compiled kernel only; "
                        f"compiled_law(laws, code, {name!r}) is the law's function")

    by_tag.__name__ = by_tag.__qualname__ = called

    @overload(by_tag, jit_options=STORY_LINK)
    def typed(tag, *args):
        function = compiled_law(laws, len(tag.types) - 1, name)

        def resolved(tag, *args):
            return function(*args)
        return resolved
    return by_tag


story_force = _by_tag(tuple(story_registry.LAWS.values()), "force", "story_force")
"""story_force(tag, drift, state, row) -> N: the story law's force at a story's drift (m)."""
isolator_force = _by_tag(isolator_registry.BY_CODE, "force", "isolator_force")
"""isolator_force(tag, u, state, row) -> N: the isolator law's force."""
isolator_advance = _by_tag(isolator_registry.BY_CODE, "advance", "isolator_advance")
"""isolator_advance(tag, state, velocity, dt, row): its state committed after a step."""
isolator_force_xy = _by_tag(isolator_registry.BY_CODE, "force_xy", "isolator_force_xy")
"""isolator_force_xy(tag, ux, uy, state, row) -> (N, N): in plan."""
isolator_advance_xy = _by_tag(isolator_registry.BY_CODE, "advance_xy", "isolator_advance_xy")
"""isolator_advance_xy(tag, state, vx, vy, dt, row): in plan."""
