"""The Torsion component (engine/torsion_fields.py): its fields checked on construction and
against the building that holds it, and the accidental eccentricity as a parameter of its own,
distinct from the mass centre's offset."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import engine
from engine import Building, Torsion
from engine.torsion import shifted
from engine.torsion_fields import ACCIDENTAL_ECCENTRICITY

PLAN = (30.0, 20.0)  # m


def test_values_are_kept_as_floats_and_pairs():
    twist = Torsion(plan_size=np.array([30, 20]), mass_offset=[1, 0],
                    isolator_positions=[[-15, -10], [15, 10]])
    assert twist.plan_size == (30.0, 20.0) and twist.mass_offset == (1.0, 0.0)
    assert twist.isolator_positions == ((-15.0, -10.0), (15.0, 10.0))
    assert hash(Building(torsion=twist)) == hash(Building(torsion=dataclasses.replace(twist)))


def test_the_accidental_eccentricity_moves_the_mass_offset():
    """5% of each plan dimension, added to the mass centre's own offset (ASCE 7-22
    17.5.3.3); 0 leaves the building itself."""
    building = Building(torsion=Torsion(plan_size=PLAN, mass_offset=(1.0, -1.0)))
    moved = shifted(building, 0.05)
    assert moved.torsion.mass_offset == pytest.approx((1.0 + 1.5, -1.0 + 1.0))
    assert shifted(building, 0.0) is building
    assert ACCIDENTAL_ECCENTRICITY.units == "1" and "17.5.3.3" in ACCIDENTAL_ECCENTRICITY.equation
    with pytest.raises(engine.EngineError, match="torsion component"):
        shifted(Building(), 0.05)


def test_per_level_values_are_counted_against_the_building():
    with pytest.raises(engine.EngineError, match=r"mass_inertia must be 5 positive values"):
        Building(torsion=Torsion(plan_size=PLAN, mass_inertia=(1e7,) * 4))
    Building(torsion=Torsion(plan_size=PLAN, mass_inertia=(1e7,) * 5))
    with pytest.raises(engine.EngineError, match="torsion must be an engine.Torsion"):
        Building(torsion=PLAN)
