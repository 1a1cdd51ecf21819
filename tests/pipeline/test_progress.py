"""The progress line (pipeline.progress, issue 30): counts and time left, a running
batch's partial work, nothing guessed before a batch finished, silence when quiet; within
0-100%, never a negative time left, one line a run (a log a line every 10%, a terminal one
line redrawn in place).
(A lost dask worker's reports: test_progress_worker_loss.py.)"""
from __future__ import annotations

import io
import re

import pytest

from pipeline import progress as progress_module
from pipeline.progress import Progress, percent, progress_line

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


def test_progress_bar_shows_counts_and_time_left():
    stream = io.StringIO()
    progress = progress_module.Progress(total=10, done=2, stream=stream, delay=0.0)
    progress.advance(3)
    progress.close()
    text = stream.getvalue()
    assert " 50% done (5 of 10 simulations finished)" in text and "left" in text
    # a running batch's partial work moves the percentage, never the count of finished ones
    partial = io.StringIO()
    progress = progress_module.Progress(total=10, stream=partial, delay=0.0)
    progress.running("batch", 1.4)
    progress.close()
    assert " 14% done (0 of 10 simulations finished, others under way)" in partial.getvalue()
    # no time left is guessed before anything finished (the kernel may be compiling)
    assert "time left: once the first finishes" in partial.getvalue()
    assert "~" not in partial.getvalue()
    # a log file gets whole lines, never a carriage return
    assert "\r" not in text + partial.getvalue() and text.endswith("\n")
    quiet = io.StringIO()
    progress_module.Progress(total=10, quiet=True, stream=quiet, delay=0.0).close()
    assert quiet.getvalue() == ""
