"""The building's isolator parameters as sweep dimensions: every member equals the engine run on
the building with those values (built independently, not through the grid), the baseline and
unconstrained runs repeat per isolator, and wrong parameters fail before any compute."""
import numpy as np
import pytest

import engine
import pipeline
from pipeline.errors import SweepError
from tests.helpers import assert_udunits
from tests.pipeline.small_sweep import RECORDS, synthetic

DT = 0.002  # s
GAPS = [0.04, 0.08]  # m: the pulses reach both walls at each (asserted below)
FRICTION_PENDULUM = dict(radius=2.0, mu_slow=0.04, mu_fast=0.08, rate=25.0)


def engine_peaks(record, building, contact):
    return engine.simulate(record.accel, record.dt, contact, building=building, dt=DT).peaks()


def test_bilinear_sweep_equals_each_building_run_alone():
    k2 = [18e6, 25e6, 32e6]
    ds = pipeline.sweep(RECORDS, gap=GAPS, thickness=0.03, k2=k2, fy_ratio=0.08, dt=DT,
                        baseline=True, unconstrained=True, quiet=True)
    assert ds.peak_isolator_disp.dims == ("record", "gap", "k2")
    assert ds.baseline_peak_total_accel.dims == ("record", "gap", "k2", "floor")
    assert ds.unconstrained_peak_isolator_disp.dims == ("record", "k2")
    assert ds.k2.attrs["units"] == "N m-1" and "K2" in ds.k2.attrs["long_name"]
    assert float(ds.fy_ratio) == 0.08  # fixed: a scalar coordinate
    assert "k2, fy_ratio" in ds.attrs["isolator_parameters"]
    assert ds.attrs["building_isolator_k2"] == 25e6  # the building as given, described
    assert_udunits(ds)
    assert (ds.n_impacts > 0).all() and (ds.baseline_n_impacts > 0).all()
    bumpers = engine.Contact.bumper(GAPS, thickness=0.03)
    bare = engine.Contact.linear(GAPS)
    for r, rec in enumerate(RECORDS):
        for value in k2:
            building = engine.Building(k2=value, fy_ratio=0.08)  # the shorthand, not the grid
            alone = engine_peaks(rec, building, bumpers)
            base = engine_peaks(rec, building, bare)
            free = engine_peaks(rec, building, engine.Contact.none(1))
            at = ds.isel(record=r).sel(k2=value)
            for name, value_alone in alone.items():
                np.testing.assert_array_equal(at[name].values, value_alone, err_msg=name)
                np.testing.assert_array_equal(at["baseline_" + name].values, base[name],
                                              err_msg=name)
                np.testing.assert_array_equal(at["unconstrained_" + name].values,
                                              free[name][0], err_msg=name)
    # Each isolator gives its own response (no member ran on the building as given).
    free = ds.unconstrained_peak_isolator_disp.values
    assert np.all(np.abs(np.diff(free, axis=1)) > 1e-3)


def test_friction_pendulum_sweep_over_two_parameters():
    building = engine.Building(isolator=engine.Isolator.friction_pendulum(**FRICTION_PENDULUM))
    mu_fast, radius = [0.06, 0.10], [1.5, 3.0]
    record = synthetic("pulse-c", 2.0, 5.0, 0.0)
    ds = pipeline.sweep(record, gap=0.05, thickness=0.03, mu_fast=mu_fast, radius=radius,
                        dt=DT, building=building, quiet=True)
    assert ds.peak_isolator_disp.dims == ("record", "radius", "mu_fast")  # declared order
    assert ds.radius.attrs["units"] == "m"
    assert (ds.n_impacts > 0).any()
    for mu in mu_fast:
        for r in radius:
            isolator = engine.Isolator.friction_pendulum(
                **{**FRICTION_PENDULUM, "mu_fast": mu, "radius": r})
            alone = engine_peaks(record, engine.Building(isolator=isolator),
                                 engine.Contact.bumper(0.05, thickness=0.03))
            at = ds.isel(record=0).sel(mu_fast=mu, radius=r)
            for name, value in alone.items():
                np.testing.assert_array_equal(at[name].values, value[0], err_msg=name)
    # More friction, less sliding: the peak falls with mu_fast at either radius.
    assert (ds.peak_isolator_disp.diff("mu_fast") < 0).all()


@pytest.mark.parametrize("building, given, match", [
    (None, {"radius": [1.5, 2.0]}, "radius is a parameter of the 'friction_pendulum' isolator"),
    (None, {"k2": [20e6, 250e6]}, r"0 < k2 < k1, got k1=200000000.0, k2=250000000.0"),
    (None, {"k2": [-1.0, 2e6]}, r"k2"),
    (engine.Building(isolator=engine.Isolator.friction_pendulum(**FRICTION_PENDULUM)),
     {"mu_slow": [0.05, 0.12]}, "mu_slow <= mu_fast"),
    (None, {"bogus": 1.0}, "no such sweep parameter"),
])
def test_bad_isolator_parameters_fail_before_any_compute(building, given, match, monkeypatch):
    from pipeline.execute import executor

    monkeypatch.setattr(executor, "execute", lambda *a, **k: pytest.fail("computed"))
    with pytest.raises(SweepError, match=match):
        pipeline.sweep(RECORDS[0], gap=0.10, building=building, dt=DT, quiet=True, **given)


def test_command_line_takes_isolator_stiffness_in_kn_per_mm(tmp_path, capsys):
    import xarray as xr

    from studies import sweep

    assert sweep.main(["--records", "kobe", "--gap-cm", "30", "--k2-kn-mm", "20", "30",
                       "--quiet", "--out", str(tmp_path)]) == 0
    with xr.open_dataset(tmp_path / "sweep.nc") as ds:
        np.testing.assert_array_equal(ds.k2.values, [20e6, 30e6])
    assert sweep.main(["--records", "kobe", "--gap-cm", "30", "--radius", "2",
                       "--out", str(tmp_path / "x")]) == 2
    assert "the building stands on a 'bilinear' isolator" in capsys.readouterr().err
