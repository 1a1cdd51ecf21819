"""The main recipe, gap_size (Figs. 14-15), in --quick form: archive, figure, paper check."""
import numpy as np
import pytest
import xarray as xr

from engine.units import CM
from studies import gap_size
from studies.common.plot import plt, record_label
from studies.common.recipe import verdicts
from tests.helpers import (
    assert_figure_files,
    assert_on_variables_page,
    assert_udunits,
    drawn,
    recipe_outputs,
)


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory, records_dir_args):
    return recipe_outputs(gap_size, ["--quick", "--workers", "1", *records_dir_args],
                          tmp_path_factory.mktemp("gap_size"))


def test_archive_is_labelled_and_complete(quick_run):
    with xr.open_dataset(quick_run / "gap_size.nc") as ds:
        assert dict(ds.sizes) == {"record": 4, "gap": 4, "floor": 5, "story": 4}
        np.testing.assert_allclose(ds.gap, [0.15, 0.25, 0.35, 0.45])
        assert ds.gap.attrs["units"] == "m"
        assert ds.thickness.item() == 0.05 and ds.n_bumpers.item() == 4
        for name in ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
                     "max_indentation", "max_impact_force", "baseline_peak_total_accel",
                     "amplification_total_accel", "amplification_interstory_drift",
                     "unconstrained_peak_isolator_disp"):
            assert not ds[name].isnull().any(), name
            assert "units" in ds[name].attrs, name
        ratio = ds.peak_total_accel / ds.baseline_peak_total_accel
        np.testing.assert_allclose(ds.amplification_total_accel, ratio)
        assert "paper 5.1" in ds.attrs["paper_check"]
        assert [v["conclusion"] for v in verdicts(ds)] == ["5.1", "5.1"]
        assert_udunits(ds)
        assert_on_variables_page(ds, "gap_size.nc")
        assert ds.attrs["recipe"] == "gap_size" and ds.attrs["quick"] == 1


def test_figure_files_and_replot(quick_run):
    png, pdf = quick_run / "gap_size.png", quick_run / "gap_size.pdf"
    assert_figure_files(png, pdf)
    png.unlink()
    assert gap_size.main(["--replot", "--out", str(quick_run)]) == 0
    assert png.exists()


def test_figure_shows_the_archive(quick_run):
    """Figs. 14-15: a panel per floor (top row) and per story (bottom row), a line per record
    of its amplification against the gap in cm, the no-change line at 1."""
    ds = xr.load_dataset(quick_run / "gap_size.nc")
    fig = gap_size.plot(ds)
    assert fig._suptitle.get_text() == ("Amplification by rubber bumpers against the seismic "
                                        "gap (paper Figs. 14-15)")
    axes = np.reshape(fig.axes, (2, 5))
    rows = [("amplification_total_accel", "floor", ["Base (isolation level)", "1st floor",
                                                    "2nd floor", "3rd floor", "Roof"]),
            ("amplification_interstory_drift", "story", ["1st story", "2nd story",
                                                         "3rd story", "4th story"])]
    for row, (name, dim, titles) in zip(axes, rows, strict=True):
        assert [ax.get_title() for ax in row[:len(titles)]] == titles
        for ax, index in zip(row, ds[dim].values, strict=False):
            lines = drawn(ax)
            assert [label for label, _, _ in lines[:-1]] == \
                [record_label(ds, str(r)) for r in ds.record.values]
            for (_, x, y), record in zip(lines, ds.record.values, strict=False):
                np.testing.assert_allclose(x, ds.gap.values / CM)
                np.testing.assert_array_equal(y, ds[name].sel(record=record, **{dim: index}))
            assert np.all(lines[-1][2] == 1.0)  # the no-change line
    assert axes[0, 0].get_ylabel() == "Amplification of peak\nfloor acceleration"
    assert axes[1, 0].get_ylabel() == "Amplification of peak\ninterstory deflection"
    assert [ax.get_xlabel() for ax in axes[1, :4]] == ["Seismic gap (cm)"] * 4
    assert not axes[1, 4].axison  # the legend's place
    plt.close(fig)


def test_help_and_bad_input(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_info:
        gap_size.main(["--help"])
    assert exit_info.value.code == 0
    assert "15-45 cm" in capsys.readouterr().out
    assert gap_size.main(["--replot", "--out", str(tmp_path)]) == 2
    assert gap_size.main(["--quick", "--records", "no-such-record", "--workers", "1",
                          "--out", str(tmp_path)]) == 2
    assert "no-such-record" in capsys.readouterr().err
