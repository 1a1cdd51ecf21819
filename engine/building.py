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

from . import torsion
from .chain import chain_matrix
from .errors import EngineError
from .isolators import Isolator
from .stories import Stories
from .stories.registry import MAX_FIELDS, MAX_STATE
from .units import G

MAX_STORIES = 30
PAPER_MASSES = (320e3, 320e3, 320e3, 320e3, 250e3)
"""kg, levels 0 (isolation slab) .. 4 (roof): the paper's Fig. 7c."""
FIELD_UNITS = {"masses": "kg", "story_stiffness": "N m-1", "k1": "N m-1", "k2": "N m-1",
               "fy_ratio": "1", "zeta_iso": "1", "zeta_sup": "1", "damping": None, "g": "m s-2",
               "isolator": None, "story_yield_force": "N", "story_post_yield_ratio": "1",
               "story_stiffness_y": "N m-1", "stories": None, "story_height": "m",
               "p_delta": None, "collapse_drift_ratio": "1", "plan_size": "m",
               "eccentricity": "m", "mass_inertia": "kg m2", "isolator_positions": "m",
               "story_torsional_stiffness": "N m rad-1", "story_stiffness_centre": "m"}
"""Every Building field and its SI unit (None: text or an Isolator), for files and archives."""
PER_LEVEL = ("masses", "mass_inertia")
"""Fields with one value per level, the isolation slab first."""
PER_STORY = ("story_stiffness", "story_yield_force", "story_stiffness_y", "story_height",
             "story_torsional_stiffness")
IN_PLAN = ("plan_size", "eccentricity", "isolator_positions", "story_stiffness_centre")
TORSION_FIELDS = ("plan_size", "eccentricity", "mass_inertia", "isolator_positions",
                  "story_torsional_stiffness", "story_stiffness_centre")
"""The fields of a building that twists (engine/torsion.py), plan_size first: the others are
given only with it."""
"""Fields of coordinates in plan, (x, y) pairs: one pair, or one per level or per bearing."""
"""Fields with one value per story, the first story first."""


