"""Independent OpenSeesPy model of a base-isolated shear building, for cross-validating the engine.

This module is a test helper, not part of the package: it rebuilds the base-isolated shear
building of SPEC sections 1-2 in OpenSees (through ``openseespy``) without using any code from
``engine/`` (nor from ``independent_building.py``, the other reference), runs it under one
ground-acceleration record, and returns the same peak quantities the engine reports.
Agreement between the two is evidence that both implement the stated physics; disagreement
points at one of them. Units SI throughout (kg, m, s, N).

The building (``building(...)`` resolves every number; defaults: the paper's)
-----------------------------------------------------------------------------
* Levels 0..N (level 0 = isolation slab, N stories, 1 <= N <= 30) with lumped masses
  m_0..m_N; story i joins level i-1 to level i with stiffness k_i. Default: the paper's
  5 levels (320, 320, 320, 320, 250 t), k = 600 MN/m for every story.
* Story dashpots c_i = 2 zeta_sup k_i / omega_1 (zeta_sup = 2 %), omega_1 the first circular
  frequency of the fixed-base superstructure (levels 1..N, level 0 held fixed), each a
  ``Viscous`` (alpha = 1) in parallel with its story spring. No Rayleigh damping; all damping
  is in the discrete dashpots.
* Story springs: ``Elastic`` k_i, or, when ``story_yield`` gives the story a finite yield
  force F_i, ``Steel01`` (Fy = F_i, E0 = k_i, b = story_b, default 0.02; no isotropic
  hardening): bilinear kinematic hardening, which equals elastic b k_i in parallel with an
  elastic-perfectly-plastic (1 - b) k_i spring of limit (1 - b) F_i (yield drift
  d_y,i = F_i / k_i). Peak story ductility = peak |drift| / d_y,i.
* Isolation dashpot ``Viscous`` c_iso = 2 zeta_iso sqrt(k_ref M_tot) between the ground and
  level 0 (M_tot = sum of all masses; k_ref = K1 for the bilinear isolator, k_0 + W / R for
  the friction pendulum; zeta_iso 5 % for the bilinear, 0 for the friction pendulum, in which
  case there is no dashpot element).
* Isolator ``{"kind": "bilinear", "K1", "K2", "fy_ratio"}`` (default 200 MN/m, 25 MN/m, 0.1):
  ``Parallel`` of ``Elastic`` (K2) and ``ElasticPP`` (K1 - K2, yield deformation
  u_y = Fy / K1), i.e. an exact bilinear kinematic law with Fy = fy_ratio g M_tot, g = 9.81.
* Isolator ``{"kind": "friction_pendulum", "radius", "mu_slow", "mu_fast", "rate",
  "yield_disp" (default 0.5 mm), "weight" (default W = g M_tot)}``: a linear restoring spring
  ``Elastic`` W / R (a ``zeroLength``) in parallel with ``flatSliderBearing`` carrying the
  constant weight W, friction model ``VelDependent mu_slow mu_fast rate``
  (mu = mu_fast - (mu_fast - mu_slow) exp(-rate |v|), Constantinou et al. 1990) and
  kInit = k_0 = mu_fast W / yield_disp. The element's shear law is a return map on an
  elastic-perfectly-plastic spring (stiffness k_0, limit mu(|v|) N, v the trial velocity of
  the slider, i.e. level 0's relative velocity; FlatSliderSimple2d.cpp, OpenSees 3.7): the
  SPEC's F_f exactly, in its discrete form F_f(n+1) = clip(F_f(n) + k_0 du,
  +-mu(|v(n+1)|) W). ``flatSliderBearing`` is a 2-D element, so this model is 2-D
  (``-ndm 2 -ndf 3``): all nodes at (0, 0), the vertical and rotational DOFs of every level
  fixed, the horizontal DOF free; the element is zero-length with ``-orient 0 1 0 -1 0 0``
  (local x = axial = global Y; local y = shear = -global X; the law is symmetric, so the sign
  does not matter). The normal force is the constant N = W: the axial material is
  ``InitStressMaterial`` (initial stress -W) around a stiff ``Elastic``, and since the
  vertical DOF is fixed the axial deformation stays 0 and the force stays -W (compression)
  for the whole run; ``-Mz`` is an ``Elastic`` of zero stiffness (rotations fixed).
  ``singleFPBearing`` is not used: it takes the normal force as W + V u / R (V its shear;
  a second-order term, ~0.4 % here), the sliding speed as |v| sqrt(1 + (u / R)^2) and its
  pre-slip stiffness as kInit - N / R; ``flatSliderBearing`` + the W / R spring is the
  engine's first-order law exactly. ``fp_bearing_loop`` drives this same element
  quasi-statically (static ``DisplacementControl``, the slider's velocity set by
  ``setNodeVel``): it reproduces the closed-form loops to round-off
  (tests/reference/test_references.py).
* Isolator ``{"kind": "triple_friction_pendulum", "L1", "L2", "L3", "d1", "d2", "d3", "mu1",
  "mu2", "mu3", "yield_disp" (default 0.5 mm, OpenSees' uy), "weight" (default W = g M_tot)}``:
  resolved here (its reference stiffness k_ref = mu1 W / yield_disp, the element's initial
  one; no isolation dashpot by default), modelled by opensees_plan.py only: the
  ``TripleFrictionPendulum`` element is 3-D (its description there).

Other modelling choices
-----------------------
* Bilinear isolator: 1-D model (``model basic -ndm 1 -ndf 1``): a fixed ground node and N + 1
  nodes carrying the masses of levels 0..N; every spring, dashpot and gap is a ``zeroLength``
  element with ``-mat <tag> -dir 1``; its deformation is u(jNode) - u(iNode). (With the
  paper's building this is exactly the model of earlier versions of this file.)
* Ground motion: ``timeSeries Path -dt ag_dt -values ... -useLast`` (linear interpolation
  between samples; ``-useLast`` holds the last sample past the end, where the last step may
  end ~1e-12 s late from the round-off of the summed steps: without it the series drops to 0
  there and the last recorded acceleration jumps by a_g(end)) driving
  ``pattern UniformExcitation`` in direction 1.  Node responses are relative
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
  1 ms with contact or a friction pendulum, 2 ms otherwise), ``Newton`` with
  ``NormDispIncr`` 1e-10 m; when a step fails it is retried with ModifiedNewton -initial, then
  KrylovNewton, then split in halves (down to dt / 2**8).  Responses are recorded after every
  converged (sub)step; peaks are the largest recorded values.
* The run covers the whole record, (npts - 1) * ag_dt (pass a slice for a shorter run).

Contact bookkeeping: indentation delta = max(|u_0| - gap, 0); an impact is a transition
from delta = 0 to delta > 0 between recorded steps; the impact force is read from the gap
elements (``eleForce``), i.e. includes the Jankowski damping term.

Accuracy (tests/reference/test_references.py, against the solve_ivp model and closed forms):
drifts, displacements and wall peaks within 1e-4 at dt 0.25-0.5 ms. The accelerations that
peak at a corner of a hysteretic law (the isolator yielding, the friction pendulum slipping
again after a stop, a story yielding) are sampled only at the steps, so they can fall short
by up to (slope of the acceleration) x (distance to the nearest step): measured 3.6e-4
(8-story bilinear, dt 0.5 ms), 6.4e-4 (yielding stories, dt 0.25 ms), 2.6e-3 (the paper's
building on the friction pendulum, dt 0.25 ms; the stuck slab's jerk k0 v / m0 is
~500 m/s^3). The friction pendulum's return map places the elastic branch after a stop at
mu(|v|) W of the last step before the stop, not at mu_slow W: an O(dt) offset of up to
W (mu_fast - mu_slow) rate |v'| dt.

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
0.8%, Hertzdamp 0.04%). tests/engine/test_simulate_opensees.py asserts it; benchmarks/vs_opensees.py
quotes it."""

