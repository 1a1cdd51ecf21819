"""`bumpers export` and `bumpers plot` (studies/archive_tools/) on a small sweep archive: the
CSV holds the archive's values, the pelicun sample pelicun's columns and units row (read back
by pelicun when it is installed), the plot a PNG, and bad input is one line, exit status 2,
nothing written."""
import importlib.util
import warnings

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import pipeline
from engine.units import G
from pipeline.records import Record
from studies import cli
from studies.archive_tools import export, plot
from studies.common.plot import plt
from tests.helpers import PNG_SIGNATURE, drawn

HEIGHT = 3.5  # m, every story


def pulse(name: str, period: float, amplitude: float) -> Record:
    """6 s of a sine under a sin^2 envelope: a record that makes contact in a second."""
    dt = 0.01
    t = np.arange(0.0, 6.0, dt)
    accel = amplitude * np.sin(np.pi * t / t[-1]) ** 2 * np.sin(2 * np.pi * t / period)
    return Record(name=name, rsn=None, event="synthetic", station="", component="", dt=dt,
                  accel=accel, source="tests: synthetic pulse")


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    """A 2 gaps x 2 bumper counts sweep of one record, with both reference blocks, as the
    sweep writes it (NetCDF), and the same archive as a Zarr store."""
    folder = tmp_path_factory.mktemp("sweep")
    path = folder / "small.nc"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the coarse dt's plausibility warning
        pipeline.sweep([pulse("pulse-a", 1.5, 4.0)], gap=[0.06, 0.10], n_bumpers=[4, 8],
                       thickness=0.03, dt=0.004, baseline=True, unconstrained=True,
                       quiet=True, out=path)
    with xr.open_dataset(path) as ds:
        ds = ds.load()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # zarr's notes on its format's string types
        ds.to_zarr(folder / "small.zarr")
    return path, ds


def one_line_error(capsys, status: int) -> str:
    assert status == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and len(err.strip().splitlines()) == 1, err
    return err


