"""What every member of a sweep runs under, besides its own member record: the records, their
names and intensity factors, the step, the building, the moat; and the keys that identify it.
One value that the stores, the batches and the archive's builders all read."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .keys import context_key


@dataclass(frozen=True)
class Run:
    """records: the Record objects run (RecordPair in plan); names (R,): their labels in the
    archive; dt: integration step, s; building: the sweep's engine.Building; moat: None for a
    planar run, else the moat of a run in plan; factors: None, or (R,) intensity factors (-)
    multiplying each record's ground acceleration, times each member's level (a code suite's
    MCE_R factors); arguments: the call's arguments, stored in the archive;
    bumper_positions: None, or the bumpers' positions along the walls of a building that
    twists (engine.simulate's)."""

    records: list
    names: list
    dt: float
    building: object
    moat: str | None = None
    factors: np.ndarray | None = None
    arguments: dict = field(default_factory=dict)
    bumper_positions: tuple | None = None

    def factor(self, r: int) -> float | None:
        """Record r's intensity factor (None: the record as it is)."""
        return None if self.factors is None else self.factors[r]

    def contexts(self) -> list[str]:
        """Each record's context key (keys.context_key): what decides a member's result
        besides its member record."""
        return [context_key(rec, self.dt, self.building, self.moat, self.factor(r),
                            self.bumper_positions)
                for r, rec in enumerate(self.records)]

    @property
    def n_points(self) -> int | None:
        """The moat's contact points of a building that twists (None: it does not)."""
        if not self.building.twists:
            return None
        from engine.torsion import contact_points

        return contact_points(np.array([self.building.torsion.plan_size]),
                              self.bumper_positions).wall.size
