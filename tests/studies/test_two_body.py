"""The two-body recipes together (impact_validation, Fig. 6; damping_calibration, Eq. 9): one
quick run of each, checked alike. (engine.damping_fit: tests/engine/test_damping_fit.py.)"""
import numpy as np
import pytest
import xarray as xr

from studies import damping_calibration, impact_validation
from tests.helpers import assert_udunits

# --- the recipes ----------------------------------------------------------------------------

RECIPES = {"impact_validation": impact_validation, "damping_calibration": damping_calibration}
DIMS = {"impact_validation": {"model": 2, "velocity": 3},
        "damping_calibration": {"cor": 3, "m_eff": 2, "v_imp": 2}}


@pytest.fixture(scope="module")
def quick_runs(tmp_path_factory):
    out = tmp_path_factory.mktemp("two_body")
    for module in RECIPES.values():
        assert module.main(["--quick", "--out", str(out), "--quiet"]) == 0
    return out / "quick"  # a quick run's outputs never replace a full run's


@pytest.mark.parametrize("name", RECIPES)
def test_archive_is_labelled_and_complete(quick_runs, name):
    with xr.open_dataset(quick_runs / f"{name}.nc") as ds:
        for dim, size in DIMS[name].items():
            assert ds.sizes[dim] == size, dim
        for var in [*ds.data_vars, *ds.coords]:  # numbers carry units, text none (CF)
            assert bool(ds[var].attrs.get("units")) == (ds[var].dtype.kind in "biufc"), var
            assert ds[var].attrs.get("long_name"), var
            if ds[var].dtype.kind == "f":
                assert not ds[var].isnull().any(), var
        assert ds.attrs["paper_check"].strip()
        assert_udunits(ds)
        assert ds.attrs["recipe"] == name and ds.attrs["quick"] == 1


def test_impact_validation_numbers(quick_runs):
    with xr.open_dataset(quick_runs / "impact_validation.nc") as ds:
        assert ds.sizes["step"] > 1000
        assert float(ds.k_imp) / (1e3 * 1e3**2.65) == pytest.approx(0.45, rel=1e-4)
        proposed, hertzdamp = ds.sel(model="proposed"), ds.sel(model="hertzdamp")
        np.testing.assert_allclose(proposed.area_ratio, 1.0, atol=0.01)
        assert np.all(hertzdamp.area_ratio < 0.7)
        assert float(proposed.approach_deviation.max()) < 1e-9
        assert np.all(ds.peak_indentation < ds.delta_u)
        assert np.all((ds.peak_force > 10e3) & (ds.peak_force < 60e3))  # a few tens of kN
        assert np.all(ds.indentation >= 0) and np.all(ds.force >= 0)
        assert "agrees" in ds.attrs["paper_check"]


def test_damping_calibration_numbers(quick_runs):
    with xr.open_dataset(quick_runs / "damping_calibration.nc") as ds:
        np.testing.assert_allclose(ds.hysteresis_area / ds.energy_loss, 1.0, atol=1e-3)
        assert abs(float(ds.fit_p2)) < 1e-6
        assert float(ds.fit_p3) == pytest.approx(1.0, abs=1e-6)
        assert float(ds.fit_c0) == pytest.approx(1.55, rel=0.1)
        assert float(ds.fit_p1) == pytest.approx(0.7076, abs=0.1)
        assert np.all(ds.peak_indentation < ds.delta_u)
        np.testing.assert_allclose(ds.cor_fit / ds.cor, 1.0, atol=0.01)
        assert "c0 = 1.55" in ds.attrs["paper_check"]


@pytest.mark.parametrize("name", RECIPES)
def test_figure_files_and_replot(quick_runs, name):
    png, pdf = quick_runs / f"{name}.png", quick_runs / f"{name}.pdf"
    assert png.stat().st_size > 10_000 and pdf.stat().st_size > 10_000
    png.unlink()
    assert RECIPES[name].main(["--replot", "--out", str(quick_runs), "--quiet"]) == 0
    assert png.exists()


@pytest.mark.parametrize("name", RECIPES)
def test_help_and_missing_archive(tmp_path, capsys, name):
    with pytest.raises(SystemExit) as exit_info:
        RECIPES[name].main(["--help"])
    assert exit_info.value.code == 0
    text = capsys.readouterr().out
    # no records to choose, but the options every recipe shares are accepted (so one loop
    # over all recipes works), and said to be unused
    assert "--records " not in text and "--records NAME" not in text
    assert "--workers" in text and "--records-dir" in text and "does not use it" in text
    assert RECIPES[name].main(["--replot", "--out", str(tmp_path)]) == 2
