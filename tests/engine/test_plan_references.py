"""The building in plan against two independent implementations (tests/reference/): an OpenSeesPy
3-D model (opensees_plan.py: elastomericBearingPlasticity, flatSliderBearing, ElasticPPGap
walls per direction) and a solve_ivp model with every switch an event (independent_plan.py:
the continuous flow rule of the coupled slip element, a circular moat).

Both horizontal components of one real record, Northridge 1994 at Beverly Hills - Mulholland
(RSN953, 009 as x and 279 as y), its first 15 s (the strong motion); the engine at its default
step, 0.5 ms, on the compiled loop here. The NumPy loop gives the compiled loop's peaks to 1e-9
on a real pair with every wall law, both moats and both isolators
(test_plan.py::test_the_compiled_loop_gives_the_numpy_loops_numbers; 3e-14 here, measured), so
it meets these bounds too without running each reference case twice. Tolerance: every
resultant and per-direction peak, and every wall's force, within 0.5% (the issue's bound).
Worst deviations measured (NumPy loop; the compiled loop gives the same peaks to 3e-14):

* against OpenSees at the same step (Newmark): no wall, bilinear 0.0025%; no wall, friction
  pendulum 0.10% (peak_total_accel_xy; the friction limit at Newmark's |v_n+1| there, at the
  half-step speed here); rectangular moat of elastic walls (all four walls hit, 8 impacts)
  0.033%. The coupled isolator laws are the same radial return in both, hence the agreement.
* against solve_ivp (the exact flow rule, event-located switches): circular moat with the
  linear viscoelastic wall (COR 0.5, 2 impacts) 0.39% (peak_total_accel); with the paper's
  bumpers (3 impacts, one past the crush limit) 0.20%. These are the engine's own errors at
  0.5 ms. At dt = 0.5, 0.25, 0.125 ms: bumpers 0.20, 0.091, 0.048%; no wall, bilinear 0.061,
  0.031, 0.015%, friction pendulum 0.32, 0.16, 0.080%: first order. The radial return is
  backward Euler on the flow rule, so in plan the force's direction lags by O(dt) (in 1-D the
  clip is the exact integral of the flow rule over a step), and OpenSees shares that lag,
  hence its closer agreement. The Kelvin-Voigt wall converges unevenly, 0.39, 0.50, 0.031%:
  its force jumps by c v_imp at touch, which costs the engine up to 0.81, 0.21, 0.0006% even
  in 1-D (this record's x component alone, gap 0.13 m). Not tested here, measured: the
  friction pendulum against that wall (gap 0.20 m), 0.54, 0.27, 0.14% (and 0.066% at
  0.0625 ms): above the bound at 0.5 ms.
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

import engine
from engine import Building, Contact, Isolator
from engine.isolators import registry as isolator_registry
from tests.reference import independent_plan as ivp
from tests.reference.opensees_plan import isolator_path, plan_peaks

SECONDS = 15.0
COMPONENTS = ("RSN953:009", "RSN953:279")  # x, y
TOLERANCE = 5e-3
FP = dict(radius=2.0, mu_slow=0.05, mu_fast=0.10, rate=30.0)
RECT_GAP = 0.13  # m: the unconstrained slab reaches 0.168 m along x, 0.164 m along y
CIRCLE_GAP = 0.18  # m: ... and 0.229 m along its path (resultant)
BUMPER_GAP = 0.20  # m, bumpers 5 cm thick: the clear gap is 0.15 m
WALL_K = 2.5e9  # N/m
PEAKS = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
         "peak_total_accel_xy", "peak_interstory_drift_xy", "peak_isolator_disp_xy",
         "max_indentation", "max_impact_force", "max_impact_force_wall")
OPENSEES_CASES = {
    # name: (engine building, engine contact, reference keywords); rectangular moat
    "no-wall-bilinear": (Building(), Contact.none(1), {}),
    "no-wall-friction-pendulum": (Building(isolator=Isolator.friction_pendulum(**FP)),
                                  Contact.none(1),
                                  {"isolator": {"kind": "friction_pendulum", **FP}}),
    "rectangular-elastic-walls": (Building(), Contact.linear(RECT_GAP, k=WALL_K, cor=1.0),
                                  {"gap": RECT_GAP, "k": WALL_K}),
}
IVP_CASES = {
    # name: (engine contact, reference wall); circular moat, the paper's building
    "circular-linear-wall": (Contact.linear(CIRCLE_GAP, k=WALL_K, cor=0.5),
                             ivp.RadialWall.linear(CIRCLE_GAP, k=WALL_K, cor=0.5)),
    "circular-bumpers": (Contact.bumper(BUMPER_GAP), ivp.RadialWall.bumper(BUMPER_GAP)),
}
BACKENDS = ("numba",)  # the NumPy loop: see the module docstring


@functools.cache
def pair() -> tuple[np.ndarray, float]:
    """(T, 2) m/s^2, the two components side by side over the first SECONDS, and their step.
    Loaded one by one (pipeline.records.load_record): the pair is the record's two
    horizontal components as recorded, no rotation."""
    from pipeline.records import load_record

    x, y = (load_record(name) for name in COMPONENTS)
    assert x.dt == y.dt and x.npts == y.npts
    n = int(round(SECONDS / x.dt)) + 1
    return np.column_stack([x.accel[:n], y.accel[:n]]), x.dt


@functools.cache
def engine_runs(backend: str, moat: str) -> dict[str, dict]:
    """The engine's peaks of every case of one moat, member by member, in one batch."""
    accel, dt = pair()
    if moat == "rectangular":
        names = list(OPENSEES_CASES)
        buildings = [OPENSEES_CASES[n][0] for n in names]
        contact = Contact.concat([OPENSEES_CASES[n][1] for n in names])
    else:
        names = list(IVP_CASES)
        buildings = Building()
        contact = Contact.concat([IVP_CASES[n][0] for n in names])
    result = engine.simulate(accel, dt, contact, buildings, moat=moat, backend=backend)
    peaks = {**result.peaks(), **result.plan_peaks()}
    return {name: {k: v[i] for k, v in peaks.items()} for i, name in enumerate(names)}


