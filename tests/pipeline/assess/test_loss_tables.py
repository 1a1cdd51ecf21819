"""pipeline.assess.loss_tables: the tables pelicun reads beside FEMA P-58's database hold the
numbers they are given, in pelicun's columns."""
from __future__ import annotations

import pytest

from pipeline.assess import loss_tables


def test_the_irreparable_drift_fragility_is_the_given_lognormal():
    table = loss_tables.fragilities(0.01, 0.3)
    row = table.loc["excessiveRID"]
    assert row[("Demand", "Type")] == "Residual Interstory Drift Ratio"
    assert row[("LS1", "Family")] == "lognormal"
    assert (row[("LS1", "Theta_0")], row[("LS1", "Theta_1")]) == (0.01, 0.3)
    # the placeholder a realization's irreparable damage state is carried by: never by demand
    assert table.loc["irreparable", ("LS1", "Theta_0")] >= 1e10


def test_the_replacement_costs_the_building_without_dispersion():
    table = loss_tables.replacement(2.7e7, 36000.0)
    assert table.loc[("replacement", "Cost"), ("DS1", "Theta_0")] == pytest.approx(2.7e7)
    assert table.loc[("replacement", "Time"), ("DS1", "Theta_0")] == pytest.approx(36000.0)
    assert table.loc[("replacement", "Cost"), ("DV", "Unit")] == "USD_2011"
