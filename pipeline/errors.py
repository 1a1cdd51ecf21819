"""The pipeline's error for bad sweep input, and the small input checks that raise it."""
from __future__ import annotations

import operator


class SweepError(ValueError):
    """Invalid sweep input; the message names the offending parameter."""


def check_count(name: str, value, minimum: int) -> int:
    """`value` as an int >= minimum, or SweepError naming it."""
    try:
        count = operator.index(value)
    except TypeError:
        raise SweepError(f"{name} must be a whole number, got {value!r}") from None
    if count < minimum:
        raise SweepError(f"{name} must be >= {minimum}, got {count}")
    return count


class ClusterError(SweepError):
    """A dask cluster that cannot run the sweep; the message names the cause and the fix."""


class Interrupted(KeyboardInterrupt):
    """A run stopped by the user (Ctrl-C, SIGINT) after saving what was finished.

    kept: simulations stored in the work folder (those found from earlier runs included);
    total: simulations of the run; work_dir: the folder (None: nothing is kept).
    """

    def __init__(self, kept: int, total: int, work_dir=None):
        self.kept, self.total, self.work_dir = kept, total, work_dir
        where = f"kept in {work_dir}" if work_dir is not None else "kept nowhere (no work folder)"
        super().__init__(f"interrupted: {kept} of {total} simulations {where}")

    def __str__(self) -> str:
        return self.args[0]
