"""Beyond the paper: fragility curves of the moat, with and without bumpers.

The paper's building in plan (coupled isolators, a square moat) under the FEMA P695 far-field
record pairs, scaled to a site's MCE_R by a code's rule (pipeline.motions.code_suite: ASCE 7-22
chapter 17 by default), then run at intensity levels that are fractions of the MCE_R (a
multiple-stripe analysis: every pair at every level, the levels one more batch dimension). The
moat's clear gap is a fraction of the code's D_M (and the code's clearance D_TM), against the bare
wall (the paper's linear law) and with the paper's bumpers (4 x 5 cm a side).

Per pair, level and configuration the archive keeps the peaks and the events (`event_*`, 1
where it happens): contact with the wall or bumpers, bumpers crushed beyond their ultimate
strain, the largest floor acceleration or interstory drift ratio above each of its thresholds
(the median capacities of the first damage states of an office building's components, FEMA
P-58: pipeline.assess.thresholds; --accel-threshold-g and --drift-threshold-ratio for others),
a story beyond its capacity (yielding stories: their yield
drift; linear ones: the code's superstructure capacity,
pipeline.assess.validity.code_story_capacity), and, if a capacity is given, the wall's force above
it. For each event and configuration a lognormal fragility P(event | IM) = Phi(ln(IM / theta) /
beta) is fitted by maximum likelihood over the stripes (Baker 2015; pipeline.assess.fragility),
pairs weighted per earthquake, with percentile bootstrap intervals of theta and beta over the
pairs, and beta_TOT beside the record-to-record beta (FEMA P695 section 7.3.1 with the
quality ratings, --ratings); IM is the level as a fraction of the MCE_R (and, equivalently, the
target's Sa(T_M)). Runs outside the model's range (pipeline.assess.validity) are flagged
(`invalid_*`) and counted in the summary, how each run ended beside its collapse flag
(`collapse_mode`: a story's drift, the isolator's capacity, a numerical instability; 0 where
it stood) and the collapses counted by mode (`collapse_modes`). The
largest floor acceleration and interstory drift, the bumpers' stress and "crushed" are
pipeline.assess.derived's (names, units, long names, formulas); --moat, --wall-capacity-mn and the
default pairs are studies.common.options'.
"""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM, G
from pipeline.assess import derived
from pipeline.assess.collapse import RATINGS
from pipeline.assess.thresholds import ACCELERATION, DRIFT, Threshold
from pipeline.motions.code_suite import describe
from pipeline.suite_labels import archive_variables

from ..common.options import (
    QUICK_PAIRS,
    add_bound,
    add_moat,
    add_stories,
    add_wall_capacity,
    bare_wall_text,
    checked_gaps,
    chosen_pairs,
    scaled_suite,
    site_options,
    wall_capacity,
)
from ..common.paper import AREA, DELTA_U, N_BUMPERS, THICKNESS
from ..common.recipe import Recipe, Verdict, provenance, run_options
from .figure import caption, plot  # noqa: F401 - caption: the recipe's caption, as every recipe has

LEVELS = (0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.5)
"""Intensity levels, multiples of the MCE_R target (1 = MCE_R), the stripes run (the archive's
`levels` attribute names those run: `levels_text`)."""
QUICK_LEVELS = (0.5, 1.0, 1.5)
GAPS = (0.8, 1.0)
"""Clear gaps as fractions of D_M; the code's clearance D_TM is added."""
BUMPER_COUNTS = (N_BUMPERS, 32)
"""Bumpers per wall of the configurations (the paper's 4, and Fig. 19's 32, which section 5.4
says stay within the crush limit), each 5 cm thick."""
BARRIERS = ("bare wall", *(f"{n} bumpers" for n in BUMPER_COUNTS))
BOOTSTRAP = 200
"""Bootstrap resamples of the pairs per fit (QUICK_BOOTSTRAP with --quick)."""
QUICK_BOOTSTRAP = 20
EVENTS = {
    "contact": "the slab touches the wall or the bumpers",
    "bumpers_crushed": "the bumpers are compressed beyond their ultimate strain (delta_u)",
    "floor_accel": "the largest peak floor acceleration exceeds {what}",
    "drift": "the largest peak interstory drift ratio exceeds {what}",
    "story_capacity": "a story exceeds its capacity (its yield drift, or a linear story's "
                      "shear above the code's superstructure capacity)",
    "wall_force": "the wall's largest force exceeds its capacity",
    "collapse": "the building collapses (a story's drift past the collapse drift); a "
                "collapsed run counts as every other event too",
}


