"""What a building that twists takes beyond a run in plan, declared once: its plan, the
offset of its masses, its bearings where they stand, its stories' torsional stiffness,
and the moat's contact points (the slab's corners against a bare wall, the bumpers where they
are fixed); the per-member arrays the torsional loops read (loops/numpy_torsion.py,
loops/numba_torsion.py) and their stability limit.

The model (SI; small rotations). Every level j is a rigid diaphragm with three degrees of
freedom at the centre of its plan, (u_x, u_y, theta): the material point (X, Y) of the level
(m, from the plan's centre) moves by (u_x - theta Y, u_y + theta X). Its mass m_j sits at the
offset e_j = (e_x, e_y) (Torsion.mass_offset) with the polar moment J_j about its own centre
(a uniform slab unless given: m (b_x^2 + b_y^2) / 12), so its mass matrix about the plan's centre is
    [[m, 0, -m e_y], [0, m, m e_x], [-m e_y, m e_x, J + m (e_x^2 + e_y^2)]]
and the ground's (a_x, a_y) loads it by -M (a_x, a_y, 0): a torque where e != 0.
- The isolation layer is n bearings at their positions (X_b, Y_b), each the building's
  isolator law with its stiffnesses and strength divided by n (identical bearings; the law's
  coupled slip element at the bearing's own displacement and speed), so that the torsional
  stiffness and strength follow from the layout; the isolation dashpot is shared the same way
  (c_iso / n at each bearing along x and y).
- A story joins two levels at its centre of stiffness (x_s, y_s) (the plan's centre unless
  given): k along x, k_y along y and k_theta in torsion about that centre (N m/rad; default a
  perimeter frame's, k_y (b_x / 2)^2 + k (b_y / 2)^2: a frame on each face, the two faces
  along x carrying k), so that its drift there is (d_x - d_theta y_s, d_y + d_theta x_s,
  d_theta) and its moment about the plan's centre adds x_s f_y - y_s f_x; its dashpots are
  the building's (damping="paper") along x and y and c k_theta / k in torsion, stiffness-
  proportional like them, at the same centre. Linear stories only: the stories' laws in plan
  have no torsional counterpart yet.
- The rectangular moat's walls stand at +-(b_x / 2 + g_x) and +-(b_y / 2 + g_y), g the clear
  gaps from the slab's edges; the slab meets a wall at contact points along it: against a
  bare wall its two corners on that side, against bumpers the bumpers' positions (the same on
  opposite walls). A point at position s along the +x wall is the slab's edge point
  (b_x / 2, s); its indentation is g . u_0 - g_x with g = (1, 0, -s), and its force F pushes
  the slab by -F g (generalised force: the moment included). The wall's law (its Contact) is
  shared equally by its points: each carries Contact.part(1 / the number of points), the
  law's force times that share (tests/engine/test_torsion.py checks every law), so that a
  bumper wall of n_bumpers pads at n_bumpers positions gives each position one pad. A
  bumper-lined wall is reached through its bumpers only: past a pad's crushing the slab bears
  on the wall at that point, which meets the wall's own stiffness k_w, not a share of it
  (issue 38: shared, the wall behind a crushed pad was the softer the more pads it carried).
  So a slab that does not turn is the plan run until its pads crush; with all of a wall's n
  pads crushed at once it meets n k_w where the plan run meets k_w.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .chain import chain_matrix
from .errors import EngineError
from .torsion_fields import plan_dimensions

DEFAULT_GRID = (4, 4)
"""Bearings along x and along y of the default layout: a regular grid under the slab."""
CORNERS = ((1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0))
"""The slab's corners as signs of (b_x / 2, b_y / 2), counterclockwise from (+, +)."""


def shifted(building, fraction: float):
    """The building that twists with every level's mass centre moved by fraction (b_x, b_y)
    (ACCIDENTAL_ECCENTRICITY, Torsion.shifted), the building itself at 0."""
    if building.torsion is None:
        raise EngineError("an accidental eccentricity moves the mass of a building that twists: "
                          "give the building its torsion component (engine.Torsion)")
    moved = building.torsion.shifted(fraction)
    return building if moved is building.torsion else dataclasses.replace(building,
                                                                           torsion=moved)


