"""Beyond the paper: do bumpers help across code-scaled record pairs, and do the paper's
conclusions hold as the paper words them?

The paper draws its conclusions from four records. This recipe runs the paper's building in
plan (coupled isolators, a square moat by default: --moat) under the FEMA P695 far-field record
pairs, scaled to a site's MCE_R spectrum by a code's rule (studies._code_suite: ASCE 7-22
chapter 17 by default, --rule p695 or the labelled "displacement" option), at three intensity
levels (the service level, a third of the MCE_R; the design earthquake, two thirds; the MCE_R).
The moat's clear gap is a fraction of the code's D_M (0.4 to 1.2, GAPS) and the code's
minimum clearance D_TM. At each gap the paper's bumpers (5 cm, Fig. 19's 4, 8, 16, 32 per side
against each of Fig. 21's three wall stiffnesses) are compared with the bare wall at the same
gap (the paper's linear law); the building without wall runs once per pair and level. Every pair
runs every level and configuration in one batched engine call (per-member scale factors).

Counting (pipeline.outcomes, SPEC section 6): with bumpers against the bare wall, each
(pair, level, gap) point is HELPED (amplification with / without below 1 - 2%), NEUTRAL (within
2%, exact ties included) or HURT (above 1 + 2%), and counted only where contact occurs in at
least one of the two configurations; elsewhere the two runs are the same unconstrained run and
the point is "no contact", never a tie or harm. Pairs are weighted per earthquake
(record_weight: 1 / the pairs of the same earthquake, normalised to sum to the number of
pairs), in every share, quantile and verdict.

Validity (pipeline.validity): every run is checked against the model's range (the bumpers'
contact stress against the rubber's 30.9 MPa, the largest floor acceleration against 5 g, a
linear story's shear against the code's superstructure capacity, the wall's force against a
capacity if given); the flags are stored per run (`invalid_*`, `bare_invalid_*`,
`free_invalid_*`). Runs outside the range are kept in the helped / neutral / hurt shares, the
amplification quantiles and the verdicts, with their number stated: the share of each cell's
pairs with a run outside (`counted_outside_range`) and, in every verdict, the runs outside and
the verdict's fraction without them. Leaving them out of the statistics instead would keep
the mild cases only (a pounding hard enough to matter is the one that leaves the range), and
bias every median towards the bumpers' harm.

Verdicts: each of the paper's conclusions with its quantifier as the paper wrote it ("for all
examined excitations": every pair; "in most cases": more than half of the counted cases where
the quantity changes by more than the tolerance; "almost all": ALMOST_EVERY of them; "may",
"can": one case at least; a claim without quantifier is read as stated in its text), the
fraction it holds for, and "agrees" only when the quantifier holds. Comparisons are made only
between configurations where something happens (contact, crushing).
"""
from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np

from engine.impact import LAWS
from engine.units import CM, KN_PER_MM
from pipeline.outcomes import (
    ALMOST_EVERY,
    HELPED,
    HURT,
    NEUTRAL,
    TOLERANCE,
    amplification,
    effect,
    judged,
    weighted_quantiles,
)

from ._code_suite import LEVELS, archive_variables, code_suite, describe, site_options
from ._paper import FIG19_COUNTS, FIG21_WALL_KS, N_BUMPERS, THICKNESS, WALL_K
from ._plot import plt
from ._recipe import Recipe, Verdict, verdict

_BUMPER = LAWS["bumper"].PARAMETERS  # the paper's bumpers: the law's own area and strain
AREA, STRAIN = _BUMPER.area.default, _BUMPER.strain.default
DELTA_U = STRAIN * THICKNESS
"""m: the crush limit of the paper's bumpers, 0.8 x 5 cm (no cavity)."""
GAPS = (0.4, 0.5, 0.6, 0.8, 1.0, 1.2)
"""Clear gaps as fractions of D_M; the code's clearance D_TM is added among them. Below 0.6:
the nonlinear building in plan reaches a median 0.6 D_M at the MCE_R (the code's D_M counts
the isolators' hysteresis only, not the model's isolation dashpot), so that contact happens at
the narrower gaps; 0.4 D_M leaves 5.5 cm in front of the 5 cm bumpers."""
QUICK_GAPS = (0.4, 0.6)
QUICK_LEVELS = ("design", "MCE_R")
QUICK_COUNTS = (4, 32)
QUICK_PAIRS = 4
PEAKS = ("peak_isolator_disp", "peak_total_accel", "peak_interstory_drift", "max_impact_force",
         "max_indentation", "n_impacts")
"""The engine's peaks the archive keeps for every run (plan: resultants)."""
PREFIX = {"bumpers": "", "bare": "bare_", "free": "free_"}
"""Archive prefix of each configuration's variables: bumpers, the bare wall, no wall."""
RESPONSES = {
    "base_accel": "peak base (isolation level) acceleration",
    "floor_accel": "largest peak floor acceleration (base included)",
    "interstory_drift": "largest peak interstory deflection",
}
QUANTILES = (0.16, 0.5, 0.84)
OUTCOMES = ("helped", "neutral", "hurt", "no_contact")
QUANTIFIER_TEXT = {
    "every": "at every counted case", "most": "at more than half the counted cases where it "
    "changes", "almost every": f"at {ALMOST_EVERY:.0%} at least of the counted cases where "
    "it changes", "some": "at one counted case at least"}


def options(p) -> None:
    site_options(p)
    p.add_argument("--moat", choices=("rectangular", "circular"), default="rectangular",
                   help="the moat in plan (default: rectangular, the same walls on every side)")
    p.add_argument("--wall-capacity-mn", type=float, default=None, metavar="MN",
                   help="the moat wall's lateral capacity in MN, for the validity flag "
                        "invalid_wall_force (default: none, not checked)")


def default_pairs(quick: bool) -> list[str]:
    """The FEMA P695 far-field pairs (quick: the first QUICK_PAIRS)."""
    from pipeline.records import pair_names

    names = pair_names("far-field")
    return names[:QUICK_PAIRS] if quick else names


