"""The compiled loops' packed arrays, declared once: which column of a member's parameters,
state, per-story constants and scalar peaks holds what (engine/layout.py: a declaration is a
tuple of names numbered from 0, read in a kernel as `p[PLANAR.gap]`, a constant offset).

The three kernels (numba_loop.py, numba_plan.py, numba_torsion.py) share the state of a run
(RUN) and of a wall contact (CONTACT); each adds its own. The isolator law's constants and
state are the law's own columns (its ROW, STATE and STATE_XY, engine/isolators/laws/), read
from arrays of their own (isolator_rows). Arrays are built from the declarations by name
(`packed`), and the scalar peaks' columns are the results' own declarations
(engine/results.py), so that a new column is one name here and no number anywhere.
"""
from __future__ import annotations

import numpy as np

from ..building import distinct_members
from ..isolators.registry import BY_CODE, MAX_FIELDS, MAX_STATE, MAX_STATE_XY
from ..layout import appended, columns
from ..results import PEAKS, PLAN_PEAKS, TORSION_PEAKS
from ..scheme import distinct_step_operators
from ..stories import registry as story_registry

PLANAR = columns("Planar", "stories_nonlinear", "gap", "scale", "capacity")
"""numba_loop's per-member floats: 1.0 where the stories follow a nonlinear law, the clear gap
(m), the record's scale and the isolator's displacement capacity (m, inf: none). The slab's
compliance to a wall force is its building's: the wall response's first entry."""
PLAN = columns("Plan", "anisotropic", "mu_wall", "stories_yield", "stories_uniaxial", "cos",
               "sin", "capacity_square")
"""numba_plan's per-member floats: 1.0 where the building differs along y, the slab-wall
friction coefficient, 1.0 where the stories yield in plan (a slip element) or follow a uniaxial
law along each axis, the record's direction (cos, sin) times its scale, and the isolator's
displacement capacity squared (m^2: no root per step). The compliances along x and y are the
building's: its wall responses' first entries."""
TORSION = columns("Torsion", "cos", "sin", "mu_wall", "capacity_square")
"""numba_torsion's per-member floats: the record's direction (cos, sin) times its scale, the
slab-wall friction coefficient, a bearing's displacement capacity squared (m^2)."""

PLANAR_STORY = columns("PlanarStory", "story_k", "story_gravity", "collapse_drift")
"""numba_loop's per-story rows (B, 3, N): the linear stiffness (P-Delta folded in, N/m),
P-Delta's stiffness (N/m, subtracted from a nonlinear law's force), the collapse drift (m)."""
PLAN_STORY = columns("PlanStory", "story_k", "story_k_post", "story_k_slip", "story_f_limit",
                     "collapse_square", "story_gravity")
"""numba_plan's per-story rows (B, 6, N): the linear stiffness, the post-yield and slip
stiffnesses (N/m), the slip force (N), the collapse drift squared (m^2: no root per step),
P-Delta's stiffness (N/m)."""

RUN = columns("Run", "collapsed", "collapse_time", "collapse_mode")
"""The state every kernel keeps of a member's run: 1.0 once it collapsed, when (s) and how
(results.MODE)."""
CONTACT = columns("Contact", "v_imp", "delta_prev", "in_contact")
"""The state of one wall contact (a planar wall, a wall direction in plan, a contact point):
its impact velocity (m/s, 1.0 before any impact), previous indentation (m), 1.0 in contact."""
PLANAR_STATE = appended("PlanarState", RUN, *CONTACT._fields)
"""numba_loop's state between chunks of steps: RUN, CONTACT."""
PLAN_STATE = RUN
"""numba_plan's: RUN (per wall direction, CONTACT)."""
TORSION_STATE = appended("TorsionState", RUN, "touch_x", "touch_y")
"""numba_torsion's: RUN and 1.0 where a wall of each axis was touched at the last step (per
contact point, CONTACT)."""


def _scalar_floats(*quantities):
    """The names of the per-member float peaks among `quantities` (one value, no direction)."""
    return tuple(q.name for q in quantities
                 if q.along is None and not q.direction and q.dtype is np.float64)


PLANAR_PEAK_COLUMNS = columns("PlanarPeaks", *_scalar_floats(*PEAKS))
"""The scalar float peaks numba_loop keeps in one (B, W) matrix, by their names in
engine/results.py."""
PLAN_PEAK_COLUMNS = columns("PlanPeaks", *_scalar_floats(*PEAKS, *PLAN_PEAKS))
"""numba_plan's scalar float peaks."""
TORSION_PEAK_COLUMNS = columns("TorsionPeaks",
                                *_scalar_floats(*PEAKS, *PLAN_PEAKS, *TORSION_PEAKS))
"""numba_torsion's scalar float peaks."""

SQUARED = tuple(q.name for q in (*PEAKS, *PLAN_PEAKS, *TORSION_PEAKS)
                if q.units in ("m", "m s-1", "m s-2", "N") and not q.wall)
"""The peaks of the structure's displacements, velocities, accelerations and forces, which the
kernels in plan keep squared while running (no root per step: sqrt is monotone, and
sqrt(x * x) == |x| in binary floating point) and finish_peaks roots."""