G = 9.81
_MASSES = np.array([320e3, 320e3, 320e3, 320e3, 250e3])  # levels 0..4, kg
_K_STORY = 600e6  # N/m
_K1 = 200e6  # N/m
_K2 = 25e6  # N/m
_FY_RATIO = 0.1
_M_TOT = float(_MASSES.sum())  # 1530e3 kg
_FY = _FY_RATIO * G * _M_TOT  # N
_UY = _FY / _K1  # m
_ZETA_B = 0.05
_ZETA_S = 0.02
_STORY_B = 0.02
_YIELD_DISP = 5e-4  # m, friction pendulum pre-slip displacement
_TFP_KEYS = ("L1", "L2", "L3", "d1", "d2", "d3", "mu1", "mu2", "mu3")
MAX_STORIES = 30


def fixed_base_omega1(masses, story_k) -> float:
    """First circular frequency (rad/s) of levels 1..N with level 0 held fixed.

    masses: m_0..m_N (kg; m_0 unused); story_k: k_1..k_N (N/m)."""
    m = np.asarray(masses, dtype=float)[1:]
    kk = np.asarray(story_k, dtype=float)
    n = m.size
    k = np.zeros((n, n))
    for s in range(n):  # story s+1 connects level s (fixed when s == 0) to level s+1
        j = s
        k[j, j] += kk[s]
        if s > 0:
            i = s - 1
            k[i, i] += kk[s]
            k[i, j] -= kk[s]
            k[j, i] -= kk[s]
    w2 = scipy.linalg.eigh(k, np.diag(m), eigvals_only=True)
    return float(math.sqrt(w2.min()))


