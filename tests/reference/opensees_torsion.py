"""Independent OpenSeesPy 3-D models of an isolated building that can twist: its slab a rigid
diaphragm on bearings at their positions, its mass centres off the plan centre (the reference
the torsional model, /work/archives/torsion_model.md, is to be checked against; a test helper,
no code from engine/, numbers only as inputs; the building's numbers resolved by
``opensees_reference.building``, as tests/reference/opensees_plan.py does). Units SI.

The slab alone, linear (``build``; ``eigen_frequencies``, ``static_twist``)
--------------------------------------------------------------------------
``model basic -ndm 3 -ndf 6``. A master node at the mass centre (e_x, e_y, 0) carries the
slab's mass m along x and y and its polar moment J about z (a uniform slab of plan b_x x b_y:
J = m (b_x^2 + b_y^2) / 12 about its own centre, the mass centre here); its vertical
translation and its rotations about x and y are fixed. One node per bearing at (x_i, y_i, 0),
tied to the master by ``rigidDiaphragm 3`` (their x, y and rotation about z follow the
slab's), its other DOFs fixed; a fixed ground node at the same place; a ``zeroLength`` bearing
between them, ``Elastic`` k_i along x and along y. Constraints ``Transformation``.

The building under a pair of ground motions (``build_transient``; ``torsion_peaks``)
-----------------------------------------------------------------------------------
The spec's model: levels j = 0 (isolation slab) .. N (roof), each a rigid diaphragm with the
three DOFs (u_x, u_y, theta) of its PLAN CENTRE (the origin), relative to the ground.
``model basic -ndm 3 -ndf 6``; every node at z = 0 (every element is zero-length).

* Masters: node 1 + j at (0, 0, 0) per level j, X, Y and RZ free, Z, RX, RY fixed, no mass.
  Each level's slave nodes are tied to it by ``rigidDiaphragm 3`` (a slave at (X, Y) moves by
  (u_x - theta Y, u_y + theta X), rotates by theta: the spec's linearised kinematics); every
  slave has Z, RX, RY fixed, so the only free DOFs of the model are the masters' (x, y, rz).
  Constraints ``Transformation``.
* Mass: a slave node 100 + j at the level's eccentricity (e_x, e_y) (one pair for every level,
  or one per level) carrying m_j along X and Y and J_j about Z (default the uniform slab's
  m_j (b_x^2 + b_y^2) / 12): about the plan centre the level's mass matrix is then the
  spec's [[m, 0, -m e_y], [0, m, m e_x], [-m e_y, m e_x, J + m (e_x^2 + e_y^2)]].
* Stories: between the masters of levels j - 1 and j, a ``zeroLength`` with ``Elastic`` k_j in
  ``-dir 1 2`` and ``Elastic`` k_theta_j in ``-dir 6`` (default the perimeter frame's
  k_j (b_x^2 + b_y^2) / 4), and one with ``Viscous`` (alpha 1) c_j in ``-dir 1 2`` and
  c_j k_theta_j / k_j in ``-dir 6``, c_j = 2 zeta_sup k_j / omega_1 (omega_1 the fixed-base
  superstructure's first circular frequency along x: the planar "paper" damping, as
  ``opensees_reference.building`` gives it). No Rayleigh damping.
* Bearings: n identical bearings at positions (X_b, Y_b), each a slave node 1000 + b of level
  0 and a fixed ground node 2000 + b at the same place, joined by an
  ``elastomericBearingPlasticity`` (zero length) with kInit = K1 / n,
  qd = Fy (1 - K2 / K1) / n, alpha1 = K2 / K1, alpha2 0, mu 2, ``-orient 0 0 1 1 0 0``,
  ``-P`` stiff ``Elastic`` (the vertical DOF is fixed), ``-T``/``-My``/``-Mz`` ``Elastic`` 0
  (the bearing has no torsional stiffness of its own: the slab's comes from the bearings'
  shear forces at their positions; RX, RY fixed): opensees_plan.py's bearing (see its
  docstring for what the element implements: the engine's circular radial return exactly)
  divided by n, so n bearings at one point are opensees_plan's bearing. In parallel, a
  ``zeroLength`` ``Viscous`` c_iso / n in ``-dir 1 2``, c_iso = 2 zeta_iso sqrt(K1 M_tot)
  (no element when c_iso = 0). Only the bilinear isolator.
* Walls: none, or the rectangular moat: walls normal to x at x = +-(b_x / 2 + g_x), normal to
  y at y = +-(b_y / 2 + g_y). The slab's four corners are slave nodes 3000 + c of level 0 (c
  in CORNERS order), each with a fixed ground node 4000 + c; between them two ``zeroLength``
  elements, one along X towards the corner's x wall and one along Y towards its y wall, each
  an ``ElasticPPGap`` (stiffness k / 2 of its wall, a yield force of +-1e30 N never reached,
  gap +-g of its axis, eta 0, ``noDamage``: compression only, no damping, COR 1); a corner's
  relative displacement along X is u_x0 - theta_0 Y_c, so the +x element closes when it
  exceeds g_x: the spec's indentation. Each wall's two corners thus carry half its law;
  elements 5000 + p, p the contact point's index in POINTS order.
* Ground motion: two ``timeSeries Path`` (x, y; linear between samples, ``-useLast``) driving
  ``pattern UniformExcitation`` in directions 1 and 2 (no rotational input). Responses are
  relative to the ground; total acceleration of a plan centre = ``nodeAccel`` + a_g(t), a_g
  interpolated at the analysis time with the same linear rule.
* Analysis: ``Transient``, ``Newmark`` gamma 1/2, beta 1/4, fixed step dt (default the
  engine's 0.5 ms), ``Newton`` with ``NormDispIncr`` 1e-10 (m and rad, the masters' DOFs),
  opensees_plan's step loop and fallbacks (its ``_run``). Peaks over the converged
  (sub)steps.

Peaks (``torsion_peaks``): peak_isolator_disp m (max_t |(u_x0, u_y0)|), peak_corner_disp m
(max over the four corners and time of |corner displacement|), peak_rotation rad
(max_t |theta_0|), peak_total_accel (N+1,) m/s^2 and peak_interstory_drift (N,) m of the plan
centres (resultants), their per-direction peaks (``_xy``: peak_isolator_disp_xy (2,),
peak_total_accel_xy (N+1, 2), peak_interstory_drift_xy (N, 2)), peak_rotation_levels (N+1,);
with walls max_impact_force_wall (4,) N (per wall, WALLS order, the peak over time of the SUM
of its points' forces), max_point_force (8,) N (per contact point, POINTS order),
max_impact_force (the largest of the four), max_indentation m (the deepest point),
n_impacts (times a wall came into contact, a wall in contact while any of its points is: the
count opensees_plan gives a wall when the slab does not twist) and n_point_impacts (times a
point came into contact). ``LAST_RUN`` holds diagnostics of the latest run.

Checks (tests/reference/test_opensees_torsion.py): the transient model's frequencies (its
initial tangent) are those of the spec's mass and stiffness matrices about the plan centres, to
1e-13, eccentric too; symmetric (four bearings at the corners, no eccentricity) it does not
twist and gives opensees_plan's peaks to 6e-14 (no wall) and 2e-14 (elastic walls, each
wall's force the sum of its two corners'); eccentric, against the walls, each corner's force
is k / 2 times its indentation from the spec's kinematics (1e-13). Cost: ~0.4 ms a step with
four bearings (the planar model ~0.12 ms), ~1.3 ms with the 16-bearing grid and walls.
"""
from __future__ import annotations