@functools.cache
def opensees(name: str) -> dict:
    accel, dt = pair()
    return plan_peaks(accel, dt, dt=engine.DEFAULT_DT, **OPENSEES_CASES[name][2])


@functools.cache
def solve_ivp(name: str) -> dict:
    accel, dt = pair()
    return ivp.simulate(accel, dt, IVP_CASES[name][1])


def deviations(peaks: dict, reference: dict, names=PEAKS) -> dict[str, float]:
    """The largest relative deviation of each peak of `names`, entry by entry; an entry the
    reference has at 0 (a wall never hit, no wall at all) must be 0 in the engine too."""
    out = {}
    for name in names:
        ref = np.atleast_1d(np.asarray(reference[name], dtype=float))
        got = np.atleast_1d(np.asarray(peaks[name], dtype=float))
        assert got.shape == ref.shape, name
        zero = ref == 0
        np.testing.assert_array_equal(got[zero], 0.0, err_msg=name)
        if not zero.all():
            out[name] = float(np.max(np.abs(got[~zero] - ref[~zero]) / np.abs(ref[~zero])))
    return out


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("case", list(OPENSEES_CASES))
def test_engine_matches_opensees_in_plan(case, backend):
    peaks = engine_runs(backend, "rectangular")[case]
    reference = opensees(case)
    assert peaks["n_impacts"] == reference["n_impacts"]
    if OPENSEES_CASES[case][2].get("gap") is not None:
        assert (reference["max_impact_force_wall"] > 0).all(), "every wall must be hit"
    worst = deviations(peaks, reference)
    assert max(worst.values()) < TOLERANCE, worst


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("case", list(IVP_CASES))
def test_engine_matches_solve_ivp_in_a_circular_moat(case, backend):
    peaks = engine_runs(backend, "circular")[case]
    reference = solve_ivp(case)
    assert reference["n_impacts"] > 0 and peaks["n_impacts"] == reference["n_impacts"]
    worst = deviations(peaks, reference)
    assert max(worst.values()) < TOLERANCE, worst


