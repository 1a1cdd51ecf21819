"""What a lost dask worker does to the progress line: a batch's last report reaching the client
after its result, a batch run again from the start on another worker, a result computed twice.
The line counts each batch once and never passes 100% nor shows a negative time left. (The
cluster itself, with workers killed mid-run: test_cluster.py.)"""
from __future__ import annotations

import io
import re

from pipeline.progress import Progress

LINE = re.compile(r"sweep: +(\d+)% done \((\d+) of 10 simulations finished"
                  r"(?:, others under way)?\), \S+ elapsed, (.*)")


def test_a_batch_counts_once_whatever_its_reports():
    stream = io.StringIO()
    progress = Progress(total=10, stream=stream, delay=0.0)
    progress.step = 0.0  # a line for every report (not every 10%)
    progress.running("a", 3.0)  # batch a (4 simulations) three quarters done...
    progress.running("a", 0.4)  # ...its worker died: a runs again, from the start
    assert progress.partial == {"a": 0.4}
    progress.advance(4, "a")
    progress.running("a", 4.0)  # a's last report, after its result
    progress.advance(4, "a")  # a's result again (computed twice)
    assert progress.done == 4 and progress.partial == {}
    progress.running("b", 5.9)
    progress.advance(6, "b")
    progress.close()
    lines = [LINE.fullmatch(line) for line in stream.getvalue().splitlines()]
    # (percent, finished): a line for each report counted; those ignored draw none
    assert [(int(m[1]), int(m[2])) for m in lines] == [(30, 0), (4, 0), (40, 4), (99, 4),
                                                       (100, 10)]
    assert all("-" not in m[3] for m in lines) and lines[-1][3] == "~0:00 left"


def test_the_line_stays_within_the_total():
    """Whatever a caller counts: at most 100%, never a negative time left."""
    stream = io.StringIO()
    progress = Progress(total=10, stream=stream, delay=0.0)
    progress.advance(9)
    progress.running("c", 3.0)
    progress.advance(3)
    progress.close()
    last = LINE.fullmatch(stream.getvalue().splitlines()[-1])
    assert last[1] == "100" and last[2] == "10" and last[3] == "~0:00 left"