@dataclass(frozen=True)
class Grid:
    """What every pair runs. level_names (L,) and levels (L,): fractions of the MCE_R;
    fractions (G,) of D_M, ascending, and gaps (G,) m; code_gap: the index of the code's
    clearance D_TM among them (None: not in the grid); counts (N,) bumpers per side; wall_ks
    (K,) N/m."""

    level_names: tuple
    levels: np.ndarray
    fractions: np.ndarray
    gaps: np.ndarray
    code_gap: int | None
    counts: tuple
    wall_ks: tuple

    @property
    def block(self) -> int:
        """Members per level: no wall, the bare wall per gap, the bumpers per (gap, n, k_w)."""
        return 1 + self.gaps.size * (1 + len(self.counts) * len(self.wall_ks))

    def members(self):
        """One level's engine.Contact, in the order of `block`."""
        import engine

        g, n, k = np.meshgrid(self.gaps, np.array(self.counts), np.array(self.wall_ks),
                              indexing="ij")
        return engine.Contact.concat([
            engine.Contact.none(1), engine.Contact.linear(self.gaps),
            engine.Contact.bumper(g.ravel(), thickness=THICKNESS, n_bumpers=n.ravel(),
                                  k_w=k.ravel())])

    def split(self, values) -> dict:
        """(R, L x block, ...) -> configuration -> free (R, L, ...), bare (R, L, G, ...),
        bumpers (R, L, G, N, K, ...)."""
        values = np.asarray(values)
        r, rest = values.shape[0], values.shape[2:]
        v = values.reshape(r, self.levels.size, self.block, *rest)
        n_g = self.gaps.size
        return {"free": v[:, :, 0], "bare": v[:, :, 1:1 + n_g],
                "bumpers": v[:, :, 1 + n_g:].reshape(r, self.levels.size, n_g,
                                                     len(self.counts), len(self.wall_ks), *rest)}


def make_grid(design, quick: bool) -> Grid:
    """The grid for the code's design (pipeline.target.IsolationDesign): the gaps GAPS x D_M
    and D_TM (which marks an existing fraction if it coincides with one)."""
    names = QUICK_LEVELS if quick else tuple(LEVELS)
    fractions = np.array(QUICK_GAPS if quick else GAPS, dtype=float)
    code = design.d_tm / design.d_m
    if not np.any(np.isclose(fractions, code)):
        fractions = np.sort(np.append(fractions, code))
    return Grid(names, np.array([LEVELS[n] for n in names]), fractions,
                fractions * design.d_m, int(np.argmin(abs(fractions - code))),
                QUICK_COUNTS if quick else FIG19_COUNTS, tuple(FIG21_WALL_KS))


def compute(args):
    from pipeline.errors import resolve_pairs
    from pipeline.validity import Limits, code_story_capacity

    pairs, names = resolve_pairs(args.records or default_pairs(args.quick), args.records_dir)
    suite = code_suite(pairs, names, args.building, args.rule, args.sms_g, args.sm1_g, args.tl,
                       args.dt)
    grid = make_grid(suite.design, args.quick)
    peaks = run(suite, grid, args)
    wall = None if args.wall_capacity_mn is None else args.wall_capacity_mn * 1e6
    limits = Limits(story_shear=code_story_capacity(suite.design, args.building),
                    wall_force=wall)
    ds = assemble(grid, peaks, suite.names, suite.weights, args.building, limits)
    data, coords, attrs = archive_variables(suite)
    attrs.update(moat=args.moat, suite=describe(suite))
    return ds.assign_coords(coords).assign(data).assign_attrs(attrs)


def run(suite, grid: Grid, args) -> dict:
    """Every pair at every level and configuration: one engine call per pair, its members the
    levels x `grid.block`, each scaled by the pair's MCE_R factor x the level; in this process
    (the kernel's threads on every core), or one task per pair on dask with --workers N >= 2 or
    --scheduler. Returns configuration -> peak name -> array (see Grid.split)."""
    import engine

    dt = engine.DEFAULT_DT if args.dt is None else args.dt
    members = engine.Contact.concat([grid.members()] * grid.levels.size)
    tasks = [(pair.accel, pair.dt, members, args.building, dt,
              np.repeat(factor * grid.levels, grid.block), args.moat)
             for pair, factor in zip(suite.pairs, suite.factors, strict=True)]
    if args.scheduler is None and args.workers <= 1:
        done = []
        for r, task in enumerate(tasks):
            if not args.quiet:
                print(f"suite: {r + 1}/{len(tasks)} {suite.names[r]}", flush=True)
            done.append(pair_peaks(*task))
    else:
        from pipeline.execute.dask_client import client

        if not args.quiet:
            print(f"suite: {len(tasks)} pairs on dask", flush=True)
        with client(args.workers, args.scheduler) as dask:
            done = dask.gather([dask.submit(pair_peaks, *task, pure=False) for task in tasks])
    split = {name: grid.split(np.stack([d[name] for d in done])) for name in PEAKS}
    return {config: {name: split[name][config] for name in PEAKS} for config in PREFIX}


def pair_peaks(accel, accel_dt, members, building, dt, scale, moat) -> dict:
    """PEAKS name -> (B, ...) of one pair (accel (N, 2) m/s^2 every accel_dt s) run in plan
    with the members (engine.Contact), each scaled by `scale` (B,)."""
    import engine

    result = engine.simulate(accel, accel_dt, members, building, dt, scale=scale, moat=moat)
    return {name: np.asarray(getattr(result, name)) for name in PEAKS}


# --- The archive: peaks, validity flags and statistics, from peaks (also hand-made ones). ---

DIMS = {"free": ("record", "level"), "bare": ("record", "level", "gap_fraction"),
        "bumpers": ("record", "level", "gap_fraction", "n_bumpers", "wall_k")}
CONFIG_TEXT = {"free": "without wall", "bare": "against the bare wall at the same gap (linear "
               "law, k 2500 kN/mm, COR 0.5)", "bumpers": "with the bumpers"}


