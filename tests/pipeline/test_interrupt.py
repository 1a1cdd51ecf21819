"""Ctrl-C: a recipe stops within seconds with one line saying what is kept, and the same
command again computes only the rest and writes a byte-identical archive."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

PROJECT = Path(__file__).resolve().parents[2]
# Three records, longest first, the quick grid (21 members a record) at a fine step so that
# each record's batch takes a quarter of a second or more: long enough to be interrupted,
# short enough for three runs of the recipe.
COMMAND = [sys.executable, "-m", "studies.n_bumpers", "--records", "kobe", "sylmar_converter",
           "pacoima", "--dt", "1e-4", "--quick"]
MEMBERS = 4 * 4 + 4 + 1  # quick grid: 4 gaps x 4 counts, 4 gaps of bare wall, 1 without wall


def _env():
    return {**os.environ, "SOURCE_DATE_EPOCH": "1700000000", "NUMBA_NUM_THREADS": "2"}


def _run(out: Path, timeout: float = 600) -> subprocess.CompletedProcess:
    return subprocess.run([*COMMAND, "--out", str(out), "--quiet"], cwd=PROJECT, env=_env(),
                          capture_output=True, text=True, timeout=timeout)


@pytest.mark.slow
def test_interrupted_recipe_resumes_to_the_same_bytes(tmp_path):
    whole = tmp_path / "whole"
    assert _run(whole).returncode == 0

    parts = tmp_path / "parts"
    work = parts / "quick" / "n_bumpers.nc.work"
    proc = subprocess.Popen([*COMMAND, "--out", str(parts), "--quiet"], cwd=PROJECT,
                            env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    deadline = time.monotonic() + 300
    while not list(work.glob("*.npz")):  # the first record's batch is kept
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline
        time.sleep(0.05)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    stopped = time.monotonic() - sent
    assert proc.returncode == 130, err
    assert stopped < 3.0
    (line,) = err.strip().splitlines()  # one line, no traceback
    assert line.startswith("n_bumpers: interrupted: ")
    assert f"kept in {work}; run the same command again to resume" in line
    kept, total = (int(x) for x in line.split(": interrupted: ")[1].split(" simulations")[0]
                   .split(" of "))
    assert 0 < kept < total and total == 3 * MEMBERS
    assert not (parts / "quick" / "n_bumpers.nc").exists()

    resumed = _run(parts)
    assert resumed.returncode == 0, resumed.stderr
    assert not work.exists()
    assert (parts / "quick" / "n_bumpers.nc").read_bytes() \
        == (whole / "quick" / "n_bumpers.nc").read_bytes()
