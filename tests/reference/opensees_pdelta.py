"""Independent OpenSeesPy model of the base-isolated shear building with P-Delta from a leaning
column, and collapse: a cross-check of the engine's ``p_delta`` / ``collapse_drift_ratio``.

A test helper, not part of the package. It rebuilds the building of ``opensees_reference``
(the same isolator, story springs, dashpots and damping rule, resolved by
``opensees_reference.building``; no code from ``engine/``) in a 2-D OpenSees model, and adds
the gravity loads through a leaning column. This makes the second-order effect come from
OpenSees' own geometric transformation, not from a negative spring. Units SI (kg, m, s, N).

The P-Delta statement checked (the engine's)
--------------------------------------------
Story i (joining level i-1 to level i, height h_i) gets the force term -(P_i / h_i) drift_i
added to its restoring force, P_i = g (m_i + ... + m_N) the constant gravity load it carries
(small-displacement geometric stiffness). Level 0 (the isolation slab) stands on the isolators
with the weight of the whole building, but the isolation level gets no P-Delta term: the
isolator's law is unchanged.

The model (``build_model``)
---------------------------
* ``model basic -ndm 2 -ndf 3``. Ground node 100 and level nodes 1..N+1 (levels 0..N), all at
  (0, 0): their vertical and rotational DOFs are fixed, the horizontal DOF is free and carries
  the level's mass (``mass m_j 0 0``). Every spring, dashpot, isolator and wall element is a
  ``zeroLength`` in direction 1 (horizontal), with the materials of ``opensees_reference``
  (``Steel01`` Fy = F_i, E0 = k_i, b = story_b, or ``Elastic`` k_i, or with
  ``story_material="imk"`` the deteriorating ``IMKBilin``, ``imk_material_args``; ``Viscous``
  dashpots c_i = 2 zeta_sup k_i / omega_1 with omega_1 the fixed-base superstructure's first
  circular frequency from the elastic k_i; the bilinear isolator ``Parallel(Elastic K2,
  ElasticPP K1 - K2)`` or the friction pendulum ``flatSliderBearing`` + W/R spring; the
  isolation dashpot; the optional moat-wall gap elements).
* Leaning column: nodes 300..300+N at (0, Y_j), Y_0 = 0 (the isolation level) and
  Y_j = h_1 + ... + h_j. Node 300+j is tied horizontally to level j's node
  (``equalDOF level_j 300+j 1``; constraints ``Transformation``). The base node 300 is fixed
  vertically (the isolators carry the weight down to the ground), and every leaning-column
  node has its rotation fixed; the other leaning nodes are free vertically.
* Column segment j (node 300+j-1 to 300+j, j = 1..N): ``elasticBeamColumn`` with EA =
  ``LEAN_EA`` (axially rigid: shortening under the full weight ~1e-7 m) and I = 0 (no
  flexural stiffness: it carries no lateral load by bending, only the P-Delta couple), on a
  ``PDelta`` (default) or ``Corotational`` geomTransf.
* Gravity: loads W_j = m_j g downwards at leaning nodes 300+j (j = 0..N; W_0 goes straight
  into the base node's vertical support), a static ``LoadControl`` analysis in 10 steps,
  held with ``loadConst -time 0.0``. The column's axial force in segment j is then exactly
  -P_i (the column is statically determinate vertically) and stays so: it has no vertical
  mass and the vertical loads are constant.
* Why this is the engine's statement: with the ``PDelta`` transformation, the segment's
  global resisting force gains N (u_top - u_bot) / L at its two ends, equal and opposite
  (PDeltaCrdTransf2d), N = -P_i the axial force: a horizontal force -(P_i / h_i) drift_i on
  level i and +(P_i / h_i) drift_i on level i-1, i.e. exactly the term added to story i's
  restoring force, and its tangent -P_i / h_i. Level 0's leaning node is the bottom of
  segment 1 and is supported vertically, so the isolation level has no P-Delta term of its
  own. ``Corotational`` is the exact large-displacement version: horizontal force
  P_i tan(theta_i) = P_i drift_i / sqrt(h_i^2 - drift_i^2) (N cos(theta) = P_i), a relative
  excess of drift_i^2 / (2 h_i^2): 0.02 % at 2 % drift, 0.5 % at 10 %.
* Ground motion, analysis, substeps and fallbacks exactly as ``opensees_reference``:
  ``Path`` series ``-useLast``, ``UniformExcitation`` direction 1, ``Newmark`` 1/2, 1/4,
  ``Newton`` with ``NormDispIncr`` 1e-10, retried with ModifiedNewton -initial, then
  KrylovNewton, then halved (down to dt / 2**8).
* Collapse: after every converged (sub)step, if some story's |drift_i| / h_i exceeds
  ``collapse_drift_ratio`` the run stops, collapsed, at that step's time. A step that fails
  to converge even at dt / 2**8 also ends the run as collapsed (at the last converged time).
  The peaks are those of the recorded steps up to the end of the run.

Deteriorating stories (``story_material="imk"``)
-------------------------------------------------
Each story spring is OpenSees' ``IMKBilin`` (modified Ibarra-Medina-Krawinkler, bilinear
hysteresis; the Nov. 2022 "AE_KI" code openseespy 3.7.1.2 runs) with symmetric properties,
its elastic stiffness the story's k_i. Its parameters are given as the engine's ``imk`` story
law names them (``IMK_DEFAULTS``; the mapping is that law's docstring, restated here without
its code): deformations are story drifts in m (theta_p, theta_pc, theta_u the same both ways),
F_y the effective yield force (N, IMKBilin's "Mpe"), capping_ratio F_c / F_y ("MmaxMpe"),
residual_ratio F_r / F_y ("ResM"), and the deterioration capacities dimensionless: OpenSees'
Lamda = lambda theta_p (its reference energy Lamda F_y = lambda F_y theta_p), one
deterioration factor D for both directions. ``imk_energy`` replays a drift history through
the material alone (committed step by step), to tell how much of the energy capacity a run
used: where the dissipated energy exceeds E_t = lambda F_y theta_p the engine's law fails
the story and IMKBilin does not (the one place they differ on purpose), so a cross-check
must stay short of it.

``LAST_RUN`` holds diagnostics of the latest call.
"""
from __future__ import annotations

