"""One time loop, many simulations: batch invariance, stability limit, histories."""
import numpy as np
import pytest

import engine
from engine import Building, Contact, History


@pytest.fixture(scope="module")
def short_record(paper_record):
    """The strongest 12 s of Pacoima Dam 164 (enough for several poundings)."""
    rec = paper_record("pacoima")
    n = int(12.0 / rec.dt)
    return rec.accel[:n], rec.dt


def _mixed_batch(size, rng):
    """`size` members mixing every law and varied parameters, buildings included."""
    gaps = rng.uniform(0.08, 0.25, size)
    parts = [
        Contact.none(size // 10),
        Contact.linear(gaps[: size // 5], k=rng.uniform(5e8, 2.5e9, size // 5)),
        Contact.jankowski(gaps[: size // 5], beta=rng.uniform(1e10, 1e11, size // 5)),
        Contact.hertzdamp(gaps[: size // 5], k=rng.uniform(1e10, 1e11, size // 5)),
    ]
    rest = size - sum(len(p) for p in parts)
    parts.append(Contact.bumper(gaps[:rest] + 0.06, thickness=rng.uniform(0.03, 0.06, rest),
                                strain=rng.uniform(0.6, 1.0, rest),
                                n_bumpers=rng.integers(1, 33, rest),
                                k_w=rng.uniform(5e8, 2.5e9, rest), cor=rng.uniform(0.3, 1.0, rest)))
    contact = Contact.concat(parts)
    perm = rng.permutation(size)
    k1s, fys = rng.uniform(150e6, 250e6, size), rng.uniform(0.05, 0.15, size)
    buildings = [Building(k1=float(k1), fy_ratio=float(f)) for k1, f in zip(k1s, fys, strict=True)]
    return contact[perm], [buildings[i] for i in perm]


def test_member_peaks_do_not_depend_on_the_batch(short_record, backend):
    accel, accel_dt = short_record
    # the NumPy loop, a step per Python iteration, on a smaller batch (it costs 10x more)
    size = 520 if backend == "numba" else 130
    contact, buildings = _mixed_batch(size, np.random.default_rng(7))
    dt = 1e-3
    batch = engine.simulate(accel, accel_dt, contact, buildings, dt=dt, backend=backend)
    assert np.count_nonzero(batch.n_impacts) > 0.55 * size      # the batch really pounds
    # Each member alone costs the NumPy loop a step per Python iteration whatever the batch
    # size: three members there (first, middle, last), five on the kernel.
    alone_ones = (0, 1, size // 4 + 7, size // 2 + 51, size - 1) if backend == "numba" \
        else (0, size // 2 + 3, size - 1)
    for i in alone_ones:
        alone = engine.simulate(accel, accel_dt, contact[i], [buildings[i]], dt=dt,
                                backend=backend)
        for name, value in alone.peaks().items():
            np.testing.assert_allclose(getattr(batch, name)[i], value[0], rtol=1e-12, atol=0,
                                       err_msg=f"{name}, member {i}")


def test_unstable_dt_is_refused_with_the_limit(backend):
    contact = Contact.linear([0.1, 0.2], k=[2.5e9, 2.5e11])
    limit = engine.stable_dt(contact, Building())
    assert limit[1] < limit[0] < 0.02
    with pytest.raises(engine.UnstableTimeStep, match=f"{limit[1]:.4g} s"):
        engine.simulate(np.zeros(100), 0.01, contact, dt=1.01 * limit[1], backend=backend)
    engine.simulate(np.zeros(100), 0.01, contact, dt=0.99 * limit[1], backend=backend)


def test_stability_limit_is_the_central_difference_limit():
    """Undamped linear contact: the limit is 2 / omega_max of the stiffened building, and an
    unconstrained building's limit is set by its own highest mode."""
    b = Building(zeta_iso=0, zeta_sup=0)
    k = b.stiffness_matrix()
    k[0, 0] += 2.5e9
    m = np.asarray(b.masses)
    omega_max = np.sqrt(np.linalg.eigvalsh(k / np.sqrt(np.outer(m, m)))[-1])
    contact = Contact.linear(0.1, k=2.5e9, cor=1.0)
    assert engine.stable_dt(contact, b)[0] == pytest.approx(2 / omega_max, rel=1e-12)
    free = engine.stable_dt(Contact.none(1), b)[0]
    assert free == pytest.approx(2 / (2 * np.pi / b.natural_periods().min()), rel=1e-12)


def test_history_matches_peaks(short_record, backend):
    accel, accel_dt = short_record
    contact = Contact.concat([Contact.none(1), Contact.bumper([0.2, 0.25]), Contact.linear(0.2)])
    res = engine.simulate(accel, accel_dt, contact, dt=1e-3, history=History([3, 1], every=1),
                          backend=backend)
    h = res.history
    assert h["isolator_disp"].shape == (2, h["time"].size)
    assert h["time"][1] == pytest.approx(1e-3)
    for row, member in enumerate([3, 1]):
        assert np.abs(h["isolator_disp"][row]).max() == res.peak_isolator_disp[member]
        assert np.abs(h["total_accel"][row]).max(axis=0) == pytest.approx(
            res.peak_total_accel[member], rel=0, abs=0)
        assert h["impact_force"][row].max() == res.max_impact_force[member]
        assert h["indentation"][row].max() == res.max_indentation[member]
    sparse = engine.simulate(accel, accel_dt, contact, dt=1e-3, history=History([1], every=10),
                             backend=backend)
    np.testing.assert_array_equal(sparse.history["isolator_disp"][0], h["isolator_disp"][1, ::10])


# The compiled loop: the NumPy loop gives its impact energies to 1e-9 with linear walls of
# COR 0.3 to 1 (tests/engine/loops/test_numba_loop.py::test_backends_agree_on_every_peak).
@pytest.mark.parametrize("backend", ["numba"])
def test_energy_balance_of_an_elastic_wall(short_record, backend):
    """With COR = 1 the wall dissipates nothing: the work done on it over the record is zero
    to within the discretisation (contacts that are closed at the end excepted)."""
    accel, accel_dt = short_record
    contact = Contact.linear([0.15, 0.20], k=2.5e9, cor=1.0)
    res = engine.simulate(accel, accel_dt, contact, dt=5e-4, backend=backend)
    elastic_energy_scale = res.max_impact_force**2 / (2 * 2.5e9)
    assert np.all(res.n_impacts > 0)
    np.testing.assert_allclose(res.impact_energy, 0, atol=1e-3 * elastic_energy_scale.max())
    damped = engine.simulate(accel, accel_dt, Contact.linear([0.15, 0.20], cor=0.5), dt=5e-4,
                             backend=backend)
    assert np.all(damped.impact_energy > 0.05 * elastic_energy_scale)


def test_bad_input_is_refused():
    c = Contact.none(1)
    with pytest.raises(engine.EngineError, match="accel"):
        engine.simulate(np.array([0.0, np.nan, 1.0]), 0.01, c)
    with pytest.raises(engine.EngineError, match="accel_dt"):
        engine.simulate(np.zeros(10), 0.0, c)
    with pytest.raises(engine.EngineError, match="dt"):
        engine.simulate(np.zeros(10), 0.01, c, dt=-1e-3)
    with pytest.raises(engine.EngineError, match="building"):
        engine.simulate(np.zeros(10), 0.01, Contact.none(2), [Building()] * 3)
    with pytest.raises(engine.EngineError, match="k2"):
        Building(k2=300e6)
