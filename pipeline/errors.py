"""The pipeline's errors (bad input, an unfit cluster, a run interrupted), and the small input
checks that raise SweepError."""
from __future__ import annotations

import operator


class SweepError(ValueError):
    """Invalid sweep input; the message names the offending parameter."""


class PlausibilityWarning(UserWarning):
    """Valid input that may not give what was meant (e.g. a step coarser than the converged
    one); raised before any compute, shown by the commands as one 'warning: ...' line."""


def check_count(name: str, value, minimum: int) -> int:
    """`value` as an int >= minimum, or SweepError naming it."""
    try:
        count = operator.index(value)
    except TypeError:
        raise SweepError(f"{name} must be a whole number, got {value!r}") from None
    if count < minimum:
        raise SweepError(f"{name} must be >= {minimum}, got {count}")
    return count


def check_building(building):
    """The paper's engine.Building for None, `building` if it is one, else SweepError; a
    building no real structure is (pipeline.building_file.check_plausible) too."""
    import engine

    building = engine.Building() if building is None else building
    if not isinstance(building, engine.Building):
        raise SweepError(f"building must be an engine.Building, got {type(building).__name__}")
    from .building_file import check_plausible

    check_plausible(building)
    return building


def resolve_pairs(pairs, records_dir=None) -> tuple[list, list[str]]:
    """pipeline.records.resolve_pairs, its RecordError raised as SweepError."""
    from .records import RecordError
    from .records import resolve_pairs as resolve

    try:
        return resolve(pairs, records_dir)
    except RecordError as err:
        raise SweepError(str(err)) from err


def resolve_records(records, records_dir=None) -> tuple[list, list[str]]:
    """pipeline.records.resolve_records, its RecordError raised as SweepError."""
    from .records import RecordError
    from .records import resolve_records as resolve

    try:
        return resolve(records, records_dir)
    except RecordError as err:
        raise SweepError(str(err)) from err


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
