"""Beyond the paper: what bumpers to install for a building and a gap short of the code's.

The record pairs (default: the 22 FEMA P695 far-field pairs, as recorded) are scaled to the
site's MCE_R by a code's rule (studies._code_suite: ASCE 7-22 chapter 17 by default) and run in
plan (a rectangular moat by default) at three intensity levels, the service, design and MCE_R
levels of _code_suite.LEVELS (1/3, 2/3 and 1 x the MCE_R factors). The gap is the user's
(--gap-cm, or --gap-dm as a fraction of the code's D_M); by default 0.8 D_M, short of the
code's clearance D_TM: where bumpers matter.

A candidate is a bumper layout: thickness t, cavity depth as a ratio c/t (paper 5.3), count per
wall n, shape factor S (a square pad of side 4 S t: the plan size follows from S and t) and
wall stiffness k_w. Each is judged at every level on every pair, with the validity flags of
pipeline.validity per member (contact stress against the rubber's limit, floor acceleration,
story shear against the code's capacity when the stories are linear, wall force if a capacity
is given), and the statistics weighted per earthquake (studies._code_suite: no event dominates).

Objective (--objective): the weighted 84th percentile (default) or median over the pairs of the
largest peak floor acceleration at the MCE_R (the other one breaks ties). The 84th percentile by
default: at a gap short of D_TM but near D_M about half the pairs reach the wall at the MCE_R,
and the median pair, which does not, cannot tell one layout from another. Constraints, each a
command-line option:
- within limits (--within-limits, default 0.84): under at least this weighted fraction of the
  pairs at the MCE_R the bumpers stay uncrushed and their contact stress within the rubber's
  limit (pipeline.validity.RUBBER_STRESS_LIMIT, 30.9 MPa; --no-stress-limit: uncrushed only,
  the old criterion);
- service (--service-contact, default 0): at most this weighted fraction of the pairs touches
  the bumpers at the service level;
- design (--hurt-design, default 1: not constrained): at most this weighted fraction of the
  pairs is hurt at the design level by the bumpers against the bare wall at the same gap
  (pipeline.outcomes, 2% tolerance);
- valid (--valid, default 0: not constrained): at least this weighted fraction of the pairs at
  the MCE_R raises no other validity flag (floor acceleration, story shear, wall force).

Search bounds, from physical limits (Bounds; each named where the optimum meets it):
- thickness - cavity <= gap - D_S: the bumpers leave the clearance the code's procedure gives
  at the service level (D_S: pipeline.target.isolation_design at LEVELS["service"] x S_M1; 4.8
  cm for the paper's building at the default site), so that frequent earthquakes do not reach
  them by the code's own estimate (the service constraint checks it on the pairs);
  thickness >= 3 cm (its usable stroke, under 2 cm, is of the order of the gap's tolerances);
- c/t <= 1 - the rubber's usable strain (the least of its crush strain and the strain at the
  stress limit, 0.59 for the paper's rubber): a deeper cavity lets the slab bear on the wall's
  edge before the rubber reaches it (paper 5.3: deep enough to use the rubber, no deeper);
- 0.5 <= S <= 1.5 (--shape-factor): the law's stiffness A K_r / t^n is calibrated on a pad
  of S = 1.0 (Kajita et al., 40 x 40 x 10 mm; the paper's bumper: 0.75); by Gent's compression
  modulus E (1 + 2 S^2) a pad of S 0.5 is half as stiff and one of S 1.5 1.8 times as stiff:
  beyond the range the law is off by more than a factor of 2, and below S 0.5 (side < 2 t) the
  pad is a column that bulges and buckles;
- 2 <= n and 2 n x side <= the wall's length (--wall-length-m, default 18 m: a square slab of
  320 t at a typical 10 kPa floor weight is 17.7 m a side): the bumpers stand at least one
  side apart, free to bulge, one near each end at least;
- 500 <= k_w <= 2500 kN/mm: the paper's range of moat walls (5.5).

Search: a coarse grid within the bounds, then a pattern search around the best (the best
feasible one; if none is feasible, the one closest to feasible): each round runs the best's
neighbours one step up and down in every variable (clipped to the bounds), moves to a better
one (and doubles the steps again, up to the first ones) or halves the steps, until the finest
steps (a quarter of the first) find nothing better. Every evaluated candidate is kept
(dimension `candidate`) with its per-pair peaks and flags and its statistics per level.
The optimum is reported as interior (evaluated neighbours on both sides in every variable, with
the constraints its neighbours fail) or at a named bound (physical, or the evaluated grid's edge:
"the optimum may lie beyond"). Beside it, the references at every level: the code's design
(bare wall at D_TM, no bumpers), the bare wall at the gap, and the building without wall.

A member whose clear gap the building without wall never reaches is not run: it is the free run
(engine.simulate is bitwise independent of the batch, and a wall never touched adds exact
zeros), which the tests check against a direct run.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

from engine.units import CM, KN_PER_MM, G

from ._code_suite import LEVELS, site_options
from ._plot import plt
from ._recipe import Recipe, Verdict

GAP_FRACTION = 0.8
"""Default gap / D_M: short of the code's clearance D_TM (1.15 D_M), where bumpers matter."""
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
WALL_LENGTH = 18.0  # m
WITHIN_LIMITS = 0.84
OBJECTIVES = {"median": "weighted median", "p84": "weighted 84th percentile"}
QUANTILES = (0.16, 0.5, 0.84)
REFERENCES = ("no wall", "bare wall at the gap", "code clearance D_TM")
PEAKS = {  # what is kept per member: units, long name
    "peak_floor_accel": ("m s-2", "largest peak total acceleration over the levels (the base "
                                  "slab and the floors; resultant in plan)"),
    "peak_isolator_disp": ("m", "peak isolator displacement (resultant in plan)"),
    "peak_interstory_drift": ("m", "largest peak interstory drift over the stories "
                                   "(resultant in plan)"),
    "max_impact_force": ("N", "largest impact force on a wall of the moat"),
    "max_indentation": ("m", "largest indentation at the moat wall"),
    "n_impacts": ("1", "number of impacts"),
}
SERVICE, DESIGN, MCE = 0, 1, 2  # indices of LEVELS
assert tuple(LEVELS) == ("service", "design", "MCE_R")
OTHER_FLAGS = ("invalid_floor_accel", "invalid_story_shear", "invalid_wall_force")
CRITERIA = ("within_limits", "service", "hurt_design", "valid")


# ----------------------------------------------------------------------------- command line


