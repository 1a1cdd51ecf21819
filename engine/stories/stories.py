"""`Stories`: the law a building's stories follow and its parameters, built from the law's
declaration (`Stories.of(law, ...)` or the constructor named after the law, e.g.
`Stories.bilinear(yield_force=(8e6, 7e6, 5e6), post_yield_ratio=0.02)`). Each value is one
number for every story or one per story (the first story first); the story's elastic
stiffness is the building's story_stiffness.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import EngineError
from ..parameters import law_constructor
from .registry import LAW_CODES, LAWS


@dataclass(frozen=True)
class Stories:
    """law: a registered story law's name; parameters: (name, value) pairs in the law's
    declaration order, SI units, checked; each value a float or a tuple of per-story floats.
    Hashable, so that equal buildings share their arrays in a batch."""

    law: str
    parameters: tuple[tuple[str, float | tuple[float, ...]], ...] = ()

    @classmethod
    def of(cls, law: str, **params) -> Stories:
        """Stories of the named law; omitted parameters take their defaults. EngineError
        names a parameter that is unknown, missing or out of range."""
        if law not in LAWS:
            raise EngineError(f"unknown story law {law!r}; choose one of {tuple(LAWS)}")
        values = LAWS[law].PARAMETERS.resolve(params)
        for name, value in values.items():
            if value.ndim > 1:
                raise EngineError(f"story {name} must be one number or one per story, "
                                  f"got shape {value.shape}")
            values[name] = float(value) if value.ndim == 0 else tuple(map(float, value))
        return cls(law, tuple(values.items()))

    @property
    def values(self) -> dict:
        return dict(self.parameters)

    @property
    def module(self):
        return LAWS[self.law]

    @property
    def code(self) -> int:
        """The law's code in the time loops."""
        return LAW_CODES[self.law]

    @property
    def is_linear(self) -> bool:
        return bool(getattr(self.module, "LINEAR", False))

    def per_story(self, n_stories: int) -> dict[str, np.ndarray]:
        """name -> (N,) values, one per story; EngineError for a tuple of another length."""
        out = {}
        for name, value in self.parameters:
            array = np.asarray(value, float)
            if array.ndim == 1 and array.size != n_stories:
                raise EngineError(f"story {name} must be one number or {n_stories} (one per "
                                  f"story), got {array.size}")
            out[name] = np.broadcast_to(array, (n_stories,)).copy()
        try:
            self.module.check(**out)
        except ValueError as err:
            raise EngineError(f"{self.law} stories: {err}") from None
        return out

    def fields(self, stiffness) -> np.ndarray:
        """(N, N_FIELDS) the law's constants per story, for stiffnesses (N,) N/m."""
        stiffness = np.asarray(stiffness, float)
        return np.asarray(self.module.fields(stiffness, **self.per_story(stiffness.size)),
                          float).reshape(stiffness.size, self.module.N_FIELDS)

    def strength(self, stiffness) -> np.ndarray:
        """(N,) the largest force each story carries (N; inf for linear stories)."""
        stiffness = np.asarray(stiffness, float)
        return np.asarray(self.module.strength(stiffness, **self.per_story(stiffness.size)),
                          float)

    def yield_strength(self, stiffness) -> np.ndarray:
        """(N,) the force at which each story starts to yield (N; inf for linear stories)."""
        stiffness = np.asarray(stiffness, float)
        return np.asarray(self.module.yield_strength(stiffness,
                                                     **self.per_story(stiffness.size)), float)

    def describe(self) -> str:
        """'bilinear(yield_force = 8e+06 N, post_yield_ratio = 0.02)'."""
        declaration = self.module.PARAMETERS
        parts = []
        for name, value in self.parameters:
            if isinstance(value, tuple):
                unit = "" if declaration[name].units == "1" else f" {declaration[name].units}"
                parts.append(f"{name} = ({', '.join(f'{v:g}' for v in value)}){unit}")
            else:
                parts.append(declaration[name].value_text(value))
        return f"{self.law}(" + ", ".join(parts) + ")"


def _build(cls, law, **arguments):
    return cls.of(law, **arguments)


for _name, _module in LAWS.items():
    setattr(Stories, _name, law_constructor(
        "Stories", _name, _module.PARAMETERS,
        f"{_name} stories ({_module.__name__}); each value one number or one per story:",
        _build, keyword_only=True))
