"""Buildings that twist (engine/torsion.py; loops/numpy_torsion.py and numba_torsion.py): the
invariants that tie the model to the run in plan and to mechanics, on both loops, to 1e-9.

- a slab whose mass is centred, on a symmetric layout, does not turn: its run is the plan
  run's, peak for peak, with every wall law, against bare walls (its corners) and bumpers
  (crushed too: the plan run's wall then k_w times the wall's points, each point behind its
  crushed pad meeting the wall's own k_w);
- turning the pair by 180 degrees and the building with it (its eccentricity reversed)
  mirrors the response: the same peaks, each wall's force on the opposite wall;
- without damping, on bearings that stay elastic, the slab's coupled torsional and
  translational free vibration keeps the energy the central-difference scheme conserves
  (1/2 v' M v at the half step plus 1/2 u_n' K u_{n+1}), to round-off: the loops' forces are
  the stiffness matrix's, stories off centre included;
- every impact law carries its share: Contact.part(s) is s times the law's force.
Pacoima Dam 164 from 1.5 to 3.7 s (its pulse hits every wall), along y the same 0.7 times and
0.4 s later.
"""
from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

import engine
from engine import Building, Contact, History, Isolator, Moat, Torsion
from engine.impact.contact import law_arguments
from engine.impact.registry import LAW_MODULES
from engine.torsion import contact_points, grid_positions, torsion_arrays
from engine.torsion_fields import FIELDS as TORSION_FIELDS

START, END = 1.5, 3.7  # s: the record's quiet start left out, its pulse in
RTOL = 1e-9
PLAN = (30.0, 20.0)  # m
CORNER_BEARINGS = ((-15.0, -10.0), (15.0, -10.0), (15.0, 10.0), (-15.0, 10.0))
BACKENDS = ("numba", "numpy")


@functools.cache
def pair():
    """(T, 2) m/s^2 and its step: the paper's Pacoima record from START to END along x (its
    pulse: every wall is hit from 2.8 s), along y the same 0.7 times and 0.4 s later, so that
    the two differ."""
    from pipeline.records import paper_record

    rec = paper_record("pacoima")
    i0, i1 = (int(t / rec.dt) for t in (START, END))
    x = rec.accel[i0:i1 + 1]
    y = 0.7 * rec.accel[i0 - int(0.4 / rec.dt):i1 + 1 - int(0.4 / rec.dt)]
    return np.column_stack([x, y]), rec.dt


def walls() -> Contact:
    """Every wall law at gaps the pulse reaches."""
    return Contact.concat([Contact.none(1), Contact.linear([0.08, 0.14]),
                           Contact.bumper([0.12], thickness=0.05, n_bumpers=3),
                           Contact.hertzdamp([0.10], k=2.75e9),
                           Contact.jankowski([0.10], beta=2.75e9)])


def assert_peaks_equal(a: dict, b: dict, names=None):
    for name in names or b:
        value = np.asarray(b[name], float)
        np.testing.assert_allclose(np.asarray(a[name], float), value, rtol=RTOL,
                                   atol=RTOL * np.abs(value).max(), err_msg=name)


def plan_peaks(result) -> dict:
    return {**result.peaks(), **result.plan_peaks()}


