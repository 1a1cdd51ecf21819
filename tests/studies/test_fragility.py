"""studies.fragility --quick: code-scaled pairs at intensity levels in plan, the events, the
fragility fits and the validity flags, each checked against what it is made of: the engine's
run of a member, the events recomputed from the stored peaks, the fit recomputed from the
stored events (pipeline.assess.fragility), the scaling recomputed (pipeline.motions.code_suite)."""
import json

import numpy as np
import pytest

import engine
from engine.units import G
from pipeline.assess.fragility_outcomes import fit_outcomes
from pipeline.assess.validity import RUBBER_STRESS_LIMIT
from pipeline.checks import resolve_pairs
from pipeline.motions.code_suite import code_suite
from studies import fragility
from tests.helpers import (
    assert_collapse_modes,
    assert_on_variables_page,
    assert_udunits,
    run_recipe,
)


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    return run_recipe(fragility, ["--quick"], tmp_path_factory.mktemp("fragility"))


def test_archive(quick):
    ds = quick
    assert ds.event_contact.dims == ("record", "level", "gap_fraction", "barrier")
    assert ds.fragility_median.dims == ("event", "gap_fraction", "barrier")
    assert list(ds.level.values) == list(fragility.QUICK_LEVELS) and ds.sizes["record"] == 4
    assert ds.gap_fraction.values[-1] == pytest.approx(ds.attrs["D_TM"] / ds.attrs["D_M"])
    assert ds.attrs["scaling_rule"] == "asce7" and ds.attrs["quick"] == 1
    # the bound run (lower by default), its T_M, D_M, D_TM, the others and the dashpot beside
    assert ds.attrs["isolator_bound"] == "lower"
    for name in ("T_M", "D_M", "D_TM"):
        assert ds.attrs[name] == ds.attrs[f"{name}_lower"]
    assert ds.attrs["D_M_lower"] > ds.attrs["D_M_nominal"] > ds.attrs["D_M_upper"]
    assert ds.attrs["D_M_with_dashpot"] < ds.attrs["D_M"]
    assert_udunits(ds)
    assert_on_variables_page(ds, "fragility.nc")
    # one verdict per floor acceleration threshold, each naming its threshold
    verdicts = json.loads(ds.attrs["paper_verdicts"])
    accel = [e for e in json.loads(ds.attrs["thresholds"]) if e.startswith("floor_accel_")]
    assert [v["numbers"]["event"] for v in verdicts] == accel
    for v in verdicts:
        assert v["verdict"] in ("agrees", "differs", "not tested")
        assert f"above {v['numbers']['threshold'] / G:g} g" in v["claim"]


def test_scaling_and_one_member_are_the_engines(quick):
    ds = quick
    pairs, names = resolve_pairs(list(ds.record.values))
    # the default bound (lower), on the superstructure the code designs (--stories imk)
    suite = code_suite(pairs, names, engine.Building()).with_superstructure("imk")
    np.testing.assert_allclose(ds.scale_factor.values, suite.factors, rtol=1e-12)
    r, level, g = 1, 1.0, 0
    gap = float(ds.gap.isel(gap_fraction=g))
    assert ds.gap.values[-1] == suite.design.d_tm  # the lower bound's D_TM
    run = engine.simulate(pairs[r].accel, pairs[r].dt,
                          engine.Contact.bumper([gap], thickness=0.05, n_bumpers=4),
                          suite.building, scale=suite.factors[r] * level, moat="rectangular")
    got = ds.isel(record=r, gap_fraction=g).sel(level=level, barrier="4 bumpers")
    assert float(got.peak_isolator_disp) == run.peak_isolator_disp[0]
    assert float(got.max_impact_force) == run.max_impact_force[0]
    assert float(got.peak_floor_accel) == run.peak_total_accel[0].max()