def _fixed_base_omega1() -> float:
    return fixed_base_omega1(_MASSES, np.full(4, _K_STORY))


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
"""The paper's building (the default of every function here)."""

LAST_RUN: dict = {}

_GROUND = 100
_LEVEL_NODES = (1, 2, 3, 4, 5)  # levels 0..4 of the paper's building (level i is node i + 1)
_GAP_ELES = (201, 202)
_FY_NEVER = 1e30
_MAX_HALVINGS = 8
_AXIAL_K = 1e15  # N/m, the friction pendulum's axial material (its deformation stays 0)


def jankowski_xi(cor: float) -> float:
    """Jankowski (2006) impact damping ratio for a coefficient of restitution."""
    num = 9.0 * math.sqrt(5.0) * (1.0 - cor**2)
    return num / (2.0 * cor * (cor * (9.0 * math.pi - 16.0) + 16.0))


def building(masses=None, story_k=None, isolator=None, story_yield=None, story_b=_STORY_B,
             zeta_iso=None, zeta_sup=_ZETA_S) -> dict:
    """Every number of the model, resolved from the inputs (defaults: the paper's building).

    masses: m_0..m_N, kg (N + 1 values, level 0 the isolation slab); story_k: k_1..k_N, N/m
    (a scalar is used for every story); isolator: None (the paper's bilinear isolator) or a
    dict, ``{"kind": "bilinear", "K1": N/m, "K2": N/m, "fy_ratio": 1}`` (missing keys take
    200e6, 25e6, 0.1) or ``{"kind": "friction_pendulum", "radius": m, "mu_slow", "mu_fast",
    "rate": s/m, "yield_disp": m (default 5e-4), "weight": N (default g M_tot)}`` or
    ``{"kind": "triple_friction_pendulum", "L1", "L2", "L3": m, "d1", "d2", "d3": m, "mu1",
    "mu2", "mu3", "yield_disp": m (default 5e-4), "weight": N (default g M_tot)}`` (3-D
    only: opensees_plan.py models it);
    story_yield: None (elastic stories) or F_1..F_N, N (np.inf: that story stays elastic);
    story_b: post-yield stiffness ratio (scalar or per story); zeta_iso: isolation damping
    ratio (default 0.05 bilinear, 0 friction pendulum); zeta_sup: story damping ratio.
    """
    m = _MASSES.copy() if masses is None else np.asarray(masses, dtype=float).ravel()
    n = m.size - 1
    if not 1 <= n <= MAX_STORIES:
        raise ValueError(f"need 2 to {MAX_STORIES + 1} masses (levels 0..N), got {m.size}")
    if np.any(m <= 0):
        raise ValueError("masses must be positive")
    k = np.broadcast_to(np.asarray(_K_STORY if story_k is None else story_k, dtype=float),
                        (n,)).copy()
    if np.any(k <= 0):
        raise ValueError("story stiffnesses must be positive")
    m_tot = float(m.sum())
    iso = dict(isolator or {"kind": "bilinear"})
    kind = iso.get("kind", "bilinear")
    if kind == "bilinear":
        iso.setdefault("K1", _K1)
        iso.setdefault("K2", _K2)
        iso.setdefault("fy_ratio", _FY_RATIO)
        if not 0 < iso["K2"] < iso["K1"]:
            raise ValueError("the bilinear isolator needs 0 < K2 < K1")
        iso["Fy"] = iso["fy_ratio"] * G * m_tot
        iso["u_y"] = iso["Fy"] / iso["K1"]
        k_ref = iso["K1"]
        zeta_default = _ZETA_B
    elif kind == "friction_pendulum":
        for key in ("radius", "mu_slow", "mu_fast", "rate"):
            if key not in iso:
                raise ValueError(f"the friction pendulum needs {key!r}")
        iso.setdefault("yield_disp", _YIELD_DISP)
        iso.setdefault("weight", G * m_tot)
        if not 0 < iso["mu_slow"] <= iso["mu_fast"]:
            raise ValueError("need 0 < mu_slow <= mu_fast")
        iso["k0"] = iso["mu_fast"] * iso["weight"] / iso["yield_disp"]
        iso["k_pendulum"] = iso["weight"] / iso["radius"]
        k_ref = iso["k0"] + iso["k_pendulum"]
        zeta_default = 0.0
    elif kind == "triple_friction_pendulum":
        for key in _TFP_KEYS:
            if key not in iso:
                raise ValueError(f"the triple friction pendulum needs {key!r}")
        iso.setdefault("yield_disp", _YIELD_DISP)
        iso.setdefault("weight", G * m_tot)
        if not (iso["L1"] < iso["L2"] and iso["L1"] < iso["L3"]
                and 0 < iso["mu1"] <= iso["mu2"] <= iso["mu3"]):
            raise ValueError("need L1 < L2, L1 < L3 and 0 < mu1 <= mu2 <= mu3")
        k_ref = iso["mu1"] * iso["weight"] / iso["yield_disp"]  # the element's initial
        zeta_default = 0.0
    else:
        raise ValueError(f"unknown isolator kind {kind!r}")
    iso["kind"] = kind
    zeta_iso = zeta_default if zeta_iso is None else float(zeta_iso)
    omega1 = fixed_base_omega1(m, k)
    b = np.broadcast_to(np.asarray(story_b, dtype=float), (n,)).copy()
    if story_yield is None:
        f_y = np.full(n, np.inf)
    else:
        f_y = np.broadcast_to(np.asarray(story_yield, dtype=float), (n,)).copy()
        if np.any(f_y <= 0):
            raise ValueError("story yield forces must be positive (np.inf: elastic)")
    if np.any((b < 0) | (b >= 1)):
        raise ValueError("story_b must be in [0, 1)")
    return {"masses": m, "n_stories": n, "story_k": k, "M_tot": m_tot, "isolator": iso,
            "zeta_iso": zeta_iso, "zeta_sup": float(zeta_sup), "omega1": omega1,
            "c_story": 2.0 * float(zeta_sup) * k / omega1,
            "c_iso": 2.0 * zeta_iso * math.sqrt(k_ref * m_tot),
            "story_yield": f_y, "story_b": b, "yield_drift": f_y / k,
            "yielding": story_yield is not None}


