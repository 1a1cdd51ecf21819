"""pipeline.assess.hazard: the default curve against its form and its fit, the time-based
integration against closed forms (a power law, the second-order form), and a hazard table read
or refused."""
from __future__ import annotations

import math

import numpy as np
import pytest

from engine.units import G
from pipeline.assess import hazard


def test_the_default_curve_is_the_second_order_form_through_the_mce_r_rate():
    s_mt = 0.8 * G
    curve = hazard.default(s_mt)
    assert curve.rate_at(s_mt) == pytest.approx(hazard.MCE_R_RATE, rel=1e-12)
    # ln(lambda / lambda_MCE) = -k1 x - k2 x^2 between the table's points too
    x = np.linspace(math.log(0.1), math.log(50.0), 777)
    exact = hazard.MCE_R_RATE * np.exp(-hazard.SLOPE * x - hazard.CURVATURE * x * x)
    assert curve.rate_at(s_mt * np.exp(x)) == pytest.approx(exact, rel=1e-4)
    # its local slope k1 + 2 k2 x: 3.2 at twice S_MT, 1.3 at a fifth (it flattens below)
    slope = lambda r: -math.log(curve.rate_at(r * 1.001 * s_mt) / curve.rate_at(r * s_mt)) \
        / math.log(1.001)  # noqa: E731
    assert slope(2.0) == pytest.approx(3.16, abs=0.01)
    assert slope(0.2) == pytest.approx(1.26, abs=0.01)
    # flat below its vertex, where the quadratic turns: under 1% more per halving of Sa
    vertex = s_mt * math.exp(-hazard.SLOPE / (2 * hazard.CURVATURE))
    assert vertex == pytest.approx(0.0435 * s_mt, rel=1e-2)
    assert 1.0 < curve.rate_at(vertex / 2) / curve.rate_at(vertex) < 1.01


def test_the_default_shape_is_the_fit_to_the_peer_hazard():
    # refitted without the module's helper: the normal equations of the anchored quadratic
    sa = np.array(hazard.PEER_SA_G)
    x = np.log(sa / 0.50)  # the peer's 2475-year intensity
    y = np.log(2475.0 / np.array(hazard.PEER_RETURN_PERIODS))
    a = np.array([[np.sum(x * x), np.sum(x ** 3)], [np.sum(x ** 3), np.sum(x ** 4)]])
    k1, k2 = np.linalg.solve(a, -np.array([np.sum(x * y), np.sum(x * x * y)]))
    assert (hazard.SLOPE, hazard.CURVATURE) == pytest.approx((k1, k2), rel=1e-9)
    assert (k1, k2) == pytest.approx((2.59, 0.413), abs=0.005)
    # the fit stays within a third (in rate) of every point of the peer's curve
    fit = -k1 * x - k2 * x * x
    assert np.abs(fit - y).max() < 0.29


def test_a_power_law_is_the_form_without_curvature():
    curve = hazard.second_order(0.8 * G, 3.0, 0.0)
    assert curve.rate_at(0.8 * G) == pytest.approx(hazard.MCE_R_RATE, rel=1e-12)
    for sa in (0.1 * G, 2.0 * G, 500.0 * G):  # beyond the table's points too
        assert curve.rate_at(2 * sa) / curve.rate_at(sa) == pytest.approx(2 ** -3.0, rel=1e-9)
    with pytest.raises(ValueError, match="slope must be positive"):
        hazard.second_order(G, -1.0, 0.4)


def test_interval_rates_add_up_to_the_rate_at_the_lowest_edge():
    curve = hazard.default(G)
    sa = np.array([0.2, 0.4, 2 / 3, 1.0, 1.5]) * G
    w = hazard.interval_rates(sa, curve)
    lowest = sa[0] ** 2 / math.sqrt(sa[0] * sa[1])
    assert w.sum() == pytest.approx(float(curve.rate_at(lowest)), rel=1e-12)
    # the top interval is open: its rate is the rate above its lower edge
    assert w[-1] == pytest.approx(float(curve.rate_at(math.sqrt(sa[-1] * sa[-2]))), rel=1e-12)
    # a certain event at every stripe happens at that total rate; the mean is linear
    assert hazard.mean_annual(sa, np.ones(5), curve) == pytest.approx(w.sum(), rel=1e-12)
    x = np.stack([np.arange(5.0), 2 * np.arange(5.0)], axis=1)
    assert hazard.mean_annual(sa, x, curve) == pytest.approx([w @ x[:, 0], 2 * w @ x[:, 0]])


def test_a_lognormal_fragility_over_a_power_law_is_the_closed_form():
    # lambda_c = lambda(median) exp(k^2 beta^2 / 2) (Cornell et al. 2002)
    curve = hazard.second_order(0.9 * G, 3.0, 0.0)
    for median, beta in ((1.5 * G, 0.5), (3.0 * G, 0.3)):
        exact = float(curve.rate_at(median)) * math.exp((3.0 * beta) ** 2 / 2)
        assert hazard.lognormal_annual(median, beta, curve) == pytest.approx(exact, rel=1e-4)


def test_a_lognormal_fragility_over_the_second_order_form_is_its_closed_form():
    # Vamvatsikos 2013: lambda_c = sqrt(p) k0^(1-p) lambda(median)^p exp(k1^2 beta^2 p / 2),
    # p = 1 / (1 + 2 k2 beta^2), with lambda(s) = k0 exp(-k2 ln^2 s - k1 ln s) in s / S_MT
    curve = hazard.default(0.9 * G)
    k0, k1, k2 = hazard.MCE_R_RATE, hazard.SLOPE, hazard.CURVATURE
    for median, beta in ((1.8, 0.5), (2.5, 0.35)):
        p = 1.0 / (1.0 + 2.0 * k2 * beta ** 2)
        at_median = k0 * math.exp(-k2 * math.log(median) ** 2 - k1 * math.log(median))
        exact = math.sqrt(p) * k0 ** (1 - p) * at_median ** p * math.exp(p * (k1 * beta) ** 2
                                                                          / 2)
        assert hazard.lognormal_annual(median * 0.9 * G, beta, curve) == pytest.approx(
            exact, rel=1e-3)


def test_a_hazard_table_is_read_and_a_bad_one_refused_in_one_line(tmp_path):
    good = tmp_path / "site.csv"
    good.write_text("sa_g,annual_rate\n1.0,0.0004\n0.1,0.1\n0.5,0.002\n")
    curve = hazard.from_table(good)
    assert curve.sa.tolist() == pytest.approx([0.1 * G, 0.5 * G, 1.0 * G])
    assert curve.rate_at(0.5 * G) == pytest.approx(0.002)
    bad = tmp_path / "bad.csv"
    bad.write_text("sa_g,annual_rate\n0.1,0.001\n0.5,0.002\n")
    with pytest.raises(ValueError, match="rates must decrease"):
        hazard.from_table(bad)
    (tmp_path / "cols.csv").write_text("sa,rate\n0.1,0.1\n")
    with pytest.raises(ValueError, match="needs the columns sa_g and annual_rate"):
        hazard.from_table(tmp_path / "cols.csv")