import math
import time

import numpy as np
import openseespy.opensees as ops
import scipy.linalg

from tests.reference import opensees_reference as osr

G = osr.G
LEAN_EA = 1e14  # N: axially rigid leaning column (EA / h ~ 3e13 N/m >> k, 4 M / dt^2)
TRANSFORMATIONS = ("PDelta", "Corotational")
LAST_RUN: dict = {}

# node and element tags, limits: those of opensees_reference
_GROUND, _GAP_ELES, _FY_NEVER = osr._GROUND, osr._GAP_ELES, osr._FY_NEVER
_MAX_HALVINGS, _AXIAL_K = osr._MAX_HALVINGS, osr._AXIAL_K
_LEAN0 = 300  # leaning-column node j is 300 + j, its segment j element 300 + j


def gravity_loads(masses, g=G) -> np.ndarray:
    """P_1..P_N (N): the gravity load story i carries, g (m_i + ... + m_N)."""
    m = np.asarray(masses, dtype=float).ravel()
    return g * np.cumsum(m[1:][::-1])[::-1]


STORY_MATERIALS = ("steel01", "imk")
IMK_DEFAULTS = {"capping_ratio": 1.11, "ultimate_deformation": math.inf, "residual_ratio": 0.4,
                "lambda_s": 50.0, "lambda_c": 50.0, "lambda_k": 50.0, "c_s": 1.0, "c_c": 1.0,
                "c_k": 1.0, "deterioration_factor": 1.0}