def grid_positions(plan_size, per_side: tuple[int, int] = DEFAULT_GRID) -> np.ndarray:
    """(n, 2) m: a regular grid of bearings under a rectangular slab of plan_size (b_x, b_y),
    per_side bearings along x and y, the outer ones at the slab's edges, centred on it."""
    b_x, b_y = plan_dimensions(plan_size)
    n_x, n_y = (int(n) for n in per_side)
    if n_x < 2 or n_y < 2:
        raise EngineError(f"per_side: at least 2 bearings along each side, got {per_side}")
    x, y = np.meshgrid(np.linspace(-b_x / 2, b_x / 2, n_x), np.linspace(-b_y / 2, b_y / 2, n_y))
    return np.column_stack([x.ravel(), y.ravel()])


def corner_orbits(disp, rotation, corners) -> np.ndarray:
    """(..., 4, 2) m: the corners' displacements (u_x - theta Y, u_y + theta X) from the plan
    centre's displacement disp (..., 1, 2) m and the rotation (..., 1) rad, corners (..., 4,
    2) their positions (X, Y) m (CORNERS times half the plan)."""
    return disp + rotation[..., None] * np.stack([-corners[..., 1], corners[..., 0]], axis=-1)


def slab_inertia(masses, plan_size) -> np.ndarray:
    """kg m^2: the polar moment of uniform rectangular slabs of `masses` (kg) about their own
    centres, m (b_x^2 + b_y^2) / 12."""
    b_x, b_y = plan_dimensions(plan_size)
    return np.asarray(masses, float) * (b_x**2 + b_y**2) / 12


def torsional_stiffness(building) -> np.ndarray:
    """(N,) the stories' torsional stiffness (N m/rad): story_torsional_stiffness, or the
    perimeter frame's k_y (b_x / 2)^2 + k (b_y / 2)^2."""
    if building.torsion.story_torsional_stiffness is not None:
        return np.asarray(building.torsion.story_torsional_stiffness, float)
    b_x, b_y = building.torsion.plan_size
    k = np.asarray(building.story_stiffness, float)
    k_y = np.asarray(building.along_y().story_stiffness, float)
    return k_y * (b_x / 2) ** 2 + k * (b_y / 2) ** 2


def bearing_positions(building) -> np.ndarray:
    """(n, 2) m: isolator_positions, or the default grid under the slab."""
    if building.torsion.isolator_positions is None:
        return grid_positions(building.torsion.plan_size)
    return np.asarray(building.torsion.isolator_positions, float)


@dataclass(frozen=True)
class TorsionArrays:
    """Per-member arrays of a batch of B buildings that twist, L levels, n bearings each.

    mass, damping, stiffness (B, 3L, 3L): the matrices about the plans' centres, degrees of
    freedom level by level (x, y, theta) (kg and kg m^2; N s/m and N m s; N/m and N m, the
    isolators at their initial stiffness, for stability limits); load (B, 3L, 2): M times the
    ground's influence along x and along y (the step's load is -load @ (a_x, a_y)); story_k
    (B, L - 1, 3): the stories' k, k_y, k_theta; story_centre (B, L - 1, 2) m: their centres
    of stiffness; bearings (B, n, 2) m; plan (B, 2) m."""

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    load: np.ndarray
    story_k: np.ndarray
    story_centre: np.ndarray
    bearings: np.ndarray
    plan: np.ndarray


def torsion_arrays(members: Sequence, size: int) -> TorsionArrays:
    """Stack the buildings (one broadcast, or `size` of them) into TorsionArrays; every member
    must twist (plan_size given) and stand on as many bearings as the others."""
    members = list(members)
    if len(members) == 1:
        members = members * size
    rows = {b: _row(b) for b in dict.fromkeys(members)}
    names = [f.name for f in dataclasses.fields(TorsionArrays)]
    counts = {row[names.index("bearings")].shape[0] for row in rows.values()}
    if len(counts) > 1:
        raise EngineError(f"building: the members of one batch must stand on as many bearings, "
                          f"got {sorted(counts)}")
    return TorsionArrays(*(np.stack([rows[b][i] for b in members]) for i in range(len(names))))


