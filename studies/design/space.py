"""The space studies.design searches (see its docstring for what and why): the candidates'
variables, their grids and steps, the physical bounds (Bounds) and the user's constraints
(Criteria). The search itself, over this space, is search.py."""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from engine.impact.laws import rubber_bumper
from engine.results import quantity as peak
from engine.units import CM, KN_PER_MM
from pipeline.assess.derived import quantity as derived

VARIABLES = {  # the searched variables: units, long name
    "thickness": ("m", "bumper thickness t"),
    "cavity_ratio": ("1", "depth of the wall cavity holding each bumper / its thickness, c/t"),
    "n_bumpers": ("1", "bumpers on each wall, acting in parallel"),
    "shape_factor": ("1", "shape factor S of the square bumper: loaded area / area free to "
                          "bulge = side / (4 t)"),
    "wall_k": ("N m-1", "moat wall stiffness k_w behind the crushed bumpers"),
}


# The first grid; thickness as fractions of what the bumpers may protrude (gap - D_S), so that
# it spans the bound whatever the gap (a cavity lets a bumper be thicker than that).
COARSE = {"thickness": (0.4, 0.7, 1.0, 1.3, 1.6), "cavity_ratio": (0.0, 0.2, 0.4),
          "n_bumpers": (4, 8, 16, 32), "shape_factor": (0.5, 1.0, 1.5),
          "wall_k": (5e8, 2.5e9)}


QUICK = {"thickness": (0.6, 1.0), "cavity_ratio": (0.0, 0.4), "n_bumpers": (4, 16),
         "shape_factor": (0.75,), "wall_k": (1.5e9,)}


QUICK_PAIRS = ("RSN848", "RSN1148", "RSN725")  # three short pairs of three earthquakes


ROUNDS, QUICK_ROUNDS = 30, 1  # pattern-search rounds at most


FINEST = 2  # the steps are halved twice at most


THICKNESS_MIN = 0.03  # m


SHAPE_FACTOR = (0.5, 1.5)


N_MIN = 2


WALL_K = (5e8, 2.5e9)  # N/m: the paper's range (5.5)


WALL_LENGTH = rubber_bumper.WALL_LENGTH  # m: where no plan gives it (not the paper's)


WITHIN_LIMITS = 0.84


OBJECTIVES = {"median": "weighted median", "p84": "weighted 84th percentile"}


REFERENCES = ("no wall", "bare wall at the gap", "code clearance D_TM")


PEAKS = {  # what is kept per member: units, long name
    # The units are the declarations' (pipeline.assess.derived, engine.results); the long names are
    # worded as this archive has always had them where they differ from the declarations'.
    "peak_floor_accel": (derived("peak_floor_accel").units, "largest peak total acceleration "
                         "over the levels (the base slab and the floors; resultant in plan)"),
    "peak_isolator_disp": (peak("peak_isolator_disp").units,
                           f"{peak('peak_isolator_disp').long_name} (resultant in plan)"),
    # the archive's name for pipeline.assess.derived's peak_story_drift
    "peak_interstory_drift": (derived("peak_story_drift").units,
                              f"{derived('peak_story_drift').long_name} over the stories "
                              "(resultant in plan)"),
    "max_impact_force": (peak("max_impact_force").units,
                         "largest impact force on a wall of the moat"),
    "max_indentation": (peak("max_indentation").units, "largest indentation at the moat wall"),
    "n_impacts": (peak("n_impacts").units, "number of impacts"),
}


SERVICE, DESIGN, MCE = 0, 1, 2  # indices of LEVELS


OTHER_FLAGS = ("invalid_floor_accel", "invalid_story_shear", "invalid_wall_force",
               "invalid_collapse")


CRITERIA = ("within_limits", "service", "hurt_design", "valid")


@dataclass(frozen=True)
class Criteria:
    """What is minimised and what a feasible candidate must meet (see the module docstring):
    objective "median" | "p84"; within_limits, service_contact, hurt_design fractions (-);
    stress_limit: whether the stress limit counts beside crushing."""

    objective: str = "p84"
    within_limits: float = WITHIN_LIMITS
    stress_limit: bool = True
    service_contact: float = 0.0
    hurt_design: float = 1.0
    valid: float = 0.0

    def margins(self, stats) -> dict[str, np.ndarray]:
        """(K,) per constraint (CRITERIA): how far inside it each candidate is (>= 0 met),
        in fractions of the pairs' weight. stats: `statistics` of the candidates."""
        within = stats["fraction_within_limits" if self.stress_limit
                       else "fraction_uncrushed"][MCE]
        return {"within_limits": within - self.within_limits,
                "service": self.service_contact - stats["fraction_contact"][SERVICE],
                "hurt_design": self.hurt_design - stats["fraction_hurt"][DESIGN],
                "valid": stats["fraction_valid"][MCE] - self.valid}

    def objective_of(self, stats) -> np.ndarray:
        """(K,) the objective, m/s^2."""
        return stats[f"{self.objective}_peak_floor_accel"][MCE]

    def text(self) -> str:
        limit = "uncrushed and within the stress limit" if self.stress_limit else "uncrushed"
        return (f"minimise the {OBJECTIVES[self.objective]} of the largest peak floor "
                f"acceleration at the MCE_R; bumpers {limit} under >= {self.within_limits:.0%} "
                f"of the pairs at the MCE_R; contact at the service level under <= "
                f"{self.service_contact:.0%}; hurt at the design level under <= "
                f"{self.hurt_design:.0%}" + (" (not constrained)" if self.hurt_design >= 1
                                             else "")
                + f"; otherwise valid under >= {self.valid:.0%} of the pairs at the MCE_R"
                + (" (not constrained)" if self.valid <= 0 else ""))


