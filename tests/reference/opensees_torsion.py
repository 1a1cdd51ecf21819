"""Independent OpenSeesPy 3-D model of an isolated slab that can twist: a rigid diaphragm on
bearings at their positions, its mass centre off the centre of the bearings (the reference the
torsional model is to be checked against; a test helper, no code from engine/).

The model (``build``): ``model basic -ndm 3 -ndf 6``. A master node at the mass centre
(e_x, e_y, 0) carries the slab's mass m along x and y and its polar moment J about z (a
uniform slab of plan b_x x b_y: J = m (b_x^2 + b_y^2) / 12 about its own centre, the mass
centre here); its vertical translation and its rotations about x and y are fixed. One node per
bearing at (x_i, y_i, 0), tied to the master by ``rigidDiaphragm 3`` (their x, y and rotation
about z follow the slab's), its other DOFs fixed; a fixed ground node at the same place; a
``zeroLength`` bearing between them, ``Elastic`` k_i along x and along y. Constraints
``Transformation``. Units SI.
"""
from __future__ import annotations

import numpy as np

MASTER, SLAB, GROUND = 1, 1000, 2000  # node tags: the master, slab bearing nodes, ground nodes


def slab_inertia(mass: float, plan_size) -> float:
    """kg m^2: the polar moment of a uniform rectangular slab about its centre."""
    b_x, b_y = plan_size
    return mass * (b_x**2 + b_y**2) / 12


def build(mass: float, plan_size, positions, k, eccentricity=(0.0, 0.0)) -> None:
    """The model in a fresh OpenSees domain: a rigid slab of `mass` (kg) and plan_size (m),
    its mass centre at `eccentricity` (m) from the origin, on bearings at `positions` (n, 2) m
    of stiffness k (N/m, one number or one per bearing) in both horizontal directions."""
    import openseespy.opensees as ops

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
    import openseespy.opensees as ops

    build(mass, plan_size, positions, k, eccentricity)
    values = np.asarray(ops.eigen("-fullGenLapack", 3), float)
    ops.wipe()
    return np.sqrt(np.sort(values))


def static_twist(mass: float, plan_size, positions, k, torque: float,
                 eccentricity=(0.0, 0.0)) -> np.ndarray:
    """(3,) the master's (u_x m, u_y m, theta rad) under a torque (N m) about z at the mass
    centre, by a linear static analysis."""
    import openseespy.opensees as ops

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