def test_events_and_fits_follow_from_the_stored_numbers(quick):
    ds = quick
    np.testing.assert_array_equal(ds.event_contact.values, ds.n_impacts.values > 0)
    thresholds = json.loads(ds.attrs["thresholds"])
    assert thresholds["floor_accel_lights"]["component"] == "C.30.34.001"
    for event, t in thresholds.items():
        if event.startswith("floor_accel_"):
            np.testing.assert_array_equal(ds[f"event_{event}"].values,
                                          ds.peak_floor_accel.values > t["value"])
    crushed = ds.event_bumpers_crushed
    assert not crushed.sel(barrier="bare wall").any()
    np.testing.assert_array_equal(crushed.sel(barrier="4 bumpers").values,
                                  ds.max_indentation.sel(barrier="4 bumpers").values
                                  > 0.8 * 0.05)  # beyond the crush limit, strictly
    for event in ds.event.values:
        for barrier in ds.barrier.values:
            seen = ds[f"event_{event}"].sel(barrier=barrier).isel(gap_fraction=0).values
            fit = fit_outcomes(ds.level.values, seen, ds.record_weight.values)
            stored = ds.sel(event=event, barrier=barrier).isel(gap_fraction=0)
            np.testing.assert_equal(float(stored.fragility_median), fit.theta)
            assert str(stored.fragility_status.values) == fit.status
    # beta_TOT: the fitted beta with the default ratings' (B B B) uncertainties; the
    # bootstrap intervals ordered where the fit is identified
    np.testing.assert_allclose(ds.fragility_beta_total,
                               np.sqrt(ds.fragility_beta ** 2 + 3 * 0.2 ** 2), rtol=1e-12)
    interval = ds.fragility_median_interval
    known = np.isfinite(interval.isel(bound=0))
    assert (interval.isel(bound=0) <= interval.isel(bound=1)).values[known.values].all()
    assert (ds.fragility_identifiable == 1).values[known.values].all()
    # the stronger the shaking, the likelier every event (stripes nest: a record's peaks grow
    # with the level here)
    share = ds.event_contact.mean("record")
    assert (share.diff("level") >= 0).all()


def test_validity_is_flagged_and_counted(quick):
    ds = quick
    counts = json.loads(ds.attrs["invalid_counts"])
    for name, count in counts.items():
        assert int(ds[name].sum()) == count
    np.testing.assert_array_equal(ds.invalid_floor_accel.values,
                                  ds.peak_floor_accel.values > 5 * G)
    for barrier, n in (("4 bumpers", 4), ("32 bumpers", 32)):
        stress = ds.bumper_stress.sel(barrier=barrier)
        np.testing.assert_allclose(stress, ds.max_impact_force.sel(barrier=barrier)
                                   / (n * 0.15 ** 2), rtol=1e-12)
        np.testing.assert_array_equal(ds.invalid_bumper_stress.sel(barrier=barrier).values,
                                      stress.values > RUBBER_STRESS_LIMIT)
    assert not ds.invalid_bumper_stress.sel(barrier="bare wall").any()
    assert ds.bumper_stress.sel(barrier="bare wall").isnull().all()
    assert "outside the model's range" in ds.attrs["paper_check"]


def test_how_each_run_ended_is_stored_and_counted_by_mode(quick):
    """collapse_mode beside the collapse flag and event, counted by mode in collapse_modes;
    a verdict names the modes of the collapses it counts (here on made-up counts: the quick
    run does not collapse)."""
    ds = quick
    assert ds.collapse_mode.dims == ds.invalid_collapse.dims
    assert_collapse_modes(ds.collapse_mode, ds.invalid_collapse.values)
    assert_collapse_modes(ds.collapse_mode, ds.event_collapse.values)
    modes = json.loads(ds.attrs["collapse_modes"])
    assert modes["collapsed"] == json.loads(ds.attrs["invalid_counts"])["invalid_collapse"]
    made = ds.copy()
    made.attrs["invalid_counts"] = json.dumps({"invalid_floor_accel": 2, "invalid_collapse": 3})
    made.attrs["collapse_modes"] = json.dumps({"collapsed": 3, "story_drift": 2,
                                               "isolator_capacity": 0,
                                               "numerical_instability": 1})
    verdict = fragility.check(made)[0]
    assert (f"runs outside the model's range (of {ds.attrs['runs']}): floor_accel 2, 3 "
            "collapsed (2 story drift, 0 isolator capacity, 1 numerical instability)") \
        in verdict.finding
    assert verdict.numbers["collapse_modes"]["numerical_instability"] == 1
