"""How the runs that collapsed ended, counted by mode: a story's drift past its collapse drift,
the isolator past its displacement capacity, or a numerical instability (engine.results'
COLLAPSE_MODES, the codes 1, 2, 3 of each run's `collapse_mode`; 0 where it did not collapse),
as the numbers and the text every summary that counts collapses states. Pure functions of the
codes."""
from __future__ import annotations

import numpy as np

from engine.results import COLLAPSE_MODES

MODES = COLLAPSE_MODES[1:]
"""The modes a collapse can have, in the order of their codes 1, 2, ... (COLLAPSE_MODES less
"none")."""


def mode_counts(mode, axis=None) -> np.ndarray:
    """(len(MODES), ...) int64: how many runs collapsed by each mode. mode: the runs' codes
    (any shape, engine.results.COLLAPSE_MODES: 0 none, 1 story drift, 2 isolator capacity, 3
    numerical instability); counted over `axis` (None: every run, giving (len(MODES),); an int
    or a tuple: those axes, the others kept). ValueError for a code that is not a mode's."""
    codes = np.asarray(mode)
    if codes.size and (codes.min() < 0 or codes.max() > len(MODES)):
        raise ValueError(f"collapse_mode codes are 0 to {len(MODES)} (engine.results."
                         f"COLLAPSE_MODES), got {codes.min()} to {codes.max()}")
    return np.stack([np.sum(codes == code, axis=axis) for code in range(1, len(MODES) + 1)])


def collapse_numbers(mode) -> dict[str, int]:
    """Of every run's code `mode` (any shape): {"collapsed": how many collapsed, then each of
    MODES: how many by it}, the numbers a summary (an archive attribute, a verdict) states."""
    counts = mode_counts(mode)
    return {"collapsed": int(counts.sum()),
            **{name: int(n) for name, n in zip(MODES, counts, strict=True)}}


def collapse_text(numbers: dict) -> str:
    """The numbers of `collapse_numbers` (or an archive's, read back) as a summary says them:
    '3 collapsed (3 story drift, 0 isolator capacity, 0 numerical instability)'."""
    modes = ", ".join(f"{numbers[name]} {name.replace('_', ' ')}" for name in MODES)
    return f"{numbers['collapsed']} collapsed ({modes})"
