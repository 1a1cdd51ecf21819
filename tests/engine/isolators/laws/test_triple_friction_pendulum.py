"""The triple friction pendulum (engine/isolators/laws/triple_friction_pendulum.py) and its
series solve (engine/isolators/series.py): the declaration and its checks; Dao et al.'s
(2013) check case, the rigid-plastic backbone of regimes I-V, and the law pushed
quasi-statically onto it once the pre-slip displacements are counted; the code's formulas
against the law's own loops; OpenSees' TripleFrictionPendulum element along a path and an
orbit (the same forces to round-off), and the building on it in a short run along one
direction and in plan, with and without a moat wall (every peak within TOLERANCE: the issue
asks for 1%); the two time loops on the building.

Measured (numba loop, RSN953's 2.5-5 s, 0.5 ms): the worst peak deviation from OpenSees, along
one direction 0.03% without wall and 0.10% with (3 impacts), in plan 0.03% and 0.09% (5
impacts). OpenSees' element needs its tol at 1e-8: at 1e-10 its own iterations fail on some
steps of a dynamic run, and its force then leaves its own series model (stale for a step,
or a drop of up to 4%: tests/reference/opensees_plan.py).
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

import engine
from engine import Building, Contact, Isolator
from engine.isolators import series
from engine.isolators.registry import LAW_CODES, LAWS
from tests.reference.opensees_plan import isolator_path, plan_peaks

LAW = LAWS["triple_friction_pendulum"]
DAO = dict(L1=0.36, L2=1.25, L3=1.25, d1=0.1, d2=0.2, d3=0.2, mu1=0.012, mu2=0.052, mu3=0.14)
"""Dao et al. (2013)'s check case (their Table 1; OpenSees' example of the element)."""
G = 9.81
MASS = 1000.0 / G  # kg: a weight of 1000 N, forces in per mille of it
WEIGHT = 1000.0
TOLERANCE = 5e-3
"""Every peak of the building against OpenSees (the issue's bound is 1%; the worst measured
is 0.10%)."""


def _push(isolator, path, plan=False, states=None):
    """The law's force (N) after each point of a displacement path (m) from rest, along x
    ((T,) path) or in plan ((T, 2) path), one step per point, through its advance and force as
    written (the compiled loops' are the same bits: tests/engine/loops/
    test_numpy_isolators.py). states: a list receiving each step's state."""
    row = isolator.row(MASS, G)
    if not plan:
        state, out = np.zeros(len(LAW.STATE)), np.empty(len(path))
        for i, du in enumerate(np.diff(path, prepend=0.0)):
            LAW.advance(state, du, 1.0, row)
            out[i] = LAW.force(path[i], state, row)
        return out
    state, out = np.zeros(len(LAW.STATE_XY)), np.empty_like(path)
    for i, (dx, dy) in enumerate(np.diff(path, axis=0, prepend=0.0)):
        LAW.advance_xy(state, dx, dy, 1.0, row)
        out[i] = LAW.force_xy(*path[i], state, row)
        if states is not None:
            states.append(state.copy())
    return out