def check_table(table: pd.DataFrame, ds: xr.Dataset):
    assert list(table.columns[:4]) == ["record", "gap [m]", "n_bumpers", "block"]
    assert table.block.value_counts().to_dict() == {"bumpers": 4, "baseline": 2,
                                                    "unconstrained": 1}
    for _, row in table.iterrows():
        at = {"record": row["record"]}
        prefix = {"bumpers": "", "baseline": "baseline_", "unconstrained": "unconstrained_"}
        prefix = prefix[row.block]
        if row.block != "unconstrained":
            at["gap"] = row["gap [m]"]
        if row.block == "bumpers":
            at["n_bumpers"] = int(row["n_bumpers"])
        else:
            assert pd.isna(row["n_bumpers"])  # the references run no bumpers
        for floor in ds.floor.values:
            assert row[f"peak_total_accel_floor{floor} [m s-2]"] == \
                ds[prefix + "peak_total_accel"].sel({**at, "floor": floor}).item()
        for story in ds.story.values:
            assert row[f"peak_interstory_drift_story{story} [m]"] == \
                ds[prefix + "peak_interstory_drift"].sel({**at, "story": story}).item()
        assert row["max_impact_force [N]"] == ds[prefix + "max_impact_force"].sel(at).item()
        assert row["n_impacts"] == ds[prefix + "n_impacts"].sel(at).item()
        ratio = row["amplification_total_accel_floor4"]
        if row.block == "bumpers":
            assert ratio == ds.amplification_total_accel.sel({**at, "floor": 4}).item()
        else:
            assert pd.isna(ratio)


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_csv_holds_the_archive_values(archive, tmp_path, suffix, capsys):
    path, ds = archive
    out = tmp_path / "peaks.csv"
    assert cli.main(["export", str(path.with_suffix(suffix)), "--csv", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    check_table(pd.read_csv(out, float_precision="round_trip"), ds)


def test_csv_of_one_block_at_one_value(archive, tmp_path):
    path, ds = archive
    out = tmp_path / "peaks.csv"
    assert export.main([str(path), "--csv", str(out), "--block", "bumpers",
                        "--sel", "n_bumpers=8"]) == 0
    table = pd.read_csv(out, float_precision="round_trip")
    assert len(table) == 2 and set(table.block) == {"bumpers"}
    np.testing.assert_array_equal(table["peak_isolator_disp [m]"],
                                  ds.peak_isolator_disp.sel(n_bumpers=8).values.ravel())


def test_pelicun_sample_columns_and_units_row(archive, tmp_path):
    path, ds = archive
    out = tmp_path / "demands.csv"
    assert export.main([str(path), "--pelicun", str(out), "--story-height-m", str(HEIGHT),
                        "--sel", "gap=0.1"]) == 0
    lines = out.read_text().splitlines()
    floors, stories = ds.sizes["floor"], ds.sizes["story"]
    assert lines[0].split(",") == ["", *(f"1-PFA-{f}-1" for f in range(floors)),
                                   *(f"1-PID-{s}-1" for s in range(1, stories + 1))]
    assert lines[1].split(",") == ["Units", *["g"] * floors, *["rad"] * stories]
    sample = pd.read_csv(out, index_col=0, skiprows=[1], float_precision="round_trip")
    assert list(sample.index) == [0, 1]  # one row per run: n_bumpers 4 and 8
    np.testing.assert_allclose(sample["1-PFA-4-1"], ds.peak_total_accel.sel(
        gap=0.1, floor=4).values.ravel() / export.PELICUN_G, rtol=1e-14)
    np.testing.assert_allclose(sample["1-PID-1-1"], ds.peak_interstory_drift.sel(
        gap=0.1, story=1).values.ravel() / HEIGHT, rtol=1e-14)


@pytest.mark.skipif(importlib.util.find_spec("pelicun") is None,
                    reason="pelicun (an optional extra) is not installed")
def test_pelicun_reads_the_sample_back(archive, tmp_path):
    from pelicun.assessment import Assessment

    path, ds = archive
    out = tmp_path / "demands.csv"
    assert export.main([str(path), "--pelicun", str(out), "--story-height-m", str(HEIGHT)]) == 0
    assessment = Assessment({"PrintLog": False})
    assessment.demand.load_sample(str(out))
    sample = assessment.demand.sample  # pelicun's SI: m/s^2 and rad
    np.testing.assert_allclose(sample["PFA"]["4"]["1"].values,
                               ds.peak_total_accel.sel(floor=4).values.ravel(), rtol=1e-12)
    np.testing.assert_allclose(sample["PID"]["2"]["1"].values,
                               ds.peak_interstory_drift.sel(story=2).values.ravel() / HEIGHT,
                               rtol=1e-12)


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


def test_bad_input_is_one_line_exit_2_nothing_written(archive, tmp_path, capsys):
    path, _ = archive
    out = tmp_path / "out.csv"
    text = tmp_path / "notes.txt"
    text.write_text("not an archive\n")
    other = tmp_path / "other.nc"
    xr.Dataset({"a": ("t", [1.0, 2.0])}).to_netcdf(other)
    cases = [
        (export.main, [str(tmp_path / "missing.nc"), "--csv", str(out)], "no such file"),
        (export.main, [str(text), "--csv", str(out)], "not a NetCDF or Zarr archive"),
        (export.main, [str(other), "--csv", str(out)], "peak_total_accel"),
        (export.main, [str(path), "--pelicun", str(out)], "--story-height-m"),
        (export.main, [str(path), "--csv", str(out), "--sel", "gap=0.5"], "0.06, 0.1"),
        (export.main, [str(path), "--csv", str(out), "--sel", "gapp=1"], "n_bumpers"),
        (export.main, [str(path), "--csv", str(tmp_path / "out.xlsx")], ".csv"),
        (plot.main, [str(path), "--x", "wall_k", "--out", str(tmp_path / "f.png")],
         "record, gap, n_bumpers"),
        (plot.main, [str(path), "--x", "gap", "--y", "pfa", "--out", str(tmp_path / "f.png")],
         "peak_interstory_drift"),
        (plot.main, [str(other), "--x", "t", "--out", str(tmp_path / "f.png")],
         "not the layout of a sweep archive"),
    ]
    for main, argv, said in cases:
        err = one_line_error(capsys, main(argv))
        assert said in err, err
    with pytest.raises(SystemExit) as stop:  # argparse: neither --csv nor --pelicun
        export.main([str(path)])
    one_line_error_text = capsys.readouterr().err
    assert stop.value.code == 2 and len(one_line_error_text.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt", "other.nc"]
