"""The progress line of a run: 'done/total simulations, elapsed, time left' on stderr."""
from __future__ import annotations

import math
import sys
import threading
import time


class Progress:
    """'done/total simulations, elapsed, time left' on stderr, once a run passes `delay` s.

    On a terminal one line redrawn in place; in a log file (stderr not a terminal) a whole
    line every `every` s, never a carriage return. No time left is guessed before something
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
        self.every = 0.5 if self.tty else 10.0  # a log file gets a line now and then
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
        if self.quiet or elapsed < self.delay or (not final and now - self.last < self.every):
            return
        # Never past the total, so never a negative time left, whatever a caller counts.
        finished = min(self.done, self.total)
        done = min(finished + sum(self.partial.values()), self.total)
        rate = (done - self.start_done) / elapsed
        if finished > self.start_done and rate > 0:
            left = f"~{_clock((self.total - done) / rate)} left"
        else:
            left = "time left: once the first finishes"
        line = (f"{self.label}: {100 * done / max(self.total, 1):3.0f}% ({int(finished)} of "
                f"{self.total} {self.unit} finished), {_clock(elapsed)} elapsed, {left}")
        if final and line == self.last_line and not self.tty:
            return  # already said
        self.last, self.last_line = now, line
        end = "\n" if final or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + line + end)
        self.stream.flush()


def _clock(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "?"
    minutes, sec = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours}:{minutes:02d}:{sec:02d}" if hours else f"{minutes}:{sec:02d}"