def build_model(ag, ag_dt, contact, gap, k, beta, cor, m_eff, n=1.5, *, masses=None,
                story_k=None, isolator=None, story_yield=None, story_b=_STORY_B,
                zeta_iso=None, zeta_sup=_ZETA_S) -> dict:
    """Build the model in OpenSees' domain, ready for ``ops.analyze(steps, dt)``.

    The building keywords are those of ``building``; returns its resolved numbers, with
    "level_nodes" (the node tags of levels 0..N)."""
    bld = building(masses, story_k, isolator, story_yield, story_b, zeta_iso, zeta_sup)
    iso = bld["isolator"]
    friction = iso["kind"] == "friction_pendulum"
    nodes = tuple(range(1, bld["n_stories"] + 2))
    bld["level_nodes"] = nodes

    ops.wipe()
    if friction:
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        ops.node(_GROUND, 0.0, 0.0)
        ops.fix(_GROUND, 1, 1, 1)
        for node, m in zip(nodes, bld["masses"], strict=True):
            ops.node(node, 0.0, 0.0)
            ops.fix(node, 0, 1, 1)  # only the horizontal DOF is free
            ops.mass(node, float(m), 0.0, 0.0)
    else:
        ops.model("basic", "-ndm", 1, "-ndf", 1)
        ops.node(_GROUND, 0.0)
        ops.fix(_GROUND, 1)
        for node, m in zip(nodes, bld["masses"], strict=True):
            ops.node(node, 0.0)
            ops.mass(node, float(m))

    # isolator + isolation dashpot
    if friction:
        w = float(iso["weight"])
        ops.frictionModel("VelDependent", 1, float(iso["mu_slow"]), float(iso["mu_fast"]),
                          float(iso["rate"]))
        ops.uniaxialMaterial("Elastic", 30, _AXIAL_K)
        ops.uniaxialMaterial("InitStressMaterial", 31, 30, -w)  # constant compression W
        ops.uniaxialMaterial("Elastic", 32, 0.0)
        ops.uniaxialMaterial("Elastic", 33, float(iso["k_pendulum"]))
        ops.element("flatSliderBearing", 1, _GROUND, nodes[0], 1, float(iso["k0"]),
                    "-P", 31, "-Mz", 32, "-orient", 0.0, 1.0, 0.0, -1.0, 0.0, 0.0)
        ops.element("zeroLength", 3, _GROUND, nodes[0], "-mat", 33, "-dir", 1)
    else:
        ops.uniaxialMaterial("Elastic", 3, float(iso["K2"]))
        ops.uniaxialMaterial("ElasticPP", 4, float(iso["K1"] - iso["K2"]), float(iso["u_y"]))
        ops.uniaxialMaterial("Parallel", 5, 3, 4)
        ops.element("zeroLength", 1, _GROUND, nodes[0], "-mat", 5, "-dir", 1)
    if bld["c_iso"] > 0.0:
        ops.uniaxialMaterial("Viscous", 6, float(bld["c_iso"]), 1.0)
        ops.element("zeroLength", 2, _GROUND, nodes[0], "-mat", 6, "-dir", 1)
    # stories
    for s in range(1, bld["n_stories"] + 1):
        k_s, f_y = float(bld["story_k"][s - 1]), float(bld["story_yield"][s - 1])
        if math.isfinite(f_y):
            ops.uniaxialMaterial("Steel01", 1000 + s, f_y, k_s, float(bld["story_b"][s - 1]))
        else:
            ops.uniaxialMaterial("Elastic", 1000 + s, k_s)
        ops.uniaxialMaterial("Viscous", 2000 + s, float(bld["c_story"][s - 1]), 1.0)
        i, j = nodes[s - 1], nodes[s]
        ops.element("zeroLength", 1000 + s, i, j, "-mat", 1000 + s, "-dir", 1)
        ops.element("zeroLength", 2000 + s, i, j, "-mat", 2000 + s, "-dir", 1)

    if contact == "elastic":
        ops.uniaxialMaterial("ElasticPPGap", 7, float(k), _FY_NEVER, float(gap), 0.0, "noDamage")
        ops.uniaxialMaterial("ElasticPPGap", 8, float(k), -_FY_NEVER, -float(gap), 0.0, "noDamage")
        ops.element("zeroLength", _GAP_ELES[0], _GROUND, nodes[0], "-mat", 7, "-dir", 1)
        ops.element("zeroLength", _GAP_ELES[1], _GROUND, nodes[0], "-mat", 8, "-dir", 1)
    elif contact in ("jankowski", "hertzdamp"):
        if contact == "jankowski":
            xi = jankowski_xi(float(cor))
            ops.uniaxialMaterial("JankowskiImpact", 7, float(beta), xi, float(m_eff),
                                 -float(gap), 1.5)
        else:
            chi = 0.75 * (1.0 - float(cor) ** 2)
            ops.uniaxialMaterial("Hertzdamp", 7, float(k), chi, -float(gap), float(n))
        # "-" wall: deformation u_0 closes when u_0 < -gap
        ops.element("zeroLength", _GAP_ELES[1], _GROUND, nodes[0], "-mat", 7, "-dir", 1)
        # "+" wall: reversed node order, deformation -u_0 closes when u_0 > gap
        ops.element("zeroLength", _GAP_ELES[0], nodes[0], _GROUND, "-mat", 7, "-dir", 1)

    ag = np.asarray(ag, dtype=float)
    # -useLast: a step that ends a hair past the record (the steps' times accumulate
    # round-off) keeps the last sample instead of dropping to 0, a jump of the inertia load.
    ops.timeSeries("Path", 1, "-dt", float(ag_dt), "-values", *ag.tolist(), "-factor", 1.0,
                   "-useLast")
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)

    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-10, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    return bld


