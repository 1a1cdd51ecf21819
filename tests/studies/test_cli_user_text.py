"""What a user reads (issue 30): the program named as it was run, help texts with units in the
paper's spelling and no internal references, and a progress line that stays within 0-100%,
never shows a negative time left and is one line a run."""
from __future__ import annotations

import io
import re
import subprocess
import sys
from pathlib import Path

import pytest

from engine.parameters import unit_text, user_text
from pipeline.execute.progress import Progress, percent, progress_line
from studies import cli

PROJECT = Path(__file__).resolve().parents[2]
INTERNAL = ("SPEC", "tests/", "../shared", "^(-")
"""What no help text may show: the project's specification, test files, shared folders, and
units in UDUNITS' spelling of a fractional power (N m^(-1.5): the paper writes N/m^1.5)."""


def _help(capsys, *argv: str) -> str:
    assert cli.main(list(argv)) == 0
    return capsys.readouterr().out


def test_bumpers_names_the_command_as_typed(capsys):
    assert _help(capsys, "sweep", "--help").startswith("usage: bumpers sweep")
    assert _help(capsys, "gap_size", "--help").startswith("usage: bumpers gap_size")
    assert cli.main(["sweep", "--bogus"]) == 2
    assert capsys.readouterr().err.startswith("bumpers sweep: error:")
    # the name holds while bumpers runs the command only
    assert cli.program("studies.sweep") == "python -m studies.sweep"


@pytest.mark.parametrize("argv, usage", [
    (["-m", "studies.cli", "sweep", "--help"], "usage: bumpers sweep"),
    (["-m", "studies.sweep", "--help"], "usage: python -m studies.sweep"),
])
def test_the_program_name_follows_how_it_was_run(argv, usage):
    out = subprocess.run([sys.executable, *argv], cwd=PROJECT, capture_output=True, text=True,
                         check=True).stdout
    assert out.startswith(usage)


def test_no_help_text_shows_internal_references_or_raw_units(capsys):
    texts = {"bumpers": _help(capsys, "--help")}
    for command in cli.commands():
        texts[command.name] = _help(capsys, command.name, "--help")
    for name, text in texts.items():
        found = [word for word in INTERNAL if word in text]
        assert not found, f"bumpers {name} --help shows {found}"
    sweep = texts["sweep"]
    assert "N/m^1.5" in sweep and "N m-1" not in sweep and "N/m," in sweep
    assert "N/m^1.5, N/m^1.5" not in sweep  # a unit said once


def test_units_in_the_papers_spelling():
    assert unit_text("N m-1") == "N/m"
    assert unit_text("N m^(-1.5)") == "N/m^1.5"
    assert unit_text("m s-2") == "m/s^2"
    assert unit_text("s m-1") == "s/m"
    assert unit_text("1") == "" and unit_text("kN/mm") == "kN/mm"
    assert user_text("stiffness beta, N m^(-1.5)") == "stiffness beta, N/m^1.5"
    # words and record names are not units
    for text in ("RSN<n>:H1, A.AT2+B.AT2", "ASCE 7-22 ch. 17, Figs. 9-13", "16-84% band"):
        assert user_text(text) == text


def test_internal_references_in_plain_words():
    assert user_text("against an immovable wall (SPEC decision)") == \
        "against an immovable wall (a value chosen here: the paper does not state it)"
    assert user_text("SPEC section 1") == ""  # a reference to it alone: dropped
    assert user_text("(halving it moves no peak by 0.5%; tests/engine/test_x.py): peaks") == \
        "(halving it moves no peak by 0.5%): peaks"
    assert user_text("Eq. 11") == "Eq. 11" and user_text("ASCE 7-22 17.3") == "ASCE 7-22 17.3"


LINE = re.compile(r"(\w+): +(\d+)% done \((\d+) of (\d+) (.+) finished(, others under way)?\), "
                  r"(\S+) elapsed, (time left: once the first finishes|~(\S+) left)")


@pytest.mark.parametrize("total", [0, 1, 7, 10, 22, 8000])
@pytest.mark.parametrize("elapsed", [0.0, 1e-3, 5.0, 3600.0, 1e6, -1.0])
def test_the_line_stays_within_0_100_and_never_negative(total, elapsed):
    counts = sorted({*range(0, total + 1, max(total // 50, 1)), total, total + 3})
    for finished in counts:
        for running in (0.0, 0.4, total * 0.08, total * 1.2):
            for start in (0, total // 2):
                line = progress_line("sweep", "simulations", total, finished,
                                     finished + running, elapsed, start)
                m = LINE.fullmatch(line)
                assert m, line
                shown, whole = int(m[2]), int(m[3])
                assert 0 <= shown <= 100 and whole <= total and int(m[4]) == total, line
                # consistent with the counts: at least the finished share, 100 only when all
                assert shown >= (100 * whole // total if total else 100), line
                assert (shown == 100) == (whole == total), line
                assert "-" not in m[7] + (m[9] or ""), line


def test_percent_rounds_down_until_all_finished():
    assert percent(9.96, 9, 10) == 99 and percent(10, 10, 10) == 100
    assert percent(0.08 * 8000, 0, 8000) == 8
    assert percent(11, 11, 10) == 100 and percent(-1, -1, 10) == 0


def test_a_log_gets_a_line_every_10_percent():
    """22 batches (studies.fragility: one a record pair): about ten lines, not 22."""
    stream = io.StringIO()
    progress = Progress(total=22 * 36, stream=stream, delay=0.0)
    for batch in range(22):
        for step in range(1, 11):
            progress.running(batch, 36 * step / 10)
        progress.advance(36, batch)
    progress.close()
    lines = stream.getvalue().splitlines()
    shown = [int(LINE.fullmatch(line)[2]) for line in lines]
    assert "\r" not in stream.getvalue() and len(lines) <= 12
    assert shown == sorted(shown) and shown[-1] == 100
    assert len({value // 10 for value in shown}) == len(shown)  # one line per 10% step


class Terminal(io.StringIO):
    def isatty(self):
        return True


def test_a_terminal_gets_one_line_redrawn_in_place():
    stream = Terminal()
    progress = Progress(total=10, stream=stream, delay=0.0)
    progress.every = 0.0  # redraw at every report
    for n in range(10):
        progress.running(n, 0.5)
        progress.advance(1, n)
    progress.close()
    text = stream.getvalue()
    assert text.count("\n") == 1 and text.endswith("\n") and text.count("\r") > 10
    assert text.rsplit("\r", 1)[1].startswith("sweep: 100% done (10 of 10")


def test_bumpers_records_names_itself_so(capsys):
    assert cli.main(["records", "--help"]) == 0
    assert capsys.readouterr().out.startswith("usage: bumpers records")
    import os

    assert "BUMPERS_PROGRAM" not in os.environ  # set only while the command runs
