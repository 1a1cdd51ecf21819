"""The OpenSees 3-D reference of a building that twists (tests/reference/opensees_torsion.py)
against closed forms; the pair and the cases its transient model runs under, which
tests/engine/test_torsion_references.py compares with the engine (and checks the reference's
own kinematics on).

The rigid slab on linear bearings has the stiffness matrix, about its mass centre (p_i, q_i the
bearings' positions from it),
    K = sum_i k_i [[1, 0, -q_i], [0, 1, p_i], [-q_i, p_i, p_i^2 + q_i^2]],
and the mass matrix diag(m, m, J): its frequencies are those of M^-1 K, and a torque T alone
twists a symmetric layout by T / sum k_i r_i^2 without moving its centre. The whole building
of the transient model (its initial tangent: K1 / n per bearing) has the spec's matrices about
the plan centres (measured: its frequencies to 1e-13).

Measured when the reference was written, not rerun by the suite (the engine equals both
OpenSees references, and its symmetric slab its plan run, which implies it): under both
horizontal components of the plan references' record (Northridge 1994 at Beverly Hills -
Mulholland, RSN953 009 as x and 279 as y) from 2.5 s (the motion before is ~1 mm) to 7 s, the
paper's building at the engine's 0.5 ms, symmetric on four bearings at the slab's corners, the
model does not twist (theta ~1e-20 rad) and its plan centre's peaks are
opensees_plan.plan_peaks' (6e-14 relative without walls, 2e-14 with elastic walls at 40 mm,
all four hit, whose two corners of k / 2 carry one wall of k). Run times (one core, idle):
3.7 s without walls, 4.1 s with them, 1.1 s for the planar model.
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

pytest.importorskip("openseespy.opensees")

from pipeline.motions.torsion import grid_positions  # noqa: E402
from tests.reference import opensees_torsion as ot  # noqa: E402

MASS = 1.53e6  # kg, the paper's building's total mass
PLAN = (30.0, 20.0)  # m
K_BEARING = 24e6 / 16  # N/m: the paper's post-yield isolation stiffness over 16 bearings


def closed_form(mass, plan, positions, k, eccentricity):
    """(3,) rad/s from M^-1 K about the mass centre."""
    p = positions[:, 0] - eccentricity[0]
    q = positions[:, 1] - eccentricity[1]
    ks = np.broadcast_to(k, p.shape)
    stiffness = np.array([[ks.sum(), 0.0, -(ks * q).sum()],
                          [0.0, ks.sum(), (ks * p).sum()],
                          [-(ks * q).sum(), (ks * p).sum(), (ks * (p**2 + q**2)).sum()]])
    inertia = ot.slab_inertia(mass, plan)
    m_isqrt = 1 / np.sqrt([mass, mass, inertia])
    return np.sqrt(np.sort(np.linalg.eigvalsh(m_isqrt[:, None] * stiffness * m_isqrt)))


@pytest.mark.parametrize("eccentricity", [(0.0, 0.0), (1.5, 0.0), (1.5, -2.0)])
def test_frequencies_are_the_closed_forms(eccentricity):
    positions = grid_positions(PLAN)
    got = ot.eigen_frequencies(MASS, PLAN, positions, K_BEARING, eccentricity)
    np.testing.assert_allclose(got, closed_form(MASS, PLAN, positions, K_BEARING,
                                                np.asarray(eccentricity)), rtol=1e-9)
    if eccentricity == (0.0, 0.0):  # symmetric: x and y at sqrt(sum k / m), twist apart
        np.testing.assert_allclose(got[:2], np.sqrt(16 * K_BEARING / MASS), rtol=1e-9)


def test_a_torque_twists_a_symmetric_layout_about_its_centre():
    positions = grid_positions(PLAN)
    torque = 5e6  # N m
    got = ot.static_twist(MASS, PLAN, positions, K_BEARING, torque)
    polar = K_BEARING * np.sum(positions**2)
    assert abs(got[0]) < 1e-12 and abs(got[1]) < 1e-12
    assert got[2] == pytest.approx(torque / polar, rel=1e-12)


def building_matrices(masses, story_k, k_theta, inertia, eccentricity, positions, k_bearing):
    """(3L, 3L) mass and stiffness matrices of the spec about the plan centres, DOFs
    (u_x, u_y, theta) of levels 0..N."""
    n_lev = len(masses)
    m_mat, k_mat = np.zeros((3 * n_lev, 3 * n_lev)), np.zeros((3 * n_lev, 3 * n_lev))
    e_x, e_y = eccentricity
    for j, (m, inert) in enumerate(zip(masses, inertia, strict=True)):
        m_mat[3 * j:3 * j + 3, 3 * j:3 * j + 3] = [
            [m, 0, -m * e_y], [0, m, m * e_x], [-m * e_y, m * e_x, inert + m * (e_x**2 + e_y**2)]]
    for x, y in positions:
        k_mat[:3, :3] += k_bearing * np.array([[1, 0, -y], [0, 1, x], [-y, x, x**2 + y**2]])
    for s, (k, k_t) in enumerate(zip(story_k, k_theta, strict=True)):
        block = np.diag([k, k, k_t])
        i, j = slice(3 * s, 3 * s + 3), slice(3 * s + 3, 3 * s + 6)
        k_mat[i, i] += block
        k_mat[j, j] += block
        k_mat[i, j] -= block
        k_mat[j, i] -= block
    return m_mat, k_mat


@pytest.mark.parametrize("eccentricity", [(0.0, 0.0), (3.0, -1.0)])
def test_the_transient_models_matrices_are_the_specs(eccentricity):
    import openseespy.opensees as ops
    import scipy.linalg

    positions = grid_positions(PLAN)
    bld = ot.build_transient(np.zeros((2, 2)), 0.01, plan_size=PLAN, positions=positions,
                             eccentricity=eccentricity)
    n_dof = 3 * bld["masses"].size
    got = np.sqrt(np.sort(ops.eigen("-fullGenLapack", n_dof)))
    ops.wipe()
    m_mat, k_mat = building_matrices(bld["masses"], bld["story_k"], bld["k_theta"],
                                     bld["inertia"], eccentricity, positions,
                                     bld["isolator"]["K1"] / len(positions))
    want = np.sqrt(np.sort(scipy.linalg.eigh(k_mat, m_mat, eigvals_only=True)))
    np.testing.assert_allclose(got, want, rtol=1e-9)
    # the perimeter frame's default: k (b_x^2 + b_y^2) / 4
    np.testing.assert_allclose(bld["k_theta"], 600e6 * (30**2 + 20**2) / 4, rtol=1e-15)


COMPONENTS = ("RSN953:009", "RSN953:279")  # x, y: the plan references' pair
WINDOW = (2.5, 7.0)  # s: the strong motion's start (the isolator's peak is 62 mm here)
CORNER_BEARINGS = np.array([[-15.0, -10.0], [15.0, -10.0], [-15.0, 10.0], [15.0, 10.0]])
SHORT_GAP = 0.04  # m: the walls are hit in this window (the 15 s pair's 0.13 m is not)
WALL_K = 2.5e9  # N/m


@functools.cache
def short_pair() -> tuple[np.ndarray, float]:
    """(T, 2) m/s^2 over WINDOW and its step."""
    from pipeline.records import load_record

    x, y = (load_record(name) for name in COMPONENTS)
    assert x.dt == y.dt and x.npts == y.npts
    i0, i1 = (int(round(t / x.dt)) for t in WINDOW)
    return np.column_stack([x.accel[i0:i1 + 1], y.accel[i0:i1 + 1]]), x.dt
