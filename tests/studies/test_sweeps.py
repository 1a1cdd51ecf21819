"""The parametric recipes of sections 5.2-5.6 (Figs. 16, 18-22), each run once in --quick form:
archive dimensions and units, finite peaks, the paper check, the figure files, --replot, --help.
"""

import numpy as np
import pytest
import xarray as xr

from studies import n_bumpers, restitution, strain, thickness, wall_stiffness
from studies.common.recipe import verdicts
from tests.helpers import SHARED_RECORDS, assert_udunits

RECORDS_DIR = ["--records-dir", str(SHARED_RECORDS)] if SHARED_RECORDS.is_dir() else []
QUICK_GAPS = [0.15, 0.25, 0.35, 0.45]  # m

# module, its swept dimensions (beyond record, floor, story), paper section, text in --help
RECIPES = {
    "thickness": (thickness, {"record": 2, "gap": 4, "thickness": 3}, "5.2", "3, 5 and 8 cm"),
    "strain": (strain, {"record": 4, "gap": 4, "strain": 3}, "5.3", "0.6, 0.8 and 1.0"),
    "n_bumpers": (n_bumpers, {"record": 4, "gap": 4, "n_bumpers": 4}, "5.4", "75%"),
    "wall_stiffness": (wall_stiffness, {"record": 4, "gap": 4, "wall_k": 3}, "5.5", "10%"),
    "restitution": (restitution, {"record": 1, "gap": 2, "cor": 3, "impact": 2}, "5.6",
                    "COR 0.3 to 1.0"),
}
UNITS = {"gap": "m", "thickness": "m", "strain": "1", "n_bumpers": "1", "wall_k": "N m-1",
         "cor": "1", "record_pga": "m s-2", "record_dt": "s", "record_duration": "s"}
FINITE = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp", "max_indentation",
          "max_impact_force", "unconstrained_peak_isolator_disp")


@pytest.fixture(scope="module", params=list(RECIPES))
def run(request, tmp_path_factory):
    """(name, output folder) after one --quick run of the recipe."""
    name = request.param
    out = tmp_path_factory.mktemp(name)
    args = ["--quick", "--workers", "1", "--quiet", "--out", str(out), *RECORDS_DIR]
    assert RECIPES[name][0].main(args) == 0
    return name, out / "quick"  # a quick run's outputs never replace a full run's


def test_archive(run):
    name, out = run
    module, sizes, section, _ = RECIPES[name]
    with xr.open_dataset(out / f"{name}.nc") as ds:
        assert dict(ds.sizes) == {**sizes, "floor": 5, "story": 4}
        if "gap" in sizes and name != "restitution":
            np.testing.assert_allclose(ds.gap, QUICK_GAPS)
        assert list(ds.record.values) == list(module.recipe.records)
        for var in ds.data_vars.values():  # numbers carry units, text none (CF)
            assert ("units" in var.attrs) == (var.dtype.kind in "biufc"), var.name
        for coord, units in UNITS.items():
            assert ds[coord].attrs["units"] == units, coord
        for prefix in ("", "baseline_") if name != "restitution" else ("",):
            for var in FINITE[:-1]:
                assert not ds[prefix + var].isnull().any(), prefix + var
        assert not ds[FINITE[-1]].isnull().any()
        assert f"paper {section}" in ds.attrs["paper_check"]
        found = verdicts(ds)
        assert found and {v["conclusion"] for v in found} == {section}
        for v in found:  # the prose holds each verdict, the JSON its numbers
            assert f"{v['claim']} (paper {section}); here: " in ds.attrs["paper_check"]
            assert v["numbers"]
        assert_udunits(ds)
        assert ds.attrs["recipe"] == name and ds.attrs["quick"] == 1
        assert ds.attrs["values_chosen"] == module.recipe.chosen
        if name == "restitution":
            check_restitution_gap(ds)


def check_restitution_gap(ds):
    """The gap is 0.9 x the engine's own unconstrained peak, to the mm, and stored."""
    peak = ds.unconstrained_peak_isolator_disp.item()
    gap = ds.attrs["chosen_gap"]
    assert abs(gap - 0.9 * peak) <= 0.5e-3 and ds.attrs["chosen_gap_units"] == "m"
    np.testing.assert_allclose(ds.gap, sorted([gap, 0.285]))  # and the paper's gap
    assert ds.attrs["clear_gap"] == pytest.approx(gap - 0.05)
    assert float(ds.thickness) == 0.05
    assert "0.9 x unconstrained peak" in ds.attrs["gap_rule"]


def test_figures_and_replot(run):
    name, out = run
    png, pdf = out / f"{name}.png", out / f"{name}.pdf"
    assert png.stat().st_size > 10_000 and pdf.stat().st_size > 10_000
    png.unlink()
    assert RECIPES[name][0].main(["--replot", "--out", str(out)]) == 0
    assert png.exists()


@pytest.mark.parametrize("name", list(RECIPES))
def test_help(name, capsys):
    with pytest.raises(SystemExit) as exit_info:
        RECIPES[name][0].main(["--help"])
    assert exit_info.value.code == 0
    assert RECIPES[name][3] in " ".join(capsys.readouterr().out.split())


def test_restitution_takes_one_record(tmp_path, capsys):
    args = ["--records", "sylmar_converter", "pacoima", "--out", str(tmp_path), "--quiet"]
    assert restitution.main(args) == 2
    assert "one record" in capsys.readouterr().err