@dataclass(frozen=True)
class Building:
    """One building's properties. Defaults are the paper's (Fig. 7c).

    masses : kg per level 0..N (N + 1 values); story_stiffness : N/m per story 1..N (N values);
    k1, k2, fy_ratio : the bilinear isolator's initial and post-yield stiffness (N/m) and yield
        force as a fraction of the total weight: the shorthand for
        isolator=Isolator.bilinear(k1, k2, fy_ratio) (leave them at their defaults when an
        isolator is given);
    isolator : an engine.Isolator (engine/isolators/laws/: bilinear, friction_pendulum), or
        None for the bilinear shorthand;
    zeta_iso : isolation damping ratio on the isolator's initial stiffness; None: the isolator
        law's default (bilinear 0.05, friction pendulum 0: friction is its damping);
    zeta_sup : superstructure damping ratio;
    damping : "paper" (isolation dashpot 2*zeta_iso*sqrt(k_0*M_tot), k_0 the isolator's
        initial stiffness, plus stiffness-proportional story dashpots 2*zeta_sup*k/omega_1 of
        the fixed-base superstructure; SPEC decision) or "modal" (classical damping of the
        linear building with the isolator at k_0: zeta_iso in mode 1, zeta_sup in the others);
    g : m/s^2, used for the weight;
    story_yield_force : None (linear stories) or N yield forces F_i (N): each story then
        follows bilinear kinematic hardening, elastic k_i up to the yield drift F_i / k_i, then
        story_post_yield_ratio * k_i (exact return mapping, like the isolator's).
    story_stiffness_y : None (isotropic stories: the default) or N story stiffnesses (N/m)
        along y for runs in plan, story_stiffness then being along x; the y direction's
        damping follows the same `damping` rule with them. Linear stories only: a circular
        yield surface needs the same stiffness both ways. A planar run is along x.
    stories : None (linear stories, or the bilinear shorthand story_yield_force) or an
        engine.Stories: the stories' law and its parameters (engine/stories/laws/: linear,
        bilinear, imk), the elastic stiffness being story_stiffness either way;
    story_height : None or N story heights (m), needed by p_delta and collapse_drift_ratio;
    p_delta : the weight of the levels above each story acting on its drift, a geometric
        stiffness -P_i / h_i in parallel with story i (P_i = g times the masses of levels
        i..N; small displacements, constant gravity; the isolators carry no P-Delta term:
        their law is their test's). Default False: the paper's building;
    collapse_drift_ratio : None, or the drift ratio |drift_i| / h_i past which a member's run
        ends as collapsed (e.g. COLLAPSE_DRIFT_RATIO); a non-finite state (a numerical
        instability) ends a run as collapsed whatever this is;
    plan_size : None (a run in plan moves the levels without rotating them) or (b_x, b_y) m,
        the rectangular plan of every level: the building then twists in plan (three degrees
        of freedom per level, engine/torsion.py: the model, its limits);
    eccentricity : (e_x, e_y) m, or one pair per level: the mass centre from the plan's centre;
    mass_inertia : None (uniform slabs, m (b_x^2 + b_y^2) / 12) or per level the polar moment
        (kg m^2) about the level's own mass centre;
    isolator_positions : None (a 4 x 4 grid under the slab, the outer bearings at its edges)
        or (n, 2) m, the bearings' positions from the plan's centre, each 1/n of the isolator;
    story_torsional_stiffness : None (a perimeter frame's, k_y (b_x/2)^2 + k (b_y/2)^2) or N
        values in N m/rad, about the stories' centre of stiffness;
    story_stiffness_centre : None (the plan's centre) or (x, y) m, or one pair per story: where
        the stories' stiffness acts (a frame stiffer on one side moves it).
    """

    masses: tuple[float, ...] = PAPER_MASSES
    story_stiffness: tuple[float, ...] = (600e6,) * (len(PAPER_MASSES) - 1)
    k1: float = 200e6
    k2: float = 25e6
    fy_ratio: float = 0.1
    zeta_iso: float | None = None
    zeta_sup: float = 0.02
    damping: str = "paper"
    g: float = G
    isolator: Isolator | None = None
    story_yield_force: tuple[float, ...] | None = None
    story_post_yield_ratio: float = 0.02
    story_stiffness_y: tuple[float, ...] | None = None
    stories: Stories | None = None
    story_height: tuple[float, ...] | None = None
    p_delta: bool = False
    collapse_drift_ratio: float | None = None
    plan_size: tuple[float, float] | None = None
    eccentricity: tuple = (0.0, 0.0)
    mass_inertia: tuple[float, ...] | None = None
    isolator_positions: tuple | None = None
    story_torsional_stiffness: tuple[float, ...] | None = None
    story_stiffness_centre: tuple | None = None

    def __post_init__(self):
        masses = np.asarray(self.masses, dtype=float)
        stiff = np.asarray(self.story_stiffness, dtype=float)
        if masses.ndim != 1 or not 2 <= masses.size <= MAX_STORIES + 1 \
                or not np.all(masses > 0):
            raise EngineError(f"masses must be 2 to {MAX_STORIES + 1} positive values in kg "
                              f"(levels 0..N, level 0 the isolation slab), got {self.masses!r}")
        if stiff.shape != (masses.size - 1,) or not np.all(stiff > 0):
            raise EngineError(
                f"story_stiffness must be {masses.size - 1} positive values in N/m (one per "
                f"story, as masses has {masses.size} levels), got {self.story_stiffness!r}")
        if self.isolator is None:
            try:
                object.__setattr__(self, "_isolation", Isolator.bilinear(
                    k1=self.k1, k2=self.k2, fy_ratio=self.fy_ratio))
            except EngineError as err:
                raise EngineError(f"isolator: {err}") from None
        elif not isinstance(self.isolator, Isolator):
            raise EngineError(f"isolator must be an engine.Isolator, got {self.isolator!r}")
        else:
            shorthand = {name: getattr(self, name) for name in ("k1", "k2", "fy_ratio")
                         if getattr(self, name) != _FIELDS[name].default}
            if shorthand:
                raise EngineError(f"give the isolator either as isolator= or by k1, k2, "
                                  f"fy_ratio, not both (got isolator and {shorthand})")
            object.__setattr__(self, "_isolation", self.isolator)
        zeta_iso = self.isolation_zeta
        if not 0 <= zeta_iso < 1:
            raise EngineError(f"zeta_iso must be in [0, 1), got {zeta_iso}")
        if not 0 <= self.zeta_sup < 1:
            raise EngineError(f"zeta_sup must be in [0, 1), got {self.zeta_sup}")
        if self.damping not in ("paper", "modal"):
            raise EngineError(f"damping must be 'paper' or 'modal', got {self.damping!r}")
        if not 0 <= self.story_post_yield_ratio < 1:
            raise EngineError(f"story_post_yield_ratio must be in [0, 1), got "
                              f"{self.story_post_yield_ratio}")
        if self.story_yield_force is not None:
            yields = np.asarray(self.story_yield_force, dtype=float)
            if yields.shape != stiff.shape or not np.all(yields > 0):
                raise EngineError(f"story_yield_force must be {stiff.size} positive forces in N "
                                  f"(one per story), got {self.story_yield_force!r}")
        self._check_stories(stiff)
        if self.story_stiffness_y is not None:
            stiff_y = np.asarray(self.story_stiffness_y, dtype=float)
            if stiff_y.shape != stiff.shape or not np.all(stiff_y > 0):
                raise EngineError(f"story_stiffness_y must be {stiff.size} positive values in "
                                  f"N/m (one per story, along y), got "
                                  f"{self.story_stiffness_y!r}")
            if not self.story_law.is_linear:
                raise EngineError("story_stiffness_y applies to linear stories: yielding "
                                  "stories have a circular yield surface, the same stiffness "
                                  "both ways")
        self._check_plan()

    def _check_plan(self) -> None:
        """The fields of a building that twists: given only with plan_size, checked there."""
        if self.plan_size is not None:
            for name, value in torsion.checked_layout(self).items():
                object.__setattr__(self, name, value)
            return
        given = [name for name in TORSION_FIELDS[2:] if getattr(self, name) is not None]
        if given or np.any(np.asarray(self.eccentricity, float) != 0):
            raise EngineError(f"{', '.join(given) or 'eccentricity'}: a building that twists "
                              "needs its plan_size (b_x, b_y) m")

    def _check_stories(self, stiff: np.ndarray) -> None:
        """The story law (the shorthand or `stories`), heights, P-Delta and collapse."""
        if self.stories is not None:
            if not isinstance(self.stories, Stories):
                raise EngineError(f"stories must be an engine.Stories, got {self.stories!r}")
            if self.story_yield_force is not None \
                    or self.story_post_yield_ratio != _FIELDS["story_post_yield_ratio"].default:
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
        if self.story_height is not None:
            height = np.asarray(self.story_height, dtype=float)
            if height.shape != stiff.shape or not np.all(np.isfinite(height) & (height > 0)):
                raise EngineError(f"story_height must be {stiff.size} positive heights in m "
                                  f"(one per story), got {self.story_height!r}")
        if not isinstance(self.p_delta, (bool, np.bool_)):
            raise EngineError(f"p_delta must be True or False, got {self.p_delta!r}")
        ratio = self.collapse_drift_ratio
        if ratio is not None and not (isinstance(ratio, (int, float, np.floating))
                                      and 0 < ratio <= 1):
            raise EngineError(f"collapse_drift_ratio must be a drift ratio in (0, 1] (e.g. "
                              f"0.1 for 10%), got {ratio!r}")
        if (self.p_delta or ratio is not None) and self.story_height is None:
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
        """Whether the building has a collapse criterion (collapse_drift_ratio)."""
        return self.collapse_drift_ratio is not None

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
        defaults = {name: _FIELDS[name].default for name in ("k1", "k2", "fy_ratio")}
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
        mass for the bilinear law, mu_fast W + W yield_disp / R for a friction pendulum."""
        return self.isolator_stiffness * self.yield_displacement

    @property
    def isolator_stiffness(self) -> float:
        """The isolator's initial stiffness (N/m): K1, or k_0 + W/R for a friction pendulum."""
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
    isolator's hysteresis fields (B,) each (engine/isolators/hysteresis.py): k_elastic, k_slip
    N/m, f_limit N, slow_drop, rate s/m; the story law (engine/stories/): story_linear (B,)
    bool (the loops multiply by story_k), story_code (B,) its code, story_fields
    (B, L - 1, MAX_FIELDS) its constants, story_state (B, L - 1, MAX_STATE) its initial
    state, story_gravity (B, L - 1) N/m the P-Delta stiffness subtracted from a nonlinear
    law's force; in plan, the stories as a spring plus a circular slip element:
    story_k_post (N/m, P-Delta subtracted), story_k_slip (N/m), story_f_limit (N; inf for
    linear stories), story_yields (B,) bool (stories that yield so) and story_uniaxial (B,)
    bool (a law without plan_fields: in plan it acts along x and y, uncoupled, with its
    state along each); collapse_drift (B, L - 1) m (inf: no criterion); damping (B, L, L)
    N*s/m; stiffness (B, L, L) N/m with the isolator at its initial stiffness (for stability
    limits). Every member of a batch has the same number of levels L.
    """

    masses: np.ndarray
    story_k: np.ndarray
    k_elastic: np.ndarray
    k_slip: np.ndarray
    f_limit: np.ndarray
    slow_drop: np.ndarray
    rate: np.ndarray
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

    def take(self, index) -> BuildingArrays:
        return BuildingArrays(*(getattr(self, f)[index] for f in self.__dataclass_fields__))


def building_arrays(building: Building | Sequence[Building], size: int) -> BuildingArrays:
    """Stack one building (broadcast) or a sequence of `size` buildings into batch arrays."""
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
    rows = [_building_row(b) for b in unique]
    fields = [np.array(col) for col in zip(*rows, strict=True)]
    which = np.array([unique[b] for b in members]) if len(members) > 1 else np.zeros(size, int)
    return BuildingArrays(*(f[which] for f in fields))


@lru_cache(maxsize=4096)
def _building_row(b: Building) -> tuple:
    """One building's batch arrays, in BuildingArrays' order (its damping needs eigenvalues:
    computed once per Building; the arrays are copied into the batch, never handed out)."""
    iso = b.isolation.fields(b.total_mass, b.g)
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
    return (np.asarray(b.masses, float), story_k, iso["k_elastic"], iso["k_slip"],
            iso["f_limit"], iso["slow_drop"], iso["rate"], law.is_linear, law.code, fields, state,
            gravity, post, slip, limit, not law.is_linear and not uniaxial, uniaxial,
            b.collapse_drift,
            b.damping_matrix(), b.stiffness_matrix())


_FIELDS = Building.__dataclass_fields__
assert set(_FIELDS) == set(FIELD_UNITS), "FIELD_UNITS must name every Building field"
