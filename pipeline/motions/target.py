"""Target spectra, and the code's displacement of an isolated building (ASCE 7-22), SI units.

    asce7_sa / asce7_target   the two-period spectrum of ASCE 7-22 section 11.4.5.2 (section
                              11.4.6 in ASCE 7-16) from S_S-like and S_1-like parameters and T_L
    design_parameters         S_DS = 2/3 S_MS, S_D1 = 2/3 S_M1 (section 11.4.4)
    TargetSpectrum            a target as a table: periods (P,) s, sa (P,) m/s^2, its level and
                              source; `at(T)` log-log interpolation; `from_table` for a user's
    damping_coefficient       B_M of Table 17.5-1 from the effective damping beta_M
    isolation_design          T_M, D_M, beta_M, B_M, k_M and D_TM of section 17.5.3 for an
                              engine.Building on any isolator law that declares the code's
                              formulas (engine.isolators.registry.CODE_INTERFACE)

Spectral parameters (S_MS, S_M1, S_DS, S_D1) are given in g, as the standard and the USGS
tools give them; every returned acceleration is in m/s^2, converted with G = engine.units.G
(9.81 m/s^2, the project's one value of g, so that a record given in g and a target given in
g meet at the same scale factor whatever g is). Periods in s, displacements in m.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from engine.units import G

from .spectra import SPECTRA

LEVELS = ("MCE_R", "design", "service", "user")
"""What a target spectrum represents: the risk-targeted maximum considered earthquake, the
design earthquake (2/3 of MCE_R), a service level, or a user's table."""
DESIGN_FRACTION = 2.0 / 3.0
"""S_DS = 2/3 S_MS and S_D1 = 2/3 S_M1 (ASCE 7-22 section 11.4.4)."""
BM_TABLE = ((0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9),
            (0.50, 2.0))
"""(beta_M, B_M) of ASCE 7-22 Table 17.5-1 (damping coefficient), linear in between, 0.8 at
or below 2% and 2.0 at or above 50% of critical."""
TORSION_FACTOR = 1.15
"""D_TM >= 1.15 D_M: the lower bound of the total maximum displacement (ASCE 7-22 section
17.5.3.3); the building model here has no torsion, so the bound is D_TM."""
DEFAULT_PERIODS = np.geomspace(0.01, 20.0, 301)
"""s: the grid of asce7_target (before the corner periods are added)."""


def asce7_sa(periods, s_short: float, s_one: float, t_long: float) -> np.ndarray:
    """The two-period response spectrum (m/s^2) at periods (s, any shape, >= 0).

    s_short, s_one: the short-period and 1-s spectral accelerations in g (S_MS and S_M1 for
    the MCE_R spectrum, S_DS and S_D1 for the design spectrum); t_long: T_L (s). With
    T_S = s_one / s_short and T_0 = 0.2 T_S (ASCE 7-22 section 11.4.5.2; 7-16 section 11.4.6):
    s_short (0.4 + 0.6 T / T_0) below T_0, s_short up to T_S, s_one / T up to T_L,
    s_one T_L / T^2 beyond; times G.
    """
    _positive(s_short=s_short, s_one=s_one, t_long=t_long)
    t = np.asarray(periods, dtype=float)
    if not np.all(np.isfinite(t) & (t >= 0)):
        raise ValueError(f"periods must be finite and >= 0 s, got {periods!r}")
    t_s = s_one / s_short
    t_0 = 0.2 * t_s
    with np.errstate(divide="ignore"):  # 1 / T at T = 0 is never selected
        sa = np.where(t < t_0, s_short * (0.4 + 0.6 * t / t_0),
                      np.where(t <= t_s, s_short,
                               np.where(t <= t_long, s_one / t, s_one * t_long / t**2)))
    return sa * G


def design_parameters(s_ms: float, s_m1: float) -> tuple[float, float]:
    """(S_DS, S_D1) in g from the MCE_R parameters (S_MS, S_M1) in g: 2/3 of each (ASCE 7-22
    section 11.4.4)."""
    _positive(s_ms=s_ms, s_m1=s_m1)
    return DESIGN_FRACTION * s_ms, DESIGN_FRACTION * s_m1


