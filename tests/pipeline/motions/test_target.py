"""pipeline.motions.target: the ASCE 7 spectrum at hand-computed points and against the asce7-16
package, a user's table checked, the damping coefficients B_M, and the code's D_M of the
paper's building by a hand iteration, with a friction pendulum and the dashpot."""
from __future__ import annotations

import math

import numpy as np
import pytest

import engine
from engine.units import G
from pipeline.motions import target as tg
from pipeline.motions.intensity import isolated_period

S_MS, S_M1, T_L = 1.5, 0.9, 8.0  # g, g, s: a high-seismicity site (T_S = 0.6 s, T_0 = 0.12 s)

# --- target spectra -------------------------------------------------------------------------

def test_asce7_spectrum_at_hand_points():
    """S_MS = 1.5 g, S_M1 = 0.9 g, T_L = 8 s: T_S = 0.6 s, T_0 = 0.12 s. By hand: 0.4 S_MS =
    0.6 g at T = 0; 1.05 g at T_0 / 2; S_MS at T_0 and T_S; S_M1 / T = 0.9 g at 1 s and 0.1125 g
    at T_L; S_M1 T_L / T^2 = 0.072 g at 10 s."""
    periods = [0.0, 0.06, 0.12, 0.6, 1.0, 8.0, 10.0]
    hand_g = [0.6, 1.05, 1.5, 1.5, 0.9, 0.1125, 0.072]
    np.testing.assert_allclose(tg.asce7_sa(periods, S_MS, S_M1, T_L), np.array(hand_g) * G,
                               rtol=1e-14)
    spectrum = tg.asce7_target(S_MS, S_M1, T_L)
    assert spectrum.level == "MCE_R" and "11.4.5.2" in spectrum.source
    # The table holds the corners, and log-log interpolation is exact on the 1/T, 1/T^2
    # branches and the plateau; on the rising line it is close.
    np.testing.assert_allclose(spectrum.at(periods[2:]), np.array(hand_g[2:]) * G, rtol=1e-12)
    assert spectrum.at(1.2345) == pytest.approx(0.9 / 1.2345 * G, rel=1e-12)
    assert spectrum.at(13.0) == pytest.approx(0.9 * 8 / 13.0**2 * G, rel=1e-12)
    assert spectrum.at(0.06) == pytest.approx(1.05 * G, rel=1e-3)


def test_design_spectrum_is_two_thirds_and_matches_asce7_16_package():
    """Design parameters are 2/3 of MCE_R (section 11.4.4); the design spectrum agrees with
    the independent asce7_16 package's design_response_spectrum (in g)."""
    s_ds, s_d1 = tg.design_parameters(S_MS, S_M1)
    assert (s_ds, s_d1) == pytest.approx((1.0, 0.6), rel=1e-15)
    design = tg.asce7_target(s_ds, s_d1, T_L, level="design")
    mce = tg.asce7_target(S_MS, S_M1, T_L)
    np.testing.assert_allclose(design.sa, mce.at(design.periods) * 2 / 3, rtol=1e-12)
    seismic = pytest.importorskip("asce7_16.seismic")
    periods = np.geomspace(0.01, 15, 97)
    theirs = seismic.design_response_spectrum(s_ds, s_d1, T_L)(periods)
    np.testing.assert_allclose(tg.asce7_sa(periods, s_ds, s_d1, T_L) / G, theirs, rtol=1e-12)


def test_user_table_checks():
    table = tg.TargetSpectrum.from_table([0.1, 1.0, 4.0], [1.0, 0.5, 0.1])
    assert table.level == "user"
    np.testing.assert_allclose(table.sa_g, [1.0, 0.5, 0.1])
    assert table.at(2.0) == pytest.approx(0.5 * (0.1 / 0.5) ** (np.log(2) / np.log(4)) * G)
    with pytest.raises(ValueError, match="strictly increasing: 1 s is followed by 0.5 s"):
        tg.TargetSpectrum.from_table([0.1, 1.0, 0.5], [1, 1, 1])
    with pytest.raises(ValueError, match="finite and > 0, got -0.2 g at 1 s"):
        tg.TargetSpectrum.from_table([0.1, 1.0], [1.0, -0.2])
    with pytest.raises(ValueError, match="one value per period"):
        tg.TargetSpectrum.from_table([0.1, 1.0], [1.0, 0.5, 0.2])
    with pytest.raises(ValueError, match="periods must be finite and > 0"):
        tg.TargetSpectrum.from_table([0.0, 1.0], [1.0, 0.5])
    with pytest.raises(ValueError, match="defined for 0.1 to 4 s only"):
        table.at(5.0)
    with pytest.raises(ValueError, match="level"):
        tg.TargetSpectrum.from_table([0.1, 1.0], [1.0, 0.5], level="MCE")
    assert table.component == "RotD100"  # as ASCE 7-22's spectra; another said so
    with pytest.raises(ValueError, match="component must be one of"):
        tg.TargetSpectrum.from_table([0.1, 1.0], [1.0, 0.5], component="maximum")


