"""The OpenSees 3-D reference of a slab that twists (tests/reference/opensees_torsion.py)
against closed forms: the rigid slab on linear bearings has the stiffness matrix, about its
mass centre (p_i, q_i the bearings' positions from it),
    K = sum_i k_i [[1, 0, -q_i], [0, 1, p_i], [-q_i, p_i, p_i^2 + q_i^2]],
and the mass matrix diag(m, m, J): its frequencies are those of M^-1 K, and a torque T alone
twists a symmetric layout by T / sum k_i r_i^2 without moving its centre."""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.motions.torsion import grid_positions
from tests.reference import opensees_torsion as ot

pytest.importorskip("openseespy.opensees")

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
