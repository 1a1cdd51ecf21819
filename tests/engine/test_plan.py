"""The building in plan (loops/numpy_plan.py and numba_plan.py): the invariants that tie it to
the planar model (on both backends, or on the compiled loop where the two loops' agreement
below covers the case), the two loops against each other, and the coupled slip element's
return mapping.

- a pair whose y component is zero gives the planar run's peaks (every moat, every law);
- with a circular moat and an isotropic building, one component applied at any angle gives
  the planar run's resultant peaks;
- rotating the pair by 90 degrees swaps the x and y peaks, and the walls accordingly.
First 4 s of Pacoima Dam 164 (its pulse: three impacts on every wall), two buildings in one
batch (the paper's; yielding stories on friction pendulums); all to 1e-9.
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

import engine
from engine import Building, Contact, Isolator
from engine.isolators.hysteresis import plastic_spring_force, radial_return

SECONDS = 4.0
RTOL = 1e-9


@functools.cache
def record():
    from pipeline.records import paper_record

    rec = paper_record("pacoima")
    return rec.accel[: int(SECONDS / rec.dt) + 1], rec.dt


def walls() -> Contact:
    """No wall, the bare wall and bumpers, each at gaps the pulse reaches."""
    return Contact.concat([Contact.none(1), Contact.linear([0.08, 0.14]),
                           Contact.bumper([0.10, 0.16], thickness=0.05),
                           Contact.hertzdamp([0.10], k=2.75e9)])


BUILDINGS = (
    Building(),
    Building(story_yield_force=(3e6,) * 4,
             isolator=Isolator.friction_pendulum(radius=2.0, mu_slow=0.05, mu_fast=0.10,
                                                 rate=30.0)),
)


def batch(copies: int = 1) -> tuple[Contact, list]:
    """Every wall on every building, `copies` times over: (contact, buildings)."""
    contact = walls()
    size = len(contact)
    buildings = [b for b in BUILDINGS for _ in range(size)] * copies
    return Contact.concat([contact] * len(BUILDINGS) * copies), buildings


BACKENDS = ("numba", "numpy")


@functools.cache
def planar(backend: str) -> dict:
    accel, dt = record()
    contact, buildings = batch()
    result = engine.simulate(accel, dt, contact, buildings, backend=backend)
    assert (result.n_impacts[1:len(walls())] > 0).all()  # every wall is hit
    return result.peaks()


def assert_peaks_equal(a: dict, b: dict):
    for name, value in b.items():
        np.testing.assert_allclose(a[name], value, rtol=RTOL, atol=RTOL * np.abs(value).max(),
                                   err_msg=name)


# On the compiled loop: the NumPy loop gives its numbers to 1e-9 in both moats
# (test_the_compiled_loop_gives_the_numpy_loops_numbers).
@pytest.mark.parametrize("backend", ["numba"])
@pytest.mark.parametrize("moat", ["rectangular", "circular"])
def test_pair_without_y_component_is_the_planar_run(moat, backend):
    accel, dt = record()
    contact, buildings = batch()
    plan = engine.simulate(np.column_stack([accel, np.zeros_like(accel)]), dt, contact,
                           buildings, moat=moat, backend=backend)
    assert isinstance(plan, engine.PlanResult) and plan.moat == moat
    assert_peaks_equal(plan.peaks(), planar(backend))
    assert_peaks_equal({"x": plan.peak_isolator_disp_xy[:, 0]},
                       {"x": planar(backend)["peak_isolator_disp"]})
    np.testing.assert_array_equal(plan.peak_isolator_disp_xy[:, 1], 0.0)


# The invariants of a general pair (angles, rotations) on the compiled loop: the NumPy loop
# gives its numbers on real pairs at many angles, every wall, both buildings and both moats
# (test_the_compiled_loop_gives_the_numpy_loops_numbers, to 1e-9). A pair whose y component is
# exactly zero (test_pair_without_y_component_is_the_planar_run) stays on both loops.
GENERAL_PAIR_BACKENDS = ("numba",)


@pytest.mark.parametrize("backend", GENERAL_PAIR_BACKENDS)
def test_one_component_at_any_angle_in_a_circular_moat_is_the_planar_run(backend):
    accel, dt = record()
    contact, buildings = batch(copies=2)
    size = len(contact) // 2
    # The component along 37 degrees (as the member's angle) and along 121 degrees (as a pair)
    theta = np.radians(121.0)
    first = engine.simulate(np.column_stack([accel, np.zeros_like(accel)]), dt,
                            contact[:size], buildings[:size], moat="circular", angle=37.0,
                            backend=backend)
    second = engine.simulate(np.column_stack([np.cos(theta) * accel, np.sin(theta) * accel]),
                             dt, contact[size:], buildings[size:], moat="circular",
                             backend=backend)
    for result in (first, second):
        assert_peaks_equal(result.peaks(), planar(backend))
    # ... and along 37 degrees the motion divides between x and y by cos and sin
    np.testing.assert_allclose(first.peak_isolator_disp_xy,
                               planar(backend)["peak_isolator_disp"][:, None]
                               * np.abs([np.cos(np.radians(37)), np.sin(np.radians(37))]),
                               rtol=RTOL)


@pytest.mark.parametrize("backend", GENERAL_PAIR_BACKENDS)
def test_rotating_the_pair_by_90_degrees_swaps_x_and_y(backend):
    """x' = -y, y' = x: the +x wall takes what the -y wall took, -x +y, +y +x, -y -x."""
    accel, dt = record()
    pair = np.column_stack([accel, 0.6 * accel[::-1]])
    contact, buildings = batch(copies=2)
    size = len(contact) // 2
    result = engine.simulate(pair, dt, contact, buildings, moat="rectangular",
                             angle=np.repeat([0.0, 90.0], size), backend=backend)
    first, turned = slice(0, size), slice(size, 2 * size)
    assert_peaks_equal({k: v[turned] for k, v in result.peaks().items()},
                       {k: v[first] for k, v in result.peaks().items()})
    for name, value in result.plan_peaks().items():
        expected = value[first][..., ::-1] if name.endswith("_xy") \
            else value[first][:, [3, 2, 0, 1]]
        np.testing.assert_allclose(value[turned], expected, rtol=RTOL,
                                   atol=RTOL * np.abs(value).max(), err_msg=name)
    assert (result.max_impact_force_wall[first] > 0).sum() >= 4  # walls in both directions


@pytest.mark.parametrize("moat", ["rectangular", "circular"])
def test_the_compiled_loop_gives_the_numpy_loops_numbers(moat):
    """A real pair (a record and its reversal), every wall, both buildings, many angles."""
    accel, dt = record()
    pair = np.column_stack([accel, 0.7 * accel[::-1]])
    contact, buildings = batch()
    angles = np.linspace(0.0, 150.0, len(contact))
    fast, ref = (engine.simulate(pair, dt, contact, buildings, moat=moat, angle=angles,
                                 backend=backend) for backend in BACKENDS)
    assert (ref.n_impacts[1:] > 0).any()
    np.testing.assert_array_equal(fast.n_impacts, ref.n_impacts)
    assert_peaks_equal({**fast.peaks(), **fast.plan_peaks()},
                       {**ref.peaks(), **ref.plan_peaks()})


@pytest.mark.parametrize("moat", ["rectangular", "circular"])
def test_orbits_on_both_backends(moat):
    """The histories in plan: the orbit's largest radius is the resultant peak, the loops
    agree, and a pair without y component records the planar history along x."""
    accel, dt = record()
    pair = np.column_stack([accel, 0.7 * accel[::-1]])
    contact, buildings = batch()
    wanted = engine.History(members=[1, 4, 1], every=1)
    fast, ref = (engine.simulate(pair, dt, contact, buildings, moat=moat, history=wanted,
                                 backend=backend) for backend in BACKENDS)
    for name in ("isolator_disp", "total_accel", "impact_force", "indentation"):
        np.testing.assert_allclose(fast.history[name], ref.history[name], rtol=RTOL,
                                   atol=RTOL * np.abs(ref.history[name]).max(), err_msg=name)
    orbit = fast.history["isolator_disp"]  # (3, T, 2)
    assert orbit.shape == (3, fast.history["time"].size, 2)
    np.testing.assert_allclose(np.hypot(orbit[..., 0], orbit[..., 1]).max(axis=1),
                               fast.peak_isolator_disp[[1, 4, 1]], rtol=1e-12)
    np.testing.assert_allclose(fast.history["impact_force"].max(axis=1),
                               fast.max_impact_force[[1, 4, 1]], rtol=1e-12)
    x_only = engine.simulate(np.column_stack([accel, np.zeros_like(accel)]), dt, contact,
                             buildings, moat=moat, history=wanted)
    flat = engine.simulate(accel, dt, contact, buildings, history=wanted)
    np.testing.assert_allclose(x_only.history["isolator_disp"][..., 0],
                               flat.history["isolator_disp"], rtol=RTOL, atol=1e-15)
    np.testing.assert_allclose(x_only.history["impact_force"], flat.history["impact_force"],
                               rtol=RTOL, atol=RTOL * flat.history["impact_force"].max())


def test_corner_hits_load_both_walls_and_the_circle_differs():
    """The same pair in a square moat and in the circle inscribed in it: at a corner both
    walls push; the circle, closer to the slab along the diagonals, is hit at least as hard."""
    accel, dt = record()
    pair = np.column_stack([accel, accel])  # along the diagonal
    contact = Contact.linear([0.08])
    square = engine.simulate(pair, dt, contact, moat="rectangular")
    circle = engine.simulate(pair, dt, contact, moat="circular")
    forces = square.max_impact_force_wall[0]
    assert forces[0] > 0 and forces[2] > 0 and forces[0] == pytest.approx(forces[2], rel=1e-9)
    assert circle.peak_isolator_disp[0] < square.peak_isolator_disp[0]
    assert circle.n_impacts[0] >= 1


def test_radial_return():
    rng = np.random.default_rng(7)
    f = rng.normal(size=(2, 1000)) * 0.5
    du = rng.normal(size=(2, 1000)) * 0.3
    fx, fy = radial_return(f[0], f[1], du[0], du[1], 2.0, 1.0)
    trial = f + 2.0 * du
    size = np.hypot(*trial)
    outside = size > 1.0
    np.testing.assert_allclose(np.hypot(fx, fy)[outside], 1.0, rtol=1e-15)  # on the circle
    np.testing.assert_allclose(fx[~outside], trial[0][~outside], rtol=0)    # elastic inside
    # along the trial direction, and along x alone the 1-D law
    np.testing.assert_allclose(np.arctan2(fy, fx), np.arctan2(trial[1], trial[0]), atol=1e-12)
    x = radial_return(f[0], 0.0 * f[0], du[0], 0.0 * du[0], 2.0, 1.0)[0]
    np.testing.assert_allclose(x, plastic_spring_force(f[0], du[0], 2.0, 1.0), rtol=1e-15)
    # slipping along x leaves the element softer along y: less than the elastic k dy
    fx, fy = radial_return(1.0, 0.0, 0.0, 0.01, 2.0, 1.0)
    assert 0 < fy < 2.0 * 0.01 and np.hypot(fx, fy) == pytest.approx(1.0)


@pytest.mark.parametrize("kwargs, match", [
    ({"moat": "hexagonal"}, "moat must be one of"),
    ({"moat": engine.Moat(contact_y=Contact.linear([0.1, 0.2]))}, "contact_y"),
    ({"history": engine.History([5])}, "history.members"),
    ({"angle": [1.0, 2.0]}, "angle"),
])
def test_bad_plan_input(kwargs, match):
    accel, dt = record()
    with pytest.raises(engine.EngineError, match=match):
        engine.simulate(np.column_stack([accel, accel]), dt, Contact.linear([0.1]), **kwargs)
    with pytest.raises(engine.EngineError, match="moat: the planar model takes none"):
        engine.simulate(accel, dt, Contact.linear([0.1]), moat="circular")


def test_each_member_steps_with_its_own_buildings_operators_in_a_mixed_batch():
    """The loops build the step operators once per distinct building and index them per member:
    in a batch of buildings alike along y but not along x (the second is the first's
    y direction turned: their y arrays are one building), and an isotropic third, each
    member's peaks are its building's run alone, to an ulp (the isotropic building's story
    shear peaks alone as stiffness times drift, in a batch stiffer along y from its forces)."""
    accel, dt = record()
    pair = np.column_stack([accel, 0.7 * accel])
    base = Building()
    turned = Building(story_stiffness=(6e8, 6e8, 5e8, 4e8),
                      story_stiffness_y=tuple(base.story_stiffness))
    buildings = [turned, base, Building(story_stiffness_y=(9e8, 9e8, 8e8, 7e8))] * 2
    contact = Contact.linear([0.08] * len(buildings))
    together = engine.simulate(pair, dt, contact, buildings, backend="numba").peaks()
    for member, building in enumerate(buildings[:3]):
        alone = engine.simulate(pair, dt, Contact.linear(0.08), building,
                                backend="numba").peaks()
        for name, value in alone.items():
            for copy in (member, member + 3):
                np.testing.assert_allclose(together[name][copy], value[0], rtol=1e-15, atol=0,
                                           err_msg=name)