@dataclass(frozen=True)
class TargetSpectrum:
    """A target spectrum as a table: periods (P,) s, strictly increasing and > 0; sa (P,)
    m/s^2, > 0; level one of LEVELS; source the clause or table it comes from; component the
    horizontal spectrum it describes (pipeline.motions.spectra.SPECTRA: "RotD100", the maximum
    direction, as ASCE 7-22's MCE_R and design spectra are, section 11.2's definition of the
    MCE_R: "determined for the orientation that results in the largest maximum response to
    horizontal ground motions"; "geomean" for FEMA P695's own S_MT and older targets).

    `at(T)` interpolates log(sa) linearly in log(T) (exact on the 1/T and 1/T^2 branches of
    the code's spectrum) and refuses periods outside the table.
    """

    periods: np.ndarray
    sa: np.ndarray
    level: str
    source: str
    component: str = "RotD100"

    def __post_init__(self):
        periods = np.array(self.periods, dtype=float)
        sa = np.array(self.sa, dtype=float)
        if periods.ndim != 1 or periods.size < 2:
            raise ValueError(f"target periods must be a 1-D table of at least 2 periods, got "
                             f"shape {periods.shape}")
        if not np.all(np.isfinite(periods) & (periods > 0)):
            raise ValueError("target periods must be finite and > 0 s (log-log "
                             "interpolation; give T = 0 as a small positive period)")
        if not np.all(np.diff(periods) > 0):
            bad = int(np.flatnonzero(np.diff(periods) <= 0)[0])
            raise ValueError(f"target periods must be strictly increasing: "
                             f"{periods[bad]:g} s is followed by {periods[bad + 1]:g} s")
        if sa.shape != periods.shape:
            raise ValueError(f"target sa has shape {sa.shape}, periods {periods.shape}: one "
                             f"value per period")
        if not np.all(np.isfinite(sa) & (sa > 0)):
            bad = int(np.flatnonzero(~(np.isfinite(sa) & (sa > 0)))[0])
            raise ValueError(f"target spectral accelerations must be finite and > 0, got "
                             f"{sa[bad]:g} m/s^2 at {periods[bad]:g} s")
        if self.level not in LEVELS:
            raise ValueError(f"target level must be one of {LEVELS}, got {self.level!r}")
        if self.component not in SPECTRA:
            raise ValueError(f"target component must be one of {SPECTRA}, got "
                             f"{self.component!r}")
        for name, value in (("periods", periods), ("sa", sa)):
            value.flags.writeable = False  # a frozen target must not change under a suite
            object.__setattr__(self, name, value)

    @classmethod
    def from_table(cls, periods, sa_g, level: str = "user", source: str = "user's table",
                   component: str = "RotD100") -> TargetSpectrum:
        """A target from a user's table: periods (P,) s and spectral accelerations sa_g (P,)
        in g (converted with G), of the horizontal spectrum `component` (default RotD100, as
        ASCE 7-22's site-specific and multi-period spectra are). ValueError names what is
        wrong (order, sign, shape)."""
        periods, sa_g = np.asarray(periods, dtype=float), np.asarray(sa_g, dtype=float)
        bad = np.flatnonzero(~(np.isfinite(sa_g) & (sa_g > 0)))
        if bad.size and sa_g.shape == periods.shape:  # said in the user's unit, g
            raise ValueError(f"target spectral accelerations must be finite and > 0, got "
                             f"{sa_g[bad[0]]:g} g at {periods[bad[0]]:g} s")
        return cls(periods, sa_g * G, level, source, component)

    @property
    def sa_g(self) -> np.ndarray:
        """(P,) the table's spectral accelerations in g."""
        return self.sa / G

    def at(self, periods):
        """Sa (m/s^2) at periods (s, scalar or any shape) inside the table's range, by
        log-log interpolation; a float for a scalar. ValueError outside the range."""
        t = np.asarray(periods, dtype=float)
        lo, hi = self.periods[0], self.periods[-1]
        # A relative slack, so that a period computed as the table's end still counts.
        if not np.all(np.isfinite(t) & (t >= lo * (1 - 1e-12)) & (t <= hi * (1 + 1e-12))):
            raise ValueError(f"the target ({self.source}) is defined for {lo:g} to {hi:g} s "
                             f"only, asked for {np.min(t):g} to {np.max(t):g} s")
        t = np.clip(t, lo, hi)
        out = np.exp(np.interp(np.log(t), np.log(self.periods), np.log(self.sa)))
        return float(out) if out.ndim == 0 else out