def options(p) -> None:
    site_options(p)
    gap = p.add_mutually_exclusive_group()
    gap.add_argument("--gap-cm", type=float, default=None, metavar="CM",
                     help="the seismic gap to design for, cm (default "
                          f"{GAP_FRACTION:g} D_M)")
    gap.add_argument("--gap-dm", type=float, default=None, metavar="RATIO",
                     help=f"the gap as a ratio to the code's D_M (default {GAP_FRACTION:g})")
    p.add_argument("--moat", choices=("rectangular", "circular"), default="rectangular",
                   help="the moat in plan (default rectangular: walls normal to x and y)")
    p.add_argument("--objective", choices=tuple(OBJECTIVES), default="p84",
                   help="what is minimised: the weighted 84th percentile (p84, default) or "
                        "median over the pairs of the largest peak floor acceleration at the "
                        "MCE_R")
    p.add_argument("--within-limits", type=float, default=WITHIN_LIMITS, metavar="FRACTION",
                   help="least weighted fraction of the pairs at the MCE_R under which the "
                        "bumpers stay uncrushed and within the stress limit (default "
                        f"{WITHIN_LIMITS:g})")
    p.add_argument("--no-stress-limit", action="store_true",
                   help="uncrushed only, no stress limit (the old criterion; the cavity is "
                        "then bounded by the crush strain)")
    p.add_argument("--stress-limit-mpa", type=float, default=None, metavar="MPA",
                   help="the rubber's contact stress limit, MPa (default 30.9: "
                        "pipeline.validity.RUBBER_STRESS_LIMIT)")
    p.add_argument("--service-contact", type=float, default=0.0, metavar="FRACTION",
                   help="largest weighted fraction of the pairs touching the bumpers at the "
                        "service level (default 0: none)")
    p.add_argument("--hurt-design", type=float, default=1.0, metavar="FRACTION",
                   help="largest weighted fraction of the pairs the bumpers hurt at the "
                        "design level against the bare wall at the gap (default 1: not "
                        "constrained)")
    p.add_argument("--valid", type=float, default=0.0, metavar="FRACTION",
                   help="least weighted fraction of the pairs at the MCE_R with no other "
                        "validity flag (floor acceleration, story shear, wall force; default "
                        "0: not constrained, the flags counted only)")
    p.add_argument("--shape-factor", type=float, nargs=2, default=list(SHAPE_FACTOR),
                   metavar=("LO", "HI"), help="the bumpers' shape factor range searched "
                   f"(default {SHAPE_FACTOR[0]:g} {SHAPE_FACTOR[1]:g}: the law's calibration "
                   "within a factor of 2 in stiffness)")
    p.add_argument("--wall-length-m", type=float, default=WALL_LENGTH, metavar="M",
                   help=f"length of each moat wall, m, bounding the count (default "
                        f"{WALL_LENGTH:g})")
    p.add_argument("--wall-capacity-mn", type=float, default=None, metavar="MN",
                   help="the wall's force capacity, MN, for the validity flags (default: not "
                        "checked)")


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


# ------------------------------------------------------------------------ the search's bounds


