"""The compiled kernel against the NumPy reference loop: same physics functions, same scheme,
so the same peaks and histories to round-off; the fallback without numba; the compile cache."""
import subprocess
import sys
import warnings

import numpy as np
import pytest

import engine
from engine import Building, Contact, History, backends
from engine.loops import numba_loop, numpy_loop
from engine.scheme import checked_record

RTOL = 1e-9


@pytest.fixture(scope="module")
def short_record(paper_record):
    rec = paper_record("pacoima")
    n = int(12.0 / rec.dt)
    return rec.accel[:n], rec.dt


def _every_case(rng):
    """All laws, bumpers crushed (thin, small strain) and in cavities, Kelvin-Voigt walls
    whose onset weighting matters (stiff, low COR), no wall, and per-member buildings. The
    Hertz exponents come from a short list: each new one costs the calibration table ~2 s."""
    parts = [
        Contact.none(3),
        Contact.linear(rng.uniform(0.08, 0.2, 8), k=rng.uniform(5e8, 2.5e9, 8),
                       cor=rng.uniform(0.3, 1.0, 8)),
        Contact.linear([0.1, 0.12], k=2.5e9, cor=0.5, xi_rule="eq3"),
        Contact.jankowski(rng.uniform(0.08, 0.2, 6), beta=rng.uniform(1e10, 1e11, 6),
                          cor=rng.uniform(0.3, 0.9, 6)),
        Contact.hertzdamp(rng.uniform(0.08, 0.2, 6), k=rng.uniform(1e10, 1e11, 6),
                          n=rng.choice([1.2, 1.5, 2.0], 6), chi_rule="calibrated"),
        Contact.bumper(rng.uniform(0.12, 0.25, 8), thickness=rng.uniform(0.03, 0.06, 8),
                       n_bumpers=rng.integers(1, 33, 8), cor=rng.uniform(0.3, 1.0, 8)),
        Contact.bumper([0.08, 0.1, 0.12], thickness=0.02, strain=0.4, n_bumpers=1),  # crushed
        Contact.bumper([0.15, 0.18], thickness=0.05, cavity=0.02, c_imp_rule="calibrated"),
        Contact.bumper(0.16, c_imp=0.5),
    ]
    contact = Contact.concat(parts)
    size = len(contact)
    buildings = [Building(k1=float(k1), fy_ratio=float(f), damping=d)
                 for k1, f, d in zip(rng.uniform(150e6, 250e6, size),
                                     rng.uniform(0.05, 0.15, size),
                                     rng.choice(["paper", "modal"], size), strict=True)]
    perm = rng.permutation(size)
    return contact[perm], [buildings[i] for i in perm]


@pytest.fixture(scope="module")
def both(short_record):
    accel, accel_dt = short_record
    contact, buildings = _every_case(np.random.default_rng(11))
    history = History([0, 5, len(contact) - 1, 5], every=7)
    return {name: engine.simulate(accel, accel_dt, contact, buildings, dt=1e-3, history=history,
                                  backend=name)
            for name in ("numba", "numpy")}, contact


def test_backends_agree_on_every_peak(both):
    results, contact = both
    fast, ref = results["numba"], results["numpy"]
    assert np.count_nonzero(ref.n_impacts) > 0.8 * len(contact)
    assert np.any(ref.max_indentation > contact.delta_u)          # some bumpers crush
    for name, value in ref.peaks().items():
        np.testing.assert_allclose(getattr(fast, name), value, rtol=RTOL, atol=0,
                                   err_msg=name)
    np.testing.assert_array_equal(fast.n_impacts, ref.n_impacts)


def test_backends_agree_on_histories(both):
    results, _ = both
    fast, ref = results["numba"].history, results["numpy"].history
    assert fast.keys() == ref.keys()
    for name, value in ref.items():
        assert fast[name].shape == value.shape, name
        scale = np.max(np.abs(value)) if value.size else 1.0
        np.testing.assert_allclose(fast[name], value, rtol=0, atol=RTOL * scale, err_msg=name)


def test_progress_chunks_do_not_change_a_bit(short_record, monkeypatch):
    from engine.loops import numba_support

    accel, accel_dt = short_record
    contact, buildings = _every_case(np.random.default_rng(3))
    calls = []
    few = []
    engine.simulate(accel, accel_dt, contact, buildings, dt=1e-3, backend="numba",
                    progress=lambda step, n: few.append(step))
    assert len(few) < 10  # a small batch: chunks of MIN_CHUNK_MEMBER_STEPS, not 1% each
    monkeypatch.setattr(numba_support, "MIN_CHUNK_MEMBER_STEPS", 1)
    chunked = engine.simulate(accel, accel_dt, contact, buildings, dt=1e-3,
                              progress=lambda step, n: calls.append((step, n)), backend="numba")
    whole = engine.simulate(accel, accel_dt, contact, buildings, dt=1e-3, backend="numba")
    assert 90 <= len(calls) <= 110 and calls[-1][0] == calls[-1][1]
    for name, value in whole.peaks().items():
        np.testing.assert_array_equal(getattr(chunked, name), value, err_msg=name)


def test_threads_do_not_change_a_bit(short_record):
    numba = pytest.importorskip("numba")
    accel, accel_dt = short_record
    contact, buildings = _every_case(np.random.default_rng(5))
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        serial = engine.simulate(accel, accel_dt, contact, buildings, dt=1e-3, backend="numba")
        numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
        threaded = engine.simulate(accel, accel_dt, contact, buildings, dt=1e-3,
                                   backend="numba")
    finally:
        numba.set_num_threads(before)
    for name, value in serial.peaks().items():
        np.testing.assert_array_equal(getattr(threaded, name), value, err_msg=name)