import time

import numpy as np
import openseespy.opensees as ops

from .opensees_plan import DEFAULT_DT, WALLS, _checked_pair, _checked_walls, _run
from .opensees_reference import building

MASTER, SLAB, GROUND = 1, 1000, 2000  # node tags: the master, slab bearing nodes, ground nodes

CORNERS = ((-1, -1), (1, -1), (1, 1), (-1, 1))
"""The slab's corners as the signs of (X, Y) (counterclockwise from (-b_x/2, -b_y/2)): the
order of the corner histories."""
POINTS = tuple((w, c) for w, (axis, sign) in enumerate(((0, 1), (0, -1), (1, 1), (1, -1)))
               for c in sorted((c for c in range(4) if CORNERS[c][axis] == sign),
                               key=lambda c: CORNERS[c][1 - axis]))
"""The contact points as (wall index in WALLS, corner index in CORNERS), in the spec's order:
the +x wall's two corners by ascending Y, the -x wall's, the +y wall's by ascending X, the
-y wall's."""

LAST_RUN: dict = {}

_MASS_NODE, _CORNER, _CORNER_GROUND = 100, 3000, 4000  # + level / + corner index
_BEARING_ELE, _BEARING_DASHPOT, _POINT_ELE = 10000, 20000, 5000  # + bearing / + point index
_FY_NEVER = 1e30  # N, the walls' "yield" force: never reached
_AXIAL_K = 1e15  # N/m, the bearings' axial material (the vertical DOF is fixed)
_ORIENT = (0.0, 0.0, 1.0, 1.0, 0.0, 0.0)  # bearings: local x = global Z, local y = global X