def asce7_target(s_short: float, s_one: float, t_long: float, level: str = "MCE_R",
                 periods=None) -> TargetSpectrum:
    """The two-period spectrum of asce7_sa as a TargetSpectrum: s_short, s_one in g (S_MS and
    S_M1 for level "MCE_R", S_DS and S_D1 for "design"), t_long T_L in s, on periods (s, > 0;
    default DEFAULT_PERIODS) with the corner periods T_0, T_S and T_L added, so that log-log
    interpolation is exact on the plateau and on the 1/T and 1/T^2 branches."""
    if level not in ("MCE_R", "design"):
        raise ValueError(f"an ASCE 7 target is 'MCE_R' or 'design', got {level!r}")
    _positive(s_short=s_short, s_one=s_one, t_long=t_long)
    grid = DEFAULT_PERIODS if periods is None else np.asarray(periods, dtype=float)
    t_s = s_one / s_short
    corners = [c for c in (0.2 * t_s, t_s, t_long) if grid.min() < c < grid.max()]
    grid = np.unique(np.concatenate([grid, corners]))
    names = ("S_MS", "S_M1") if level == "MCE_R" else ("S_DS", "S_D1")
    source = (f"ASCE 7-22 section 11.4.5.2 two-period {level} spectrum, {names[0]} = "
              f"{s_short:g} g, {names[1]} = {s_one:g} g, T_L = {t_long:g} s")
    # ASCE 7-22's MCE_R is the maximum-direction spectrum (section 11.2), its design spectrum
    # two thirds of it.
    return TargetSpectrum(grid, asce7_sa(grid, s_short, s_one, t_long), level, source,
                          "RotD100")


def damping_coefficient(beta):
    """B_M (-) for effective damping beta (ratio of critical, scalar or array): ASCE 7-22
    Table 17.5-1 (BM_TABLE), linear between its entries, 0.8 at or below 2%, 2.0 at or above
    50%. A float for a scalar."""
    beta = np.asarray(beta, dtype=float)
    if not np.all(np.isfinite(beta) & (beta >= 0)):
        raise ValueError(f"effective damping must be a ratio >= 0, got {beta!r}")
    betas, coefficients = zip(*BM_TABLE, strict=True)
    out = np.interp(beta, betas, coefficients)
    return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class IsolationDesign:
    """The code's isolation-system quantities at the MCE_R (ASCE 7-22 section 17.5.3).

    t_m: effective period T_M (s); d_m: maximum displacement D_M (m); beta_m: effective
    damping (ratio); b_m: damping coefficient B_M (-); k_m: effective stiffness at D_M (N/m);
    d_tm: total maximum displacement (m), TORSION_FACTOR D_M here (no torsion in the model);
    iterations: of the root finder; s_m1: the S_M1 used (g); law: the isolator law; dashpot:
    whether the model's isolation dashpot counted in beta_m.
    """

    t_m: float
    d_m: float
    beta_m: float
    b_m: float
    k_m: float
    d_tm: float
    iterations: int
    s_m1: float
    law: str
    dashpot: bool