def test_the_declaration_and_its_checks():
    iso = Isolator.triple_friction_pendulum(**DAO)
    assert iso == Isolator.of("triple_friction_pendulum", **DAO, yield_disp=5e-4)
    assert iso.code == LAW_CODES["triple_friction_pendulum"] and iso.default_zeta == 0.0
    assert iso.initial_stiffness(MASS, G) == pytest.approx(0.012 * WEIGHT / 5e-4, rel=1e-14)
    assert iso.yield_displacement(MASS, G) == 5e-4
    fields = iso.fields(MASS, G)
    stop = 3 * 0.012 * WEIGHT / 5e-4  # OpenSees: every element's E = 3 mu1 W / uy
    assert fields["stop"] == pytest.approx(stop, rel=1e-14)
    for name, pendulum, mu, gap in (("inner", WEIGHT / 0.72, 0.012, 2 * (0.36 * 0.2 / 1.25 + 0.1)),
                                    ("lower", WEIGHT / 0.89, 0.052, 0.2 * (1 - 0.36 / 1.25)),
                                    ("upper", WEIGHT / 0.89, 0.14, 0.2 * (1 - 0.36 / 1.25))):
        assert fields[f"pendulum_{name}"] == pytest.approx(pendulum, rel=1e-14)
        assert fields[f"slip_{name}"] == pytest.approx(stop - pendulum, rel=1e-14)
        assert fields[f"limit_{name}"] == pytest.approx(mu * WEIGHT * (1 - pendulum / stop),
                                                        rel=1e-14)
        assert fields[f"gap_{name}"] == pytest.approx(gap, rel=1e-14)
    assert set(LAW.CARRIED) == {n for n in LAW.ROW._fields if not n.startswith("gap")}
    for bad, match in (({"L2": 0.3}, "L1 < L2 and L1 < L3"),
                       ({"mu2": 0.2}, "mu1 <= mu2 <= mu3"),
                       ({"mu1": 0.06}, "mu1 <= mu2 <= mu3")):
        with pytest.raises(engine.EngineError, match=match):
            Isolator.triple_friction_pendulum(**{**DAO, **bad})
    with pytest.raises(engine.EngineError, match="yield_disp=0.05 is too large"):
        Isolator.triple_friction_pendulum(**DAO, yield_disp=0.05)
    with pytest.raises(engine.EngineError, match="L1 is required"):
        Isolator.of("triple_friction_pendulum", **{k: v for k, v in DAO.items() if k != "L1"})


def test_the_backbone_is_dao_et_al_s():
    """Dao et al.'s regimes of the rigid-plastic series: F/W 0.052 at 0.0288 m, 0.14 at 0.1705,
    0.212 at 0.3505, 0.30 at 0.4922, 0.4498 at the ultimate 0.600 m (their printed digits),
    slopes 1/0.72, 1/1.61, 1/2.5, 1/1.61, 1/0.72 per m."""
    values = Isolator.triple_friction_pendulum(**DAO).values
    corners = np.array([0.0288, 0.1705, 0.3505, 0.4922, 0.600])
    force = LAW.backbone(MASS, G, corners, **values) / WEIGHT
    np.testing.assert_allclose(force, [0.052, 0.14, 0.212, 0.30, 0.4498], rtol=5e-4)
    middles = np.concatenate([[0.01], 0.5 * (corners[:-1] + corners[1:])])
    slopes = (LAW.backbone(MASS, G, middles + 1e-4, **values)
              - LAW.backbone(MASS, G, middles - 1e-4, **values)) / 2e-4 / WEIGHT
    np.testing.assert_allclose(slopes, 1 / np.array([0.72, 1.61, 2.5, 1.61, 0.72]), rtol=1e-9)


def _series_deformation(force, uy):
    """m: the displacement of the elastic-plastic series carrying `force` (N, > 0) pushed
    from rest, written here from the model: each element elastic at E = 3 mu1 W / uy up to
    its friction mu_i W, then sliding at its pendulum stiffness k_i, past its gap stiffer by
    E (OpenSees' element)."""
    e = 3 * 0.012 * WEIGHT / uy
    total = 0.0
    for pendulum, mu, gap in ((WEIGHT / 0.72, 0.012, 0.3152), (WEIGHT / 0.89, 0.052, 0.1424),
                              (WEIGHT / 0.89, 0.14, 0.1424)):
        friction = mu * WEIGHT
        d = force / e if force <= friction else friction / e + (force - friction) / pendulum
        if d > gap:  # the stop engaged at the force where the sliding element reached it
            at_gap = friction + (gap - friction / e) * pendulum
            d = gap + (force - at_gap) / (pendulum + e)
        total += d
    return total


