"""The shear building on its isolators: the paper's 5-mass building on bilinear isolators by
default (section 4, Fig. 7; SPEC section 1); any number of stories N (1 <= N <= MAX_STORIES),
stories that yield (bilinear kinematic hardening) and any isolator law (engine/isolators/)
otherwise.

Levels are numbered 0 (isolation slab) to N (roof); story i joins level i-1 to level i.
Everything is SI: kg, N/m, N*s/m, s.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .chain import chain_matrix
from .declared import checked, declared, defaults_of, fields_of
from .errors import EngineError
from .isolators import Isolator
from .model import TWISTING
from .stories import Stories
from .stories.registry import MAX_FIELDS, MAX_STATE
from .torsion_fields import Torsion
from .units import G

MAX_STORIES = 30
PAPER_MASSES = (320e3, 320e3, 320e3, 320e3, 250e3)
"""kg, levels 0 (isolation slab) .. 4 (roof): the paper's Fig. 7c."""


@dataclass(frozen=True)
class Building:
    """One building's properties, each field declared once below (unit, shape, range,
    meaning, default: engine/declared.py); the defaults are the paper's (Fig. 7c).

    Two pairs of fields are a shorthand or its explicit form, never both: k1, k2, fy_ratio for
    isolator=Isolator.bilinear(k1, k2, fy_ratio); story_yield_force, story_post_yield_ratio
    for stories=Stories.bilinear(...). A `torsion` component (engine.Torsion) makes the
    building twist (engine/model.py's twisting model, engine/torsion.py's physics).

    damping="paper": the isolation dashpot 2 zeta_iso sqrt(k_0 M_tot), k_0 the isolator's
    initial stiffness, plus stiffness-proportional story dashpots 2 zeta_sup k / omega_1 of the
    fixed-base superstructure (SPEC decision); "modal": classical damping of the linear
    building with the isolator at k_0, zeta_iso in mode 1, zeta_sup in the others.
    p_delta: the weight of the levels above each story on its drift, a geometric stiffness
    -P_i / h_i in parallel with story i (P_i = g times the masses of levels i..N; small
    displacements, constant gravity; the isolators carry no P-Delta term: their law is their
    test's). collapse_drift_ratio: a member's run ends as collapsed past |drift_i| / h_i (e.g.
    COLLAPSE_DRIFT_RATIO); a non-finite state (a numerical instability) ends a run as
    collapsed whatever it is.
    """

    masses: tuple[float, ...] = declared(
        PAPER_MASSES, "kg", "mass of each level, the isolation slab (level 0) first",
        per="level", valid="(0, inf)", plausible="[1e3, 1e9]")
    story_stiffness: tuple[float, ...] = declared(
        (600e6,) * (len(PAPER_MASSES) - 1), "N m-1", "elastic stiffness of each story (along "
        "x in plan), the first story first", per="story", valid="(0, inf)",
        plausible="[1e5, 1e13]")
    k1: float = declared(200e6, "N m-1", "the bilinear isolator's initial stiffness (the "
                         "shorthand isolator)", kind="shorthand")
    k2: float = declared(25e6, "N m-1", "the bilinear isolator's post-yield stiffness (the "
                         "shorthand isolator)", kind="shorthand")
    fy_ratio: float = declared(0.1, "1", "the bilinear isolator's yield force over the total "
                               "weight (the shorthand isolator)", kind="shorthand")
    zeta_iso: float | None = declared(
        None, "1", "isolation damping ratio on the isolator's initial stiffness (None: the "
        "isolator law's default: bilinear 0.05, the friction pendulums 0)", valid="[0, 1)",
        optional=True)
    zeta_sup: float = declared(0.02, "1", "superstructure damping ratio", valid="[0, 1)")
    damping: str = declared("paper", None, "the damping rule (see the class docstring)",
                            kind="text", choices=("paper", "modal"))
    g: float = declared(G, "m s-2", "the acceleration of gravity, for the weight",
                        valid="(0, inf)")
    isolator: Isolator | None = declared(
        None, None, "the isolator law and its values, an engine.Isolator (None: the bilinear "
        "shorthand k1, k2, fy_ratio)", kind="law", optional=True)
    story_yield_force: tuple[float, ...] | None = declared(
        None, "N", "each story's yield force: bilinear kinematic hardening, elastic up to "
        "F_i / k_i, then story_post_yield_ratio k_i (the shorthand stories; None: linear)",
        per="story", valid="(0, inf)", plausible="[1e3, 1e10]", optional=True)
    story_post_yield_ratio: float = declared(
        0.02, "1", "the shorthand stories' post-yield stiffness over the elastic",
        valid="[0, 1)")
    story_stiffness_y: tuple[float, ...] | None = declared(
        None, "N m-1", "each story's stiffness along y in plan (None: as along x); linear "
        "stories only", per="story", valid="(0, inf)", plausible="[1e5, 1e13]",
        optional=True)
    stories: Stories | None = declared(
        None, None, "the stories' law and its values, an engine.Stories (None: linear, or the "
        "bilinear shorthand story_yield_force)", kind="law", optional=True)
    story_height: tuple[float, ...] | None = declared(
        None, "m", "each story's height (P-Delta and collapse need them)", per="story",
        valid="(0, inf)", plausible="[1.5, 30]", optional=True)
    p_delta: bool = declared(False, None, "the stories' P-Delta (see the class docstring)",
                             kind="flag")
    collapse_drift_ratio: float | None = declared(
        None, "1", "the drift ratio abs(drift_i) / h_i past which a run ends as collapsed",
        valid="(0, 1]", optional=True)
    torsion: Torsion | None = declared(
        None, None, "a building that twists: its plan, masses' offsets and inertia, bearings "
        "and stories' torsion, an engine.Torsion (None: it does not twist)",
        kind="component", optional=True)

    def __post_init__(self):
        masses = np.asarray(self.masses, dtype=float)
        if masses.ndim != 1 or not 2 <= masses.size <= MAX_STORIES + 1 \
                or not np.all(masses > 0):
            raise EngineError(f"masses must be 2 to {MAX_STORIES + 1} positive values in kg "
                              f"(levels 0..N, level 0 the isolation slab), got {self.masses!r}")
        counts = {"level": masses.size, "story": masses.size - 1}
        for name, spec in FIELDS.items():
            value = getattr(self, name)
            if name == "masses" or (value is None and spec.optional):
                continue
            if spec.kind == "number":
                why = f", as masses has {masses.size} levels" if name == "story_stiffness" else ""
                checked(name, spec, value, counts.get(spec.per), why)
            elif spec.kind == "text" and value not in spec.choices:
                raise EngineError(f"{name} must be {' or '.join(map(repr, spec.choices))}, got "
                                  f"{value!r}")
            elif spec.kind == "flag" and not isinstance(value, (bool, np.bool_)):
                raise EngineError(f"{name} must be True or False, got {value!r}")
        self._check_isolator()
        self._check_stories(np.asarray(self.story_stiffness, dtype=float))
        if self.story_stiffness_y is not None and not self.story_law.is_linear:
            raise EngineError("story_stiffness_y applies to linear stories: yielding stories "
                              "have a circular yield surface, the same stiffness both ways")
        self._check_torsion()

    def _check_isolator(self) -> None:
        """The isolator: `isolator`, or the bilinear shorthand k1, k2, fy_ratio (not both)."""
        if self.isolator is None:
            try:
                object.__setattr__(self, "_isolation", Isolator.bilinear(
                    k1=self.k1, k2=self.k2, fy_ratio=self.fy_ratio))
            except EngineError as err:
                raise EngineError(f"isolator: {err}") from None
        elif not isinstance(self.isolator, Isolator):
            raise EngineError(f"isolator must be an engine.Isolator, got {self.isolator!r}")
        else:
            shorthand = {name: getattr(self, name) for name in SHORTHAND_ISOLATOR
                         if getattr(self, name) != DEFAULTS[name]}
            if shorthand:
                raise EngineError(f"give the isolator either as isolator= or by k1, k2, "
                                  f"fy_ratio, not both (got isolator and {shorthand})")
            object.__setattr__(self, "_isolation", self.isolator)

    def _check_torsion(self) -> None:
        """The torsion component: an engine.Torsion fitting this building's levels and
        stories, on what the twisting model supports (engine.model.SUPPORTS)."""
        if self.torsion is None:
            return
        if not isinstance(self.torsion, Torsion):
            raise EngineError(f"torsion must be an engine.Torsion, got {self.torsion!r}")
        self.torsion.for_building(self.n_levels, self.n_stories)
        TWISTING.check("story law", self.story_law.law)
        TWISTING.check("p_delta", self.p_delta)
        TWISTING.check("damping", self.damping)

    @property
    def twists(self) -> bool:
        """Whether the building twists in plan (it has a torsion component)."""
        return self.torsion is not None

    def _check_stories(self, stiff: np.ndarray) -> None:
        """The story law (the shorthand or `stories`), heights, P-Delta and collapse."""
        if self.stories is not None:
            if not isinstance(self.stories, Stories):
                raise EngineError(f"stories must be an engine.Stories, got {self.stories!r}")
            if self.story_yield_force is not None \
                    or self.story_post_yield_ratio != DEFAULTS["story_post_yield_ratio"]:
                raise EngineError("give the stories either as stories= or by "
                                  "story_yield_force (and story_post_yield_ratio), not both")
            law = self.stories
        elif self.story_yield_force is None:
            law = Stories.of("linear")
        else:
            try:
                law = Stories.of("bilinear", yield_force=self.story_yield_force,
                                 post_yield_ratio=self.story_post_yield_ratio)
            except EngineError as err:
                raise EngineError(f"story_yield_force: {err}") from None
        law.fields(stiff)  # per-story lengths and the law's own consistency
        object.__setattr__(self, "_stories", law)
        if (self.p_delta or self.collapse_drift_ratio is not None) \
                and self.story_height is None:
            raise EngineError("p_delta and collapse_drift_ratio need story_height (m, one per "
                              "story)")

    @property
    def isotropic(self) -> bool:
        """Whether the stories are as stiff along y as along x (story_stiffness_y None or
        equal)."""
        return self.story_stiffness_y is None or tuple(map(float, self.story_stiffness_y)) \
            == tuple(map(float, self.story_stiffness))

    def along_y(self) -> Building:
        """This building as the y direction sees it: story_stiffness_y as its stiffnesses
        (itself when isotropic)."""
        if self.isotropic:
            return self
        return dataclasses.replace(self, story_stiffness=tuple(self.story_stiffness_y),
                                   story_stiffness_y=None)

    @property
    def story_law(self) -> Stories:
        """The law the stories follow: `stories`, the bilinear shorthand's or linear."""
        return self._stories

    @property
    def gravity_stiffness(self) -> np.ndarray:
        """(N,) P_i / h_i (N/m), the stiffness P-Delta takes from each story (0 without
        p_delta): P_i = g times the masses of levels i..N, h_i the story's height."""
        if not self.p_delta:
            return np.zeros(self.n_stories)
        above = np.cumsum(np.asarray(self.masses, float)[::-1])[::-1][1:]
        return self.g * above / np.asarray(self.story_height, float)

    @property
    def can_collapse(self) -> bool:
        """Whether the building has a collapse criterion: a collapse_drift_ratio, or an
        isolator with a displacement capacity."""
        return self.collapse_drift_ratio is not None or bool(np.isfinite(
            self.isolation.displacement_capacity(self.total_mass, self.g)))

    @property
    def collapse_drift(self) -> np.ndarray:
        """(N,) the drift (m) past which a story has collapsed: collapse_drift_ratio h_i, inf
        without a collapse criterion."""
        if self.collapse_drift_ratio is None:
            return np.full(self.n_stories, np.inf)
        return self.collapse_drift_ratio * np.asarray(self.story_height, float)

    @property
    def isolation(self) -> Isolator:
        """The isolator this building stands on: `isolator`, or the bilinear shorthand's."""
        return self._isolation

    def with_isolator(self, **values) -> Building:
        """This building on its isolator law with some parameters replaced (SI, the law's
        declared names, e.g. k2=30e6): one member of a sweep over isolator parameters.
        EngineError names a parameter the law does not take or a value out of range."""
        law = self.isolation.law
        try:
            isolator = Isolator.of(law, **{**self.isolation.values, **values})
        except EngineError as err:
            raise EngineError(f"isolator: {err}") from None
        defaults = {name: DEFAULTS[name] for name in SHORTHAND_ISOLATOR}
        return dataclasses.replace(self, isolator=isolator, **defaults)

    @property
    def isolation_zeta(self) -> float:
        """The isolation damping ratio in force: zeta_iso, or the isolator law's default."""
        return self.isolation.default_zeta if self.zeta_iso is None else self.zeta_iso

    @property
    def story_yield_drift(self) -> np.ndarray | None:
        """(N,) yield drifts F_i / k_i (m), F_i where the story law starts to yield, or None
        for linear stories."""
        if self.story_law.is_linear:
            return None
        k = np.asarray(self.story_stiffness, float)
        return self.story_law.yield_strength(k) / k

    @property
    def n_levels(self) -> int:
        """Levels, the isolation slab (level 0) included."""
        return len(self.masses)

    @property
    def n_stories(self) -> int:
        """Stories above the isolation slab."""
        return len(self.story_stiffness)

    @property
    def total_mass(self) -> float:
        """kg, base slab included."""
        return float(np.sum(self.masses))

    @property
    def isolation_dashpot(self) -> float:
        """N s/m: the isolation level's dashpot under damping="paper", 2 zeta_iso sqrt(k_0 M)."""
        return float(2 * self.isolation_zeta * np.sqrt(self.isolator_stiffness
                                                        * self.total_mass))

    @property
    def yield_displacement(self) -> float:
        """Isolator displacement at which it starts to yield or slide (m): u_y = Fy / K1 for
        the bilinear law, Fy = fy_ratio * g * total mass."""
        return self.isolation.yield_displacement(self.total_mass, self.g)

    @property
    def yield_force(self) -> float:
        """Isolator force (N) where it starts to yield or slide: Fy = fy_ratio * g * total
        mass for the bilinear law, mu_fast W + W yield_disp / R for a friction pendulum, mu1 W
        for a triple friction pendulum."""
        return self.isolator_stiffness * self.yield_displacement

    @property
    def isolator_stiffness(self) -> float:
        """The isolator's initial stiffness (N/m): K1, k_0 + W/R for a friction pendulum,
        mu1 W / yield_disp for a triple friction pendulum."""
        return self.isolation.initial_stiffness(self.total_mass, self.g)

    def stiffness_matrix(self, isolator_stiffness: float | None = None) -> np.ndarray:
        """(L, L) linear stiffness matrix (N/m) with the isolator at `isolator_stiffness` (its
        initial stiffness unless given)."""
        k_iso = self.isolator_stiffness if isolator_stiffness is None else isolator_stiffness
        springs = np.concatenate([[k_iso], np.asarray(self.story_stiffness, dtype=float)])
        return chain_matrix(springs)

    def fixed_base_omega1(self) -> float:
        """First circular frequency (rad/s) of the superstructure with level 0 held fixed."""
        k = self.stiffness_matrix()[1:, 1:]
        m = np.asarray(self.masses[1:], dtype=float)
        return float(np.sqrt(_generalized_eigvals(k, m)[0]))

    def dashpots(self) -> tuple[float, np.ndarray]:
        """damping="paper"'s dashpots: the isolation's 2 zeta_iso sqrt(k_0 M) and the stories'
        (N,) stiffness-proportional 2 zeta_sup k_i / omega_1 (N s/m), omega_1 the fixed-base
        superstructure's first circular frequency."""
        c_story = 2 * self.zeta_sup * np.asarray(self.story_stiffness) / self.fixed_base_omega1()
        return self.isolation_dashpot, c_story

    def damping_matrix(self) -> np.ndarray:
        """(L, L) viscous damping matrix, N*s/m, per the `damping` choice."""
        if self.damping == "paper":
            c_iso, c_story = self.dashpots()
            return chain_matrix(np.concatenate([[c_iso], c_story]))
        m = np.asarray(self.masses, dtype=float)
        omega2, phi = _generalized_eig(self.stiffness_matrix(), m)
        zeta = np.full(self.n_levels, self.zeta_sup)
        zeta[0] = self.isolation_zeta
        mphi = m[:, None] * phi  # mass-normalised modes: C = M Phi diag(2 zeta omega) Phi^T M
        return mphi @ np.diag(2 * zeta * np.sqrt(omega2)) @ mphi.T

    def natural_periods(self, isolator_stiffness: float | None = None) -> np.ndarray:
        """(L,) periods (s) of the linear building, the isolator at its initial stiffness
        unless given."""
        omega2 = _generalized_eigvals(self.stiffness_matrix(isolator_stiffness), self.masses)
        return 2 * np.pi / np.sqrt(omega2)


