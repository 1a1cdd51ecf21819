"""The run's model named once (engine/model.py): derived from the inputs, one table of what
each model takes, consulted and quoted by engine.simulate's refusals and printed in the docs."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import engine
from engine import Building, Contact, Moat, Stories, Torsion
from engine.model import MODELS, PLAN, PLANAR, SUPPORTS, TWISTING, model_of, support_table

PLAN_SIZE = (30.0, 20.0)  # m
TWISTS = Building(torsion=Torsion(plan_size=PLAN_SIZE))


def pulse(components: int) -> tuple[np.ndarray, float]:
    """A short half-sine ground motion, (N,) or (N, 2) m/s^2, and its step (s)."""
    t = np.arange(0.0, 0.5, 0.01)
    x = 2.0 * np.sin(2 * np.pi * t)
    return (x if components == 1 else np.column_stack([x, 0.5 * x])), 0.01


def test_the_model_follows_from_the_inputs_once():
    assert model_of(1, False) is PLANAR
    assert model_of(2, False) is PLAN
    assert model_of(2, True) is TWISTING
    with pytest.raises(engine.EngineError, match=r"twists.*accel as \(N, 2\)"):
        model_of(1, True)
    with pytest.raises(engine.EngineError, match="1 or 2 horizontal components, got 3"):
        model_of(3, False)
    assert set(MODELS) == {"planar", "plan", "twisting"}


def test_each_model_returns_its_results():
    """The result of a run carries exactly its model's peaks."""
    for model, building in ((PLANAR, Building()), (PLAN, Building()), (TWISTING, TWISTS)):
        accel, dt = pulse(model.components)
        result = engine.simulate(accel, dt, Contact.none(1), building, backend="numpy")
        for quantity in model.peaks:
            assert getattr(result, quantity.name).shape[0] == 1, quantity.name
        assert type(result).__name__ == {"planar": "Result", "plan": "PlanResult",
                                         "twisting": "TorsionResult"}[model.name]


REFUSED = [  # (model, what SUPPORTS row, the run's arguments, the building)
    (PLANAR, "moat", {"moat": "circular"}, Building()),
    (PLANAR, "angle", {"angle": [30.0]}, Building()),
    (PLAN, "bumper_positions", {"moat": Moat(bumper_positions=((0.0,), (0.0,)))}, Building()),
    (TWISTING, "moat", {"moat": "circular"}, TWISTS),
]


@pytest.mark.parametrize("model, what, kwargs, building", REFUSED,
                         ids=[f"{m.name}-{w}" for m, w, _, _ in REFUSED])
def test_a_refusal_quotes_the_table(model, what, kwargs, building):
    """What a model does not take is refused by its SUPPORTS row, naming the model that does
    and how to run it."""
    accel, dt = pulse(model.components)
    with pytest.raises(engine.EngineError) as refused:
        engine.simulate(accel, dt, Contact.linear([0.1]), building, backend="numpy", **kwargs)
    text = str(refused.value)
    assert text.startswith(what) and f"the {model.name} model takes" in text
    assert "engine.model.SUPPORTS" in text
    assert "; the " in text and " model takes it: " in text


@pytest.mark.parametrize("fields, row", [
    ({"stories": Stories.of("imk", yield_force=3e6, plastic_deformation=0.09,
                            post_capping_deformation=0.35)}, "story law"),
    ({"damping": "modal"}, "damping"),
    ({"p_delta": True, "story_height": (3.5,) * 4}, "p_delta"),
])
def test_the_twisting_model_refuses_what_its_row_excludes(fields, row):
    """Each exclusion of the twisting model's column is an actual refusal of the building."""
    value = TWISTING.takes(row)
    assert value is False or value == ("linear",) or value == ("paper",)
    Building(**fields)  # the planar and plan models take it
    with pytest.raises(engine.EngineError, match=f"^{row}.*the twisting model takes"):
        Building(**fields, torsion=Torsion(plan_size=PLAN_SIZE))


def test_the_docs_print_the_table():
    text = (Path(__file__).resolve().parents[2] / "docs" / "model.md").read_text()
    assert support_table() in text, "docs/model.md: paste engine.model.support_table()"
    for what in SUPPORTS:
        assert f"| {what} |" in support_table()
