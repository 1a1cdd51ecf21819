"""The compiled kernels most of the suite runs, compiled once before pytest-xdist's workers
start (tests/conftest.py), so that the workers load them from numba's on-disk cache instead of
each compiling the same ones (measured on a fresh clone, 2 cores: a cold cache cost the suite
53 s of its 258, a warm one none). Two processes, one per core; a kernel variant missing here
is compiled by the first worker that needs it, as before."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

PLANAR = """
import numpy as np, engine
accel = np.sin(np.linspace(0.0, 20.0, 200))
for building in (engine.Building(), engine.Building(story_yield_force=(3e6,) * 4)):
    engine.simulate(accel, 0.01, engine.Contact.bumper([0.1]), building, backend="numba")
"""
IN_PLAN = """
import numpy as np, engine
accel = np.sin(np.linspace(0.0, 20.0, 200))
pair = np.column_stack([accel, 0.5 * accel])
engine.simulate(pair, 0.01, engine.Contact.bumper([0.1]), backend="numba")
twists = engine.Building(torsion=engine.Torsion(plan_size=(30.0, 20.0)))
engine.simulate(pair, 0.01, engine.Contact.bumper([0.1]), twists, backend="numba")
"""
SCRIPTS = (PLANAR, IN_PLAN)
"""What each process runs: the paper's building planar (linear and yielding stories), then
in plan and twisting (the default 16 bearings, 8 contact points)."""


def warm(root: Path) -> None:
    """Compile SCRIPTS' kernels in `root`'s checkout, two processes at once; a failure is
    left to the tests that run those kernels to report."""
    processes = [subprocess.Popen([sys.executable, "-c", script], cwd=root,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                 for script in SCRIPTS]
    for process in processes:
        process.wait()
