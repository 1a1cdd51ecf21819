"""engine.units: the conversions between the paper's units and SI."""

import numpy as np
import pytest

from engine import units
from engine.impact.laws import rubber_bumper


def test_units_conversions():
    assert 15 * units.CM == pytest.approx(0.15, rel=1e-15)
    assert 4 * units.MM == pytest.approx(0.004, rel=1e-15)
    assert units.G == 9.81  # SPEC's value, not the standard 9.80665
    assert 2500 * units.KN_PER_MM == 2.5e9
    assert 320 * units.TONNE == 320e3
    assert 3 * units.KN == 3000.0
    # kN/mm^n: n = 1 is kN/mm, n = 0 is kN; one paper bumper is 0.089 kN/mm^2.65 (SPEC 2).
    assert units.kn_per_mm_n(1.0) == units.KN_PER_MM
    assert units.kn_per_mm_n(0.0) == units.KN
    np.testing.assert_allclose(units.kn_per_mm_n([1.5, 2.65]), [1e3 * 1e3**1.5, 1e3 * 1e3**2.65],
                               rtol=1e-15)
    one = rubber_bumper.impact_stiffness(rubber_bumper.PARAMETERS.area.default, 5 * units.CM)
    assert one / units.kn_per_mm_n(2.65) == pytest.approx(0.089, abs=5e-4)
    # The record layer converts g with the same G.
    from pipeline.records import G as records_g
    assert records_g == units.G
