"""Independent OpenSeesPy model of the paper's building, for cross-validating the engine.

This module is a test helper, not part of the package: it rebuilds the 5-level base-isolated
shear building of SPEC sections 1-2 in OpenSees (through ``openseespy``) without using any
code from ``engine/``, runs it under one ground-acceleration record, and returns the same
peak quantities the engine reports.  Agreement between the two is evidence that both
implement the stated physics; disagreement points at one of them.

Modelling choices
-----------------
* 1-D model (``model basic -ndm 1 -ndf 1``): a fixed ground node and 5 nodes carrying the
  lumped masses of levels 0..4 (320, 320, 320, 320, 250 t).  Every spring, dashpot and gap
  is a ``zeroLength`` element with ``-mat <tag> -dir 1``; its deformation is
  u(jNode) - u(iNode).
* Stories 1..4: ``Elastic`` (k = 600 MN/m) in parallel with a separate ``Viscous``
  (c_s, alpha = 1) dashpot, c_s = 2 zeta_s k / omega_1, zeta_s = 2 %, omega_1 the first
  circular frequency of the fixed-base superstructure (levels 1..4, level 0 fixed).
* Isolator (ground -> level 0): ``Parallel`` of ``Elastic`` (K2 = 25 MN/m) and
  ``ElasticPP`` (K1 - K2 = 175 MN/m, yield deformation u_y = Fy / K1), i.e. an exact bilinear
  kinematic law with Fy = 0.1 * 9.81 * 1530 t.  Isolation dashpot ``Viscous``
  c_b = 2 * 0.05 * sqrt(K1 * M_tot).
* No Rayleigh damping; all damping is in the discrete dashpots.
* Ground motion: ``timeSeries Path -dt ag_dt -values ...`` (linear interpolation between
  samples) driving ``pattern UniformExcitation`` in direction 1.  Node responses are relative
  to the ground; total acceleration = ``nodeAccel`` + a_g(t), a_g interpolated at the
  analysis time with the same linear rule.
* Moat wall, contact on both sides of level 0 at clearance ``gap`` (one gap element per side):
    - ``contact="elastic"``: ``ElasticPPGap`` with stiffness k, a yield force of 1e30 N (never
      yields), eta = 0, ``noDamage``.  The "+" wall uses element (ground -> level 0) with
      +Fy, +gap (closes when u_0 > gap); the "-" wall uses the same node order with -Fy, -gap
      (closes when u_0 < -gap).
    - ``contact="jankowski"``: ``JankowskiImpact Kh xi Meff gap <n=1.5>``, Kh = beta,
      xi = 9 sqrt5 (1 - COR^2) / (2 COR (COR (9 pi - 16) + 16)), Meff = m_eff.  The material
      is compression-only and wants a negative gap (it closes when its deformation < gap).
      The "-" wall is element (ground -> level 0) with gap = -gap; the "+" wall is the
      element with the node order reversed (level 0 -> ground), whose deformation is -u_0.
      Approach (deformation rate < 0): F = Kh d^1.5 + 2 xi sqrt(Kh sqrt(d) Meff) d_dot;
      restitution: F = Kh d^1.5.  Note: the OpenSees 3.7 material returns a tangent of the
      wrong sign (-n Kh d^(n-1)); the force is right, so Newton still converges here because
      the inertia term 4 M / dt^2 dominates, but more slowly.  It also prints a line to
      stderr for every impact.
    - ``contact="hertzdamp"``: ``Hertzdamp Kh xiNorm gap <n>`` (P. J. Hughes' material after
      Muthukumar & DesRoches 2006), Kh = k, xiNorm = chi = 3 (1 - COR^2) / 4, n = 1.5; the
      elements as for Jankowski. At the first step in contact it takes the deformation rate
      as the impact velocity v_imp and then gives F = Kh d^n (1 + chi d_dot / v_imp) (not
      clipped at zero; with chi < 1 and |d_dot| <= v_imp it never pulls).
* Analysis: ``Transient``, ``Newmark`` gamma = 1/2, beta = 1/4, fixed step dt (default
  1 ms with contact, 2 ms without), ``Newton`` with ``NormDispIncr`` 1e-10 m; when a step
  fails it is retried with ModifiedNewton -initial, then KrylovNewton, then split in halves
  (down to dt / 2**8).  Responses are recorded after every converged (sub)step.
* The run covers the whole record, (npts - 1) * ag_dt.

Contact bookkeeping: indentation delta = max(|u_0| - gap, 0); an impact is a transition
from delta = 0 to delta > 0 between recorded steps; the impact force is read from the gap
elements (``eleForce``), i.e. includes the Jankowski damping term.

``LAST_RUN`` holds diagnostics of the latest call (steps, fallbacks, wall time).
"""
from __future__ import annotations

