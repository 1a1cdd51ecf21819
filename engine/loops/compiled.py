"""The physics both compiled loops (numba_loop.py, numba_plan.py) call, compiled for scalars
from the modules that write it once: the isolator's and the stories' slip elements
(isolators/hysteresis.py), the scheme's contact solve and onset weight (scheme.py), and the
impact laws' force terms chained into one dispatch on a member's law code (the registry).

JIT: the options of the cached kernels; LINK: those of the functions compiled into them.
"""
from __future__ import annotations

from numba import njit

from .. import scheme
from ..impact import registry
from ..isolators import hysteresis

PHYSICS_FILES = [m.__file__ for m in (hysteresis, scheme, registry, *registry.LAWS.values())]
"""The sources a cached kernel compiles besides its own file (numba_support's cache key)."""

JIT = {"cache": True, "nogil": True, "error_model": "numpy"}
LINK = {"nogil": True, "error_model": "numpy"}  # compiled into the cached kernels that call it

isolator_force = njit(**LINK)(hysteresis.isolator_force)
plastic_spring = njit(**LINK)(hysteresis.plastic_spring_force)
radial_return = njit(**LINK)(hysteresis.radial_return)
slip_limit = njit(**LINK)(hysteresis.slip_limit)
implicit_force = njit(**LINK)(scheme.implicit_force)
onset_weight = njit(**LINK)(scheme.onset_weight)


def _no_wall(code, delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot, damping_ratio, chi,
             c_imp_coef, c_imp_exponent):
    return 0.0, 0.0


def _link(code, force_terms, otherwise):
    """A dispatch that runs force_terms for members of law `code`, else `otherwise`."""
    def dispatch(law, delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot, damping_ratio,
                 chi, c_imp_coef, c_imp_exponent):
        if law == code:
            return force_terms(delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot,
                               damping_ratio, chi, c_imp_coef, c_imp_exponent)
        return otherwise(law, delta, rate, v_imp, k, n, m_eff, delta_u, k_w, dashpot,
                         damping_ratio, chi, c_imp_coef, c_imp_exponent)
    return njit(**LINK)(dispatch)


def _law_dispatch():
    """(elastic, dashpot) of the member's law, dispatched on its code: every law of the
    registry, chained; (0, 0) for a member without wall."""
    dispatch = njit(**LINK)(_no_wall)
    for code, module in registry.LAW_MODULES.items():
        dispatch = _link(code, njit(**LINK)(module.force_terms), dispatch)
    return dispatch


law_terms = _law_dispatch()