# The invariants below run on the compiled loop: the NumPy loop gives its numbers to 1e-9
# (test_the_compiled_loop_gives_the_numpy_loops_numbers: eccentric, bumpers where they stand,
# wall friction, both isolator laws, histories), so they hold on it too.
@pytest.mark.parametrize("backend", ["numba"])
@pytest.mark.parametrize("layout", ["grid", "corners", "bumpers"])
def test_a_slab_that_does_not_turn_is_the_plan_run(layout, backend):
    accel, dt = pair()
    contact = walls()
    angle = np.linspace(0.0, 75.0, len(contact))
    bearings = None if layout == "grid" else CORNER_BEARINGS
    bumpers = ((-8.0, 0.0, 8.0), (0.0,)) if layout == "bumpers" else None  # 3 + 3 + 1 + 1
    points = (3, 1) if layout == "bumpers" else (2, 2)  # on each x wall, each y wall
    # each point behind a crushed pad meets the wall's own k_w: all n at once, n k_w
    x_walls, y_walls = (dataclasses.replace(contact, k_w=contact.k_w * n) for n in points)
    plan = engine.simulate(accel, dt, x_walls, Building(), angle=angle, backend=backend,
                           moat=Moat(contact_y=y_walls))
    twist = engine.simulate(accel, dt, contact, Building(torsion=Torsion(
        plan_size=PLAN, isolator_positions=bearings)), angle=angle,
        moat=Moat(bumper_positions=bumpers), backend=backend)
    assert (plan.n_impacts[1:] > 0).all()  # every wall law is hit
    assert np.any(twist.max_point_indentation[3] > contact.delta_u[3])  # the pads crush
    assert_peaks_equal(plan_peaks(twist), plan_peaks(plan))
    assert np.all(twist.peak_rotation < 1e-15)  # rad: round-off only
    np.testing.assert_allclose(twist.peak_corner_disp, plan.peak_isolator_disp, rtol=RTOL)
    # each wall's points share its force equally when the slab does not turn
    walls_of_points = twist.points.wall
    for w in range(4):
        on = walls_of_points == w
        np.testing.assert_allclose(twist.max_point_force[:, on] * on.sum(),
                                   np.repeat(twist.max_impact_force_wall[:, w:w + 1],
                                             on.sum(), axis=1), rtol=RTOL, atol=1e-6)


MIRRORED_WALLS = [1, 0, 3, 2]  # +x <-> -x, +y <-> -y


@pytest.mark.parametrize("backend", ["numba"])  # the NumPy loop: as above
def test_a_half_turn_of_the_pair_mirrors_the_response(backend):
    accel, dt = pair()
    contact = walls()
    ecc = (2.5, -1.5)
    first = engine.simulate(accel, dt, contact,
                            Building(torsion=Torsion(plan_size=PLAN, mass_offset=ecc)),
                            backend=backend)
    turned = engine.simulate(accel, dt, contact, Building(
        torsion=Torsion(plan_size=PLAN, mass_offset=(-ecc[0], -ecc[1]))),
                             angle=180.0, backend=backend)
    assert np.all(first.peak_rotation[1:] > 1e-4)  # it twists
    names = [*plan_peaks(first), "peak_corner_disp", "peak_rotation"]
    names.remove("max_impact_force_wall")
    assert_peaks_equal({**plan_peaks(turned), **turned.torsion_peaks()},
                       {**plan_peaks(first), **first.torsion_peaks()}, names)
    assert_peaks_equal({"wall": turned.max_impact_force_wall[:, MIRRORED_WALLS]},
                       {"wall": first.max_impact_force_wall})


def scheme_energy(t, disp, rotation, dt):
    """(T - 1,) J: 1/2 v' M v + 1/2 u_n' K u_{n+1} of one member from its floors'
    displacements (T, L, 2) m and rotations (T, L) rad, v = (u_{n+1} - u_n) / dt."""
    u = np.concatenate([disp, rotation[..., None]], axis=-1).reshape(len(disp), -1)
    v = np.diff(u, axis=0) / dt
    mass, stiffness = t.mass[0], t.stiffness[0]
    return 0.5 * np.einsum("ti,ij,tj->t", v, mass, v) \
        + 0.5 * np.einsum("ti,ij,tj->t", u[:-1], stiffness, u[1:])