"""The IMK parameters' defaults (those of the engine's ``imk`` story law, restated);
yield_force, plastic_deformation and post_capping_deformation have none."""
IMK_REQUIRED = ("yield_force", "plastic_deformation", "post_capping_deformation")


def imk_parameters(n, imk) -> dict:
    """The IMK story parameters (dict, the engine's names, each a scalar or one per story)
    resolved to (n,) arrays with the defaults filled in; ValueError for a missing or unknown
    name."""
    imk = dict(imk or {})
    unknown = set(imk) - set(IMK_DEFAULTS) - set(IMK_REQUIRED)
    missing = [name for name in IMK_REQUIRED if name not in imk]
    if unknown or missing:
        raise ValueError(f"imk: unknown {sorted(unknown)}, missing {missing}")
    return {name: np.broadcast_to(np.asarray(imk.get(name, IMK_DEFAULTS.get(name)), float),
                                  (n,)).copy() for name in IMK_REQUIRED + tuple(IMK_DEFAULTS)}


def imk_material_args(k_story, p, s) -> list:
    """IMKBilin's arguments after the tag for story s (0-based) of elastic stiffness k_story
    (N/m) and resolved parameters p (``imk_parameters``): Ke, then theta_p, theta_pc, theta_u,
    Mpe, MmaxMpe, ResM for the positive and (the same) negative direction, then
    Lamda_S, Lamda_C, Lamda_K = lambda theta_p, c_S, c_C, c_K, D_pos, D_neg."""
    theta_p = float(p["plastic_deformation"][s])
    side = [theta_p, float(p["post_capping_deformation"][s]),
            float(p["ultimate_deformation"][s]), float(p["yield_force"][s]),
            float(p["capping_ratio"][s]), float(p["residual_ratio"][s])]
    lamda = [float(p[name][s]) * theta_p for name in ("lambda_s", "lambda_c", "lambda_k")]
    d = float(p["deterioration_factor"][s])
    return [float(k_story), *side, *side, *lamda, float(p["c_s"][s]), float(p["c_c"][s]),
            float(p["c_k"][s]), d, d]


def imk_energy(drift, k_story, imk, story=0) -> dict:
    """Replay a drift history (m, from rest) through one story's IMKBilin alone, one
    committed state per value: "force" (N) at every value, "energy" the hysteretic energy
    dissipated (J, trapezoidal: IMKBilin's own rule), "capacity" the smallest reference
    energy min(lambda) F_y theta_p (J) and "used" energy / capacity."""
    drift = np.asarray(drift, float).ravel()
    p = imk_parameters(max(np.size(v) for v in imk.values()), imk)
    ops.wipe()
    try:
        ops.uniaxialMaterial("IMKBilin", 1, *imk_material_args(k_story, p, story))
        ops.testUniaxialMaterial(1)
        force = np.empty(drift.size)
        for i, d in enumerate(drift):
            ops.setStrain(float(d))
            force[i] = ops.getStress()
    finally:
        ops.wipe()
    d0 = np.r_[0.0, drift]
    f0 = np.r_[0.0, force]
    energy = float(np.sum(0.5 * (f0[1:] + f0[:-1]) * np.diff(d0)))
    lam = min(float(p[name][story]) for name in ("lambda_s", "lambda_c", "lambda_k"))
    capacity = lam * float(p["yield_force"][story]) * float(p["plastic_deformation"][story])
    return {"force": force, "energy": energy, "capacity": capacity,
            "used": energy / capacity}