def options(p) -> None:
    site_options(p)
    add_bound(p)
    add_stories(p)
    p.add_argument("--accel-threshold-g", type=float, nargs="+", default=None, metavar="G",
                   help="floor acceleration event thresholds in g, one event each (default: "
                        "the FEMA P-58 median capacities of an office's acceleration-sensitive "
                        "components, " + ", ".join(f"{t.value / G:g} g ({t.name})"
                                                   for t in ACCELERATION) + ")")
    p.add_argument("--drift-threshold-ratio", type=float, nargs="+", default=None,
                   metavar="RATIO",
                   help="interstory drift ratio event thresholds, one event each (default: "
                        "the FEMA P-58 median capacities of its drift-sensitive components, "
                        + ", ".join(f"{t.value:g} ({t.name})" for t in DRIFT) + ")")
    p.add_argument("--ratings", nargs=3, default=list(RATINGS), metavar=("DR", "TD", "MDL"),
                   choices=("A", "B", "C", "D"),
                   help="quality ratings of the design requirements, test data and model for "
                        f"beta_TOT (FEMA P695 ch. 3 and 5; default {' '.join(RATINGS)})")
    add_wall_capacity(p, "its event and the validity flag invalid_wall_force")
    add_moat(p)
    p.add_argument("--method", choices=("stripes", "ida"), default="stripes",
                   help="the fit (Baker 2015): stripes (default), the binomial likelihood of "
                        "the events per level; ida, each pair's first level with the event as "
                        "its capacity (censored above the highest level)")


def chosen_thresholds(args) -> tuple[Threshold, ...]:
    """The event thresholds: the components' (pipeline.assess.thresholds), or the user's
    (named by their value; SweepError for one not positive)."""
    from pipeline.errors import SweepError

    accel, drift = ACCELERATION, DRIFT
    if args.accel_threshold_g is not None:
        accel = tuple(Threshold(f"{g:g}g".replace(".", "p"), "floor_accel", g * G, "", 0,
                                f"{g:g} g") for g in args.accel_threshold_g)
    if args.drift_threshold_ratio is not None:
        drift = tuple(Threshold(f"{r:g}".replace(".", "p"), "drift_ratio", r, "", 0,
                                f"{r:g}") for r in args.drift_threshold_ratio)
    if any(not t.value > 0 for t in accel + drift):
        raise SweepError("--accel-threshold-g and --drift-threshold-ratio must be positive")
    return accel + drift


def event_text(name: str, thresholds) -> str:
    """What event `name` is (EVENTS, a threshold's event naming its component)."""
    for t in thresholds:
        if name == t.event:
            what = (f"{t.value / G:g} g" if t.demand == "floor_accel" else f"{t.value:g}")
            if t.component:
                what += (f", the median capacity of FEMA P-58 {t.component} damage state "
                         f"{t.damage_state}: {t.description}")
            return EVENTS["floor_accel" if t.demand == "floor_accel" else "drift"].format(
                what=what)
    return EVENTS[name]


def compute(args):
    args.thresholds = chosen_thresholds(args)
    args.bootstrap = QUICK_BOOTSTRAP if args.quick else BOOTSTRAP
    pairs, names = chosen_pairs(args, QUICK_PAIRS)
    suite = scaled_suite(args, pairs, names)  # at --bound: its building, its D_M and D_TM
    levels = np.array(QUICK_LEVELS if args.quick else LEVELS)
    fractions = np.array([*GAPS, suite.design.d_tm / suite.design.d_m])
    gaps = checked_gaps(fractions * suite.design.d_m, suite.design)
    peaks, swept = run(suite, levels, gaps, args)
    ds = _dataset(suite, levels, fractions, gaps, peaks, args)
    return ds.assign_attrs({**provenance(swept), **ds.attrs})


