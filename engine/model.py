"""The run's model, named once: planar, in plan, or twisting (in the manner of OpenSees'
`model basic -ndm 2 -ndf 3`, said once at the top of a script).

    planar    one horizontal component along x; the building's levels move along x, the moat
              is a wall on each side (the paper's model, sections 4-5)
    plan      a record pair (x, y); the levels move in x and y without rotating, on coupled
              isolators, against a rectangular or circular moat (SPEC section 7)
    twisting  a record pair; every level is a rigid diaphragm (u_x, u_y, theta), on bearings
              where they stand, against the rectangular moat's contact points (engine/
              torsion.py; a Building with a `torsion` component)

`model_of(components, twists)` derives it once from the inputs (the ground motion's
components, whether the building has a `torsion` component); `SUPPORTS` is the one table of
what each model takes. engine.simulate refuses what its model does not support by quoting
that table (Model.refuse), the pipeline asks the same table before any record is read, and
docs/model.md prints it (`support_table`).
"""
from __future__ import annotations

from dataclasses import dataclass

from .errors import EngineError
from .results import (
    COLLAPSE,
    HISTORIES,
    PEAKS,
    PLAN_HISTORIES,
    PLAN_PEAKS,
    RESIDUALS,
    TORSION_HISTORIES,
    TORSION_PEAKS,
    WALLS,
    Quantity,
)

EVERY = "every registered law"
"""A SUPPORTS entry: every law of the registry (engine/stories/laws/, engine/isolators/laws/)."""


SUPPORTS: dict[str, str] = {
    "ground motion components": "horizontal components of the record (1: accel (N,); 2: a "
                                "pair, accel (N, 2))",
    "moat": "the moat's shape (engine.simulate's moat; planar: a wall on each side)",
    "story law": "the stories' laws (engine.Stories)",
    "isolator law": "the isolators' laws (engine.Isolator)",
    "damping": "the damping rule (Building.damping)",
    "p_delta": "the stories' P-Delta (Building.p_delta)",
    "collapse_drift_ratio": "a run ending as collapsed past a story drift ratio",
    "history": "time histories of chosen members (engine.History)",
    "contact_y": "y walls of their own (engine.Moat's contact_y)",
    "angle": "incidence angles of the record pair (engine.simulate's angle)",
    "mu_wall": "friction between slab and wall (engine.Moat's mu_wall)",
    "bumper_positions": "bumpers placed along the walls (engine.Moat's bumper_positions)",
    "story_stiffness_y": "stories of another stiffness along y (Building.story_stiffness_y)",
    "backend": "the time loops that run it (engine.simulate's backend)",
}
"""What a model may or may not take, one row per input -> its meaning: the one table
engine.simulate, the pipeline and docs/model.md read (each Model's `supports` holds its
column)."""


@dataclass(frozen=True, eq=False)  # a model is itself: compared and hashed by identity
class Model:
    """One model of the run and what it supports.

    name: "planar", "plan" or "twisting"; meaning: one line; components: the ground motion's
    horizontal components (1: (N,), 2: (N, 2)); supports: its column of SUPPORTS, each row
    True / False, or the names it takes (EVERY: every registered law); peaks, histories: what
    it returns (engine/results.py); loop: the name of its loop modules in engine/loops/
    (numba_<loop>, numpy_<loop>, and cuda_<loop> where its backend row has cuda); how: what a
    run does to be of this model (the advice of another model's refusal).
    """

    name: str
    meaning: str
    components: int
    supports: dict
    peaks: tuple[Quantity, ...]
    histories: tuple[Quantity, ...]
    loop: str
    how: str

    def __post_init__(self):
        if set(self.supports) != set(SUPPORTS) - {"ground motion components"}:
            raise ValueError(f"model {self.name}: supports must give every SUPPORTS row")

    def __repr__(self) -> str:
        return f"engine.model.{self.name.upper()}"

    @property
    def in_plan(self) -> bool:
        """Whether the building moves in x and y (plan or twisting)."""
        return self.components == 2

    def quantities(self, collapse: bool = False) -> tuple[Quantity, ...]:
        """What a run of this model returns and an archive keeps of it: its peaks, the
        RESIDUALS, then COLLAPSE for a building with a collapse criterion (so that a building
        without one, the paper's, keeps the archive it had)."""
        return (*self.peaks, *RESIDUALS, *(COLLAPSE if collapse else ()))

    def takes(self, what: str):
        """This model's entry of the SUPPORTS row `what`."""
        return self.components if what == "ground motion components" else self.supports[what]

    def refuse(self, what: str, given=None) -> EngineError:
        """The EngineError for `what` (a SUPPORTS row), which this model does not take as
        given: the table's row says what it does take, and which model would."""
        others = [m for m in MODELS.values() if m is not self and _admits(m.takes(what), given)]
        shown = "" if given is None else f" {given!r}"
        advice = "" if not others else \
            f"; the {' or '.join(m.name for m in others)} model takes it: {others[0].how}"
        return EngineError(f"{what}{shown}: the {self.name} model takes "
                           f"{_text(self.takes(what))} (engine.model.SUPPORTS){advice}")

    def check(self, what: str, value) -> None:
        """EngineError (refuse) unless this model takes `value` for the SUPPORTS row `what`:
        a name among its names, or True for a yes/no row (False always passes)."""
        takes = self.takes(what)
        if isinstance(takes, bool):
            if value and not takes:
                raise self.refuse(what)
        elif takes != EVERY and value not in takes:
            raise self.refuse(what, value)


