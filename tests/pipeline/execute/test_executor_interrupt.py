"""Ctrl-C and kill -9: a recipe stops within seconds with one line saying what is kept (Ctrl-C)
or with nothing said (SIGKILL), and the same command again computes only the rest and writes
a byte-identical archive. The recipe: fragility, the code-scaled pairs in plan at intensity
levels (pipeline.sweep with levels and record factors), a study beyond the paper.

One sequence serves both tests: the command killed once it has kept its first pair, the same
command again interrupted once it has kept one pair more (it resumed from what the killed run
kept), and the same command a third time, to its end. The last run reads the batches of both
stopped runs; its archive is compared with an uninterrupted run's."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from tests.helpers import wait_until

PROJECT = Path(__file__).resolve().parents[3]
# Three short pairs, the quick grid (3 levels x (no wall + 3 gaps x (bare wall, 4 and 32
# bumpers)) = 30 members a pair) at a fine step so that each pair's batch takes half a second
# or more: long enough to be stopped, short enough for four runs of the recipe.
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


def _work(parts: Path) -> Path:
    return parts / "quick" / "fragility.nc.work"


def _stopped(parts: Path, sig: int, already: int = 0) -> tuple[int, str]:
    """Start the recipe, send `sig` once it has kept a pair beyond the `already` kept in
    `parts`; (exit status, stderr)."""
    work = _work(parts)
    proc = subprocess.Popen([*COMMAND, "--out", str(parts), "--quiet"], cwd=PROJECT,
                            env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, preexec_fn=_interruptible)
    def running():
        assert proc.poll() is None, proc.communicate()

    wait_until(lambda: len(list(work.glob("*.npz"))) > already,  # a pair of its own kept
               "a pair kept", check=running)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)  # a guard against a hang, not a speed check
    return proc.returncode, err


@pytest.fixture(scope="module")
def killed(tmp_path_factory) -> dict:
    """The command killed (SIGKILL) once its first pair is kept: its folder, exit status, the
    batches it kept and whether an archive was there."""
    parts = tmp_path_factory.mktemp("parts")
    status, _ = _stopped(parts, signal.SIGKILL)
    return {"parts": parts, "status": status, "kept": sorted(_work(parts).glob("*.npz")),
            "archive": (parts / ARCHIVE).exists()}


@pytest.fixture(scope="module")
def interrupted(killed) -> dict:
    """The same command again in the killed run's folder, interrupted (Ctrl-C) once it has
    kept one pair more: its exit status, stderr, the batches then in the work folder and
    whether an archive was there."""
    parts = killed["parts"]
    status, err = _stopped(parts, signal.SIGINT, already=len(killed["kept"]))
    return {"status": status, "err": err,
            "kept": sorted(_work(parts).glob("*.npz")), "archive": (parts / ARCHIVE).exists()}


@pytest.fixture(scope="module")
def resumed(killed, interrupted) -> bytes:
    """The same command a third time, in the same folder, to its end: the archive's bytes."""
    parts = killed["parts"]
    done = _run(parts)
    assert done.returncode == 0, done.stderr
    assert not _work(parts).exists()
    return (parts / ARCHIVE).read_bytes()


@pytest.mark.slow
def test_interrupted_recipe_resumes_to_the_same_bytes(killed, interrupted, resumed, whole):
    work = _work(killed["parts"])
    # Ctrl-C stops the run where it is (kept < total below, no archive), not at its end
    assert interrupted["status"] == 130, interrupted["err"]
    (line,) = interrupted["err"].strip().splitlines()  # one line, no traceback
    assert line.startswith("fragility: interrupted: ")
    assert f"kept in {work}; run the same command again to resume" in line
    kept, total = (int(x) for x in line.split(": interrupted: ")[1].split(" simulations")[0]
                   .split(" of "))
    assert 0 < kept < total and total == 3 * MEMBERS
    # the killed run's pairs counted among those kept, one more of its own
    assert len(killed["kept"]) < len(interrupted["kept"]) < 3
    assert kept == MEMBERS * len(interrupted["kept"])
    assert not interrupted["archive"]
    assert resumed == whole


@pytest.mark.slow
def test_killed_recipe_resumes_to_the_same_bytes(killed, resumed, whole):
    assert killed["status"] == -signal.SIGKILL
    assert not killed["archive"]
    assert 0 < len(killed["kept"]) < 3  # some pairs kept, not all
    assert resumed == whole
