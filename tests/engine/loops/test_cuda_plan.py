"""The device loop in plan (engine/loops/cuda_plan.py) gives the compiled CPU loop's results:
rectangular and circular moats, every impact law along the wall's normal, wall friction,
incidence angles, stories stiffer along y, yielding stories (slip elements) and uniaxial laws
along each axis, every isolator law in plan, P-Delta, collapse and histories. On numba's CUDA
simulator in CI (tests/conftest.py)."""
from __future__ import annotations

import numpy as np
import pytest

from engine import Building, Contact, History, Moat
from tests.engine.loops.cuda_cases import (
    AG_XY,
    ISOLATORS,
    assert_same,
    both,
    mixed_batch,
    walls,
)

pytest.importorskip("numba.cuda")


def test_every_law_in_plan_as_on_the_cpu():
    contact, buildings, scale = mixed_batch()
    size = len(contact)
    angle = np.linspace(0.0, 170.0, size)
    friction = np.where(np.arange(size) % 2 == 0, 0.3, 0.0)
    history = History(members=[1, 7, size - 1], every=5)
    device, cpu = both(AG_XY, 0.01, contact, buildings, history=history, scale=scale,
                       moat=Moat("rectangular", mu_wall=friction), angle=angle)
    assert_same(device, cpu)
    assert np.all(np.delete(cpu.n_impacts[:15], [4, 9, 14]) > 0)  # every wall
    assert cpu.collapsed.any() and not cpu.collapsed.all()


def test_a_circular_moat_as_on_the_cpu():
    """Every impact law on every isolator law against a circular moat, with friction (the
    story laws and collapse: the rectangular moat's test)."""
    contact = Contact.concat([wall for _ in ISOLATORS for wall in walls()])
    buildings = [Building(isolator=isolator) for isolator in ISOLATORS for _ in walls()]
    angle = np.linspace(0.0, 170.0, len(contact))
    device, cpu = both(AG_XY, 0.01, contact, buildings, angle=angle,
                       moat=Moat("circular", mu_wall=0.3))
    assert_same(device, cpu)
    assert np.all(np.delete(cpu.n_impacts, [4, 9, 14]) > 0)


def test_stories_stiffer_along_y_as_on_the_cpu():
    building = Building(story_stiffness_y=(9e8, 9e8, 8e8, 7e8))
    contact = Contact.concat(walls())  # one wall of each law
    device, cpu = both(AG_XY, 0.01, contact, building, angle=[10.0, 30.0, 50.0, 70.0, 90.0])
    assert_same(device, cpu)
