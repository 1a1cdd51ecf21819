"""Isolator laws and yielding stories: the declarations, the friction law's closed form, each
law's energy per cycle (the code's design formulas) against the area of its own hysteresis loop
and the literature's closed form, limit cases that must equal the bilinear law or linear stories,
and the two time loops agreeing on buildings of 1 to 20 stories."""
from __future__ import annotations

import numpy as np
import pytest

import engine
from engine import Building, Contact, Isolator
from engine.isolators import registry
from engine.isolators.hysteresis import slip_limit

FP = dict(radius=2.0, mu_slow=0.05, mu_fast=0.10, rate=30.0)


def test_friction_follows_constantinou():
    """mu(v) W = (mu_fast - (mu_fast - mu_slow) exp(-rate |v|)) W: the friction pendulum's
    slip limit at each sliding speed, where its friction force stops (its own advance,
    pushed far in one step)."""
    b = Building(isolator=Isolator.friction_pendulum(**FP))
    f = b.isolation.fields(b.total_mass, b.g)
    row = b.isolation.row(b.total_mass, b.g)
    law = registry.LAWS["friction_pendulum"]
    weight = b.g * b.total_mass
    for v in (0.0, 0.01, -0.05, 0.3, 5.0):
        mu = 0.10 - (0.10 - 0.05) * np.exp(-30.0 * abs(v))
        assert slip_limit(f["f_limit"], f["slow_drop"], f["rate"], v) == \
            pytest.approx(mu * weight, rel=1e-14)
        state = np.zeros(len(law.STATE))
        law.advance(state, v, 1.0 if v else 0.0, row)
        assert abs(state[law.STATE.slip_force]) == pytest.approx(mu * weight if v else 0.0,
                                                                 rel=1e-14)
    assert f["k_elastic"] == pytest.approx(weight / 2.0)
    assert f["k_slip"] == pytest.approx(0.10 * weight / 5e-4)
    assert b.isolation_zeta == 0.0 and b.yield_displacement == 5e-4
    # the bilinear law's limit does not depend on speed: exactly f_limit, slow or fast
    bilinear = registry.LAWS["bilinear"]
    g_row = Building().isolation.row(Building().total_mass, 9.81)
    for v in (0.01, 0.7, 30.0):
        state = np.zeros(len(bilinear.STATE))
        bilinear.advance(state, v, 1.0, g_row)
        assert state[bilinear.STATE.slip_force] == g_row[bilinear.ROW.f_limit]


def test_declarations_and_their_checks():
    iso = Isolator.friction_pendulum(2.0, 0.05, 0.1, 30.0)
    assert iso == Isolator.of("friction_pendulum", **FP)
    assert iso.values["yield_disp"] == 5e-4  # the declared default
    assert Building().isolation == Isolator.bilinear()  # the shorthand's defaults
    with pytest.raises(engine.EngineError, match="mu_slow <= mu_fast"):
        Isolator.friction_pendulum(2.0, 0.2, 0.1, 30.0)
    with pytest.raises(engine.EngineError, match="radius is required"):
        Isolator.of("friction_pendulum", mu_slow=0.05, mu_fast=0.1, rate=30.0)
    with pytest.raises(engine.EngineError, match="unknown isolator law"):
        Isolator.of("lead_rubber")
    with pytest.raises(engine.EngineError, match="either as isolator= or by k1"):
        Building(isolator=iso, k1=300e6)
    with pytest.raises(engine.EngineError, match="story_yield_force must be 4 positive"):
        Building(story_yield_force=(1e6, 1e6))
    with pytest.raises(engine.EngineError, match="story_stiffness must be 2 positive"):
        Building(masses=(1e5, 1e5, 1e5), story_stiffness=(1e9,))
    # A building with some isolator values replaced (a member of an isolator sweep).
    fp = Building(isolator=iso, zeta_sup=0.03)
    assert fp.with_isolator(mu_fast=0.12) == Building(
        isolator=Isolator.friction_pendulum(**{**FP, "mu_fast": 0.12}), zeta_sup=0.03)
    assert Building().with_isolator(k2=30e6).isolation == Isolator.bilinear(k2=30e6)
    with pytest.raises(engine.EngineError, match="unknown parameter.*radius"):
        Building().with_isolator(radius=2.0)
    with pytest.raises(engine.EngineError, match="0 < k2 < k1"):
        Building().with_isolator(k2=300e6)
    with pytest.raises(engine.EngineError, match="same number of levels"):
        engine.simulate(np.zeros(10), 0.01, Contact.none(2),
                        building=[Building(), Building(masses=(1e5, 1e5),
                                                       story_stiffness=(1e9,))])