def opensees_peaks(ag, ag_dt, *, contact=None, gap=None, k=None, beta=None, cor=None,
                   m_eff=320e3, dt=None, masses=None, story_k=None, isolator=None,
                   story_yield=None, story_b=_STORY_B, zeta_iso=None,
                   zeta_sup=_ZETA_S) -> dict:
    """Run the OpenSees reference model under ground acceleration ``ag`` (m/s^2, step ag_dt s).

    contact: None (no wall), "elastic" (needs gap [m], k [N/m]; cor is ignored),
    "jankowski" (needs gap [m], beta [N/m^1.5], cor; m_eff [kg]) or "hertzdamp" (needs gap
    [m], k [N/m^1.5], cor).
    dt: analysis step, default 0.001 s with contact or a friction pendulum, 0.002 s otherwise.
    masses, story_k, isolator, story_yield, story_b, zeta_iso, zeta_sup: the building, see
    ``building`` (defaults: the paper's).
    Returns peak_total_accel (N+1,) m/s^2, peak_interstory_drift (N,) m, peak_isolator_disp m,
    max_indentation m, max_impact_force N, n_impacts, and peak_story_ductility (N,) (peak
    |drift| / (F_i / k_i); 0 for a story without a yield force) when story_yield is given.
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
    friction = isolator is not None and isolator.get("kind") == "friction_pendulum"
    if dt is None:
        dt = 0.001 if (contact or friction) else 0.002
    dt = float(dt)
    t_rec = np.arange(ag.size) * float(ag_dt)
    duration = float(t_rec[-1])

    t0 = time.perf_counter()
    bld = build_model(ag, ag_dt, contact, gap, k, beta, cor, m_eff, masses=masses,
                      story_k=story_k, isolator=isolator, story_yield=story_yield,
                      story_b=story_b, zeta_iso=zeta_iso, zeta_sup=zeta_sup)

    times, disp, accel, fgap = [], [], [], []
    nodes = bld["level_nodes"]
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
    drift = np.abs(np.diff(disp, axis=1)).max(axis=0)
    out = {
        "peak_total_accel": np.abs(accel).max(axis=0),
        "peak_interstory_drift": drift,
        "peak_isolator_disp": float(np.abs(u0).max()),
        "max_indentation": 0.0,
        "max_impact_force": 0.0,
        "n_impacts": 0,
    }
    if bld["yielding"]:
        out["peak_story_ductility"] = drift / bld["yield_drift"]
    if has_gap:
        delta = np.maximum(np.abs(u0) - float(gap), 0.0)
        inside = delta > 0.0
        out["max_indentation"] = float(delta.max())
        out["max_impact_force"] = float(np.max(fgap))
        out["n_impacts"] = int(np.count_nonzero(inside[1:] & ~inside[:-1]) + int(inside[0]))

    LAST_RUN.clear()
    LAST_RUN.update(stats, wall_time_s=time.perf_counter() - t0, recorded_points=len(times),
                    end_time=float(times[-1]), duration=duration, dt=dt, contact=contact,
                    isolator=bld["isolator"]["kind"], n_stories=bld["n_stories"])
    return out


def fp_bearing_loop(displacements, velocities, *, radius, mu_slow, mu_fast, rate, weight,
                    yield_disp=_YIELD_DISP) -> np.ndarray:
    """Horizontal force (N) of this module's friction pendulum (``flatSliderBearing`` under
    the constant weight + the W / R spring) along an imposed path, quasi-statically.

    A static ``DisplacementControl`` analysis moves the slider through ``displacements`` (m,
    from 0); before each step the slider's trial velocity is set to the matching entry of
    ``velocities`` (m/s, ``setNodeVel``), which is the velocity the friction model reads. No
    inertia, no damping. Returns the force after each step."""
    u = np.asarray(displacements, dtype=float).ravel()
    v = np.broadcast_to(np.asarray(velocities, dtype=float), u.shape)
    k0 = mu_fast * weight / yield_disp
    ops.wipe()
    try:
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        ops.node(1, 0.0, 0.0)
        ops.fix(1, 1, 1, 1)
        ops.node(2, 0.0, 0.0)
        ops.fix(2, 0, 1, 1)
        ops.frictionModel("VelDependent", 1, float(mu_slow), float(mu_fast), float(rate))
        ops.uniaxialMaterial("Elastic", 30, _AXIAL_K)
        ops.uniaxialMaterial("InitStressMaterial", 31, 30, -float(weight))
        ops.uniaxialMaterial("Elastic", 32, 0.0)
        ops.uniaxialMaterial("Elastic", 33, float(weight) / float(radius))
        ops.element("flatSliderBearing", 1, 1, 2, 1, float(k0), "-P", 31, "-Mz", 32,
                    "-orient", 0.0, 1.0, 0.0, -1.0, 0.0, 0.0)
        ops.element("zeroLength", 3, 1, 2, "-mat", 33, "-dir", 1)
        ops.timeSeries("Linear", 1)
        ops.pattern("Plain", 1, 1)
        ops.load(2, 1.0, 0.0, 0.0)
        ops.constraints("Plain")
        ops.numberer("Plain")
        ops.system("BandGeneral")
        ops.test("NormDispIncr", 1e-12, 50)
        ops.algorithm("Newton")
        force = np.empty(u.size)
        previous = 0.0
        for i, (target, vel) in enumerate(zip(u, v, strict=True)):
            ops.integrator("DisplacementControl", 2, 1, float(target - previous))
            ops.analysis("Static")
            ops.setNodeVel(2, 1, float(vel))
            if ops.analyze(1) != 0:
                raise RuntimeError(f"fp_bearing_loop: step {i} failed")
            previous = ops.nodeDisp(2, 1)
            force[i] = ops.eleForce(1)[3] + ops.eleForce(3)[3]
    finally:
        ops.wipe()
    return force


def steel01_loop(drifts, *, k, f_y, b=_STORY_B) -> np.ndarray:
    """Force (N) of this module's yielding story spring (``Steel01 f_y k b``) along the drift
    path ``drifts`` (m, from 0), strain by strain (``testUniaxialMaterial``)."""
    ops.wipe()
    try:
        ops.model("basic", "-ndm", 1, "-ndf", 1)
        ops.uniaxialMaterial("Steel01", 1, float(f_y), float(k), float(b))
        ops.testUniaxialMaterial(1)
        force = np.empty(len(drifts))
        for i, d in enumerate(np.asarray(drifts, dtype=float)):
            ops.setStrain(float(d))
            force[i] = ops.getStress()
    finally:
        ops.wipe()
    return force
