"""The practical_example recipe (Figs. 9-13) in --quick form. (pipeline.histories with real
numbers: tests/pipeline/test_histories.py.)"""
import numpy as np
import pytest
import xarray as xr

from engine.units import CM, KN, G
from studies import practical_example
from studies.common.plot import plt, record_label
from tests.helpers import (
    assert_figure_files,
    assert_on_variables_page,
    assert_udunits,
    drawn,
    recipe_outputs,
)

PEAKS = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp", "max_indentation",
         "max_impact_force", "n_impacts")
HISTORIES = ("base_total_accel", "impact_force", "indentation", "isolator_disp")
CONFIGS = ["no_pounding", "no_bumpers", "bumpers", "no_bumpers_at_paper_gap",
           "bumpers_at_paper_gap"]


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory, records_dir_args):
    return recipe_outputs(practical_example, ["--quick", "--workers", "1", *records_dir_args],
                          tmp_path_factory.mktemp("practical_example"))


def test_archive_is_labelled_and_complete(quick_run):
    with xr.open_dataset(quick_run / "practical_example.nc") as ds:
        assert list(ds.record.values) == ["kobe", "pacoima"]
        assert list(ds.configuration.values) == CONFIGS
        assert ds.sizes["floor"] == 5 and ds.sizes["story"] == 4 and ds.sizes["time"] > 1000
        for name in PEAKS:
            assert ds[name].dims[:2] == ("record", "configuration"), name
            assert not ds[name].isnull().any(), name
            assert ds[name].attrs["units"] and ds[name].attrs["long_name"], name
        for name in HISTORIES:
            assert ds[name].dims == ("record", "configuration", "time"), name
            assert ds[name].attrs["units"] and ds[name].attrs["long_name"], name
        assert ds.time.attrs["units"] == "s"
        np.testing.assert_allclose(np.diff(ds.time.values), 0.002)  # every 4 steps of 0.5 ms
        for record in ds.record.values:
            sel = ds.sel(record=record)
            assert not sel[list(HISTORIES)].sel(time=slice(0, float(sel.history_end))) \
                .to_array().isnull().any()

        # The gap rule: 90% of the engine's unconstrained peak, to the mm, beside the paper's.
        assert ds.chosen_gap.attrs["units"] == "m" and not ds.chosen_gap.isnull().any()
        np.testing.assert_allclose(ds.chosen_gap,
                                   np.round(0.9 * ds.unconstrained_peak_isolator_disp, 3))
        np.testing.assert_allclose(ds.paper_gap, [0.15, 0.24])
        free = ds.sel(configuration="no_pounding")
        np.testing.assert_array_equal(free.peak_isolator_disp, ds.unconstrained_peak_isolator_disp)
        assert (free.n_impacts == 0).all() and (free.max_impact_force == 0).all()
        for config, clear in (("no_bumpers", 0.0), ("bumpers", 0.05)):
            sel = ds.sel(configuration=config)
            np.testing.assert_allclose(sel.gap, ds.chosen_gap)
            np.testing.assert_allclose(sel.clear_gap, ds.chosen_gap - clear)
            assert (sel.n_impacts > 0).all(), config  # the gaps are hit: strong motion kept
        np.testing.assert_allclose(ds.crush_indentation.sel(configuration="bumpers"), 0.04)
        assert list(ds.impact.values) == ["none", "linear", "bumper", "linear", "bumper"]
        for config in ("no_bumpers_at_paper_gap", "bumpers_at_paper_gap"):
            np.testing.assert_allclose(ds.gap.sel(configuration=config), ds.paper_gap)

        # Histories every 2 ms: their maxima within a whisker under the exact peaks.
        base_peak = ds.peak_total_accel.sel(floor=0)
        base_max = abs(ds.base_total_accel).max("time")
        assert (base_max <= base_peak).all() and (base_max >= 0.95 * base_peak).all()
        force_max = ds.impact_force.max("time")
        assert (force_max <= ds.max_impact_force).all()
        assert (force_max >= 0.95 * ds.max_impact_force).all()

        assert "kobe" in ds.attrs["paper_check"] and "pacoima" in ds.attrs["paper_check"]
        assert_udunits(ds)
        assert_on_variables_page(ds, "practical_example.nc")
        assert "15 cm" in ds.attrs["gap_rule"] and "24 cm" in ds.attrs["gap_rule"]
        assert ds.attrs["recipe"] == "practical_example" and ds.attrs["quick"] == 1
        assert ds.attrs["record_kobe_source"] and ds.attrs["record_pacoima_source"]