_IN_PLAN = {"contact_y": True, "angle": True, "mu_wall": True, "story_stiffness_y": True}
"""What both models in plan take and the planar one does not."""
_EVERY_LOOP = ("numba", "numpy", "cuda")
"""The time loops of engine/backends.py: the compiled kernel, the NumPy reference, the device
(engine/loops/<backend>_<Model.loop>.py)."""

PLANAR = Model(
    "planar", "one component along x, the levels moving along x against a wall on each side "
    "(the paper's model)", components=1,
    supports={"moat": (), "story law": EVERY, "isolator law": EVERY,
              "damping": ("paper", "modal"), "p_delta": True, "collapse_drift_ratio": True,
              "history": True, **dict.fromkeys(_IN_PLAN, False), "bumper_positions": False,
              "backend": _EVERY_LOOP},
    peaks=PEAKS, histories=HISTORIES, loop="loop",
    how="one component (accel (N,); a sweep without moat)")
PLAN = Model(
    "plan", "a record pair, the levels moving in x and y without rotating on coupled "
    "isolators", components=2,
    supports={"moat": tuple(WALLS), "story law": EVERY, "isolator law": EVERY,
              "damping": ("paper", "modal"), "p_delta": True, "collapse_drift_ratio": True,
              "history": True, **_IN_PLAN, "bumper_positions": False,
              "backend": _EVERY_LOOP},
    peaks=(*PEAKS, *PLAN_PEAKS), histories=PLAN_HISTORIES, loop="plan",
    how="a record pair (accel (N, 2), its x and y components; a sweep's moat)")
TWISTING = Model(
    "twisting", "a record pair, every level a rigid diaphragm (u_x, u_y, theta) on bearings "
    "where they stand (a Building with a torsion component)", components=2,
    supports={"moat": ("rectangular",), "story law": ("linear",), "isolator law": EVERY,
              "damping": ("paper",), "p_delta": False, "collapse_drift_ratio": True,
              "history": True, **_IN_PLAN, "bumper_positions": True,
              "backend": ("numba", "numpy")},
    peaks=(*PEAKS, *PLAN_PEAKS, *TORSION_PEAKS), histories=TORSION_HISTORIES, loop="torsion",
    how="a building with a torsion component (engine.Torsion) under a record pair")

MODELS: dict[str, Model] = {m.name: m for m in (PLANAR, PLAN, TWISTING)}
"""The models by name."""


def model_of(components: int, twists: bool) -> Model:
    """The model of a run whose ground motion has `components` horizontal components (1 or 2)
    on buildings that twist or not; EngineError for a building that twists under one
    component (it needs a record pair)."""
    if components == 1:
        if twists:
            raise EngineError("a building that twists (its torsion component) runs in plan: "
                              "give accel as (N, 2), the record pair's x and y components "
                              "(engine.model.TWISTING)")
        return PLANAR
    if components != 2:
        raise EngineError(f"the ground motion has 1 or 2 horizontal components, got "
                          f"{components}")
    return TWISTING if twists else PLAN


def _admits(takes, given=None) -> bool:
    """Whether a SUPPORTS entry admits `given` (None: anything at all)."""
    if isinstance(takes, bool) or given is None:
        return takes is True or (not isinstance(takes, bool) and bool(takes))
    return takes == EVERY or given in takes


def _text(takes) -> str:
    """A SUPPORTS entry in words."""
    if isinstance(takes, bool):
        return "it" if takes else "none"
    if isinstance(takes, int):
        return str(takes)
    if takes == EVERY:
        return EVERY
    return " or ".join(map(repr, takes)) if takes else "none"


def support_table() -> str:
    """SUPPORTS as a Markdown table, one column per model (docs/model.md holds it; a test
    keeps it current)."""
    names = list(MODELS)
    lines = ["| input | " + " | ".join(names) + " |", "|---" * (len(names) + 1) + "|"]
    for what in SUPPORTS:
        cells = [("yes" if m.takes(what) else "no") if isinstance(m.takes(what), bool)
                 else _text(m.takes(what)).replace("'", "") for m in MODELS.values()]
        lines.append(f"| {what} | " + " | ".join(cells) + " |")
    return "\n".join(lines)