def criteria(args) -> Criteria:
    """The Criteria of the command line; SweepError for a fraction outside [0, 1]."""
    from pipeline.errors import SweepError

    for name in ("within_limits", "service_contact", "hurt_design", "valid"):
        value = getattr(args, name)
        if not 0 <= value <= 1:
            raise SweepError(f"--{name.replace('_', '-')} must be a fraction in [0, 1], got "
                             f"{value}")
    return Criteria(args.objective, args.within_limits, not args.no_stress_limit,
                    args.service_contact, args.hurt_design, args.valid)


@dataclass(frozen=True)
class Bounds:
    """The physical limits of a bumper layout (module docstring): gap m; clearance m, the least
    clear gap the bumpers leave (D_S); usable_strain -, the rubber's, or a function of the pad's
    shape factor S giving it (the stress limit is reached at a strain that depends on the
    pad's shape: `usable_strain` below); wall_length m."""

    gap: float
    clearance: float
    usable_strain: float | Callable[[float], float]
    wall_length: float = WALL_LENGTH
    thickness_min: float = THICKNESS_MIN
    shape_factor: tuple[float, float] = SHAPE_FACTOR
    n_min: int = N_MIN
    wall_k: tuple[float, float] = WALL_K

    def usable(self, s: float) -> float:
        """The rubber's usable strain (-) in a pad of shape factor s."""
        return float(self.usable_strain(s) if callable(self.usable_strain)
                     else self.usable_strain)

    @property
    def least_usable(self) -> float:
        """The least usable strain over the shape factor range (-): the stiffest pad's."""
        return min(self.usable(s) for s in self.shape_factor)

    def least_shape(self, cavity_ratio: float) -> float:
        """The least shape factor of the range whose pad may sit in a cavity of depth
        cavity_ratio x t: usable strain <= 1 - c/t (the usable strain falls as S grows,
        bisected to 1e-12); the range's upper end when none may."""
        s_lo, s_hi = self.shape_factor
        if self.usable(s_lo) <= 1 - cavity_ratio or not callable(self.usable_strain):
            return s_lo
        if self.usable(s_hi) > 1 - cavity_ratio:
            return s_hi
        lo, hi = s_lo, s_hi
        while hi - lo > 1e-12 * hi:
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if self.usable(mid) <= 1 - cavity_ratio else (mid, hi)
        return hi

    def limits(self, config: dict) -> dict[str, tuple[tuple[float, str], tuple[float, str]]]:
        """Per variable, ((lower bound, why), (upper bound, why)) given the other variables of
        `config` (name -> value): the tightest of the limits that involve it."""
        t, r, n, s = (config[k] for k in ("thickness", "cavity_ratio", "n_bumpers",
                                          "shape_factor"))
        room = self.gap - self.clearance  # what the bumpers may protrude, m
        clear = "the clearance: thickness - cavity <= gap - D_S (the code's service level)"
        wall = f"the wall's length: 2 n x side <= {self.wall_length:g} m"
        usable = (f"the cavity: c/t <= 1 - the usable strain {self.usable(s):.3g} (the "
                  "slab would bear on the wall before the rubber reaches it)")
        along = self.wall_length / (8 * n * s)  # 8 n S t <= L: the count's limit on t
        s_lo, s_hi = self.shape_factor
        shape = f"the shape factor range [{s_lo:g}, {s_hi:g}] of the law's calibration"
        cavity = (f"the cavity: c/t {r:.3g} <= 1 - the usable strain, which falls as S grows "
                  "(a softer pad would not be used up before the slab bears on the wall)")
        paper_k = (f"the paper's walls, {self.wall_k[0] / KN_PER_MM:g}-"
                   f"{self.wall_k[1] / KN_PER_MM:g} kN/mm (5.5)")
        return {
            "thickness": ((self.thickness_min, "the thinnest bumper searched"),
                          min((room / (1 - r), clear), (along, wall))),
            "cavity_ratio": (max((0.0, "no cavity"), (1 - room / t, clear)),
                             (1 - self.usable(s), usable)),
            "n_bumpers": ((float(self.n_min), f"{self.n_min} bumpers per wall"),
                          (self.wall_length / (8 * s * t), wall)),
            "shape_factor": (max((s_lo, shape), (self.least_shape(r), cavity)),
                             min((s_hi, shape), (self.wall_length / (8 * n * t), wall))),
            "wall_k": ((self.wall_k[0], paper_k), (self.wall_k[1], paper_k)),
        }

    def allows(self, config: dict) -> bool:
        """Whether the layout is within every limit (to rounding)."""
        for name, ((lo, _), (hi, _)) in self.limits(config).items():
            value = config[name]
            if not lo * (1 - 1e-9) - 1e-12 <= value <= hi * (1 + 1e-9) + 1e-12:
                return False
        return True

    def text(self) -> str:
        s_lo, s_hi = self.shape_factor
        cavity = (f"c/t <= {1 - self.usable(s_lo):.3g}" if self.usable(s_lo) == self.usable(s_hi)
                  else f"c/t <= {1 - self.usable(s_lo):.3g} (S {s_lo:g}) to "
                       f"{1 - self.usable(s_hi):.3g} (S {s_hi:g})")
        return (f"thickness - cavity <= {(self.gap - self.clearance) / CM:.3g} cm (gap "
                f"{self.gap / CM:.3g} cm - D_S {self.clearance / CM:.3g} cm); thickness >= "
                f"{self.thickness_min / CM:g} cm; {cavity}; shape "
                f"factor {s_lo:g}-{s_hi:g}; {self.n_min} <= n, "
                f"2 n side <= {self.wall_length:g} m; k_w {self.wall_k[0] / KN_PER_MM:g}-"
                f"{self.wall_k[1] / KN_PER_MM:g} kN/mm")