def test_figure_files_and_replot(quick_run):
    png, pdf = quick_run / "practical_example.png", quick_run / "practical_example.pdf"
    assert_figure_files(png, pdf)
    png.unlink()
    assert practical_example.main(["--replot", "--out", str(quick_run)]) == 0
    assert png.exists()


def test_figure_shows_the_archive(quick_run):
    """Figs. 9-13, per record: the base's total acceleration in time with each configuration's
    peak in its label, the impact force against the indentation, and the peak floor
    accelerations and interstory deflections up the building."""
    ds = xr.load_dataset(quick_run / "practical_example.nc")
    fig = practical_example.plot(ds)
    assert fig._suptitle.get_text() == "Practical example (paper section 4)"
    labels = practical_example.CONFIG_LABELS
    shown = [str(c) for c in ds.configuration.values if c in labels]
    assert len(fig.axes) == 4 * ds.sizes["record"]
    for i, record in enumerate(ds.record.values):
        base, force, accel, drift = fig.axes[4 * i:4 * i + 4]
        sel = ds.sel(record=record)
        keep = sel.time.values <= float(sel.history_end)
        assert base.get_title(loc="left").startswith(
            f"Fig. {9 + i}: {record_label(ds, str(record))}, ")
        assert base.get_xlabel() == "Time (s)"
        assert base.get_ylabel() == "Base total\nacceleration (g)"
        lines = drawn(base)
        drawn_in = ["no_bumpers", "bumpers", "no_pounding"]
        base_peak = sel.peak_total_accel.sel(floor=0) / G
        assert [label for label, _, _ in lines] == [
            f"{labels[c]} (peak {float(base_peak.sel(configuration=c)):.2f} g)"
            for c in drawn_in]
        for (_, x, y), config in zip(lines, drawn_in, strict=True):
            np.testing.assert_array_equal(x, sel.time.values[keep])
            np.testing.assert_array_equal(
                y, sel.base_total_accel.sel(configuration=config).values[keep] / G)
        *loops, (_, crush, _) = drawn(force)
        np.testing.assert_array_equal(  # the crush indentation's line
            crush, float(sel.crush_indentation.sel(configuration="bumpers")) / CM)
        for (label, x, y), config in zip(loops, ["no_bumpers", "bumpers"], strict=True):
            c = sel.sel(configuration=config)
            touching = np.isfinite(x)
            assert label == labels[config] and touching.any()
            np.testing.assert_array_equal(x[touching], c.indentation.values[touching] / CM)
            np.testing.assert_array_equal(y[touching], c.impact_force.values[touching] / KN)
            assert np.nanmax(y) <= float(c.max_impact_force) / KN  # the history is sampled
        for ax, name, unit, level in ((accel, "peak_total_accel", G, "floor"),
                                      (drift, "peak_interstory_drift", CM, "story")):
            for (_, x, y), config in zip(drawn(ax), shown, strict=True):
                np.testing.assert_array_equal(x, sel[name].sel(configuration=config) / unit)
                np.testing.assert_array_equal(y, ds[level].values)
        assert accel.get_xlabel() == "Peak floor acceleration (g)"
        assert drift.get_xlabel() == "Peak interstory\ndeflection (cm)"
    plt.close(fig)


def test_help_and_bad_input(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        practical_example.main(["--help"])
    assert exit_info.value.code == 0
    assert "Figs. 9-13" in capsys.readouterr().out
    assert practical_example.main(["--replot", "--out", str(tmp_path)]) == 2
