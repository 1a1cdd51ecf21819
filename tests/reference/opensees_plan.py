"""Independent OpenSeesPy model of the base-isolated shear building IN PLAN (both horizontal
directions), for cross-validating the engine's runs in plan (``engine.simulate(pair, ...)``).

A test helper, not part of the package: it rebuilds the building of SPEC sections 1-2 moving in
x and y as an OpenSees 3-D model (through ``openseespy``), without any code from ``engine/``
(numbers only as inputs), runs it under a pair of ground-acceleration components and returns
the peaks the engine's PlanResult reports: resultants (vector magnitudes) and per-direction
peaks, and the largest force on each wall. It resolves the building's numbers with
``opensees_reference.building`` (the planar OpenSees reference, which documents them; no code
of the solve_ivp references). Units SI throughout (kg, m, s, N).

The model (``-ndm 3 -ndf 6``)
-----------------------------
* Nodes: a fixed ground node and one node per level 0..N, all at (0, 0, 0) (every element is
  zero-length). Each level node has its horizontal DOFs X and Y free and Z, RX, RY, RZ fixed
  (no vertical motion, no rotation: the shear building of the planar model, in both
  directions), and the level's mass m_j in X and Y.
* Stories: per story, one ``zeroLength`` element with ``Elastic`` k_j in ``-dir 1 2`` (two
  uncoupled springs: a linear isotropic spring is exactly that) and one with ``Viscous``
  c_j = 2 zeta_sup k_j / omega_1 (alpha 1) in ``-dir 1 2``; omega_1 the first circular
  frequency of the fixed-base superstructure ("paper" damping, as the planar reference). No
  Rayleigh damping: all damping is in the discrete dashpots. Yielding stories are not
  modelled in plan (uncoupled Steel01 springs per direction would not be the engine's coupled
  story law): there is no story_yield input.
* Isolation dashpot: ``Viscous`` c_iso = 2 zeta_iso sqrt(k_ref M_tot) in ``-dir 1 2`` between
  ground and level 0 (k_ref = K1 for the bilinear isolator, k_0 + W / R for the friction
  pendulum; zeta_iso 5 % and 0 by default; no element when c_iso = 0).
* Bilinear isolator, coupled: ``elastomericBearingPlasticity`` (3-D, ElastomericBearing-
  Plasticity3d.cpp, OpenSees 3.7) with kInit = K1, qd = Fy (1 - K2 / K1), alpha1 = K2 / K1,
  alpha2 = 0, mu = 2 (mu only enters the term alpha2 kInit sgn(u) |u|^mu, 0 here; mu >= 1
  keeps its tangent 0 * |u|^(mu-1) finite at u = 0), ``-orient 0 0 1 1 0 0`` (local x, the axial
  direction, = global Z; local y = global X; local z = x cross y = global Y), ``-P``/``-T``/
  ``-My``/``-Mz`` ``Elastic`` materials on DOFs that are fixed anyway. What it implements (read
  from the source; ``isolator_path`` drives it along a path in plan, and it gives the engine's
  radial return to round-off, tests/engine/test_plan_references.py): shear force
  q = k2 u + q_h, k2 = alpha1 kInit = K2, with the hysteretic part q_h = k0 (u - u_p),
  k0 = (1 - alpha1) kInit = K1 - K2, a 2-vector; its yield surface is
  the CIRCLE |q_h| = qYield, qYield = qd (OpenSees 3.7's constructor takes qd as the yield
  force of the hysteretic part, the characteristic strength; older versions scaled it by
  (1 - alpha1), and qd = Fy would raise the yield force by K1 / (K1 - K2), 14% here); a
  plastic step is the backward-Euler return map from the committed plastic
  displacement, q_trial = k0 (u_{n+1} - u_p,n), q_h = qYield q_trial / |q_trial| when
  |q_trial| > qYield: the exact radial return of a perfectly plastic spring with a circular
  yield surface, which is the engine's law (K2 in parallel with a slip element of stiffness
  K1 - K2 and limit (K1 - K2) u_y = Fy (1 - K2 / K1), circular) exactly; what differs is the
  time integration around it (Newmark here, central differences there).
* Friction pendulum, coupled: ``flatSliderBearing`` (3-D, FlatSliderSimple3d.cpp) with the
  ``VelDependent`` friction model (mu_slow, mu_fast, rate: mu = mu_fast - (mu_fast - mu_slow)
  exp(-rate |v|)), kInit = k_0 = mu_fast W / yield_disp, the same orientation, under the
  constant normal force W (``-P``: ``InitStressMaterial`` with initial stress -W around a stiff
  ``Elastic``; the vertical DOF is fixed, so its deformation stays 0 and N = W, as in the
  planar reference), in parallel with ``Elastic`` W / R springs in ``-dir 1 2`` (a
  ``zeroLength``). What the element implements: the friction force is the hysteretic part of
  the same circular plasticity, q_trial = k_0 (u_{n+1} - u_p,n) returned radially onto the
  circle of radius mu(|v_{n+1}|) N, |v| = sqrt(v_x^2 + v_y^2) the slider's resultant trial
  velocity (the friction model gets the sliding SPEED, so the law is isotropic); N also has
  the terms -qb(1) ul(5) + qb(2) ul(4), zero with rotations fixed. The engine: the same
  radial return onto mu(|v|) W, with |v| its half-step speed (``isolator_path`` with the
  engine's speeds: the same forces to round-off); ``singleFPBearing`` is not used
  for the reasons the planar reference gives (second-order terms the engine leaves out).
* Triple friction pendulum, coupled: ``TripleFrictionPendulum`` (3-D, Dao et al. 2013;
  TripleFrictionPendulum.cpp) with L1 L2 L3 d1 d2 d3, W, uy = yield_disp, kvt 1 N/m, minFv
  0.1 N, tol 1e-10, three ``Coulomb`` friction models (mu1 inner, mu2 lower, mu3 upper
  outer), the vertical material an ``InitStressMaterial`` of initial stress -W around the
  stiff ``Elastic`` (the vertical DOF is fixed: N = W throughout), the rotations ``Elastic``
  0. The element uses global X, Y as its shear directions (no orientation). What it
  implements (read from the source): three elements in series, each a circular plasticity
  with kinematic hardening (E = 3 mu1 / uy, yield mu_i, post-yield stiffness 1 / (2 L1),
  1 / (L2 - L1), 1 / (L3 - L1), all per unit W) in parallel with a circular gap spring of
  stiffness E past 2 (L1 d3 / L3 + d1), d2 (1 - L1 / L2), d3 (1 - L1 / L3), solved by its
  own nested Newton iterations to tol (which leave the model's Newton at ~1e-9 m: its test
  is ``NormDispIncr`` 1e-8 m with this element, 1e-10 m otherwise; a tol of 1e-13 makes the
  element's iterations fail). The engine's law: the same elements
  (tests/engine/isolators/laws/test_triple_friction_pendulum.py holds them to the same
  forces along paths in plan, ``isolator_path``).
* Walls: none, or a rectangular moat of elastic walls: four ``zeroLength`` elements between
  ground and level 0, in WALLS order +x, -x, +y, -y, each an ``ElasticPPGap`` (stiffness k,
  a yield force of 1e30 N that is never reached, gap +-g, eta 0, ``noDamage``) in ``-dir 1``
  (x walls, gap g_x, stiffness k_x) or ``-dir 2`` (y walls, g_y, k_y): one compression-only
  linear spring per wall along its normal, no damping (COR 1). A corner loads a x wall and a
  y wall at once, each along its own normal, as the engine's rectangular moat.
* Ground motion: two ``timeSeries Path`` (x and y components, linear between samples,
  ``-useLast``) driving two ``pattern UniformExcitation`` in directions 1 and 2. Node
  responses are relative to the ground; total acceleration = ``nodeAccel`` + a_g(t) per
  direction, a_g interpolated at the analysis time with the same linear rule.
* Analysis: ``Transient``, ``Newmark`` gamma 1/2, beta 1/4 (average acceleration), fixed
  step dt (default the engine's 0.5 ms), ``Newton`` with ``NormDispIncr`` 1e-10 m (1e-8 m
  with the triple friction pendulum, above), the planar reference's fallbacks
  (ModifiedNewton -initial, KrylovNewton, then halved steps down to dt / 2**8). Peaks are
  taken over the converged (sub)steps.

Peaks (the engine's PlanResult names): peak_total_accel (N+1,) m/s^2, peak_interstory_drift
(N,) m, peak_isolator_disp m (resultants: the peak of |a_j(t)|, |u_j(t) - u_{j-1}(t)|,
|u_0(t)|), their per-direction peaks peak_total_accel_xy (N+1, 2), peak_interstory_drift_xy
(N, 2), peak_isolator_disp_xy (2,); and with walls max_indentation m (the deepest of the four),
max_impact_force N (the largest force of one wall), n_impacts (how many times a wall came into
contact, all walls counted), max_impact_force_wall (4,) N in +x, -x, +y, -y order.

``LAST_RUN`` holds diagnostics of the latest call (steps, fallbacks, wall time).
"""
from __future__ import annotations

