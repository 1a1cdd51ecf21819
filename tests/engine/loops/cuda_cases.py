"""Batches the device loops' tests run on both backends (tests/engine/loops/test_cuda_*.py):
every impact law, isolator law and story law, P-Delta, collapse and histories, small enough
for numba's CUDA simulator (which runs each member's thread in Python)."""
from __future__ import annotations

import numpy as np

import engine
from engine import Building, Contact, Isolator, Stories
from engine.results import RESIDUALS

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
    """The device's result is the CPU kernel's: collapse flags, modes and times (the step)
    equal; peaks to rtol; the RESIDUALS to rtol of the displacements they are differences of
    (the member's peak isolator displacement plus its stories' peak drifts), and histories to
    rtol of the member's largest value of each: the device fuses multiplications and
    additions, so a value near zero carries the round-off of the magnitudes it came from (a
    GPU showed 2.4e-17 m on a residual drift of 4.1e-6 m, 1.3e-8 N on a force of 4.8e3 N in a
    history peaking near 1e6 N)."""
    assert device.collapsed.tolist() == cpu.collapsed.tolist()
    assert device.collapse_mode.tolist() == cpu.collapse_mode.tolist()
    np.testing.assert_array_equal(device.collapse_time, cpu.collapse_time)
    residual = {quantity.name for quantity in RESIDUALS}
    scale = cpu.peak_isolator_disp + cpu.peak_interstory_drift.sum(axis=1)
    for name, value in vars(cpu).items():
        if isinstance(value, np.ndarray) and name != "collapse_time":
            atol = rtol * scale.reshape((-1,) + (1,) * (value.ndim - 1)) if name in residual \
                else 1e-300
            assert_close(getattr(device, name), value, rtol, atol, name)
    if cpu.history is not None:
        for name, value in cpu.history.items():
            largest = np.abs(value).reshape(len(value), -1).max(axis=1) if value.ndim > 1 \
                else np.abs(value).max()
            atol = rtol * np.reshape(largest, (-1,) + (1,) * (value.ndim - 1))
            assert_close(device.history[name], value, rtol, atol, name)


def assert_close(actual, desired, rtol: float, atol, name: str) -> None:
    """|actual - desired| <= atol + rtol |desired| everywhere (NaN where both are), atol an
    array broadcast against them (numpy's assert_allclose takes a number only)."""
    assert np.shape(actual) == np.shape(desired), name
    close = np.isclose(actual, desired, rtol=rtol, atol=atol, equal_nan=True)
    if not close.all():
        first = tuple(int(i) for i in np.argwhere(~close)[0])
        raise AssertionError(f"{name}: {close.size - close.sum()} of {close.size} differ; first "
                             f"at {first}: {float(actual[first])!r} against "
                             f"{float(desired[first])!r}")


def both(*args, **kwargs):
    """engine.simulate on the device and on the compiled CPU loop, at DT."""
    return (engine.simulate(*args, dt=DT, backend="cuda", **kwargs),
            engine.simulate(*args, dt=DT, backend="numba", **kwargs))
