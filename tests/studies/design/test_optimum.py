"""studies.design.optimum: the optimum's nature on hand-made candidate tables (interior, at the
grid's edge, on a physical bound, a tie at a bound)."""
from __future__ import annotations

import numpy as np

from studies.design import optimum, space

# --------------------------------------------------------------------- hand-made tables

BOUNDS = space.Bounds(gap=0.20, clearance=0.10, usable_strain=0.6, wall_length=100.0)
AXES = {"thickness": (0.04, 0.06, 0.08), "cavity_ratio": (0.0, 0.1, 0.2),
        "n_bumpers": (4, 8, 16), "shape_factor": (0.6, 0.8, 1.0), "wall_k": (5e8, 1e9, 2e9)}


def table_of(axes=AXES) -> dict:
    mesh = np.meshgrid(*(np.asarray(axes[v], float) for v in space.VARIABLES), indexing="ij")
    return {v: m.ravel() for v, m in zip(space.VARIABLES, mesh, strict=True)}


def at(table, **config) -> int:
    same = np.ones(table["thickness"].size, dtype=bool)
    for name, value in config.items():
        same &= np.isclose(table[name], value)
    return int(np.flatnonzero(same)[0])


def centre(axes=AXES) -> dict:
    return {v: axes[v][1] for v in space.VARIABLES}


def test_an_optimum_inside_the_grid_is_interior():
    table = table_of()
    found = optimum.nature(table, at(table, **centre()), BOUNDS)
    assert found.interior and not found.bounds
    assert found.text().startswith("interior")


def test_an_optimum_at_the_grids_edge_is_named_and_may_lie_beyond():
    table = table_of()
    found = optimum.nature(table, at(table, **{**centre(), "thickness": 0.08}), BOUNDS)
    assert not found.interior
    (bound,) = found.bounds
    assert (bound["variable"], bound["side"], bound["kind"]) == ("thickness", "upper", "grid")
    assert "thickness at its upper bound 0.08 m" in found.text()
    assert "the optimum may lie beyond the grid" in found.text()


def test_an_optimum_on_a_physical_bound_names_it():
    # 8 cm bumpers without cavity protrude 8 cm: the most a 14 cm gap leaves beyond 6 cm
    tight = space.Bounds(gap=0.14, clearance=0.06, usable_strain=0.6, wall_length=100.0)
    table = table_of()
    best = at(table, **{**centre(), "thickness": 0.08, "cavity_ratio": 0.0})
    found = optimum.nature(table, best, tight)
    kinds = {(b["variable"], b["side"]): b["kind"] for b in found.bounds}
    assert kinds == {("thickness", "upper"): "physical", ("cavity_ratio", "lower"): "physical"}
    assert "(physical: the clearance: thickness - cavity <= gap - D_S" in found.text()


def test_a_tie_at_a_bound_is_indifferent_and_a_failing_neighbour_an_active_constraint():
    table = table_of()
    best = at(table, **{**centre(), "wall_k": 2e9})
    scores = np.column_stack([np.arange(table["thickness"].size, dtype=float)] * 2)
    scores[at(table, **{**centre(), "wall_k": 1e9})] = scores[best]  # k_w plays no part
    fails = [[] for _ in scores]
    fails[at(table, **{**centre(), "wall_k": 2e9, "thickness": 0.04})] = ["within_limits"]
    found = optimum.nature(table, best, BOUNDS, fails=fails, scores=scores)
    assert found.interior and found.bounds[0]["indifferent"]
    assert found.active == ({"variable": "thickness", "side": "lower", "neighbour": 0.04,
                             "fails": ["within_limits"]},)
    assert "indifferent: wall_k" in found.text() and "thickness 0.04 m fails within_limits" \
        in found.text()
    # without the tie, the wall's bound holds the optimum
    distinct = np.column_stack([np.arange(table["thickness"].size, dtype=float)] * 2)
    assert not optimum.nature(table, best, BOUNDS, scores=distinct).interior