@pytest.mark.parametrize("backend", ["numba"])  # the NumPy loop: as above
def test_undamped_torsional_vibration_keeps_its_energy(backend):
    dt = engine.DEFAULT_DT
    t_pulse = np.arange(0.0, 1.0, 0.01)
    accel = np.zeros((300, 2))
    accel[:t_pulse.size, 0] = 1.5 * np.sin(2 * np.pi * t_pulse)  # m/s^2: one cycle, then rest
    accel[:t_pulse.size, 1] = -0.8 * np.sin(4 * np.pi * t_pulse)
    building = Building(zeta_iso=0.0, zeta_sup=0.0,
                        isolator=Isolator.bilinear(k1=40e6, k2=20e6, fy_ratio=50.0),
                        torsion=Torsion(plan_size=PLAN, mass_offset=(3.0, 2.0),
                                        isolator_positions=((-15.0, -10.0), (15.0, -6.0),
                                                            (9.0, 10.0), (-15.0, 10.0)),
                                        story_stiffness_centre=((2.0, -1.0), (0.0, 0.0),
                                                                (-3.0, 4.0), (1.0, 1.0))))
    result = engine.simulate(accel, 0.01, Contact.none(1), building, dt=dt,
                             history=History([0]), backend=backend)
    hist = result.history
    rest = hist["time"] >= 1.0 + dt
    energy = scheme_energy(torsion_arrays([building], 1), hist["floor_disp"][0, rest],
                           hist["floor_rotation"][0, rest], dt)
    assert np.ptp(hist["floor_rotation"][0, rest, 0]) > 1e-4  # rad: it twists freely
    np.testing.assert_allclose(energy, energy[0], rtol=1e-9)
    assert energy[0] > 1e3  # J


@pytest.mark.parametrize("law", list(LAW_MODULES.values()), ids=lambda m: m.NAME)
def test_every_law_carries_its_share(law):
    """Contact.part(s): the law's elastic force and dashpot times s at any indentation short
    of crushing, rate and impact velocity (what lets a wall's points share its law); past a
    pad's crushing, s times the rubber's force at delta_u plus the wall's own k_w (delta -
    delta_u), written out, and the same restitution factor (dashpot over elastic)."""
    example = {"linear": Contact.linear(0.1), "jankowski": Contact.jankowski(0.1, beta=2.75e9),
               "hertzdamp": Contact.hertzdamp(0.1, k=2.75e9), "bumper": Contact.bumper(0.1)}
    contact = example[law.NAME]
    rng = np.random.default_rng(3)
    delta = np.concatenate([rng.uniform(0, 0.03, 20), [0.045, 0.06]])  # past crushing too
    rate = rng.uniform(-0.5, 0.5, delta.size)
    v_imp = rng.uniform(0.05, 0.8, delta.size)
    for share in (0.5, 1 / 3, 0.125):
        full = law.force_terms(delta, rate, v_imp, law_arguments(contact, law))
        part = contact.part(share)
        got = law.force_terms(delta, rate, v_imp, law_arguments(part, law))
        short = delta < contact.delta_u[0]
        for f, g in zip(full, got, strict=True):
            f, g = (np.broadcast_to(x, delta.shape) for x in (f, g))
            np.testing.assert_allclose(g[short], share * f[short], rtol=1e-12)
        if law.NAME == "bumper":
            k, n, delta_u, k_w = (getattr(contact, name)[0]
                                  for name in ("k", "n", "delta_u", "k_w"))
            past = delta[~short]
            np.testing.assert_allclose(got[0][~short], share * k * delta_u ** n
                                       + k_w * (past - delta_u), rtol=1e-12)
            np.testing.assert_allclose(got[1][~short] * full[0][~short],
                                       full[1][~short] * got[0][~short], rtol=1e-12)
    assert np.any(full[1] > 0)
    assert short.sum() == (20 if law.NAME == "bumper" else 22)  # the pads crushed twice


