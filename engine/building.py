"""The shear building on its isolators: the paper's 5-mass building by default (section 4,
Fig. 7; SPEC section 1), any number of stories N (1 <= N <= MAX_STORIES) otherwise.

Levels are numbered 0 (isolation slab) to N (roof); story i joins level i-1 to level i.
Everything is SI: kg, N/m, N*s/m, s.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .errors import EngineError
from .units import G

MAX_STORIES = 30
PAPER_MASSES = (320e3, 320e3, 320e3, 320e3, 250e3)
"""kg, levels 0 (isolation slab) .. 4 (roof): the paper's Fig. 7c."""


@dataclass(frozen=True)
class Building:
    """One building's properties. Defaults are the paper's (Fig. 7c).

    masses : kg per level 0..N (N + 1 values); story_stiffness : N/m per story 1..N (N values);
    k1, k2 : isolator initial and post-yield stiffness (N/m);
    fy_ratio : isolator yield force Fy as a fraction of the total weight (u_y = Fy / k1);
    zeta_iso, zeta_sup : damping ratios of the isolation system and the superstructure;
    damping : "paper" (isolation dashpot 2*zeta_iso*sqrt(k1*M_tot) plus stiffness-proportional
        story dashpots 2*zeta_sup*k/omega_1 of the fixed-base superstructure; SPEC decision) or
        "modal" (classical damping of the linear building with the isolator at k1: zeta_iso in
        mode 1, zeta_sup in modes 2-5);
    g : m/s^2, used for the weight.
    """

    masses: tuple[float, ...] = PAPER_MASSES
    story_stiffness: tuple[float, ...] = (600e6,) * (len(PAPER_MASSES) - 1)
    k1: float = 200e6
    k2: float = 25e6
    fy_ratio: float = 0.1
    zeta_iso: float = 0.05
    zeta_sup: float = 0.02
    damping: str = "paper"
    g: float = G

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
        if not 0 < self.k2 < self.k1:
            raise EngineError(
                f"isolator stiffness needs 0 < k2 < k1, got k1={self.k1}, k2={self.k2}")
        if not self.fy_ratio > 0:
            raise EngineError(f"fy_ratio must be positive, got {self.fy_ratio}")
        for name in ("zeta_iso", "zeta_sup"):
            if not 0 <= getattr(self, name) < 1:
                raise EngineError(f"{name} must be in [0, 1), got {getattr(self, name)}")
        if self.damping not in ("paper", "modal"):
            raise EngineError(f"damping must be 'paper' or 'modal', got {self.damping!r}")

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
    def yield_force(self) -> float:
        """Isolator yield force Fy (N) = fy_ratio * g * total mass."""
        return self.fy_ratio * self.g * self.total_mass

    @property
    def yield_displacement(self) -> float:
        """Isolator yield displacement u_y = Fy / k1 (m)."""
        return self.yield_force / self.k1

    def stiffness_matrix(self, isolator_stiffness: float | None = None) -> np.ndarray:
        """(L, L) linear stiffness matrix (N/m) with the isolator at `isolator_stiffness` (k1)."""
        k_iso = self.k1 if isolator_stiffness is None else isolator_stiffness
        springs = np.concatenate([[k_iso], np.asarray(self.story_stiffness, dtype=float)])
        return _chain_matrix(springs)

    def fixed_base_omega1(self) -> float:
        """First circular frequency (rad/s) of the superstructure with level 0 held fixed."""
        k = self.stiffness_matrix()[1:, 1:]
        m = np.asarray(self.masses[1:], dtype=float)
        return float(np.sqrt(_generalized_eigvals(k, m)[0]))

    def damping_matrix(self) -> np.ndarray:
        """(L, L) viscous damping matrix, N*s/m, per the `damping` choice."""
        if self.damping == "paper":
            c_iso = 2 * self.zeta_iso * np.sqrt(self.k1 * self.total_mass)
            omega_1 = self.fixed_base_omega1()
            c_story = 2 * self.zeta_sup * np.asarray(self.story_stiffness) / omega_1
            return _chain_matrix(np.concatenate([[c_iso], c_story]))
        m = np.asarray(self.masses, dtype=float)
        omega2, phi = _generalized_eig(self.stiffness_matrix(), m)
        zeta = np.full(self.n_levels, self.zeta_sup)
        zeta[0] = self.zeta_iso
        mphi = m[:, None] * phi  # mass-normalised modes: C = M Phi diag(2 zeta omega) Phi^T M
        return mphi @ np.diag(2 * zeta * np.sqrt(omega2)) @ mphi.T

    def natural_periods(self, isolator_stiffness: float | None = None) -> np.ndarray:
        """(L,) periods (s) of the linear building, isolator at k1 unless given."""
        omega2 = _generalized_eigvals(self.stiffness_matrix(isolator_stiffness), self.masses)
        return 2 * np.pi / np.sqrt(omega2)


def _chain_matrix(springs: np.ndarray) -> np.ndarray:
    """Assemble a chain of springs (or dashpots): element 0 joins ground to level 0,
    element i joins level i-1 to level i."""
    n = len(springs)
    mat = np.zeros((n, n))
    for i, s in enumerate(springs):
        mat[i, i] += s
        if i > 0:
            mat[i - 1, i - 1] += s
            mat[i - 1, i] -= s
            mat[i, i - 1] -= s
    return mat


def _generalized_eig(k: np.ndarray, m) -> tuple[np.ndarray, np.ndarray]:
    """Eigenpairs of K phi = omega^2 M phi for diagonal M; phi mass-normalised."""
    m_isqrt = 1 / np.sqrt(np.asarray(m, dtype=float))
    omega2, psi = np.linalg.eigh(m_isqrt[:, None] * k * m_isqrt[None, :])
    return omega2, m_isqrt[:, None] * psi


def _generalized_eigvals(k: np.ndarray, m) -> np.ndarray:
    return _generalized_eig(k, m)[0]


@dataclass(frozen=True)
class BuildingArrays:
    """Per-member building arrays for a batch of B simulations.

    masses (B, L) kg; story_k (B, L - 1) N/m; k2, k_plastic, f_plastic_yield (B,) for the
    isolator (k_plastic = k1 - k2, f_plastic_yield = (k1 - k2) * u_y); damping (B, L, L) N*s/m;
    stiffness (B, L, L) N/m with the isolator at k1 (for stability limits). Every member of a
    batch has the same number of levels L.
    """

    masses: np.ndarray
    story_k: np.ndarray
    k2: np.ndarray
    k_plastic: np.ndarray
    f_plastic_yield: np.ndarray
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
    """One building's batch arrays (its damping needs eigenvalues: computed once per Building;
    the arrays are copied into the batch, never handed out)."""
    return (np.asarray(b.masses, float), np.asarray(b.story_stiffness, float), b.k2,
            b.k1 - b.k2, (b.k1 - b.k2) * b.yield_displacement, b.damping_matrix(),
            b.stiffness_matrix())
