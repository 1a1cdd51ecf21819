"""pipeline.motions.tfp_design: a triple friction pendulum designed for T_M at D_M and for D_TM.
The designed bearing's effective period at D_M, from the law's own effective_stiffness, is the
target to 1e-9 (the design equation is regime III's line, the law's backbone the series model:
they agree to round-off); its stiffening starts at (1 + margin) D_TM on the law's backbone and
its capacity is past it; D_M and D_TM are in regime III; the capacity formula and the regimes
against Dao et al.'s (2013) check case; the effective damping against a hand calculation; the
code's D_M of a building on the designed bearing (isolation_design) at the S_M1 that should give
the target; the refusals. Quasi-static only: no time history."""
from __future__ import annotations

import math

import pytest

import engine
from engine.units import G
from pipeline.motions import target as tg
from pipeline.motions import tfp_design as td

DAO = dict(L1=0.36, L2=1.25, L3=1.25, d1=0.1, d2=0.2, d3=0.2, mu1=0.012, mu2=0.052, mu3=0.14)
"""Dao et al. (2013)'s check case (as tests/engine/isolators/laws/test_triple_friction_pendulum
reads their Table 1): ultimate displacement 0.600 m, regime corners at 0.0288, 0.1705, 0.3505,
0.4922 m (forces 0.052, 0.14, 0.212, 0.30 W)."""
PERIOD_TOLERANCE = 1e-9
"""Relative: the effective period at D_M against the target."""
TARGETS = [(3.0, 0.30, None), (2.5, 0.25, 0.35), (4.0, 0.60, 0.72), (3.5, 0.40, 0.40)]
"""(T_M s, D_M m, D_TM m or None for 1.15 D_M): a range of sites and periods."""


@pytest.mark.parametrize(("period", "d_m", "d_tm"), TARGETS)
def test_design_meets_its_target_in_regime_three(period, d_m, d_tm):
    design = td.design_triple_friction_pendulum(period, d_m, d_tm)
    d_tm = 1.15 * d_m if d_tm is None else d_tm
    assert design.total_displacement == pytest.approx(d_tm, rel=1e-15)
    # the law's own secant stiffness at D_M gives the target period
    k = float(design.isolator().effective_stiffness(1000.0, G, d_m))
    assert 2 * math.pi * math.sqrt(1000.0 / k) == pytest.approx(period, rel=PERIOD_TOLERANCE)
    assert design.period_at_dm == pytest.approx(period, rel=PERIOD_TOLERANCE)
    assert design.period_at_dtm >= design.period_at_dm  # softening until regime IV
    assert design.sliding_period > design.period_at_dtm
    # the configuration with equal outer surfaces
    assert design.L2 == design.L3 and design.d2 == design.d3
    assert design.L1 == pytest.approx(td.INNER_RADIUS_RATIO * design.L2, rel=1e-15)
    assert design.d1 == pytest.approx(td.INNER_LIMIT_RATIO * design.d2, rel=1e-15)
    assert (design.mu1, design.mu2, design.mu3) == td.FRICTION
    # stiffening at (1 + margin) D_TM, on the law's backbone: the lower outer slider's stop
    # force mu2 W + W d2 / L2 there
    start = design.stiffening_displacement
    assert start == pytest.approx((1 + td.STIFFENING_MARGIN) * d_tm, rel=1e-12)
    force = float(engine.isolators.LAWS["triple_friction_pendulum"].backbone(
        1.0, G, start, **design.values))
    assert force / G == pytest.approx(design.mu2 + design.d2 / design.L2, rel=1e-12)
    # capacity: past D_TM by at least the margin; the law's, as the closed form 2 d1 + 2 d2
    assert design.capacity >= (1 + td.STIFFENING_MARGIN) * d_tm
    assert design.capacity_margin == pytest.approx(design.capacity / d_tm - 1, rel=1e-15)
    assert design.capacity == pytest.approx(2 * design.d1 + 2 * design.d2, rel=1e-14)
    # quasi-static: every surface sliding at D_M and D_TM, no slider at its restrainer
    assert design.regime(d_m) == design.regime(d_tm) == "III"
    assert design.regime(start * (1 + 1e-6)) in ("IV", "V")
    assert design.regime(design.capacity * (1 + 1e-6)) == td.BEYOND
    assert 0.05 < design.damping_at_dm < 0.4 and 0.05 < design.damping_at_dtm < 0.4
    assert f"T_M {period:.3g} s" in design.describe()


