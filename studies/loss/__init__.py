"""Beyond the paper: the designer's decision between a wider moat and bumpers, on repair cost,
collapse and annual rates (FEMA P-58 by pelicun: pip install -e ".[loss]").

The building, pairs, scaling, gaps and barriers of studies.collapse (its archive gives each
configuration's collapse fragility: --collapse, or it runs first); every pair at stripes up to
1.5 x MCE_R (LEVELS) without wall, against the bare wall and with 4 to 32 bumpers a wall, in
plan. Per stripe and configuration (pipeline.assess.loss, FEMA P-58-1 chapters 5 to 7): a
joint lognormal of the peak floor accelerations and drift ratios fitted to every run that did
not collapse, SAMPLES realizations, damage to an office inventory (--inventory) of
--floor-area per floor, collapse from its fragility, repair cost (by component group) and
time; over a hazard curve (--hazard; default a documented second-order form) the expected
annual loss and the annual rates of contact, crushed bumpers and collapse (chapter 8). The
decision table: gap x barrier -> P(collapse | MCE_R), median repair cost at the MCE_R, EAL,
pounding per year.
"""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM
from pipeline.assess import annual_loss, derived, moat_damage
from pipeline.assess import hazard as hazards
from pipeline.assess import loss as p58

from ..common import collapse_ida as collapse
from ..common.paper import AREA, DELTA_U, THICKNESS
from ..common.recipe import Recipe, Verdict, provenance, run_options
from .basis import collapse_archive, same_basis
from .figure import caption, plot  # noqa: F401  (caption: the docs cite studies.loss.caption)
from .table import decision_table

LEVELS = (0.2, 0.4, 2 / 3, 1.0, 1.5)
"""The stripes, x MCE_R: a service level (a fifth of the MCE_R, a stated choice), 0.4, the
design earthquake (2/3, ASCE 7-22 section 11.4.5), the MCE_R and 1.5 x MCE_R."""
QUICK_LEVELS = (1.0, 1.5)
FLOOR_AREA = 900.0
"""Floor area per story, m^2 (a 30 m square plan: a stated choice)."""
PLAUSIBLE_FLOOR_AREA = (20.0, 1e5)
"""m^2: the floor area of one story a loss study takes (a stated range: a room to about the
largest floor plates built, 10 ha; 9,000,000 is most likely a slip)."""
QUICK_SAMPLES = 100
QUANTILES = (0.1, 0.5, 0.9)
"""The repair cost's and time's quantiles over the realizations."""
PEAKS = ("peak_total_accel_xy", "peak_interstory_drift_xy", "n_impacts", "max_indentation",
         "max_impact_force", "peak_total_accel", "peak_interstory_drift", "collapsed",
         "collapse_mode", "peak_isolator_disp")
MOAT_GROUP = "moat and isolation plane"
"""The component group of what pounding and the isolators' largest displacements damage
beyond FEMA P-58's inventory (pipeline.assess.moat_damage)."""


def options(p) -> None:
    collapse.options(p)
    p.add_argument("--collapse", metavar="ARCHIVE",
                   help="a collapse archive (python -m studies.collapse) of the same site, "
                        "bound, stories, moat and pairs: each configuration's collapse "
                        "fragility (default: the collapse study runs first)")
    p.add_argument("--hazard", metavar="CSV",
                   help="the site's hazard curve: a CSV table with the columns sa_g "
                        "(Sa(T_M), g) and annual_rate (1/yr); default: 1/"
                        f"{1 / hazards.MCE_R_RATE:.0f} per year at S_MT, log-log slope "
                        f"{hazards.SLOPE:.2f} there, flatter below (a documented default "
                        "shaped after a published site's, not this site's hazard)")
    p.add_argument("--inventory", metavar="CSV",
                   help="the building's components (the columns of the default "
                        "pipeline/data/office_inventory.csv: FEMA P-58 IDs, quantities per m^2 "
                        "or per story)")
    p.add_argument("--moat-inventory", metavar="CSV",
                   help="what the moat and the isolation plane hold, priced once pounding or "
                        "the isolators' displacement damage it (the columns of the default "
                        "pipeline/data/moat_inventory.csv: item, trigger, per, unit_cost in USD "
                        "2011, description; pipeline.assess.moat_damage)")
    p.add_argument("--floor-area", type=float, default=FLOOR_AREA, metavar="M2",
                   help=f"floor area per story, m^2 (default {FLOOR_AREA:g})")
    p.add_argument("--samples", type=int, default=None, metavar="N",
                   help=f"loss realizations per stripe and configuration (default "
                        f"{p58.SAMPLES}; {QUICK_SAMPLES} with --quick)")


