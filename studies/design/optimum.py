"""The nature of the design search's optimum: interior, or at a named bound (physical, or
the grid's edge), with the constraints active there (`nature`, `Nature`)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.units import KN_PER_MM

from .space import VARIABLES, Bounds, row


@dataclass(frozen=True)
class Nature:
    """Where the optimum lies: bounds, [{variable, side, value, kind ("physical" | "grid"),
    why, indifferent}] for each variable without an evaluated neighbour on a side
    (indifferent: the neighbour on the other side scores the same, so the bound only breaks a
    tie); active, [{variable, side, neighbour, fails}] for each evaluated neighbour that fails
    a constraint."""

    bounds: tuple
    active: tuple

    @property
    def interior(self) -> bool:
        """No bound holds the optimum where it is (ties broken at a bound do not)."""
        return all(b["indifferent"] for b in self.bounds)

    def text(self) -> str:
        held = [b for b in self.bounds if not b["indifferent"]]
        flat = [b for b in self.bounds if b["indifferent"]]
        if not held:
            head = "interior: evaluated neighbours on both sides in every variable that matters"
        else:
            by_variable = {}
            for b in held:
                by_variable.setdefault(b["variable"], []).append(b)
            head = "at a bound: " + "; ".join(bound_text(sides)
                                              for sides in by_variable.values())
        if flat:
            head += "; indifferent: " + "; ".join(
                f"{b['variable']} (the same statistics on the other side; the tie goes to "
                f"its {b['side']} bound {_value(b['variable'], b['value'])})" for b in flat)
        if self.active:
            head += "; active constraints: " + "; ".join(
                f"{a['variable']} {_value(a['variable'], a['neighbour'])} fails "
                f"{', '.join(a['fails'])}" for a in self.active)
        return head

    def as_dict(self) -> dict:
        return {"interior": self.interior, "bounds": list(self.bounds),
                "active": list(self.active)}


def bound_text(sides: list[dict]) -> str:
    """One variable of the optimum without an evaluated neighbour on one side or both (its
    Nature.bounds entries): named once, with the bound it sits on. Both sides physical: the
    lower and upper bounds coincide there (the variable is fixed); a side of the grid's edge
    says the optimum may lie beyond the grid."""
    name, value = sides[0]["variable"], _value(sides[0]["variable"], sides[0]["value"])
    grid = "the evaluated grid's edge: the optimum may lie beyond the grid"
    if len(sides) == 1:
        b = sides[0]
        return (f"{name} at its {b['side']} bound {value} ("
                + (f"physical: {b['why']}" if b["kind"] == "physical" else grid) + ")")
    physical = [b for b in sides if b["kind"] == "physical"]
    whys = list(dict.fromkeys(b["why"] for b in physical if b["why"]))
    if len(physical) == len(sides):
        return (f"{name} fixed at {value} (lower = upper bound"
                + (f"; physical: {'; '.join(whys)}" if whys else "") + ")")
    if physical:
        b = physical[0]
        other = next(x["side"] for x in sides if x["kind"] != "physical")
        return (f"{name} at its {b['side']} bound {value} (physical: {b['why']}; the only "
                f"value evaluated: on the {other} side, {grid})")
    return f"{name} at {value}, the only value evaluated ({grid}, on both sides)"


def nature(table: dict, best: int, bounds: Bounds, fails=None, scores=None) -> Nature:
    """Where candidate `best` of `table` (VARIABLES -> (K,)) lies: for each variable, the
    evaluated candidates equal to it in every other variable; a side without one is a bound,
    physical when the value sits on the bound `bounds` sets there (Bounds.limits), else the
    grid's edge. fails: (K,) lists of the constraints each candidate fails, for the neighbours
    that keep the optimum where it is; scores: (K, m) what ranks the candidates (a bound
    whose inward neighbour scores the same is indifferent). None: not given."""
    config = row(table, best)
    limits = bounds.limits(config)
    found, active = [], []
    for name in VARIABLES:
        others = np.ones(len(table[name]), dtype=bool)
        for v in VARIABLES:
            if v != name:
                others &= np.isclose(table[v], config[v], rtol=1e-9, atol=0)
        values = np.asarray(table[name], float)
        nearest = {}
        for sign in (-1, 1):
            beyond = others & ((values - config[name]) * sign > 1e-9 * abs(config[name]))
            if beyond.any():
                nearest[sign] = int(np.flatnonzero(beyond)[np.argmin(
                    np.abs(values[beyond] - config[name]))])
        for side, sign, (bound, why) in (("lower", -1, limits[name][0]),
                                         ("upper", 1, limits[name][1])):
            if sign in nearest:
                k = nearest[sign]
                if fails is not None and fails[k]:
                    active.append({"variable": name, "side": side,
                                   "neighbour": float(values[k]), "fails": list(fails[k])})
                continue
            on = _on_bound(name, config[name], bound, sign)
            inward = nearest.get(-sign)
            flat = bool(scores is not None and inward is not None and np.allclose(
                scores[inward], scores[best], rtol=1e-12, atol=0))
            found.append({"variable": name, "side": side, "value": config[name],
                          "kind": "physical" if on else "grid", "why": why if on else "",
                          "indifferent": flat})
    return Nature(tuple(found), tuple(active))


def _on_bound(name: str, value: float, bound: float, sign: int) -> bool:
    """Whether value sits on the bound: within rounding, or (a count) one more would pass it."""
    if name == "n_bumpers":
        return value + sign > bound + 1e-9 if sign > 0 else value + sign < bound - 1e-9
    return abs(value - bound) <= 1e-5 * max(abs(bound), 1e-12)


def _value(name: str, value: float) -> str:
    units = VARIABLES[name][0]
    if name == "wall_k":
        return f"{value / KN_PER_MM:g} kN/mm"
    if name == "n_bumpers":
        return f"{int(round(value))}"
    return f"{value:.4g} m" if units == "m" else f"{value:.4g}"
