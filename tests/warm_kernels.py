"""The compiled kernels the suite runs, compiled once before pytest-xdist's workers start
(tests/conftest.py), so that the workers load them from numba's on-disk cache instead of each
compiling the same ones (measured on a fresh clone, 2 cores: a cold cache cost the suite 53 s of
its 258, a warm one none). A kernel is compiled per isolator law, and per number of levels and
story law (the planar one), per story law (in plan) and per multiple of 8 contact points
(twisting): the variants below are all those the suite compiles (a variant missing here is
compiled by every worker and subprocess that needs it before one has cached it). Two
processes on 2 cores, measured on a fresh clone: 49 s for these 22 variants (57 s in four
processes), the suite 272 s and 527 s of CPU (303 s and 559 s with 19 of 25 variants warmed in
two processes, the other 6 left to the workers; 67 s and 127 s of CPU for 25)."""
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
SHORT = COMMON + """
for n in (1, 4, 8):
    for yielding in (False, True):
        planar(n, yielding)
"""
TALL = COMMON + """
for yielding in (False, True):
    planar(20, yielding)
    planar(4, yielding, isolator=fp)
planar(8, True, isolator=fp)
planar(4, False, isolator=engine.Isolator.triple_friction_pendulum(
    L1=0.3, L2=2.0, L3=2.0, d1=0.05, d2=0.3, d3=0.3, mu1=0.02, mu2=0.04, mu3=0.08))
imk = engine.Stories.imk(yield_force=3e6, plastic_deformation=0.09,
                         post_capping_deformation=0.35)
engine.simulate(accel, 0.01, wall, engine.Building(stories=imk), backend="numba")
"""
IN_PLAN = COMMON + """
imk = engine.Stories.imk(yield_force=3e6, plastic_deformation=0.09,
                         post_capping_deformation=0.35)
for building in (engine.Building(), engine.Building(story_yield_force=(3e6,) * 4),
                 engine.Building(stories=imk), engine.Building(isolator=fp)):
    engine.simulate(pair, 0.01, wall, building, backend="numba")
tfp = engine.Isolator.triple_friction_pendulum(L1=0.3, L2=2.0, L3=2.0, d1=0.05, d2=0.3, d3=0.3,
                                               mu1=0.02, mu2=0.04, mu3=0.08)
engine.simulate(pair, 0.01, wall, engine.Building(isolator=tfp), backend="numba")
"""
FP_YIELDING_IN_PLAN = """
engine.simulate(pair, 0.01, wall, engine.Building(isolator=fp, story_yield_force=(3e6,) * 4),
                backend="numba")
"""
TWISTING = COMMON + """
for isolator in (engine.Isolator.bilinear(), fp):
    engine.simulate(pair, 0.01, wall, engine.Building(
        isolator=isolator, torsion=engine.Torsion(plan_size=(30.0, 20.0))), backend="numba")
"""
SCRIPTS = (IN_PLAN + TWISTING, SHORT + TALL + FP_YIELDING_IN_PLAN)
"""What each process runs, about as long each: in plan, the kernel of linear, bilinear and IMK
stories on bilinear isolators, of linear stories on friction pendulums and of linear stories on
triple friction pendulums; twisting (the default 16 bearings, 8 contact points) on bilinear
isolators and on friction pendulums. Planar, on 1, 4, 8 and 20 stories, linear and yielding;
on friction pendulums (4 stories linear and yielding, 8 yielding), on triple friction
pendulums and on 4 IMK stories; and in plan bilinear stories on friction pendulums, which
balances the two (measured on a fresh clone, 2 cores, 2026-11-28: 47.5 s and 47.9 s, against
42.9 s and 50.5 s with it in the first). These are every variant the suite compiles but
the device simulator's. Two processes, not one per group: a process compiles the functions its
kernels call once (3-4 s), and two processes keep 2 cores busy without a third and fourth
contending for them (measured on a fresh clone, 2 cores: 49 s and 93 s of CPU for two, 57 s
and 112 s for four)."""


def warm(root: Path) -> None:
    """Compile SCRIPTS' kernels in `root`'s checkout, a process each, both at once; a failure
    is left to the tests that run those kernels to report."""
    processes = [subprocess.Popen([sys.executable, "-c", script], cwd=root,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                 for script in SCRIPTS]
    for process in processes:
        process.wait()
