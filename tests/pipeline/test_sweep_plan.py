"""Sweeps in plan: record pairs, the incidence angle as a dimension, the per-direction and
per-wall peaks labelled; every member equals the engine's run of its pair at its angle."""
import warnings

import numpy as np
import pytest

import engine
import pipeline
from pipeline.errors import SweepError
from pipeline.records import load_pair, pair_accel
from tests.helpers import assert_udunits

PAIRS = ["RSN953", "pacoima"]  # a FEMA P695 pair; the paper's Pacoima Dam with its 254
GAPS = [0.15, 0.30]  # m
ANGLES = [0.0, 45.0, 90.0]  # degrees


@pytest.fixture(scope="module")
def plan_sweep(tmp_path_factory):
    out = tmp_path_factory.mktemp("plan") / "plan.nc"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pipeline.sweep(PAIRS, gap=GAPS, angle=ANGLES, moat="rectangular",
                              baseline=True, unconstrained=True, quiet=True, out=out)


def test_every_member_is_the_engine_run_of_its_pair_at_its_angle(plan_sweep):
    ds = plan_sweep
    for name in PAIRS:
        acc, dt = pair_accel(*load_pair(name))
        bumpers = engine.Contact.bumper(np.repeat(GAPS, len(ANGLES)))
        angles = np.tile(ANGLES, len(GAPS))
        alone = engine.simulate(acc, dt, bumpers, moat="rectangular", angle=angles)
        bare = engine.simulate(acc, dt, engine.Contact.linear(np.repeat(GAPS, len(ANGLES))),
                               moat="rectangular", angle=angles)
        for result, prefix in ((alone, ""), (bare, "baseline_")):
            for peak, value in {**result.peaks(), **result.plan_peaks()}.items():
                got = ds[prefix + peak].sel(record=name).transpose("gap", "angle", ...)
                np.testing.assert_array_equal(got.values.reshape(value.shape), value,
                                              err_msg=prefix + peak)
    assert (ds.n_impacts.sel(gap=0.15) > 0).all()


def test_labels_units_and_conventions(plan_sweep):
    ds = plan_sweep
    assert ds.peak_isolator_disp.dims == ("record", "angle", "gap")
    assert ds.peak_total_accel_xy.dims == ("record", "angle", "gap", "floor", "direction")
    assert ds.max_impact_force_wall.dims == ("record", "angle", "gap", "wall")
    assert ds.unconstrained_peak_isolator_disp.dims == ("record", "angle")
    assert list(ds.direction.values) == ["x", "y"]
    assert list(ds.wall.values) == ["+x", "-x", "+y", "-y"]
    assert ds.angle.attrs["units"] == "degree" and "counterclockwise" in ds.angle.attrs[
        "long_name"]
    assert ds.attrs["moat"] == "rectangular" and "resultants" in ds.attrs["plan_conventions"]
    assert_udunits(ds)
    # 90 degrees swaps the directions: x' = -y, y' = x
    turned = ds.peak_isolator_disp_xy.sel(angle=90.0).values
    np.testing.assert_allclose(turned, ds.peak_isolator_disp_xy.sel(angle=0.0).values[..., ::-1],
                               rtol=1e-9)
    # resultant at least each direction's peak
    assert (ds.peak_isolator_disp >= ds.peak_isolator_disp_xy.max("direction") - 1e-15).all()
    ratio = ds.amplification_total_accel
    np.testing.assert_allclose(ratio, ds.peak_total_accel / ds.baseline_peak_total_accel)


@pytest.mark.parametrize("kwargs, match", [
    ({"angle": [0, 30]}, "angle applies to runs in plan"),
    ({"moat": "hexagonal"}, "moat 'hexagonal': the plan model takes 'rectangular' or "
                            "'circular'"),
    ({"moat": "circular", "records": ["RSN953", "RSN953"]}, "each pair must appear once"),
])
def test_bad_plan_sweeps_fail_before_compute(kwargs, match, tmp_path, monkeypatch):
    from pipeline.execute import executor

    monkeypatch.setattr(executor, "execute", lambda *a, **k: pytest.fail("computed"))
    if "out" in kwargs:
        kwargs = {**kwargs, "out": tmp_path / kwargs["out"]}
    records = kwargs.pop("records", ["RSN953"])
    with pytest.raises(SweepError, match=match):
        pipeline.sweep(records, gap=0.2, quiet=True, **kwargs)


def test_command_line_runs_in_plan(plan_sweep, tmp_path, capsys):
    from studies import sweep

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert sweep.main(["--records", *PAIRS, "--gap-cm", "15", "30", "--angle", "0", "45",
                           "90", "--moat", "rectangular", "--quiet",
                           "--out", str(tmp_path)]) == 0
    import xarray as xr

    with xr.open_dataset(tmp_path / "sweep.nc") as ds:
        np.testing.assert_array_equal(ds.peak_isolator_disp_xy,
                                      plan_sweep.peak_isolator_disp_xy)
    assert sweep.main(["--records", "kobe", "--gap-cm", "15", "--angle", "30",
                       "--out", str(tmp_path / "x")]) == 2
    assert "angle applies to runs in plan" in capsys.readouterr().err


def test_wall_friction_and_stories_along_y_sweep_like_the_angle(tmp_path):
    """mu_wall is a dimension of its own; a building stiffer along x than along y reaches the
    engine; every member is the engine's run."""
    building = engine.Building(story_stiffness_y=(3e8, 2.8e8, 2.5e8, 2e8))
    ds = pipeline.sweep(["RSN953"], gap=0.12, angle=[0.0, 60.0], mu_wall=[0.0, 0.4],
                        moat="circular", building=building, quiet=True)
    assert ds.peak_isolator_disp.dims == ("record", "angle", "mu_wall")
    assert ds.mu_wall.attrs["units"] == "1" and "friction" in ds.mu_wall.attrs["long_name"]
    acc, dt = pair_accel(*load_pair("RSN953"))
    run = engine.simulate(acc, dt, engine.Contact.bumper([0.12] * 4), building,
                          moat=engine.Moat("circular", mu_wall=[0.0, 0.4, 0.0, 0.4]),
                          angle=[0.0, 0.0, 60.0, 60.0])
    for peak, value in {**run.peaks(), **run.plan_peaks()}.items():
        got = ds[peak].isel(record=0).transpose("angle", "mu_wall", ...)
        np.testing.assert_array_equal(got.values.reshape(value.shape), value, err_msg=peak)
    assert (ds.n_impacts > 0).all()
    with pytest.raises(SweepError, match="mu_wall applies to runs in plan"):
        pipeline.sweep(["RSN953"], gap=0.12, mu_wall=0.2, quiet=True)
    with pytest.raises(SweepError, match=r"mu_wall 5 is implausible \(outside \[0, 1.5\]\)"):
        pipeline.sweep(["RSN953"], gap=0.12, mu_wall=5.0, moat="circular", quiet=True)


def test_a_sweep_in_plan_into_a_zarr_store_equals_the_netcdf_archive(plan_sweep, tmp_path):
    """The same sweep written region by region (small chunks: many batches) into Zarr."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        store = pipeline.sweep(PAIRS, gap=GAPS, angle=ANGLES, moat="rectangular",
                               baseline=True, unconstrained=True, quiet=True,
                               out=tmp_path / "plan.zarr", batch_size=4).load()
    for name, value in plan_sweep.data_vars.items():
        np.testing.assert_array_equal(store[name].values, value.values, err_msg=name)
    assert store.attrs["moat"] == "rectangular" and store.attrs["complete"] == 1
    assert store.max_impact_force_wall.dims == ("record", "angle", "gap", "wall")