def _row(b) -> tuple:
    """One building's TorsionArrays row, in its fields' order."""
    n_levels, twist = b.n_levels, b.torsion
    masses = np.asarray(b.masses, float)
    ecc = np.broadcast_to(np.asarray(twist.mass_offset, float), (n_levels, 2))
    inertia = slab_inertia(masses, twist.plan_size) if twist.mass_inertia is None \
        else np.asarray(twist.mass_inertia, float)
    mass = np.zeros((3 * n_levels, 3 * n_levels))
    for j in range(n_levels):
        e_x, e_y = ecc[j]
        mass[3 * j:3 * j + 3, 3 * j:3 * j + 3] = masses[j] * np.array(
            [[1.0, 0.0, -e_y], [0.0, 1.0, e_x], [-e_y, e_x, e_x**2 + e_y**2]])
        mass[3 * j + 2, 3 * j + 2] += inertia[j]
    xy = bearing_positions(b)
    # the bearings' generalised directions along x and along y: (1, 0, -Y), (0, 1, X)
    g_x = np.column_stack([np.ones(len(xy)), np.zeros(len(xy)), -xy[:, 1]])
    g_y = np.column_stack([np.zeros(len(xy)), np.ones(len(xy)), xy[:, 0]])
    layout = (g_x.T @ g_x + g_y.T @ g_y) / len(xy)  # per unit of the isolation's stiffness
    k_theta = torsional_stiffness(b)
    k_y = np.asarray(b.along_y().story_stiffness, float)
    story_k = np.column_stack([b.story_stiffness, k_y, k_theta])
    c_iso, c_story = b.dashpots()
    c_story_y = b.along_y().dashpots()[1]
    c_theta = c_story * k_theta / np.asarray(b.story_stiffness, float)
    centre = np.zeros((b.n_stories, 2)) if twist.story_stiffness_centre is None else \
        np.broadcast_to(np.asarray(twist.story_stiffness_centre, float), (b.n_stories, 2))
    damping = _story_chain(np.column_stack([c_story, c_story_y, c_theta]), centre)
    stiffness = _story_chain(story_k, centre)
    damping[:3, :3] += c_iso * layout
    stiffness[:3, :3] += b.isolator_stiffness * layout
    influence = np.zeros((3 * n_levels, 2))
    influence[0::3, 0] = influence[1::3, 1] = 1.0
    return (mass, damping, stiffness, mass @ influence, story_k, np.array(centre), xy,
            np.asarray(twist.plan_size, float))