def building(masses=None, story_k=None, isolator=None, story_yield=None,
             story_b=osr._STORY_B, story_height=3.5, p_delta=True, zeta_iso=None,
             zeta_sup=osr._ZETA_S, omega1_pdelta=False, story_material="steel01",
             imk=None) -> dict:
    """``opensees_reference.building`` plus the P-Delta numbers: "story_height" h_i (m),
    "level_heights" Y_0..Y_N (m), "gravity_load" P_i (N), "geometric_k" P_i / h_i (N/m; 0
    without p_delta). omega1_pdelta: compute the story dashpots' omega_1 from k_i - P_i / h_i
    instead of k_i (default False: the existing reference's rule, from the elastic k_i).
    story_material: "steel01" (story_yield, story_b: Steel01, or Elastic) or "imk" (IMKBilin
    stories of the parameters ``imk``, a dict of the engine's imk law names, scalars or one
    per story; story_yield must then be None: F_y is imk["yield_force"]); adds
    "story_material" and, for "imk", "imk" (the resolved (N,) arrays)."""
    if story_material not in STORY_MATERIALS:
        raise ValueError(f"story_material must be one of {STORY_MATERIALS}")
    if story_material == "imk":
        if story_yield is not None:
            raise ValueError("IMK stories take their yield force from imk['yield_force']")
        n_st = np.asarray(osr._MASSES if masses is None else masses).size - 1
        params = imk_parameters(n_st, imk)
        story_yield = params["yield_force"]  # for the yield drifts (ductilities)
    elif imk is not None:
        raise ValueError("imk parameters need story_material='imk'")
    bld = osr.building(masses, story_k, isolator, story_yield, story_b, zeta_iso, zeta_sup)
    bld["story_material"] = story_material
    if story_material == "imk":
        bld["imk"] = params
    n = bld["n_stories"]
    h = np.broadcast_to(np.asarray(story_height, dtype=float), (n,)).copy()
    if np.any(h <= 0):
        raise ValueError("story heights must be positive")
    p = gravity_loads(bld["masses"])
    kg = p / h if p_delta else np.zeros(n)
    if np.any(bld["story_k"] - kg <= 0):
        raise ValueError("some story's elastic stiffness k_i - P_i / h_i is not positive")
    if omega1_pdelta:
        bld["omega1"] = osr.fixed_base_omega1(bld["masses"], bld["story_k"] - kg)
        bld["c_story"] = 2.0 * bld["zeta_sup"] * bld["story_k"] / bld["omega1"]
    bld.update(story_height=h, level_heights=np.r_[0.0, np.cumsum(h)], gravity_load=p,
               geometric_k=kg, p_delta=bool(p_delta))
    return bld


