"""pipeline.motions.intensity against closed forms: ground velocity of known accelerations, the
linear
oscillator under a step and a ramp, and the isolated period of the paper's building by hand."""
from __future__ import annotations

import numpy as np
import pytest

import engine
from pipeline.motions.intensity import (
    ground_velocity,
    isolated_period,
    peak_ground_velocity,
    sdof_displacement,
    spectral_displacement,
)


def test_velocity_of_a_linear_acceleration_is_exact():
    """The trapezoidal rule integrates a piecewise-linear acceleration exactly: a = 2 + 3 t
    gives v = 2 t + 1.5 t^2."""
    dt = 0.01
    t = np.arange(501) * dt
    v = ground_velocity(2.0 + 3.0 * t, dt)
    assert v.shape == t.shape and v[0] == 0.0
    np.testing.assert_allclose(v, 2.0 * t + 1.5 * t**2, rtol=1e-12, atol=1e-12)
    assert peak_ground_velocity(2.0 + 3.0 * t, dt) == pytest.approx(2.0 * 5 + 1.5 * 25,
                                                                    rel=1e-12)


def test_pgv_of_a_sine_pulse():
    """One cycle a = A sin(2 pi t / Tp): v = A Tp / (2 pi) (1 - cos(2 pi t / Tp)), largest at
    Tp / 2: PGV = A Tp / pi (here 3 m/s^2, 0.5 s: 0.4775 m/s)."""
    amplitude, pulse, n = 3.0, 0.5, 1000
    dt = pulse / n
    t = np.arange(n + 1) * dt
    accel = amplitude * np.sin(2 * np.pi * t / pulse)
    # the trapezoidal rule's error on a sine: (w dt)^2 / 12 = 3.3e-6 of it at 1000 samples
    assert peak_ground_velocity(accel, dt) == pytest.approx(amplitude * pulse / np.pi, rel=1e-5)
    assert amplitude * pulse / np.pi == pytest.approx(0.477465, rel=1e-6)
    # the sign does not matter: a pulse downwards has the same PGV
    assert peak_ground_velocity(-accel, dt) == peak_ground_velocity(accel, dt)


def test_undamped_oscillator_under_a_step():
    """u'' + w^2 u = -a0 from rest: u = -(a0 / w^2)(1 - cos w t), peak 2 a0 / w^2 at T / 2."""
    a0, period = 2.0, 1.0
    w = 2 * np.pi / period
    dt = period / 1000  # T / 2 is a sample
    t = np.arange(3001) * dt
    accel = np.full(t.size, a0)
    u = sdof_displacement(accel, dt, period, damping=0.0)
    np.testing.assert_allclose(u, -(a0 / w**2) * (1 - np.cos(w * t)), rtol=0,
                               atol=1e-9 * a0 / w**2)
    assert spectral_displacement(accel, dt, period, damping=0.0) == pytest.approx(
        2 * a0 / w**2, rel=1e-9)


def test_damped_oscillator_under_a_step():
    """With damping zeta the first peak under a step is (a0 / w^2)(1 + exp(-zeta pi /
    sqrt(1 - zeta^2))): the overshoot of a damped oscillator; 5% damping, T = 2 s."""
    a0, period, zeta = 1.5, 2.0, 0.05
    w = 2 * np.pi / period
    dt = 1e-3
    accel = np.full(int(20 / dt), a0)
    expected = a0 / w**2 * (1 + np.exp(-zeta * np.pi / np.sqrt(1 - zeta**2)))
    assert spectral_displacement(accel, dt, period, zeta) == pytest.approx(expected, rel=1e-5)
    assert spectral_displacement(accel, dt, period) == spectral_displacement(accel, dt, period,
                                                                             0.05)


def test_oscillator_is_exact_for_a_ramp():
    """Linear between samples is taken as exact: a = b t, undamped, gives
    u = -(b / w^2)(t - sin(w t) / w) at every sample, even with coarse samples."""
    b, period = 4.0, 0.7
    w = 2 * np.pi / period
    dt = 0.05  # 14 samples per period
    t = np.arange(200) * dt
    u = sdof_displacement(b * t, dt, period, damping=0.0)
    np.testing.assert_allclose(u, -(b / w**2) * (t - np.sin(w * t) / w), rtol=0,
                               atol=1e-9 * b / w**2 * t[-1])


def test_isolated_period_of_the_paper_building():
    """The paper's building (Fig. 7c): M = 4 x 320 t + 250 t = 1530 t, k1 = 200 MN/m,
    k2 = 25 MN/m, Fy = 0.1 M g, so u_y = 0.1 x 1530e3 x 9.81 / 200e6 = 7.50465 mm. At D = 0.30 m
    the secant stiffness is (200e6 x 0.00750465 + 25e6 x 0.29249535) / 0.30 = 29.3777125 MN/m
    and T = 2 pi sqrt(1530e3 / 29.3777125e6) = 1.4339 s."""
    secant = (200e6 * 0.00750465 + 25e6 * (0.30 - 0.00750465)) / 0.30
    assert secant == pytest.approx(29.3777125e6, rel=1e-12)
    by_hand = 2 * np.pi * np.sqrt(1530e3 / secant)
    assert isolated_period(0.30) == pytest.approx(by_hand, rel=1e-12)
    assert isolated_period(0.30) == pytest.approx(1.4339, abs=1e-4)
    # below yield the isolator is linear at k1: the period of M on k1, whatever D
    elastic = 2 * np.pi * np.sqrt(1530e3 / 200e6)
    np.testing.assert_allclose(isolated_period(np.array([0.001, 0.005])), elastic, rtol=1e-12)
    # arrays keep their shape; a softer second branch lengthens the period
    periods = isolated_period(np.array([[0.1, 0.2], [0.3, 0.4]]))
    assert periods.shape == (2, 2) and np.all(np.diff(periods.ravel()) > 0)
    softer = engine.Building(k2=15e6)
    assert isolated_period(0.30, softer) > isolated_period(0.30)
