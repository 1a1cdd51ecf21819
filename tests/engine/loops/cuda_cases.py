"""Batches the device loops' tests run on both backends (tests/engine/loops/test_cuda_*.py):
every impact law, isolator law and story law, P-Delta, collapse and histories, small enough
for numba's CUDA simulator (which runs each member's thread in Python)."""
from __future__ import annotations

import numpy as np

import engine
from engine import Building, Contact, Isolator, Stories

T = np.arange(151) * 0.01  # s: 1.5 s of record, 1500 steps of DT
DT = 1e-3  # s: within every member's stability limit (the simulator costs ~40 us a step)
AG = 7.0 * np.sin(2 * np.pi * T / 1.3) + np.random.default_rng(3).normal(0.0, 0.5, T.size)
AG_XY = np.column_stack([AG, 5.0 * np.cos(2 * np.pi * T / 0.9)])
HEIGHTS = (4.0, 3.5, 3.5, 3.5)
TFP = dict(L1=0.3, L2=1.5, L3=1.6, d1=0.05, d2=0.15, d3=0.15, mu1=0.01, mu2=0.02, mu3=0.03)
ISOLATORS = (Isolator.bilinear(),
             Isolator.friction_pendulum(radius=2.0, mu_slow=0.04, mu_fast=0.09, rate=30.0),
             Isolator.triple_friction_pendulum(**TFP))
STORIES = (None,  # the paper's linear stories
           Stories.bilinear(yield_force=(2.5e6, 2.2e6, 1.7e6, 1.0e6), post_yield_ratio=0.02),
           Stories.imk(yield_force=(2.5e6, 2.2e6, 1.7e6, 1.0e6), plastic_deformation=0.03,
                       post_capping_deformation=0.3))


def walls(gap: float = 0.06) -> list[Contact]:
    """One wall of each impact law, and a member without wall."""
    return [Contact.linear([gap]), Contact.jankowski([gap], beta=2.75e9),
            Contact.hertzdamp([gap], k=2.75e9), Contact.bumper([gap + 0.03], thickness=0.05,
                                                               n_bumpers=3),
            Contact.none(1)]


def mixed_batch():
    """(contact, buildings, scale): each isolator law under each wall, then each story law
    with P-Delta and a collapse drift at intensities from standing to collapse, one on an
    isolator with a displacement capacity it passes."""
    contacts, buildings, scale = [], [], []
    for isolator in ISOLATORS:
        for wall in walls():
            contacts.append(wall)
            buildings.append(Building(isolator=isolator))
            scale.append(1.0)
    for stories in STORIES:
        for level in (0.4, 1.0, 2.5):
            contacts.append(Contact.linear([0.08]))
            buildings.append(Building(stories=stories, story_height=HEIGHTS, p_delta=True,
                                      collapse_drift_ratio=0.03))
            scale.append(level)
    contacts.append(Contact.none(1))
    buildings.append(Building(isolator=Isolator.bilinear(capacity=0.05)))
    scale.append(1.0)
    return Contact.concat(contacts), buildings, np.array(scale)


def assert_same(device, cpu, rtol: float = 1e-12) -> None:
    """The device's result is the CPU kernel's: peaks to rtol, collapse flags, modes and
    times (the step) equal, histories to rtol."""
    assert device.collapsed.tolist() == cpu.collapsed.tolist()
    assert device.collapse_mode.tolist() == cpu.collapse_mode.tolist()
    np.testing.assert_array_equal(device.collapse_time, cpu.collapse_time)
    for name, value in vars(cpu).items():
        if isinstance(value, np.ndarray) and name != "collapse_time":
            np.testing.assert_allclose(getattr(device, name), value, rtol=rtol, atol=1e-300,
                                       err_msg=name)
    if cpu.history is not None:
        for name, value in cpu.history.items():
            np.testing.assert_allclose(device.history[name], value, rtol=rtol, atol=1e-9,
                                       err_msg=name)


def both(*args, **kwargs):
    """engine.simulate on the device and on the compiled CPU loop, at DT."""
    return (engine.simulate(*args, dt=DT, backend="cuda", **kwargs),
            engine.simulate(*args, dt=DT, backend="numba", **kwargs))