def assemble(grid: Grid, peaks: dict, names, weights, building, limits):
    """The archive from the peaks: configuration (free, bare, bumpers) -> PEAKS name -> array
    shaped as Grid.split gives (SI: m, m/s^2 over the building's levels, m over its stories, N,
    m, impacts); names (R,) of the pairs; weights (R,) per earthquake; building: the
    engine.Building run; limits: pipeline.validity.Limits. Adds the validity flags, the
    bumpers' contact stress and the statistics (add_statistics)."""
    from engine.results import quantity
    from pipeline.archive import labelled_dataset, variable
    from pipeline.validity import FLAGS, flags, shape_factor

    data = {}
    for config, prefix in PREFIX.items():
        along = {"peak_total_accel": ("floor",), "peak_interstory_drift": ("story",)}
        for name in PEAKS:
            q = quantity(name)
            data[prefix + name] = variable(DIMS[config] + along.get(name, ()),
                                           peaks[config][name], q.units,
                                           f"{q.long_name} {CONFIG_TEXT[config]} (resultant)")
        n_bumpers = np.array(grid.counts, float)[:, None] if config == "bumpers" else None
        flagged = flags(peaks[config]["peak_total_accel"],
                        peaks[config]["peak_interstory_drift"],
                        peaks[config]["max_impact_force"], building.story_stiffness, limits,
                        n_bumpers=n_bumpers, area=AREA,
                        stories_yield=building.story_yield_force is not None)
        for name, value in flagged.items():
            data[prefix + name] = variable(DIMS[config], value.astype(np.int8), "1",
                                           f"1 where {FLAGS[name]} ({CONFIG_TEXT[config]})")
    data["bumper_stress"] = variable(
        DIMS["bumpers"], peaks["bumpers"]["max_impact_force"]
        / (np.array(grid.counts, float)[:, None] * AREA), "Pa",
        f"mean contact stress on each bumper ({AREA * 1e6:g} mm2) at the largest impact force")
    data["record_weight"] = variable("record", np.asarray(weights, float), "1",
                                     "the pair's weight: 1 / the pairs of the same earthquake, "
                                     "normalised to sum to the number of pairs")
    coords = {
        "record": variable("record", np.array(names), "1", "record pair"),
        "level": variable("level", np.array(grid.level_names), "1", "intensity level"),
        "level_factor": variable("level", grid.levels, "1", "the level as a fraction of the "
                                 "MCE_R: every pair's MCE_R factor times this"),
        "gap_fraction": variable("gap_fraction", grid.fractions, "1", "seismic gap / D_M"),
        "gap": variable("gap_fraction", grid.gaps, "m", "seismic gap (clear, before bumpers)"),
        "code_clearance": variable("gap_fraction", (np.arange(grid.fractions.size)
                                                    == grid.code_gap).astype(np.int8), "1",
                                   "1 at the code's minimum clearance D_TM"),
        "n_bumpers": variable("n_bumpers", np.array(grid.counts), "1",
                              f"bumpers of {THICKNESS / CM:g} cm on each side"),
        "wall_k": variable("wall_k", np.array(grid.wall_ks), "N m-1",
                           "moat-wall stiffness behind the bumpers"),
        "floor": variable("floor", np.arange(building.n_levels), "1", "level: 0 the base"),
        "story": variable("story", np.arange(1, building.n_stories + 1), "1", "story"),
    }
    counts = {prefix + name: int(np.sum(data[prefix + name].values))
              for prefix in PREFIX.values() for name in FLAGS}
    ds = labelled_dataset(data, coords, {
        "validity_limits": limits.describe(), "invalid_counts": json.dumps(counts),
        "runs": int(sum(np.prod(peaks[c]["n_impacts"].shape) for c in PREFIX)),
        "bumper_shape_factor": float(shape_factor(AREA, THICKNESS)),
        "bumper_crush_limit": DELTA_U, "story_capacity": limits.story_shear or "none",
        "statistics": STATISTICS_TEXT})
    ds["bumper_shape_factor"] = ((), float(shape_factor(AREA, THICKNESS)), {
        "units": "1", "long_name": "the bumpers' shape factor: loaded area / area free to "
        "bulge (side / (4 t))"})
    return add_statistics(ds)


STATISTICS_TEXT = (
    "with bumpers against the bare wall at the same gap: helped (amplification below 1 - 2%), "
    "neutral (within 2%, ties included), hurt (above 1 + 2%), pipeline.outcomes; counted only "
    "where contact occurs with the bumpers or the bare wall, else no_contact; pairs weighted "
    "per earthquake (record_weight); runs outside the model's range (invalid_*) kept in the "
    "shares, quantiles and verdicts, their number stated (counted_outside_range, and in each "
    "verdict with its fraction without them)")


def response(ds, name: str, config: str = "bumpers"):
    """The response `name` (RESPONSES, or "upper_accel": the largest over the floors above the
    base) of a configuration's runs."""
    prefix = PREFIX[config]
    accel = ds[prefix + "peak_total_accel"]
    return {"base_accel": lambda: accel.isel(floor=0),
            "floor_accel": lambda: accel.max("floor"),
            "upper_accel": lambda: accel.isel(floor=slice(1, None)).max("floor"),
            "interstory_drift": lambda: ds[prefix + "peak_interstory_drift"].max("story"),
            }[name]()


def contact(ds):
    """(record, level, gap_fraction, n_bumpers, wall_k) bool: the bumpers or the bare wall at
    the same gap are hit."""
    return (ds.n_impacts > 0) | (ds.bare_n_impacts > 0)


def outside(ds, config: str):
    """A configuration's runs outside the model's range (any invalid_* flag): a bool
    DataArray over the configuration's dims."""
    from functools import reduce

    from pipeline.validity import FLAGS

    prefix = PREFIX[config]
    return reduce(lambda a, b: a | b, [ds[prefix + name].astype(bool) for name in FLAGS])