@pytest.mark.parametrize("plan", [False, True], ids=["one-axis", "plan"])
def test_a_quasi_static_push_is_the_backbone_with_its_pre_slip_displacements(plan):
    """Pushed to the displacement the series carries Dao et al.'s corner forces at (their
    backbone plus each element's pre-slip displacement, mu_i W / E once sliding, and its
    stop's give), the law carries those forces; with a pre-slip displacement of 1 micron its
    slopes are the backbone's."""
    iso = Isolator.triple_friction_pendulum(**DAO, yield_disp=1e-3)
    forces = WEIGHT * np.array([0.052, 0.14, 0.212, 0.30, 0.4498, 0.5])
    targets = np.array([_series_deformation(f, 1e-3) for f in forces])
    path = np.sort(np.concatenate([np.linspace(0.0, 0.7, 141), targets]))
    pushed = _push(iso, np.column_stack([path, 0 * path]) if plan else path, plan)
    got = pushed[np.searchsorted(path, targets), 0] if plan else \
        pushed[np.searchsorted(path, targets)]
    np.testing.assert_allclose(got, forces, rtol=1e-12)
    # in the rigid-plastic limit, the backbone's slopes
    iso = Isolator.triple_friction_pendulum(**DAO, yield_disp=1e-6)
    path = np.linspace(0.0, 0.6, 1201)
    pushed = _push(iso, path)
    for lo, hi, slope in ((0.005, 0.025, 1 / 0.72), (0.05, 0.15, 1 / 1.61),
                          (0.2, 0.34, 1 / 2.5), (0.37, 0.48, 1 / 1.61), (0.5, 0.59, 1 / 0.72)):
        i, j = np.searchsorted(path, [lo, hi])
        assert (pushed[j] - pushed[i]) / (path[j] - path[i]) / WEIGHT == \
            pytest.approx(slope, rel=1e-3)


def _loop_energy(isolator, amplitude, steps=500):
    """J: the area of the law's loop over one full cycle of u = amplitude sin, after the
    virgin quarter."""
    t = np.linspace(0.0, 1.25, 5 * steps + 1)
    u = amplitude * np.sin(2 * np.pi * t)
    force = _push(isolator, u)
    return float(np.trapezoid(force[steps:], u[steps:]))


@pytest.mark.parametrize("amplitude", [0.02, 0.1, 0.3, 0.45, 0.58],
                         ids=["regime-I", "II", "III", "IV", "V"])
def test_the_code_formulas_are_the_law_s_own(amplitude):
    """energy_per_cycle against the area of the law's loop (a pre-slip displacement of 1
    micron); effective_stiffness the backbone's secant; post_yield_stiffness W / (L2 + L3),
    below the secant everywhere; the code's design runs on it; bounded scales the friction."""
    iso = Isolator.triple_friction_pendulum(**DAO, yield_disp=1e-6)
    energy = iso.energy_per_cycle(MASS, G, amplitude)
    assert _loop_energy(iso, amplitude) == pytest.approx(energy, rel=2e-3)
    values = iso.values
    assert iso.effective_stiffness(MASS, G, amplitude) == pytest.approx(
        LAW.backbone(MASS, G, amplitude, **values) / amplitude, rel=1e-15)
    k_d = iso.post_yield_stiffness(MASS, G)
    assert k_d == pytest.approx(WEIGHT / 2.5, rel=1e-15)
    grid = np.geomspace(1e-4, 2.0, 200)
    assert (iso.effective_stiffness(MASS, G, grid) > k_d).all()
    assert LAW.bounded(values, 0.8, 1.7) == {**values, "mu1": 0.8 * 0.012,
                                             "mu2": 0.8 * 0.052, "mu3": 0.8 * 0.14}


