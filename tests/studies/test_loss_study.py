"""studies.loss: the quick archive holds the repair cost and time per stripe and
configuration with their quantiles, the expected annual loss and the annual rates per
configuration, pelicun's version; its expected annual loss and annual rates recompute from its
own conditional values and hazard curve (FEMA P-58-1 chapter 8), and its collapse rate from
the collapse fragility."""
from __future__ import annotations

import numpy as np
import pytest

from tests.helpers import assert_udunits, run_recipe

pytest.importorskip("pelicun")


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    from studies import loss

    return run_recipe(loss, ["--quick"], tmp_path_factory.mktemp("loss"))


def test_the_archive_holds_the_decision(quick):
    ds = quick
    assert_udunits(ds)
    for name in ("repair_cost", "repair_time", "repair_cost_quantile", "repair_time_quantile",
                 "expected_annual_loss", "annual_rate_contact", "annual_rate_crushed",
                 "annual_rate_collapse", "collapse_probability", "median_repair_cost_mce",
                 "runs_used", "runs_outside_range"):
        assert name in ds, name
    assert ds.repair_cost.dims == ("level", "barrier", "gap_fraction")
    assert ds.attrs["pelicun_version"]
    # every run is counted once: used, collapsed or outside the model's range
    runs = ds.runs_used + ds.runs_collapsed + ds.runs_outside_range
    assert (runs == ds.record.size).all()
    # the quantiles are ordered and the median lies within them
    q = ds.repair_cost_quantile
    assert (q.diff("quantile").fillna(0) >= 0).all()
    # no bumpers: nothing crushed
    assert np.isnan(ds.annual_rate_crushed.sel(barrier=["no wall", "bare wall"])).all()
    assert (ds.annual_rate_contact.sel(barrier="no wall") == 0).all()


def test_annual_values_recompute_from_the_stripes_and_the_hazard(quick):
    from pipeline.assess import hazard

    ds = quick
    curve = hazard.Hazard(ds.hazard_sa.values, ds.hazard_rate.values, "archive")
    sa = ds.level_sa.values
    eal = hazard.mean_annual(sa, ds.repair_cost.values, curve)
    np.testing.assert_allclose(ds.expected_annual_loss.values, eal, rtol=1e-12)
    contact = hazard.mean_annual(sa, ds.contact_probability.values, curve)
    np.testing.assert_allclose(ds.annual_rate_contact.values, contact, rtol=1e-12)
    s_mt = sa[list(ds.level.values).index(1.0)]
    rate = hazard.lognormal_annual(ds.acmr.values * s_mt, ds.beta_total.values, curve)
    np.testing.assert_allclose(ds.annual_rate_collapse.values, rate, rtol=1e-12)
