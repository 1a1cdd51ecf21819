"""The search of studies.design over its space (space.py: variables, bounds,
constraints; see design.py's docstring for what and why): the members a candidate runs, the
statistics weighted per earthquake, the judgement and ranking and the pattern search (Search);
the nature of its optimum is optimum.py's. No files, no figures: the recipe in design.py runs
it and writes its archive."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from engine.units import CM, KN_PER_MM
from pipeline.assess.derived import crushed, largest_floor_accel, largest_story_drift
from pipeline.assess.derived import quantity as derived_quantity
from pipeline.assess.outcomes import QUANTILES, weighted_quantiles
from pipeline.motions.code_suite import LEVELS

from .space import (
    FINEST,
    MCE,
    OTHER_FLAGS,
    VARIABLES,
    Bounds,
    Criteria,
    neighbours,
    row,
)

assert tuple(LEVELS) == ("service", "design", "MCE_R")


# ---------------------------------------------------------------------- running the members


@dataclass(frozen=True)
class Members:
    """Walls to run, K of them: contact (engine.Contact, for their clear gaps); columns: the
    same walls as a table of listed members (pipeline.listed: law and parameters, (K,) each);
    n_bumpers, area, thickness (K,) for the stress and strain (inf, 1 and inf for a bare wall:
    no bumper stress or strain)."""

    contact: object
    columns: dict
    n_bumpers: np.ndarray
    area: np.ndarray
    thickness: np.ndarray


def bumper_members(table: dict, gap: float, strain: float, shape_k: float = 0.0) -> Members:
    """The candidates of a table (VARIABLES -> (K,)) as bumpers at the gap (m), of a rubber
    whose stiffness scales with the pad's shape by the factor shape_k (the bumper law's
    Gent-Lindley k; 0: the paper's Eq. 11). The shape factor S of the table is the law's
    sqrt(area) / (4 t) of the pads: side 4 S t."""
    import engine

    t = table["thickness"]
    side = 4 * table["shape_factor"] * t
    cavity = table["cavity_ratio"] * t
    contact = engine.Contact.bumper(gap, thickness=t, cavity=cavity,
                                    n_bumpers=table["n_bumpers"].astype(int),
                                    k_w=table["wall_k"], strain=strain, area=side ** 2,
                                    shape_k=shape_k)
    k = t.size
    columns = {"law": np.full(k, "bumper"), "gap": np.full(k, gap, dtype=float),
               "thickness": t, "cavity": cavity, "n_bumpers": table["n_bumpers"],
               "wall_k": table["wall_k"], "strain": np.full(k, strain), "area": side ** 2,
               "shape_k": np.full(k, float(shape_k))}
    return Members(contact, columns, table["n_bumpers"].astype(float), side ** 2, t)


def reference_members(gap: float, d_tm: float) -> Members:
    """REFERENCES: no wall, the bare wall (the linear law at its defaults) at the gap and at
    the code's clearance D_TM (m)."""
    import engine

    contact = engine.Contact.concat([engine.Contact.none(1), engine.Contact.linear([gap, d_tm])])
    columns = {"law": np.array(["none", "linear", "linear"]),
               "gap": np.array([np.nan, gap, d_tm])}
    return Members(contact, columns, np.full(3, np.inf), np.ones(3), np.full(3, np.inf))


