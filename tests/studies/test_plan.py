"""studies.plan --quick: record pairs in plan against the planar model over the gap; the
archive, its summary of plan / planar, and each number against a direct engine run. (The
verdicts counted on a hand-made dataset: tests/studies/plan/test_verdicts.py.)"""
import json

import numpy as np
import pytest

import engine
from pipeline.records import load_pair, pair_accel
from studies import plan
from tests.helpers import assert_on_variables_page, assert_udunits, run_recipe

CONCLUSIONS = ["4, 5.1", "5.1", "5.1", "5.1", "6", "6"]


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    return run_recipe(plan, ["--quick"], tmp_path_factory.mktemp("plan"))


def test_archive(quick):
    ds = quick
    dims = ("record", "angle", "gap_fraction", "model", "barrier")
    for name in plan.PEAK_NAMES:
        assert ds[name].dims == dims, name
    assert ds.gap.dims == ds.bumpers_fit.dims == dims[:3]
    assert ds.angle_gain.dims == ("record", "model")
    assert list(ds.angle.values) == [0.0, 90.0] and ds.sizes["record"] == 3
    assert list(ds.gap_fraction.values) == [0.7, 0.9]
    np.testing.assert_array_equal(ds.gap.sel(gap_fraction=0.7) / 0.7,
                                  ds.gap.sel(gap_fraction=0.9) / 0.9)
    assert ds.orbit.dims == ("orbit_record", "time", "direction")
    assert ds.attrs["moat"] == "rectangular" and ds.attrs["quick"] == 1
    assert_udunits(ds)
    assert_on_variables_page(ds, "plan.nc")
    assert all(var.attrs.get("long_name") for var in ds.variables.values())
    # One free run serves every gap: the same numbers at each fraction.
    free = ds.peak_isolator_disp.sel(barrier="none")
    np.testing.assert_array_equal(free.sel(gap_fraction=0.7), free.sel(gap_fraction=0.9))
    summary = json.loads(ds.attrs["plan_vs_planar"])
    assert summary["isolator displacement (no wall)"]["points"] == 6
    for key in plan.GAIN_KEYS.values():
        assert summary[key]["points"] == 3
    found = json.loads(ds.attrs["paper_verdicts"])
    assert [v["conclusion"] for v in found] == CONCLUSIONS
    assert all(v["verdict"] in ("agrees", "differs", "not tested") for v in found)


def test_angle_gain(quick):
    """The largest peak without wall over the angles / the larger as-recorded component's
    planar peak: the quick angles are the as-recorded ones, so planar it is 1."""
    free = quick.peak_isolator_disp.sel(barrier="none", gap_fraction=0.9)
    larger = free.sel(model="planar").max("angle")
    np.testing.assert_array_equal(quick.angle_gain.sel(model="planar"), 1.0)
    np.testing.assert_allclose(quick.angle_gain.sel(model="plan"),
                               free.sel(model="plan").max("angle") / larger, rtol=1e-15)


@pytest.mark.parametrize("fraction", [0.7, 0.9])
def test_numbers_are_the_engines(quick, fraction):
    """The first pair at 90 degrees: the planar model under the component along 90 degrees
    (-y), the model in plan under the rotated pair, at the gap `fraction` x the planar peak."""
    ds = quick.isel(record=0).sel(angle=90.0, gap_fraction=fraction)
    x, y = load_pair(str(ds.record.values))
    accel, dt = pair_accel(x, y)
    along = np.cos(np.pi / 2) * accel[:, 0] - np.sin(np.pi / 2) * accel[:, 1]
    free = engine.simulate(along, dt, engine.Contact.none(1))
    gap = fraction * free.peak_isolator_disp[0]
    assert float(ds.gap) == gap
    walls = engine.Contact.concat([engine.Contact.none(1), plan.bare(gap), plan.bumpers(gap)])
    planar = engine.simulate(along, dt, walls)
    inplan = engine.simulate(accel, dt, walls, moat="rectangular", angle=90.0)
    for model, result in (("planar", planar), ("plan", inplan)):
        got = ds.sel(model=model)
        peaks = {"peak_isolator_disp": result.peak_isolator_disp,
                 "peak_floor_accel": result.peak_total_accel.max(axis=1),
                 "peak_base_accel": result.peak_total_accel[:, 0],
                 "peak_interstory_drift": result.peak_interstory_drift.max(axis=1),
                 "max_impact_force": result.max_impact_force, "n_impacts": result.n_impacts}
        for name, value in peaks.items():
            expected = value.astype(float)
            if not plan.fits(gap):
                expected[2] = -1 if name == "n_impacts" else np.nan
            np.testing.assert_array_equal(got[name].values, expected, err_msg=name)
