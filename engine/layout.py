"""Named columns, declared once: the packed rows the compiled loops read (a member's
parameters, its state, an impact law's constants), each a tuple of names whose columns are
numbered from the declaration rather than typed by hand.

`columns("Name", "a", "b")` is a namedtuple instance, (a=0, b=1): `row[COLS.b]` reads a
column by name, `len(COLS)` is the row's width, `COLS._fields` its names. It is a tuple of
ints, so numba freezes it as a constant when a kernel reads it as a global: `row[COLS.b]`
compiles to a load at a fixed offset, as a hand-typed number would. The NumPy loops index
tuples of (B,) arrays with the same names.
"""
from __future__ import annotations

from collections import namedtuple


def columns(name: str, *names: str):
    """The columns `names` numbered 0, 1, ...: a namedtuple instance of type `name`."""
    return namedtuple(name, names)(*range(len(names)))


def appended(name: str, first, *names: str):
    """The columns of `first` followed by `names` (numbered on from len(first))."""
    return columns(name, *first._fields, *names)
