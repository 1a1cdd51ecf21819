"""The two-body recipes together (impact_validation, Fig. 6; damping_calibration, Eq. 9): one
quick run of each, checked alike: a group file (TESTED_IN of tests/test_layout.py).
(engine.damping_fit: tests/engine/test_damping_fit.py.)"""
import numpy as np
import pytest
import xarray as xr

from engine.units import KN, MM
from studies import damping_calibration, impact_validation
from studies.common.plot import plt
from tests.helpers import assert_figure_files, assert_on_variables_page, assert_udunits, drawn

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
        assert_on_variables_page(ds, f"{name}.nc")
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
    assert_figure_files(png, pdf)
    png.unlink()
    assert RECIPES[name].main(["--replot", "--out", str(quick_runs), "--quiet"]) == 0
    assert png.exists()


def test_impact_validation_figure_shows_the_archive(quick_runs):
    """Fig. 6: the static test curve, then per impact velocity each model's force against its
    indentation while in contact, over the static curve."""
    ds = xr.load_dataset(quick_runs / "impact_validation.nc")
    fig = impact_validation.plot(ds)
    assert fig._suptitle.get_text() == "Fig. 6: impact tests of a 10 mm rubber bumper"
    static, *impacts = fig.axes
    assert static.get_title() == "Static test curve"
    assert [ax.get_title() for ax in impacts] == [f"$v_{{imp}}$ = {v:.2g} m/s"
                                                 for v in ds.velocity.values]
    assert [ax.get_xlabel() for ax in fig.axes[2:]] == ["Indentation (mm)"] * 2
    assert [ax.get_ylabel() for ax in fig.axes[::2]] == ["Impact force (kN)"] * 2
    (_, grid, curve), *_ = drawn(static)
    for ax, v in zip(impacts, ds.velocity.values, strict=True):
        *models, (label, x, y) = drawn(ax)
        assert label == "Static curve"
        np.testing.assert_array_equal(x, grid)
        np.testing.assert_array_equal(y, curve)
        for (label, x, y), model in zip(models, ds.model.values, strict=True):
            case = ds.sel(model=model, velocity=v)
            end = int(case.n_contact_steps)
            assert label == impact_validation.MODEL_LABELS[str(model)]
            np.testing.assert_array_equal(x, case.indentation.values[:end] / MM)
            np.testing.assert_array_equal(y, case.force.values[:end] / KN)
    plt.close(fig)


def test_damping_calibration_figure_shows_the_archive(quick_runs):
    """Eq. 9's figure: the damping coefficient found at each impact velocity and mass (one
    series of points per COR and mass), and each realised COR's error against its target."""
    ds = xr.load_dataset(quick_runs / "damping_calibration.nc")
    fig = damping_calibration.plot(ds)
    assert fig._suptitle.get_text() == \
        "Eq. 9 re-derived by energy equilibrium (paper section 3.2)"
    coefficient, realised = fig.axes
    assert coefficient.get_title() == "Impact damping coefficient"
    assert coefficient.get_xlabel() == "Impact velocity $v_{imp}$ (m/s)"
    assert realised.get_xlabel() == "Target COR"
    assert realised.get_ylabel() == "Realised COR / target - 1 (%)"
    lines = iter(drawn(coefficient))
    for cor in ds.cor.values:
        found = (ds.c_imp_found.sel(cor=cor) / (1 - cor**2)).values  # (m_eff, v_imp)
        for row in found:
            _, x, y = next(lines)
            np.testing.assert_array_equal(x, ds.v_imp.values)
            np.testing.assert_array_equal(y, row)
        next(lines), next(lines)  # the refit's law and Eq. 9's
    points = iter(drawn(realised))
    for name, shift in (("cor_eq9", -0.012), ("cor_fit", 0.012)):
        error = (ds[name] / ds.cor - 1).values.reshape(ds.sizes["cor"], -1) * 100
        for target, values in zip(ds.cor.values, error, strict=True):
            _, x, y = next(points)
            np.testing.assert_allclose(x, target + shift)
            np.testing.assert_array_equal(y, values)
        next(points)  # its legend entry
    plt.close(fig)


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