import math
import time

import numpy as np
import openseespy.opensees as ops

from .opensees_reference import building

WALLS = ("+x", "-x", "+y", "-y")
"""The rectangular moat's walls, each named by its outward normal (the engine's order)."""
DEFAULT_DT = 5e-4  # s, the engine's step

LAST_RUN: dict = {}

_GROUND = 100
_WALL_ELES = (201, 202, 203, 204)  # +x, -x, +y, -y
_FY_NEVER = 1e30  # N, the walls' "yield" force: never reached
_AXIAL_K = 1e15  # N/m, the friction pendulum's axial material (its deformation stays 0)
_MAX_HALVINGS = 8
_ORIENT = (0.0, 0.0, 1.0, 1.0, 0.0, 0.0)  # bearings: local x = global Z, local y = global X
_TFP_MIN_FV = 0.1  # N, the triple friction pendulum's least normal force (never reached)
_TFP_TOL = 1e-8  # its relative tolerance (1e-10 and below: its own iterations fail, it glitches)
_TFP_NORM = 1e-10  # m, Newton's tolerance with it


def _node_tags(n_levels: int) -> tuple[int, ...]:
    """Node tags of levels 0..N (level j is node j + 1)."""
    return tuple(range(1, n_levels + 1))


def _nodes(bld: dict) -> tuple[int, ...]:
    """The ground node (fixed) and the level nodes: X, Y free, Z and rotations fixed, the
    level's mass in X and Y."""
    ops.node(_GROUND, 0.0, 0.0, 0.0)
    ops.fix(_GROUND, 1, 1, 1, 1, 1, 1)
    nodes = _node_tags(bld["masses"].size)
    for node, m in zip(nodes, bld["masses"], strict=True):
        ops.node(node, 0.0, 0.0, 0.0)
        ops.fix(node, 0, 0, 1, 1, 1, 1)
        ops.mass(node, float(m), float(m), 0.0, 0.0, 0.0, 0.0)
    return nodes


