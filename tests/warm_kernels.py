"""The compiled kernels the suite runs, compiled once before pytest-xdist's workers start
(tests/conftest.py), so that the workers load them from numba's on-disk cache instead of each
compiling the same ones (measured on a fresh clone, 2 cores: a cold cache cost the suite 53 s of
its 258, a warm one none). A kernel is compiled per isolator law, and per number of levels and
story law (the planar one), per story law (in plan) and per multiple of 8 contact points
(twisting): the variants below are those the suite's in-process tests compile. Two processes,
one per core; a variant missing here is compiled by the first worker that needs it, as before."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

COMMON = """
import numpy as np, engine
accel = np.sin(np.linspace(0.0, 20.0, 200))
pair = np.column_stack([accel, 0.5 * accel])
wall = engine.Contact.bumper([0.1])

fp = engine.Isolator.friction_pendulum(radius=2.0, mu_slow=0.04, mu_fast=0.08, rate=30.0)

def planar(n, yielding, **isolator):
    building = engine.Building(
        masses=(5e5,) + (4e5,) * n, story_stiffness=(8e8,) * n,
        story_yield_force=(6e6,) * n if yielding else None, **isolator)
    engine.simulate(accel, 0.01, wall, building, backend="numba")
"""
PLANAR = COMMON + """
for n in (1, 4, 8):
    for yielding in (False, True):
        planar(n, yielding)
planar(20, True)
for yielding in (False, True):
    planar(4, yielding, isolator=fp)
planar(8, True, isolator=fp)
"""
IN_PLAN = COMMON + """
planar(20, False)
imk = engine.Stories.imk(yield_force=3e6, plastic_deformation=0.09,
                         post_capping_deformation=0.35)
engine.simulate(accel, 0.01, wall, engine.Building(stories=imk), backend="numba")
for building in (engine.Building(), engine.Building(story_yield_force=(3e6,) * 4),
                 engine.Building(stories=imk),
                 engine.Building(torsion=engine.Torsion(plan_size=(30.0, 20.0))),
                 engine.Building(isolator=fp),
                 engine.Building(isolator=fp, torsion=engine.Torsion(plan_size=(30.0, 20.0)))):
    engine.simulate(pair, 0.01, wall, building, backend="numba")
"""
SCRIPTS = (PLANAR, IN_PLAN)
"""What each process runs: the planar kernel on 1, 4 and 8 stories, linear and yielding, on 20
yielding, and on friction pendulums (a kernel per isolator law) on 4, linear and yielding, and
8 yielding; then on 20 linear, on 4 IMK stories, in plan (linear, bilinear and IMK stories,
and on friction pendulums) and
twisting (the default 16 bearings, 8 contact points; on bilinear isolators and on friction
pendulums): about as long each."""


def warm(root: Path) -> None:
    """Compile SCRIPTS' kernels in `root`'s checkout, two processes at once; a failure is
    left to the tests that run those kernels to report."""
    processes = [subprocess.Popen([sys.executable, "-c", script], cwd=root,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                 for script in SCRIPTS]
    for process in processes:
        process.wait()
