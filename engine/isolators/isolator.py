"""`Isolator`: one building's isolation system, a law and its parameters, built from the law's
declaration (`Isolator.of(law, ...)` or the constructor named after the law, e.g.
`Isolator.friction_pendulum(radius=2.0, mu_slow=0.05, mu_fast=0.10, rate=30.0)`: one per law
of the registry, its signature and docstring generated from the law's declaration).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import EngineError
from ..parameters import Option, law_constructor
from .registry import LAW_CODES, LAWS, MAX_FIELDS, law_function


@dataclass(frozen=True)
class Isolator:
    """law: a registered isolator law's name; parameters: (name, value) pairs in the law's
    declaration order, SI units, checked. Hashable, so that equal buildings share their
    operators in a batch."""

    law: str
    parameters: tuple[tuple[str, float], ...]

    @classmethod
    def of(cls, law: str, **params) -> Isolator:
        """An isolator of the named law from its declared parameters; omitted ones take their
        defaults. EngineError names a parameter that is unknown, missing or out of range."""
        if law not in LAWS:
            raise EngineError(f"unknown isolator law {law!r}; choose one of {tuple(LAWS)}")
        declaration = LAWS[law].PARAMETERS
        # an optional parameter left unset (e.g. no displacement capacity) is left out, so
        # that the isolator, its description and provenance are those it had without it
        values = {name: value for name, value in declaration.resolve(params).items()
                  if value is not None}
        for name, value in values.items():
            if not isinstance(declaration[name], Option):
                if getattr(value, "ndim", 0) != 0:
                    raise EngineError(f"isolator {name} must be one number, got {value!r}")
                values[name] = float(value)
        try:
            LAWS[law].check(**values)
        except ValueError as err:
            raise EngineError(str(err)) from None
        return cls(law, tuple(values.items()))

    @property
    def values(self) -> dict[str, float]:
        """Parameter name -> value (SI)."""
        return dict(self.parameters)

    @property
    def default_zeta(self) -> float:
        """The isolation damping ratio this law implies unless one is given."""
        return LAWS[self.law].DEFAULT_ZETA

    @property
    def code(self) -> int:
        """The law's code in the time loops."""
        return LAW_CODES[self.law]

    def fields(self, mass: float, g: float) -> dict[str, float]:
        """The constants the time loops read (the law's ROW, by name, SI) under a building of
        total mass `mass` kg (weight g M)."""
        return LAWS[self.law].fields(mass, g, **self.values)

    def row(self, mass: float, g: float) -> np.ndarray:
        """(MAX_FIELDS,) the law's ROW in its order, zero beyond: the loops' packed row."""
        module = LAWS[self.law]
        row = np.zeros(MAX_FIELDS)
        row[:len(module.ROW)] = [self.fields(mass, g)[name] for name in module.ROW._fields]
        return row

    def initial_stiffness(self, mass: float, g: float) -> float:
        """Stiffness before any slip, N/m (stability limit, damping rules)."""
        return LAWS[self.law].initial_stiffness(mass, g, **self.values)

    def displacement_capacity(self, mass: float, g: float) -> float:
        """Displacement (m) past which the bearing has failed (inf: no capacity)."""
        return float(LAWS[self.law].displacement_capacity(mass, g, **self.values))

    def yield_displacement(self, mass: float, g: float) -> float:
        """Displacement at which the slip element starts to slip, m."""
        return LAWS[self.law].yield_displacement(mass, g, **self.values)

    def effective_stiffness(self, mass: float, g: float, displacement):
        """Secant stiffness, N/m, at a displacement (m; scalar or array)."""
        return LAWS[self.law].effective_stiffness(mass, g, displacement, **self.values)

    def post_yield_stiffness(self, mass: float, g: float) -> float:
        """The secant stiffness's limit at large displacements, N/m (the code's design; an
        EngineError names a law that does not declare it)."""
        return law_function(self.law, "post_yield_stiffness")(mass, g, **self.values)

    def energy_per_cycle(self, mass: float, g: float, displacement: float) -> float:
        """Energy dissipated per cycle at a displacement amplitude (m, one number), J (the
        code's design; an EngineError names a law that does not declare it)."""
        return law_function(self.law, "energy_per_cycle")(mass, g, displacement, **self.values)

    @property
    def dashpot_text(self) -> str:
        """The isolation dashpot of damping="paper" in the law's symbols (provenance)."""
        return LAWS[self.law].DASHPOT_TEXT

    def describe(self) -> str:
        """'bilinear(k1 = 2e+08 N m-1, k2 = 2.5e+07 N m-1, fy_ratio = 0.1)'."""
        declaration = LAWS[self.law].PARAMETERS
        return f"{self.law}(" + ", ".join(declaration[name].value_text(value)
                                          for name, value in self.parameters) + ")"


def _build(cls, law, **arguments):
    return cls.of(law, **arguments)


for _name, _module in LAWS.items():
    setattr(Isolator, _name, law_constructor(
        "Isolator", _name, _module.PARAMETERS,
        f"A {_name} isolator ({_module.__name__}); every parameter one number:", _build))
