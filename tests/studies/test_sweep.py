"""The sweep command (studies/sweep.py): it writes the archive from AT2 files and units in the
paper's spelling, reports an error on one line, and its help lists its options."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from pipeline.records import Record
from tests.pipeline.small_sweep import (
    DT,
    RECORDS,
)

PROJECT = Path(__file__).resolve().parents[2]


# --------------------------------------------------------------------------- command line


def write_at2(path: Path, rec: Record):
    """A small NGA-West2 style AT2 file (values in g)."""
    values = rec.accel / 9.81
    rows = [" ".join(f"{v: .7E}" for v in values[i:i + 5]) for i in range(0, values.size, 5)]
    path.write_text("PEER NGA STRONG MOTION DATABASE RECORD\nSynthetic, 1/1/2000, Test, 0\n"
                    "ACCELERATION TIME SERIES IN UNITS OF G\n"
                    f"NPTS= {values.size}, DT= {rec.dt:.4f} SEC\n" + "\n".join(rows) + "\n")


def test_cli_writes_archive_and_reports_errors_on_one_line(tmp_path, capsys):
    from studies.sweep import main

    at2 = tmp_path / "PULSE_A.AT2"
    write_at2(at2, RECORDS[0])
    out = tmp_path / "cli.nc"
    code = main(["--records", str(at2), "--gap-cm", "6", "10", "--thickness-cm", "3",
                 "--wall-k-kn-mm", "1500", "--dt", str(DT), "--workers", "1", "--quiet",
                 "--out", str(out)])
    assert code == 0, capsys.readouterr().err
    with xr.open_dataset(out) as ds:
        np.testing.assert_allclose(ds.gap, [0.06, 0.10])
        assert ds.thickness.item() == pytest.approx(0.03) and ds.wall_k.item() == 1.5e9
        assert list(ds.record.values) == ["PULSE_A"]
    capsys.readouterr()

    code = main(["--records", str(at2), "--gap", "0.05", "--thickness", "0.05",
                 "--out", str(tmp_path / "bad.nc")])
    err = capsys.readouterr().err
    assert code == 2 and err.startswith("error: thickness") and err.count("\n") == 1
    help_text = subprocess.run([sys.executable, "-m", "studies.sweep", "--help"], cwd=PROJECT,
                               capture_output=True, text=True).stdout
    for option in ("--gap-cm", "--wall-k-kn-mm", "--baseline", "--unconstrained", "--workers",
                   "--scheduler", "--quiet", "N/m"):
        assert option in help_text


# --------------------------------------------------------------------------- --history

def test_history_keeps_the_time_histories_of_chosen_configurations(tmp_path, capsys):
    """Issue 40: time histories from the command line. --history writes <archive>.histories.nc
    beside the archive; a configuration that is one of the sweep's members has its peaks,
    bit for bit (the engine's result does not depend on the batch), and histories whose largest
    |u| is at most that peak."""
    from studies import sweep as cli

    out = tmp_path / "x.nc"
    assert cli.main(["--records", "pacoima", "--gap", "0.2", "0.3", "--dt", "0.002",
                     "--history", "gap=0.2", "--history", "gap=0.3,n_bumpers=8",
                     "--quiet", "--out", str(out)]) == 0
    assert "(the time histories of gap=0.2; gap=0.3,n_bumpers=8)" in capsys.readouterr().out
    with xr.open_dataset(out) as swept, \
            xr.open_dataset(tmp_path / "x.histories.nc") as kept:
        assert kept.configuration.values.tolist() == ["gap=0.2", "gap=0.3,n_bumpers=8"]
        peak = kept.peak_isolator_disp.sel(configuration="gap=0.2").values.ravel()
        assert peak.tobytes() == swept.peak_isolator_disp.sel(gap=0.2).values.ravel().tobytes()
        assert kept.isolator_disp.attrs["units"] == "m"
        u = np.abs(kept.isolator_disp.sel(configuration="gap=0.2")).max("time").values.ravel()
        assert np.all(u <= peak) and np.all(u > 0.9 * peak)


@pytest.mark.parametrize("extra, said", [
    (["--history", "gap"], "--history gap: give NAME=VALUE"),
    (["--history", "gap=0.2,colour=3"], "unknown parameter(s) ['colour']"),
    (["--history", "gap=0.2", "--moat", "rectangular"], "--history keeps the time histories "
                                                        "of planar sweeps"),
])
def test_a_history_the_sweep_cannot_keep_is_refused_before_compute(extra, said, tmp_path,
                                                                   capsys):
    from studies import sweep as cli

    out = tmp_path / "x.nc"
    assert cli.main(["--records", "pacoima", "--gap", "0.2", *extra, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and said in err, err
    assert not out.exists() and not list(tmp_path.iterdir())


def test_an_archive_of_another_sweep_is_refused_with_the_command_lines_options(tmp_path,
                                                                               capsys):
    from studies import sweep as cli

    out = ["--out", str(tmp_path / "x.nc"), "--quiet", "--records", "pacoima", "--dt", "0.004"]
    assert cli.main([*out, "--gap", "0.2"]) == 0
    kept = (tmp_path / "x.nc").read_bytes()
    capsys.readouterr()
    assert cli.main([*out, "--gap", "0.3"]) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]  # after the coarse step's warning
    assert err.startswith("error: ") and "Give --force to replace it, or another --out" in err
    assert "force=True" not in err and (tmp_path / "x.nc").read_bytes() == kept


def test_more_bumpers_than_a_wall_holds_are_refused_and_the_advice_runs(tmp_path, capsys,
                                                                        monkeypatch):
    """Issue 40: `--n-bumpers 1000` on one wall ran. Now refused before compute in one line
    giving the most 150 mm pads an 18 m wall holds; that count, as advised, runs and a wall of
    them stays a plausible wall (impacts, a finite peak)."""
    from studies import sweep as cli
    from tests.pipeline.small_sweep import no_compute

    at2 = tmp_path / "PULSE_A.AT2"
    write_at2(at2, RECORDS[0])
    out = tmp_path / "x.nc"
    common = ["--records", str(at2), "--gap", "0.06", "--thickness", "0.03", "--dt", str(DT),
              "--quiet", "--out", str(out)]
    with monkeypatch.context() as nothing_runs:
        no_compute(nothing_runs)
        assert cli.main([*common, "--n-bumpers", "4", "1000"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "need 300 m of moat wall" in err, err
    assert "give at most 60 bumpers a side" in err and not out.exists()
    assert cli.main([*common, "--n-bumpers", "4", "60"]) == 0
    with xr.open_dataset(out) as ds:
        assert ds.n_bumpers.values.tolist() == [4, 60] and np.all(ds.n_impacts > 0)
        assert np.all(np.isfinite(ds.peak_isolator_disp)) and np.all(ds.peak_isolator_disp > 0)