def _with_without(ds, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The response `name` with the bumpers and against the bare wall at the same gap, both
    as arrays over DIMS["bumpers"]."""
    dims = DIMS["bumpers"]
    a = response(ds, name)
    return (a.transpose(*dims).values,
            response(ds, name, "bare").broadcast_like(a).transpose(*dims).values)


def add_statistics(ds):
    """Amplifications, effects, the weighted shares of helped / neutral / hurt / no contact,
    the weighted quantiles of the amplification over the pairs with contact, the share of
    those with a run outside the model's range, and the share
    of pairs whose bumpers are crushed."""
    from pipeline.archive import variable

    names = list(RESPONSES)
    dims = DIMS["bumpers"]
    pairs = [_with_without(ds, r) for r in names]
    amp = np.stack([amplification(a, b) for a, b in pairs])
    eff = np.stack([effect(a, b) for a, b in pairs])
    touch = contact(ds).transpose(*dims).values
    valid = ~(outside(ds, "bumpers") | outside(ds, "bare")).transpose(*dims).values
    w = ds.record_weight.values
    out = ds.assign_coords(
        response=variable("response", np.array(names), "1",
                          "; ".join(f"{k}: {v}" for k, v in RESPONSES.items())),
        outcome=variable("outcome", np.array(OUTCOMES), "1", "helped / neutral / hurt within "
                         "the tolerance where contact occurs, else no_contact"),
        quantile=variable("quantile", np.array(QUANTILES), "1", "quantile over the pairs"))
    out["amplification"] = variable(("response", *dims), amp, "1",
                                    "peak with bumpers / against the bare wall at the same gap")
    out["contact"] = variable(dims, touch.astype(np.int8), "1", "1 where the bumpers or the "
                              "bare wall at the same gap are hit")
    out["effect"] = variable(("response", *dims), np.where(touch, eff, 0).astype(np.int8), "1",
                             "-1 helped, 0 neutral or no contact (see contact), 1 hurt")
    out["outcome_share"] = variable(
        ("response", "outcome", *dims[1:]), _shares(eff, touch, w), "1",
        "weighted share of the pairs (record_weight) helped, neutral, hurt, or with no contact")
    out["amplification_quantile"] = variable(
        ("response", "quantile", *dims[1:]), _quantiles(amp, touch, w), "1",
        "weighted 16th, 50th, 84th percentiles of the amplification over the pairs with "
        "contact, runs outside the model's range included (see counted_outside_range; NaN: "
        "no contact)")
    out["quantile_pairs"] = variable(dims[1:], touch.sum(axis=0), "1",
                                     "pairs behind amplification_quantile")
    out["counted_outside_range"] = variable(
        dims[1:], _weighted_mean(~valid, touch, w), "1", "weighted share of the pairs with "
        "contact whose bumper or bare-wall run is outside the model's range (NaN: none)")
    crushed = (ds.max_indentation > DELTA_U).transpose(*dims).values
    out["fraction_crushed"] = variable(
        dims[1:], _weighted_mean(crushed, np.ones_like(crushed), w), "1",
        f"weighted share of the pairs whose bumpers are crushed beyond {DELTA_U / CM:g} cm")
    return out


def _weights(w, shape):
    """(R,) weights broadcast over (R, ...)."""
    return np.broadcast_to(np.reshape(w, (-1,) + (1,) * (len(shape) - 1)), shape)


def _weighted_mean(values, counted, w) -> np.ndarray:
    """Over axis 0 (records): the weighted share of `values` among the `counted`, NaN where
    nothing is counted."""
    ww = _weights(w, values.shape) * counted
    total = ww.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(total > 0, (ww * values).sum(axis=0) / total, np.nan)


def _shares(eff, touch, w) -> np.ndarray:
    """(response, outcome, ...) weighted shares of all pairs in each outcome (sum 1)."""
    ww = _weights(w, touch.shape)
    total = ww.sum(axis=0)
    out = []
    for e in eff:
        parts = [(ww * (touch & (e == k))).sum(axis=0) for k in (HELPED, NEUTRAL, HURT)]
        out.append(np.stack([*parts, (ww * ~touch).sum(axis=0)]) / total)
    return np.stack(out)


def _quantiles(amp, keep, w) -> np.ndarray:
    """(response, quantile, ...) weighted quantiles over the records (axis 1 of amp) at the
    points kept (records x cells)."""
    n_resp = amp.shape[0]
    cells = amp.shape[2:]
    out = np.full((n_resp, len(QUANTILES), *cells), np.nan)
    for r in range(n_resp):
        for cell in np.ndindex(*cells):
            k = keep[(slice(None), *cell)]
            out[(r, slice(None), *cell)] = weighted_quantiles(
                amp[(r, slice(None), *cell)][k], np.asarray(w)[k], QUANTILES)
    return out


# --- The paper's conclusions, each with its quantifier. ---

POINT = ("record", "level", "gap_fraction")  # a case: one pair at one level and gap


def runs(ds, n=None, k=None) -> dict:
    """One configuration's runs over (record, level, gap_fraction) as arrays: the bumpers (n,
    k) or, with n None, the bare wall. Keys: base, upper, floor, drift (responses), force,
    indentation, hit (bool), outside (name of the flag -> bool), outside_any (bool)."""
    from pipeline.validity import FLAGS

    config = "bare" if n is None else "bumpers"
    at = {} if n is None else {"n_bumpers": n, "wall_k": k}
    prefix = PREFIX[config]

    def get(value):
        return value.sel(**at).transpose(*POINT).values

    out = {key: get(response(ds, name, config)) for key, name in (
        ("base", "base_accel"), ("upper", "upper_accel"), ("floor", "floor_accel"),
        ("drift", "interstory_drift"))}
    out["force"] = get(ds[prefix + "max_impact_force"])
    out["indentation"] = get(ds[prefix + "max_indentation"])
    out["hit"] = get(ds[prefix + "n_impacts"]) > 0
    out["outside"] = {name: get(ds[prefix + name]).astype(bool) for name in FLAGS}
    out["outside_any"] = np.any(list(out["outside"].values()), axis=0)
    return out


@dataclass(frozen=True)
class Case:
    """A conclusion asked of the runs: held, counted (bool over POINT: the cases where what it
    speaks of happens) and changed (bool: the quantity changes beyond the tolerance; None for
    a yes/no claim); runs: the runs behind each case (dicts of `runs`: their flags "outside"
    and "outside_any" over POINT); by_record: judged per pair (it holds for a pair when it
    holds at every counted case of that pair)."""

    held: np.ndarray
    counted: np.ndarray
    changed: np.ndarray | None
    runs: tuple
    by_record: bool = False
    unit: str = "cases (pair, level, gap)"


def judge(conclusion, claim, quantifier, points, case: Case, weights, levels,
          extra="") -> Verdict:
    """The Verdict of a claim with the paper's quantifier over the counted cases (those that
    change, for "most" and "almost every"), pairs weighted per earthquake; the runs outside
    the model's range among them counted and stated, and the fraction without them."""
    weighted = _weights(weights, case.counted.shape)
    denominator = case.counted if case.changed is None or quantifier in ("every", "some") \
        else case.counted & case.changed
    flagged = denominator & np.any([r["outside_any"] for r in case.runs], axis=0)
    all_ = _held_counted(case, denominator, weighted, weights)
    kept = _held_counted(case, denominator & ~flagged, weighted, weights)
    h, n, units = all_
    unit = "pairs" if case.by_record else case.unit
    share = f"{h / n:.0%} (weighted) of {units} {unit}" if n else f"none of 0 {unit}"
    neutral = int((case.counted & ~denominator).sum())
    text = f"holds for {share} ({points})"
    if case.changed is not None and quantifier not in ("every", "some"):
        text += f"; {neutral} more within the {TOLERANCE:.0%} tolerance, not counted"
    text += "; " + _outside_text(case, denominator)
    if flagged.any():
        text += (f"; without them: {kept[0] / kept[1]:.0%} of {kept[2]}" if kept[1]
                 else "; without them: nothing left")
    agrees = judged(quantifier, h, n)
    by_level = {str(lv): [int((case.held & denominator)[:, i].sum()),
                          int(denominator[:, i].sum())] for i, lv in enumerate(levels)}
    return Verdict(conclusion, f"{claim} [{QUANTIFIER_TEXT[quantifier]}]", text + extra,
                   agrees, {"quantifier": quantifier, "counted_at": points,
                            "fraction": h / n if n else None, "held_weight": h,
                            "counted_weight": n, "counted": units, "unit": unit,
                            "not_counted_within_tolerance": neutral,
                            "fraction_inside_range": kept[0] / kept[1] if kept[1] else None,
                            "verdict_inside_range": verdict(judged(quantifier, kept[0],
                                                                   kept[1])),
                            "held_counted_by_level": by_level,
                            **_outside_numbers(case, denominator)})