@dataclass
class Problem:
    """What every run shares: the scaled suite (pipeline.motions.code_suite.CodeSuite), the
    building,
    dt s, the moat, the validity limits (pipeline.assess.validity.Limits), how and where the runs go
    (options: pipeline.sweep's workers, scheduler, quiet, work_dir); `free` holds the building
    without wall per pair and level (filled by `run_free`), `swept` its sweep's Dataset (whose
    provenance the archive keeps)."""

    suite: object
    building: object
    dt: float
    moat: str
    limits: object
    levels: np.ndarray = field(default_factory=lambda: np.array(list(LEVELS.values())))
    free: dict | None = None
    options: dict = field(default_factory=dict)
    swept: object = None

    def run(self, members: Members) -> dict[str, np.ndarray]:
        """Every member at every level under every pair: PEAKS, `crushed` and the validity
        flags, (R, L, K) each, on the pipeline's executor (resumable from the work folder,
        here or on dask). A member whose clear gap the building without wall never reaches
        at a level is that level's free run (no wall: the same member as in `run_free`, so
        the work folder holds it and it is not run again)."""
        n_l, k = self.levels.size, len(members.contact)
        reach = members.contact.clear_gap[None, None, :] <= self.free["reach"][:, :, None]
        ds = self._sweep(_listed(members.columns, reach, self.levels))
        shape = (len(self.suite.pairs), n_l, k)
        peaks = _peaks(ds, shape, self.building, self.limits, members.n_bumpers,
                       members.area, members.thickness)
        peaks["crushed"] = crushed(peaks["max_indentation"], members.contact.delta_u)
        return peaks

    def run_free(self) -> None:
        """The building without wall per pair and level (`free`, (R, L) each), and `reach`:
        the largest displacement toward a wall (per direction for a rectangular moat), m."""
        n_l = self.levels.size
        ds = self._sweep({"law": np.full(n_l, "none"), "level": self.levels})
        shape = (len(self.suite.pairs), n_l)
        peaks = _peaks(ds, shape, self.building, self.limits, np.full(n_l, np.inf),
                       np.ones(n_l), np.full(n_l, np.inf))
        peaks["crushed"] = np.zeros(shape, dtype=bool)
        peaks["reach"] = (ds.peak_isolator_disp_xy.max("direction").values
                          if self.moat == "rectangular" else
                          ds.peak_isolator_disp.values).reshape(shape)
        self.free, self.swept = peaks, ds

    def _sweep(self, table: dict):
        import pipeline

        options = {**self.options, "dt": self.dt, "building": self.building}
        return pipeline.sweep(self.suite.pairs, moat=self.moat, members=table,
                              factors=self.suite.factors, **options)


def _listed(columns: dict, reach: np.ndarray, levels: np.ndarray) -> dict:
    """The table (pipeline.listed) of every member (columns (K,)) at every level, (R, L x K)
    for reach (R, L, K): where False, no wall at that level instead (the free run)."""
    r, n_l, k = reach.shape
    table = {}
    for name, values in columns.items():
        values = np.broadcast_to(np.asarray(values)[None, None, :], reach.shape)
        unset = "none" if name == "law" else np.nan
        table[name] = np.where(reach, values, unset).reshape(r, n_l * k)
    table["level"] = np.repeat(levels, k)
    return table


def _peaks(ds, shape: tuple, building, limits, n_bumpers, area,
           thickness) -> dict[str, np.ndarray]:
    """PEAKS, the validity flags and how each run ended (collapse_mode, int8: the engine's
    codes, engine.results.COLLAPSE_MODES; 0 for every run of a building that cannot collapse)
    of a sweep's Dataset over (record, member), each shaped `shape` (the members split as the
    caller listed them)."""
    from pipeline.assess import validity

    peaks = {name: ds[name].values.reshape(*shape, *ds[name].shape[2:]) for name in
             ("peak_total_accel", "peak_interstory_drift", "max_impact_force",
              "peak_isolator_disp", "max_indentation", "n_impacts", "collapsed",
              "collapse_mode") if name in ds}
    flags = validity.flags_of(peaks, building, limits, n_bumpers=n_bumpers, area=area,
                              thickness=thickness)
    return {"peak_floor_accel": largest_floor_accel(peaks["peak_total_accel"]),
            "peak_isolator_disp": peaks["peak_isolator_disp"],
            "peak_interstory_drift": largest_story_drift(peaks["peak_interstory_drift"]),
            "max_impact_force": peaks["max_impact_force"],
            "max_indentation": peaks["max_indentation"],
            "n_impacts": peaks["n_impacts"].astype(np.int64), **flags,
            "collapse_mode": peaks.get("collapse_mode", np.zeros(shape, np.int8))}