def run(suite, levels, gaps, args):
    """Every pair at every level (x its MCE_R factor) without wall, against the bare wall and
    with each count of bumpers at every gap (m), on the pipeline's executor (pipeline.sweep:
    resumable, here or on dask). Returns (peak name -> (R, L, W, ...) arrays, float but the
    counts' and codes' (n_impacts, collapse_mode: integers, as engine.results declares them),
    the walls
    W in the order: no wall, the bare wall at each gap, then each BUMPER_COUNTS' gaps; the
    sweep's Dataset, whose provenance the archive keeps). The building at the suite's bound
    (suite.building)."""
    import pipeline

    ds = pipeline.sweep(suite.pairs, moat=args.moat, gap=gaps, thickness=THICKNESS,
                        n_bumpers=list(BUMPER_COUNTS), baseline=True, unconstrained=True,
                        level=levels, factors=suite.factors,
                        **{**run_options(args), "building": suite.building})
    peaks = {}
    for name in (*PEAK_NAMES, "peak_total_accel", "peak_interstory_drift", "collapsed",
                 "collapse_mode"):
        if name not in ds:  # a building without a collapse criterion
            continue
        free, bare = ds["unconstrained_" + name], ds["baseline_" + name]
        bumpers = [ds[name].sel(n_bumpers=n) for n in BUMPER_COUNTS]
        walls = [free.expand_dims("wall", 2), *(b.rename(gap="wall") for b in (bare, *bumpers))]
        values = np.concatenate([w.values for w in walls], axis=2)
        # counts (n_impacts: engine.results declares int64) and codes stay integers; the rest
        # float
        peaks[name] = values if values.dtype.kind in "iu" else values.astype(float)
    return peaks, ds


PEAK_NAMES = ("peak_isolator_disp", "max_impact_force", "max_indentation", "n_impacts")


