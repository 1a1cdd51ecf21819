"""The building model: the paper's constants, and the linear response against an exact solution."""
import numpy as np
import pytest
from scipy import signal

import engine
from engine.building import Building


def test_paper_constants():
    b = Building()
    assert b.total_mass == pytest.approx(1530e3)
    assert b.yield_force == pytest.approx(0.1 * 15_009.3e3)      # 0.1 W_tot, N
    assert b.yield_displacement == pytest.approx(7.50e-3, abs=5e-6)
    c = b.damping_matrix()
    c_iso = 2 * 0.05 * np.sqrt(200e6 * 1530e3)
    assert c_iso == pytest.approx(1.749e6, rel=1e-3)            # SPEC: 1.749 MN*s/m
    c_story = -c[0, 1]
    assert c[0, 0] == pytest.approx(c_iso + c_story)
    assert c_story == pytest.approx(2 * 0.02 * 600e6 / b.fixed_base_omega1())
    np.testing.assert_allclose(c, c.T)


def test_modal_damping_gives_the_requested_modal_ratios():
    b = Building(damping="modal")
    m = np.asarray(b.masses)
    omega2, phi = np.linalg.eigh(b.stiffness_matrix() / np.sqrt(np.outer(m, m)))
    phi = phi / np.sqrt(m)[:, None]
    modal_c = phi.T @ b.damping_matrix() @ phi
    zeta = np.diag(modal_c) / (2 * np.sqrt(omega2))
    np.testing.assert_allclose(zeta, [0.05, 0.02, 0.02, 0.02, 0.02], rtol=1e-9)
    np.testing.assert_allclose(modal_c - np.diag(np.diag(modal_c)), 0, atol=1e-6 * modal_c.max())


def _exact_linear_peaks(building, ag, dt):
    """Exact response of the linear building (isolator at k1) to a piecewise-linear a_g:
    state space with a first-order hold, which is exact for linear interpolation."""
    m = np.asarray(building.masses)
    k, c = building.stiffness_matrix(), building.damping_matrix()
    minv = np.diag(1 / m)
    a = np.block([[np.zeros((5, 5)), np.eye(5)], [-minv @ k, -minv @ c]])
    bvec = np.concatenate([np.zeros(5), -np.ones(5)])[:, None]
    cmat = np.block([[np.eye(5), np.zeros((5, 5))], [-minv @ k, -minv @ c]])  # u, total accel
    d = np.zeros((10, 1))
    t = np.arange(ag.size) * dt
    _, y, _ = signal.lsim((a, bvec, cmat, d), ag, t, interp=True)
    u, acc_total = y[:, :5], y[:, 5:]
    return {"peak_total_accel": np.abs(acc_total).max(0),
            "peak_interstory_drift": np.abs(np.diff(u, axis=1)).max(0),
            "peak_isolator_disp": np.abs(u[:, 0]).max()}


# The compiled loop: the NumPy loop gives its peaks to 1e-9 with either damping rule
# (tests/engine/loops/test_numba_loop.py::test_backends_agree_on_every_peak, "paper" and "modal"
# buildings, with and without walls).
@pytest.mark.parametrize("backend", ["numba"])
@pytest.mark.parametrize("damping", ["paper", "modal"])
def test_linear_building_matches_exact_solution(paper_record, damping, backend):
    """No isolator yield (huge Fy), no wall: the engine's peaks are within 0.01% of the exact
    state-space solution on the same time grid (measured: 0.0012% paper, 0.0032% modal)."""
    rec = paper_record("olive_view")
    accel = rec.accel
    building = Building(fy_ratio=100.0, damping=damping)
    dt = engine.DEFAULT_DT
    res = engine.simulate(accel, rec.dt, engine.Contact.none(1), building, dt=dt,
                          backend=backend)
    n_steps = int(np.floor((len(accel) - 1) * rec.dt / dt + 1e-9)) + 1
    ag = np.interp(np.arange(n_steps) * dt, np.arange(len(accel)) * rec.dt, accel)
    exact = _exact_linear_peaks(building, ag, dt)
    for name, value in exact.items():
        np.testing.assert_allclose(getattr(res, name)[0], value, rtol=1e-4, err_msg=name)


def test_isolator_hysteresis_is_exact_bilinear():
    """Quasi-static check of the isolator law: force = k2 u + clipped plastic spring."""
    from engine.isolators.hysteresis import isolator_force, plastic_spring_force

    b = Building()
    uy, k1, k2 = b.yield_displacement, b.k1, b.k2
    path = np.concatenate([np.linspace(0, 3 * uy, 301), np.linspace(3 * uy, -3 * uy, 601)])
    fp, forces = np.zeros(1), []
    prev = 0.0
    for u in path:
        fp = plastic_spring_force(fp, np.array([u - prev]), k1 - k2, (k1 - k2) * uy)
        forces.append(isolator_force(np.array([u]), fp, k2)[0])
        prev = u
    forces = np.array(forces)
    assert forces[100] == pytest.approx(k1 * uy, rel=1e-9)                    # yield point
    assert forces[300] == pytest.approx(k1 * uy + k2 * 2 * uy, rel=1e-9)      # post-yield
    # Unloading from 3 u_y: elastic with k1 over 2 u_y, then yields in reverse.
    assert forces[501] == pytest.approx(forces[300] - k1 * 2 * uy, rel=1e-9)
    assert forces[-1] == pytest.approx(-(k1 * uy + k2 * 2 * uy), rel=1e-9)
