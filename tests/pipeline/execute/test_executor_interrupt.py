"""Ctrl-C and kill -9: a recipe stops within seconds with one line saying what is kept (Ctrl-C)
or with nothing said (SIGKILL), and the same command again computes only the rest and writes
a byte-identical archive. The recipe: fragility, the code-scaled pairs in plan at intensity
levels (pipeline.sweep with levels and record factors), a study beyond the paper."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

PROJECT = Path(__file__).resolve().parents[3]
# Three short pairs, the quick grid (3 levels x (no wall + 3 gaps x (bare wall, 4 and 32
# bumpers)) = 30 members a pair) at a fine step so that each pair's batch takes half a second
# or more: long enough to be stopped, short enough for five runs of the recipe.
COMMAND = [sys.executable, "-m", "studies.fragility", "--records", "RSN1148", "RSN848",
           "RSN725", "--dt", "1e-4", "--quick"]
MEMBERS = 3 * (1 + 3 * 3)
ARCHIVE = Path("quick") / "fragility.nc"


def _env():
    return {**os.environ, "SOURCE_DATE_EPOCH": "1700000000", "NUMBA_NUM_THREADS": "2"}


def _interruptible():
    """In the recipe's process before it starts: Ctrl-C at its default. A shell starts a
    background job (CI's `... &`, nohup) with SIGINT ignored, and a child inherits that: Python
    then installs no KeyboardInterrupt handler, and the recipe would run to its end."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _run(out: Path, timeout: float = 600) -> subprocess.CompletedProcess:
    return subprocess.run([*COMMAND, "--out", str(out), "--quiet"], cwd=PROJECT, env=_env(),
                          capture_output=True, text=True, timeout=timeout)


@pytest.fixture(scope="module")
def whole(tmp_path_factory) -> bytes:
    """The archive of an uninterrupted run."""
    out = tmp_path_factory.mktemp("whole")
    done = _run(out)
    assert done.returncode == 0, done.stderr
    return (out / ARCHIVE).read_bytes()


def _stopped(parts: Path, sig: int) -> tuple[int, str, float]:
    """Start the recipe, send `sig` once its first batch is kept; (exit status, stderr,
    seconds it took to stop)."""
    work = parts / "quick" / "fragility.nc.work"
    proc = subprocess.Popen([*COMMAND, "--out", str(parts), "--quiet"], cwd=PROJECT,
                            env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, preexec_fn=_interruptible)
    deadline = time.monotonic() + 300
    while not list(work.glob("*.npz")):  # the first pair's batch is kept
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline
        time.sleep(0.05)
    sent = time.monotonic()
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    return proc.returncode, err, time.monotonic() - sent


@pytest.mark.slow
def test_interrupted_recipe_resumes_to_the_same_bytes(tmp_path, whole):
    parts = tmp_path / "parts"
    work = parts / "quick" / "fragility.nc.work"
    status, err, stopped = _stopped(parts, signal.SIGINT)
    assert status == 130, err
    assert stopped < 3.0
    (line,) = err.strip().splitlines()  # one line, no traceback
    assert line.startswith("fragility: interrupted: ")
    assert f"kept in {work}; run the same command again to resume" in line
    kept, total = (int(x) for x in line.split(": interrupted: ")[1].split(" simulations")[0]
                   .split(" of "))
    assert 0 < kept < total and total == 3 * MEMBERS
    assert not (parts / ARCHIVE).exists()

    resumed = _run(parts)
    assert resumed.returncode == 0, resumed.stderr
    assert not work.exists()
    assert (parts / ARCHIVE).read_bytes() == whole


@pytest.mark.slow
def test_killed_recipe_resumes_to_the_same_bytes(tmp_path, whole):
    parts = tmp_path / "parts"
    status, _, _ = _stopped(parts, signal.SIGKILL)
    assert status == -signal.SIGKILL
    assert not (parts / ARCHIVE).exists()
    kept = list((parts / "quick" / "fragility.nc.work").glob("*.npz"))
    assert 0 < len(kept) < 3  # some pairs kept, not all

    resumed = _run(parts)
    assert resumed.returncode == 0, resumed.stderr
    assert (parts / ARCHIVE).read_bytes() == whole