def test_three_second_design_in_numbers():
    """T_M 3 s at D_M 0.30 m, D_TM 0.345 m, default friction (mu_e = 0.288 0.012 + 0.712
    0.052 = 0.04048): by hand 1 / (2 L) = 4 pi^2 / (9.81 9) - 0.04048 / 0.3 = 0.31221, L2 = L3
    = 1.6015 m, L1 = 0.4612 m; d = 1.1 0.345 / 2 - 1.6015 (0.052 - 0.04048) = 0.1713 m, d1 =
    0.0857 m; capacity 2 (0.1713 + 0.0857) = 0.514 m. beta at D_M by hand from the elements'
    slides at F / W = 0.3 / 3.2030 + 0.04048 = 0.13414: inner 2 L1 (F/W - mu1) = 0.11267 m,
    each outer (L - L1)(F/W - mu2) = 0.09366 m; E / W = 4 (0.012 0.11267 + 0.052 2 0.09366) =
    0.044372 m; beta = E / (2 pi k D^2) = 0.044372 / (2 pi 0.44714 0.09) = 0.1755."""
    design = td.design_triple_friction_pendulum(3.0, 0.30)
    assert td.effective_friction(design.values) == pytest.approx(0.04048, rel=1e-12)
    assert design.L2 == pytest.approx(1.6015, rel=1e-4)
    assert design.L1 == pytest.approx(0.4612, rel=1e-3)
    assert design.d2 == pytest.approx(0.1713, rel=1e-3)
    assert design.d1 == pytest.approx(0.0857, rel=1e-3)
    assert design.capacity == pytest.approx(0.514, rel=1e-3)
    assert design.damping_at_dm == pytest.approx(0.1755, rel=1e-3)
    assert design.yield_disp == 5e-4 and design.g == G
    assert isinstance(design.isolator(), engine.Isolator)
    assert design.isolator().law == "triple_friction_pendulum"


def test_dao_check_case_capacity_and_regimes():
    """The capacity formula the design uses, 2 d1 + d2 + d3 + L1 d3 / L3 - L1 d2 / L2, is Dao
    et al.'s ultimate 0.600 m, and the law's; regime IV starts at their 0.3505 m; the regimes
    between their corners are I to V."""
    closed_form = (2 * DAO["d1"] + DAO["d2"] + DAO["d3"] + DAO["L1"] * DAO["d3"] / DAO["L3"]
                   - DAO["L1"] * DAO["d2"] / DAO["L2"])
    assert closed_form == pytest.approx(0.600, abs=1e-12)
    iso = engine.Isolator.triple_friction_pendulum(**DAO)
    assert iso.displacement_capacity(1.0, G) == pytest.approx(closed_form, rel=1e-14)
    values = {**DAO, "yield_disp": 5e-4}
    assert td.regime_iv_start(values) == pytest.approx(0.3505, abs=5e-5)
    regimes = [td.regime(values, d) for d in (0.02, 0.1, 0.3, 0.45, 0.55, 0.65)]
    assert regimes == [*td.REGIMES, td.BEYOND]


def test_code_design_of_the_designed_building_finds_the_target():
    """A building on the designed bearing, at the S_M1 whose D_M = G S_M1 T_M / (4 pi^2 B_M) is
    the design's D_M (B_M from the design's beta_M, Table 17.5-1): the code's
    isolation_design finds that T_M and D_M again."""
    design = td.design_triple_friction_pendulum(3.0, 0.30)
    b_m = tg.damping_coefficient(design.damping_at_dm)
    s_m1 = 0.30 * 4 * math.pi**2 * b_m / (G * 3.0)
    code = tg.isolation_design(s_m1, engine.Building(isolator=design.isolator()))
    assert code.d_m == pytest.approx(0.30, rel=1e-8)
    assert code.t_m == pytest.approx(3.0, rel=1e-8)
    assert code.beta_m == pytest.approx(design.damping_at_dm, rel=1e-8)


def test_unequal_outer_friction():
    """mu2 < mu3 (Dao et al.'s friction): regime II before III, D_M past it, the same
    checks."""
    design = td.design_triple_friction_pendulum(2.5, 0.25, 0.30, friction=(0.012, 0.052, 0.14),
                                                margin=0.2)
    assert design.period_at_dm == pytest.approx(2.5, rel=PERIOD_TOLERANCE)
    assert design.stiffening_displacement == pytest.approx(1.2 * 0.30, rel=1e-12)
    assert [design.regime(d) for d in (0.01, 0.1, 0.25, 0.30)] == ["I", "II", "III", "III"]
    assert design.capacity >= 1.2 * 0.30


@pytest.mark.parametrize(("args", "kwargs", "message"), [
    ((6.0, 0.10), {}, r"T_M = 6 s cannot be reached at D_M = 0.1 m: the friction alone "
                      r"\(mu_e = 0.04048\) allows at most 3.15 s there; target a shorter"),
    ((3.14, 0.10), {}, r"needs L2 = .* m, outside the plausible \[0.05, 20\] m: target a "
                       r"shorter period"),
    ((1.0, 0.30), {}, r"needs L1 = 0.037 m, outside the plausible .* target a longer period"),
    ((5.0, 3.6), {}, r"needs d2 = .* m, outside the plausible \[0.001, 2\] m"),
    ((2.0, 0.10), {"friction": (0.012, 0.052, 0.14)},
     r"D_M = 0.1 m comes before regime III .* lower mu3 toward mu2"),
    ((3.0, 0.30), {"inner_limit_ratio": 0.02}, r"raise inner_limit_ratio"),
    ((3.0, 0.30, 0.25), {}, r"D_TM = 0.25 m must be at least"),
    ((3.0, 0.30), {"friction": (0.05, 0.03, 0.06)}, r"mu1 <= mu2 <= mu3"),
    ((-3.0, 0.30), {}, r"target_period must be a positive number"),
])
def test_refusals_say_what_to_change(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        td.design_triple_friction_pendulum(*args, **kwargs)
