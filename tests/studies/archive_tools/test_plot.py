"""bumpers plot (studies/archive_tools/plot.py) on a small sweep archive: a PNG written, a line
per combination of the other dimensions with the archive's peaks, the median and its band over
many runs."""

import numpy as np
import xarray as xr

from engine.units import G
from studies import cli
from studies.archive_tools import plot
from studies.common.plot import plt
from tests.helpers import PNG_SIGNATURE, drawn


def test_plot_writes_a_png(archive, tmp_path, capsys):
    path, _ = archive
    out = tmp_path / "fig.png"
    assert cli.main(["plot", str(path), "--x", "gap", "--out", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert cli.main(["plot", str(path.with_suffix(".zarr")), "--x", "n_bumpers", "--y",
                     "peak_interstory_drift", "--story", "1", "--out", str(out)]) == 0
    assert [p.name for p in tmp_path.iterdir()] == ["fig.png"]  # no temporary file left


def test_plot_draws_a_line_per_combination_of_the_other_dimensions(archive):
    """What `bumpers plot ARCHIVE --x gap` shows: the largest peak floor acceleration in g
    against the gap, a line per bumper count, the axes labelled from the archive."""
    path, ds = archive
    fig = plot.figure(ds, plot.parser().parse_args([str(path), "--x", "gap"]))
    ax, = fig.axes
    lines = drawn(ax)
    assert [label for label, _, _ in lines] == ["n_bumpers 4", "n_bumpers 8"]
    for (_, x, y), n in zip(lines, ds.n_bumpers.values, strict=True):
        np.testing.assert_array_equal(x, ds.gap.values)
        np.testing.assert_allclose(
            y, ds.peak_total_accel.max("floor").sel(n_bumpers=n).squeeze("record") / G,
            rtol=1e-12)
    assert ax.get_xlabel() == f"{ds.gap.attrs['long_name']} [m]"
    assert ax.get_ylabel() == \
        f"largest {ds.peak_total_accel.attrs['long_name']} over the floors [g]"
    plt.close(fig)


def test_plot_draws_a_band_over_many_combinations(archive, tmp_path):
    """Seven records x two bumper counts: more lines than MAX_LINES, so a median and band."""
    _, ds = archive
    many = xr.concat([ds.assign_coords(record=[f"r{i}"]) for i in range(7)], "record")
    many.to_netcdf(tmp_path / "many.nc")
    out = tmp_path / "band.png"
    args = plot.parser().parse_args([str(tmp_path / "many.nc"), "--x", "gap"])
    values, _ = plot.curve(many, args)
    assert values.dims == ("gap", "record", "n_bumpers")
    assert plot.main([str(tmp_path / "many.nc"), "--x", "gap", "--out", str(out)]) == 0
    assert out.read_bytes().startswith(PNG_SIGNATURE)
    fig = plot.figure(many, args)  # what the PNG shows: the median line and its band
    (label, x, y), = drawn(fig.axes[0])
    peak = many.peak_total_accel.max("floor").transpose("gap", ...).values.reshape(2, -1) / G
    assert label == "median over record, n_bumpers (14 runs each)"
    np.testing.assert_array_equal(x, many.gap.values)
    np.testing.assert_allclose(y, np.median(peak, axis=1), rtol=1e-12)
    band, = fig.axes[0].collections
    assert band.get_label() == "16%-84% over record, n_bumpers"
    plt.close(fig)