def test_the_bumpers_are_crushed_in_the_circle():
    """The bumper case reaches the crushed branch (k_w) of the law, both models. The engine's
    run is the compiled loop's, already run for the comparison above: the NumPy loop gives its
    peaks to 1e-9 with bumpers in a circular moat
    (test_plan.py::test_the_compiled_loop_gives_the_numpy_loops_numbers)."""
    wall = IVP_CASES["circular-bumpers"][1]
    assert solve_ivp("circular-bumpers")["max_indentation"] > wall.delta_u
    assert engine_runs("numba", "circular")["circular-bumpers"]["max_indentation"] \
        > wall.delta_u


def test_the_reference_walls_have_the_engine_numbers():
    """The solve_ivp model derives its wall constants from the SPEC's equations (the COR of
    the no-tension Kelvin-Voigt contact in closed form; Eq. 9, 11, 12 for the bumpers): the
    same numbers as the engine's Contact."""
    for contact, wall in IVP_CASES.values():
        for name in ("clear_gap", "k", "n", "dashpot", "delta_u", "k_w", "c_imp_coef",
                     "c_imp_exponent"):
            engine_value = float(getattr(contact, name)[0])
            if np.isinf(engine_value):
                assert np.isinf(getattr(wall, name)), name
                continue
            assert getattr(wall, name) == pytest.approx(engine_value, rel=1e-9, abs=1e-12), \
                (wall.law, name)



@pytest.mark.parametrize("building", [Building(),
                                      Building(isolator=Isolator.friction_pendulum(**FP))],
                         ids=["bilinear", "friction-pendulum"])
def test_opensees_bearings_are_the_engine_isolator_law(building):
    """Along a path in plan (a Lissajous figure through both yield circles, each step's
    velocity the friction model's speed) OpenSees' elastomericBearingPlasticity (qd = Fy (1 -
    K2/K1)) and flatSliderBearing + W/R springs give the engine's isolator force, the law's own
    force_xy after advance_xy (the functions both time loops run), to round-off."""
    t = np.linspace(0.0, 1.0, 400)
    h = t[1] - t[0]
    u = np.column_stack([0.2 * np.sin(7 * t) * np.cos(3 * t), 0.15 * np.sin(11 * t) * t])
    v = np.diff(u, axis=0, prepend=0.0) / h  # each step's velocity: u is where it takes the slab
    law = isolator_registry.LAWS[building.isolation.law]
    row = building.isolation.row(building.total_mass, building.g)
    state, expected = np.zeros(len(law.STATE_XY)), np.empty_like(u)
    for i in range(t.size):
        law.advance_xy(state, v[i, 0], v[i, 1], h, row)
        expected[i] = law.force_xy(u[i, 0], u[i, 1], state, row)
    iso = {} if building.isolator is None else {"isolator": {"kind": "friction_pendulum", **FP}}
    force = isolator_path(u, v, **iso)
    assert np.abs(force - expected).max() < 1e-12 * np.abs(expected).max()
    fields = building.isolation.fields(building.total_mass, building.g)
    slip = np.hypot(*(expected - fields["k_elastic"] * u).T)
    assert slip.max() >= 0.999 * fields["f_limit"] * (1 - fields.get("slow_drop", 0.0))  # slips


def test_solve_ivp_in_plan_along_one_axis_is_the_planar_reference():
    """The plan model's flow rule and radial wall, under a pair with no y component, are the
    planar solve_ivp reference's isolator and wall (tests/reference/independent_building.py):
    the same peaks to 1e-9 (first 10 s: both impacts on the bumpers)."""
    from tests.reference import independent_building as planar

    accel, dt = pair()
    x = accel[: int(round(10.0 / dt)) + 1, 0]
    plan = ivp.simulate(np.column_stack([x, 0.0 * x]), dt, ivp.RadialWall.bumper(0.17))
    line = planar.simulate(x, dt, planar.Wall.bumper(0.17))
    assert plan["n_impacts"] == line["n_impacts"] == 2
    assert plan["switches"]["isolator"] == line["switches"]["isolator"]
    for name in ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp",
                 "max_indentation", "max_impact_force"):
        np.testing.assert_allclose(plan[name], line[name], rtol=1e-9, err_msg=name)
    # sin(pi) of the force's angle on the circle: y moves by round-off only
    assert plan["peak_isolator_disp_xy"][1] < 1e-15