@dataclass(frozen=True)
class Bounds:
    """The physical limits of a bumper layout (module docstring): gap m; clearance m, the least
    clear gap the bumpers leave (D_S); usable_strain -, the rubber's; wall_length m."""

    gap: float
    clearance: float
    usable_strain: float
    wall_length: float = WALL_LENGTH
    thickness_min: float = THICKNESS_MIN
    shape_factor: tuple[float, float] = SHAPE_FACTOR
    n_min: int = N_MIN
    wall_k: tuple[float, float] = WALL_K

    def limits(self, config: dict) -> dict[str, tuple[tuple[float, str], tuple[float, str]]]:
        """Per variable, ((lower bound, why), (upper bound, why)) given the other variables of
        `config` (name -> value): the tightest of the limits that involve it."""
        t, r, n, s = (config[k] for k in ("thickness", "cavity_ratio", "n_bumpers",
                                          "shape_factor"))
        room = self.gap - self.clearance  # what the bumpers may protrude, m
        clear = "the clearance: thickness - cavity <= gap - D_S (the code's service level)"
        wall = f"the wall's length: 2 n x side <= {self.wall_length:g} m"
        usable = (f"the cavity: c/t <= 1 - the usable strain {self.usable_strain:.3g} (the "
                  "slab would bear on the wall before the rubber reaches it)")
        along = self.wall_length / (8 * n * s)  # 8 n S t <= L: the count's limit on t
        s_lo, s_hi = self.shape_factor
        shape = f"the shape factor range [{s_lo:g}, {s_hi:g}] of the law's calibration"
        paper_k = (f"the paper's walls, {self.wall_k[0] / KN_PER_MM:g}-"
                   f"{self.wall_k[1] / KN_PER_MM:g} kN/mm (5.5)")
        return {
            "thickness": ((self.thickness_min, "the thinnest bumper searched"),
                          min((room / (1 - r), clear), (along, wall))),
            "cavity_ratio": (max((0.0, "no cavity"), (1 - room / t, clear)),
                             (1 - self.usable_strain, usable)),
            "n_bumpers": ((float(self.n_min), f"{self.n_min} bumpers per wall"),
                          (self.wall_length / (8 * s * t), wall)),
            "shape_factor": ((s_lo, shape), min((s_hi, shape),
                                                (self.wall_length / (8 * n * t), wall))),
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
        return (f"thickness - cavity <= {(self.gap - self.clearance) / CM:.3g} cm (gap "
                f"{self.gap / CM:.3g} cm - D_S {self.clearance / CM:.3g} cm); thickness >= "
                f"{self.thickness_min / CM:g} cm; c/t <= {1 - self.usable_strain:.3g}; shape "
                f"factor {self.shape_factor[0]:g}-{self.shape_factor[1]:g}; {self.n_min} <= n, "
                f"2 n side <= {self.wall_length:g} m; k_w {self.wall_k[0] / KN_PER_MM:g}-"
                f"{self.wall_k[1] / KN_PER_MM:g} kN/mm")


def usable_strain(strain: float, stress_limit: float | None) -> float:
    """The strain (-) the rubber may reach: its crush strain, or less where the impact law's
    stress alpha K_r eps^n (independent of the pad's size) reaches the limit (Pa; None: no
    limit). 0.589 for the paper's rubber at 30.9 MPa."""
    from engine.impact import LAWS

    law = LAWS["bumper"].PARAMETERS
    if stress_limit is None:
        return strain
    at_limit = (stress_limit / (law.alpha.default * law.k_r.default)) ** (1 / law.n.default)
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


# ---------------------------------------------------------------------- running the members


@dataclass(frozen=True)
class Members:
    """Walls to run, K of them: contact (engine.Contact); n_bumpers, area (K,) for the stress
    (inf and 1 for a bare wall: no bumper stress)."""

    contact: object
    n_bumpers: np.ndarray
    area: np.ndarray


def bumper_members(table: dict, gap: float, strain: float) -> Members:
    """The candidates of a table (VARIABLES -> (K,)) as bumpers at the gap (m)."""
    import engine

    t = table["thickness"]
    side = 4 * table["shape_factor"] * t
    contact = engine.Contact.bumper(gap, thickness=t, cavity=table["cavity_ratio"] * t,
                                    n_bumpers=table["n_bumpers"].astype(int),
                                    k_w=table["wall_k"], strain=strain, area=side ** 2)
    return Members(contact, table["n_bumpers"].astype(float), side ** 2)


def reference_members(gap: float, d_tm: float) -> Members:
    """REFERENCES: no wall, the bare wall (the linear law at its defaults) at the gap and at
    the code's clearance D_TM (m)."""
    import engine

    contact = engine.Contact.concat([engine.Contact.none(1), engine.Contact.linear([gap, d_tm])])
    return Members(contact, np.full(3, np.inf), np.ones(3))


@dataclass
class Problem:
    """What every run shares: the scaled suite (studies._code_suite.CodeSuite), the building,
    dt s, the moat, the validity limits (pipeline.validity.Limits); `free` holds the building
    without wall per pair and level (filled by `run_free`)."""

    suite: object
    building: object
    dt: float
    moat: str
    limits: object
    levels: np.ndarray = field(default_factory=lambda: np.array(list(LEVELS.values())))
    free: dict | None = None

    def run(self, members: Members) -> dict[str, np.ndarray]:
        """Every member at every level under every pair: PEAKS, `crushed` and the validity
        flags, (R, L, K) each. One engine call per pair; a member whose clear gap the building
        without wall never reaches takes the free run's peaks (see the module docstring)."""
        r, n_l, k = len(self.suite.pairs), self.levels.size, len(members.contact)
        out = {name: np.zeros((r, n_l, k), dtype=values.dtype)
               for name, values in self.free.items() if name != "reach"}
        for name in out:
            out[name][...] = self.free[name][:, :, None]
        reach = self.free["reach"]
        for p, pair in enumerate(self.suite.pairs):
            run = members.contact.clear_gap[None, :] <= reach[p][:, None]  # (L, K)
            lev, mem = np.nonzero(run)
            if lev.size == 0:
                continue
            peaks = self._simulate(pair, members.contact[mem],
                                   self.suite.factors[p] * self.levels[lev],
                                   members.n_bumpers[mem], members.area[mem])
            peaks["crushed"] = peaks["max_indentation"] > members.contact.delta_u[mem]
            for name, values in peaks.items():
                out[name][p, lev, mem] = values
        return out

    def run_free(self) -> None:
        """The building without wall per pair and level (`free`, (R, L) each), and `reach`:
        the largest displacement toward a wall (per direction for a rectangular moat), m."""
        import engine

        levels = self.levels
        rows = []
        for pair, factor in zip(self.suite.pairs, self.suite.factors, strict=True):
            res = engine.simulate(pair.accel, pair.dt, engine.Contact.none(levels.size),
                                  self.building, self.dt, moat=self.moat,
                                  scale=factor * levels)
            peaks = _peaks(res, self.building, self.limits, np.full(levels.size, np.inf),
                           np.ones(levels.size))
            peaks["crushed"] = np.zeros(levels.size, dtype=bool)
            peaks["reach"] = (res.peak_isolator_disp_xy.max(axis=1) if self.moat == "rectangular"
                              else res.peak_isolator_disp)
            rows.append(peaks)
        self.free = {name: np.stack([r[name] for r in rows]) for name in rows[0]}

    def _simulate(self, pair, contact, scale, n_bumpers, area) -> dict[str, np.ndarray]:
        import engine

        res = engine.simulate(pair.accel, pair.dt, contact, self.building, self.dt,
                              moat=self.moat, scale=scale)
        return _peaks(res, self.building, self.limits, n_bumpers, area)


def _peaks(res, building, limits, n_bumpers, area) -> dict[str, np.ndarray]:
    """PEAKS and the validity flags of an engine result, (B,) each."""
    from pipeline import validity

    flags = validity.flags(res.peak_total_accel, res.peak_interstory_drift,
                           res.max_impact_force, building.story_stiffness, limits,
                           n_bumpers=n_bumpers, area=area,
                           stories_yield=building.story_yield_force is not None)
    return {"peak_floor_accel": res.peak_total_accel.max(axis=1),
            "peak_isolator_disp": res.peak_isolator_disp,
            "peak_interstory_drift": res.peak_interstory_drift.max(axis=1),
            "max_impact_force": res.max_impact_force,
            "max_indentation": res.max_indentation,
            "n_impacts": res.n_impacts.astype(np.int64), **flags}


# ------------------------------------------------------------------------------ statistics


def weighted_quantile(values, weights, q) -> np.ndarray:
    """Quantiles q (Q,) of values (R, ...) over axis 0 with weights (R,), (Q, ...): the
    weighted empirical distribution, its steps' midpoints interpolated (with equal weights,
    Hazen's (i - 1/2) / R)."""
    values = np.asarray(values, float)
    order = np.argsort(values, axis=0)
    ranked = np.take_along_axis(values, order, axis=0)
    w = np.asarray(weights, float)[order]
    position = (np.cumsum(w, axis=0) - w / 2) / w.sum(axis=0)
    flat_v = ranked.reshape(ranked.shape[0], -1)
    flat_p = position.reshape(position.shape[0], -1)
    out = np.array([[np.interp(x, flat_p[:, j], flat_v[:, j]) for j in range(flat_v.shape[1])]
                    for x in np.atleast_1d(q)])
    return out.reshape((len(np.atleast_1d(q)), *values.shape[1:]))


def weighted_fraction(condition, weights) -> np.ndarray:
    """The weighted fraction (-) of the records (axis 0) where condition holds."""
    w = np.asarray(weights, float)
    w = w.reshape((-1,) + (1,) * (np.ndim(condition) - 1))
    return (np.asarray(condition, bool) * w).sum(axis=0) / w.sum()


def statistics(peaks: dict, weights, bare: dict | None = None) -> dict[str, np.ndarray]:
    """Per level and member, (L, K) each, over the pairs (weights (R,)): the 16th, 50th and
    84th weighted percentiles of the largest peak floor acceleration (m/s^2); the weighted
    fractions uncrushed, within the stress limit, within both, and with contact; the number of
    pairs (unweighted) flagged by each validity flag; with `bare` (the bare wall at the gap,
    (R, L) peaks), the weighted fractions of all the pairs the member helps and hurts against
    it, and of those counted (contact in one of the two; pipeline.outcomes)."""
    from pipeline import outcomes, validity

    accel = peaks["peak_floor_accel"]
    q16, med, q84 = weighted_quantile(accel, weights, QUANTILES)
    over = peaks["invalid_bumper_stress"]
    out = {"p16_peak_floor_accel": q16, "median_peak_floor_accel": med,
           "p84_peak_floor_accel": q84,
           "fraction_uncrushed": weighted_fraction(~peaks["crushed"], weights),
           "fraction_within_stress": weighted_fraction(~over, weights),
           "fraction_within_limits": weighted_fraction(~over & ~peaks["crushed"], weights),
           "fraction_contact": weighted_fraction(peaks["n_impacts"] > 0, weights),
           "fraction_valid": weighted_fraction(~np.any([peaks[f] for f in OTHER_FLAGS],
                                                       axis=0), weights)}
    for name in validity.FLAGS:
        out[f"n_{name}"] = peaks[name].sum(axis=0)
    if bare is not None:
        effect = outcomes.effect(accel, bare["peak_floor_accel"][..., None])
        counted = outcomes.where_contact(peaks["n_impacts"], bare["n_impacts"][..., None])
        out["fraction_helped"] = weighted_fraction(counted & (effect == outcomes.HELPED),
                                                   weights)
        out["fraction_hurt"] = weighted_fraction(counted & (effect == outcomes.HURT), weights)
        out["fraction_counted"] = weighted_fraction(counted, weights)
    return out


def ranking(objective, secondary, n_bumpers, wall_k, feasible) -> np.ndarray:
    """(K,) rank of each feasible candidate (1 = best), 0 for the infeasible: by the objective,
    then the other statistic (the 84th percentile for the median, and back), then fewer
    bumpers (equal dynamics: the stiffness depends on n x area only), then the stiffer wall
    (k_w plays no part while the bumpers are uncrushed, and a stiff wall needs no special
    construction)."""
    order = [i for i in np.lexsort((-np.asarray(wall_k), n_bumpers, secondary, objective))
             if feasible[i]]
    rank = np.zeros(len(feasible), dtype=int)
    rank[order] = np.arange(1, len(order) + 1)
    return rank


def judge(stats, criteria: Criteria, n_bumpers, wall_k) -> dict:
    """The candidates judged by the criteria from their statistics (name -> (L, K), as
    `statistics` returns or an archive holds): margins per constraint, feasible, objective
    and secondary (m/s^2), rank, and shortfall (the total of the missed margins, >= 0), (K,)
    each."""
    stats = {name: np.asarray(stats[name]) for name in STAT_TEXT}
    margins = criteria.margins(stats)
    feasible = np.all([m >= -1e-12 for m in margins.values()], axis=0)
    objective = criteria.objective_of(stats)
    other = stats["p84_peak_floor_accel" if criteria.objective == "median"
                  else "median_peak_floor_accel"][MCE]
    return {"margins": margins, "feasible": feasible, "objective": objective,
            "secondary": other, "rank": ranking(objective, other, n_bumpers, wall_k, feasible),
            "shortfall": -sum(np.minimum(m, 0) for m in margins.values())}


def rejudge(ds, criteria: Criteria) -> dict:
    """`judge` of an archive's candidates by other criteria (no run needed)."""
    return judge(ds, criteria, ds.n_bumpers.values, ds.wall_k.values)


# ------------------------------------------------------------------------------ the search


@dataclass
class Search:
    """The candidates evaluated so far: table (VARIABLES -> (K,)), stage (K,) (0: coarse
    grid, i: round i of the pattern search), peaks ((R, L, K) each), and what judges them."""

    problem: Problem
    criteria: Criteria
    bounds: Bounds
    gap: float
    strain: float
    bare: dict
    table: dict = field(default_factory=lambda: {v: np.zeros(0) for v in VARIABLES})
    stage: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    peaks: dict | None = None

    def add(self, table: dict, stage: int) -> int:
        """Evaluate the candidates of `table` not evaluated yet; how many were new. Candidates
        with the same dynamics (t, c, n x area, k_w) run once."""
        new, seen = [], set()
        for i in range(len(table["thickness"])):
            key = _key(row(table, i))
            if key not in seen and self.index(row(table, i)) is None:
                new.append(i)
                seen.add(key)
        if not new:
            return 0
        part = {v: np.asarray(table[v], float)[new] for v in VARIABLES}
        keys = [_dynamics(row(part, i)) for i in range(len(new))]
        unique = list(dict.fromkeys(keys))
        first = {k: keys.index(k) for k in unique}
        runs = self.problem.run(bumper_members(
            {v: part[v][[first[k] for k in unique]] for v in VARIABLES}, self.gap, self.strain))
        back = [unique.index(k) for k in keys]
        runs = {name: values[:, :, back] for name, values in runs.items()}
        self.table = {v: np.concatenate([self.table[v], part[v]]) for v in VARIABLES}
        self.stage = np.concatenate([self.stage, np.full(len(new), stage)])
        self.peaks = runs if self.peaks is None else {
            name: np.concatenate([self.peaks[name], runs[name]], axis=2) for name in runs}
        return len(new)

    def index(self, config: dict) -> int | None:
        """The candidate equal to config, or None."""
        same = np.ones(self.stage.size, dtype=bool)
        for v in VARIABLES:
            same &= np.isclose(self.table[v], config[v], rtol=1e-9, atol=0)
        hits = np.flatnonzero(same)
        return int(hits[0]) if hits.size else None

    def judged(self) -> dict:
        """`judge` of every candidate, with its statistics ("stats")."""
        stats = statistics(self.peaks, self.problem.suite.weights, self.bare)
        return {"stats": stats, **judge(stats, self.criteria, self.table["n_bumpers"],
                                        self.table["wall_k"])}

    def best(self) -> int:
        """The best feasible candidate, else the closest to feasible (least total shortfall,
        then the objective)."""
        j = self.judged()
        if np.any(j["rank"] == 1):
            return int(np.flatnonzero(j["rank"] == 1)[0])
        return int(np.lexsort((j["objective"], j["shortfall"]))[0])

    def refine(self, rounds: int, quiet: bool = True) -> int:
        """The pattern search (module docstring) from the best; the rounds run."""
        level, best = 0, self.best()
        for done in range(1, rounds + 1):
            self.add(neighbours(row(self.table, best), level, self.bounds), stage=done)
            moved = self.best()
            if not quiet:
                print(f"design: round {done}, step 1/{2 ** level}, {self.stage.size} "
                      f"candidates, best {describe(self.table, moved)}", flush=True)
            if moved == best:  # nothing better one step away: finer steps
                if level == FINEST:
                    return done
                level += 1
            else:  # a better one: a longer step again (a compass search's expansion)
                level = max(level - 1, 0)
            best = moved
        return rounds


def _key(config: dict) -> tuple:
    return tuple(float(f"{config[v]:.9g}") for v in VARIABLES)


def _dynamics(config: dict) -> tuple:
    """What the engine sees of a layout: t, c, n x area, k_w (rounded)."""
    t = config["thickness"]
    area = (4 * config["shape_factor"] * t) ** 2
    return tuple(float(f"{x:.9g}") for x in (t, config["cavity_ratio"] * t,
                                             config["n_bumpers"] * area, config["wall_k"]))


# ---------------------------------------------------------------------- the optimum's nature


@dataclass(frozen=True)
class Nature:
    """Where the optimum lies: bounds, [{variable, side, value, kind ("physical" | "grid"),
    why, indifferent}] for each variable without an evaluated neighbour on a side
    (indifferent: the neighbour on the other side scores the same, so the bound only breaks a
    tie); active, [{variable, side, neighbour, fails}] for each evaluated neighbour that fails
    a constraint."""

    bounds: tuple
    active: tuple

    @property
    def interior(self) -> bool:
        """No bound holds the optimum where it is (ties broken at a bound do not)."""
        return all(b["indifferent"] for b in self.bounds)

    def text(self) -> str:
        held = [b for b in self.bounds if not b["indifferent"]]
        flat = [b for b in self.bounds if b["indifferent"]]
        if not held:
            head = "interior: evaluated neighbours on both sides in every variable that matters"
        else:
            head = "at a bound: " + "; ".join(
                f"{b['variable']} at its {b['side']} bound {_value(b['variable'], b['value'])}"
                + (f" (physical: {b['why']})" if b["kind"] == "physical" else
                   " (the evaluated grid's edge: the optimum may lie beyond the grid)")
                for b in held)
        if flat:
            head += "; indifferent: " + "; ".join(
                f"{b['variable']} (the same statistics on the other side; the tie goes to "
                f"its {b['side']} bound {_value(b['variable'], b['value'])})" for b in flat)
        if self.active:
            head += "; active constraints: " + "; ".join(
                f"{a['variable']} {_value(a['variable'], a['neighbour'])} fails "
                f"{', '.join(a['fails'])}" for a in self.active)
        return head

    def as_dict(self) -> dict:
        return {"interior": self.interior, "bounds": list(self.bounds),
                "active": list(self.active)}


def nature(table: dict, best: int, bounds: Bounds, fails=None, scores=None) -> Nature:
    """Where candidate `best` of `table` (VARIABLES -> (K,)) lies: for each variable, the
    evaluated candidates equal to it in every other variable; a side without one is a bound,
    physical when the value sits on the bound `bounds` sets there (Bounds.limits), else the
    grid's edge. fails: (K,) lists of the constraints each candidate fails, for the neighbours
    that keep the optimum where it is; scores: (K, m) what ranks the candidates (a bound
    whose inward neighbour scores the same is indifferent). None: not given."""
    config = row(table, best)
    limits = bounds.limits(config)
    found, active = [], []
    for name in VARIABLES:
        others = np.ones(len(table[name]), dtype=bool)
        for v in VARIABLES:
            if v != name:
                others &= np.isclose(table[v], config[v], rtol=1e-9, atol=0)
        values = np.asarray(table[name], float)
        nearest = {}
        for sign in (-1, 1):
            beyond = others & ((values - config[name]) * sign > 1e-9 * abs(config[name]))
            if beyond.any():
                nearest[sign] = int(np.flatnonzero(beyond)[np.argmin(
                    np.abs(values[beyond] - config[name]))])
        for side, sign, (bound, why) in (("lower", -1, limits[name][0]),
                                         ("upper", 1, limits[name][1])):
            if sign in nearest:
                k = nearest[sign]
                if fails is not None and fails[k]:
                    active.append({"variable": name, "side": side,
                                   "neighbour": float(values[k]), "fails": list(fails[k])})
                continue
            on = _on_bound(name, config[name], bound, sign)
            inward = nearest.get(-sign)
            flat = bool(scores is not None and inward is not None and np.allclose(
                scores[inward], scores[best], rtol=1e-12, atol=0))
            found.append({"variable": name, "side": side, "value": config[name],
                          "kind": "physical" if on else "grid", "why": why if on else "",
                          "indifferent": flat})
    return Nature(tuple(found), tuple(active))


def _on_bound(name: str, value: float, bound: float, sign: int) -> bool:
    """Whether value sits on the bound: within rounding, or (a count) one more would pass it."""
    if name == "n_bumpers":
        return value + sign > bound + 1e-9 if sign > 0 else value + sign < bound - 1e-9
    return abs(value - bound) <= 1e-5 * max(abs(bound), 1e-12)


def _value(name: str, value: float) -> str:
    units = VARIABLES[name][0]
    if name == "wall_k":
        return f"{value / KN_PER_MM:g} kN/mm"
    if name == "n_bumpers":
        return f"{int(round(value))}"
    return f"{value:.4g} m" if units == "m" else f"{value:.4g}"


# ------------------------------------------------------------------------------ compute


def default_pairs(quick: bool) -> list[str]:
    from pipeline.records import pair_names

    return list(QUICK_PAIRS) if quick else pair_names("far-field")


def shape_range(args) -> tuple[float, float]:
    """--shape-factor as (lo, hi); SweepError unless 0 < lo <= hi."""
    from pipeline.errors import SweepError

    lo, hi = args.shape_factor
    if not 0 < lo <= hi:
        raise SweepError(f"--shape-factor needs 0 < LO <= HI, got {lo:g} {hi:g}")
    return float(lo), float(hi)


def design_gap(args, design) -> float:
    """The gap (m): --gap-cm, --gap-dm x D_M, or GAP_FRACTION x D_M."""
    from pipeline.errors import SweepError

    if args.gap_cm is not None:
        gap = args.gap_cm * CM
    else:
        gap = (GAP_FRACTION if args.gap_dm is None else args.gap_dm) * design.d_m
    if not gap > 0:
        raise SweepError(f"the gap must be positive, got {gap:g} m")
    return gap


def compute(args):
    import engine
    from pipeline import validity
    from pipeline.errors import SweepError, resolve_pairs
    from pipeline.target import isolation_design

    from ._code_suite import code_suite
    from ._code_suite import describe as describe_suite

    crit = criteria(args)
    pairs, names = resolve_pairs(args.records or default_pairs(args.quick), args.records_dir)
    building = args.building
    try:
        suite = code_suite(pairs, names, building, args.rule, args.sms_g, args.sm1_g, args.tl,
                           args.dt)
    except ValueError as err:
        raise SweepError(str(err)) from err
    if not suite.pairs:
        raise SweepError("the scaling rule kept no pair: nothing to design for")
    if not args.quiet:
        print("design:", describe_suite(suite), flush=True)
    gap = design_gap(args, suite.design)
    strain = engine.impact.LAWS["bumper"].PARAMETERS.strain.default
    stress = validity.RUBBER_STRESS_LIMIT if args.stress_limit_mpa is None \
        else args.stress_limit_mpa * 1e6
    for name in ("stress_limit_mpa", "wall_length_m", "wall_capacity_mn"):
        value = getattr(args, name)
        if value is not None and not value > 0:
            raise SweepError(f"--{name.replace('_', '-')} must be positive, got {value:g}")
    # the code's displacement at the service level, by the procedure that gave D_M
    service = isolation_design(suite.site["s_m1"] * LEVELS["service"], building,
                               dashpot=suite.design.dashpot)
    bounds = Bounds(gap=gap, clearance=service.d_m,
                    usable_strain=usable_strain(strain, None if args.no_stress_limit
                                                else stress),
                    wall_length=args.wall_length_m, shape_factor=shape_range(args))
    if gap - bounds.clearance <= THICKNESS_MIN * bounds.usable_strain:
        raise SweepError(f"the gap {gap / CM:.3g} cm leaves no room for bumpers: they must "
                         f"leave D_S = {bounds.clearance / CM:.3g} cm clear (the code's "
                         "displacement at the service level)")
    linear = building.story_yield_force is None
    limits = validity.Limits(
        bumper_stress=stress,
        story_shear=validity.code_story_capacity(suite.design, building) if linear else None,
        wall_force=None if args.wall_capacity_mn is None else args.wall_capacity_mn * 1e6)
    problem = Problem(suite, building, engine.DEFAULT_DT if args.dt is None else args.dt,
                      args.moat, limits)
    problem.run_free()
    references = problem.run(reference_members(gap, suite.design.d_tm))
    bare = {name: values[:, :, 1] for name, values in references.items()}
    search = Search(problem, crit, bounds, gap, strain, bare)
    coarse = grid(QUICK if args.quick else COARSE, bounds)
    if not coarse["thickness"].size:
        raise SweepError("no layout of the grid fits the bounds: " + bounds.text())
    search.add(coarse, stage=0)
    if not args.quiet:
        print(f"design: coarse grid, {search.stage.size} candidates", flush=True)
    rounds = search.refine(QUICK_ROUNDS if args.quick else ROUNDS, quiet=args.quiet)
    return dataset(search, references, rounds, args)


# ------------------------------------------------------------------------------ the archive


def dataset(search: Search, references: dict, rounds: int, args):
    """The archive: every candidate and reference, per pair and level, with the statistics,
    the constraints, the ranking and the optimum's nature."""
    from pipeline.archive import labelled_dataset, variable
    from pipeline.provenance import common_attributes, plan_attributes, run_attributes

    from ._code_suite import archive_variables

    problem, suite = search.problem, search.problem.suite
    judged = search.judged()
    ref_stats = statistics(references, suite.weights, search.bare)
    table = search.table
    t = table["thickness"]
    members = bumper_members(table, search.gap, search.strain)
    data, coords, attrs = archive_variables(suite)
    coords.update({
        "record": variable("record", np.array(suite.names), "1", "record pair"),
        "level": variable("level", problem.levels, "1",
                          "intensity level: fraction of the MCE_R factors"),
        "level_name": variable("level", np.array(list(LEVELS)), "1", "intensity level"),
        "reference": variable("reference", np.array(REFERENCES), "1",
                              "reference designs: the building without wall; the bare wall "
                              "(linear law, k 2500 kN/mm, COR 0.5) at the gap; the code's "
                              "design, the bare wall at the clearance D_TM"),
    })
    for name, (units, long_name) in VARIABLES.items():
        coords[name] = variable("candidate", table[name], units, long_name)
    derived = {
        "cavity": ("m", "depth of the wall cavity holding each bumper", table["cavity_ratio"] * t),
        "side": ("m", "side of the square bumper, 4 S t", 4 * table["shape_factor"] * t),
        "bumper_area": ("m2", "contact area of one bumper", members.area),
        "clear_gap": ("m", "clear gap in front of the bumpers, gap - (t - c)",
                      members.contact.clear_gap),
        "delta_u": ("m", "crush limit min(strain t, t - c)", members.contact.delta_u),
        "stage": ("1", "0: the coarse grid; i: round i of the pattern search", search.stage),
    }
    for name, (units, long_name, values) in derived.items():
        data[name] = variable("candidate", values, units, long_name)
    dims = ("record", "level", "candidate")
    for name, values in search.peaks.items():
        data[name] = _peak_variable(dims, name, values)
        data[f"reference_{name}"] = _peak_variable(("record", "level", "reference"), name,
                                                   references[name])
    data["reference_gap"] = variable("reference", [np.inf, search.gap, suite.design.d_tm], "m",
                                     "the reference's gap (inf: no wall)")
    for name, values in judged["stats"].items():
        data[name] = _stat_variable(("level", "candidate"), name, values)
        data[f"reference_{name}"] = _stat_variable(("level", "reference"), name,
                                                   ref_stats[name])
    for name, margin in judged["margins"].items():
        data[f"margin_{name}"] = variable("candidate", margin, "1", f"how far inside the "
                                          f"{name} constraint (>= 0: met), fraction of the "
                                          "pairs' weight")
    data["feasible"] = variable("candidate", judged["feasible"].astype(np.int8), "1",
                                "1 where every constraint is met")
    data["objective"] = variable("candidate", judged["objective"], "m s-2",
                                 f"{OBJECTIVES[search.criteria.objective]} of the largest "
                                 "peak floor acceleration at the MCE_R")
    data["rank"] = variable("candidate", judged["rank"], "1", "rank among the feasible "
                            "candidates (1 = chosen; 0 = infeasible)")
    best = search.best()
    chosen = best if judged["feasible"][best] else -1
    found = nature(table, best, search.bounds, fails=_fails(judged),
                   scores=np.column_stack([judged["objective"], judged["secondary"]]))
    attrs.update(common_attributes("bumper design search (beyond the paper)"))
    attrs.update(run_attributes(problem.dt, problem.building))
    attrs.update(plan_attributes(problem.moat))
    attrs.update(
        design_gap=search.gap, design_gap_units="m", gap_over_D_M=search.gap / suite.design.d_m,
        objective=search.criteria.objective, criteria=search.criteria.text(),
        within_limits_required=search.criteria.within_limits,
        stress_limit_counted=int(search.criteria.stress_limit),
        service_contact_allowed=search.criteria.service_contact,
        hurt_design_allowed=search.criteria.hurt_design,
        validity_limits=problem.limits.describe(), bumper_stress_limit=problem.limits.bumper_stress,
        bounds=search.bounds.text(), usable_strain=search.bounds.usable_strain,
        wall_length=search.bounds.wall_length, D_S=search.bounds.clearance,
        search_rounds=rounds,
        chosen_candidate=chosen, closest_candidate=best,
        optimum_nature=found.text(), optimum_interior=int(found.interior),
        optimum_bounds=json.dumps(found.as_dict()),
        optimum=describe(table, best))
    return labelled_dataset(data, coords, attrs)


def _fails(judged) -> list[list[str]]:
    """(K,) the constraints each candidate fails."""
    margins = judged["margins"]
    return [[c for c in CRITERIA if margins[c][i] < -1e-12]
            for i in range(judged["objective"].size)]


def _peak_variable(dims, name, values):
    from pipeline import validity
    from pipeline.archive import variable

    if name in PEAKS:
        units, long_name = PEAKS[name]
        return variable(dims, values, units, long_name)
    if name == "crushed":
        return variable(dims, values.astype(np.int8), "1",
                        "1 where the bumpers are crushed beyond delta_u")
    return variable(dims, values.astype(np.int8), "1", f"1 where {validity.FLAGS[name]}")


STAT_TEXT = {
    "p16_peak_floor_accel": ("m s-2", "weighted 16th percentile over the pairs of the largest "
                                      "peak floor acceleration"),
    "median_peak_floor_accel": ("m s-2", "weighted median over the pairs of the largest peak "
                                         "floor acceleration"),
    "p84_peak_floor_accel": ("m s-2", "weighted 84th percentile over the pairs of the largest "
                                      "peak floor acceleration"),
    "fraction_uncrushed": ("1", "weighted fraction of the pairs with the bumpers uncrushed"),
    "fraction_within_stress": ("1", "weighted fraction of the pairs with the bumpers' contact "
                                    "stress within the limit"),
    "fraction_within_limits": ("1", "weighted fraction of the pairs with the bumpers "
                                    "uncrushed and within the stress limit"),
    "fraction_contact": ("1", "weighted fraction of the pairs with contact"),
    "fraction_valid": ("1", "weighted fraction of the pairs without a validity flag other than "
                            "the bumper stress (floor acceleration, story shear, wall force)"),
    "fraction_helped": ("1", "weighted fraction of all the pairs helped against the bare wall "
                             "at the gap (2% tolerance, where contact occurs)"),
    "fraction_hurt": ("1", "weighted fraction of all the pairs hurt against the bare wall at "
                           "the gap (2% tolerance, where contact occurs)"),
    "fraction_counted": ("1", "weighted fraction of the pairs with contact here or at the bare "
                              "wall at the gap (the pairs counted as helped, neutral or hurt)"),
}


def _stat_variable(dims, name, values):
    from pipeline import validity
    from pipeline.archive import variable

    if name in STAT_TEXT:
        units, long_name = STAT_TEXT[name]
        return variable(dims, values, units, long_name)
    flag = name.removeprefix("n_")
    return variable(dims, values, "1", f"number of pairs where {validity.FLAGS[flag]}")


# ------------------------------------------------------------------------------ reporting


def describe(table, i: int) -> str:
    """One candidate as a designer reads it."""
    t, r = float(table["thickness"][i]), float(table["cavity_ratio"][i])
    s = float(table["shape_factor"][i])
    return (f"{int(table['n_bumpers'][i])} x {4 * s * t / CM:.3g} cm square, t "
            f"{t / CM:.3g} cm (S {s:.3g}), cavity {r * t / CM:.3g} cm (c/t {r:.3g}), k_w "
            f"{float(table['wall_k'][i]) / KN_PER_MM:.4g} kN/mm")


def _line(label: str, ds, prefix: str, dim: str, i: int) -> list[str]:
    """Rows of the table for one candidate or reference, one per level."""
    lines = []
    for lev, name in enumerate(ds.level_name.values):
        def at(stat, lev=lev):
            return float(ds[f"{prefix}{stat}"].isel(level=lev, **{dim: i}))
        flagged = flagged_text(ds, prefix, dim, i, lev)
        lines.append(f"{label if lev == 0 else '':54.54s} {name:>7} "
                     f"{at('median_peak_floor_accel') / G:6.3f} "
                     f"{at('p16_peak_floor_accel') / G:6.3f}-"
                     f"{at('p84_peak_floor_accel') / G:<6.3f} "
                     f"{at('fraction_uncrushed'):7.0%} {at('fraction_within_stress'):6.0%} "
                     f"{at('fraction_contact'):7.0%} "
                     f"{at('fraction_helped'):6.0%} {at('fraction_hurt'):5.0%}  "
                     f"{flagged or '-'}")
    return lines


def flagged_text(ds, prefix: str, dim: str, i: int, level: int) -> str:
    """The pairs each validity flag counts for a candidate or reference at a level:
    'bumper_stress 3, story_shear 17' ('' when none)."""
    from pipeline import validity

    counts = {name: int(ds[f"{prefix}n_{name}"].isel(level=level, **{dim: i}))
              for name in validity.FLAGS}
    return ", ".join(f"{name.removeprefix('invalid_')} {n}" for name, n in counts.items() if n)


def table_lines(ds, best_few: int = 3) -> list[str]:
    """The chosen design (and the next ranks), the closest one if none is feasible, and the
    references, at every level, as text."""
    lines = [f"{'design':54s} {'level':>7} {'median':>6} {'16-84% (g)':>13} "
             f"{'uncrush':>7} {'stress':>6} {'contact':>7} {'helped':>6} {'hurt':>5}  "
             "flagged pairs"]
    rank = ds["rank"].values
    order = [int(i) for i in np.argsort(np.where(rank > 0, rank, 10 ** 9))[:best_few]
             if rank[i] > 0]
    if not order:
        order = [int(ds.attrs["closest_candidate"])]
        lines.append("no feasible candidate; the closest to feasible:")
    table = {v: ds[v].values for v in VARIABLES}
    for i in order:
        label = (f"#{rank[i]} " if rank[i] else "") + describe(table, i)
        lines += _line(label, ds, "", "candidate", i)
    for j, name in enumerate(REFERENCES):
        gap = float(ds.reference_gap[j])
        label = name + ("" if not np.isfinite(gap) else f" ({gap / CM:.3g} cm)")
        lines += _line(label, ds, "reference_", "reference", j)
    return lines


def check(ds) -> list[Verdict]:
    """The search's result, and the paper's advice on cavities (5.3), soft walls (5.5) and
    bumpers at narrow gaps (6) asked of the evaluated candidates."""
    for line in [f"design gap {float(ds.attrs['design_gap']) / CM:.3g} cm = "
                 f"{float(ds.attrs['gap_over_D_M']):.3g} D_M (D_M {ds.attrs['D_M'] / CM:.3g} "
                 f"cm, D_TM {ds.attrs['D_TM'] / CM:.3g} cm); {ds.sizes['record']} pairs; "
                 f"{ds.sizes['candidate']} candidates",
                 f"criteria: {ds.attrs['criteria']}", f"bounds: {ds.attrs['bounds']}",
                 *table_lines(ds), f"optimum: {ds.attrs['optimum_nature']}"]:
        print(line)
    return [_design_verdict(ds), _cavity_verdict(ds), _wall_verdict(ds), _narrow_verdict(ds)]


def _design_verdict(ds) -> Verdict:
    chosen = int(ds.attrs["chosen_candidate"])
    n_feasible = int(ds.feasible.sum())
    nature_text = ds.attrs["optimum_nature"]
    if chosen < 0:
        i = int(ds.attrs["closest_candidate"])
        fails = [c for c in CRITERIA if float(ds[f"margin_{c}"][i]) < -1e-12]
        over = int(ds.n_invalid_bumper_stress.isel(level=MCE, candidate=i))
        return Verdict("design", "A bumper layout meets the constraints at the gap",
                       f"none of {ds.sizes['candidate']} candidates does; the closest "
                       f"({ds.attrs['optimum']}) fails {', '.join(fails)}, its bumpers over "
                       f"the stress limit under {over} of {ds.sizes['record']} pairs at the "
                       f"MCE_R; {nature_text}", False,
                       {"closest": ds.attrs["optimum"], "fails": fails})
    over = int(ds.n_invalid_bumper_stress.isel(level=MCE, candidate=chosen))
    code = REFERENCES.index("code clearance D_TM")
    return Verdict("design", "A bumper layout meets the constraints at the gap",
                   f"{n_feasible} of {ds.sizes['candidate']} candidates do; the best, "
                   f"{ds.attrs['optimum']}, objective {float(ds.objective[chosen]) / G:.3g} g "
                   f"(the code's design at D_TM: "
                   f"{float(ds['reference_' + _stat(ds)][MCE, code]) / G:.3g} g); bumpers over "
                   f"the stress limit under {over} of {ds.sizes['record']} pairs at the MCE_R; "
                   f"flagged pairs at the MCE_R: "
                   f"{flagged_text(ds, '', 'candidate', chosen, MCE) or 'none'} (the code's "
                   f"design: {flagged_text(ds, 'reference_', 'reference', code, MCE) or 'none'})"
                   f"; optimum {nature_text}", True,
                   {"chosen": ds.attrs["optimum"], "objective": float(ds.objective[chosen]),
                    "optimum": json.loads(ds.attrs["optimum_bounds"])})


def _stat(ds) -> str:
    """The statistic the objective takes: median_peak_floor_accel or p84_peak_floor_accel."""
    return f"{ds.attrs['objective']}_peak_floor_accel"


def _paired(ds, name: str, low, high):
    """Pairs of candidates equal but in `name` (low vs high value): (objective at low,
    at high), (P,) each."""
    others = [v for v in VARIABLES if v != name]
    key = {tuple(np.round([float(ds[v][i]) for v in others], 9)): i
           for i in range(ds.sizes["candidate"]) if high(float(ds[name][i]))}
    pairs = [(i, key[k]) for i in range(ds.sizes["candidate"]) if low(float(ds[name][i]))
             and (k := tuple(np.round([float(ds[v][i]) for v in others], 9))) in key]
    obj = ds.objective.values
    return np.array([obj[i] for i, _ in pairs]), np.array([obj[j] for _, j in pairs])


def _compare(conclusion, claim, ds, name, low, high, what) -> Verdict:
    """A claim that `low` beats `high` in `name`, asked of every pair of candidates that differ
    only there: counted where the objective changes by more than the tolerance."""
    from pipeline import outcomes

    a, b = _paired(ds, name, low, high)
    effect = outcomes.effect(a, b)
    counted = int((effect != outcomes.NEUTRAL).sum())
    held = int((effect == outcomes.HELPED).sum())
    agrees = outcomes.judged("most", held, counted)
    return Verdict(conclusion, claim,
                   f"{what}: the objective lower in {held} of {counted} pairs of candidates "
                   f"differing only there and changing by more than "
                   f"{outcomes.TOLERANCE:.0%} ({a.size} pairs in all)", agrees,
                   {"pairs": int(a.size), "counted": counted, "held": held})


def _cavity_verdict(ds) -> Verdict:
    return _compare("5.3", "Bumpers set in cavities (using more of the rubber) lower the "
                    "responses", ds, "cavity_ratio", lambda r: r > 0, lambda r: r == 0,
                    "a cavity against none")


def _wall_verdict(ds) -> Verdict:
    lo, hi = float(ds.wall_k.min()), float(ds.wall_k.max())
    return _compare("5.5", "A flexible moat wall lowers the floor accelerations", ds, "wall_k",
                    lambda k: k == lo, lambda k: k == hi,
                    f"k_w {lo / KN_PER_MM:.4g} against {hi / KN_PER_MM:.4g} kN/mm")


def _narrow_verdict(ds) -> Verdict:
    from pipeline import outcomes

    i = int(ds.attrs["chosen_candidate"])
    if i < 0:
        return Verdict("6", "Bumpers reduce the floor accelerations at gaps narrow compared with "
                       "the displacement", "no feasible design to ask", None)
    at = {lev: (float(ds.fraction_helped[lev, i]), float(ds.fraction_hurt[lev, i]),
                float(ds.fraction_counted[lev, i])) for lev in (DESIGN, MCE)}
    helped, hurt, counted = at[MCE]
    agrees = outcomes.judged("most", helped, counted)
    return Verdict("6", "Bumpers reduce the floor accelerations at gaps narrow compared with "
                   "the displacement",
                   f"the chosen design against the bare wall at the gap, weighted pairs where "
                   f"contact occurs: at the MCE_R helped {helped:.0%}, hurt {hurt:.0%} of "
                   f"{counted:.0%} counted; at the design level helped {at[DESIGN][0]:.0%}, "
                   f"hurt {at[DESIGN][1]:.0%} of {at[DESIGN][2]:.0%}", agrees,
                   {"MCE_R": at[MCE], "design": at[DESIGN]})


def plot(ds):
    fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.8), layout="constrained")
    stress = bool(ds.attrs["stress_limit_counted"])
    within = ds["fraction_within_limits" if stress else "fraction_uncrushed"].isel(
        level=MCE).values
    obj = ds.objective.values / G
    feasible = ds.feasible.values.astype(bool)
    t = ds.thickness.values / CM
    for sel, marker in ((~feasible, "x"), (feasible, "o")):
        points = left.scatter(within[sel], obj[sel], c=t[sel], cmap="viridis", s=14,
                              vmin=t.min(), vmax=t.max(), marker=marker)
    fig.colorbar(points, ax=left, label="thickness (cm)")
    left.axvline(float(ds.attrs["within_limits_required"]), color="k", ls=":", lw=0.8,
                 label="required")
    stat = _stat(ds)
    for j, (name, ls) in enumerate(zip(REFERENCES[1:], ("--", "-."), strict=True), start=1):
        left.axhline(float(ds[f"reference_{stat}"].isel(level=MCE, reference=j)) / G,
                     color="k", ls=ls, lw=0.8, label=name)
    best = int(ds.attrs["closest_candidate"])
    left.plot(within[best], obj[best], marker="*", ms=13, color="C3", ls="none",
              label=("chosen" if feasible[best] else "closest (infeasible)"))
    left.set_xlabel(f"weighted fraction of pairs {'within limits' if stress else 'uncrushed'}"
                    " at the MCE_R")
    left.set_ylabel(f"{OBJECTIVES[ds.attrs['objective']]} largest peak floor accel. (g)")
    left.set_title("Candidates (o feasible, x infeasible)")
    left.legend(fontsize=6)
    rows = [("chosen" if feasible[best] else "closest", "", "candidate", best, "C3")]
    rows += [(name, "reference_", "reference", j, c)
             for j, (name, c) in enumerate(zip(REFERENCES, ("0.6", "C0", "C2"), strict=True))]
    x = np.arange(ds.sizes["level"])
    for k, (name, prefix, dim, i, color) in enumerate(rows):
        med, lo, hi = (ds[f"{prefix}{s}_peak_floor_accel"].isel(**{dim: i}).values / G
                       for s in ("median", "p16", "p84"))
        right.errorbar(x + (k - 1.5) * 0.15, med, yerr=[med - lo, hi - med], fmt="o",
                       color=color, capsize=2, label=name)
    right.set_xticks(x, [str(n) for n in ds.level_name.values])
    right.set_ylabel("largest peak floor acceleration (g): median, 16-84%")
    right.set_title("At each level")
    right.legend(fontsize=6)
    fig.suptitle(f"Bumper design at a {float(ds.attrs['design_gap']) / CM:.3g} cm gap "
                 f"({float(ds.attrs['gap_over_D_M']):.2g} D_M), {ds.sizes['record']} pairs; "
                 f"optimum {'interior' if ds.attrs['optimum_interior'] else 'at a bound'}")
    return fig


recipe = Recipe(
    name="design", figure="beyond the paper",
    summary="Bumper design search: thickness, cavity, count, size and wall stiffness judged at "
            "the service, design and MCE_R levels on code-scaled record pairs in plan, the "
            "stress limit and crushing as constraints, the code's clearance D_TM beside it",
    compute=compute, plot=plot, check=check, records=(), options=options,
    chosen=(f"gap {GAP_FRACTION:g} D_M; the 22 FEMA P695 far-field pairs as recorded (quick: "
            f"{', '.join(QUICK_PAIRS)}); coarse grid t 4-20 cm, c/t 0-0.4, 4-32 bumpers, S "
            "0.5-1.5, k_w 500 and 2500 kN/mm, then a pattern search; strain and COR the "
            f"law's defaults; wall length {WALL_LENGTH:g} m"))
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