def slab_inertia(mass: float, plan_size) -> float:
    """kg m^2: the polar moment of a uniform rectangular slab about its centre."""
    b_x, b_y = plan_size
    return mass * (b_x**2 + b_y**2) / 12


def build(mass: float, plan_size, positions, k, eccentricity=(0.0, 0.0)) -> None:
    """The model in a fresh OpenSees domain: a rigid slab of `mass` (kg) and plan_size (m),
    its mass centre at `eccentricity` (m) from the origin, on bearings at `positions` (n, 2) m
    of stiffness k (N/m, one number or one per bearing) in both horizontal directions."""
    xy = np.asarray(positions, float)
    ks = np.broadcast_to(np.asarray(k, float), (xy.shape[0],))
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    e_x, e_y = (float(v) for v in eccentricity)
    ops.node(MASTER, e_x, e_y, 0.0)
    ops.fix(MASTER, 0, 0, 1, 1, 1, 0)
    ops.mass(MASTER, mass, mass, 0.0, 0.0, 0.0, slab_inertia(mass, plan_size))
    for i, ((x, y), k_i) in enumerate(zip(xy, ks, strict=True)):
        ops.node(SLAB + i, float(x), float(y), 0.0)
        ops.fix(SLAB + i, 0, 0, 1, 1, 1, 0)
        ops.node(GROUND + i, float(x), float(y), 0.0)
        ops.fix(GROUND + i, 1, 1, 1, 1, 1, 1)
        ops.uniaxialMaterial("Elastic", 10 + i, float(k_i))
        ops.element("zeroLength", 10 + i, GROUND + i, SLAB + i, "-mat", 10 + i, 10 + i,
                    "-dir", 1, 2)
    ops.rigidDiaphragm(3, MASTER, *[SLAB + i for i in range(xy.shape[0])])
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("FullGeneral")


def eigen_frequencies(mass: float, plan_size, positions, k, eccentricity=(0.0, 0.0)):
    """(3,) rad/s: the slab's circular frequencies (two translations, one twist, coupled by
    the eccentricity), ascending."""
    build(mass, plan_size, positions, k, eccentricity)
    values = np.asarray(ops.eigen("-fullGenLapack", 3), float)
    ops.wipe()
    return np.sqrt(np.sort(values))


def static_twist(mass: float, plan_size, positions, k, torque: float,
                 eccentricity=(0.0, 0.0)) -> np.ndarray:
    """(3,) the master's (u_x m, u_y m, theta rad) under a torque (N m) about z at the mass
    centre, by a linear static analysis."""
    build(mass, plan_size, positions, k, eccentricity)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(MASTER, 0.0, 0.0, 0.0, 0.0, 0.0, float(torque))
    ops.algorithm("Linear")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    ops.analyze(1)
    out = np.array([ops.nodeDisp(MASTER, 1), ops.nodeDisp(MASTER, 2), ops.nodeDisp(MASTER, 6)])
    ops.wipe()
    return out


def _per_level(value, n_levels: int, name: str) -> np.ndarray:
    """(n_levels, 2) eccentricities from one (2,) pair or one per level."""
    e = np.asarray(value, float)
    if e.shape == (2,):
        e = np.broadcast_to(e, (n_levels, 2))
    if e.shape != (n_levels, 2) or not np.all(np.isfinite(e)):
        raise ValueError(f"{name}: (2,) or ({n_levels}, 2) finite metres, got {e.shape}")
    return e