def test_each_point_behind_a_crushed_pad_adds_the_walls_own_stiffness_to_the_limit():
    """stable_dt of a building that twists, its pads where the moat puts them: 2 / omega_max
    of M^-1 (K + sum over the points of k_p g g'), k_p the stiffer of the point's rubber
    tangent at delta_u (its 1/n of the wall's k_imp) and the wall's own k_w, g the point's
    direction (1, 0, -s) on an x wall, (0, 1, s) on a y wall, written out; simulate refuses a
    step just above it."""
    building = Building(torsion=Torsion(plan_size=PLAN))
    contact = Contact.bumper([0.12], thickness=0.05, n_bumpers=3, k_w=5e9)
    along_x, along_y = (-8.0, 0.0, 8.0), (0.0,)
    t = torsion_arrays([building], 1)
    k = t.stiffness[0].copy()
    k_imp, n, delta_u, k_w = (float(getattr(contact, name)[0])
                              for name in ("k", "n", "delta_u", "k_w"))
    for positions, direction in ((along_x, lambda s: (1.0, 0.0, -s)),
                                 (along_y, lambda s: (0.0, 1.0, s))):
        k_p = max(k_imp / len(positions) * n * delta_u ** (n - 1), k_w)
        for s in positions:  # the same on the opposite wall: -g, the same g g'
            g = np.array(direction(s))
            k[:3, :3] += 2 * k_p * np.outer(g, g)
    lower = np.linalg.cholesky(t.mass[0])
    inverse = np.linalg.inv(lower)
    expected = 2 / np.sqrt(np.linalg.eigvalsh(inverse @ k @ inverse.T)[-1])
    moat = Moat(bumper_positions=(along_x, along_y))
    limit = engine.stable_dt(contact, building, moat=moat)[0]
    assert limit == pytest.approx(expected, rel=1e-12)
    accel, dt = pair()
    with pytest.raises(engine.UnstableTimeStep, match=f"{limit:.4g} s"):
        engine.simulate(accel, dt, contact, building, dt=1.01 * limit, moat=moat)


def test_a_story_off_centre_is_its_springs_moved_there():
    """One story's stiffness about the plan's centre: T' diag(k, k_y, k_theta) T, T the drift
    at its centre (x_s, y_s) = (2, -1) m, written out."""
    k, k_t = 600e6, 3e10
    building = Building(masses=(320e3, 250e3), story_stiffness=(k,), torsion=Torsion(
        plan_size=PLAN, story_torsional_stiffness=(k_t,), story_stiffness_centre=(2.0, -1.0)))
    got = torsion_arrays([building], 1).stiffness[0, 3:, 3:]
    story = np.array([[k, 0.0, k * 1.0], [0.0, k, k * 2.0],
                      [k * 1.0, k * 2.0, k_t + k * (2.0**2 + 1.0**2)]])
    np.testing.assert_allclose(got, story, rtol=1e-15)


def test_the_points_are_the_corners_and_the_bumpers():
    plan = np.array([PLAN])
    corners = contact_points(plan)
    np.testing.assert_array_equal(corners.wall, [0, 0, 1, 1, 2, 2, 3, 3])
    np.testing.assert_array_equal(corners.along[0], [-10, 10, -10, 10, -15, 15, -15, 15])
    # the +x wall's point at Y = -10: its distance grows with u_x and with a clockwise turn
    np.testing.assert_array_equal(corners.direction[0, 0], [1.0, 0.0, 10.0])
    np.testing.assert_array_equal(corners.share, 0.5)
    bumpers = contact_points(plan, ((-5.0, 5.0, 0.0), (3.0,)))
    np.testing.assert_array_equal(bumpers.along[0], [-5, 0, 5, -5, 0, 5, 3, 3])
    np.testing.assert_allclose(bumpers.share, [1 / 3] * 6 + [1.0, 1.0])
    np.testing.assert_array_equal(grid_positions(PLAN, (2, 2)), [[-15, -10], [15, -10],
                                                                 [-15, 10], [15, 10]])


TWISTS = Building(torsion=Torsion(plan_size=PLAN))