def test_damping_coefficient_table():
    """Table 17.5-1 at its entries, linear between them, constant beyond 2% and 50%."""
    for beta, b in tg.BM_TABLE:
        assert tg.damping_coefficient(beta) == pytest.approx(b, rel=1e-15)
    assert tg.damping_coefficient(0.15) == pytest.approx(1.35)
    assert tg.damping_coefficient(0.035) == pytest.approx(0.9)
    np.testing.assert_allclose(tg.damping_coefficient([0.0, 0.01, 0.6]), [0.8, 0.8, 2.0])


def test_paper_building_d_m_by_hand_iteration():
    """The paper's building (M = 1530 t, K1 = 200 MN/m, K2 = 25 MN/m, Fy = 0.1 W) at
    S_M1 = 0.9 g: the plain fixed point D <- g S_M1 T(D) / (4 pi^2 B(D)), written out here,
    converges to the module's D_M; T_M is intensity.isolated_period(D_M); D_TM = 1.15 D_M."""
    mass, k1, k2 = 1530e3, 200e6, 25e6
    d_y = 0.1 * mass * G / k1
    q_d = (k1 - k2) * d_y
    betas, coefficients = zip(*tg.BM_TABLE, strict=True)
    d = 0.3
    for _ in range(500):
        k = (k1 * d_y + k2 * (d - d_y)) / d
        t = 2 * math.pi * math.sqrt(mass / k)
        beta = 4 * q_d * (d - d_y) / (2 * math.pi * k * d * d)
        d_new = G * 0.9 * t / (4 * math.pi**2 * float(np.interp(beta, betas, coefficients)))
        if abs(d_new - d) < 1e-15:
            break
        d = d_new
    design = tg.isolation_design(0.9)
    assert design.d_m == pytest.approx(d, rel=1e-10)
    assert design.d_m == pytest.approx(0.2623, abs=1e-4)  # the value, for the record
    assert design.t_m == pytest.approx(isolated_period(design.d_m), rel=1e-12)
    assert design.k_m == pytest.approx((k1 * d_y + k2 * (d - d_y)) / d, rel=1e-9)
    assert design.d_tm == pytest.approx(1.15 * design.d_m, rel=1e-15)
    assert design.law == "bilinear" and not design.dashpot


def test_friction_pendulum_and_dashpot():
    """A friction pendulum (E = 4 mu W D) satisfies the code's equation at its D_M; counting
    the paper's isolation dashpot adds c w_M / (2 k_M) of damping and lowers D_M; modal
    damping has no dashpot to count."""
    building = engine.Building(isolator=engine.Isolator.friction_pendulum(
        radius=2.5, mu_slow=0.04, mu_fast=0.07, rate=30.0))
    design = tg.isolation_design(0.6, building)
    weight = building.total_mass * building.g
    k = weight / 2.5 + 0.07 * weight / design.d_m
    beta = 4 * 0.07 * weight * design.d_m / (2 * math.pi * k * design.d_m**2)
    assert design.beta_m == pytest.approx(beta, rel=1e-12)
    assert design.d_m == pytest.approx(
        G * 0.6 * design.t_m / (4 * math.pi**2 * tg.damping_coefficient(beta)), rel=1e-10)
    plain, damped = tg.isolation_design(0.9), tg.isolation_design(0.9, dashpot=True)
    assert damped.beta_m > plain.beta_m and damped.d_m < plain.d_m
    with pytest.raises(ValueError, match="dashpot"):
        tg.isolation_design(0.9, engine.Building(damping="modal"), dashpot=True)