def _pair_of(tag: int, eletag: int, i: int, j: int, material: tuple):
    """One uniaxial material (args after the tag) acting along X and Y between nodes i and j:
    a zeroLength element with the material in -dir 1 2 (two uncoupled springs)."""
    ops.uniaxialMaterial(material[0], tag, *material[1:])
    ops.element("zeroLength", eletag, i, j, "-mat", tag, tag, "-dir", 1, 2)


def _isolator(bld: dict, level0: int):
    """The coupled isolator and the isolation dashpot between the ground and level 0."""
    iso = bld["isolator"]
    ops.uniaxialMaterial("Elastic", 30, _AXIAL_K)
    ops.uniaxialMaterial("Elastic", 32, 0.0)  # torsion and bending: DOFs fixed anyway
    if iso["kind"] == "bilinear":
        k1, k2 = float(iso["K1"]), float(iso["K2"])
        qd = float(iso["Fy"]) * (1.0 - k2 / k1)  # the hysteretic part's yield force
        ops.element("elastomericBearingPlasticity", 1, _GROUND, level0, k1, qd, k2 / k1, 0.0,
                    2.0, "-P", 30, "-T", 32, "-My", 32, "-Mz", 32, "-orient", *_ORIENT)
    elif iso["kind"] == "triple_friction_pendulum":
        w = float(iso["weight"])
        for tag, mu in enumerate((iso["mu1"], iso["mu2"], iso["mu3"]), start=1):
            ops.frictionModel("Coulomb", tag, float(mu))
        ops.uniaxialMaterial("InitStressMaterial", 31, 30, -w)  # constant compression W
        ops.element("TripleFrictionPendulum", 1, _GROUND, level0, 1, 2, 3, 31, 32, 32, 32,
                    *(float(iso[key]) for key in ("L1", "L2", "L3", "d1", "d2", "d3")), w,
                    float(iso["yield_disp"]), 1.0, _TFP_MIN_FV, _TFP_TOL)
    else:
        w = float(iso["weight"])
        ops.frictionModel("VelDependent", 1, float(iso["mu_slow"]), float(iso["mu_fast"]),
                          float(iso["rate"]))
        ops.uniaxialMaterial("InitStressMaterial", 31, 30, -w)  # constant compression W
        ops.element("flatSliderBearing", 1, _GROUND, level0, 1, float(iso["k0"]), "-P", 31,
                    "-T", 32, "-My", 32, "-Mz", 32, "-orient", *_ORIENT)
        _pair_of(33, 3, _GROUND, level0, ("Elastic", float(iso["k_pendulum"])))
    if bld["c_iso"] > 0.0:
        _pair_of(6, 2, _GROUND, level0, ("Viscous", float(bld["c_iso"]), 1.0))