def _dataset(suite, levels, fractions, gaps, peaks, args):
    from engine.results import quantity
    from pipeline.archive import collapse_mode_variable, labelled_dataset, variable
    from pipeline.assess.collapse_modes import collapse_numbers
    from pipeline.assess.fragility_outcomes import BOOTSTRAP_QUANTILES
    from pipeline.assess.thresholds import total_beta
    from pipeline.assess.validity import FLAGS, Limits, code_story_capacity, flags_of, shape_factor

    building = suite.building  # at the suite's bound
    # the superstructure's strength from the code's largest base shear over the bounds
    capacity = code_story_capacity(suite.basis.force_design, building)
    wall_force = wall_capacity(args)
    limits = Limits(story_shear=capacity, wall_force=wall_force)
    # configurations: member 0 no wall, then each barrier's gaps (BARRIERS order)
    n_gaps = gaps.size
    pick = {b: slice(1 + k * n_gaps, 1 + (k + 1) * n_gaps) for k, b in enumerate(BARRIERS)}
    dims = ("record", "level", "gap_fraction", "barrier")

    def by_config(values):  # (R, L, members, ...) -> (R, L, gap, barrier, ...)
        return np.stack([values[:, :, pick[b]] for b in BARRIERS], axis=3)

    data = {}
    for name in PEAK_NAMES:
        q = quantity(name)
        data[name] = variable(dims, by_config(peaks[name]), q.units, q.long_name + " (plan: "
                              "resultant)")
    largest = derived.derive(peaks, ("peak_floor_accel", "peak_story_drift"))
    for name, value in largest.items():
        q = derived.quantity(name)
        data[name] = variable(dims, by_config(value), q.units, q.long_name + " (resultant)")
    free = {"peak_isolator_disp": peaks["peak_isolator_disp"][:, :, 0],
            **{name: value[:, :, 0] for name, value in largest.items()}}
    for name, value in free.items():
        data[f"unconstrained_{name}"] = variable(("record", "level"), value,
                                                 data[name].attrs["units"],
                                                 data[name].attrs["long_name"] + " without wall")
    events = _events(peaks, building, args, capacity, wall_force, by_config)
    for name, value in events.items():
        data[f"event_{name}"] = variable(dims, value.astype(np.int8), "1",
                                         f"1 where {event_text(name, args.thresholds)}")
    flagged = flags_of(peaks, building, limits, n_bumpers=_bumper_counts(n_gaps)[None, None, :],
                       area=AREA, thickness=THICKNESS)
    for name, value in flagged.items():
        data[name] = variable(dims, by_config(value).astype(np.int8), "1",
                              f"1 where {FLAGS[name]} ({limits.describe()})")
    # how each run ended (0 for every run of a building that cannot collapse)
    mode = by_config(peaks.get("collapse_mode", np.zeros(flagged["invalid_collapse"].shape)))
    data["collapse_mode"] = collapse_mode_variable(dims, mode)
    q = derived.quantity("bumper_stress")
    stress = by_config(q(peaks, n_bumpers=_bumper_counts(n_gaps), area=AREA))
    stress[..., 0] = np.nan  # the bare wall has no bumpers
    data["bumper_stress"] = variable(dims, stress, q.units, q.long_name + " (NaN: no bumpers)")

    fits = _fits(levels, events, suite.weights, args)
    fit_dims = ("event", "gap_fraction", "barrier")
    target_tm = float(suite.target.at(suite.design.t_m))
    data["fragility_median"] = variable(fit_dims, fits["theta"], "1",
                                        "median intensity of the event, x the MCE_R target")
    data["fragility_median_sa"] = variable(fit_dims, fits["theta"] * target_tm, "m s-2",
                                           "median intensity as the target's Sa(T_M)")
    data["fragility_beta"] = variable(fit_dims, fits["beta"], "1",
                                      "logarithmic standard deviation of the fragility")
    data["fragility_median_interval"] = variable(
        (*fit_dims, "bound"), fits["theta_bounds"], "1", "bootstrap interval of the median "
        "intensity, x MCE_R (pairs resampled; NaN: not identifiable)")
    data["fragility_beta_interval"] = variable(
        (*fit_dims, "bound"), fits["beta_bounds"], "1", "bootstrap interval of beta")
    data["fragility_beta_total"] = variable(
        fit_dims, total_beta(fits["beta"], args.ratings), "1", "beta_TOT: the fitted "
        "(record-to-record) beta with the quality ratings' design, test and model "
        "uncertainties (FEMA P695 section 7.3.1, unrounded)")
    data["fragility_identifiable"] = variable(fit_dims, fits["identifiable"].astype(np.int8),
                                              "1", "1 where the data identify both parameters")
    data["fragility_status"] = variable(fit_dims, fits["status"], "1",
                                        "the fit's status (pipeline.assess.fragility): ok, "
                                        "never or always observed, beta not identifiable, "
                                        "extrapolated")
    more, more_coords, attrs = archive_variables(suite)
    attrs["levels"] = levels_text(levels)  # the stripes run, not the code suite's levels
    data.update(more)
    coords = {
        "record": variable("record", np.array(suite.names), "1", "record pair"),
        "level": variable("level", levels, "1", "intensity: the pairs' MCE_R factors times "
                          "this (1: MCE_R, 2/3: the design earthquake)"),
        "level_sa": variable("level", levels * target_tm, "m s-2",
                             "the level as the target's Sa(T_M)"),
        "gap_fraction": variable("gap_fraction", fractions, "1",
                                 "seismic gap / D_M (the last: the code's clearance D_TM)"),
        "gap": variable("gap_fraction", gaps, "m", "seismic gap"),
        "barrier": variable("barrier", np.array(BARRIERS), "1", f"the bare wall "
                            f"({bare_wall_text()}) or n bumpers of {THICKNESS / CM:g} cm "
                            "on each wall"),
        "event": variable("event", np.array(list(events)), "1", "what happens: "
                          + "; ".join(f"{k}: {event_text(k, args.thresholds)}"
                                      for k in events)),
        "bound": variable("bound", np.array(BOOTSTRAP_QUANTILES), "1", "quantile of the "
                          "bootstrap interval"),
        **more_coords,
    }
    counts = {name: int(by_config(value).sum()) for name, value in flagged.items()}
    attrs.update({
        "moat": args.moat, "thresholds": json.dumps(
            {t.event:
             {"value": t.value, "units": "m s-2" if t.demand == "floor_accel" else "1",
              "component": t.component, "damage_state": t.damage_state,
              "what": t.description} for t in args.thresholds}),
        "thresholds_source": "FEMA P-58 (2018) component fragilities, median capacities "
                             "(pipeline.assess.thresholds)" if all(
                                 t.component for t in args.thresholds) else "user-set",
        "bootstrap": args.bootstrap, "quality_ratings": " ".join(args.ratings),
        "story_capacity": capacity,
        "wall_capacity": "none" if wall_force is None else wall_force,
        "validity_limits": limits.describe(), "invalid_counts": json.dumps(counts),
        "collapse_modes": json.dumps(collapse_numbers(data["collapse_mode"].values)),
        "runs": int(np.prod([len(suite.names), levels.size, gaps.size, len(BARRIERS)])),
        "bumper_shape_factor": float(shape_factor(AREA, THICKNESS)),
        "suite": describe(suite), "fragility_method": (
            "multiple stripes, binomial maximum likelihood" if args.method == "stripes" else
            "incremental dynamic analysis: each pair's first level with the event, lognormal "
            "maximum likelihood, censored above the highest level")
        + " (Baker 2015, Earthquake Spectra 31(1)), pairs weighted per earthquake",
    })
    return labelled_dataset(data, coords, attrs)


