"""pipeline.assess.hazard: the time-based integration against closed forms of a power-law
hazard, and a hazard table read or refused."""
from __future__ import annotations

import math

import numpy as np
import pytest

from engine.units import G
from pipeline.assess import hazard


def test_the_default_curve_passes_the_mce_r_rate_with_its_slope():
    curve = hazard.default(0.8 * G)
    assert curve.rate_at(0.8 * G) == pytest.approx(hazard.MCE_R_RATE, rel=1e-12)
    # a power law: doubling Sa divides the rate by 2^k, beyond the table's points too
    for sa in (0.1 * G, 2.0 * G, 500.0 * G):
        assert curve.rate_at(2 * sa) / curve.rate_at(sa) == pytest.approx(2 ** -hazard.SLOPE,
                                                                          rel=1e-9)


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
    curve = hazard.default(0.9 * G)
    for median, beta in ((1.5 * G, 0.5), (3.0 * G, 0.3)):
        exact = float(curve.rate_at(median)) * math.exp((hazard.SLOPE * beta) ** 2 / 2)
        assert hazard.lognormal_annual(median, beta, curve) == pytest.approx(exact, rel=1e-4)


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
