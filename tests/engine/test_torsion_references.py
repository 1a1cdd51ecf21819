"""Buildings that twist against an independent OpenSeesPy 3-D model (tests/reference/
opensees_torsion.py: a rigid diaphragm per level, elastomericBearingPlasticity bearings at
their positions, the eccentric mass on a node of the diaphragm, ElasticPPGap elements at the
slab's corners), with and without pounding, within 0.5% (the issue's bound) on the plan
centre's and the worst corner's peak displacements, the peak rotation, the walls' forces
(each wall's total and each corner's), the floors' accelerations and the stories' drifts.

Both components of Northridge 1994 at Beverly Hills - Mulholland (RSN953, 009 as x and 279 as
y) from 2.5 to 7 s (the strong motion: tests/reference/test_opensees_torsion.py), the paper's
building on four bearings at the slab's corners (30 x 20 m), its mass 10% of b_x off centre
along x (and 5% of b_y along y with the walls), bare elastic walls 40 mm clear (all four
hit, every corner against both its walls). Worst deviations measured: CASES' comments (the
compiled loop runs here; it gives the NumPy loop's peaks to 1e-9,
tests/engine/test_torsion.py). The reference's own kinematics are checked on the same run:
its corners follow its diaphragm as the engine's model says, sign of the rotation included.
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

import engine
from engine import Building, Contact, Torsion

pytest.importorskip("openseespy.opensees")

from tests.engine.test_plan_references import deviations  # noqa: E402
from tests.reference import opensees_torsion as ot  # noqa: E402
from tests.reference.test_opensees_torsion import (  # noqa: E402
    CORNER_BEARINGS,
    PLAN,
    SHORT_GAP,
    WALL_K,
    short_pair,
)

TOLERANCE = 5e-3
PEAKS = ("peak_isolator_disp", "peak_corner_disp", "peak_rotation", "peak_total_accel",
         "peak_interstory_drift", "max_impact_force_wall", "max_point_force")
CASES = {
    # name: (eccentricity, walls). Measured (NumPy loop): without walls 1.1e-4 at most (a
    # story drift; the rotation 1.3e-5, the corner 7.8e-6); with the walls 1.4e-3 at most (a
    # corner's force; the walls' totals 6.0e-4, the rotation 8.6e-5, the corner 4.1e-5).
    "eccentric-no-wall": ((0.1 * PLAN[0], 0.0), False),
    "two-way-eccentric-walls": ((0.1 * PLAN[0], -0.05 * PLAN[1]), True),
}


@functools.cache
def engine_runs(backend: str) -> dict[str, dict]:
    """Every case, one member each, in one call per building."""
    pair, pair_dt = short_pair()
    out = {}
    for name, (ecc, walls) in CASES.items():
        building = Building(torsion=Torsion(plan_size=PLAN, mass_offset=ecc,
                                            isolator_positions=CORNER_BEARINGS))
        contact = Contact.linear(SHORT_GAP, k=WALL_K, cor=1.0) if walls else Contact.none(1)
        result = engine.simulate(pair, pair_dt, contact, building, backend=backend)
        out[name] = {k: np.asarray(getattr(result, k))[0] for k in PEAKS}
    return out


@functools.cache
def opensees(name: str) -> dict:
    """The reference's peaks and histories of a case."""
    pair, pair_dt = short_pair()
    ecc, walls = CASES[name]
    return ot.torsion_peaks(pair, pair_dt, plan_size=PLAN, positions=CORNER_BEARINGS,
                            eccentricity=ecc, history=True,
                            **({"gap": SHORT_GAP, "k": WALL_K} if walls else {}))


@pytest.mark.parametrize("case", list(CASES))
def test_engine_matches_opensees_when_the_slab_twists(case):
    got, want = engine_runs("numba")[case], opensees(case)
    assert want["peak_rotation"] > 1e-4  # rad: it twists
    if CASES[case][1]:
        assert np.all(want["max_point_force"] > 0)  # every corner hits both its walls
    worst = deviations(got, want, PEAKS)
    assert max(worst.values()) < TOLERANCE, worst


def test_the_references_corners_follow_its_diaphragm():
    """The reference on its own, against the walls: its corners move as the spec's
    (u_x - theta Y, u_y + theta X) from the master's motion, the sign of theta included, and
    each corner's gap element gives k / 2 times that corner's indentation; twisting, a wall's
    two corners do not share its force equally."""
    got = opensees("two-way-eccentric-walls")
    hist = got["history"]
    corners = np.array(ot.CORNERS) * [PLAN[0] / 2, PLAN[1] / 2]
    want = hist["centre"][:, None, :] + hist["theta"][:, None, None] * np.stack(
        [-corners[:, 1], corners[:, 0]], axis=-1)
    np.testing.assert_allclose(hist["corners"], want, rtol=0, atol=1e-15)
    assert np.linalg.norm(hist["corners"], axis=-1).max() == got["peak_corner_disp"]
    delta = np.column_stack([(1, -1)[w % 2] * hist["corners"][:, c, w // 2] - SHORT_GAP
                             for w, c in ot.POINTS])
    assert np.all(delta.max(axis=0) > 0)  # every corner hit both its walls
    np.testing.assert_allclose(got["max_point_force"], WALL_K / 2 * delta.max(axis=0),
                               rtol=1e-9)
    pairs = got["max_point_force"].reshape(4, 2)
    assert np.all(np.abs(pairs[:, 0] - pairs[:, 1]) > 0.05 * pairs.max(axis=1))
    assert np.all(got["max_impact_force_wall"] >= pairs.max(axis=1))
    assert np.all(got["max_impact_force_wall"] <= pairs.sum(axis=1))

