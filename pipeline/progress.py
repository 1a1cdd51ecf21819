"""The progress line of a run on stderr, e.g.
    sweep: 40% done (4 of 10 simulations finished, others under way), 0:12 elapsed, ~0:18 left
"""
from __future__ import annotations

import math
import sys
import threading
import time


class Progress:
    """'done/total simulations, elapsed, time left' on stderr, once a run passes `delay` s.

    On a terminal one line redrawn in place (at most every `every` s); in a log file (stderr
    not a terminal) a whole line each time the run passes another `step` percent (10: about
    ten lines a run), never a carriage return, and the last line once. The percentage counts
    the work of the simulations under way as well (a batch's simulations run together and
    finish together), so the line says when some are under way; it stays within 0-100 and is
    100 only once all have finished. No time left is guessed before something
    has finished in this run: until then the kernel may still be compiling. label: what is
    running ("sweep", "scaling"); unit: what total counts. Thread-safe: dask reports running
    batches from the client's event-loop thread.

    A batch's reports may come late, or twice: a dask worker's last report can reach the client
    after the batch's result, and a batch runs again from the start when the worker running it
    dies. So a batch counts once, when first finished, its later reports ignored; a running
    batch's latest report replaces its earlier ones; and the line never shows more than the
    total, nor a negative time left.
    """

    def __init__(self, total: int, done: int = 0, quiet: bool = False, stream=None,
                 delay: float = 2.0, label: str = "sweep", unit: str = "simulations"):
        self.label, self.unit = label, unit
        self.total, self.done = total, done
        self.start_done = done
        self.partial: dict = {}  # running batch -> simulations' worth done
        self.finished: set = set()  # batches counted in done
        self.quiet = quiet
        self.stream = sys.stderr if stream is None else stream
        self.tty = getattr(self.stream, "isatty", lambda: False)()
        self.delay = delay
        self.every = 0.5  # a terminal's redraws
        self.step = 10.0  # a log file's lines: one per `step` percent
        self.next_percent = -math.inf  # a log file's next line: once the run passes it
        self.t0 = time.monotonic()
        self.last = -math.inf
        self.last_line = ""
        self.lock = threading.Lock()

    def advance(self, n: int, batch=None) -> None:
        """n more simulations finished: those of `batch` (counted once, whatever the calls),
        or, batch None, n of no batch in particular."""
        with self.lock:
            if batch is not None:
                if batch in self.finished:
                    return
                self.finished.add(batch)
                self.partial.pop(batch, None)
            self.done += n
            self._draw()

    def running(self, batch, n: float) -> None:
        """`batch` has done n simulations' worth so far (since it last started: after a run
        again, less than before); nothing once it finished."""
        with self.lock:
            if batch in self.finished:
                return
            self.partial[batch] = n
            self._draw()

    def close(self) -> None:
        with self.lock:
            self._draw(final=True)

    def interrupted(self) -> None:
        """End a bar left open on a terminal, so the next line starts clean."""
        with self.lock:
            if self.tty and self.last_line and not self.quiet:
                self.stream.write("\n")
                self.stream.flush()
            self.quiet = True

    def _draw(self, final: bool = False) -> None:
        now = time.monotonic()
        elapsed = now - self.t0
        if self.quiet or elapsed < self.delay:
            return
        # Never past the total, so never a negative time left, whatever a caller counts.
        finished = min(self.done, self.total)
        done = min(max(finished + sum(self.partial.values()), finished), self.total)
        if not final:
            if self.tty and now - self.last < self.every:
                return
            if not self.tty and percent(done, finished, self.total) < self.next_percent:
                return
        line = progress_line(self.label, self.unit, self.total, finished, done, elapsed,
                             self.start_done)
        if final and line == self.last_line and not self.tty:
            return  # already said
        self.last, self.last_line = now, line
        if self.step > 0:
            reached = percent(done, finished, self.total)
            self.next_percent = (reached // self.step + 1) * self.step
        end = "\n" if final or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + line + end)
        self.stream.flush()


def percent(done: float, finished: int, total: int) -> int:
    """The whole percentage of the work done: rounded down, within 0-100, 100 only when all
    `total` have finished (done: the work, those under way included; finished: those whole)."""
    if total <= 0:
        return 100
    whole = math.floor(100 * min(max(done, finished, 0), total) / total)
    return 100 if finished >= total else min(max(whole, 0), 99)


def progress_line(label: str, unit: str, total: int, finished: int, done: float,
                  elapsed: float, start_done: float = 0) -> str:
    """The progress line: 'sweep: 40% done (4 of 10 simulations finished, others under way),
    0:12 elapsed, ~0:18 left'. finished: whole ones; done: the work, those under way included
    (the percentage's); start_done: the work already done when this run started (a resumed
    run), not counted in its rate. Counts are clipped to 0..total, so the percentage stays
    within 0-100 and the time left is never negative."""
    total = max(int(total), 0)
    finished = min(max(int(finished), 0), total)
    done = min(max(float(done), finished), total)
    elapsed = max(float(elapsed), 0.0)
    rate = (done - start_done) / elapsed if elapsed > 0 else 0.0
    if finished >= total:
        left = "~0:00 left"
    elif finished > start_done and rate > 0:
        left = f"~{_clock((total - done) / rate)} left"
    else:
        left = "time left: once the first finishes"
    under_way = ", others under way" if done > finished else ""
    return (f"{label}: {percent(done, finished, total):3d}% done ({finished} of {total} {unit} "
            f"finished{under_way}), {_clock(elapsed)} elapsed, {left}")


def _clock(seconds: float) -> str:
    """'1:02:03' or '2:03' for a duration in s (never negative), '?' for no finite one."""
    if not math.isfinite(seconds):
        return "?"
    seconds = max(seconds, 0.0)
    minutes, sec = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}:{minutes:02d}:{sec:02d}" if hours else f"{minutes}:{sec:02d}"