import math
import time

import numpy as np
import openseespy.opensees as ops
import scipy.linalg

AGREEMENT = {"none": 2e-4, "elastic": 1e-3, "jankowski": 0.015, "hertzdamp": 1e-3}
"""Relative tolerance of the engine's peaks against this model, per contact: the worst deviation
measured on the paper's records plus a margin (measured: none 0.01%, elastic 0.04%, Jankowski
0.8%, Hertzdamp 0.04%). tests/engine/test_opensees.py asserts it; benchmarks/vs_opensees.py
quotes it."""

G = 9.81
_MASSES = np.array([320e3, 320e3, 320e3, 320e3, 250e3])  # levels 0..4, kg
_K_STORY = 600e6  # N/m
_K1 = 200e6  # N/m
_K2 = 25e6  # N/m
_M_TOT = float(_MASSES.sum())  # 1530e3 kg
_FY = 0.1 * G * _M_TOT  # N
_UY = _FY / _K1  # m
_ZETA_B = 0.05
_ZETA_S = 0.02


def _fixed_base_omega1() -> float:
    m = _MASSES[1:]
    n = m.size
    k = np.zeros((n, n))
    for s in range(n):  # story s+1 connects level s (fixed when s == 0) to level s+1
        j = s
        k[j, j] += _K_STORY
        if s > 0:
            i = s - 1
            k[i, i] += _K_STORY
            k[i, j] -= _K_STORY
            k[j, i] -= _K_STORY
    w2 = scipy.linalg.eigh(k, np.diag(m), eigvals_only=True)
    return float(math.sqrt(w2.min()))


_OMEGA1 = _fixed_base_omega1()

BUILDING = {
    "masses_kg": tuple(float(x) for x in _MASSES),
    "k_story_N_per_m": _K_STORY,
    "K1_N_per_m": _K1,
    "K2_N_per_m": _K2,
    "Fy_N": _FY,
    "u_y_m": _UY,
    "M_tot_kg": _M_TOT,
    "g_m_per_s2": G,
    "zeta_b": _ZETA_B,
    "zeta_s": _ZETA_S,
    "omega1_fixed_base_rad_per_s": _OMEGA1,
    "c_story_N_s_per_m": 2.0 * _ZETA_S * _K_STORY / _OMEGA1,
    "c_base_N_s_per_m": 2.0 * _ZETA_B * math.sqrt(_K1 * _M_TOT),
}

LAST_RUN: dict = {}

_GROUND = 100
_LEVEL_NODES = (1, 2, 3, 4, 5)  # levels 0..4
_GAP_ELES = (201, 202)
_FY_NEVER = 1e30
_MAX_HALVINGS = 8


def jankowski_xi(cor: float) -> float:
    """Jankowski (2006) impact damping ratio for a coefficient of restitution."""
    num = 9.0 * math.sqrt(5.0) * (1.0 - cor**2)
    return num / (2.0 * cor * (cor * (9.0 * math.pi - 16.0) + 16.0))


