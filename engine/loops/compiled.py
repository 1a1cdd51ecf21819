"""The physics the compiled loops (numba_loop.py, numba_plan.py, numba_torsion.py) call,
compiled for scalars from the modules that write it once: the stories' slip element in plan
(isolators/hysteresis.py), the scheme's contact solve and onset weight (scheme.py), and the
impact laws' force terms, the story laws' forces and the isolator laws' forces and state, each
chained into one dispatch on a member's law code (the registries): law_terms(code, delta,
rate, v_imp, row) with the member's packed law row (impact.contact.law_rows),
story_force(code, drift, state, row), isolator_force(code, u, state, row) and its kin.

JIT: the options of the cached kernels; LINK: those of the functions compiled into them.
"""
from __future__ import annotations

import functools
import types

import numpy as np
from numba import njit

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


def _link(code, force_terms, otherwise):
    """A dispatch that runs force_terms for members of law `code`, else `otherwise`."""
    def dispatch(law, delta, rate, v_imp, row):
        if law == code:
            return force_terms(delta, rate, v_imp, row)
        return otherwise(law, delta, rate, v_imp, row)
    return njit(**LINK)(dispatch)


def _law_dispatch():
    """(elastic, dashpot) of the member's law, dispatched on its code: every law of the
    registry, chained; (0, 0) for a member without wall. law_terms(code, delta, rate, v_imp,
    row): row the member's law row (contact.law_rows), of floats."""
    dispatch = njit(**LINK)(_no_wall)
    for code, module in registry.LAW_MODULES.items():
        dispatch = _link(code, njit(**LINK)(module.force_terms), dispatch)
    return dispatch


law_terms = _law_dispatch()


def _no_story(code, drift, state, row):
    return 0.0


def _link_story(code, force, otherwise):
    """A dispatch that runs a story law's force for stories of law `code`, else `otherwise`."""
    def dispatch(law, drift, state, row):
        if law == code:
            return force(drift, state, row)
        return otherwise(law, drift, state, row)
    return njit(**STORY_LINK)(dispatch)


SHARED_PHYSICS = (hysteresis.__name__, series.__name__)
"""Modules whose physics a law may call (the slip element of isolators/hysteresis.py, the
elements in series of isolators/series.py): compiled with the law like its own helpers."""


@functools.cache
def compiled_in_module(function):
    """`function` (a story law's force) compiled for scalars with STORY_LINK, with the plain
    functions of its own module (and of SHARED_PHYSICS) that it calls compiled alongside (a
    law may write its physics as several small functions; numba would otherwise refuse them
    as untyped globals). The module itself is left as it is. Once per function: a helper
    several functions call (the series solve's) is compiled once for all of them."""
    module_name = function.__module__
    scope = dict(function.__globals__)
    for name in function.__code__.co_names:
        value = scope.get(name)
        if isinstance(value, types.FunctionType) and (
                value.__module__ == module_name or value.__module__ in SHARED_PHYSICS):
            scope[name] = compiled_in_module(value)
    rebuilt = types.FunctionType(function.__code__, scope, function.__name__,
                                 function.__defaults__, function.__closure__)
    return njit(**STORY_LINK)(rebuilt)


def _story_dispatch():
    """The story force (N) of the member's story law, dispatched on its code: every law of
    the story registry, chained."""
    dispatch = njit(**STORY_LINK)(_no_story)
    for code, module in enumerate(story_registry.LAWS.values()):
        dispatch = _link_story(code, compiled_in_module(module.force), dispatch)
    return dispatch


story_force = _story_dispatch()


def _otherwise(function):
    """The end of a chain: `function` for every code not matched before."""
    def dispatch(law, *args):
        return function(*args)
    return njit(**STORY_LINK)(dispatch)


def _link_law(code, function, otherwise):
    """A dispatch that runs `function` for members of law `code`, else `otherwise`."""
    def dispatch(law, *args):
        if law == code:
            return function(*args)
        return otherwise(law, *args)
    return njit(**STORY_LINK)(dispatch)


def _isolator_dispatch(name):
    """The isolator laws' function `name` (force, advance, force_xy, advance_xy), dispatched
    on the member's isolator law code: every law of the isolator registry, chained (the last
    law ends the chain), each compiled as the story laws are (compiled_in_module)."""
    laws = isolator_registry.BY_CODE
    dispatch = _otherwise(compiled_in_module(getattr(laws[-1], name)))
    for code in range(len(laws) - 2, -1, -1):
        dispatch = _link_law(code, compiled_in_module(getattr(laws[code], name)), dispatch)
    return dispatch


isolator_force = _isolator_dispatch("force")
"""isolator_force(code, u, state, row) -> N: the member's isolator law's force."""
isolator_advance = _isolator_dispatch("advance")
"""isolator_advance(code, state, velocity, dt, row): its state committed after a step."""
isolator_force_xy = _isolator_dispatch("force_xy")
"""isolator_force_xy(code, ux, uy, state, row) -> (N, N): in plan."""
isolator_advance_xy = _isolator_dispatch("advance_xy")
"""isolator_advance_xy(code, state, vx, vy, dt, row): in plan."""