def isolation_design(s_m1: float, building=None, *, torsion_factor: float = TORSION_FACTOR,
                     dashpot: bool = False,
                     supplemental_damping: float = 0.0) -> IsolationDesign:
    """D_M and T_M of an isolated building by the code's equivalent-linear procedure.

    ASCE 7-22 section 17.5.3: D_M = G S_M1 T_M / (4 pi^2 B_M), T_M = 2 pi sqrt(W / (k_M G_b))
    = 2 pi sqrt(M / k_M) (Eqs. 17.5-1 and 17.5-2 of ASCE 7-16; W = M G_b the building's
    weight, G_b = building.g), k_M the isolator law's secant stiffness at D_M (the law's
    effective_stiffness), B_M from Table 17.5-1 for the effective damping beta_M =
    E / (2 pi k_M D_M^2), E the energy dissipated per cycle at D_M (the law's
    energy_per_cycle, where each law states its loop). dashpot=True adds the model's isolation
    dashpot (damping="paper": c = 2 zeta_iso sqrt(k_0 M)): E = pi c w_M D^2, i.e.
    c w_M / (2 k_M) more damping; the code's procedure counts hysteresis only (default): a
    prototype test of a bearing does not measure the model's dashpot (dashpot=True is there to
    show what counting it would give, pipeline.motions.bounds). supplemental_damping: the
    effective damping ratio of supplemental dampers the building has (added to beta_M;
    default 0: the building files declare none). Upper- and lower-bound properties:
    pipeline.motions.bounds.design_basis calls this at each.

    D_M depends on itself through k_M and B_M: it is the root of D - G S_M1 T_M(D) /
    (4 pi^2 B_M(D)), found by brentq after a scan of (1 micron, the bound at the post-yield
    stiffness and B_M = 0.8); should there be several roots, the largest (the conservative
    clearance) is returned. D_TM = torsion_factor D_M: the code's lower bound of the total
    displacement with torsion (section 17.5.3.3); this model has no torsion.

    s_m1: S_M1 in g; building: engine.Building (default the paper's). ValueError
    for a bad argument, or (engine.EngineError, naming it) for an isolator law that does not
    declare post_yield_stiffness and energy_per_cycle.
    """
    from scipy.optimize import brentq

    import engine

    _positive(s_m1=s_m1)
    if not (math.isfinite(supplemental_damping) and 0 <= supplemental_damping < 1):
        raise ValueError(f"supplemental_damping must be a ratio in [0, 1), got "
                         f"{supplemental_damping!r}")
    if not (math.isfinite(torsion_factor) and torsion_factor >= 1):
        raise ValueError(f"torsion_factor must be >= 1, got {torsion_factor!r}")
    b = engine.Building() if building is None else building
    iso, mass = b.isolation, b.total_mass
    k_inf = iso.post_yield_stiffness(mass, b.g)  # the stiffness k_M tends to at large D
    c_iso = _dashpot(b) if dashpot else 0.0

    def quantities(d):
        k = float(iso.effective_stiffness(mass, b.g, d))
        t = 2 * math.pi * math.sqrt(mass / k)
        beta = iso.energy_per_cycle(mass, b.g, d) / (2 * math.pi * k * d * d) \
            + c_iso * (2 * math.pi / t) / (2 * k) + supplemental_damping
        return k, t, beta, damping_coefficient(beta)

    def excess(d):
        _, t, _, b_m = quantities(d)
        return d - G * s_m1 * t / (4 * math.pi**2 * b_m)

    # k_M > k_inf and B_M >= 0.8 everywhere, so the excess is positive at this bound.
    high = G * s_m1 * 2 * math.pi * math.sqrt(mass / k_inf) / (4 * math.pi**2 * 0.8)
    grid = np.geomspace(1e-6, high, 400)
    values = np.array([excess(d) for d in grid])
    crossings = np.flatnonzero((values[:-1] < 0) & (values[1:] >= 0))
    if crossings.size == 0:  # cannot happen for the laws here; say so rather than guess
        raise RuntimeError(f"no D_M found between {grid[0]:g} and {high:g} m")
    i = crossings[-1]
    d_m, info = brentq(excess, grid[i], grid[i + 1], xtol=1e-12, rtol=1e-14,
                       full_output=True)
    k_m, t_m, beta_m, b_m = quantities(d_m)
    return IsolationDesign(t_m=t_m, d_m=float(d_m), beta_m=beta_m, b_m=b_m, k_m=k_m,
                           d_tm=torsion_factor * float(d_m), iterations=info.iterations,
                           s_m1=float(s_m1), law=iso.law, dashpot=dashpot)


def _dashpot(building) -> float:
    """The model's isolation dashpot (N s/m): 2 zeta_iso sqrt(k_0 M) (damping="paper")."""
    if building.damping != "paper":
        raise ValueError("dashpot=True needs damping='paper' (one isolation dashpot); with "
                         "modal damping there is none to count")
    return building.isolation_dashpot


def _positive(**values) -> None:
    """ValueError unless every value is a positive finite number."""
    for name, value in values.items():
        if not (isinstance(value, (int, float, np.floating)) and math.isfinite(value)
                and value > 0):
            raise ValueError(f"{name} must be a positive number, got {value!r}")
