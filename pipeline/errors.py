"""The pipeline's errors: bad input, an unfit cluster, a run interrupted, a command's reader
gone. A leaf: it imports nothing of the project, so that every module can raise them (the checks
that raise them: checks.py)."""
from __future__ import annotations

import os
import sys

CLOSED_PIPE_STATUS = 141
"""A command's exit status when its output's reader has gone (`bumpers | head`): a shell's for
a command a closed pipe ended, 128 + SIGPIPE (13)."""


def closed_pipe() -> int:
    """What a command does on BrokenPipeError (its output's reader gone, as `| head` does once
    it has its lines): say nothing more, point standard output at os.devnull so that Python's
    flush at exit cannot fail on it again (the Python documentation's recipe, signal module:
    'Note on SIGPIPE'), and return CLOSED_PIPE_STATUS."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (AttributeError, OSError, ValueError):  # an output with no descriptor: nothing held
        pass
    return CLOSED_PIPE_STATUS


class SweepError(ValueError):
    """Invalid sweep input; the message names the offending parameter.

    command_line: the same message for a user of the commands, where its advice names an
    option as the command line spells it (`--force`) rather than as Python does
    (`force=True`); the message itself when not given (see `said`)."""

    def __init__(self, message: str = "", command_line: str | None = None):
        super().__init__(message)
        self.command_line = message if command_line is None else command_line


def said(err: Exception) -> str:
    """An error's message for a command's one line: a SweepError's command-line wording, any
    other error's message, white space collapsed."""
    return " ".join(str(getattr(err, "command_line", None) or err).split())


class PlausibilityWarning(UserWarning):
    """Valid input that may not give what was meant (e.g. a step coarser than the converged
    one); raised before any compute, shown by the commands as one 'warning: ...' line."""


class KeptWorkNotice(UserWarning):
    """A finished run's work folder still holds simulations of another configuration (a run
    interrupted, then run with other options): kept, not deleted, and said in one line."""


class BuildingError(SweepError):
    """A building file or setting that does not describe a building; the message names the
    key and what it expects."""


class ClusterError(SweepError):
    """A dask cluster that cannot run the sweep; the message names the cause and the fix."""


class Interrupted(KeyboardInterrupt):
    """A run stopped by the user (Ctrl-C, SIGINT) after saving what was finished.

    kept: simulations stored (those found from earlier runs included); total: simulations of
    the run; work_dir: where they are kept, the work folder of a NetCDF run or the Zarr store
    (None: nothing is kept).
    """

    def __init__(self, kept: int, total: int, work_dir=None):
        self.kept, self.total, self.work_dir = kept, total, work_dir
        where = f"kept in {work_dir}" if work_dir is not None else "kept nowhere (no work folder)"
        super().__init__(f"interrupted: {kept} of {total} simulations {where}")

    def __str__(self) -> str:
        return self.args[0]
