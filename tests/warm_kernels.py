"""Compile the engine's common kernels into numba's on-disk cache, so that the test
processes load them instead of each compiling its own (tests/conftest.py runs this before
pytest-xdist starts its workers, one process per loop module).

    python -m tests.warm_kernels planar|plan
"""
from __future__ import annotations

import sys

import numpy as np

LEVELS = (2, 5, 9, 21)
"""Level counts the tests simulate: 1-, 4-, 8- and 20-story buildings."""


def planar() -> None:
    """The planar kernel, serial (one member) and parallel (two), for every LEVELS; the
    two-body kernel."""
    import engine

    accel = np.zeros(50)
    for levels in LEVELS:
        building = engine.Building(masses=(5e5,) + (4e5,) * (levels - 1),
                                   story_stiffness=(9e8,) * (levels - 1))
        for size in (1, 2):
            engine.simulate(accel, 0.01, engine.Contact.linear(np.full(size, 0.2)), building)
    engine.two_body(1.0, 1.0, 1.0, engine.Contact.linear(0.1, m_eff=0.5))


def plan() -> None:
    """The plan kernel, for the paper's building."""
    import engine

    engine.simulate(np.zeros((50, 2)), 0.01, engine.Contact.linear([0.2, 0.3]))


if __name__ == "__main__":
    {"planar": planar, "plan": plan}[sys.argv[1]]()
