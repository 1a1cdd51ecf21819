"""studies.plan --quick: record pairs in plan against the planar model; the archive, its
summary of plan / planar, the verdict, and each number against a direct engine run."""
import json

import numpy as np
import pytest

import engine
from pipeline.records import load_pair, pair_accel
from studies import plan
from tests.helpers import assert_udunits, run_recipe


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    return run_recipe(plan, ["--quick"], tmp_path_factory.mktemp("plan"))


def test_archive(quick):
    ds = quick
    assert ds.peak_isolator_disp.dims == ("record", "angle", "model", "barrier")
    assert list(ds.angle.values) == [0.0, 90.0] and ds.sizes["record"] == 3
    assert ds.orbit.dims == ("orbit_record", "time", "direction")
    assert ds.attrs["moat"] == "rectangular" and ds.attrs["quick"] == 1
    assert_udunits(ds)
    summary = json.loads(ds.attrs["plan_vs_planar"])
    assert summary["isolator displacement (no wall)"]["points"] == 6
    (verdict,) = json.loads(ds.attrs["paper_verdicts"])
    assert verdict["conclusion"] == "4, 5.1" and verdict["verdict"] in ("agrees", "differs")


def test_numbers_are_the_engines(quick):
    """The first pair at 90 degrees: the planar model under the component along 90 degrees
    (-y), the model in plan under the rotated pair, at the gap 0.9 x the planar peak."""
    ds = quick.isel(record=0).sel(angle=90.0)
    x, y = load_pair(str(ds.record.values))
    accel, dt = pair_accel(x, y)
    along = np.cos(np.pi / 2) * accel[:, 0] - np.sin(np.pi / 2) * accel[:, 1]
    free = engine.simulate(along, dt, engine.Contact.none(1))
    gap = 0.9 * free.peak_isolator_disp[0]
    assert float(ds.gap) == gap
    walls = engine.Contact.concat([engine.Contact.none(1), plan.bare(gap), plan.bumpers(gap)])
    planar = engine.simulate(along, dt, walls)
    inplan = engine.simulate(accel, dt, walls, moat="rectangular", angle=90.0)
    for model, result in (("planar", planar), ("plan", inplan)):
        got = ds.sel(model=model)
        fit = plan.fits(gap)
        for name, value in (("peak_isolator_disp", result.peak_isolator_disp),
                            ("max_impact_force", result.max_impact_force)):
            expected = value.copy()
            if not fit:
                expected[2] = np.nan
            np.testing.assert_array_equal(got[name].values, expected, err_msg=name)
