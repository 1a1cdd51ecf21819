"""What every member of a sweep runs under, besides its own member record: the records, their
names and intensity factors, the step, the building, the moat; and the keys that identify it.
One value that the stores, the batches and the archive's builders all read."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .keys import context_key


def run_model(moat: str | None, building):
    """The run's model (engine.model: planar, plan, twisting), derived once from a sweep's
    moat (None: planar, one record component) and its building (a torsion component: it
    twists); SweepError quoting engine.model.SUPPORTS for a moat the model does not take."""
    from engine.errors import EngineError
    from engine.model import TWISTING, model_of

    from ..errors import SweepError

    if moat is None and building.twists:
        raise SweepError(f"a building that twists runs in plan ({TWISTING.meaning}): give "
                         "moat='rectangular' (--moat rectangular) and record pairs")
    model = model_of(1 if moat is None else 2, building.twists)
    try:
        if moat is not None:
            model.check("moat", moat)
    except EngineError as err:
        raise SweepError(str(err)) from None
    return model


@dataclass(frozen=True)
class Run:
    """records: the Record objects run (RecordPair in plan); names (R,): their labels in the
    archive; dt: integration step, s; building: the sweep's engine.Building; moat: None for a
    planar run, else the moat of a run in plan; factors: None, or (R,) intensity factors (-)
    multiplying each record's ground acceleration, times each member's level (a code suite's
    MCE_R factors); arguments: the call's arguments, stored in the archive;
    bumper_positions: None, or the bumpers' positions along the walls of a building that
    twists (engine.simulate's); backend: the engine's time loop (engine.simulate's; None: its
    default)."""

    records: list
    names: list
    dt: float
    building: object
    moat: str | None = None
    factors: np.ndarray | None = None
    arguments: dict = field(default_factory=dict)
    bumper_positions: tuple | None = None
    backend: str | None = None

    @property
    def model(self):
        """The run's model (engine.model.Model; run_model)."""
        return run_model(self.moat, self.building)

    def factor(self, r: int) -> float | None:
        """Record r's intensity factor (None: the record as it is)."""
        return None if self.factors is None else self.factors[r]

    def contexts(self) -> list[str]:
        """Each record's context key (keys.context_key): what decides a member's result
        besides its member record."""
        return [context_key(rec, self.dt, self.building, self.moat, self.factor(r),
                            self.bumper_positions, self.backend)
                for r, rec in enumerate(self.records)]

    def engine_keywords(self, r: int) -> dict:
        """What batches.simulate_batch takes of the run for record r besides the building
        and dt: moat, factor, bumper_positions, backend (in its order)."""
        return {"moat": self.moat, "factor": self.factor(r),
                "bumper_positions": self.bumper_positions, "backend": self.backend}

    @property
    def n_points(self) -> int | None:
        """The moat's contact points of a building that twists (None: it does not)."""
        if not self.building.twists:
            return None
        from engine.torsion import contact_points

        return contact_points(np.array([self.building.torsion.plan_size]),
                              self.bumper_positions).wall.size
