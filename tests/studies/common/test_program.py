"""The program named as it was run (studies/common/program.py): python -m studies.cli,
bumpers, python -m studies.sweep each in its usage line."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

PROJECT = Path(__file__).resolve().parents[3]


@pytest.mark.parametrize("argv, usage", [
    (["-m", "studies.cli", "sweep", "--help"], "usage: bumpers sweep"),
    (["-m", "studies.sweep", "--help"], "usage: python -m studies.sweep"),
])
def test_the_program_name_follows_how_it_was_run(argv, usage):
    out = subprocess.run([sys.executable, *argv], cwd=PROJECT, capture_output=True, text=True,
                         check=True).stdout
    assert out.startswith(usage)
