"""Intensity measures of a ground motion, for describing records (studies.suite).

Pure functions of a sampled ground acceleration, SI units throughout (m, s, m/s^2, m/s):

    ground_velocity / peak_ground_velocity   the acceleration integrated (PGV)
    isolated_period                          effective period of the isolated building at a
                                             displacement (secant stiffness of the isolator)
    sdof_displacement / spectral_displacement
                                             linear oscillator response, its peak (Sd)

An acceleration is a 1-D array (N,) of samples every dt s, starting at t = 0; between samples
it is taken as linear (the piecewise-linear ground motion of the response-spectrum methods).
Nothing here runs the building model: that is engine.simulate's.
"""
from __future__ import annotations

import numpy as np


def ground_velocity(accel: np.ndarray, dt: float) -> np.ndarray:
    """(N,) ground velocity (m/s) from ground acceleration accel (N,) (m/s^2) every dt (s).

    The trapezoidal rule from rest, v[0] = 0 and v[i] = v[i-1] + dt (a[i-1] + a[i]) / 2: the
    exact integral of the piecewise-linear acceleration. No baseline correction.
    """
    accel = np.asarray(accel, dtype=float)
    return np.concatenate([[0.0], np.cumsum(0.5 * (accel[1:] + accel[:-1])) * dt])


def peak_ground_velocity(accel: np.ndarray, dt: float) -> float:
    """PGV (m/s): max |ground_velocity(accel, dt)| of accel (N,) (m/s^2) every dt (s); of the
    record as given (the acceleration integrated, no baseline correction)."""
    return float(np.max(np.abs(ground_velocity(accel, dt))))


def isolated_period(displacement, building=None):
    """Effective period (s) of the isolated building at isolator displacement D (m).

    T_eff = 2 pi sqrt(M / k_eff): M the total mass (kg; the superstructure taken as rigid on
    the isolators), k_eff the secant stiffness of the building's isolator at D (N/m; the
    isolator law's effective_stiffness: for the bilinear law (k1 min(D, u_y) + k2 max(D - u_y,
    0)) / D, u_y its yield displacement; for the friction pendulum W / R + mu_fast W / D; for
    the triple friction pendulum its rigid-plastic backbone's F(D) / D).
    This is the effective period at the design displacement of the equivalent-linear
    isolator design (ASCE 7 chapter 17, T = 2 pi sqrt(W / (k_eff g))).

    displacement: D > 0, m, a scalar or an array (any shape); building: engine.Building
    (default: the paper's, Fig. 7c). Returns a float for a scalar D, else an array of D's
    shape.
    """
    import engine

    b = engine.Building() if building is None else building
    D = np.asarray(displacement, dtype=float)
    secant = b.isolation.effective_stiffness(b.total_mass, b.g, D)
    period = 2 * np.pi * np.sqrt(b.total_mass / secant)
    return float(period) if period.ndim == 0 else period


def sdof_displacement(accel: np.ndarray, dt: float, period: float,
                      damping: float = 0.05) -> np.ndarray:
    """(N,) relative displacement (m) of a linear oscillator under ground acceleration.

    u'' + 2 zeta w u' + w^2 u = -a_g(t), w = 2 pi / period (s), zeta = damping (ratio), from
    rest; a_g = accel (N,) (m/s^2) every dt (s), linear between samples. Solved exactly for
    that input (state-space, first-order hold: scipy.signal.lsim with interp=True), as the
    piecewise-exact method of Nigam & Jennings (1969) used for response spectra (Chopra,
    Dynamics of Structures, ch. 5-6).
    """
    from scipy import signal

    accel = np.asarray(accel, dtype=float)
    w = 2 * np.pi / period
    system = signal.StateSpace([[0, 1], [-w * w, -2 * damping * w]], [[0], [-1]], [[1, 0]],
                               [[0]])
    t = np.arange(accel.size) * dt
    _, y, _ = signal.lsim(system, accel, t, interp=True)
    return np.asarray(y)


def spectral_displacement(accel: np.ndarray, dt: float, period: float,
                          damping: float = 0.05) -> float:
    """Sd (m): the peak |relative displacement| of sdof_displacement (a linear oscillator of
    period s and damping ratio) under accel (N,) (m/s^2) every dt (s), over the samples; the
    displacement response spectrum at one period (Chopra, Dynamics of Structures, ch. 6)."""
    return float(np.max(np.abs(sdof_displacement(accel, dt, period, damping))))