def _generalized_eig(k: np.ndarray, m) -> tuple[np.ndarray, np.ndarray]:
    """Eigenpairs of K phi = omega^2 M phi for diagonal M; phi mass-normalised."""
    m_isqrt = 1 / np.sqrt(np.asarray(m, dtype=float))
    omega2, psi = np.linalg.eigh(m_isqrt[:, None] * k * m_isqrt[None, :])
    return omega2, m_isqrt[:, None] * psi


def _generalized_eigvals(k: np.ndarray, m) -> np.ndarray:
    return _generalized_eig(k, m)[0]


@dataclass(frozen=True)
class BuildingArrays:
    """Per-member building arrays for a batch of B simulations, L levels each.

    masses (B, L) kg; story_k (B, L - 1) N/m: the stories' elastic stiffness less what
    P-Delta takes (Building.gravity_stiffness; exactly story_stiffness without p_delta); the
    isolator law (engine/isolators/): isolator_code (B,) its code, isolator_fields
    (B, MAX_FIELDS) its ROW (for the whole building: a building that twists shares the CARRIED
    ones among its bearings), isolator_capacity (B,) m its displacement capacity (inf: none;
    a bearing's, in a building that twists); the story law (engine/stories/): story_linear (B,)
    bool (the loops multiply by story_k), story_code (B,) its code, story_fields
    (B, L - 1, MAX_FIELDS) its constants, story_state (B, L - 1, MAX_STATE) its initial
    state, story_gravity (B, L - 1) N/m the P-Delta stiffness subtracted from a nonlinear
    law's force; in plan, the stories as a spring plus a circular slip element:
    story_k_post (N/m, P-Delta subtracted), story_k_slip (N/m), story_f_limit (N; inf for
    linear stories), story_yields (B,) bool (stories that yield so) and story_uniaxial (B,)
    bool (a law without plan_fields: in plan it acts along x and y, uncoupled, with its
    state along each); collapse_drift (B, L - 1) m (inf: no criterion); damping (B, L, L)
    N*s/m; stiffness (B, L, L) N/m with the isolator at its initial stiffness (for stability
    limits); distinct (B,) int: which of the batch's distinct buildings the member is (the
    per-building work, the step operators' inverses and the stability limit's eigenvalues, is
    done once per distinct building: `distinct_members`). Every member of a batch has the same
    number of levels L.
    """

    masses: np.ndarray
    story_k: np.ndarray
    isolator_code: np.ndarray
    isolator_fields: np.ndarray
    isolator_capacity: np.ndarray
    story_linear: np.ndarray
    story_code: np.ndarray
    story_fields: np.ndarray
    story_state: np.ndarray
    story_gravity: np.ndarray
    story_k_post: np.ndarray
    story_k_slip: np.ndarray
    story_f_limit: np.ndarray
    story_yields: np.ndarray
    story_uniaxial: np.ndarray
    collapse_drift: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    distinct: np.ndarray

    def take(self, index) -> BuildingArrays:
        """The members at `index` (an index array or slice)."""
        return BuildingArrays(**{name: getattr(self, name)[index] for name in ARRAY_FIELDS})