def _story_chain(springs: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """(3L, 3L) the stories' springs (or dashpots) (N, 3) along x, y and in torsion at their
    centres (N, 2) m, about the plans' centres: T' diag(springs) T per story, T the drift at
    the centre from the plan centre's, [[1, 0, -y_s], [0, 1, x_s], [0, 0, 1]]; chained level
    to level (chain_matrix's rule, the first element, the isolation, left out)."""
    n = springs.shape[0] + 1
    out = np.zeros((3 * n, 3 * n))
    for d in range(3):  # centres at the plan's: each direction its own chain, exactly
        out[d::3, d::3] = chain_matrix(np.concatenate([[0.0], springs[:, d]]))
    for i, (x_s, y_s) in enumerate(centre):
        if x_s == 0 and y_s == 0:
            continue
        t = np.array([[1.0, 0.0, -y_s], [0.0, 1.0, x_s], [0.0, 0.0, 1.0]])
        block = t.T @ np.diag(springs[i]) @ t - np.diag(springs[i])
        lo, hi = slice(3 * i, 3 * i + 3), slice(3 * i + 3, 3 * i + 6)
        out[lo, lo] += block
        out[hi, hi] += block
        out[lo, hi] -= block
        out[hi, lo] -= block
    return out


@dataclass(frozen=True)
class ContactPoints:
    """Where the slab meets the moat, for a batch of B members and P points (in the order of
    the walls +x, -x, +y, -y, each wall's points by their position along it).

    wall (P,) int: the point's wall (results.WALLS["rectangular"] index); along (B, P) m: its
    position along the wall (Y for the x walls, X for the y walls); direction (B, P, 3): g, its
    generalised direction, the unit outward normal with the moment arm (the point's distance
    towards its wall is g . u_0); tangent (B, P, 3): the same along the wall (x walls: (0, 1,
    X), y walls: (1, 0, -Y)), for friction; share (P,): the part of its wall's law it
    carries."""

    wall: np.ndarray
    along: np.ndarray
    direction: np.ndarray
    tangent: np.ndarray
    share: np.ndarray

    @property
    def axis(self) -> np.ndarray:
        """(P,) 0 for a point of an x wall, 1 of a y wall."""
        return self.wall // 2


def contact_points(plan: np.ndarray, bumper_positions=None) -> ContactPoints:
    """The moat's contact points for plans (B, 2) m: the corners of each slab against bare
    walls (bumper_positions None), else bumper_positions = (along the x walls, along the y
    walls), positions (m) from the plan's centre (Y for the x walls, X for the y walls), the
    same on opposite walls and for every member, each within its slab's side."""
    size = plan.shape[0]
    if bumper_positions is None:
        along_x = np.column_stack([-plan[:, 1] / 2, plan[:, 1] / 2])
        along_y = np.column_stack([-plan[:, 0] / 2, plan[:, 0] / 2])
    else:
        try:
            along_x, along_y = (np.sort(np.asarray(p, float).ravel()) for p in bumper_positions)
        except (TypeError, ValueError):
            raise EngineError("bumper_positions must be (positions along the x walls, "
                              "positions along the y walls), metres") from None
        for name, pos, half in (("x", along_x, plan[:, 1] / 2), ("y", along_y, plan[:, 0] / 2)):
            if pos.size < 1 or not np.all(np.isfinite(pos)) \
                    or np.any(np.abs(pos)[None, :] > half[:, None] * (1 + 1e-12)):
                raise EngineError(f"bumper_positions along the {name} walls must be one or "
                                  f"more finite positions (m) within the slab's side "
                                  f"(+-{half.min():g} m), got {pos.tolist()}")
        along_x, along_y = (np.broadcast_to(p, (size, p.size)) for p in (along_x, along_y))
    half_x, half_y = plan[:, :1] / 2, plan[:, 1:] / 2
    walls, along, direction, tangent, share = [], [], [], [], []
    for wall, (axis, sign) in enumerate(((0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0))):
        s = along_x if axis == 0 else along_y
        n = s.shape[1]
        zero, one = np.zeros_like(s), np.ones_like(s)
        if axis == 0:  # the point (sign b_x / 2, s): g = sign (1, 0, -s); tangent (0, 1, X)
            g = sign * np.stack([one, zero, -s], axis=-1)
            t = np.stack([zero, one, sign * half_x * one], axis=-1)
        else:  # the point (s, sign b_y / 2): g = sign (0, 1, s); tangent (1, 0, -Y)
            g = sign * np.stack([zero, one, s], axis=-1)
            t = np.stack([one, zero, -sign * half_y * one], axis=-1)
        walls.append(np.full(n, wall))
        along.append(s)
        direction.append(g)
        tangent.append(t)
        share.append(np.full(n, 1.0 / n))
    return ContactPoints(np.concatenate(walls), np.concatenate(along, axis=1),
                         np.concatenate(direction, axis=1), np.concatenate(tangent, axis=1),
                         np.concatenate(share))


def point_laws(contacts, points: ContactPoints) -> list:
    """Each axis' points' laws, [(columns (Pa,) of the axis' points, the walls' Contact (B,),
    its laws flattened member by member (B * Pa,): Contact.part of each point's share)], for
    contacts (x walls, y walls) and points that have any on that axis."""
    out = []
    for axis, contact in enumerate(contacts):
        columns = np.flatnonzero(points.axis == axis)
        if columns.size:
            size = len(contact)
            flat = contact[np.repeat(np.arange(size), columns.size)].part(
                np.tile(points.share[columns], size))
            out.append((columns, contact, flat))
    return out


def stability_limit(t: TorsionArrays, points: ContactPoints, contacts,
                    indentation_bound: float) -> np.ndarray:
    """(B,) central-difference stability limit (s): 2 / omega_max of M^-1 K, the isolators at
    their initial stiffness and every contact point at the largest tangent stiffness of its
    part of its wall's law (point_laws: a crushed pad's point at the wall's own k_w), contacts
    (x walls, y walls) and indentation_bound (m) as Contact.max_tangent_stiffness takes them."""
    k = t.stiffness.copy()
    for columns, contact, flat in point_laws(contacts, points):
        k_pt = flat.max_tangent_stiffness(indentation_bound).reshape(len(contact), columns.size)
        g = points.direction[:, columns]
        k[:, :3, :3] += np.einsum("bp,bpi,bpj->bij", k_pt, g, g)
    lower = np.linalg.cholesky(t.mass)
    inverse = np.linalg.inv(lower)
    omega2 = np.linalg.eigvalsh(inverse @ k @ np.swapaxes(inverse, 1, 2))[:, -1]
    return 2 / np.sqrt(omega2)
