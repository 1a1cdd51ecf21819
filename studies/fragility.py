"""Beyond the paper: fragility curves of the moat, with and without bumpers.

The paper's building in plan (coupled isolators, a square moat) under the FEMA P695 far-field
record pairs, scaled to a site's MCE_R by a code's rule (pipeline.motions.code_suite: ASCE 7-22
chapter 17 by default), then run at intensity levels that are fractions of the MCE_R (a
multiple-stripe analysis: every pair at every level, the levels one more batch dimension). The
moat's clear gap is a fraction of the code's D_M (and the code's clearance D_TM), against the bare
wall (the paper's linear law) and with the paper's bumpers (4 x 5 cm a side).

Per pair, level and configuration the archive keeps the peaks and the events (`event_*`, 1
where it happens): contact with the wall or bumpers, bumpers crushed beyond their ultimate
strain, the largest floor acceleration or interstory drift above a threshold (defaults
ACCEL_THRESHOLD, DRIFT_THRESHOLD), a story beyond its capacity (yielding stories: their yield
drift; linear ones: the code's superstructure capacity,
pipeline.assess.validity.code_story_capacity), and, if a capacity is given, the wall's force above
it. For each event and configuration a lognormal fragility P(event | IM) = Phi(ln(IM / theta) /
beta) is fitted by maximum likelihood over the stripes (Baker 2015; pipeline.assess.fragility),
pairs weighted per earthquake; IM is the level as a fraction of the MCE_R (and, equivalently, the
target's Sa(T_M)). Runs outside the model's range (pipeline.assess.validity) are flagged
(`invalid_*`) and counted in the summary. The
largest floor acceleration and interstory drift, the bumpers' stress and "crushed" are
pipeline.assess.derived's (names, units, long names, formulas); --moat, --wall-capacity-mn and the
default pairs are studies.common.options'.
"""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM, G
from pipeline.assess import derived
from pipeline.motions.code_suite import archive_variables, describe