# ------------------------------------------------------------------------------ statistics


def weighted_fraction(condition, weights) -> np.ndarray:
    """The weighted fraction (-) of the records (axis 0) where condition holds."""
    w = np.asarray(weights, float)
    w = w.reshape((-1,) + (1,) * (np.ndim(condition) - 1))
    return (np.asarray(condition, bool) * w).sum(axis=0) / w.sum()


def statistics(peaks: dict, weights, bare: dict | None = None) -> dict[str, np.ndarray]:
    """Per level and member, (L, K) each, over the pairs (weights (R,)): the 16th, 50th and
    84th weighted percentiles of the largest peak floor acceleration (m/s^2); the weighted
    fractions uncrushed, within the stress limit, within both (and standing), and with contact
    (a collapsed run: infinite acceleration, never within the limits); the number of
    pairs (unweighted) flagged by each validity flag, and those collapsed by each mode
    (n_invalid_collapse_by_mode, (modes, L, K): pipeline.assess.collapse_modes, from the
    peaks' collapse_mode); with `bare` (the bare wall at the gap,
    (R, L) peaks), the weighted fractions of all the pairs the member helps and hurts against
    it, and of those counted (contact in one of the two; pipeline.assess.outcomes)."""
    from pipeline.assess import outcomes, validity
    from pipeline.assess.collapse_modes import mode_counts

    # A collapsed run is a collapse: the worst floor acceleration there is in the quantiles
    # (never its peak before the collapse), and in the comparison with the bare wall it is
    # hurt or helped by the collapse itself (pipeline.assess.outcomes.with_collapse).
    collapsed = peaks["invalid_collapse"]
    accel = np.where(collapsed, np.inf, peaks["peak_floor_accel"])
    q16, med, q84 = weighted_quantiles(accel, weights, QUANTILES)
    over = peaks["invalid_bumper_stress"]
    out = {"p16_peak_floor_accel": q16, "median_peak_floor_accel": med,
           "p84_peak_floor_accel": q84,
           "fraction_uncrushed": weighted_fraction(~peaks["crushed"], weights),
           "fraction_within_stress": weighted_fraction(~over, weights),
           "fraction_within_limits": weighted_fraction(
               ~over & ~peaks["crushed"] & ~peaks["invalid_collapse"], weights),
           "fraction_contact": weighted_fraction(peaks["n_impacts"] > 0, weights),
           "fraction_valid": weighted_fraction(~np.any([peaks[f] for f in OTHER_FLAGS],
                                                       axis=0), weights)}
    for name in validity.FLAGS:
        out[f"n_{name}"] = peaks[name].sum(axis=0)
    out["n_invalid_collapse_by_mode"] = mode_counts(peaks["collapse_mode"], axis=0)
    if bare is not None:
        effect = outcomes.with_collapse(
            outcomes.effect(peaks["peak_floor_accel"], bare["peak_floor_accel"][..., None]),
            collapsed, bare["invalid_collapse"][..., None])
        counted = outcomes.where_contact(peaks["n_impacts"], bare["n_impacts"][..., None])
        out["fraction_helped"] = weighted_fraction(counted & (effect == outcomes.HELPED),
                                                   weights)
        out["fraction_hurt"] = weighted_fraction(counted & (effect == outcomes.HURT), weights)
        out["fraction_counted"] = weighted_fraction(counted, weights)
    return out


