"""The building's fields declared once (engine/declared.py, engine/building.py,
engine/torsion_fields.py): every field has a declaration, and the constructor refuses a value
against it, naming the field, its count and its unit."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import engine
from engine.building import DEFAULTS, FIELDS
from engine.declared import Field, checked
from engine.torsion_fields import FIELDS as TORSION_FIELDS


def test_every_field_is_declared():
    assert list(FIELDS) == [f.name for f in dataclasses.fields(engine.Building)]
    assert list(TORSION_FIELDS) == [f.name for f in dataclasses.fields(engine.Torsion)]
    for name, spec in {**FIELDS, **TORSION_FIELDS}.items():
        assert spec.meaning and (spec.units is not None) == (spec.kind in ("number",
                                                                           "shorthand")), name


@pytest.mark.parametrize("name", [n for n, s in FIELDS.items() if s.per == "story"])
def test_a_per_story_field_of_the_wrong_length_is_refused(name):
    """Each per-story field, given for 3 stories of the paper's 4: refused, naming itself,
    the count and the unit the declaration gives."""
    spec = FIELDS[name]
    given = {name: (1.0e6,) * 3}
    if name in ("story_height",):
        given["p_delta"] = True
    with pytest.raises(engine.EngineError,
                       match=rf"^{name} must be 4 positive values in {spec.unit_text}"):
        engine.Building(**given)


@pytest.mark.parametrize("name, bad", [("zeta_sup", 1.0), ("zeta_iso", -0.1),
                                       ("story_post_yield_ratio", 1.5), ("g", 0.0),
                                       ("collapse_drift_ratio", 0.0)])
def test_a_value_outside_its_declared_range_is_refused(name, bad):
    with pytest.raises(engine.EngineError, match=rf"^{name} must be in \S+, \S+[\])]"):
        engine.Building(**{name: bad})


def test_text_and_flag_fields():
    with pytest.raises(engine.EngineError, match="damping must be 'paper' or 'modal'"):
        engine.Building(damping="rayleigh")
    with pytest.raises(engine.EngineError, match="p_delta must be True or False"):
        engine.Building(p_delta="yes")


def test_the_defaults_are_the_papers_building():
    assert DEFAULTS["masses"] == (320e3, 320e3, 320e3, 320e3, 250e3)
    assert DEFAULTS["story_stiffness"] == (600e6,) * 4
    assert engine.Building().isolation.law == "bilinear"


def test_checked_returns_what_the_dataclass_keeps():
    spec = Field("N m-1", "a stiffness", per="story", valid="(0, inf)")
    assert checked("k", spec, np.array([1.0, 2.0]), 2) == (1.0, 2.0)
    with pytest.raises(engine.EngineError, match=r"k must be 2 positive values in N/m"):
        checked("k", spec, [1.0, -2.0], 2)
    with pytest.raises(ValueError, match="kind must be one of"):
        Field("m", "a length", kind="length")


def test_the_docs_list_every_field_as_declared():
    from pathlib import Path

    from engine.declared import defaults_of, field_table

    text = (Path(__file__).resolve().parents[2] / "docs" / "model.md").read_text()
    for table in (field_table(FIELDS, DEFAULTS),
                  field_table(TORSION_FIELDS, defaults_of(engine.Torsion), "torsion.")):
        assert table in text, "docs/model.md: paste engine.declared.field_table's tables"
