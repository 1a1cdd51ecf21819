"""studies.design.space: the design space's bounds from physical limits."""
from __future__ import annotations

import numpy as np
import pytest

from studies.design import space


def test_bounds_from_physical_limits():
    b = space.Bounds(gap=0.131, clearance=0.048, usable_strain=0.589, wall_length=18.0)
    limits = b.limits({"thickness": 0.10, "cavity_ratio": 0.2, "n_bumpers": 8,
                       "shape_factor": 0.5, "wall_k": 1.5e9})
    assert limits["thickness"][1][0] == pytest.approx(0.083 / 0.8)  # t (1 - c/t) <= room
    assert limits["cavity_ratio"][1][0] == pytest.approx(0.411)
    assert limits["n_bumpers"][1][0] == pytest.approx(18.0 / (2 * 4 * 0.5 * 0.10))
    # the neighbours stop at a bound, exactly on it
    config = {"thickness": 0.10, "cavity_ratio": 0.4, "n_bumpers": 8, "shape_factor": 0.5,
              "wall_k": 2.5e9}
    near = space.neighbours(config, 0, b)
    up = near["cavity_ratio"] > 0.4
    assert near["cavity_ratio"][up].tolist() == [pytest.approx(0.411)]
    assert not np.any(near["wall_k"] > 2.5e9) and not np.any(near["shape_factor"] < 0.5)
    assert all(b.allows(space.row(near, i)) for i in range(near["thickness"].size))
    assert space.usable_strain(0.8, None) == 0.8
    assert space.usable_strain(0.8, 30.9e6) == pytest.approx(0.589, abs=1e-3)
