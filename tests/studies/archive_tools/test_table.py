"""An archive read as runs (studies/archive_tools/table.py) refuses anything else: bad input to
bumpers export and bumpers plot is one line, exit status 2, nothing written."""

import pytest
import xarray as xr

from studies.archive_tools import export, plot


def one_line_error(capsys, status: int) -> str:
    assert status == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and len(err.strip().splitlines()) == 1, err
    return err


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
        # a height in cm for one in m (issue 40): every drift ratio 100 times too small
        (export.main, [str(path), "--pelicun", str(out), "--story-height-m", "350"],
         "a story 350 m high is implausible (outside [1.5, 30] m)"),
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