def usable_strain(strain: float, stress_limit: float | None, shape_factor: float | None = None,
                  shape_k: float | None = None) -> float:
    """The strain (-) the rubber may reach: its crush strain, or less where the impact law's
    stress alpha K_r rho(S) eps^n reaches the limit (Pa; None: no limit), rho(S) the law's
    compression_ratio of a pad of shape factor S with the rubber's factor shape_k (None: the
    law's default, and the law's calibration shape; independent of the pad's size). 0.589 for
    the paper's rubber at 30.9 MPa without shape effect (or at S = S_cal, 1.0); with
    Gent & Lindley's k = 1: 0.765 at S 0.5, 0.469 at S 1.5."""
    from engine.impact import LAWS

    law = LAWS["bumper"].PARAMETERS
    if stress_limit is None:
        return strain
    ratio = 1.0 if shape_factor is None else float(LAWS["bumper"].compression_ratio(
        shape_factor, law.shape_k.default if shape_k is None else shape_k))
    at_limit = (stress_limit / (law.alpha.default * law.k_r.default * ratio)) \
        ** (1 / law.n.default)
    return min(strain, at_limit)


def grid(values: dict, bounds: Bounds) -> dict[str, np.ndarray]:
    """Every combination of `values` (name -> sequence; thickness as fractions of gap - D_S,
    rounded to the mm) the bounds allow, as (K,) arrays."""
    values = {**values, "thickness": np.round(np.asarray(values["thickness"])
                                              * (bounds.gap - bounds.clearance), 3)}
    mesh = np.meshgrid(*(np.asarray(values[v], float) for v in VARIABLES), indexing="ij")
    table = {v: m.ravel() for v, m in zip(VARIABLES, mesh, strict=True)}
    keep = [i for i in range(mesh[0].size) if bounds.allows(row(table, i))]
    return {v: table[v][keep] for v in VARIABLES}


def row(table: dict, i: int) -> dict:
    """Candidate i of a table (name -> (K,) array) as name -> value."""
    return {v: float(table[v][i]) for v in VARIABLES}


def neighbours(config: dict, level: int, bounds: Bounds) -> dict[str, np.ndarray]:
    """The candidates one step up and one step down from `config` in each variable (step
    halved `level` times; clipped to the bounds, none past a bound it sits on), as a table."""
    out = []
    for name in VARIABLES:
        (lo, _), (hi, _) = bounds.limits(config)[name]
        for sign in (-1, 1):
            value = float(f"{_stepped(name, config[name], sign, level):.6g}")
            # past a bound: the bound itself, exactly (a count: the last whole one inside)
            if value > hi:
                value = float(math.floor(hi + 1e-9)) if name == "n_bumpers" else hi
            elif value < lo:
                value = float(math.ceil(lo - 1e-9)) if name == "n_bumpers" else lo
            elif name == "n_bumpers":
                value = float(round(value))
            if (value - config[name]) * sign > 1e-9 * abs(config[name]):
                candidate = {**config, name: value}
                if bounds.allows(candidate):
                    out.append(candidate)
    return {v: np.array([c[v] for c in out]) for v in VARIABLES}


def _stepped(name: str, value: float, sign: int, level: int) -> float:
    """One search step from value: geometric for t, n, k_w; additive for c/t and S."""
    frac = sign / 2 ** level
    if name == "thickness":
        return value * 1.25 ** frac
    if name == "n_bumpers":
        new = value * 2 ** (0.5 * frac)
        return new if abs(round(new) - value) >= 1 else value + sign  # an integer step
    if name == "cavity_ratio":
        return value + 0.1 * frac
    if name == "shape_factor":
        return value + 0.25 * frac
    return value * (5 / 3) ** frac  # wall_k