from .common.options import (
    QUICK_PAIRS,
    add_bound,
    add_moat,
    add_stories,
    add_wall_capacity,
    bare_wall_text,
    chosen_pairs,
    scaled_suite,
    site_options,
    wall_capacity,
)
from .common.paper import AREA, DELTA_U, N_BUMPERS, THICKNESS
from .common.plot import plt
from .common.recipe import Recipe, Verdict, provenance, run_options

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
ACCEL_THRESHOLD = 1.0 * G
"""m/s^2: a floor acceleration an isolated building is not designed for (isolation keeps its
floors near 0.3-0.5 g at the MCE_R: the paper's building, 0.51 g median without wall) and that
damages contents and equipment: beyond it, pounding rather than the ground motion drives it."""
DRIFT_THRESHOLD = 0.015
"""m: 0.5% of a 3 m story, about where a superstructure designed to stay elastic (R_I <= 2)
starts to be damaged."""
EVENTS = {
    "contact": "the slab touches the wall or the bumpers",
    "bumpers_crushed": "the bumpers are compressed beyond their ultimate strain (delta_u)",
    "floor_accel": "the largest peak floor acceleration exceeds the threshold",
    "drift": "the largest peak interstory drift exceeds the threshold",
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
    p.add_argument("--accel-threshold-g", type=float, default=ACCEL_THRESHOLD / G, metavar="G",
                   help=f"floor acceleration event threshold in g (default "
                        f"{ACCEL_THRESHOLD / G:g})")
    p.add_argument("--drift-threshold-cm", type=float, default=DRIFT_THRESHOLD / CM,
                   metavar="CM", help=f"interstory drift event threshold in cm (default "
                                      f"{DRIFT_THRESHOLD / CM:g})")
    add_wall_capacity(p, "its event and the validity flag invalid_wall_force")
    add_moat(p)
    p.add_argument("--method", choices=("stripes", "ida"), default="stripes",
                   help="the fit (Baker 2015): stripes (default), the binomial likelihood of "
                        "the events per level; ida, each pair's first level with the event as "
                        "its capacity (censored above the highest level)")


def compute(args):
    pairs, names = chosen_pairs(args, QUICK_PAIRS)
    suite = scaled_suite(args, pairs, names)  # at --bound: its building, its D_M and D_TM
    levels = np.array(QUICK_LEVELS if args.quick else LEVELS)
    fractions = np.array([*GAPS, suite.design.d_tm / suite.design.d_m])
    gaps = fractions * suite.design.d_m
    peaks, swept = run(suite, levels, gaps, args)
    ds = _dataset(suite, levels, fractions, gaps, peaks, args)
    return ds.assign_attrs({**provenance(swept), **ds.attrs})


def run(suite, levels, gaps, args):
    """Every pair at every level (x its MCE_R factor) without wall, against the bare wall and
    with each count of bumpers at every gap (m), on the pipeline's executor (pipeline.sweep:
    resumable, here or on dask). Returns (peak name -> (R, L, W, ...) arrays, float but the
    counts' (n_impacts: integers, as engine.results declares them), the walls
    W in the order: no wall, the bare wall at each gap, then each BUMPER_COUNTS' gaps; the
    sweep's Dataset, whose provenance the archive keeps). The building at the suite's bound
    (suite.building)."""
    import pipeline

    ds = pipeline.sweep(suite.pairs, moat=args.moat, gap=gaps, thickness=THICKNESS,
                        n_bumpers=list(BUMPER_COUNTS), baseline=True, unconstrained=True,
                        level=levels, factors=suite.factors,
                        **{**run_options(args), "building": suite.building})
    peaks = {}
    for name in (*PEAK_NAMES, "peak_total_accel", "peak_interstory_drift", "collapsed"):
        if name not in ds:  # a building without a collapse criterion
            continue
        free, bare = ds["unconstrained_" + name], ds["baseline_" + name]
        bumpers = [ds[name].sel(n_bumpers=n) for n in BUMPER_COUNTS]
        walls = [free.expand_dims("wall", 2), *(b.rename(gap="wall") for b in (bare, *bumpers))]
        values = np.concatenate([w.values for w in walls], axis=2)
        # counts (n_impacts: engine.results declares int64) stay integers; the rest float
        peaks[name] = values if values.dtype.kind in "iu" else values.astype(float)
    return peaks, ds


PEAK_NAMES = ("peak_isolator_disp", "max_impact_force", "max_indentation", "n_impacts")


def _dataset(suite, levels, fractions, gaps, peaks, args):
    from engine.results import quantity
    from pipeline.archive import labelled_dataset, variable
    from pipeline.assess.fragility_outcomes import fit_outcomes
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
                                         f"1 where {EVENTS[name]}")
    flagged = flags_of(peaks, building, limits, n_bumpers=_bumper_counts(n_gaps)[None, None, :],
                       area=AREA, thickness=THICKNESS)
    for name, value in flagged.items():
        data[name] = variable(dims, by_config(value).astype(np.int8), "1",
                              f"1 where {FLAGS[name]} ({limits.describe()})")
    q = derived.quantity("bumper_stress")
    stress = by_config(q(peaks, n_bumpers=_bumper_counts(n_gaps), area=AREA))
    stress[..., 0] = np.nan  # the bare wall has no bumpers
    data["bumper_stress"] = variable(dims, stress, q.units, q.long_name + " (NaN: no bumpers)")

    fits = _fits(levels, events, suite.weights, fit_outcomes, args.method)
    fit_dims = ("event", "gap_fraction", "barrier")
    target_tm = float(suite.target.at(suite.design.t_m))
    data["fragility_median"] = variable(fit_dims, fits["theta"], "1",
                                        "median intensity of the event, x the MCE_R target")
    data["fragility_median_sa"] = variable(fit_dims, fits["theta"] * target_tm, "m s-2",
                                           "median intensity as the target's Sa(T_M)")
    data["fragility_beta"] = variable(fit_dims, fits["beta"], "1",
                                      "logarithmic standard deviation of the fragility")
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
                          + "; ".join(f"{k}: {EVENTS[k]}" for k in events)),
        **more_coords,
    }
    counts = {name: int(by_config(value).sum()) for name, value in flagged.items()}
    attrs.update({
        "moat": args.moat, "accel_threshold": args.accel_threshold_g * G,
        "drift_threshold": args.drift_threshold_cm * CM, "story_capacity": capacity,
        "wall_capacity": "none" if wall_force is None else wall_force,
        "validity_limits": limits.describe(), "invalid_counts": json.dumps(counts),
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
    crushed = derived.crushed(peaks["max_indentation"], DELTA_U)
    n_gaps = (peaks["n_impacts"].shape[2] - 1) // len(BARRIERS)
    crushed[:, :, :1 + n_gaps] = False  # no bumpers there
    if not building.story_law.is_linear:
        beyond = np.any(drift_all > building.story_yield_drift, axis=-1)
    else:
        beyond = (drift_all * np.asarray(building.story_stiffness)).max(axis=-1) > capacity
    out = {"contact": peaks["n_impacts"] > 0, "bumpers_crushed": crushed,
           "floor_accel": accel > args.accel_threshold_g * G,
           "drift": derived.largest_story_drift(drift_all) > args.drift_threshold_cm * CM,
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


def _fits(levels, events, weights, fit_outcomes, method: str) -> dict:
    """theta, beta, identifiable, status over (event, gap, barrier)."""
    names = list(events)
    shape = (len(names), *events[names[0]].shape[2:])
    out = {"theta": np.full(shape, np.nan), "beta": np.full(shape, np.nan),
           "identifiable": np.zeros(shape, dtype=bool), "status": np.empty(shape, dtype=object)}
    for e, name in enumerate(names):
        for g in range(shape[1]):
            for b in range(shape[2]):
                fit = fit_outcomes(levels, events[name][:, :, g, b], weights, method=method)
                out["theta"][e, g, b], out["beta"][e, g, b] = fit.theta, fit.beta
                out["identifiable"][e, g, b] = fit.identifiable
                out["status"][e, g, b] = fit.status
    out["status"] = out["status"].astype(str)
    return out


def check(ds) -> list[Verdict]:
    """Paper 4 and 5.1 in fragility terms: bumpers can reduce the floor accelerations due to
    pounding, i.e. for some bumper configuration at some gap the median intensity at which the
    floor acceleration exceeds its threshold is higher with bumpers than against the bare wall
    by more than the tolerance of pipeline.assess.outcomes (compared only where both fits are
    identified)."""
    from pipeline.assess.outcomes import TOLERANCE

    median = ds.fragility_median.sel(event="floor_accel")
    known = ds.fragility_identifiable.sel(event="floor_accel") == 1
    bare = median.sel(barrier="bare wall").values
    higher, compared, parts = [], 0, []
    for barrier in ds.barrier.values[1:]:
        ok = (known.sel(barrier=barrier) & known.sel(barrier="bare wall")).values
        with_b = median.sel(barrier=barrier).values
        higher.append(ok & (with_b > bare * (1 + TOLERANCE)))
        compared += int(ok.sum())
        parts.append(f"{barrier}: " + ", ".join(
            f"{a:.2f}/{b:.2f}" if k else "not identified"
            for a, b, k in zip(with_b, bare, ok, strict=True)))
    counts = json.loads(ds.attrs["invalid_counts"])
    flagged = ", ".join(f"{k.removeprefix('invalid_')} {v}" for k, v in counts.items() if v)
    finding = (f"the median intensity (x MCE_R) of the floor acceleration event, with bumpers / "
               f"bare wall, at gaps {', '.join(f'{f:.2f}' for f in ds.gap_fraction.values)} "
               f"D_M: " + "; ".join(parts) + f"; runs outside the model's range (of "
               f"{ds.attrs['runs']}): " + (flagged or "none"))
    held = np.array(higher)
    return [Verdict("4, 5.1", "Bumpers can reduce the floor accelerations due to pounding "
                    f"[for one configuration at one gap at least: a median intensity higher "
                    f"by more than {TOLERANCE:.0%}]", finding,
                    bool(held.any()) if compared else None,
                    {"higher_with_bumpers": held.tolist(), "compared": compared,
                     "invalid_counts": counts})]


COLOURS = ("0.35", "C0", "C3")  # the colour of each barrier, BARRIERS order
GAP_STYLES = (("-", "o"), ("--", "s"), (":", "^"))  # line and marker of each gap, in order
TITLES = {"contact": "contact with the wall or bumpers", "bumpers_crushed": "bumpers crushed",
          "floor_accel": "floor acceleration above {accel:g} g",
          "drift": "interstory drift above {drift:g} cm"}


def plot(ds):
    """One panel per event; a curve per barrier (colour) and gap (line and marker), named by
    a two-part legend below the panels."""
    from scipy.stats import norm

    from .common.plot import letter_panels, short_title, store_caption

    shown = [e for e in TITLES if e in ds.event.values]
    fig, axes = plt.subplots(1, len(shown), figsize=(2.4 * len(shown), 3.0), sharey=True,
                             squeeze=False)
    axes = axes[0]
    x = np.linspace(0.0, ds.level.values.max() * 1.25, 300)[1:]
    weights = ds.record_weight.values
    for ax, event in zip(axes, shown, strict=True):
        for g, (line, mark) in zip(range(ds.sizes["gap_fraction"]), GAP_STYLES, strict=False):
            for barrier, colour in zip(ds.barrier.values, COLOURS, strict=False):
                if event == "bumpers_crushed" and barrier == "bare wall":
                    continue
                fit = ds.sel(event=event, barrier=barrier).isel(gap_fraction=g)
                seen = ds[f"event_{event}"].sel(barrier=barrier).isel(gap_fraction=g).values
                share = (weights[:, None] * seen).sum(axis=0) / weights.sum()
                ax.plot(ds.level.values, share, mark, color=colour, ms=3, mfc="none")
                theta, beta = float(fit.fragility_median), float(fit.fragility_beta)
                if np.isfinite(theta) and np.isfinite(beta):
                    ax.plot(x, norm.cdf(np.log(x / theta) / beta), line, color=colour,
                            lw=1.2 if int(fit.fragility_identifiable) else 0.6)
        ax.axvline(1.0, color="k", lw=0.6, ls=":")
        ax.set_title(TITLES[event].format(accel=ds.attrs["accel_threshold"] / G,
                                          drift=ds.attrs["drift_threshold"] / CM))
        ax.set_xlabel("intensity, x MCE$_R$")
        ax.set_xlim(0, x[-1])
    axes[0].set_ylabel("probability of the event")
    barriers = [plt.Line2D([], [], color=c, lw=2, label=str(b))
                for b, c in zip(ds.barrier.values, COLOURS, strict=False)]
    gaps = [plt.Line2D([], [], color="k", ls=line, marker=mark, mfc="none",
                       label=f"gap {fraction:.2f} $D_M$")
            for fraction, (line, mark) in zip(ds.gap_fraction.values, GAP_STYLES,
                                              strict=False)]
    letter_panels(axes)
    short_title(fig, "Fragility of the moat with and without bumpers")
    store_caption(ds, caption(ds))
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    fig.legend(handles=barriers, loc="lower left", bbox_to_anchor=(0.08, 0.0), ncol=3,
               frameon=False, title="barrier (colour)")
    fig.legend(handles=gaps, loc="lower right", bbox_to_anchor=(0.98, 0.0), ncol=3,
               frameon=False, title="clear gap (line, marker)")
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return (f"Fragility of the moat: probability of each event against the intensity "
            f"(a multiple of the MCE_R, dotted), {ds.sizes['record']} record pairs, "
            f"{ds.attrs['scaling_rule']} scaling, T_M {ds.attrs['T_M']:.2f} s, D_M "
            f"{ds.attrs['D_M'] / CM:.1f} cm. Colour: the barrier (bare wall, bumpers); line "
            "and marker: the clear gap. Lines: lognormal fits (thin: beta not identified); "
            "open markers: observed shares, pairs weighted per earthquake.")


recipe = Recipe(
    name="fragility", figure="beyond the paper",
    summary="Fragility curves of the moat with and without bumpers: the paper's building in "
            "plan under code-scaled FEMA P695 pairs at intensity levels (multiple stripes)",
    compute=compute, plot=plot, check=check,
    chosen=(f"site S_MS 1.5 g, S_M1 0.9 g, T_L 8 s; ASCE 7-22 ch. 17 scaling; levels "
            f"{', '.join(map(str, LEVELS))} x MCE_R; gaps {', '.join(map(str, GAPS))} D_M and "
            f"D_TM; floor acceleration threshold {ACCEL_THRESHOLD / G:g} g, drift "
            f"{DRIFT_THRESHOLD / CM:g} cm; quick: {QUICK_PAIRS} pairs, levels "
            f"{', '.join(map(str, QUICK_LEVELS))}"),
    records=(), options=options)
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