def levels_text(levels) -> str:
    """The archive's `levels` attribute: the intensity levels the stripes ran, as multiples of
    the MCE_R (each pair's MCE_R factor times the level)."""
    return (f"stripes at {', '.join(f'{v:.4g}' for v in np.asarray(levels, dtype=float))} "
            "x MCE_R (each pair's MCE_R factor times the level)")


def _bumper_counts(n_gaps: int) -> np.ndarray:
    """(members,) the bumpers of each wall configuration: none for no wall and the bare wall
    (infinitely many sharing the force: no stress, not checked), BUMPER_COUNTS for the
    bumpers."""
    counts = np.full(1 + len(BARRIERS) * n_gaps, np.inf)
    for k, n in enumerate(BUMPER_COUNTS, start=1):
        counts[1 + k * n_gaps:1 + (k + 1) * n_gaps] = n
    return counts


def _events(peaks, building, args, capacity, wall_force, by_config) -> dict:
    """event name -> (R, L, gap, barrier) bool; wall_force: the wall's capacity, N (None: no
    event)."""
    accel = derived.largest_floor_accel(peaks["peak_total_accel"])
    drift_all = peaks["peak_interstory_drift"]
    ratio = (drift_all / np.asarray(building.story_height, float)).max(axis=-1)
    crushed = derived.crushed(peaks["max_indentation"], DELTA_U)
    n_gaps = (peaks["n_impacts"].shape[2] - 1) // len(BARRIERS)
    crushed[:, :, :1 + n_gaps] = False  # no bumpers there
    if not building.story_law.is_linear:
        beyond = np.any(drift_all > building.story_yield_drift, axis=-1)
    else:
        beyond = (drift_all * np.asarray(building.story_stiffness)).max(axis=-1) > capacity
    out = {"contact": peaks["n_impacts"] > 0, "bumpers_crushed": crushed,
           **{t.event: (accel if t.demand == "floor_accel" else ratio) > t.value
              for t in args.thresholds},
           "story_capacity": beyond}
    if wall_force is not None:
        out["wall_force"] = peaks["max_impact_force"] > wall_force
    if "collapsed" in peaks:
        # A collapse is past every damage state (as FEMA P-58 counts it): its run's peaks
        # stop before it, so they would understate every other event.
        fell = peaks["collapsed"].astype(bool)
        out = {name: value | fell for name, value in out.items()}
        out["collapse"] = fell
    return {name: by_config(value) for name, value in out.items()}


def _fits(levels, events, weights, args) -> dict:
    """theta, beta, identifiable, status over (event, gap, barrier); theta_bounds and
    beta_bounds (..., bound) the bootstrap intervals over the pairs (args.bootstrap
    resamples) of the identifiable fits."""
    from pipeline.assess.fragility_outcomes import BOOTSTRAP_QUANTILES, bootstrap, fit_outcomes

    names = list(events)
    shape = (len(names), *events[names[0]].shape[2:])
    out = {"theta": np.full(shape, np.nan), "beta": np.full(shape, np.nan),
           "identifiable": np.zeros(shape, dtype=bool), "status": np.empty(shape, dtype=object),
           "theta_bounds": np.full((*shape, len(BOOTSTRAP_QUANTILES)), np.nan),
           "beta_bounds": np.full((*shape, len(BOOTSTRAP_QUANTILES)), np.nan)}
    for e, name in enumerate(names):
        for g in range(shape[1]):
            for b in range(shape[2]):
                seen = events[name][:, :, g, b]
                fit = fit_outcomes(levels, seen, weights, method=args.method)
                out["theta"][e, g, b], out["beta"][e, g, b] = fit.theta, fit.beta
                out["identifiable"][e, g, b] = fit.identifiable
                out["status"][e, g, b] = fit.status
                if fit.identifiable:
                    boot = bootstrap(levels, seen, weights, method=args.method,
                                     n=args.bootstrap, seed=e * 1000 + g * 100 + b)
                    out["theta_bounds"][e, g, b] = boot["theta"]
                    out["beta_bounds"][e, g, b] = boot["beta"]
    out["status"] = out["status"].astype(str)
    return out