ARRAY_FIELDS = tuple(f.name for f in dataclasses.fields(BuildingArrays))
"""BuildingArrays' fields, in order."""


def building_arrays(building: Building | Sequence[Building], size: int) -> BuildingArrays:
    """Stack one building (broadcast) or a sequence of `size` buildings into batch arrays: of
    one building (or a sequence of one), read-only views of its rows, no copy per member."""
    if isinstance(building, Building):
        members = [building]
    else:
        members = list(building)
        if len(members) != size:
            raise EngineError(f"building: got {len(members)} buildings for a batch of {size}")
        if not all(isinstance(b, Building) for b in members):
            raise EngineError("building must be a Building or a sequence of Building")
    unique = {b: i for i, b in enumerate(dict.fromkeys(members))}
    levels = {b.n_levels for b in unique}
    if len(levels) > 1:
        raise EngineError(f"building: the members of one batch must have the same number of "
                          f"levels, got {sorted(levels)}; run each height in its own batch")
    rows = [{**_building_row(b), "distinct": i} for i, b in enumerate(unique)]
    if len(rows) == 1:  # one building for every member (a sweep's million): read-only views
        return BuildingArrays(**{name: np.broadcast_to(np.asarray(rows[0][name]),
                                                       (size, *np.shape(rows[0][name])))
                                 for name in ARRAY_FIELDS})
    which = np.array([unique[b] for b in members])
    return BuildingArrays(**{name: np.array([row[name] for row in rows])[which]
                             for name in ARRAY_FIELDS})