def _held_counted(case: Case, denominator, weighted, weights) -> tuple[float, float, int]:
    """(weight held, weight counted, number counted) over cases, or over pairs (a pair holds
    when every counted case of it holds)."""
    held = case.held & denominator
    if case.by_record:
        axes = tuple(range(1, denominator.ndim))
        counted = denominator.any(axis=axes)
        ok = counted & ~(denominator & ~held).any(axis=axes)
        w = np.asarray(weights, float)
        return float(w[ok].sum()), float(w[counted].sum()), int(counted.sum())
    return (float(weighted[held].sum()), float(weighted[denominator].sum()),
            int(denominator.sum()))


def _outside_numbers(case: Case, denominator) -> dict:
    """The runs behind the counted cases (len(case.runs) per case) and those outside the
    model's range, in all and per flag (a run can carry several flags)."""
    kinds = {name: sum(int((denominator & r["outside"][name]).sum()) for r in case.runs)
             for name in case.runs[0]["outside"]}
    outside_runs = sum(int((denominator & r["outside_any"]).sum()) for r in case.runs)
    return {"runs": len(case.runs) * int(denominator.sum()),
            "runs_outside_range": outside_runs, "outside_by_flag": kinds}


def _outside_text(case: Case, denominator) -> str:
    """'N of M runs outside the model's range: ...'."""
    n = _outside_numbers(case, denominator)
    kinds = ", ".join(f"{k.removeprefix('invalid_').replace('_', ' ')} {v}"
                      for k, v in n["outside_by_flag"].items() if v)
    return (f"{n['runs_outside_range']} of {n['runs']} runs outside the model's range"
            + (f" ({kinds})" if kinds else ""))


def _paper_config(ds) -> tuple[int, float]:
    """The paper's bumpers (4) and wall (1500 kN/mm), or the nearest the grid has."""
    n = N_BUMPERS if N_BUMPERS in ds.n_bumpers else int(ds.n_bumpers.min())
    k = WALL_K if WALL_K in ds.wall_k else float(ds.wall_k[0])
    return n, k