def build_transient(pair, pair_dt, *, plan_size, positions, eccentricity=(0.0, 0.0),
                    inertia=None, masses=None, story_k=None, story_k_theta=None,
                    isolator=None, zeta_iso=None, zeta_sup=0.02, walls=None) -> dict:
    """Build the building that twists (module docstring) in OpenSees' domain, ready for
    ``ops.analyze(1, dt)``.

    pair (T, 2) m/s^2 every pair_dt s; plan_size (b_x, b_y) m; positions (n, 2) m, the
    bearings from the plan centre; eccentricity (2,) or (N+1, 2) m, the levels' mass centres;
    inertia None (the uniform slab's m_j (b_x^2 + b_y^2) / 12) or J_j (N+1,) kg m^2 about the
    mass centres; story_k_theta None (the perimeter frame's k_j (b_x^2 + b_y^2) / 4) or
    k_theta_j N m/rad (scalar or (N,)); walls None or ((g_x, g_y) m, (k_x, k_y) N/m); the other
    building keywords those of ``opensees_reference.building``. Returns its resolved numbers
    with "level_nodes" (the masters of levels 0..N), "k_theta", "c_theta", "inertia",
    "eccentricity", "positions", "corners" (4, 2) m."""
    b_x, b_y = (float(v) for v in plan_size)
    if not (b_x > 0 and b_y > 0):
        raise ValueError(f"plan_size must be positive, got {plan_size}")
    xy = np.asarray(positions, float)
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 1 or not np.all(np.isfinite(xy)):
        raise ValueError(f"positions must be (n, 2) finite metres, got {xy.shape}")
    bld = building(masses, story_k, isolator, None, 0.02, zeta_iso, zeta_sup)
    iso = bld["isolator"]
    if iso["kind"] != "bilinear":
        raise ValueError("the torsional reference models the bilinear isolator only")
    n_lev, n_st, n_b = bld["masses"].size, bld["n_stories"], xy.shape[0]
    ecc = _per_level(eccentricity, n_lev, "eccentricity")
    polar = b_x**2 + b_y**2
    inert = (bld["masses"] * polar / 12 if inertia is None
             else np.broadcast_to(np.asarray(inertia, float), (n_lev,)).copy())
    k_theta = (bld["story_k"] * polar / 4 if story_k_theta is None
               else np.broadcast_to(np.asarray(story_k_theta, float), (n_st,)).copy())
    if np.any(inert <= 0) or np.any(k_theta <= 0):
        raise ValueError("inertia and story_k_theta must be positive")
    c_theta = bld["c_story"] * k_theta / bld["story_k"]
    corners = np.array(CORNERS, float) * [b_x / 2, b_y / 2]
    masters = tuple(MASTER + j for j in range(n_lev))
    bld.update(level_nodes=masters, k_theta=k_theta, c_theta=c_theta, inertia=inert,
               eccentricity=ecc, positions=xy, corners=corners, plan_size=(b_x, b_y))

    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)

    def slave(tag, x, y, master):
        ops.node(tag, float(x), float(y), 0.0)
        ops.fix(tag, 0, 0, 1, 1, 1, 0)
        slaves[master].append(tag)

    def ground(tag, x, y):
        ops.node(tag, float(x), float(y), 0.0)
        ops.fix(tag, 1, 1, 1, 1, 1, 1)

    slaves = {m: [] for m in masters}
    for j, master in enumerate(masters):
        ops.node(master, 0.0, 0.0, 0.0)
        ops.fix(master, 0, 0, 1, 1, 1, 0)
        slave(_MASS_NODE + j, *ecc[j], master)
        m = float(bld["masses"][j])
        ops.mass(_MASS_NODE + j, m, m, 0.0, 0.0, 0.0, float(inert[j]))
    # stories: springs and dashpots between consecutive masters
    for s in range(1, n_st + 1):
        i, j = masters[s - 1], masters[s]
        ops.uniaxialMaterial("Elastic", 1000 + s, float(bld["story_k"][s - 1]))
        ops.uniaxialMaterial("Elastic", 1100 + s, float(k_theta[s - 1]))
        ops.element("zeroLength", 1000 + s, i, j, "-mat", 1000 + s, 1000 + s, 1100 + s,
                    "-dir", 1, 2, 6)
        ops.uniaxialMaterial("Viscous", 2000 + s, float(bld["c_story"][s - 1]), 1.0)
        ops.uniaxialMaterial("Viscous", 2100 + s, float(c_theta[s - 1]), 1.0)
        ops.element("zeroLength", 2000 + s, i, j, "-mat", 2000 + s, 2000 + s, 2100 + s,
                    "-dir", 1, 2, 6)
    # bearings: the isolator's law over n, at their positions
    k1, k2 = float(iso["K1"]), float(iso["K2"])
    qd = float(iso["Fy"]) * (1.0 - k2 / k1)
    ops.uniaxialMaterial("Elastic", 30, _AXIAL_K)
    ops.uniaxialMaterial("Elastic", 32, 0.0)
    c_b = float(bld["c_iso"]) / n_b
    if c_b > 0.0:
        ops.uniaxialMaterial("Viscous", 6, c_b, 1.0)
    for b, (x, y) in enumerate(xy):
        slave(SLAB + b, x, y, masters[0])
        ground(GROUND + b, x, y)
        ops.element("elastomericBearingPlasticity", _BEARING_ELE + b, GROUND + b, SLAB + b,
                    k1 / n_b, qd / n_b, k2 / k1, 0.0, 2.0, "-P", 30, "-T", 32, "-My", 32,
                    "-Mz", 32, "-orient", *_ORIENT)
        if c_b > 0.0:
            ops.element("zeroLength", _BEARING_DASHPOT + b, GROUND + b, SLAB + b, "-mat", 6, 6,
                        "-dir", 1, 2)
    # walls: the corners' gap elements, half a wall's law each
    if walls is not None:
        gaps, stiff = walls
        for c, (x, y) in enumerate(corners):
            slave(_CORNER + c, x, y, masters[0])
            ground(_CORNER_GROUND + c, x, y)
        for p, (w, c) in enumerate(POINTS):
            axis, sign = w // 2, (1, -1)[w % 2]
            ops.uniaxialMaterial("ElasticPPGap", 40 + p, float(stiff[axis]) / 2,
                                 sign * _FY_NEVER, sign * float(gaps[axis]), 0.0, "noDamage")
            ops.element("zeroLength", _POINT_ELE + p, _CORNER_GROUND + c, _CORNER + c,
                        "-mat", 40 + p, "-dir", axis + 1)
    for master in masters:
        ops.rigidDiaphragm(3, master, *slaves[master])
    for d in range(2):
        ops.timeSeries("Path", d + 1, "-dt", float(pair_dt), "-values", *pair[:, d].tolist(),
                       "-factor", 1.0, "-useLast")
        ops.pattern("UniformExcitation", d + 1, d + 1, "-accel", d + 1)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("FullGeneral")  # 3 (N + 1) equations: the masters' DOFs
    ops.test("NormDispIncr", 1e-10, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    return bld


def torsion_peaks(pair, pair_dt, *, plan_size, positions, eccentricity=(0.0, 0.0),
                  inertia=None, masses=None, story_k=None, story_k_theta=None, isolator=None,
                  zeta_iso=None, zeta_sup=0.02, gap=None, k=None, gap_y=None, k_y=None,
                  dt=DEFAULT_DT, history=False) -> dict:
    """Run the building that twists (module docstring) under the pair (T, 2) m/s^2 (x, y
    components every pair_dt s) over the whole pair ((T - 1) pair_dt s).

    plan_size (b_x, b_y) m; positions (n, 2) m, the bearings from the plan centre;
    eccentricity (e_x, e_y) m for every level (or (N+1, 2)); inertia, story_k_theta: see
    ``build_transient``; masses, story_k, isolator (bilinear only), zeta_iso, zeta_sup: the
    building, see ``opensees_reference.building`` (defaults: the paper's). gap (m) and k (N/m):
    None for no wall, else the moat's x walls at clear gap g_x = gap from the slab's edges,
    stiffness k shared by their two corners (k / 2 each); gap_y, k_y those of the y walls
    (default the x walls'). dt: the analysis step (s). Returns the peaks of the module
    docstring; with history=True also "history": {"t" (T,) s, "centre" (T, 2) m (level 0's
    plan centre), "theta" (T,) rad (level 0), "corners" (T, 4, 2) m (CORNERS order)}.
    """
    pair = _checked_pair(pair)
    walls = _checked_walls(gap, k, gap_y, k_y)
    duration = (pair.shape[0] - 1) * float(pair_dt)
    t0 = time.perf_counter()
    bld = build_transient(pair, pair_dt, plan_size=plan_size, positions=positions,
                          eccentricity=eccentricity, inertia=inertia, masses=masses,
                          story_k=story_k, story_k_theta=story_k_theta, isolator=isolator,
                          zeta_iso=zeta_iso, zeta_sup=zeta_sup, walls=walls)
    masters = bld["level_nodes"]
    # the gap elements and their force on the corner (the j end) along the wall's normal
    points = ([(_POINT_ELE + p, 6 + w // 2) for p, (w, _) in enumerate(POINTS)]
              if walls is not None else [])
    rec = {"t": [], "u": [], "a": [], "f": []}

    def record():
        rec["t"].append(ops.getTime())
        rec["u"].append([ops.nodeDisp(n) for n in masters])
        rec["a"].append([ops.nodeAccel(n) for n in masters])
        if points:
            rec["f"].append([abs(ops.eleForce(e)[a]) for e, a in points])

    try:
        record()  # t = 0, at rest
        stats = _run(float(dt), duration, record)
    finally:
        ops.wipe()
    out = _peaks(rec, pair, float(pair_dt), walls, bld["corners"], history)
    LAST_RUN.clear()
    LAST_RUN.update(stats, wall_time_s=time.perf_counter() - t0, recorded_points=len(rec["t"]),
                    end_time=float(rec["t"][-1]), duration=duration, dt=float(dt),
                    walls=walls, n_bearings=int(bld["positions"].shape[0]),
                    k_theta=bld["k_theta"], c_theta=bld["c_theta"], c_iso=bld["c_iso"])
    return out


def _peaks(rec: dict, pair: np.ndarray, pair_dt: float, walls, corners: np.ndarray,
           history: bool) -> dict:
    """The peaks from the recorded histories: times (T,), the masters' displacements and
    relative accelerations (T, L, 6), the points' forces (T, 8)."""
    times = np.asarray(rec["t"])
    u_all = np.asarray(rec["u"])
    u, theta = u_all[..., :2], u_all[..., 5]  # (T, L, 2), (T, L)
    t_rec = np.arange(pair.shape[0]) * pair_dt
    ground = np.column_stack([np.interp(times, t_rec, pair[:, d]) for d in range(2)])
    accel = np.asarray(rec["a"])[..., :2] + ground[:, None, :]
    drift = np.diff(u, axis=1)
    u0, th0 = u[:, 0], theta[:, 0]
    # the corners' displacements: (u_x - theta Y, u_y + theta X)
    corner_u = u0[:, None, :] + th0[:, None, None] * np.stack([-corners[:, 1], corners[:, 0]],
                                                               axis=-1)[None]
    out = {
        "peak_isolator_disp": float(np.linalg.norm(u0, axis=-1).max()),
        "peak_corner_disp": float(np.linalg.norm(corner_u, axis=-1).max()),
        "peak_rotation": float(np.abs(th0).max()),
        "peak_rotation_levels": np.abs(theta).max(axis=0),
        "peak_total_accel": np.linalg.norm(accel, axis=-1).max(axis=0),
        "peak_interstory_drift": np.linalg.norm(drift, axis=-1).max(axis=0),
        "peak_total_accel_xy": np.abs(accel).max(axis=0),
        "peak_interstory_drift_xy": np.abs(drift).max(axis=0),
        "peak_isolator_disp_xy": np.abs(u0).max(axis=0),
        "max_indentation": 0.0, "max_impact_force": 0.0, "n_impacts": 0, "n_point_impacts": 0,
        "max_impact_force_wall": np.zeros(len(WALLS)),
        "max_point_force": np.zeros(len(POINTS)),
    }
    if walls is not None:
        gaps = np.asarray(walls[0])
        w_of = np.array([w for w, _ in POINTS])
        c_of = np.array([c for _, c in POINTS])
        signs = np.array([1.0, -1.0, 1.0, -1.0])[w_of]
        # indentation of each point: its corner's displacement along its wall's normal
        delta = signs * corner_u[:, c_of, w_of // 2] - gaps[w_of // 2]  # (T, 8)
        force = np.asarray(rec["f"])  # (T, 8)
        wall_force = np.stack([force[:, w_of == w].sum(axis=1) for w in range(4)], axis=1)
        point_in = delta > 0
        wall_in = np.stack([point_in[:, w_of == w].any(axis=1) for w in range(4)], axis=1)

        def onsets(inside):
            return int(np.count_nonzero(inside[1:] & ~inside[:-1])
                       + np.count_nonzero(inside[0]))

        out.update(max_indentation=float(max(delta.max(), 0.0)),
                   max_impact_force=float(wall_force.max()),
                   n_impacts=onsets(wall_in), n_point_impacts=onsets(point_in),
                   max_impact_force_wall=wall_force.max(axis=0),
                   max_point_force=force.max(axis=0))
    if history:
        out["history"] = {"t": times, "centre": u0, "theta": th0, "corners": corner_u}
    return out
