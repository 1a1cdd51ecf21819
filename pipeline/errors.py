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