@pytest.mark.parametrize("kwargs, match", [
    ({"building": TWISTS, "moat": "circular"}, "twisting model takes 'rectangular'"),
    ({"moat": Moat(bumper_positions=((0.0,), (0.0,)))}, "torsion component"),
    ({"building": TWISTS, "moat": Moat(bumper_positions=((11.0,), (0.0,)))},
     "within the slab"),
    ({"building": [TWISTS, Building()], "contact": Contact.none(2)}, "all twist"),
])
def test_bad_torsion_input(kwargs, match):
    accel, dt = pair()
    arguments = {"contact": Contact.none(1), "building": Building(), **kwargs}
    with pytest.raises(engine.EngineError, match=match):
        engine.simulate(accel, dt, arguments.pop("contact"), arguments.pop("building"),
                        backend="numpy", **arguments)


@pytest.mark.parametrize("fields, match", [
    ({"plan_size": None, "mass_offset": (1.0, 0.0)}, "plan_size"),
    ({"mass_offset": (16.0, 0.0)}, "mass_offset"),
    ({"mass_offset": ((1.0, 0.0),) * 3}, "mass_offset must be .* one pair per level \\(5\\)"),
    ({"isolator_positions": ((0.0, 0.0), (0.0, 0.0))}, "one point"),
    ({"story_torsional_stiffness": (1e10,) * 3}, "story_torsional_stiffness must be 4"),
    ({"story_yield_force": (3e6,) * 4}, "story law 'bilinear': the twisting model takes "
                                        "'linear'"),
    ({"damping": "modal"}, "damping 'modal': the twisting model takes 'paper'"),
    ({"plan_size": (30.0, -1.0)}, "plan_size"),
])
def test_bad_torsion_building(fields, match):
    """Each refusal names its field; what the twisting model does not take quotes SUPPORTS."""
    twist = {name: fields.pop(name) for name in list(fields) if name in TORSION_FIELDS}
    with pytest.raises(engine.EngineError, match=match):
        Building(**fields, torsion=Torsion(**{"plan_size": PLAN, **twist}))


def test_a_planar_record_refuses_a_building_that_twists():
    accel, dt = pair()
    with pytest.raises(engine.EngineError, match="torsion component.*accel as \\(N, 2\\)"):
        engine.simulate(accel[:, 0], dt, Contact.none(1), TWISTS)


def test_the_compiled_loop_gives_the_numpy_loops_numbers():
    """Every peak and history, eccentric, with bumpers where they stand, wall friction, a
    friction pendulum beside the bilinear isolator and histories of repeated members."""
    accel, dt = pair()
    contact = Contact.concat([walls(), Contact.bumper([0.12], n_bumpers=3)])
    size = len(contact)
    corner = Torsion(plan_size=PLAN, mass_offset=(3.0, -1.0), isolator_positions=CORNER_BEARINGS)
    buildings = [Building(torsion=dataclasses.replace(corner, story_stiffness_centre=(-2.0, 1.5))),
                 Building(torsion=corner,
                          isolator=Isolator.friction_pendulum(radius=2.0, mu_slow=0.05,
                                                              mu_fast=0.10, rate=30.0))]
    members = [buildings[i % 2] for i in range(size)]
    options = dict(angle=np.linspace(0.0, 60.0, size),
                   moat=Moat(mu_wall=0.4, bumper_positions=((-8.0, 0.0, 8.0), (-12.0,))),
                   history=History([0, 3, 3], every=3))
    runs = [engine.simulate(accel, dt, contact, members, backend=b, **options)
            for b in BACKENDS]
    compiled, reference = ({**plan_peaks(r), **r.torsion_peaks()} for r in runs)
    assert (reference["n_impacts"][1:] > 0).all() and (reference["peak_rotation"] > 1e-4).all()
    assert_peaks_equal(compiled, reference)
    for name, value in runs[1].history.items():
        np.testing.assert_allclose(runs[0].history[name], value, rtol=RTOL,
                                   atol=RTOL * np.abs(value).max(), err_msg=name)