def compute(args):
    from pipeline.errors import SweepError

    p58.pelicun()
    if args.samples is None:
        args.samples = QUICK_SAMPLES if args.quick else p58.SAMPLES
    if not 50 <= args.samples <= 100_000:
        raise SweepError(f"--samples must be 50 to 100000 realizations, got {args.samples}")
    low, high = PLAUSIBLE_FLOOR_AREA
    if not low <= args.floor_area <= high:
        raise SweepError(f"--floor-area {args.floor_area:g} m^2 is implausible for one story "
                         f"(outside [{low:g}, {high:g}] m^2); give the floor area of a story "
                         "in m^2")
    try:
        rows = p58.read_inventory(args.inventory)
    except ValueError as e:
        raise SweepError(f"--inventory: {e}") from None
    try:  # read again where the archive is made; refused here, before any compute
        moat_damage.read(args.moat_inventory)
    except ValueError as e:
        raise SweepError(f"--moat-inventory: {e}") from None
    unknown = p58.unknown_components(rows)
    if unknown:  # before any compute: pelicun would refuse them after the simulations
        raise SweepError(f"--inventory: {', '.join(unknown)}: not in FEMA P-58's fragility "
                         "database (pelicun's); give FEMA P-58 component IDs, as "
                         "pipeline/data/office_inventory.csv does")
    fragility, grid = collapse_archive(args)
    suite = collapse.oriented_suite(args)  # the collapse study's records, both orientations
    s_mt = float(suite.target.at(suite.design.t_m))
    try:
        curve = hazards.from_table(args.hazard) if args.hazard else hazards.default(s_mt)
    except ValueError as e:
        raise SweepError(f"--hazard: {e}") from None
    same_basis(fragility, suite)
    gaps = fragility.gap.values
    known = np.isclose(fragility.gap_fraction.values[:, None],
                       collapse.gap_fractions(suite.design, suite.building)[None]).any(axis=1)
    if not known.all() or list(fragility.record.values) != list(suite.names):
        raise SweepError("--collapse: the archive's gaps or pairs are not this study's (run "
                         "it with the same site, bound, stories and pairs)")
    counts = [int(b.split()[0]) for b in fragility.barrier.values[2:]]
    levels = np.array(QUICK_LEVELS if args.quick else LEVELS, dtype=float)
    peaks, swept = run(suite, levels, gaps, counts, args, grid)
    ds = dataset(suite, levels, gaps, counts, peaks, fragility, rows, curve, s_mt, args)
    taken = [] if grid is None else levels[np.isin(levels, grid.level.values)]
    return ds.assign_attrs({**provenance(swept), **ds.attrs, "stripes_from_collapse_grid": (
        ", ".join(f"{v:.3g}" for v in taken) + " x MCE_R: the collapse study's runs, run in "
        "this process (sweep_arguments: the stripes run here)" if len(taken) else "none")})


def run(suite, levels, gaps, counts, args, grid=None) -> tuple[dict, object]:
    """Every pair at every stripe without wall, against the bare wall and with the bumpers at
    every gap (pipeline.sweep, resumable, here or on dask): (PEAKS name -> (R, L, barrier,
    gap, ...) arrays, the barriers in the collapse grid's order; the sweep's Dataset). The
    stripes among the levels of `grid` (the collapse study's sweep of the same pairs, gaps and
    barriers, run in this process: collapse_ida.compute_with_grid) are taken from it, the
    same simulations; the others are run."""
    import pipeline

    done = np.zeros(levels.size, bool) if grid is None else np.isin(levels, grid.level.values)
    ds = grid
    if not done.all():
        ds = pipeline.sweep(suite.pairs, moat=args.moat, gap=gaps, thickness=THICKNESS,
                            n_bumpers=list(counts), baseline=True, unconstrained=True,
                            level=levels[~done], factors=suite.factors,
                            **{**run_options(args), "building": suite.building})
    # the levels run here, then those taken, put back in the stripes' order
    order = np.argsort(np.concatenate([np.flatnonzero(~done), np.flatnonzero(done)]))
    peaks = {}
    for name in PEAKS:
        parts = [] if done.all() else [by_barrier(ds, name, counts)]
        if done.any():
            parts.append(by_barrier(grid.sel(level=levels[done]), name, counts))
        peaks[name] = np.concatenate(parts, axis=1)[:, order]
    return peaks, ds


