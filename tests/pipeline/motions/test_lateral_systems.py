"""The lateral systems (pipeline/motions/lateral_systems.py) and the stories the code designs
for each (pipeline.motions.superstructure): stiffness and strength that agree (every story
yields at the system's drift), the strengths Omega_0 times the design shears of the
distribution at the designed building's own period (the fixed point written out), the
backbone's drift ratios, R_I's cap, and the building's own stories kept bit for bit by the
default."""
from __future__ import annotations

import math

import numpy as np
import pytest

import engine
from pipeline.motions.bounds import design_basis
from pipeline.motions.lateral_systems import SYSTEMS, LateralSystem, system
from pipeline.motions.superstructure import OVERSTRENGTH, code_designed_building, for_basis

S_M1 = 0.6  # g


@pytest.fixture(scope="module")
def basis():
    return design_basis(S_M1, engine.Building())


@pytest.mark.parametrize("name", ["steel-smf", "steel-scbf"])
def test_a_system_s_stories_yield_at_its_drift_under_omega_0_times_the_design_shears(basis,
                                                                                      name):
    """Each story's strength is Omega_0 x its design shear, its stiffness that strength over
    the system's yield drift (so it yields there, to round-off); the shears are those of
    ASCE 7-22 eq. 17.5-11 at the period of the designed building itself (k = 14 beta_M T_fb,
    T_fb its own fixed-base period: the fixed point); the deteriorating backbone takes the
    system's drift ratios."""
    chosen = SYSTEMS[name]
    d = for_basis(basis, lateral_system=name)
    h = d.story_height
    np.testing.assert_allclose(d.strength / d.stiffness, chosen.yield_drift_ratio * h,
                               rtol=1e-12)
    np.testing.assert_array_equal(d.building.story_stiffness, tuple(d.stiffness))
    t_fb = 2 * math.pi / d.building.fixed_base_omega1()
    assert t_fb == pytest.approx(d.t_fb, rel=1e-10)
    k = 14 * basis.force_design.beta_m * t_fb
    w = np.asarray(basis.building.masses[1:]) * np.cumsum(h) ** k
    shear = np.cumsum((d.v_s * w / w.sum())[::-1])[::-1]
    np.testing.assert_allclose(d.strength, chosen.omega_0 * shear, rtol=1e-9)
    assert d.overstrength == chosen.omega_0
    values = d.building.stories.values
    np.testing.assert_allclose(values["plastic_deformation"], chosen.plastic_drift_ratio * h)
    np.testing.assert_allclose(values["post_capping_deformation"],
                               chosen.post_capping_drift_ratio * h)
    # the drift at the design forces, amplified by C_d = R_I, is R_I / Omega_0 of the yield
    # drift: within ASCE 7-22 17.5.6's 0.015 h for both systems
    drift = d.r_i * d.story_shear / d.stiffness / h
    np.testing.assert_allclose(drift, d.r_i / chosen.omega_0 * chosen.yield_drift_ratio)
    assert drift.max() <= 0.015


def test_the_building_s_own_stories_are_kept_by_the_default(basis):
    """The default system keeps the building's stiffnesses, OVERSTRENGTH (2) and the
    moment-frame backbone: the same building as an explicit overstrength of 2 gives."""
    d = for_basis(basis)
    assert d.lateral_system is SYSTEMS["given"] and d.overstrength == OVERSTRENGTH == 2.0
    assert d.building.story_stiffness == basis.building.story_stiffness
    assert d.building == for_basis(basis, overstrength=2.0).building
    assert d.attributes()["lateral_system"] == "given"
    assert np.isnan(d.attributes()["story_yield_drift_ratio"])


def test_a_stiffer_system_is_stiffer_and_the_period_follows():
    """A braced frame yields at a smaller drift than a moment frame: stiffer stories, a
    shorter fixed-base period, on any isolation."""
    b = design_basis(S_M1, engine.Building())
    smf, scbf = (for_basis(b, lateral_system=n) for n in ("steel-smf", "steel-scbf"))
    assert scbf.t_fb < smf.t_fb
    assert np.all(scbf.stiffness / scbf.strength > smf.stiffness / smf.strength)


def test_r_i_is_capped_at_three_eighths_of_r_and_two():
    """R_I = 3/8 R, at most 2 (ASCE 7-22 17.5.4.2): 2 for both steel systems, 1.5 for an R of
    4; a larger R_I refused in one line naming the system."""
    assert SYSTEMS["steel-smf"].r_i == 2.0 and SYSTEMS["steel-scbf"].r_i == 2.0
    low = LateralSystem("low", "a system of R 4", "", 4.0, 2.5, 0.005, 0.01, 0.05, "test")
    assert low.r_i == 1.5
    b = design_basis(S_M1, engine.Building())
    with pytest.raises(ValueError, match=r"R_I must be in \[1, 2\] for steel special moment"):
        code_designed_building(b.force_design, b.building, r_i=2.5,
                               lateral_system="steel-smf")
    with pytest.raises(ValueError, match="unknown lateral system 'wood'; choose one of given"):
        system("wood")