def build_model(ag, ag_dt, contact, gap, k, beta, cor, m_eff, n=1.5):
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(_GROUND, 0.0)
    ops.fix(_GROUND, 1)
    for node, m in zip(_LEVEL_NODES, _MASSES, strict=True):
        ops.node(node, 0.0)
        ops.mass(node, float(m))

    c_s = BUILDING["c_story_N_s_per_m"]
    c_b = BUILDING["c_base_N_s_per_m"]
    # materials
    ops.uniaxialMaterial("Elastic", 1, _K_STORY)
    ops.uniaxialMaterial("Viscous", 2, c_s, 1.0)
    ops.uniaxialMaterial("Elastic", 3, _K2)
    ops.uniaxialMaterial("ElasticPP", 4, _K1 - _K2, _UY)
    ops.uniaxialMaterial("Parallel", 5, 3, 4)
    ops.uniaxialMaterial("Viscous", 6, c_b, 1.0)

    # isolator + isolation dashpot
    ops.element("zeroLength", 1, _GROUND, _LEVEL_NODES[0], "-mat", 5, "-dir", 1)
    ops.element("zeroLength", 2, _GROUND, _LEVEL_NODES[0], "-mat", 6, "-dir", 1)
    # stories
    for s in range(1, 5):
        i, j = _LEVEL_NODES[s - 1], _LEVEL_NODES[s]
        ops.element("zeroLength", 10 + s, i, j, "-mat", 1, "-dir", 1)
        ops.element("zeroLength", 20 + s, i, j, "-mat", 2, "-dir", 1)

    if contact == "elastic":
        ops.uniaxialMaterial("ElasticPPGap", 7, float(k), _FY_NEVER, float(gap), 0.0, "noDamage")
        ops.uniaxialMaterial("ElasticPPGap", 8, float(k), -_FY_NEVER, -float(gap), 0.0, "noDamage")
        ops.element("zeroLength", _GAP_ELES[0], _GROUND, _LEVEL_NODES[0], "-mat", 7, "-dir", 1)
        ops.element("zeroLength", _GAP_ELES[1], _GROUND, _LEVEL_NODES[0], "-mat", 8, "-dir", 1)
    elif contact in ("jankowski", "hertzdamp"):
        if contact == "jankowski":
            xi = jankowski_xi(float(cor))
            ops.uniaxialMaterial("JankowskiImpact", 7, float(beta), xi, float(m_eff),
                                 -float(gap), 1.5)
        else:
            chi = 0.75 * (1.0 - float(cor) ** 2)
            ops.uniaxialMaterial("Hertzdamp", 7, float(k), chi, -float(gap), float(n))
        # "-" wall: deformation u_0 closes when u_0 < -gap
        ops.element("zeroLength", _GAP_ELES[1], _GROUND, _LEVEL_NODES[0], "-mat", 7, "-dir", 1)
        # "+" wall: reversed node order, deformation -u_0 closes when u_0 > gap
        ops.element("zeroLength", _GAP_ELES[0], _LEVEL_NODES[0], _GROUND, "-mat", 7, "-dir", 1)

    ag = np.asarray(ag, dtype=float)
    ops.timeSeries("Path", 1, "-dt", float(ag_dt), "-values", *ag.tolist(), "-factor", 1.0)
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)

    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-10, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def opensees_peaks(ag, ag_dt, *, contact=None, gap=None, k=None, beta=None, cor=None,
                   m_eff=320e3, dt=None) -> dict:
    """Run the OpenSees reference model under ground acceleration ``ag`` (m/s^2, step ag_dt s).

    contact: None (no wall), "elastic" (needs gap [m], k [N/m]; cor is ignored),
    "jankowski" (needs gap [m], beta [N/m^1.5], cor; m_eff [kg]) or "hertzdamp" (needs gap
    [m], k [N/m^1.5], cor).
    dt: analysis step, default 0.001 s with contact, 0.002 s without.
    Returns peak_total_accel (5,), peak_interstory_drift (4,), peak_isolator_disp,
    max_indentation, max_impact_force, n_impacts.
    """
    if contact not in (None, "elastic", "jankowski", "hertzdamp"):
        raise ValueError(f"unknown contact {contact!r}")
    if contact is not None and (gap is None or gap < 0):
        raise ValueError("contact needs a gap >= 0")
    if contact in ("elastic", "hertzdamp") and k is None:
        raise ValueError(f"{contact} contact needs k")
    if contact == "hertzdamp" and cor is None:
        raise ValueError("hertzdamp contact needs cor")
    if contact == "jankowski" and (beta is None or cor is None):
        raise ValueError("jankowski contact needs beta and cor")
    ag = np.asarray(ag, dtype=float).ravel()
    if ag.size < 2:
        raise ValueError("ag needs at least 2 samples")
    if dt is None:
        dt = 0.001 if contact else 0.002
    dt = float(dt)
    t_rec = np.arange(ag.size) * float(ag_dt)
    duration = float(t_rec[-1])

    t0 = time.perf_counter()
    build_model(ag, ag_dt, contact, gap, k, beta, cor, m_eff)

    times, disp, accel, fgap = [], [], [], []
    nodes = _LEVEL_NODES
    has_gap = contact is not None
    stats = {"steps": 0, "fallback_algorithms": 0, "substeps": 0}

    def record():
        times.append(ops.getTime())
        disp.append([ops.nodeDisp(n, 1) for n in nodes])
        accel.append([ops.nodeAccel(n, 1) for n in nodes])
        if has_gap:
            fgap.append(max(abs(ops.eleForce(_GAP_ELES[0])[0]), abs(ops.eleForce(_GAP_ELES[1])[0])))

    def step(h, depth=0):
        if ops.analyze(1, h) == 0:
            stats["steps"] += 1
            record()
            return
        for alg in (("ModifiedNewton", "-initial"), ("KrylovNewton",)):
            ops.algorithm(*alg)
            ok = ops.analyze(1, h)
            ops.algorithm("Newton")
            if ok == 0:
                stats["steps"] += 1
                stats["fallback_algorithms"] += 1
                record()
                return
        if depth >= _MAX_HALVINGS:
            raise RuntimeError(f"OpenSees step failed at t = {ops.getTime():.6f} s "
                               f"even with step {h:.3e} s")
        stats["substeps"] += 1
        step(h / 2.0, depth + 1)
        step(h / 2.0, depth + 1)

    try:
        record()  # t = 0, at rest
        ratio = duration / dt
        n_full = int(round(ratio)) if abs(ratio - round(ratio)) < 1e-6 else int(math.floor(ratio))
        for _ in range(n_full):
            step(dt)
        rem = duration - n_full * dt  # a final short step when dt does not divide the record
        if rem > 1e-6 * dt:
            step(rem)
    finally:
        ops.wipe()

    times = np.asarray(times)
    disp = np.asarray(disp)
    accel = np.asarray(accel) + np.interp(times, t_rec, ag)[:, None]
    u0 = disp[:, 0]
    out = {
        "peak_total_accel": np.abs(accel).max(axis=0),
        "peak_interstory_drift": np.abs(np.diff(disp, axis=1)).max(axis=0),
        "peak_isolator_disp": float(np.abs(u0).max()),
        "max_indentation": 0.0,
        "max_impact_force": 0.0,
        "n_impacts": 0,
    }
    if has_gap:
        delta = np.maximum(np.abs(u0) - float(gap), 0.0)
        inside = delta > 0.0
        out["max_indentation"] = float(delta.max())
        out["max_impact_force"] = float(np.max(fgap))
        out["n_impacts"] = int(np.count_nonzero(inside[1:] & ~inside[:-1]) + int(inside[0]))

    LAST_RUN.clear()
    LAST_RUN.update(stats, wall_time_s=time.perf_counter() - t0, recorded_points=len(times),
                    end_time=float(times[-1]), duration=duration, dt=dt, contact=contact)
    return out
