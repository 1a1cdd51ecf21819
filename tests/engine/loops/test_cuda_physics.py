"""The physics as the device compiles it (engine/loops/cuda_physics.py): NumPy's functions on
scalars as the device has them give NumPy's numbers (NaN included), the laws compiled from their
one source give the CPU's, and a machine without a GPU is told so in one line whose advice
runs."""
from __future__ import annotations

import math

import numpy as np
import pytest

import engine
from engine import Contact
from engine.errors import EngineError

cuda_physics = pytest.importorskip("engine.loops.cuda_physics")
VALUES = (-2.5, -0.0, 0.0, 1e-300, 3.0, math.inf, -math.inf, math.nan)
host_calls = pytest.mark.skipif(not cuda_physics.simulated(),
                                reason="a device function runs inside a kernel on a GPU")
"""Tests that call the device functions from Python: the simulator's, not a GPU's."""


@host_calls
@pytest.mark.parametrize("name", ["maximum", "minimum"])
def test_scalar_maximum_and_minimum_are_numpys_nan_included(name):
    scalar, ufunc = getattr(cuda_physics.SCALAR_NUMPY, name), getattr(np, name)
    for a in VALUES:
        for b in VALUES:
            expected = ufunc(a, b)
            got = scalar(a, b)
            assert (math.isnan(got) and math.isnan(expected)) or got == expected, (a, b)


@host_calls
def test_scalar_sign_clip_and_the_rest_are_numpys():
    scalar = cuda_physics.SCALAR_NUMPY
    for x in VALUES:
        for name in ("sign", "abs", "isfinite"):
            expected, got = getattr(np, name)(x), getattr(scalar, name)(x)
            assert (math.isnan(got) and math.isnan(expected)) or got == expected, (name, x)
        expected = np.clip(x, -1.0, 2.0)
        got = scalar.clip(x, -1.0, 2.0)
        assert (math.isnan(got) and math.isnan(expected)) or got == expected
    for name in ("sqrt", "exp", "log"):
        assert getattr(scalar, name)(2.5) == getattr(np, name)(2.5)
    assert scalar.hypot(3.0, 4.0) == np.hypot(3.0, 4.0) == 5.0


@host_calls
def test_each_impact_law_compiled_for_the_device_gives_the_cpus_terms():
    contact = Contact.concat([Contact.linear([0.05]), Contact.jankowski([0.05], beta=2.75e9),
                              Contact.hertzdamp([0.05], k=2.75e9),
                              Contact.bumper([0.08], thickness=0.05, n_bumpers=3)])
    from engine.impact.contact import law_rows
    from engine.loops import compiled

    rows = law_rows(contact)
    for b, code in enumerate(contact.law):
        for delta, rate in ((1e-3, 0.4), (2e-2, -0.3), (5e-2, 0.0)):
            cpu = compiled.law_terms(code, delta, rate, 0.5, rows[b])
            device = cuda_physics.law_terms(code, delta, rate, 0.5, rows[b])
            assert device == pytest.approx(cpu, rel=1e-15, abs=0.0)
            assert cpu[0] > 0.0


def test_without_a_gpu_one_line_says_why_and_what_runs_instead(monkeypatch):
    monkeypatch.setattr(cuda_physics, "simulated", lambda: False)
    monkeypatch.setattr(cuda_physics.cuda, "is_available", lambda: False)
    cuda_physics.unavailable.cache_clear()
    try:
        with pytest.raises(EngineError) as caught:
            engine.simulate(np.zeros(10), 0.01, Contact.none(1), backend="cuda")
    finally:
        cuda_physics.unavailable.cache_clear()
    message = str(caught.value)
    assert "\n" not in message
    assert 'pip install -e ".[cuda]"' in message and "no NVIDIA GPU or driver" in message
    # the advice runs: the CPU kernel takes the same call
    assert engine.simulate(np.zeros(10), 0.01, Contact.none(1), backend="numba").n_impacts == 0