def check(ds) -> list[Verdict]:
    """The paper's conclusions 5.1-5.6 and 6, each with the paper's quantifier, counted where
    what it speaks of happens; every verdict states its runs outside the model's range."""
    n_p, k_p = _paper_config(ds)
    w, levels = ds.record_weight.values, ds.level.values.tolist()
    paper, bare = runs(ds, n_p, k_p), runs(ds, None)
    touch = paper["hit"] | bare["hit"]
    out = []

    def add(conclusion, claim, quantifier, points, case, extra=""):
        out.append(judge(conclusion, claim, quantifier, points, case, w, levels, extra))

    floor = effect(paper["floor"], bare["floor"])
    add("5.1", "For wide gaps, where poundings would not occur without bumpers, bumpers "
        "increase the response (here: the largest peak floor acceleration; stated without "
        "quantifier, read as wherever it happens)", "every",
        f"cases where the {n_p} bumpers are hit and the bare wall is not",
        Case(floor == HURT, paper["hit"] & ~bare["hit"], None, (paper, bare)))
    base = effect(paper["base"], bare["base"])
    add("5.1", "For narrow gaps, under strong motions, bumpers can be beneficial (here: the "
        "peak base acceleration lower)", "some", "cases where the bare wall is hit",
        Case(base == HELPED, bare["hit"], None, (paper, bare)))
    ratio = effect(amplification(paper["base"], bare["base"]),
                   amplification(paper["upper"], bare["upper"]))
    add("5.1", "Bumpers are more beneficial for the base than for the floors above (the "
        "paper: 'suggest'; read as in most cases)", "most",
        "cases with contact: the base's amplification against the upper floors' largest",
        Case(ratio == HELPED, touch, ratio != NEUTRAL, (paper, bare)))
    drift = effect(paper["drift"], bare["drift"])
    add("5.1", "Interstory deflections are amplified by bumpers in most of the examined cases",
        "most", "cases with contact (bumpers or bare wall)",
        Case(drift == HURT, touch, drift != NEUTRAL, (paper, bare)))
    out += [_not_tested(ds, "5.2", "Bumper thickness hardly changes the response",
                        f"the suite keeps {THICKNESS / CM:g} cm (studies.design searches it)"),
            _not_tested(ds, "5.3", "A larger usable compression (strain, cavity) lowers the "
                        "responses", f"the suite keeps strain {STRAIN:g} and no cavity "
                        "(studies.design searches the cavity)")]
    out += _number_of_bumpers(ds, k_p, w, levels)
    softer, flexible = _wall_stiffness(ds, n_p, bare, w, levels)
    out += [softer, _not_tested(ds, "5.6", "The coefficient of restitution does not affect "
                                "the peaks", "the suite keeps the declared COR "
                                "(studies.restitution)"), flexible]
    force = effect(paper["force"], bare["force"])
    add("6", "Rubber bumpers may reduce the maximum impact force", "some",
        "cases where both the bumpers and the bare wall are hit",
        Case(force == HELPED, paper["hit"] & bare["hit"], None, (paper, bare)))
    out.append(narrow_more_effective(ds, paper, bare, w, levels))
    return out


def _number_of_bumpers(ds, k_p, w, levels) -> list[Verdict]:
    """5.4: more bumpers raise the peaks in almost all cases; with the most bumpers the
    indentation stays within delta_u for all examined excitations (every pair)."""
    from pipeline.validity import RUBBER_STRESS_LIMIT

    if ds.n_bumpers.size < 2:
        return [_not_tested(ds, "5.4", "The number of bumpers", "one count in the grid")]
    few, many = int(ds.n_bumpers.min()), int(ds.n_bumpers.max())
    a, b = runs(ds, many, k_p), runs(ds, few, k_p)
    more = effect(a["floor"], b["floor"])
    stress = ds.bumper_stress.sel(n_bumpers=many, wall_k=k_p).where(
        ds.n_impacts.sel(n_bumpers=many, wall_k=k_p) > 0)
    extra = (f"; their largest contact stress {float(stress.max()) / 1e6:.3g} MPa (limit "
             f"{RUBBER_STRESS_LIMIT / 1e6:.3g} MPa, shape factor "
             f"{float(ds.bumper_shape_factor):.2f}; a crushed bumper is always above the "
             "limit)" if bool(stress.notnull().any()) else "")
    return [
        judge("5.4", f"More bumpers raise the peak responses in almost all examined cases "
              f"(here: {many} rather than {few}, the largest peak floor acceleration)",
              "almost every", f"cases where the {few} or the {many} bumpers are hit",
              Case(more == HURT, a["hit"] | b["hit"], more != NEUTRAL, (a, b)), w, levels),
        judge("5.4", f"With {many} bumpers the indentation does not exceed the crush limit "
              f"({DELTA_U / CM:g} cm) for all examined excitations", "every",
              f"pairs whose {many} bumpers are hit at some level and gap; a pair holds when "
              "they are never crushed", Case(a["indentation"] <= DELTA_U, a["hit"], None, (a,),
                                            by_record=True), w, levels, extra)]


def _wall_stiffness(ds, n_p, bare, w, levels) -> list[Verdict]:
    """5.5: a softer wall lowers the peak floor accelerations (where the bumpers are crushed:
    only there does the wall behind them act); 6: with a flexible wall both floor
    accelerations and interstory deflections fall below those without bumpers."""
    if ds.wall_k.size < 2:
        return [_not_tested(ds, c, "The stiffness of the moat wall", "one k_w in the grid")
                for c in ("5.5", "6")]
    soft, stiff = float(ds.wall_k.min()), float(ds.wall_k.max())
    a, b = runs(ds, n_p, soft), runs(ds, n_p, stiff)
    lower = effect(a["floor"], b["floor"])
    crushed = (a["indentation"] > DELTA_U) | (b["indentation"] > DELTA_U)
    floor, drift = effect(a["floor"], bare["floor"]), effect(a["drift"], bare["drift"])
    return [
        judge("5.5", "A more flexible moat wall significantly reduces the peak floor "
              f"accelerations (here: k_w {soft / KN_PER_MM:g} rather than "
              f"{stiff / KN_PER_MM:g} kN/mm; stated without quantifier, read as in most "
              "cases)", "most", f"cases where the {n_p} bumpers are crushed with either wall "
              "(only there does the wall behind them act)",
              Case(lower == HELPED, crushed, lower != NEUTRAL, (a, b)), w, levels),
        judge("6", "With a relatively flexible moat wall both floor accelerations and "
              "interstory deflections are reduced compared with no bumpers (here: k_w "
              f"{soft / KN_PER_MM:g} kN/mm against the bare wall; read as in most cases)",
              "most", "cases with contact (bumpers or bare wall); changed: either quantity",
              Case((floor == HELPED) & (drift == HELPED), a["hit"] | bare["hit"],
                   (floor != NEUTRAL) | (drift != NEUTRAL), (a, bare)), w, levels)]