def test_the_code_s_design_runs_on_it():
    from pipeline.motions.target import isolation_design

    building = Building(isolator=Isolator.triple_friction_pendulum(
        L1=0.3, L2=2.0, L3=2.0, d1=0.05, d2=0.3, d3=0.3, mu1=0.02, mu2=0.04, mu3=0.08))
    design = isolation_design(0.6, building)
    assert 0.1 < design.d_m < 0.6 and 2.0 < design.t_m < 4.0 and 0.05 < design.beta_m < 0.4


OPENSEES_TFP = {"kind": "triple_friction_pendulum", **DAO, "yield_disp": 1e-3}


def test_a_path_along_one_axis_is_opensees_element():
    """Cycles growing to past the outer stops (0.55 m), one axis: OpenSees'
    TripleFrictionPendulum and the law (along one axis and in plan) give the same forces to
    round-off (measured 3.5e-14)."""
    t = np.linspace(0.0, 1.0, 401)
    path = 0.55 * np.sin(3 * np.pi * t) * np.sqrt(t)
    u = np.column_stack([path, 0 * path])
    building = Building()
    reference = isolator_path(u, isolator=OPENSEES_TFP)
    iso = Isolator.triple_friction_pendulum(**DAO, yield_disp=1e-3)
    scale = building.total_mass / MASS
    assert np.abs(reference[:, 1]).max() == 0.0
    along = _push(iso, path) * scale
    in_plan = _push(iso, u, plan=True) * scale
    largest = np.abs(reference).max()
    assert largest > 0.3 * building.g * building.total_mass  # past the outer stops
    assert np.abs(along - reference[:, 0]).max() < 1e-12 * largest
    assert np.abs(in_plan - reference).max() < 1e-12 * largest


def test_an_orbit_in_plan_is_opensees_element():
    """An orbit in plan growing to 0.45 m (every element sliding, the outer stops met): the
    same forces as OpenSees' element to its tolerance (measured 4e-12); and every step's
    elements carry one force and add up to the bearing (the solve converged)."""
    t = np.linspace(0.0, 1.0, 600)
    u = np.column_stack([0.45 * np.sin(4 * np.pi * t), 0.4 * np.sin(5.4 * np.pi * t + 0.4)]) \
        * np.minimum(3 * t, 1.0)[:, None]
    building = Building()
    reference = isolator_path(u, isolator=OPENSEES_TFP)
    iso = Isolator.triple_friction_pendulum(**DAO, yield_disp=1e-3)
    states = []
    forces = _push(iso, u, plan=True, states=states) * building.total_mass / MASS
    largest = np.abs(reference).max()
    assert largest > 0.3 * building.g * building.total_mass
    assert np.abs(forces - reference).max() < 1e-9 * largest
    # converged: the elements add up to the bearing, each carries its force by its own law
    states = np.array(states)
    moved = np.diff(states[:, :6].reshape(-1, 3, 2).sum(axis=1), axis=0, prepend=0.0)
    assert np.abs(moved - np.diff(u, axis=0, prepend=0.0)).max() <= series.TOLERANCE
    for k, (pendulum, _, _, gap, stop) in enumerate(series.elements(iso.row(MASS, G))):
        d = states[:, 2 * k: 2 * k + 2]
        reach = np.hypot(*d.T)[:, None]
        own = pendulum * d + states[:, 6 + 2 * k: 8 + 2 * k] \
            + stop * np.maximum(reach - gap, 0.0) * d / np.maximum(reach, 1e-300)
        assert np.abs(own - states[:, 12:14]).max() < 1e-9 * WEIGHT
    assert (np.hypot(*states[:, 2:4].T) > 0.1424).any()  # an outer stop met


SECONDS = (2.5, 5.0)  # s of RSN953: its strong motion
COMPONENTS = ("RSN953:009", "RSN953:279")  # x, y
BUILDING_TFP = dict(L1=0.3, L2=2.0, L3=2.0, d1=0.05, d2=0.3, d3=0.3, mu1=0.02, mu2=0.04,
                    mu3=0.08)
