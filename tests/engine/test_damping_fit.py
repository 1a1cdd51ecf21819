"""engine.damping_fit, the energy-equilibrium procedure of section 3.2: a1 balances Eq. 5, its
dependence on mass and velocity, the bracket, and the power-law fit."""
import numpy as np
import pytest

from engine import EngineError, damping_fit
from engine.impact.calibration import hunt_crossley_chi

KAJITA = dict(thickness=0.010, area=0.040**2, strain=0.8, n_bumpers=1)  # 0.45 kN/mm^2.65


# --- engine.damping_fit ---------------------------------------------------------------------

def test_energy_equilibrium_a1_balances_eq5():
    """At the a1 found, the measured hysteresis area equals Delta E of Eq. 5 (within 0.5%),
    and C_imp v_imp is the damping factor the independent COR table of calibration.py gives."""
    cor, m_eff, v = 0.45, 150.0, 1.0
    found = damping_fit.find_a1(cor, m_eff, v, KAJITA, rtol=1e-4)
    delta_e = 0.5 * m_eff * (1 - cor**2) * v**2
    assert found.energy_loss[0] == pytest.approx(delta_e)
    assert found.hysteresis_area[0] == pytest.approx(delta_e, rel=5e-3)
    assert found.cor_realised[0] == pytest.approx(cor, rel=5e-3)
    assert not found.crushed[0]
    assert found.c_imp[0] == pytest.approx(found.a1[0] * (1 - cor**2))
    chi = hunt_crossley_chi(cor, 2.65, restitution_only=True)[0]
    assert found.c_imp[0] * v == pytest.approx(chi, rel=2e-3)
    # Eq. 9 at this point, for scale: the paper's law is within a few percent.
    assert found.c_imp[0] == pytest.approx(
        damping_fit.power_law_c_imp(cor, m_eff, v, 1.55, 0.7076, 0.0025, 0.9755), rel=0.05)


def test_a1_is_independent_of_mass_and_inverse_in_velocity():
    """Pure power law: the realised COR depends on C_imp v_imp and n only."""
    found = damping_fit.find_a1(0.6, [10.0, 1e5, 10.0], [1.0, 1.0, 2.0],
                                dict(thickness=0.2, area=1.0, strain=1.0), rtol=1e-6)
    assert found.a1[1] == pytest.approx(found.a1[0], rel=1e-5)
    assert found.a1[2] == pytest.approx(found.a1[0] / 2, rel=1e-5)


def test_find_a1_rejects_a_bracket_without_the_root():
    with pytest.raises(EngineError, match="bracket"):
        damping_fit.find_a1(0.45, 150.0, 1.0, KAJITA, bracket=(1e-3, 1e-2))
    with pytest.raises(EngineError, match="cor"):
        damping_fit.find_a1(1.0, 150.0, 1.0, KAJITA)


def test_power_law_fit_recovers_known_exponents():
    cor, m_eff, v = (a.ravel() for a in np.meshgrid([0.3, 0.5, 0.9], [10.0, 1e3, 3e5],
                                                     [0.5, 1.0, 4.0], indexing="ij"))
    c_imp = damping_fit.power_law_c_imp(cor, m_eff, v, 1.55, 0.7076, 0.0025, 0.9755)
    fit = damping_fit.fit_power_law(cor, m_eff, v, c_imp)
    np.testing.assert_allclose([fit.c0, fit.p1, fit.p2, fit.p3],
                               [1.55, 0.7076, 0.0025, 0.9755], rtol=1e-10)
    assert fit.rms_log_error < 1e-12
    np.testing.assert_allclose(fit.c_imp(cor, m_eff, v), c_imp, rtol=1e-10)
    with pytest.raises(EngineError, match="two values"):
        damping_fit.fit_power_law(cor, np.full_like(cor, 150.0), v, c_imp)
