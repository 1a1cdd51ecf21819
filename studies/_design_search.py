"""The search of studies.design (see its docstring for what and why): the candidates'
variables and grids, the physical bounds (Bounds) and the user's constraints (Criteria), the
members a candidate runs, the statistics weighted per earthquake, the judgement and ranking,
the pattern search (Search) and the nature of its optimum, interior or at a named bound
(Nature). No files, no figures: the recipe in design.py runs it and writes its archive."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from engine.units import CM, KN_PER_MM
from pipeline.outcomes import weighted_quantiles

from ._code_suite import LEVELS

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
    q16, med, q84 = weighted_quantiles(accel, weights, QUANTILES)
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


def describe(table, i: int) -> str:
    """One candidate as a designer reads it."""
    t, r = float(table["thickness"][i]), float(table["cavity_ratio"][i])
    s = float(table["shape_factor"][i])
    return (f"{int(table['n_bumpers'][i])} x {4 * s * t / CM:.3g} cm square, t "
            f"{t / CM:.3g} cm (S {s:.3g}), cavity {r * t / CM:.3g} cm (c/t {r:.3g}), k_w "
            f"{float(table['wall_k'][i]) / KN_PER_MM:.4g} kN/mm")