"""A bearing for the paper's building: the three effective radii 0.3, 2.0, 2.0 m (regime III
period 4 s)."""
GAP, WALL_K = 0.05, 2.5e9  # m, N/m: a rectangular moat of elastic walls (COR 1)


@functools.cache
def _pair(start: float = SECONDS[0], end: float = SECONDS[1]) -> tuple[np.ndarray, float]:
    from pipeline.records import load_record

    x, y = (load_record(name) for name in COMPONENTS)
    i, j = int(round(start / x.dt)), int(round(end / x.dt)) + 1
    return np.column_stack([x.accel[i:j], y.accel[i:j]]), x.dt


def _engine(plan: bool, backend: str = "numba", seconds=SECONDS, gap=GAP):
    """Peaks of the paper's building on the bearing, no wall and walls at `gap`, by name (and
    their per-direction ones in plan), member 0 without wall, 1 with."""
    pair, dt = _pair(*seconds)
    building = Building(isolator=Isolator.triple_friction_pendulum(**BUILDING_TFP))
    contact = Contact.concat([Contact.none(1), Contact.linear([gap], k=WALL_K, cor=1.0)])
    result = engine.simulate(pair if plan else pair[:, 0], dt, contact, [building] * 2,
                             backend=backend)
    return {**result.peaks(), **(result.plan_peaks() if plan else {})}


@pytest.mark.parametrize("wall", [False, True], ids=["no-wall", "wall"])
@pytest.mark.parametrize("plan", [False, True], ids=["one-direction", "plan"])
def test_the_building_on_it_matches_opensees(plan, wall):
    """The compiled loop against OpenSees (Newmark, the same 0.5 ms) along one direction (the
    pair's x component, y zero) and in plan: every peak within TOLERANCE, the same impacts.
    The NumPy loop gives the compiled loop's peaks (test_both_loops_agree_on_the_building),
    so it meets these bounds too without running each case twice."""
    pair, dt = _pair()
    peaks = {name: value[int(wall)] for name, value in _engine(plan).items()}
    reference = plan_peaks(pair if plan else pair * [1.0, 0.0], dt, dt=engine.DEFAULT_DT,
                           isolator={"kind": "triple_friction_pendulum", **BUILDING_TFP},
                           gap=GAP if wall else None, k=WALL_K if wall else None)
    assert peaks["n_impacts"] == reference["n_impacts"] and (peaks["n_impacts"] > 0) == wall
    names = ["peak_total_accel", "peak_interstory_drift", "peak_isolator_disp"]
    if plan:
        names += ["peak_total_accel_xy", "peak_interstory_drift_xy", "peak_isolator_disp_xy"]
    else:  # along x: the reference's x peaks
        reference = {**reference, "peak_total_accel": reference["peak_total_accel_xy"][:, 0],
                     "peak_interstory_drift": reference["peak_interstory_drift_xy"][:, 0],
                     "peak_isolator_disp": reference["peak_isolator_disp_xy"][0]}
    if wall:
        names += ["max_indentation", "max_impact_force"]
    assert peaks["peak_isolator_disp"] > 0.05  # every element slides (regime III)
    for name in names:
        np.testing.assert_allclose(peaks[name], reference[name], rtol=TOLERANCE, err_msg=name)


@pytest.mark.parametrize("plan", [False, True], ids=["one-direction", "plan"])
def test_both_loops_agree_on_the_building(plan):
    """The NumPy loop gives the compiled loop's peaks on the building to 1e-9 (0.4 s of the
    record from rest, walls at 0.03 m met)."""
    fast, reference = (_engine(plan, backend, (3.8, 4.2), 0.03) for backend in ("numba", "numpy"))
    assert fast["n_impacts"][1] > 0
    for name, value in fast.items():
        np.testing.assert_allclose(value, reference[name], rtol=1e-9, atol=0, err_msg=name)