def by_barrier(ds, name: str, counts) -> np.ndarray:
    """(record, level, barrier, gap, ...) of a sweep with its unconstrained (no wall) and
    baseline (bare wall) blocks and the bumpers' block over n_bumpers = counts."""
    lead = ("record", "level", "gap")
    bare = ds["baseline_" + name]
    bare = bare.transpose(*lead, ...).values
    free = ds["unconstrained_" + name].transpose("record", "level", ...).values[:, :, None]
    bumpers = [ds[name].sel(n_bumpers=n).transpose(*lead, ...).values for n in counts]
    return np.stack([np.broadcast_to(free, bare.shape), bare, *bumpers], axis=2)


def dataset(suite, levels, gaps, counts, peaks, fragility, rows, curve, s_mt, args):
    """The archive: per stripe and configuration the runs used, the repair cost and time
    (mean and QUANTILES), P(collapse) and P(irreparable) of the realizations; per
    configuration the expected annual loss and the annual rates; the decision table's
    quantities."""
    from pipeline.archive import (
        collapse_mode_coords,
        collapse_mode_variable,
        labelled_dataset,
        variable,
    )
    from pipeline.assess.collapse_modes import collapse_numbers, mode_counts
    from pipeline.assess.validity import Limits, any_flag, code_story_capacity, flags_of
    from pipeline.motions.code_suite import describe
    from pipeline.suite_labels import archive_variables

    building = suite.building
    n_b, n_g = 2 + len(counts), gaps.size
    bumpers = np.array([np.inf, np.inf, *counts], float)[None, None, :, None]
    limits = Limits(story_shear=code_story_capacity(suite.basis.force_design, building),
                    wall_force=None)
    flat = {k: v for k, v in peaks.items() if not k.endswith("_xy")}
    flags = flags_of(flat, building, limits, n_bumpers=bumpers, area=AREA, thickness=THICKNESS)
    flagged, fell = any_flag(flags), peaks["collapsed"].astype(bool)
    # Every run that did not collapse enters the demand model, as computed (dropping those
    # outside the model's range took the hardest impacts out). Past its floor acceleration,
    # 5 g, a value is uncertain but past every acceleration-sensitive component's range (the
    # default inventory's highest damage states: medians up to 4.1 g; a test checks it).
    entered = ~fell  # (R, L, barrier, gap)
    past_limit = entered & flags["invalid_floor_accel"]  # a fall is no acceleration
    height = np.asarray(building.story_height, float)
    ratio = peaks["peak_interstory_drift_xy"] / height[:, None]
    acmr = fragility.acmr.transpose("barrier", "gap_fraction").values
    beta = fragility.beta_total.transpose("barrier", "gap_fraction").values
    groups = []
    for i, level in enumerate(levels):
        for b in range(n_b):
            for g in range(n_g):
                keep = entered[:, i, b, g]
                deviate = float(np.log(level / acmr[b, g]) / beta[b, g])
                groups.append(p58.Group(peaks["peak_total_accel_xy"][keep, i, b, g],
                                        ratio[keep, i, b, g], deviate))
    yield_drift = float(np.median(np.asarray(building.story_yield_drift) / height))
    if not args.quiet:
        print(f"FEMA P-58 losses by pelicun {p58.version()}: {len(groups)} stripes x "
              f"configurations, {args.samples} realizations each", flush=True)
    from pipeline.progress import Progress

    modelled = sum(len(group.pfa) >= p58.MIN_RUNS for group in groups)
    bar = Progress(modelled, quiet=args.quiet, label="FEMA P-58",
                   unit="stripes x configurations")
    out = p58.losses(groups, rows, stories=len(height), floor_area=args.floor_area,
                     yield_drift=yield_drift, samples=args.samples, seed=1,
                     progress=lambda: bar.advance(1))
    bar.close()
    shape = (levels.size, n_b, n_g)
    q = np.array(QUANTILES)
    p_c = out["collapse_probability"].reshape(shape)
    bounded = out["bounded"].reshape(shape)  # too few runs standing: at most the replacement
    weights = np.asarray(suite.weights, float)
    share = weights / weights.sum()  # each pair's share of the weight, per earthquake
    moat_rows = moat_damage.read(args.moat_inventory)
    moat_runs = moat_damage.costs(moat_rows, peaks, d_tm=suite.design.d_tm, delta_u=DELTA_U,
                                  bumpers=np.array([0.0, 0.0, *counts])[None, None, :, None],
                                  floor_area=args.floor_area)  # (items, R, L, B, G)
    moat = moat_damage.mean_given_no_collapse(moat_runs, entered, share)  # (items, L, B, G)
    # each realization given no collapse adds a standing run's moat cost (a bound holds it)
    moat_draws = moat_damage.realizations(moat_runs.sum(axis=0), entered, share,
                                          args.samples) * ~bounded[..., None]
    mean_cost, cost_q = annual_loss.mixture(
        out["repair_cost"].reshape(*shape, -1) + moat_draws, p_c, out["replacement_cost"], q)
    mean_time, time_q = annual_loss.mixture(out["repair_time"].reshape(*shape, -1), p_c,
                                            out["replacement_time"], q)
    median_cost = cost_q[QUANTILES.index(0.5)]
    by_group = np.concatenate([np.moveaxis(out["repair_cost_by_group"].reshape(
        *shape, -1, len(p58.COMPONENT_GROUPS)).mean(axis=-2), -1, 0),
        moat_draws.mean(axis=-1)[None]])
    contact = np.einsum("r,rlbg->lbg", share, (peaks["n_impacts"] > 0).astype(float))
    crushed = np.einsum("r,rlbg->lbg", share,
                        derived.crushed(peaks["max_indentation"], DELTA_U).astype(float))
    crushed[:, :2] = np.nan  # no bumpers
    sa = levels * s_mt
    eal = hazards.mean_annual(sa, mean_cost, curve)
    cost_draws = repair_cost_draws(fragility, suite, levels, entered, out,
                                   moat_runs.sum(axis=0) * ~bounded[None])  # (draw, L, B, G)
    eal_draws = annual_loss.annual_loss(sa, cost_draws, curve)  # (draw, barrier, gap)
    with np.errstate(invalid="ignore", divide="ignore"):
        eal_ratio = eal_draws / eal_draws[:, [names_of(fragility).index("bare wall")]]
    rate_contact = hazards.mean_annual(sa, contact, curve)
    rate_crushed = hazards.mean_annual(sa, crushed, curve)
    rate_collapse = hazards.lognormal_annual(acmr * s_mt, beta, curve)
    at_mce = int(np.argmin(np.abs(levels - 1.0)))
    names = names_of(fragility)
    conf = ("barrier", "gap_fraction")
    span = ("interval_bound",) + conf
    dims = ("level",) + conf
    rdims = ("record", "level") + conf
    data = {
        "repair_cost": variable(dims, mean_cost, "USD_2011", "mean repair cost, USD_2011 "
                                "(FEMA P-58 by pelicun; a collapse or an irreparable "
                                "residual drift costs the replacement)"),
        "repair_cost_interval": variable(
            ("interval_bound",) + dims, np.quantile(cost_draws, collapse.INTERVAL, axis=0),
            "USD_2011", f"the paired bootstrap's {collapse.INTERVAL[1] - collapse.INTERVAL[0]:.0%} "
            "interval of the mean repair cost, USD_2011 (pipeline.assess.annual_loss)"),
        "repair_cost_by_group": variable(
            ("component_group",) + dims, by_group, "USD_2011", "mean repair cost given no "
            "collapse, USD_2011, by component group (summing it)"),
        "moat_damage_cost": variable(
            ("moat_item",) + dims, moat, "USD_2011", "mean repair cost given no collapse of "
            "each item of the moat inventory, USD_2011 (over the standing runs, weighted per "
            "earthquake; the realizations draw whole runs: repair_cost_by_group's moat group "
            "is their mean; pipeline.assess.moat_damage)"),
        "repair_cost_quantile": variable(("quantile",) + dims, cost_q,
                                         "USD_2011", "repair cost quantiles over the "
                                         "realizations, USD_2011"),
        "repair_time": variable(dims, mean_time, "worker_day", "mean repair time, "
                                "worker_day (all floors at once: pelicun's parallel repair "
                                "time)"),
        "repair_time_quantile": variable(("quantile",) + dims, time_q,
                                         "worker_day", "repair time quantiles over the "
                                         "realizations, worker_day"),
        "loss_collapse_probability": variable(dims, p_c, "1", "P(collapse | stripe): the "
                                              "collapse fragility at the stripe"),
        "irreparable_probability": variable(dims, out["irreparable"].reshape(*shape, -1)
                                            .mean(axis=-1), "1", "share of the realizations "
                                            "irreparable by residual drift, given no "
                                            "collapse"),
        "contact_probability": variable(dims, contact, "1", "P(contact | stripe): the pairs' "
                                        "weighted share of runs with contact"),
        "crushed_probability": variable(dims, crushed, "1", "P(bumpers crushed | stripe) "
                                        "(NaN: no bumpers)"),
        "runs_used": variable(dims, entered.sum(axis=0).astype(np.int32), "1", "runs in the "
                              "demand model: every run that did not collapse"),
        "loss_bounded": variable(dims, bounded.astype(np.int8), "1", f"1 where fewer than "
                                 f"{p58.MIN_RUNS} runs stand: no demand model, the loss given "
                                 "no collapse taken at its upper bound, the replacement"),
        "runs_past_accel_limit": variable(dims, past_limit.sum(axis=0).astype(np.int32), "1",
                                          "runs_used with a floor acceleration past what the "
                                          "model represents (validity_limits), as computed"),
        "runs_collapsed": variable(dims, fell.sum(axis=0).astype(np.int32), "1",
                                   "runs that collapsed (replaced by the collapse fragility)"),
        "runs_collapsed_by_mode": variable(
            ("mode",) + dims, mode_counts(peaks["collapse_mode"], axis=0).astype(np.int32), "1",
            "runs_collapsed by how they collapsed (collapse_mode)"),
        "runs_outside_range": variable(dims, (flagged & entered).sum(axis=0).astype(np.int32),
                                       "1", "runs_used outside the model's range in any way "
                                       "(validity_limits says which), as computed"),
        "collapsed": variable(rdims, fell.astype(np.int8), "1", "1 where the run collapsed"),
        "collapse_mode": collapse_mode_variable(rdims, peaks["collapse_mode"]),
        "expected_annual_loss": variable(conf, eal, "USD_2011 yr-1", "expected annual loss, "
                                         "USD_2011 yr-1 (FEMA P-58-1 chapter 8 over the "
                                         "hazard curve)"),
        "expected_annual_loss_interval": variable(
            span, np.quantile(eal_draws, collapse.INTERVAL, axis=0), "USD_2011 yr-1",
            f"the paired bootstrap's {collapse.INTERVAL[1] - collapse.INTERVAL[0]:.0%} interval "
            "of the expected annual loss, USD_2011 yr-1 (the collapse study's resamplings of "
            "the earthquakes; pipeline.assess.annual_loss)"),
        "expected_annual_loss_ratio": variable(
            conf, eal / eal[[names.index("bare wall")]], "1", "expected annual loss over the "
            "bare wall's at the same gap"),
        "expected_annual_loss_ratio_interval": variable(
            span, np.quantile(eal_ratio, collapse.INTERVAL, axis=0), "1", f"the paired "
            f"bootstrap's {collapse.INTERVAL[1] - collapse.INTERVAL[0]:.0%} interval of "
            "expected_annual_loss_ratio (inside it, 1 is no difference)"),
        "expected_annual_loss_bound": variable(
            conf, np.where(bounded.any(axis=0), "at most", "exact"), "1", "exact, or 'at "
            "most': a stripe's loss given no collapse bounded by the replacement "
            "(loss_bounded)"),
        "annual_rate_contact": variable(conf, rate_contact, "yr-1", "mean annual frequency "
                                        "of contact (pounding)"),
        "annual_rate_crushed": variable(conf, rate_crushed, "yr-1", "mean annual frequency "
                                        "of crushed bumpers (NaN: no bumpers)"),
        "annual_rate_collapse": variable(conf, rate_collapse, "yr-1", "mean annual frequency "
                                         "of collapse (the collapse fragility over the hazard "
                                         "curve)"),
        "collapse_probability": variable(conf, fragility.collapse_probability.transpose(
            *conf).values, "1", "P(collapse | MCE_R) (studies.collapse; an upper bound where "
            "collapse_probability_bound says so)"),
        "collapse_probability_bound": variable(conf, fragility.collapse_probability_bound
                                               .transpose(*conf).values.astype(str), "1",
                                               "exact, or 'at most': S_CT above the highest "
                                               "level of the collapse study"),
        "acmr": variable(conf, acmr, "1", "the collapse fragility's median, x MCE_R: the "
                         "adjusted collapse margin ratio (studies.collapse)"),
        "beta_total": variable(conf, beta, "1", "the collapse fragility's dispersion "
                               "beta_TOT (studies.collapse)"),
        "median_repair_cost_mce": variable(conf, median_cost[at_mce],
                                           "USD_2011", "median repair cost at the MCE_R, USD_2011"),
        "hazard_sa": variable("hazard_point", curve.sa, "m s-2", "the hazard curve's Sa(T_M)"),
        "hazard_rate": variable("hazard_point", curve.rate, "yr-1", "the hazard curve's "
                                "annual rate of exceedance"),
        "record_weight": variable("record", weights, "1", "the pair's weight: 1 / the pairs "
                                  "of its earthquake"),
    }
    more, more_coords, attrs = archive_variables(suite)
    data.update(more)
    coords = {
        "record": variable("record", np.array(suite.names), "1", "record pair"),
        "level": variable("level", levels, "1", "intensity, x MCE_R"),
        "level_sa": variable("level", sa, "m s-2", "the stripe's median Sa(T_M)"),
        "barrier": variable("barrier", np.array(names), "1", "no wall, the bare wall, or n "
                            f"bumpers of {THICKNESS / CM:g} cm on each wall"),
        "gap_fraction": variable("gap_fraction", fragility.gap_fraction.values, "1",
                                 "seismic gap / D_M"),
        "gap": variable("gap_fraction", gaps, "m", "seismic gap"),
        "quantile": variable("quantile", q, "1", "quantile over the realizations"),
        "interval_bound": variable("interval_bound", np.array(collapse.INTERVAL), "1",
                                   "the bootstrap interval's bounds (quantiles of the draws)"),
        "component_group": variable("component_group", [*p58.COMPONENT_GROUPS, MOAT_GROUP], "1",
                                    "FEMA P-58 components by their demand, the replacement, or "
                                    "the moat inventory's items"),
        "moat_item": variable("moat_item", [r["item"] for r in moat_rows], "1",
                              "an item of the moat inventory (moat_inventory)"),
        **collapse_mode_coords(),
        **more_coords,
    }
    attrs.update({
        "moat": args.moat, "suite": describe(suite), "pelicun_version": p58.version(),
        "method": "FEMA P-58 (2018) intensity-based assessments at the stripes by pelicun "
                  "(pipeline.assess.loss), the expected annual loss and mean annual "
                  "frequencies over the hazard curve (pipeline.assess.hazard; FEMA P-58-1 "
                  "chapter 8); the demand model fitted to every run that did not collapse, "
                  "unweighted (pelicun takes no weights), those outside the model's range "
                  "with the demands computed (runs_outside_range); the intervals the collapse "
                  "study's paired bootstrap over the earthquakes carried through every stripe, "
                  "the repair cost given no collapse moved by the runs' own costs, relative "
                  "(pipeline.assess.annual_loss)",
        "hazard": curve.source, "floor_area": args.floor_area, "floor_area_units": "m2",
        "inventory": args.inventory or "pipeline/data/office_inventory.csv (default)",
        "moat_inventory_file": args.moat_inventory or "pipeline/data/moat_inventory.csv "
                                                      "(default)",
        "components": json.dumps({r["component"]: r["description"] for r in rows}),
        "moat_inventory": json.dumps({r["item"]: {"trigger": r["trigger"], "per": r["per"],
                                                  "unit_cost_usd_2011": r["unit_cost"],
                                                  "description": r["description"]}
                                      for r in moat_rows}),
        "replacement_cost": out["replacement_cost"],
        "replacement_cost_units": "USD_2011", "samples": args.samples,
        "replacement_time": out["replacement_time"], "replacement_time_units": "worker_day",
        "yield_drift_ratio": yield_drift, "irreparable_drift": json.dumps(
            {"median": p58.IRREPARABLE_DRIFT[0], "beta": p58.IRREPARABLE_DRIFT[1]}),
        "validity_limits": limits.describe(),
        "collapse_archive": args.collapse or "computed (studies.collapse)",
        "collapse_modes": json.dumps(collapse_numbers(peaks["collapse_mode"])),
        "levels": ", ".join(f"{v:.3g}" for v in levels) + " x MCE_R (stripes)"})
    return labelled_dataset(data, coords, attrs)