def _loop_energy(isolator, mass, g, amplitude, period=3.0, steps=2000):
    """J: the area of the isolator's hysteresis loop, integral of F du over one full cycle of
    u = amplitude sin(2 pi t / period), after the first quarter (the virgin loading), driven
    through the law's own advance and force (the functions both time loops run) at each step's
    velocity."""
    law = registry.LAWS[isolator.law]
    row = isolator.row(mass, g)
    t = np.linspace(0.0, 1.25 * period, 5 * steps + 1)
    u = amplitude * np.sin(2 * np.pi * t / period)
    h = t[1] - t[0]
    state, force = np.zeros(len(law.STATE)), np.zeros_like(u)
    for n in range(1, u.size):
        law.advance(state, (u[n] - u[n - 1]) / h, h, row)
        force[n] = law.force(u[n], state, row)
    return float(np.trapezoid(force[steps:], u[steps:]))


@pytest.mark.parametrize("amplitude", [0.05, 0.30])
def test_energy_per_cycle_is_the_area_of_the_loop(amplitude):
    """E(D) of each law against the area of its own loop integrated numerically, and against
    the literature's closed forms: bilinear 4 Q_d (D - D_y), Q_d = (K1 - K2) D_y, D_y = Fy / K1;
    friction pendulum 4 mu W D (the pre-slip displacement yield_disp neglected, so the loop is
    4 mu W (D - yield_disp) when the friction does not depend on the speed)."""
    b = Building()
    mass, g = b.total_mass, b.g
    d_y = 0.1 * g * mass / 200e6
    closed = 4 * (200e6 - 25e6) * d_y * (amplitude - d_y)
    energy = b.isolation.energy_per_cycle(mass, g, amplitude)
    assert energy == pytest.approx(closed, rel=1e-12)
    assert _loop_energy(b.isolation, mass, g, amplitude) == pytest.approx(energy, rel=1e-6)
    assert b.isolation.energy_per_cycle(mass, g, 0.5 * d_y) == 0.0  # elastic: no loop

    coulomb = Isolator.friction_pendulum(radius=2.0, mu_slow=0.08, mu_fast=0.08, rate=30.0)
    energy = coulomb.energy_per_cycle(mass, g, amplitude)
    assert energy == pytest.approx(4 * 0.08 * g * mass * amplitude, rel=1e-12)
    assert _loop_energy(coulomb, mass, g, amplitude) == pytest.approx(
        energy * (1 - 5e-4 / amplitude), rel=1e-6)
    # Rate-dependent friction at the speeds of a 3 s cycle of 0.30 m: mu_fast, to 0.5%.
    if amplitude == 0.30:
        fp = Isolator.friction_pendulum(**FP)
        assert _loop_energy(fp, mass, g, amplitude) == pytest.approx(
            fp.energy_per_cycle(mass, g, amplitude), rel=5e-3)


def test_post_yield_stiffness_is_the_secant_stiffness_at_large_displacement():
    b = Building()
    for iso in (b.isolation, Isolator.friction_pendulum(**FP)):
        k_inf = iso.post_yield_stiffness(b.total_mass, b.g)
        assert iso.effective_stiffness(b.total_mass, b.g, 1e7) == pytest.approx(k_inf, rel=1e-6)
    assert b.isolation.post_yield_stiffness(b.total_mass, b.g) == 25e6
    assert Isolator.friction_pendulum(**FP).post_yield_stiffness(b.total_mass, b.g) == \
        pytest.approx(b.g * b.total_mass / 2.0, rel=1e-15)