def distinct_members(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(first, inverse): one member of each distinct value of `keys` ((B,) int, such as
    BuildingArrays.distinct, or float) and, for every member, which of them it is: work done on
    members[first] and indexed by `inverse` is done once per distinct value, with the same
    numbers as member by member (NumPy's batched linear algebra works matrix by matrix)."""
    keys = np.asarray(keys)
    if keys.size and np.all(keys == keys[0]):  # one building (a sweep's): no sort
        return np.zeros(1, dtype=np.intp), np.zeros(keys.size, dtype=np.intp)
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    return first, inverse.reshape(-1)


@lru_cache(maxsize=4096)
def _building_row(b: Building) -> dict:
    """One building's batch arrays by BuildingArrays' field names (its damping needs
    eigenvalues: computed once per Building; the arrays are copied into a batch of several
    buildings, or lent as read-only views to a batch of one)."""
    k = np.asarray(b.story_stiffness, float)
    law = b.story_law
    gravity = b.gravity_stiffness
    # P-Delta folded into the linear springs: k - P/h (k itself, bit for bit, without it).
    story_k = k - gravity if b.p_delta else k
    fields = np.zeros((k.size, MAX_FIELDS))
    fields[:, :law.module.N_FIELDS] = law.fields(k)
    state = np.zeros((k.size, MAX_STATE))
    for i in range(k.size):
        state[i, :law.module.N_STATE] = law.module.initial_state(fields[i])
    uniaxial = not hasattr(law.module, "plan_fields")
    if uniaxial:  # never read: in plan such a law acts along x and y, uncoupled
        post, slip, limit = story_k, np.zeros_like(k), np.full_like(k, np.inf)
    else:
        post, slip, limit = (np.asarray(x, float) for x in law.module.plan_fields(
            k, **law.per_story(k.size)))
        post = post - gravity if b.p_delta else post
    return {"masses": np.asarray(b.masses, float), "story_k": story_k,
            "isolator_code": b.isolation.code,
            "isolator_fields": b.isolation.row(b.total_mass, b.g),
            "isolator_capacity": b.isolation.displacement_capacity(b.total_mass, b.g),
            "story_linear": law.is_linear, "story_code": law.code, "story_fields": fields,
            "story_state": state, "story_gravity": gravity, "story_k_post": post,
            "story_k_slip": slip, "story_f_limit": limit,
            "story_yields": not law.is_linear and not uniaxial, "story_uniaxial": uniaxial,
            "collapse_drift": b.collapse_drift, "damping": b.damping_matrix(),
            "stiffness": b.stiffness_matrix()}


FIELDS = fields_of(Building)
"""name -> Field (engine/declared.py) of every Building field, in order: the one declaration
the constructor's checks, building files, provenance and the docs read."""
DEFAULTS = defaults_of(Building)
"""name -> the default of every Building field (the paper's building)."""
SHORTHAND_ISOLATOR = ("k1", "k2", "fy_ratio")
"""The bilinear isolator's shorthand fields (isolator=Isolator.bilinear(k1, k2, fy_ratio))."""