def ranking(objective, secondary, n_bumpers, wall_k, feasible) -> np.ndarray:
    """(K,) rank of each feasible candidate (1 = best), 0 for the infeasible: by the objective,
    then the other statistic (the 84th percentile for the median, and back), then fewer
    bumpers (equal statistics: larger pads do what more of them do), then the stiffer wall
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
    shape_k: float = 0.0
    table: dict = field(default_factory=lambda: {v: np.zeros(0) for v in VARIABLES})
    stage: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    peaks: dict | None = None

    def add(self, table: dict, stage: int) -> int:
        """Evaluate the candidates of `table` not evaluated yet; how many were new. Candidates
        with the same dynamics and flags (t, c, n x area, shape ratio, k_w) run once."""
        new, seen = [], set()
        for i in range(len(table["thickness"])):
            key = _key(row(table, i))
            if key not in seen and self.index(row(table, i)) is None:
                new.append(i)
                seen.add(key)
        if not new:
            return 0
        part = {v: np.asarray(table[v], float)[new] for v in VARIABLES}
        keys = [_dynamics(row(part, i), self.shape_k) for i in range(len(new))]
        unique = list(dict.fromkeys(keys))
        first = {k: keys.index(k) for k in unique}
        runs = self.problem.run(bumper_members(
            {v: part[v][[first[k] for k in unique]] for v in VARIABLES}, self.gap, self.strain,
            self.shape_k))
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

    def best(self, judged: dict | None = None) -> int:
        """The best feasible candidate, else the closest to feasible (least total shortfall,
        then the objective); judged: self.judged() if already at hand."""
        j = self.judged() if judged is None else judged
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


def _dynamics(config: dict, shape_k: float = 0.0) -> tuple:
    """What the engine and the flags see of a layout: t, c, n x area (the stress), the
    stiffness's shape ratio (the bumper law's; with n x area, k_imp), k_w (rounded)."""
    from engine.impact import LAWS

    t = config["thickness"]
    area = (4 * config["shape_factor"] * t) ** 2
    ratio = float(LAWS["bumper"].compression_ratio(config["shape_factor"], shape_k))
    return tuple(float(f"{x:.9g}") for x in (t, config["cavity_ratio"] * t,
                                             config["n_bumpers"] * area, ratio,
                                             config["wall_k"]))


ACCEL = derived_quantity("peak_floor_accel").units  # of the floor acceleration statistics
STAT_TEXT = {
    "p16_peak_floor_accel": (ACCEL, "weighted 16th percentile over the pairs of the largest "
                                      "peak floor acceleration"),
    "median_peak_floor_accel": (ACCEL, "weighted median over the pairs of the largest peak "
                                         "floor acceleration"),
    "p84_peak_floor_accel": (ACCEL, "weighted 84th percentile over the pairs of the largest "
                                      "peak floor acceleration"),
    "fraction_uncrushed": ("1", "weighted fraction of the pairs with the bumpers uncrushed"),
    "fraction_within_stress": ("1", "weighted fraction of the pairs with the bumpers' contact "
                                    "stress within the limit"),
    "fraction_within_limits": ("1", "weighted fraction of the pairs with the bumpers "
                                    "uncrushed and within the stress limit, and the building "
                                    "standing"),
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


def describe(table, i: int, shape_k: float | None = None) -> str:
    """One candidate as a designer reads it; with the rubber's shape_k (the bumper law's), what
    its pads' stiffness is of the paper's Eq. 11 (their shape ratio)."""
    from engine.impact import LAWS

    t, r = float(table["thickness"][i]), float(table["cavity_ratio"][i])
    s = float(table["shape_factor"][i])
    ratio = "" if shape_k is None else \
        f", k_st {float(LAWS['bumper'].compression_ratio(s, shape_k)):.3g} x Eq. 11's"
    return (f"{int(table['n_bumpers'][i])} x {4 * s * t / CM:.3g} cm square, t "
            f"{t / CM:.3g} cm (S {s:.3g}{ratio}), cavity {r * t / CM:.3g} cm (c/t {r:.3g}), "
            f"k_w {float(table['wall_k'][i]) / KN_PER_MM:.4g} kN/mm")