def packed(layout, source=None, size=None, axis=1, **values) -> np.ndarray:
    """The C-contiguous float64 array of `layout`'s columns stacked along `axis`: each
    column `values[name]` if given, else `source`'s attribute of that name, broadcast to
    (size,) where size is given (a number or a (B,) array alike)."""
    parts = []
    for name in layout._fields:
        value = values[name] if name in values else getattr(source, name)
        value = np.asarray(value, dtype=np.float64)
        parts.append(np.broadcast_to(value, (size,)) if size is not None else value)
    return np.ascontiguousarray(np.stack(parts, axis=axis))


ISOLATOR_FIELDS = MAX_FIELDS
"""The width of a member's isolator row (the isolator laws' widest ROW)."""
ISOLATOR_STATE, ISOLATOR_STATE_XY = MAX_STATE, MAX_STATE_XY
"""The width of a member's isolator state along one axis and in plan (per bearing when the
building twists): the isolator laws' widest STATE and STATE_XY."""
ISOLATOR_SLOTS, ISOLATOR_SLOTS_XY = (0,) * MAX_STATE, (0,) * MAX_STATE_XY
"""Tuples of those lengths: numba_support.stack_doubles' argument for the state on the
stack."""


def isolator_rows(arrays, bearings: int = 1) -> np.ndarray:
    """(B, MAX_FIELDS) float64: each member's isolator ROW (its law: arrays.isolator_code), the
    CARRIED columns shared among `bearings` bearings (a building that twists)."""
    rows = np.array(arrays.isolator_fields, dtype=np.float64, order="C")
    codes = np.asarray(arrays.isolator_code)
    if bearings != 1:
        for code in np.unique(codes):
            law = BY_CODE[code]
            mine = codes == code
            for name in law.CARRIED:
                column = getattr(law.ROW, name)
                rows[mine, column] = rows[mine, column] / bearings
    return rows


def per_building(arrays, dt: float):
    """What is a building's, packed once per distinct building (a sweep's 10^6 members share
    one): (first, which, building, op), one member of each distinct building (D,), each
    member's building among them (B,), their BuildingArrays (arrays.take(first)) and step
    operators (D, L, 2L) (scheme.distinct_step_operators). Member b's are at which[b]."""
    first, which = distinct_members(arrays.distinct)
    return first, which, arrays.take(first), distinct_step_operators(arrays, dt, first)


def story_states(arrays, first, directions: int = 0) -> np.ndarray:
    """The members' story law state at rest (arrays.story_state), C-contiguous float64, only
    as wide as the widest N_STATE among the batch's story laws (at least 1; `first`: one member
    of each distinct building): (B, N, W), or with `directions`, (B, N, directions, W), the
    state repeated for a law along each axis (a run in plan). A law reads its own N_STATE
    columns: a sweep of linear stories carries one column, not MAX_STATE."""
    codes = np.unique(np.asarray(arrays.story_code)[first])
    width = max(1, *(story_registry.BY_CODE[code].N_STATE for code in codes))
    state = arrays.story_state[:, :, :width]
    if directions:
        return np.ascontiguousarray(np.repeat(state[:, :, None, :], directions, axis=2),
                                    dtype=np.float64)
    return np.array(state, dtype=np.float64, order="C")  # a copy: the kernels write it


def contact_state(*shape) -> np.ndarray:
    """Zeroed CONTACT state of the given leading shape, impact velocities 1.0 (no impact yet:
    a harmless divisor)."""
    state = np.zeros((*shape, len(CONTACT)))
    state[..., CONTACT.v_imp] = 1.0
    return state


def linear_story_shear(peaks: dict, arrays, isotropic: bool = True) -> dict:
    """peak_story_shear of the members whose stories are linear (and, in plan, alike along x and
    y: `isotropic`): k times peak_interstory_drift, k the law's stiffness (story_k, P-Delta's
    share given back). The same number as the largest |k drift| over the steps (a product by
    k > 0 is monotone in binary floating point), which the loops then need not keep step by
    step; the other members' shears as the loops kept them."""
    if isotropic:
        linear = np.asarray(arrays.story_linear, dtype=bool)[:, None]
        k = np.asarray(arrays.story_k, float) + np.asarray(arrays.story_gravity, float)
        peaks["peak_story_shear"] = np.where(linear, k * peaks["peak_interstory_drift"],
                                             peaks["peak_story_shear"])
    return peaks


def finish_peaks(peaks: dict, scalar: np.ndarray, layout, state: np.ndarray,
                 rooted: bool = False) -> dict:
    """The run's peaks by name: `peaks` (the arrays a kernel filled by name) with the scalar
    peaks' columns (`scalar` (B, W), `layout` their names), the SQUARED ones rooted where
    `rooted` (a kernel in plan), and how each run ended from its state's RUN columns."""
    for name in layout._fields:
        peaks[name] = scalar[:, getattr(layout, name)].copy()
    if rooted:
        for name in SQUARED:
            if name in peaks:
                peaks[name] = np.sqrt(peaks[name])
    peaks["collapsed"] = state[:, RUN.collapsed] != 0.0
    peaks["collapse_time"] = np.where(peaks["collapsed"], state[:, RUN.collapse_time], np.nan)
    peaks["collapse_mode"] = state[:, RUN.collapse_mode].astype(np.int8)
    return peaks