def test_a_law_without_the_code_formulas_names_itself(monkeypatch):
    """A law may leave out CODE_INTERFACE: it runs, and the code's design says which law lacks
    what, at the point of use."""
    from types import SimpleNamespace

    from pipeline.motions.target import isolation_design

    bilinear = registry.LAWS["bilinear"]
    bare = SimpleNamespace(**{name: getattr(bilinear, name)
                              for name in (*registry.LAW_INTERFACE, "__name__")
                              if name != "NAME"}, NAME="bare")
    monkeypatch.setitem(registry.LAWS, "bare", bare)
    iso = Isolator("bare", Isolator.bilinear().parameters)
    assert iso.initial_stiffness(1e6, 9.81) == 200e6  # what it declares still works
    with pytest.raises(engine.EngineError, match="the bare isolator law declares no "
                                                 "energy_per_cycle"):
        iso.energy_per_cycle(1e6, 9.81, 0.3)
    with pytest.raises(ValueError, match="bare isolator law declares no post_yield_stiffness"):
        isolation_design(0.9, Building(isolator=iso))


def _run(building, backend, seconds=12.0):
    from pipeline.records import paper_record

    rec = paper_record("olive_view")
    accel = rec.accel[: int(seconds / rec.dt) + 1]
    contact = Contact.concat([Contact.none(1), Contact.linear([0.10, 0.16])])
    return engine.simulate(accel, rec.dt, contact, building=building, backend=backend)


def _assert_close(a, b, rtol):
    for name, value in a.peaks().items():
        np.testing.assert_allclose(value, getattr(b, name), rtol=rtol,
                                   atol=rtol * np.abs(value).max(), err_msg=name)


# Limit cases on the compiled loop: the NumPy loop gives its numbers with friction pendulums
# and bilinear stories, yielding or not (test_both_loops_agree_on_any_height below, to 1e-9),
# with the bilinear isolator and linear stories (tests/engine/loops/test_numba_loop.py::
# test_backends_agree_on_every_peak, to 1e-9).
@pytest.mark.parametrize("backend", ["numba"])
def test_rate_independent_friction_pendulum_is_the_equivalent_bilinear(backend):
    """mu_slow = mu_fast: Coulomb friction mu W with pre-slip stiffness k_0 in parallel with
    W / R is the bilinear law with K1 = k_0 + W / R, K2 = W / R and u_y = yield_disp."""
    fp = Building(isolator=Isolator.friction_pendulum(2.0, 0.08, 0.08, 30.0), zeta_iso=0.0)
    weight = fp.g * fp.total_mass
    k0, kr = 0.08 * weight / 5e-4, weight / 2.0
    bilinear = Building(k1=k0 + kr, k2=kr, fy_ratio=(k0 + kr) * 5e-4 / weight, zeta_iso=0.0)
    _assert_close(_run(fp, backend), _run(bilinear, backend), 1e-9)


@pytest.mark.parametrize("backend", ["numba"])
def test_stories_that_never_yield_are_linear(backend):
    strong = Building(story_yield_force=(1e12,) * 4)
    _assert_close(_run(strong, backend), _run(Building(), backend), 1e-9)


# A kernel compiles per number of levels and isolator law (engine/loops/numba_loop.py), the
# laws' physics alike at every height: the friction pendulum on 8 stories, the bilinear
# isolator on 1 and 20 (kernels the suite compiles anyway, tests/warm_kernels.py).
@pytest.mark.parametrize("n, isolator", [(1, Isolator.bilinear()),
                                         (8, Isolator.friction_pendulum(**FP)),
                                         (20, Isolator.bilinear())])
def test_both_loops_agree_on_any_height(n, isolator):
    yields = tuple(np.linspace(6e6, 2e6, n))
    building = Building(masses=(500e3,) + (400e3,) * n, story_stiffness=(900e6,) * n,
                        isolator=isolator, story_yield_force=yields)
    fast, ref = _run(building, "numba", 8.0), _run(building, "numpy", 8.0)
    assert fast.peak_total_accel.shape == (3, n + 1)
    assert fast.peak_interstory_drift.shape == (3, n)
    _assert_close(fast, ref, 1e-9)
    assert (fast.peak_interstory_drift / building.story_yield_drift).max() > 1  # it yields
