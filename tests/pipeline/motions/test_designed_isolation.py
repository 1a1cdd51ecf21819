"""pipeline.motions.designed_isolation: triple friction pendulums designed for a site and a
target period, their restrainers beyond the lower bound's D_TM, settled against the code's
displacements at the bounds."""
from __future__ import annotations

import math

import numpy as np
import pytest

import engine
from engine.units import G
from pipeline.motions.designed_isolation import TARGET_PERIOD, designed_isolation
from pipeline.motions.target import damping_coefficient
from pipeline.motions.tfp_design import STIFFENING_MARGIN

S_M1 = 0.9  # g: the default site's


@pytest.fixture(scope="module")
def designed():
    return designed_isolation(S_M1, engine.Building())


def test_the_design_is_the_codes_at_every_bound(designed):
    """At the fixed point: the nominal T_M is the target, D_M = g S_M1 T_M / (4 pi^2 B_M) with
    the bearing's own beta_M (ASCE 7-22 17.5.3, written out), the design's D_M the nominal
    bound's, its stiffening (1 + margin) times the lower bound's D_TM, its capacity beyond."""
    nominal, lower = designed.basis.designs["nominal"], designed.basis.designs["lower"]
    assert nominal.t_m == pytest.approx(TARGET_PERIOD, rel=1e-5)
    d_m = G * S_M1 * nominal.t_m / (4 * math.pi**2 * damping_coefficient(nominal.beta_m))
    assert nominal.d_m == pytest.approx(d_m, rel=1e-9)
    assert designed.design.design_displacement == pytest.approx(nominal.d_m, rel=1e-5)
    assert designed.design.stiffening_displacement == pytest.approx(
        (1 + STIFFENING_MARGIN) * lower.d_tm, rel=1e-5)
    assert designed.design.capacity > designed.design.stiffening_displacement > lower.d_tm
    # the lower bound governs displacements: the longest period, the largest D_M
    designs = designed.basis.designs
    assert designs["upper"].d_m < nominal.d_m < lower.d_m
    assert designs["upper"].t_m < nominal.t_m < lower.t_m


def test_the_building_keeps_its_masses_and_stories_on_the_designed_bearing(designed):
    paper = engine.Building()
    building = designed.building
    assert building.isolator.law == "triple_friction_pendulum"
    assert building.isolator.values == designed.design.isolator().values
    np.testing.assert_array_equal(building.masses, paper.masses)
    np.testing.assert_array_equal(building.story_stiffness, paper.story_stiffness)


def test_a_period_the_friction_forbids_is_refused_in_one_line():
    with pytest.raises(ValueError, match="cannot be reached") as err:
        designed_isolation(0.1, engine.Building(), 6.0)
    assert "\n" not in str(err.value)
