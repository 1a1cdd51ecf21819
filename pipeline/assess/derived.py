"""The responses the studies derive from the engine's peaks, declared once: name, units, long
name and the pure function that computes them (as engine.results declares the peaks
themselves). The studies' archives take `units` and `long_name` from here, and compute the
responses with these functions only.

- peak_floor_accel, m/s^2: the largest peak total acceleration over the levels, the isolation
  slab (level 0) included: peak_total_accel (..., levels) -> (...,).
- peak_story_drift, m: the largest peak interstory drift over the stories:
  peak_interstory_drift (..., stories) -> (...,).
- bumper_stress, Pa: the mean contact stress on each bumper at the largest impact force,
  max_impact_force / (n_bumpers x area), broadcast.
- crushed, bool: the bumpers compressed beyond their crush indentation delta_u (m; strain x
  thickness, or the protrusion t - c_d if less): max_indentation > delta_u, strictly, as the
  bumper law has it (engine.impact.laws.rubber_bumper.force_terms): the wall behind the rubber,
  k_w max(delta - delta_u, 0), acts only for delta > delta_u; at delta_u the force is still the
  rubber's alone.

Each declaration is called on the engine's peaks by name (an engine Result, or a dict of
arrays as engine.results.PEAKS and a sweep's blocks name them: `peaks_of`), with the bumpers'
parameters by keyword: `quantity("bumper_stress")(result, n_bumpers=4, area=0.0225)`, or
several at once with `derive`.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np


def labelled(values) -> bool:
    """Whether `values` is a labelled array (an xarray DataArray: an archive's variable, lazy
    when the archive is), which the responses keep as it is instead of reading into NumPy."""
    return hasattr(values, "dims") and hasattr(values, "variable")


def largest_floor_accel(peak_total_accel) -> np.ndarray:
    """(...,) m/s^2: the largest of peak_total_accel (..., levels) m/s^2 over its levels (a
    labelled array: over its `floor` dimension, lazily when it is lazy)."""
    if labelled(peak_total_accel):
        return peak_total_accel.max("floor")
    return np.asarray(peak_total_accel).max(axis=-1)


def largest_story_drift(peak_interstory_drift) -> np.ndarray:
    """(...,) m: the largest of peak_interstory_drift (..., stories) m over its stories."""
    return np.asarray(peak_interstory_drift).max(axis=-1)


def bumper_stress(max_impact_force, n_bumpers, area) -> np.ndarray:
    """Mean contact stress (Pa) on each bumper at the largest impact force (N): force / (n A),
    n bumpers of contact area A (m^2) sharing it. Broadcast over arrays (labelled arrays
    stay labelled, and lazy when they are)."""
    force, n, a = (x if labelled(x) else np.asarray(x, float)
                   for x in (max_impact_force, n_bumpers, area))
    return force / (n * a)


def crushed(max_indentation, delta_u) -> np.ndarray:
    """bool, broadcast: the largest indentation (m) beyond the crush indentation delta_u (m),
    strictly (see the module docstring)."""
    return np.asarray(max_indentation) > np.asarray(delta_u)


def peaks_of(result) -> Mapping:
    """The peaks by name: a mapping (a dict of arrays, a Dataset) as it is; an engine Result
    (or PlanResult) as its `peaks()`."""
    return result if isinstance(result, Mapping) else result.peaks()


@dataclass(frozen=True)
class Derived:
    """A response derived from the engine's peaks.

    name: its name in code and archives; units: UDUNITS string of its SI unit; template: its
    long name, with {fields} filled from `fields` (name, default) pairs unless `describe` is
    given others; function: the pure function computing it; peaks: the engine peaks it reads
    (engine.results.PEAKS names), passed in this order; parameters: what else it needs, by
    keyword (the bumpers' n_bumpers and area, delta_u).
    """

    name: str
    units: str
    template: str
    function: Callable[..., np.ndarray]
    peaks: tuple[str, ...]
    parameters: tuple[str, ...] = ()
    fields: tuple[tuple[str, str], ...] = ()

    @property
    def long_name(self) -> str:
        """One line (the archives' long_name), the template's fields at their defaults."""
        return self.describe()

    def describe(self, **fields) -> str:
        """The long name with some of the template's fields given, e.g. the bumpers' size."""
        return self.template.format(**{**dict(self.fields), **fields})

    def __call__(self, peaks, **parameters) -> np.ndarray:
        """The response of `peaks` (see `peaks_of`) with the `parameters` it needs."""
        found = peaks_of(peaks)
        missing = [p for p in self.parameters if p not in parameters]
        if missing:
            raise TypeError(f"{self.name} needs {', '.join(missing)}")
        return self.function(*(found[p] for p in self.peaks),
                             **{p: parameters[p] for p in self.parameters})


DERIVED: dict[str, Derived] = {d.name: d for d in (
    Derived("peak_floor_accel", "m s-2", "largest peak floor acceleration", largest_floor_accel,
            ("peak_total_accel",)),
    Derived("peak_story_drift", "m", "largest peak interstory drift", largest_story_drift,
            ("peak_interstory_drift",)),
    Derived("bumper_stress", "Pa", "mean contact stress on {each} at the largest impact force",
            bumper_stress, ("max_impact_force",), ("n_bumpers", "area"),
            (("each", "each bumper"),)),
    Derived("crushed", "1", "1 where the bumpers are crushed beyond delta_u", crushed,
            ("max_indentation",), ("delta_u",)),
)}
"""Every derived response by name."""


def quantity(name: str) -> Derived:
    """The declaration of a derived response by name (DERIVED)."""
    try:
        return DERIVED[name]
    except KeyError:
        raise KeyError(f"no derived response {name!r}; declared: {tuple(DERIVED)}") from None


def derive(peaks, names=None, **parameters) -> dict[str, np.ndarray]:
    """Derived responses of `peaks` (an engine Result or a dict of peak arrays): name -> array
    for `names` (default: every declaration whose parameters are given)."""
    if names is None:
        names = [d.name for d in DERIVED.values()
                 if all(p in parameters for p in d.parameters)]
    found = peaks_of(peaks)
    return {name: quantity(name)(found, **parameters) for name in names}