def _stories(bld: dict, nodes: tuple[int, ...]):
    """Story springs and dashpots, isotropic (the same in X and Y)."""
    for s in range(1, bld["n_stories"] + 1):
        i, j = nodes[s - 1], nodes[s]
        _pair_of(1000 + s, 1000 + s, i, j, ("Elastic", float(bld["story_k"][s - 1])))
        _pair_of(2000 + s, 2000 + s, i, j, ("Viscous", float(bld["c_story"][s - 1]), 1.0))


def _walls(level0: int, gap: tuple[float, float], k: tuple[float, float]):
    """The rectangular moat: per axis d (X = 1, Y = 2) a wall at +gap[d] and one at -gap[d],
    each an ElasticPPGap of stiffness k[d] in compression only, in WALLS order."""
    for w, (ele, sign) in enumerate(zip(_WALL_ELES, (1, -1, 1, -1), strict=True)):
        axis = w // 2
        ops.uniaxialMaterial("ElasticPPGap", 40 + w, float(k[axis]), sign * _FY_NEVER,
                             sign * float(gap[axis]), 0.0, "noDamage")
        ops.element("zeroLength", ele, _GROUND, level0, "-mat", 40 + w, "-dir", axis + 1)


def _ground_motion(pair: np.ndarray, pair_dt: float):
    """Two Path series (x, y) and their UniformExcitation patterns in directions 1 and 2.
    -useLast: a step ending a hair past the record keeps the last sample (see the planar
    reference)."""
    for d in range(2):
        ops.timeSeries("Path", d + 1, "-dt", float(pair_dt), "-values", *pair[:, d].tolist(),
                       "-factor", 1.0, "-useLast")
        ops.pattern("UniformExcitation", d + 1, d + 1, "-accel", d + 1)


def build_model(pair, pair_dt, *, walls=None, masses=None, story_k=None, isolator=None,
                zeta_iso=None, zeta_sup=0.02) -> dict:
    """Build the model in OpenSees' domain, ready for ``ops.analyze(1, dt)``.

    pair (T, 2) m/s^2 every pair_dt s; walls: None or ((g_x, g_y) m, (k_x, k_y) N/m); the
    building keywords are those of ``opensees_reference.building`` (no story_yield). Returns
    its resolved numbers with "level_nodes" (node tags of levels 0..N)."""
    bld = building(masses, story_k, isolator, None, 0.02, zeta_iso, zeta_sup)
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    nodes = _nodes(bld)
    bld["level_nodes"] = nodes
    _isolator(bld, nodes[0])
    _stories(bld, nodes)
    if walls is not None:
        _walls(nodes[0], *walls)
    _ground_motion(pair, pair_dt)
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", _TFP_NORM if bld["isolator"]["kind"] == "triple_friction_pendulum"
             else 1e-10, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    return bld


def _checked_pair(pair) -> np.ndarray:
    pair = np.asarray(pair, dtype=float)
    if pair.ndim != 2 or pair.shape[1] != 2 or pair.shape[0] < 2:
        raise ValueError(f"pair must be (T, 2) with T >= 2, got {pair.shape}")
    return pair