def narrow_more_effective(ds, paper, bare, w, levels) -> Verdict:
    """6: bumpers more effective at gaps narrow compared with the induced displacement. Per
    pair and level, among the gaps where contact occurs (bumpers or bare wall), the base
    amplification at the narrowest of them against the widest of them: never a gap where
    nothing is hit (amplification 1 by construction)."""
    amp = amplification(paper["base"], bare["base"])
    touch = paper["hit"] | bare["hit"]
    idx = np.arange(touch.shape[-1])
    has = touch.sum(axis=-1) >= 2
    narrow = np.where(touch, idx, idx.size).min(axis=-1).clip(max=idx.size - 1)
    wide = np.where(touch, idx, -1).max(axis=-1).clip(min=0)

    def at(values, where):
        return np.take_along_axis(values, where[..., None], axis=-1)[..., 0]

    narrower = effect(at(amp, narrow), at(amp, wide))

    def at_gap(r, where):  # a configuration's run flags at one chosen gap per (pair, level)
        flags = {k: _expand(at(v, where)) for k, v in r["outside"].items()}
        return {"outside": flags, "outside_any": np.any(list(flags.values()), axis=0)}

    case = Case(_expand(narrower == HELPED), _expand(has), _expand(narrower != NEUTRAL),
                tuple(at_gap(r, g) for r in (paper, bare) for g in (narrow, wide)),
                unit="cases (pair, level)")
    return judge("6", "Bumpers seem more effective for relatively narrow seismic gaps, "
                 "compared with the induced displacement (read as in most cases)", "most",
                 "(pair, level) with contact at two gaps at least: the base amplification at "
                 "the narrowest gap with contact lower than at the widest with contact", case,
                 w, levels)


def _expand(value) -> np.ndarray:
    """A (record, level) array as (record, level, 1): one case per pair and level."""
    return np.asarray(value)[..., None]


def _not_tested(ds, conclusion, claim, why) -> Verdict:
    """A conclusion the suite does not vary, with the count of all runs outside the range."""
    return Verdict(conclusion, claim, f"not tested: {why}; {_all_outside(ds)}", None,
                   {"all_runs_outside_range": _all_outside_numbers(ds)})


def _all_outside_numbers(ds) -> dict:
    """Runs of the whole archive (every configuration) and those outside the model's range."""
    total, bad = 0, 0
    for config in PREFIX:
        flagged = outside(ds, config)
        total, bad = total + flagged.size, bad + int(flagged.sum())
    return {"runs": total, "runs_outside_range": bad}


def _all_outside(ds) -> str:
    n = _all_outside_numbers(ds)
    return f"of all runs, {n['runs_outside_range']} of {n['runs']} outside the model's range"


# --- The figure. ---

def plot(ds):
    fig, axes = plt.subplots(2, 3, figsize=(13, 8), layout="constrained")
    top = "MCE_R" if "MCE_R" in ds.level.values else str(ds.level.values[-1])
    n_p, k_p = _paper_config(ds)
    for ax, name in zip(axes[0], RESPONSES, strict=True):
        _fan(ax, ds, name, top, n_p)
    axes[0, 0].set_ylabel("amplification (bumpers / bare wall)")
    axes[0, 0].legend(fontsize=6)
    net = _net(ds, "floor_accel").sel(level=top)
    rows = [(axes[1, 0], net.sel(wall_k=k_p).transpose("n_bumpers", "gap_fraction"),
             [str(n) for n in ds.n_bumpers.values], "bumpers per side",
             f"$k_w$ {k_p / KN_PER_MM:g} kN/mm"),
            (axes[1, 1], net.sel(n_bumpers=n_p).transpose("wall_k", "gap_fraction"),
             [f"{k / KN_PER_MM:g}" for k in ds.wall_k.values], "$k_w$ (kN/mm)",
             f"{n_p} bumpers")]
    touched = _touched(ds).sel(level=top)
    for ax, field, labels, ylabel, fixed in rows:
        share = touched.sel(wall_k=k_p) if ylabel.startswith("bumpers") \
            else touched.sel(n_bumpers=n_p)
        mesh = draw_map(ax, field.values, share.transpose(*field.dims).values)
        ax.set_yticks(range(len(labels)), labels)
        ax.set_xticks(range(ds.sizes["gap_fraction"]), _gap_labels(ds), fontsize=6)
        ax.set_ylabel(ylabel)
        ax.set_xlabel("gap / D_M")
        ax.set_title(f"(helped - hurt) / pairs with contact, largest floor accel.\n{top}, "
                     f"{fixed}; in each cell: % of the pairs with contact")
    bar = fig.colorbar(mesh, ax=axes[1, :2], shrink=0.8, ticks=[-1, -0.5, 0, 0.5, 1])
    bar.ax.set_yticklabels(["−1 all hurt", "−0.5", "0 neutral", "0.5", "1 all helped"])
    bar.ax.legend(handles=[no_contact_handle()], loc="upper center",
                  bbox_to_anchor=(0.5, -0.04), frameon=False, handlelength=1.5)
    _outcome_bars(axes[1, 2], ds, n_p, k_p)
    n = _all_outside_numbers(ds)
    fig.suptitle(f"{ds.sizes['record']} record pairs scaled by {ds.attrs.get('scaling_rule', '?')}"
                 f" (T_M {ds.attrs.get('T_M', np.nan):.2f} s, D_M "
                 f"{ds.attrs.get('D_M', np.nan) / CM:.1f} cm), in plan: "
                 f"{THICKNESS / CM:g} cm bumpers against the bare wall at the same gap; "
                 f"{n['runs_outside_range']} of {n['runs']} runs outside the model's range\n"
                 "(top: over the pairs with contact, hollow where most have a run outside the "
                 "model's range; pairs weighted per earthquake)")
    return fig


def _gap_labels(ds) -> list[str]:
    return [f"{f:.2f}" + ("\nD_TM" if c else "") for f, c in
            zip(ds.gap_fraction.values, ds.code_clearance.values, strict=True)]