def test_two_body_backends_agree():
    m = 300.0
    cor = np.linspace(0.3, 1.0, 8)
    contact = Contact.concat([
        Contact.linear(1.0, k=2.5e7, cor=cor, m_eff=m / 2),
        Contact.jankowski(1.0, beta=2.75e9, cor=cor, m_eff=m / 2),
        Contact.hertzdamp(1.0, k=1e9, cor=cor, m_eff=m / 2),
        Contact.bumper(1.0, cor=cor, m_eff=m / 2),
        Contact.bumper(1.0, thickness=0.01, area=0.04**2, n_bumpers=1, cor=cor, m_eff=m / 2)])
    v = np.geomspace(0.3, 4.0, len(contact))
    fast = engine.two_body(m, m, v, contact, backend="numba")
    ref = engine.two_body(m, m, v, contact, backend="numpy")
    for name in ("peak_force", "peak_indentation", "cor", "dissipated_energy",
                 "hysteresis_area", "expected_energy_loss", "dt"):
        # Energies of elastic members are differences of nearly equal numbers: scale by the
        # largest of the batch.
        value = getattr(ref, name)
        np.testing.assert_allclose(getattr(fast, name), value, rtol=RTOL,
                                   atol=RTOL * np.abs(value).max(), err_msg=name)
    for name in ("indentation", "force"):
        assert getattr(fast, name).shape == getattr(ref, name).shape
        np.testing.assert_allclose(getattr(fast, name), getattr(ref, name), rtol=0,
                                   atol=RTOL * np.abs(getattr(ref, name)).max(), err_msg=name)


def test_kernel_ground_motion_is_np_interp_bit_for_bit(short_record):
    accel, accel_dt = short_record
    accel = np.asarray(accel, dtype=float)
    for dt in (1e-4, 3.3e-4, 5e-4, 1e-3, accel_dt, 0.013):
        n_steps = checked_record(accel, accel_dt, dt)[1]
        reference = numpy_loop.ground_motion(accel, accel_dt, dt, n_steps)
        np.testing.assert_array_equal(numba_loop.ground_motion(accel, accel_dt, dt, n_steps),
                                      reference)


def test_without_numba_the_numpy_loop_runs_with_one_notice(monkeypatch):
    real_time_loop = backends.time_loop

    def no_numba(backend):
        if backend == "numba":
            raise ImportError("No module named 'numba'")
        return real_time_loop(backend)

    monkeypatch.setattr(backends, "time_loop", no_numba)
    monkeypatch.setattr(backends, "_notice_given", False)
    contact = Contact.linear([0.01, 0.02])
    accel = np.sin(np.linspace(0, 20, 400)) * 5.0
    with pytest.warns(backends.BackendNotice, match="NumPy time loop") as record:
        res = engine.simulate(accel, 0.01, contact)
        engine.simulate(accel, 0.01, contact)
        engine.two_body(1.0, 1.0, 1.0, Contact.linear(1.0, k=1e6, m_eff=0.5))
    assert len(record) == 1
    reference = engine.simulate(accel, 0.01, contact, backend="numpy")
    np.testing.assert_array_equal(res.peak_total_accel, reference.peak_total_accel)
    with pytest.raises(engine.EngineError, match="numba"):
        engine.simulate(accel, 0.01, contact, backend="numba")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        engine.simulate(accel, 0.01, contact, backend="numpy")   # asked for: no notice
    with pytest.raises(engine.EngineError, match="backend"):
        engine.simulate(accel, 0.01, contact, backend="fortran")


def test_compiled_kernel_loads_from_the_cache():
    """This session has compiled (or loaded) the kernel: a new process finds it on disk (the
    kernel is compiled once per number of levels, the paper's 5 here)."""
    pytest.importorskip("numba")
    engine.simulate(np.zeros(10), 0.01, Contact.bumper([0.3]), backend="numba")
    code = ("import numpy as np, engine\n"
            "from engine.loops import numba_loop\n"
            "engine.simulate(np.zeros(10), 0.01, engine.Contact.bumper([0.3]), backend='numba')\n"
            "stats = numba_loop._run.stats\n"
            "print(sum(stats.cache_hits.values()), sum(stats.cache_misses.values()))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    hits, misses = int(out[0]), int(out[1])
    # loaded from disk, not compiled: numba's own count, not a clock (a loaded machine must
    # not turn this red; how long a load takes is for benchmarks/)
    assert hits >= 1 and misses == 0


def test_every_compiled_loop_is_cached_on_the_physics_it_compiles():
    """Both kernel files, planar and in plan, are keyed on their physics (a change of a story
    law must recompile the plan kernel too: it once kept its cache, keyed on its own file
    alone, and ran a law's old state layout)."""
    from pathlib import Path

    from numba.core.caching import CacheImpl

    from engine.loops import compiled, numba_loop, numba_plan, numba_support
    from engine.stories.laws import imk

    locator = CacheImpl._locator_classes[0]
    assert locator.__name__ == "_PhysicsCacheLocator"
    for module in (numba_loop, numba_plan):
        sources = numba_support.KERNEL_SOURCES[Path(module.__file__).resolve()]
        for physics in (imk.__file__, compiled.__file__, module.__file__):
            assert Path(physics).resolve() in sources
        found = locator.from_function(module._run.py_func, module.__file__)
        assert found is not None and found.get_source_stamp() == locator.from_function(
            module._member.py_func, module.__file__).get_source_stamp()
