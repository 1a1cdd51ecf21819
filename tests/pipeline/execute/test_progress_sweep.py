"""The sweep's progress bar (pipeline/execute/progress.py): counts and time left, a running
batch's partial work, nothing guessed before a batch finished, whole lines in a log, silence
when quiet."""
import io

from pipeline.execute import progress as progress_module


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
