"""The parametric recipes of sections 5.2-5.6 (Figs. 16, 18-22), each run once in --quick form:
archive dimensions and units, finite peaks, the paper check, what the figure shows, --replot,
--help. A group file (TESTED_IN of tests/test_layout.py): thickness, strain, n_bumpers,
wall_stiffness and restitution, checked alike.
"""

import numpy as np
import pytest
import xarray as xr

from engine.units import CM, G
from studies import n_bumpers, restitution, strain, thickness, wall_stiffness
from studies.common.plot import floor_labels, plt, record_label, story_labels
from studies.common.recipe import verdicts
from tests.helpers import (
    SHARED_RECORDS,
    assert_figure_files,
    assert_on_variables_page,
    assert_udunits,
    drawn,
)

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
        assert_on_variables_page(ds, f"{name}.nc")
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
    assert_figure_files(png, pdf)
    png.unlink()
    assert RECIPES[name][0].main(["--replot", "--out", str(out)]) == 0
    assert png.exists()


# the panels' rows of Figs. 16, 18-21: (y label, the archive's peak as plotted, with baseline)
ROWS = [("Peak floor\nacceleration (g)",
         lambda ds, p="": ds[p + "peak_total_accel"].max("floor") / G, True),
        ("Peak interstory\ndeflection (cm)",
         lambda ds, p="": ds[p + "peak_interstory_drift"].max("story") / CM, True),
        ("Maximum\nindentation (cm)", lambda ds, p="": ds[p + "max_indentation"] / CM, False)]
DIMS = {"thickness": "thickness", "strain": "strain", "n_bumpers": "n_bumpers",
        "wall_stiffness": "wall_k"}


def test_figure_shows_the_archive(run):
    """Figs. 16, 18-21: a column per record, a row per peak, a line per value of the swept
    parameter against the gap in cm (the no-bumper baseline dashed); Fig. 22: a line per level
    and gap against the COR."""
    name, out = run
    module = RECIPES[name][0]
    ds = xr.load_dataset(out / f"{name}.nc")
    fig = module.plot(ds)
    assert fig._suptitle.get_text() == (
        module.TITLE if name != "restitution"
        else "Fig. 22: peak responses vs the bumpers' coefficient of restitution")
    if name == "restitution":
        check_restitution_figure(ds, fig)
    else:
        records, dim = list(ds.record.values), DIMS[name]
        rows = ROWS if name == "n_bumpers" else ROWS[:2]
        axes = np.reshape(fig.axes, (len(rows), len(records)))
        assert [ax.get_title() for ax in axes[0]] == [record_label(ds, str(r)) for r in records]
        assert [ax.get_ylabel() for ax in axes[:, 0]] == [ylabel for ylabel, _, _ in rows]
        assert [ax.get_xlabel() for ax in axes[-1]] == ["Seismic gap (cm)"] * len(records)
        for row, (_, peak, with_baseline) in zip(axes, rows, strict=True):
            for ax, record in zip(row, records, strict=True):
                lines = drawn(ax)
                assert len(lines) == ds.sizes[dim] + 1
                for (_, x, y), value in zip(lines, ds[dim].values, strict=False):
                    np.testing.assert_allclose(x, ds.gap.values / CM)
                    np.testing.assert_array_equal(y, peak(ds).sel(record=record, **{dim: value}))
                label, x, y = lines[-1]
                if with_baseline:
                    assert label == "No bumpers"
                    np.testing.assert_array_equal(y, peak(ds, "baseline_").sel(record=record))
                else:  # the crush limit
                    assert label.startswith("Limit") and np.all(y == n_bumpers.LIMIT / CM)
    plt.close(fig)


def check_restitution_figure(ds, fig):
    left, right = fig.axes
    assert left.get_ylabel() == "Peak floor acceleration (g)"
    assert right.get_ylabel() == "Peak interstory deflection (cm)"
    assert left.get_xlabel() == right.get_xlabel() == "Coefficient of restitution of the bumpers"
    record = ds.record.values[0]
    for ax, peak, dim, labels in ((left, ds.peak_total_accel / G, "floor",
                                   floor_labels(ds.sizes["floor"])),
                                  (right, ds.peak_interstory_drift / CM, "story",
                                   story_labels(ds.sizes["story"]))):
        lines = iter(drawn(ax))
        for level, level_label in zip(ds[dim].values, labels, strict=True):
            for k, gap in enumerate(sorted(ds.gap.values, reverse=True)):
                label, x, y = next(lines)
                assert label == (level_label if k == 0 else "_nolegend_")
                np.testing.assert_array_equal(x, ds.cor.values)
                np.testing.assert_array_equal(
                    y, peak.sel(record=record, gap=gap, **{dim: level}))
        assert next(lines, None) is None


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
