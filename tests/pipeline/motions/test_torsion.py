"""pipeline.motions.torsion: ASCE 7-22's total maximum displacement D_TM (section 17.5.3.3)
against hand calculations of its equations."""
from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.motions import torsion


def cell_centres(b_x, b_y, n_x, n_y):
    """Bearings at the centres of an n_x x n_y grid of cells: P_T tends to 1 from below."""
    x = (np.arange(n_x) + 0.5) / n_x * b_x - b_x / 2
    y = (np.arange(n_y) + 0.5) / n_y * b_y - b_y / 2
    gx, gy = np.meshgrid(x, y)
    return np.column_stack([gx.ravel(), gy.ravel()])


def test_a_square_plan_with_accidental_eccentricity_only_is_the_codes_floor():
    # P_T 1 (floored), y = L/2, e = 0.05 L: 1 + (L/2) 12 (0.05 L) / (2 L^2) = 1.15 exactly
    out = torsion.total_maximum_displacement(0.30, (30.0, 30.0),
                                             positions=cell_centres(30, 30, 20, 20))
    assert out["p_t"] == 1.0
    assert out["along_x"] == pytest.approx(1.15 * 0.30, rel=1e-12)
    assert out["d_tm"] == pytest.approx(0.345, rel=1e-12)


def test_a_rectangular_eccentric_plan_by_hand():
    # 40 x 20 m, mass centre 1 m off along y; loading along x: y = 10, e = 1 + 0.05 x 20 = 2,
    # 1 + 10 x 12 x 2 / (20^2 + 40^2) = 1.12; along y: y = 20, e = 0.05 x 40 = 2: 1.24
    out = torsion.total_maximum_displacement(0.25, (40.0, 20.0), mass_offset=(0.0, 1.0),
                                             positions=cell_centres(40, 20, 40, 20))
    assert out["along_x"] == pytest.approx(1.12 * 0.25, rel=1e-12)
    assert out["along_y"] == pytest.approx(1.24 * 0.25, rel=1e-12)
    assert out["d_tm"] == pytest.approx(0.31, rel=1e-12) and not out["floor_governs"]


def test_bearings_at_the_edges_raise_the_torsional_period_ratio():
    # a 4 x 4 grid edge to edge on a square: mean r^2 = L^2/4 + L^2/36, r_I^2 = L^2/6:
    # P_T = sqrt(10/6); the formula then gives 1 + 0.15 / P_T^2 = 1.09 and the floor governs
    grid = torsion.grid_positions((30.0, 30.0))
    assert torsion.period_ratio((30.0, 30.0), grid) == pytest.approx(math.sqrt(10 / 6))
    out = torsion.total_maximum_displacement(0.30, (30.0, 30.0))
    assert out["along_x"] == pytest.approx(0.30 * (1 + 0.15 * 6 / 10), rel=1e-12)
    assert out["floor_governs"] and out["d_tm"] == pytest.approx(0.345, rel=1e-12)


def test_bad_arguments_are_refused_in_one_line():
    for kwargs, match in (({"plan_size": (30.0, -1.0)}, "plan_size"),
                          ({"mass_offset": (1.0,)}, "mass_offset"),
                          ({"accidental": 0.7}, "accidental")):
        args = {"d_m": 0.3, "plan_size": (30.0, 30.0), **kwargs}
        with pytest.raises(ValueError, match=match):
            torsion.total_maximum_displacement(**args)
    with pytest.raises(ValueError, match="at least 2 bearings"):
        torsion.grid_positions((30.0, 30.0), (1, 4))
