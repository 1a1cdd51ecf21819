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
