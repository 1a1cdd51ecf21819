"""The planar device loop (engine/loops/cuda_loop.py) gives the compiled CPU loop's results:
every impact law, isolator law and story law, P-Delta, collapse (the same step and mode),
histories, a tall building's banded solve, runs in chunks. In CI on numba's CUDA simulator
(tests/conftest.py); on a GPU machine with NUMBA_ENABLE_CUDASIM=0, on the device, where fused
multiply-adds make them agree to round-off (1e-12 relative asked)."""
from __future__ import annotations

import numpy as np
import pytest

import engine
from engine import Building, Contact, History, Torsion
from engine.errors import EngineError
from engine.loops import numba_support
from tests.engine.loops.cuda_cases import AG, AG_XY, DT, assert_same, both, mixed_batch, walls

pytest.importorskip("numba.cuda")


def test_every_law_pounding_yielding_and_collapsing_as_on_the_cpu():
    contact, buildings, scale = mixed_batch()
    history = History(members=[0, 6, 11, len(contact) - 1], every=7)
    device, cpu = both(AG, 0.01, contact, buildings, history=history, scale=scale)
    assert_same(device, cpu)
    # the batch does what it is meant to: pounds with every law, yields, collapses both ways
    assert np.all(np.delete(cpu.n_impacts[:15], [4, 9, 14]) > 0)  # every wall
    assert set(cpu.collapse_mode[cpu.collapsed].tolist()) == {1, 2}  # story drift, capacity
    assert not cpu.collapsed[:14].any()  # (the 15th: a TFP with no wall passes its stops)


def test_a_tall_building_solves_its_banded_system_as_on_the_cpu():
    tall = Building(masses=(3e5,) * 21, story_stiffness=(8e8,) * 20)  # the CPU kernel the
    # suite compiles for 20 stories (tests/warm_kernels.py)
    contact = Contact.concat([Contact.linear([0.05]), Contact.bumper([0.08], thickness=0.05)])
    device, cpu = both(AG[:120], 0.01, contact, tall)
    assert_same(device, cpu)
    assert np.all(cpu.n_impacts > 0)


def test_chunks_of_steps_change_no_number(monkeypatch):
    monkeypatch.setattr(numba_support, "MIN_CHUNK_MEMBER_STEPS", 750)  # 5 members: 150 steps
    contact = Contact.concat(walls())
    calls = []
    chunked = engine.simulate(AG, 0.01, contact, dt=DT, backend="cuda",
                              progress=lambda step, n: calls.append((step, n)))
    whole = engine.simulate(AG, 0.01, contact, dt=DT, backend="cuda")
    n_steps = calls[-1][1]
    assert [step for step, _ in calls] == [*range(0, n_steps, 150), n_steps]
    assert_same(chunked, whole, rtol=0.0)


def test_the_twisting_model_is_refused_with_the_backend_that_runs_it():
    building = Building(torsion=Torsion(plan_size=(30.0, 30.0)))
    with pytest.raises(EngineError, match="backend 'cuda': the twisting model takes 'numba' "
                                          "or 'numpy'"):
        engine.simulate(AG_XY, 0.01, Contact.none(1), building, backend="cuda")


def test_two_bodies_run_on_the_cpu_kernel():
    contact = Contact.linear([0.01], m_eff=5e5)
    device = engine.two_body(1e6, 1e6, [1.0], contact, backend="cuda")
    cpu = engine.two_body(1e6, 1e6, [1.0], contact, backend="numba")
    for name, value in vars(cpu).items():
        if isinstance(value, np.ndarray):
            np.testing.assert_array_equal(getattr(device, name), value, err_msg=name)