def check(ds) -> list[Verdict]:
    """Paper 4 and 5.1 in fragility terms, one verdict per floor acceleration threshold (each
    a component's median capacity): bumpers can reduce the floor accelerations due to
    pounding, i.e. for some bumper configuration at some gap the median intensity at which the
    floor acceleration exceeds the threshold is higher with bumpers than against the bare wall
    by more than the tolerance of pipeline.assess.outcomes (compared only where both fits are
    identified), counted by pipeline.assess.outcomes.count: the configurations the claim
    applies to (both fits identified) whose medians differ by more than the tolerance, the
    others beside the count."""
    from pipeline.assess.collapse_modes import collapse_text
    from pipeline.assess.outcomes import TOLERANCE, count

    counts = json.loads(ds.attrs["invalid_counts"])
    modes = json.loads(ds.attrs["collapse_modes"])
    flagged = ", ".join(collapse_text(modes) if k == "invalid_collapse"
                        else f"{k.removeprefix('invalid_')} {v}" for k, v in counts.items() if v)
    thresholds = json.loads(ds.attrs["thresholds"])
    verdicts = []
    for event in [e for e in ds.event.values if str(e).startswith("floor_accel_")]:
        median = ds.fragility_median.sel(event=event)
        known = ds.fragility_identifiable.sel(event=event) == 1
        bare = median.sel(barrier="bare wall").values
        higher, compared, changed, parts = [], [], [], []
        for barrier in ds.barrier.values[1:]:
            ok = (known.sel(barrier=barrier) & known.sel(barrier="bare wall")).values
            with_b = median.sel(barrier=barrier).values
            higher.append(ok & (with_b > bare * (1 + TOLERANCE)))
            compared.append(ok)
            changed.append(np.abs(with_b - bare) > TOLERANCE * bare)
            parts.append(f"{barrier}: " + ", ".join(
                f"{a:.2f}/{b:.2f}" if k else "not identified"
                for a, b, k in zip(with_b, bare, ok, strict=True)))
        t = thresholds[str(event)]
        what = f"{t['value'] / G:g} g" + (f" ({t['component']}: {t['what']})"
                                          if t["component"] else "")
        finding = (f"the median intensity (x MCE_R) of the floor acceleration above {what}, "
                   f"with bumpers / bare wall, at gaps "
                   f"{', '.join(f'{f:.2f}' for f in ds.gap_fraction.values)} D_M: "
                   + "; ".join(parts) + f"; runs outside the model's range (of "
                   f"{ds.attrs['runs']}): " + (flagged or "none"))
        held = np.array(higher)
        c = count("can", held[None], np.array(compared)[None], np.array(changed)[None])
        finding += f"; {c.text('configurations')}"
        verdicts.append(Verdict(
            "4, 5.1", f"Bumpers can reduce the floor accelerations due to pounding [above "
            f"{t['value'] / G:g} g: for one configuration at one gap at least, a median "
            f"intensity higher by more than {TOLERANCE:.0%}]", finding,
            c.verdict,
            {"event": str(event), "threshold": t["value"],
             "higher_with_bumpers": held.tolist(), "count": c.numbers(),
             "invalid_counts": counts, "collapse_modes": modes}))
    return verdicts


recipe = Recipe(
    name="fragility", figure="beyond the paper",
    summary="Fragility curves of the moat with and without bumpers: the paper's building in "
            "plan under code-scaled FEMA P695 pairs at intensity levels (multiple stripes)",
    compute=compute, plot=plot, check=check,
    chosen=(f"site S_MS 1.5 g, S_M1 0.9 g, T_L 8 s; ASCE 7-22 ch. 17 scaling; levels "
            f"{', '.join(map(str, LEVELS))} x MCE_R; gaps {', '.join(map(str, GAPS))} D_M and "
            f"D_TM; event thresholds the FEMA P-58 median capacities of an office's "
            f"components; {BOOTSTRAP} bootstrap resamples; quick: {QUICK_PAIRS} pairs, "
            f"{QUICK_BOOTSTRAP} resamples, levels "
            f"{', '.join(map(str, QUICK_LEVELS))}"),
    records=(), options=options)
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