def _fan(ax, ds, name, level, n_p):
    """Median and 16-84% of the amplification against the gap, one line per wall; hollow
    markers where most of the pairs with contact have a run outside the model's range."""
    x = ds.gap_fraction.values
    for k, color in zip(ds.wall_k.values, ("C0", "C1", "C2"), strict=False):
        at = {"level": level, "n_bumpers": n_p, "wall_k": k}
        q = ds.amplification_quantile.sel(response=name, **at)
        median = q.sel(quantile=0.5).values
        ax.fill_between(x, q.sel(quantile=0.16), q.sel(quantile=0.84), color=color, alpha=0.15,
                        lw=0)
        ax.plot(x, median, color=color, label=f"$k_w$ {k / KN_PER_MM:g} kN/mm")
        mostly_outside = ds.counted_outside_range.sel(**at).values > 0.5
        ax.plot(x[~mostly_outside], median[~mostly_outside], "o", color=color)
        ax.plot(x[mostly_outside], median[mostly_outside], "o", mfc="white", color=color)
    code = x[ds.code_clearance.values == 1]
    for c in code:
        ax.axvline(c, color="0.5", lw=0.8, ls=":")
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.set_xlabel("gap / D_M (dotted: D_TM)")
    ax.set_title(f"{RESPONSES[name]}\n{level}, {n_p} bumpers: weighted median, 16-84%")


def _net(ds, name):
    """(level, gap, n, k): (share helped - share hurt) / share with contact; NaN: no contact."""
    s = ds.outcome_share.sel(response=name)
    counted = 1 - s.sel(outcome="no_contact")
    return ((s.sel(outcome="helped") - s.sel(outcome="hurt")) / counted).where(counted > 0)


def _touched(ds):
    """(level, gap, n, k) weighted share of the pairs with contact."""
    return 1 - ds.outcome_share.sel(response="floor_accel", outcome="no_contact")


NO_CONTACT = {"facecolor": "0.88", "edgecolor": "0.55", "hatch": "////", "lw": 0}
OUTCOME_COLORS = {"helped": "tab:green", "neutral": "gold", "hurt": "tab:red",
                  "no_contact": "0.85"}


def no_contact_handle():
    """The legend handle of the cells where no pair touches the wall."""
    from matplotlib.patches import Patch

    return Patch(**NO_CONTACT, label="no contact")


def draw_map(ax, values, touched=None):
    """Cells of `values` (rows, gap columns) coloured from all hurt (-1, red) through neutral
    (0, yellow) to all helped (+1, green); NaN cells (no contact) grey and hatched; each cell
    with contact labelled with `touched` (share of the pairs with contact) in %. Returns the
    image, for the colour bar."""
    from matplotlib.patches import Rectangle

    masked = np.ma.masked_invalid(values)
    image = ax.imshow(masked, origin="lower", aspect="auto", vmin=-1, vmax=1, cmap="RdYlGn")
    for row, col in zip(*np.nonzero(np.ma.getmaskarray(masked)), strict=True):
        ax.add_patch(Rectangle((col - 0.5, row - 0.5), 1, 1, **NO_CONTACT))
    if touched is not None:
        for row, col in zip(*np.nonzero(~np.ma.getmaskarray(masked)), strict=True):
            ax.text(col, row, f"{touched[row, col]:.0%}", ha="center", va="center", fontsize=5)
    ax.grid(False)
    return image


def _outcome_bars(ax, ds, n_p, k_p):
    """Stacked weighted shares helped / neutral / hurt / no contact of the largest floor
    acceleration, per level and gap, the paper's bumpers."""
    s = ds.outcome_share.sel(response="floor_accel", n_bumpers=n_p, wall_k=k_p)
    n_g = ds.sizes["gap_fraction"]
    ticks, labels = [], []
    for i, level in enumerate(ds.level.values):
        x = i * (n_g + 1) + np.arange(n_g)
        bottom = np.zeros(n_g)
        for outcome in OUTCOMES:
            v = s.sel(level=level, outcome=outcome).values
            ax.bar(x, v, bottom=bottom, color=OUTCOME_COLORS[outcome], width=0.85,
                   label=outcome.replace("_", " ") if i == 0 else None,
                   **({"hatch": "////", "edgecolor": "0.55", "lw": 0}
                      if outcome == "no_contact" else {}))
            bottom += v
        ticks += list(x)
        labels += [f"{f:.2f}" for f in ds.gap_fraction.values]
        ax.text(x.mean(), 1.02, str(level), ha="center", fontsize=7)
    ax.set_xticks(ticks, labels, rotation=90, fontsize=5)
    ax.set_ylim(0, 1.22)
    ax.set_xlabel("gap / D_M, per level")
    ax.set_ylabel("weighted share of the pairs")
    ax.set_title(f"largest floor acceleration, {n_p} bumpers, $k_w$ {k_p / KN_PER_MM:g} "
                 f"kN/mm:\nhelped / neutral (±2%) / hurt / no contact")
    ax.legend(fontsize=6, loc="upper center", ncols=4, frameon=False)
    ax.grid(False)


recipe = Recipe(
    name="suite", figure="beyond the paper",
    summary="Do bumpers help across code-scaled record pairs? The FEMA P695 far-field pairs "
            "scaled to a site's MCE_R (ASCE 7-22 ch. 17), in plan, at the service, design and "
            "MCE_R levels, gaps at fractions of D_M and D_TM, 4-32 bumpers and three wall "
            "stiffnesses against the bare wall; the paper's conclusions with their quantifiers",
    compute=compute, plot=plot, check=check, records=(), options=options,
    chosen=(f"site S_MS 1.5 g, S_M1 0.9 g, T_L 8 s; levels service 1/3, design 2/3, MCE_R; "
            f"gaps {', '.join(map(str, GAPS))} D_M and D_TM; {THICKNESS / CM:g} cm bumpers, "
            f"strain {STRAIN:g}, no cavity; tolerance 2% (pipeline.outcomes); pairs weighted "
            f"per earthquake; 'almost all' = {ALMOST_EVERY:.0%} of the cases that change; "
            f"quick: {QUICK_PAIRS} pairs, levels {', '.join(QUICK_LEVELS)}, gaps "
            f"{', '.join(map(str, QUICK_GAPS))} D_M and D_TM, {QUICK_COUNTS[0]} and "
            f"{QUICK_COUNTS[1]} bumpers"),
    resumable=False)
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
