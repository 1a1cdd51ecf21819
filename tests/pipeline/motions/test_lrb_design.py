"""pipeline.motions.lrb_design: a lead-rubber bearing for a target period, against the
closed forms of a bilinear backbone, and settled against the code's displacements by
pipeline.motions.designed_isolation."""
from __future__ import annotations

import math

import pytest

import engine
from engine.units import G
from pipeline.motions import lrb_design
from pipeline.motions.designed_isolation import DESIGNS, designed_isolation


def test_the_bearing_has_the_target_period_at_d_m_on_its_backbone():
    building = engine.Building()
    weight = G * building.total_mass
    design = lrb_design.design_lead_rubber(3.0, 0.6, 0.7, weight)
    assert design.q_d == pytest.approx(lrb_design.STRENGTH_RATIO * weight)
    assert design.k1 / design.k2 == pytest.approx(lrb_design.STIFFNESS_RATIO)
    assert design.capacity == pytest.approx((1 + lrb_design.CAPACITY_MARGIN) * 0.7)
    # on the backbone past yield F(D) = K2 D + Q_d, and T = 2 pi sqrt(M D / F) at D_M
    force = design.k2 * 0.6 + design.q_d
    assert 2 * math.pi * math.sqrt(weight / G * 0.6 / force) == pytest.approx(3.0, rel=1e-12)
    assert design.effective_period(0.6) == pytest.approx(3.0, rel=1e-12)
    # the engine's bilinear law of the design: yield force Fy = Q_d / (1 - K2 / K1), so that
    # its backbone's intercept is Q_d; it yields well before D_M
    building = engine.Building(isolator=design.isolator())
    fy = building.isolator.values["fy_ratio"] * G * building.total_mass
    assert fy * (1 - design.k2 / design.k1) == pytest.approx(design.q_d, rel=1e-12)
    assert fy / design.k1 < 0.05 * 0.6


def test_a_strength_stiffer_than_the_target_is_refused_in_one_line():
    with pytest.raises(ValueError, match="target a shorter period"):
        lrb_design.design_lead_rubber(6.0, 0.2, 0.25, 1e7)


def test_the_design_settles_against_the_codes_displacements_at_the_bounds():
    building = engine.Building()
    done = designed_isolation(0.9, building, 3.0, kind="designed-lrb")
    nominal, lower = done.basis.designs["nominal"], done.basis.designs["lower"]
    assert done.building.isolator.law == "bilinear" and done.title == "lead-rubber bearings"
    # designed at the nominal D_M for the target period, its capacity beyond the lower D_TM
    assert done.design.design_displacement == pytest.approx(nominal.d_m, rel=1e-5)
    assert done.design.effective_period(nominal.d_m) == pytest.approx(3.0, rel=1e-5)
    assert done.design.capacity == pytest.approx(1.1 * lower.d_tm, rel=1e-5)
    assert lower.d_tm > nominal.d_m
    assert "lead-rubber bearings designed for T_M 3 s" in done.describe()
    with pytest.raises(ValueError, match="an isolator design is one of"):
        designed_isolation(0.9, building, 3.0, kind="designed-hdr")


def test_the_studies_offer_every_design():
    from studies.common.options import ISOLATOR_CHOICES

    assert ISOLATOR_CHOICES == ("given", *DESIGNS)