def names_of(fragility) -> tuple[str, ...]:
    """The barriers of a collapse archive, in its order."""
    return tuple(str(b) for b in fragility.barrier.values)


def repair_cost_draws(fragility, suite, levels, entered, out, moat) -> np.ndarray:
    """(draw, level, barrier, gap) each stripe's mean repair cost, USD_2011, under each of the
    collapse archive's resamplings of the earthquakes (pipeline.assess.annual_loss): its
    P(collapse | MCE_R) draws, the runs' own repair costs (out: p58.losses' on the groups of
    `dataset`, level by barrier by gap, each of the runs `entered` (R, L, B, G)), the moat's
    per run (moat (R, L, B, G), USD_2011, none where a stripe's loss is bounded)."""
    from pipeline.assess.collapse import resampled_weights

    run_cost = annual_loss.runs_in_place(out["run_repair_cost"], entered)
    model = out["repair_cost"].reshape(*entered.shape[1:], -1).mean(axis=-1)
    mce = fragility.collapse_probability_draws.transpose("draw", "barrier", "gap_fraction")
    draws = resampled_weights(suite.weights, suite.events, draws=mce.sizes["draw"])
    given = annual_loss.given_no_collapse(model, run_cost, entered, suite.weights, draws) \
        + np.nan_to_num(annual_loss.weighted_means(moat, entered, draws))
    beta = fragility.beta_total.transpose("barrier", "gap_fraction").values
    p_c = annual_loss.stripe_collapse(levels, mce.values, beta)
    return annual_loss.stripe_means(p_c, given, out["replacement_cost"])