def _checked_walls(gap, k, gap_y, k_y):
    """((g_x, g_y), (k_x, k_y)) or None; the y walls default to the x walls' values."""
    if gap is None:
        return None
    gaps = (float(gap), float(gap if gap_y is None else gap_y))
    stiff = (float(k), float(k if k_y is None else k_y))
    if min(gaps) < 0 or min(stiff) <= 0:
        raise ValueError(f"walls need gaps >= 0 and k > 0, got {gaps}, {stiff}")
    return gaps, stiff


def plan_peaks(pair, pair_dt, *, gap=None, k=None, gap_y=None, k_y=None, dt=DEFAULT_DT,
               masses=None, story_k=None, isolator=None, zeta_iso=None,
               zeta_sup=0.02) -> dict:
    """Run the model under the pair (T, 2) m/s^2 (x, y components every pair_dt s) over the
    whole pair ((T - 1) pair_dt s).

    gap (m) and k (N/m): None for no wall, else the rectangular moat's x walls at +-gap with
    stiffness k; gap_y, k_y those of the y walls (default: the x walls'). dt: analysis step (s).
    masses, story_k, isolator, zeta_iso, zeta_sup: the building, see
    ``opensees_reference.building`` (defaults: the paper's). Returns the peaks named in the
    module docstring.
    """
    pair = _checked_pair(pair)
    walls = _checked_walls(gap, k, gap_y, k_y)
    duration = (pair.shape[0] - 1) * float(pair_dt)
    t0 = time.perf_counter()
    bld = build_model(pair, pair_dt, walls=walls, masses=masses, story_k=story_k,
                      isolator=isolator, zeta_iso=zeta_iso, zeta_sup=zeta_sup)
    nodes = bld["level_nodes"]
    rec = {"t": [], "u": [], "a": [], "f": []}

    def record():
        rec["t"].append(ops.getTime())
        rec["u"].append([[ops.nodeDisp(n, d) for d in (1, 2)] for n in nodes])
        rec["a"].append([[ops.nodeAccel(n, d) for d in (1, 2)] for n in nodes])
        if walls is not None:
            rec["f"].append([abs(ops.eleForce(e)[6 + w // 2])
                             for w, e in enumerate(_WALL_ELES)])

    try:
        record()  # t = 0, at rest
        stats = _run(float(dt), duration, record)
    finally:
        ops.wipe()
    out = _peaks(rec, pair, float(pair_dt), walls)
    LAST_RUN.clear()
    LAST_RUN.update(stats, wall_time_s=time.perf_counter() - t0, recorded_points=len(rec["t"]),
                    end_time=float(rec["t"][-1]), duration=duration, dt=float(dt),
                    isolator=bld["isolator"]["kind"], walls=walls)
    return out


def _run(dt: float, duration: float, record) -> dict:
    """Advance the analysis over [0, duration] in steps of dt (a shorter last step when dt does
    not divide it), calling record() after every converged (sub)step; the planar reference's
    fallbacks on a failed step."""
    stats = {"steps": 0, "fallback_algorithms": 0, "substeps": 0}

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

    ratio = duration / dt
    n_full = int(round(ratio)) if abs(ratio - round(ratio)) < 1e-6 else int(math.floor(ratio))
    for _ in range(n_full):
        step(dt)
    rest = duration - n_full * dt
    if rest > 1e-6 * dt:
        step(rest)
    return stats


def isolator_path(displacements, velocities=0.0, *, masses=None, isolator=None) -> np.ndarray:
    """(T, 2) horizontal force (N, x and y) of this module's isolator (the bearing element, plus
    the W / R springs of a friction pendulum; no dashpot) along an imposed path of the slab,
    quasi-statically: to check the element's law against a closed form.

    displacements (T, 2) m, from 0; velocities (T, 2) m/s (broadcast), the slab's trial
    velocity at each point, which is what the friction model reads (``setNodeVel``; no
    effect on the bilinear bearing). A static analysis imposes each point with ``sp``
    constraints (``Transformation``); the slab's other DOFs are fixed (the normal force stays
    W), and a dummy node on a unit spring keeps one DOF free, as a system needs one.
    isolator, masses: as for ``plan_peaks``."""
    u = np.asarray(displacements, dtype=float).reshape(-1, 2)
    v = np.broadcast_to(np.asarray(velocities, dtype=float), u.shape)
    bld = building(masses, None, isolator, None, 0.02, 0.0, 0.02)
    slab, dummy = 1, 2
    ops.wipe()
    try:
        ops.model("basic", "-ndm", 3, "-ndf", 6)
        ops.node(_GROUND, 0.0, 0.0, 0.0)
        ops.fix(_GROUND, 1, 1, 1, 1, 1, 1)
        ops.node(slab, 0.0, 0.0, 0.0)
        ops.fix(slab, 0, 0, 1, 1, 1, 1)
        ops.node(dummy, 0.0, 0.0, 0.0)
        ops.fix(dummy, 0, 1, 1, 1, 1, 1)
        ops.uniaxialMaterial("Elastic", 50, 1.0)
        ops.element("zeroLength", 50, _GROUND, dummy, "-mat", 50, "-dir", 1)
        _isolator({**bld, "c_iso": 0.0}, slab)
        ops.constraints("Transformation")
        ops.numberer("Plain")
        ops.system("FullGeneral")
        ops.test("NormDispIncr", 1e-12, 50)
        ops.algorithm("Newton")
        ops.integrator("LoadControl", 1.0)
        ops.analysis("Static")
        elements = (1, 3) if bld["isolator"]["kind"] == "friction_pendulum" else (1,)
        force = np.empty_like(u)
        for i in range(u.shape[0]):
            ops.timeSeries("Constant", 10 + i)
            ops.pattern("Plain", 10 + i, 10 + i)
            for d in range(2):
                ops.sp(slab, d + 1, float(u[i, d]))
                # -commit: without it each call restarts from the committed velocity vector,
                # so setting y would undo x
                ops.setNodeVel(slab, d + 1, float(v[i, d]), "-commit")
            if ops.analyze(1) != 0:
                raise RuntimeError(f"isolator_path: point {i} failed")
            ops.remove("loadPattern", 10 + i)
            # the force on the slab node (the element's j end) is the bearing's resistance
            force[i] = [sum(ops.eleForce(e)[6 + d] for e in elements) for d in range(2)]
    finally:
        ops.wipe()
    return force


def _peaks(rec: dict, pair: np.ndarray, pair_dt: float, walls) -> dict:
    """The PlanResult peaks from the recorded histories: times (T,), displacements and relative
    accelerations (T, L, 2), wall forces (T, 4)."""
    times = np.asarray(rec["t"])
    u = np.asarray(rec["u"])
    t_rec = np.arange(pair.shape[0]) * pair_dt
    ground = np.column_stack([np.interp(times, t_rec, pair[:, d]) for d in range(2)])
    accel = np.asarray(rec["a"]) + ground[:, None, :]
    drift = np.diff(u, axis=1)
    u0 = u[:, 0]
    out = {
        "peak_total_accel": np.linalg.norm(accel, axis=-1).max(axis=0),
        "peak_interstory_drift": np.linalg.norm(drift, axis=-1).max(axis=0),
        "peak_isolator_disp": float(np.linalg.norm(u0, axis=-1).max()),
        "peak_total_accel_xy": np.abs(accel).max(axis=0),
        "peak_interstory_drift_xy": np.abs(drift).max(axis=0),
        "peak_isolator_disp_xy": np.abs(u0).max(axis=0),
        "max_indentation": 0.0, "max_impact_force": 0.0, "n_impacts": 0,
        "max_impact_force_wall": np.zeros(len(WALLS)),
    }
    if walls is not None:
        gaps = np.repeat(walls[0], 2)  # +x, -x, +y, -y
        signs = np.array([1.0, -1.0, 1.0, -1.0])
        delta = signs * u0[:, [0, 0, 1, 1]] - gaps  # (T, 4) indentation of each wall
        inside = delta > 0
        force = np.asarray(rec["f"])
        out.update(max_indentation=float(max(delta.max(), 0.0)),
                   max_impact_force=float(force.max()),
                   n_impacts=int(np.count_nonzero(inside[1:] & ~inside[:-1])
                                 + np.count_nonzero(inside[0])),
                   max_impact_force_wall=force.max(axis=0))
    return out