def build_model(bld: dict, *, transformation="PDelta", contact=None, gap=None, k=None,
                beta=None, cor=None, m_eff=320e3, n=1.5) -> None:
    """Build the structure of ``bld`` (from ``building``) in OpenSees' domain and apply the
    gravity loads (static, held constant, time reset to 0). Adds "level_nodes" and
    "lean_nodes" to ``bld``. No ground motion, no analysis left defined."""
    if transformation not in TRANSFORMATIONS:
        raise ValueError(f"transformation must be one of {TRANSFORMATIONS}")
    iso = bld["isolator"]
    n_st = bld["n_stories"]
    nodes = tuple(range(1, n_st + 2))
    lean = tuple(_LEAN0 + j for j in range(n_st + 1))
    bld["level_nodes"], bld["lean_nodes"] = nodes, lean

    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(_GROUND, 0.0, 0.0)
    ops.fix(_GROUND, 1, 1, 1)
    for node, m in zip(nodes, bld["masses"], strict=True):
        ops.node(node, 0.0, 0.0)
        ops.fix(node, 0, 1, 1)  # only the horizontal DOF is free
        ops.mass(node, float(m), 0.0, 0.0)

    # isolator + isolation dashpot (as opensees_reference.build_model)
    if iso["kind"] == "friction_pendulum":
        w = float(iso["weight"])
        ops.frictionModel("VelDependent", 1, float(iso["mu_slow"]), float(iso["mu_fast"]),
                          float(iso["rate"]))
        ops.uniaxialMaterial("Elastic", 30, _AXIAL_K)
        ops.uniaxialMaterial("InitStressMaterial", 31, 30, -w)
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
    for s in range(1, n_st + 1):
        k_s, f_y = float(bld["story_k"][s - 1]), float(bld["story_yield"][s - 1])
        if bld.get("story_material") == "imk":
            ops.uniaxialMaterial("IMKBilin", 1000 + s, *imk_material_args(k_s, bld["imk"],
                                                                        s - 1))
        elif math.isfinite(f_y):
            ops.uniaxialMaterial("Steel01", 1000 + s, f_y, k_s, float(bld["story_b"][s - 1]))
        else:
            ops.uniaxialMaterial("Elastic", 1000 + s, k_s)
        ops.uniaxialMaterial("Viscous", 2000 + s, float(bld["c_story"][s - 1]), 1.0)
        i, j = nodes[s - 1], nodes[s]
        ops.element("zeroLength", 1000 + s, i, j, "-mat", 1000 + s, "-dir", 1)
        ops.element("zeroLength", 2000 + s, i, j, "-mat", 2000 + s, "-dir", 1)
    # moat wall (as opensees_reference.build_model)
    if contact == "elastic":
        ops.uniaxialMaterial("ElasticPPGap", 7, float(k), _FY_NEVER, float(gap), 0.0, "noDamage")
        ops.uniaxialMaterial("ElasticPPGap", 8, float(k), -_FY_NEVER, -float(gap), 0.0,
                             "noDamage")
        ops.element("zeroLength", _GAP_ELES[0], _GROUND, nodes[0], "-mat", 7, "-dir", 1)
        ops.element("zeroLength", _GAP_ELES[1], _GROUND, nodes[0], "-mat", 8, "-dir", 1)
    elif contact in ("jankowski", "hertzdamp"):
        if contact == "jankowski":
            ops.uniaxialMaterial("JankowskiImpact", 7, float(beta), osr.jankowski_xi(float(cor)),
                                 float(m_eff), -float(gap), 1.5)
        else:
            ops.uniaxialMaterial("Hertzdamp", 7, float(k), 0.75 * (1.0 - float(cor) ** 2),
                                 -float(gap), float(n))
        ops.element("zeroLength", _GAP_ELES[1], _GROUND, nodes[0], "-mat", 7, "-dir", 1)
        ops.element("zeroLength", _GAP_ELES[0], nodes[0], _GROUND, "-mat", 7, "-dir", 1)
    elif contact is not None:
        raise ValueError(f"unknown contact {contact!r}")

    # leaning column: gravity only, its P-Delta from the geometric transformation
    if not bld["p_delta"]:
        return
    ops.geomTransf(transformation, 1)
    for j, y in enumerate(bld["level_heights"]):
        ops.node(lean[j], 0.0, float(y))
        ops.fix(lean[j], 0, 1 if j == 0 else 0, 1)
        ops.equalDOF(nodes[j], lean[j], 1)
    for j in range(1, n_st + 1):
        ops.element("elasticBeamColumn", _LEAN0 + j, lean[j - 1], lean[j], LEAN_EA, 1.0, 0.0,
                    1)
    ops.timeSeries("Linear", 2)
    ops.pattern("Plain", 2, 2)
    for j, m in enumerate(bld["masses"]):
        ops.load(lean[j], 0.0, -float(m) * G, 0.0)
    ops.constraints("Transformation")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 20)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    if ops.analyze(10) != 0:
        raise RuntimeError("gravity analysis failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def _transient(tol=1e-10):
    ops.constraints("Transformation")
    ops.numberer("Plain")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", tol, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def opensees_pdelta_peaks(ag, ag_dt, *, masses=None, story_k=None, story_yield=None,
                          story_b=osr._STORY_B, story_height=3.5, isolator=None, p_delta=True,
                          collapse_drift_ratio=None, scale=1.0, dt=5e-4,
                          transformation="PDelta", contact=None, gap=None, k=None, beta=None,
                          cor=None, m_eff=320e3, zeta_iso=None, zeta_sup=osr._ZETA_S,
                          omega1_pdelta=False, story_material="steel01", imk=None,
                          keep_history=False) -> dict:
    """Run the P-Delta model under ``scale * ag`` (m/s^2, step ag_dt s) for the whole record.

    masses, story_k, story_yield, story_b, isolator, zeta_iso, zeta_sup: as
    ``opensees_reference.building`` (defaults: the paper's building); story_height: h_i (m,
    scalar or per story); p_delta: add the leaning column (False: the plain shear building,
    the same as ``opensees_reference`` but in 2-D); collapse_drift_ratio: None or the story
    drift ratio |drift_i| / h_i beyond which the run stops as collapsed; dt: analysis step
    (default the engine's 5e-4 s); transformation: "PDelta" or "Corotational"; contact, gap,
    k, beta, cor, m_eff: the moat wall, as ``opensees_reference.opensees_peaks``;
    story_material, imk: the stories' material, as ``building`` ("imk": IMKBilin);
    keep_history: also return the recorded steps' "time" (T,) s, "drift" (T, N) m,
    "isolator_disp" (T,) m and "total_accel" (T, N + 1) m/s^2.

    Returns peak_total_accel (N+1,) m/s^2, peak_interstory_drift (N,) m, peak_isolator_disp
    m, peak_story_ductility (N,) (0 for elastic stories), peak_drift_ratio (N,),
    collapsed bool, collapse_time s (NaN if not collapsed), end_time s, and with a wall
    max_indentation m, max_impact_force N, n_impacts.
    """
    ag = float(scale) * np.asarray(ag, dtype=float).ravel()
    if ag.size < 2:
        raise ValueError("ag needs at least 2 samples")
    if contact is not None and (gap is None or gap < 0):
        raise ValueError("contact needs a gap >= 0")
    dt = float(dt)
    t_rec = np.arange(ag.size) * float(ag_dt)
    duration = float(t_rec[-1])
    t0 = time.perf_counter()
    bld = building(masses, story_k, isolator, story_yield, story_b, story_height, p_delta,
                   zeta_iso, zeta_sup, omega1_pdelta, story_material, imk)
    h = bld["story_height"]
    limit = math.inf if collapse_drift_ratio is None else float(collapse_drift_ratio)
    times, disp, accel, fgap = [], [], [], []
    stats = {"steps": 0, "fallback_algorithms": 0, "substeps": 0}
    state = {"collapsed": False, "collapse_time": math.nan, "diverged": False}

    class _Stop(Exception):
        pass

    try:
        build_model(bld, transformation=transformation, contact=contact, gap=gap, k=k,
                    beta=beta, cor=cor, m_eff=m_eff)
        nodes = bld["level_nodes"]
        ops.timeSeries("Path", 1, "-dt", float(ag_dt), "-values", *ag.tolist(), "-factor", 1.0,
                       "-useLast")
        ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
        _transient()

        def record():
            times.append(ops.getTime())
            u = [ops.nodeDisp(nd, 1) for nd in nodes]
            disp.append(u)
            accel.append([ops.nodeAccel(nd, 1) for nd in nodes])
            if contact is not None:
                fgap.append(max(abs(ops.eleForce(_GAP_ELES[0])[0]),
                                abs(ops.eleForce(_GAP_ELES[1])[0])))
            if np.any(np.abs(np.diff(u)) / h > limit):
                state["collapsed"], state["collapse_time"] = True, ops.getTime()
                raise _Stop

        def step(hh, depth=0):
            if ops.analyze(1, hh) == 0:
                stats["steps"] += 1
                record()
                return
            for alg in (("ModifiedNewton", "-initial"), ("KrylovNewton",)):
                ops.algorithm(*alg)
                ok = ops.analyze(1, hh)
                ops.algorithm("Newton")
                if ok == 0:
                    stats["steps"] += 1
                    stats["fallback_algorithms"] += 1
                    record()
                    return
            if depth >= _MAX_HALVINGS:
                state["collapsed"], state["diverged"] = True, True
                state["collapse_time"] = times[-1]
                raise _Stop
            stats["substeps"] += 1
            step(hh / 2.0, depth + 1)
            step(hh / 2.0, depth + 1)

        try:
            record()
            ratio = duration / dt
            n_full = int(round(ratio)) if abs(ratio - round(ratio)) < 1e-6 \
                else int(math.floor(ratio))
            for _ in range(n_full):
                step(dt)
            rem = duration - n_full * dt
            if rem > 1e-6 * dt:
                step(rem)
        except _Stop:
            pass
    finally:
        ops.wipe()

    times = np.asarray(times)
    disp = np.asarray(disp)
    acc = np.asarray(accel) + np.interp(times, t_rec, ag)[:, None]
    drift = np.abs(np.diff(disp, axis=1)).max(axis=0)
    u0 = disp[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        ductility = np.where(np.isfinite(bld["yield_drift"]), drift / bld["yield_drift"], 0.0)
    out = {
        "peak_total_accel": np.abs(acc).max(axis=0),
        "peak_interstory_drift": drift,
        "peak_isolator_disp": float(np.abs(u0).max()),
        "peak_story_ductility": ductility,
        "peak_drift_ratio": drift / h,
        "collapsed": state["collapsed"],
        "collapse_time": state["collapse_time"],
        "end_time": float(times[-1]),
    }
    if contact is not None:
        delta = np.maximum(np.abs(u0) - float(gap), 0.0)
        inside = delta > 0.0
        out["max_indentation"] = float(delta.max())
        out["max_impact_force"] = float(np.max(fgap))
        out["n_impacts"] = int(np.count_nonzero(inside[1:] & ~inside[:-1]) + int(inside[0]))
    if keep_history:
        out.update(time=times, drift=np.diff(disp, axis=1), isolator_disp=u0,
                   total_accel=acc)
    LAST_RUN.clear()
    LAST_RUN.update(stats, wall_time_s=time.perf_counter() - t0, recorded_points=len(times),
                    end_time=float(times[-1]), duration=duration, dt=dt,
                    transformation=transformation, diverged=state["diverged"],
                    n_stories=bld["n_stories"])
    return out


def eigen_periods(n_modes=3, *, transformation="PDelta", **building_kw) -> np.ndarray:
    """The first ``n_modes`` periods (s) of the model after gravity (tangent stiffness: the
    bilinear isolator at K1, the stories at k_i, the leaning column's -P_i / h_i).
    building_kw: those of ``building``."""
    bld = building(**building_kw)
    try:
        build_model(bld, transformation=transformation)
        _transient()  # eigen needs an analysis with the Transformation handler
        w2 = np.asarray(ops.eigen("-fullGenLapack", int(n_modes)))
    finally:
        ops.wipe()
    return 2.0 * math.pi / np.sqrt(w2)


def shear_building_periods(masses, story_k, k_base, n_modes=3) -> np.ndarray:
    """The first periods (s) of the plain shear building: levels 0..N, a spring k_base from
    level 0 to the ground, story stiffnesses story_k (N/m, e.g. k_i - P_i / h_i)."""
    m = np.asarray(masses, dtype=float)
    kk = np.asarray(story_k, dtype=float)
    n = m.size
    k = np.zeros((n, n))
    k[0, 0] = k_base
    for s, ks in enumerate(kk, start=1):
        k[s - 1, s - 1] += ks
        k[s, s] += ks
        k[s - 1, s] -= ks
        k[s, s - 1] -= ks
    w2 = scipy.linalg.eigh(k, np.diag(m), eigvals_only=True)
    return 2.0 * math.pi / np.sqrt(np.sort(w2)[:n_modes])


def _static_fallback() -> bool:
    """Retry a failed static step with the transient's fallback algorithms (a step that
    Newton converges, e.g. every Steel01 one, never gets here; IMKBilin's tangent is the
    secant of the step, with which Newton can stall on its residual plateau under P-Delta);
    True if one converged."""
    for alg in (("ModifiedNewton", "-initial"), ("KrylovNewton",)):
        ops.algorithm(*alg)
        ok = ops.analyze(1)
        ops.algorithm("Newton")
        if ok == 0:
            return True
    return False


def pushover(story, drifts_top, *, transformation="PDelta", **building_kw) -> dict:
    """Static pushover after gravity: a horizontal load V at the roof, the displacement of
    level ``story`` (1..N) driven through ``drifts_top`` (m, monotone from 0, relative to the
    ground) by ``DisplacementControl``. Returns "shear" V (N, the shear of every story: the
    only horizontal load is at the roof), "drift" (N stories' drifts, m, each row a step)
    and "spring_force" (each story spring's force, N). Story s's equilibrium gives
    V = spring_force_s - (P_s / h_s) drift_s."""
    bld = building(**building_kw)
    targets = np.asarray(drifts_top, dtype=float).ravel()
    n_st = bld["n_stories"]
    if not 1 <= story <= n_st:
        raise ValueError(f"story must be 1..{n_st}")
    try:
        build_model(bld, transformation=transformation)
        nodes = bld["level_nodes"]
        ops.timeSeries("Linear", 3)
        ops.pattern("Plain", 3, 3)
        ops.load(nodes[-1], 1.0, 0.0, 0.0)
        ops.constraints("Transformation")
        ops.numberer("Plain")
        ops.system("BandGeneral")
        ops.test("NormDispIncr", 1e-12, 50)
        ops.algorithm("Newton")
        shear, drift, spring = [], [], []
        previous = 0.0
        for i, target in enumerate(targets):
            ops.integrator("DisplacementControl", nodes[story], 1, float(target - previous))
            ops.analysis("Static")
            if ops.analyze(1) != 0 and not _static_fallback():
                raise RuntimeError(f"pushover: step {i} failed")
            previous = ops.nodeDisp(nodes[story], 1)
            u = np.array([ops.nodeDisp(nd, 1) for nd in nodes])
            shear.append(ops.getLoadFactor(3))
            drift.append(np.diff(u))
            spring.append([ops.eleForce(1000 + s)[3] for s in range(1, n_st + 1)])
    finally:
        ops.wipe()
    return {"shear": np.asarray(shear), "drift": np.asarray(drift),
            "spring_force": np.asarray(spring), "building": bld}


IDA_SCALES = 0.2 * 1.25 ** np.arange(4, 14)
"""The intensities of the IDA cross-checks: 0.49 .. 3.64, steps of x1.25 (the first collapse
near 0.76, two standing steps below it)."""


def first(flags) -> int:
    """Index of the first True (len if none)."""
    flags = np.asarray(flags, bool)
    return int(np.argmax(flags)) if flags.any() else flags.size


def last_standing(flags) -> int:
    """Index of the last False (-1 if none)."""
    flags = np.asarray(flags, bool)
    return int(np.flatnonzero(~flags)[-1]) if (~flags).any() else -1


RTOL = 5e-3
"""The cross-checks' tolerance on every peak: 0.5 %."""
PEAKS = ("peak_total_accel", "peak_interstory_drift", "peak_isolator_disp")
WALL_PEAKS = ("max_indentation", "max_impact_force")


def assert_free_and_wall_match(result, references) -> None:
    """An engine Result of two members, free (0) and pounding on the wall (1), against the
    OpenSees runs `references` ("none", "wall"): neither collapsed, every peak within RTOL,
    the impacts counted alike (and some)."""
    assert not np.any(result.collapsed)
    for member, case in enumerate(("none", "wall")):
        reference = references[case]
        for name in PEAKS + (WALL_PEAKS if case == "wall" else ()):
            np.testing.assert_allclose(getattr(result, name)[member], reference[name],
                                       rtol=RTOL, atol=1e-12, err_msg=f"{case}: {name}")
    assert references["wall"]["n_impacts"] > 0
    assert result.n_impacts[1] == references["wall"]["n_impacts"]