def check(ds) -> list[Verdict]:
    """The paper's reading of Anagnostopoulos (1988) in a designer's terms: bumpers may
    reduce, in some cases, what pounding costs: the median repair cost at the MCE_R with
    bumpers below the bare wall's at the same gap, counted where the bare wall is hit at the
    MCE_R (pipeline.assess.outcomes.count, 'may')."""
    from pipeline.assess.outcomes import TOLERANCE, count

    at = int(np.argmin(np.abs(ds.level.values - 1.0)))
    bare = ds.median_repair_cost_mce.sel(barrier="bare wall").values  # (gap,)
    with_b = ds.median_repair_cost_mce.isel(barrier=slice(2, None)).values  # (n, gap)
    hit = ds.contact_probability.isel(level=at).sel(barrier="bare wall").values > 0
    holds = with_b < bare * (1 - TOLERANCE)
    changed = np.abs(with_b - bare) > TOLERANCE * bare
    c = count("may", holds[None], np.broadcast_to(hit, with_b.shape)[None], changed[None])
    table = decision_table(ds)
    return [Verdict("1.2 (Anagnostopoulos 1988)", "The use of bumpers may reduce, in some "
                    "cases, the response due to poundings [here: the median repair cost at "
                    "the MCE_R, against the bare wall at the same gap where it is hit]",
                    f"{c.text('configurations')}; decision table:\n{table}", c.verdict,
                    {"count": c.numbers(), "bare_wall": bare.tolist(),
                     "with_bumpers": with_b.tolist()})]


recipe = Recipe(
    name="loss", figure="beyond the paper",
    summary="Repair cost, expected annual loss and annual rates of pounding, crushed bumpers "
            "and collapse with and without bumpers at every gap: FEMA P-58 by pelicun for the "
            "code-designed isolated building (as studies.collapse's) in plan; the designer's "
            "decision table",
    compute=compute, plot=plot, check=check, records=(), options=options,
    chosen=(f"as studies.collapse; stripes {', '.join(f'{v:.3g}' for v in LEVELS)} x MCE_R "
            f"(service level 0.2); {FLOOR_AREA:g} m^2 floors of a default office inventory; "
            f"replacement {p58.COST_PER_M2:g} USD_2011 and {p58.TIME_PER_M2:g} worker-days "
            f"per m^2; hazard the second-order form through 1/{1 / hazards.MCE_R_RATE:.0f} per "
            f"year at S_MT, slope {hazards.SLOPE:.2f} and curvature {hazards.CURVATURE:.3f}; "
            f"{p58.SAMPLES} realizations; "
            f"quick: stripes {', '.join(map(str, QUICK_LEVELS))}, {QUICK_SAMPLES} "
            "realizations"))
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
