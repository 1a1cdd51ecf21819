"""Plan (beyond the paper): the paper's building and bumpers under record pairs, moving in both
horizontal directions, against the planar model the paper uses, over the seismic gap.

For every pair (default: the 22 FEMA P695 far-field pairs) and incidence angle theta (0-165
degrees, every 15), the planar model runs the pair's component along theta (the paper's
model: one component, walls on either side of one axis) and the model in plan runs the whole
pair rotated by theta (engine.simulate with a record pair: coupled isolators, a square or
circular moat). The gap is a fraction (0.5-1.3; the paper's rule, section 4: 0.9) of the
planar model's peak isolator displacement without wall for that component; at each gap, each
model runs against the bare wall (the paper's baseline) and with the paper's bumpers (4 x 5
cm a side), and once without wall.

How much the planar study underestimates: the ratio plan / planar of the peak isolator
displacement (without wall), of the largest impact force and of the largest peak floor
acceleration (bumpers at the paper's gap; where the planar model is hit), over pairs and
angles; and per pair, the largest peak without wall over the angles against the larger
as-recorded component's planar peak (planar rotated, and in plan). Whether the paper's
conclusions on the gap size (sections 4, 5.1, 6) hold in plan, side by side with the planar
model on the same pairs: each counted only at the points where what it speaks of happens.
"""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM, G
from pipeline.assess.derived import largest_floor_accel, largest_story_drift
from pipeline.assess.outcomes import QUANTILES

from ..common.options import add_moat, bare_wall_text, chosen_pairs
from ..common.paper import GAP_FRACTION, N_BUMPERS, THICKNESS
from ..common.plot import plt
from ..common.recipe import Recipe, Verdict, provenance, run_options
from .verdicts import (
    CLAIMS,
    MODELS,
    Claim,
    base_reduced,
    counts,
    drift_amplified,
    floor_reduced,
    force_reduced,
    narrow_more_effective,
    only_bumpers_amplify,
    side_by_side,
)

BARRIERS = ("none", "bare wall", "bumpers")
FRACTIONS = (0.5, 0.7, GAP_FRACTION, 1.1, 1.3)  # gap / the planar peak without wall
QUICK_FRACTIONS = (0.7, GAP_FRACTION)
QUICK_PLAN_PAIRS = 3  # pairs of a --quick run
ORBITS = 3  # pairs whose orbits (plan, bumpers, angle 0, the paper's gap) the figure draws
MIN_CLEARANCE = 0.01  # m: the least clear gap in front of the bumpers for them to be run
AS_RECORDED = (0.0, 90.0)  # degrees: the angles whose planar component is x, and -y


def angles(quick: bool) -> np.ndarray:
    """Incidence angles in degrees: 0-165 every 15 (quick: 0 and 90)."""
    return np.array(AS_RECORDED) if quick else np.arange(0.0, 180.0, 15.0)


def gap_fractions(quick: bool) -> np.ndarray:
    """Seismic gaps as fractions (-) of the planar model's peak isolator displacement without
    wall for the component along the angle; the paper's 0.9 among them."""
    return np.array(QUICK_FRACTIONS if quick else FRACTIONS)


def options(p) -> None:
    add_moat(p)


def compute(args):
    import engine
    import pipeline
    pairs, names = chosen_pairs(args, QUICK_PLAN_PAIRS)
    thetas, fracs = angles(args.quick), gap_fractions(args.quick)
    n_p, n_a, n_g = len(pairs), thetas.size, fracs.size
    shape = (n_p, n_a, n_g, len(MODELS), len(BARRIERS))
    out = {name: np.zeros(shape, dtype=np.int64 if name == "n_impacts" else float)
           for name in PEAK_NAMES}
    options = run_options(args)
    # 1. The planar model without wall under the component along each angle: it sets the
    # gaps, fractions of its peak isolator displacement.
    along = [along_angle(pair, theta) for pair in pairs for theta in thetas]
    free = pipeline.unconstrained_peaks(along, **options)
    free_peaks = peaks_of(free, "record")
    gaps = fracs * free.peak_isolator_disp.values.reshape(n_p, n_a, 1)
    # 2. The planar model against the walls at each component's own gaps.
    planar = pipeline.sweep(along, members=wall_table(gaps.reshape(n_p * n_a, n_g)),
                            **options)
    planar_peaks = peaks_of(planar, "member")
    for p in range(n_p):
        for a in range(n_a):
            i = p * n_a + a
            block = {k: np.concatenate([free_peaks[k][i:i + 1], planar_peaks[k][i]])
                     for k in PEAK_NAMES}
            _store(out, (p, a, slice(None), 0), block, gaps[p, a])
    # 3. In plan: each pair rotated by every angle, against the same walls.
    plan = pipeline.sweep(pairs, moat=args.moat, members=plan_table(gaps, thetas), **options)
    plan_peaks = peaks_of(plan, "member")
    block = 1 + 2 * n_g  # members per angle: no wall, then bare wall and bumpers per gap
    for p in range(n_p):
        for a in range(n_a):
            rows = slice(a * block, (a + 1) * block)
            _store(out, (p, a, slice(None), 1), {k: v[p, rows] for k, v in plan_peaks.items()},
                   gaps[p, a])
    # The orbits the figure draws: bumpers at the paper's gap, angle 0, a few pairs.
    f_paper = int(np.flatnonzero(fracs == GAP_FRACTION)[0])
    orbit_t, orbits = [], []
    for p, pair in enumerate(pairs[:ORBITS]):
        run = engine.simulate(pair.accel, pair.dt, bumpers(gaps[p, 0, f_paper]),
                              args.building, engine.DEFAULT_DT if args.dt is None else args.dt,
                              history=engine.History([0], every=10), moat=args.moat,
                              angle=thetas[:1])
        orbit_t.append(run.history["time"])
        orbits.append(run.history["isolator_disp"][0])
    ds = _dataset(out, gaps, names, pairs, thetas, fracs, orbit_t, orbits, args)
    return ds.assign_attrs({**provenance(plan), **ds.attrs})


def along_angle(pair, theta):
    """The planar model's record for a pair at the angle theta (degrees): the component along
    it (`component`), named <pair>@<theta>."""
    from pipeline.records import Record

    return Record(name=f"{pair.name}@{theta:g}", rsn=pair.rsn, event=pair.event,
                  station=pair.station, component=f"{theta:g} degrees", dt=pair.dt,
                  accel=component(pair.accel, theta), source=pair.source)


def wall_table(gaps) -> dict:
    """The members (pipeline.listed) at each record's gaps (R, G) m: per record and gap, the
    bare wall (`bare`) then the bumpers (`bumpers`: no wall where they do not fit)."""
    gaps = np.asarray(gaps, dtype=float)
    fit = fits(gaps)
    law = np.stack([np.full(gaps.shape, "linear"), np.where(fit, "bumper", "none")], axis=-1)
    gap = np.stack([gaps, np.where(fit, gaps, np.nan)], axis=-1)
    bumper = np.stack([np.full(gaps.shape, np.nan), np.where(fit, 1.0, np.nan)], axis=-1)
    r = gaps.shape[0]
    return {"law": law.reshape(r, -1), "gap": gap.reshape(r, -1),
            "thickness": (THICKNESS * bumper).reshape(r, -1),
            "n_bumpers": (N_BUMPERS * bumper).reshape(r, -1)}


def plan_table(gaps, thetas) -> dict:
    """The members in plan of each pair (pipeline.listed): per angle (thetas degrees), no wall
    then `wall_table` at that angle's gaps (R, A, G) m."""
    n_p, n_a, n_g = gaps.shape
    walls_ = wall_table(gaps.reshape(n_p * n_a, n_g))
    table = {}
    for name, values in walls_.items():
        first = "none" if name == "law" else np.nan
        values = values.reshape(n_p, n_a, 2 * n_g)
        table[name] = np.concatenate([np.full((n_p, n_a, 1), first, dtype=values.dtype),
                                      values], axis=-1).reshape(n_p, -1)
    table["angle"] = np.repeat(thetas, 1 + 2 * n_g)
    return table


def component(accel, theta) -> np.ndarray:
    """The pair's ground acceleration (N, 2) m/s^2 along the incidence angle theta (degrees):
    the x component of the pair rotated counterclockwise by theta, m/s^2."""
    rad = np.radians(theta)
    return np.cos(rad) * accel[:, 0] - np.sin(rad) * accel[:, 1]


def bare(gap):
    """The paper's bare wall (the linear law at its defaults) at the gap, m."""
    import engine

    return engine.Contact.linear([gap])


def fits(gap):
    """Whether the paper's bumpers fit in the gap (m; scalar or array) with room to spare: a
    weak record's gap rule gives gaps the 5 cm pads would fill."""
    return np.asarray(gap) > THICKNESS + MIN_CLEARANCE


def bumpers(gap):
    """The paper's bumpers (section 4) at the gap, m; no wall where they do not fit (the
    results are then NaN: see `fits`)."""
    import engine

    if not fits(gap):
        return engine.Contact.none(1)
    return engine.Contact.bumper([gap], thickness=THICKNESS, n_bumpers=N_BUMPERS)


def layout(n_gaps: int) -> np.ndarray:
    """(gap, barrier) -> member in one angle's block (no wall, then the bare wall and the
    bumpers per gap: plan_table): the one free run serves every gap."""
    rows = np.zeros((n_gaps, len(BARRIERS)), dtype=np.int64)
    rows[:, 1] = 1 + 2 * np.arange(n_gaps)
    rows[:, 2] = 2 + 2 * np.arange(n_gaps)
    return rows


PEAK_NAMES = ("peak_isolator_disp", "peak_floor_accel", "peak_base_accel",
              "peak_interstory_drift", "max_impact_force", "n_impacts")


def peaks_of(ds, last: str) -> dict:
    """The peaks this study keeps from a sweep's Dataset, shaped as its dims up to `last`
    (record, or record and member): isolator displacement (m), the largest floor and the
    base's acceleration (m/s^2), the largest interstory drift (m), the largest impact force
    (N) and the impacts (-)."""
    return {"peak_isolator_disp": ds.peak_isolator_disp.values,
            "peak_floor_accel": largest_floor_accel(ds.peak_total_accel.values),
            "peak_base_accel": ds.peak_total_accel.isel(floor=0).values,
            "peak_interstory_drift": largest_story_drift(ds.peak_interstory_drift.values),
            "max_impact_force": ds.max_impact_force.values,
            "n_impacts": ds.n_impacts.values}


def _store(out, where, block, gaps):
    """One angle's block of members (see `layout`) into out[name][where] (gap, barrier)."""
    rows = layout(gaps.size)
    unfit = ~fits(gaps)
    for name, values in block.items():
        target = out[name][where]
        target[...] = values[rows]
        # No bumpers were run there: nothing to report for them.
        target[unfit, 2] = -1 if name == "n_impacts" else np.nan


def _dataset(out, gaps, names, pairs, thetas, fracs, orbit_t, orbits, args):
    from engine.results import quantity
    from pipeline.archive import labelled_dataset, variable

    dims = ("record", "angle", "gap_fraction", "model", "barrier")

    def peak(name, values, what):  # the engine's declaration, as this archive holds it
        q = quantity(name)
        return variable(dims, values, q.units, f"{q.long_name} ({what})")

    data = {
        "peak_isolator_disp": peak("peak_isolator_disp", out["peak_isolator_disp"],
                                   "plan: resultant"),
        "peak_floor_accel": peak("peak_total_accel", out["peak_floor_accel"],
                                 "the largest over the floors; plan: resultant"),
        "peak_base_accel": peak("peak_total_accel", out["peak_base_accel"],
                                "the base, where the wall is hit; plan: resultant"),
        "peak_interstory_drift": peak("peak_interstory_drift", out["peak_interstory_drift"],
                                      "the largest over the stories; plan: resultant"),
        "max_impact_force": peak("max_impact_force", out["max_impact_force"],
                                 "the largest over the walls"),
        "n_impacts": peak("n_impacts", out["n_impacts"], "-1: the bumpers do not fit in the "
                          "gap, not run"),
        "gap": variable(("record", "angle", "gap_fraction"), gaps, "m",
                        "seismic gap: the fraction x the planar model's peak isolator "
                        "displacement without wall, for the component along the angle"),
    }
    n_t = max((t.size for t in orbit_t), default=0)
    if n_t:
        padded = np.full((len(orbits), n_t, 2), np.nan)
        for i, orbit in enumerate(orbits):
            padded[i, :orbit.shape[0]] = orbit
        data["orbit"] = variable(("orbit_record", "time", "direction"), padded, "m",
                                 f"isolator displacement in plan with bumpers, angle 0, gap "
                                 f"{GAP_FRACTION} x the planar peak (NaN after the record ends)")
    coords = {
        "record": variable("record", np.array(names), "1", "record pair"),
        "record_source": variable("record", np.array([p.source for p in pairs]), "1",
                                  "where the pair's components were read from"),
        "angle": variable("angle", thetas, "degree", "incidence angle: the pair rotated "
                          "counterclockwise, x towards y (planar: the component along it)"),
        "gap_fraction": variable("gap_fraction", fracs, "1", "seismic gap / the planar "
                                 "model's peak isolator displacement without wall for the "
                                 f"component along the angle (the paper's rule: {GAP_FRACTION}; "
                                 "barrier none: the same run at every fraction)"),
        "model": variable("model", np.array(MODELS), "1", "planar: the paper's model under "
                          "the component along the angle; plan: the building in plan under "
                          "the rotated pair"),
        "barrier": variable("barrier", np.array(BARRIERS), "1", "what stops the slab: "
                            f"nothing, the bare wall ({bare_wall_text()}), or "
                            f"{N_BUMPERS} bumpers of {THICKNESS / CM:g} cm a side"),
    }
    if n_t:
        coords["orbit_record"] = variable("orbit_record", np.array(names[:len(orbits)]), "1",
                                          "record pairs whose orbits are kept")
        coords["time"] = variable("time", orbit_t[int(np.argmax([t.size for t in orbit_t]))],
                                  "s", "time")
        coords["direction"] = variable("direction", np.array(["x", "y"]), "1",
                                       "horizontal direction")
    ds = labelled_dataset(data, coords, {"moat": args.moat})
    ds["bumpers_fit"] = (("record", "angle", "gap_fraction"), fits(gaps).astype(np.int8),
                         {"units": "1", "long_name": f"1 where the bumpers fit in the gap with "
                          f"{MIN_CLEARANCE / CM:g} cm to spare (else not run: NaN)"})
    ds["angle_gain"] = (("record", "model"), angle_gain(ds).transpose("record", "model").values,
                        {"units": "1", "long_name": "the largest peak isolator displacement "
                         "without wall over the angles / the larger planar peak of the two "
                         "as-recorded components (planar: the component along each angle; "
                         "plan: the resultant under the rotated pair)"})
    ds.attrs["plan_vs_planar"] = json.dumps(underestimates(ds))
    return ds


def angle_gain(ds):
    """(record, model) -: the largest peak without wall over the angles / the larger planar
    peak of the as-recorded components (angles 0 and 90: x and -y, the same peak as y)."""
    free = ds.peak_isolator_disp.sel(barrier="none").isel(gap_fraction=0)
    recorded = free.sel(model="planar", angle=list(AS_RECORDED)).max("angle")
    return free.max("angle") / recorded


def ratios(ds) -> dict:
    """plan / planar of the quantities the planar study underestimates at the paper's gap,
    each a flat array over (pair, angle), only where the planar model has something to
    compare (impacts)."""
    at = ds.sel(gap_fraction=GAP_FRACTION)
    plan, planar = at.sel(model="plan"), at.sel(model="planar")
    hit = (planar.n_impacts.sel(barrier="bumpers") > 0).values
    force = (plan.max_impact_force / planar.max_impact_force).sel(barrier="bumpers").values
    accel = (plan.peak_floor_accel / planar.peak_floor_accel).sel(barrier="bumpers").values
    free = (plan.peak_isolator_disp / planar.peak_isolator_disp).sel(barrier="none").values
    return {"isolator displacement (no wall)": free.ravel(),
            "impact force (bumpers)": force[hit].ravel(),
            "peak floor acceleration (bumpers)": accel[hit].ravel()}


GAIN_KEYS = {"planar": "largest peak over angles / larger component (planar, rotated)",
             "plan": "largest peak over angles in plan / larger component (planar)"}


def underestimates(ds) -> dict:
    """Median, 16th and 84th percentiles and extremes of each ratio (plan / planar, and the
    angle gains per pair), with its count."""
    data = dict(ratios(ds))
    for model, key in GAIN_KEYS.items():
        data[key] = ds.angle_gain.sel(model=model).values
    summary = {}
    for name, values in data.items():
        if values.size:
            q = np.quantile(values, QUANTILES)
            summary[name] = {"points": int(values.size), "p16": float(q[0]),
                             "median": float(q[1]), "p84": float(q[2]),
                             "min": float(values.min()), "max": float(values.max())}
        else:
            summary[name] = {"points": 0}
    return summary


def check(ds) -> list[Verdict]:
    """Section 4 / 5.1 at the paper's gap (bumpers can reduce the peak floor acceleration
    against the bare wall), then the paper's conclusions on the gap size over every gap
    fraction (5.1, 6): each in plan, the planar model's count beside it, counted only at the
    points where what it speaks of happens (bumpers run, walls hit as the claim says)."""
    summary = underestimates(ds)
    free = summary["isolator displacement (no wall)"]
    gains = {m: summary[k] for m, k in GAIN_KEYS.items()}
    extra = (f"; the isolator's peak in plan is x{free['median']:.2f} the planar one (median; "
             f"84th percentile x{free['p84']:.2f}); the largest peak over the angles / the "
             "larger as-recorded component's, per pair (median, 84th percentile, largest): "
             + "; ".join(f"{m} {_pct(g, 'median')}, {_pct(g, 'p84')}, {_pct(g, 'max')}"
                         for m, g in gains.items()))
    paper_gap = Claim("4, 5.1", f"At the paper's gap ({GAP_FRACTION} x the peak without wall), "
                      "bumpers can reduce the peak floor acceleration against the bare wall",
                      "some", "(pair, angle) points where the bare wall is hit (bumpers run)",
                      floor_reduced)
    out = [side_by_side(paper_gap, ds.sel(gap_fraction=[GAP_FRACTION]), extra,
                         {"plan_vs_planar": summary})]
    out += [side_by_side(claim, ds) for claim in CLAIMS]
    out.append(narrow_more_effective(ds))
    return out


def _pct(stats: dict, key: str) -> str:
    """A gain (ratio) as its excess in percent, e.g. 1.07 -> '+7%'."""
    return f"{stats[key] - 1:+.0%}" if stats.get("points") else "n/a"


def plot(ds):
    fig, (left, middle, right) = plt.subplots(1, 3, figsize=(13.5, 4.6))
    if "orbit" in ds:
        for i, name in enumerate(ds.orbit_record.values):
            orbit = ds.orbit.sel(orbit_record=name).values / CM
            left.plot(orbit[:, 0], orbit[:, 1], lw=0.7, label=str(name))
            gap = float(ds.gap.sel(record=name, angle=0.0, gap_fraction=GAP_FRACTION)) / CM
            _moat(left, gap, ds.attrs["moat"], f"C{i}", bumpers=i == 0)
        left.set_aspect("equal")
        left.set_xlabel("x (cm)")
        left.set_ylabel("y (cm)")
        left.set_title(f"orbits in plan with bumpers, angle 0, gap {GAP_FRACTION} x",
                       fontsize=9)
        left.legend(fontsize=6, loc="upper right")
    data = ratios(ds)
    # One line per part: three labels side by side in a third of the figure's width.
    labels = [f"{name.replace(' (', chr(10) + '(')}\n{values.size} points"
              for name, values in data.items()]
    middle.boxplot([v if v.size else [np.nan] for v in data.values()], whis=(5, 95),
                   showfliers=True, flierprops={"markersize": 2})
    middle.set_xticks(range(1, len(labels) + 1), labels, fontsize=7)
    middle.axhline(1.0, color="k", lw=0.8, ls="--")
    middle.set_ylabel("plan / planar")
    middle.set_title(f"plan / planar, {ds.sizes['record']} pairs x {ds.sizes['angle']} "
                     f"angles, gap {GAP_FRACTION} x", fontsize=9)
    _shares(right, ds)
    from ..common.plot import letter_panels, short_title, store_caption

    letter_panels([ax for ax in (left, middle, right) if ax.has_data()])
    short_title(fig, f"Beyond the paper: record pairs in plan, {ds.attrs['moat']} moat")
    store_caption(ds, caption(ds))
    fig.tight_layout()
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return (f"Beyond the paper: record pairs in plan, {ds.attrs['moat']} moat, the paper's "
            f"building and bumpers ({N_BUMPERS} x {THICKNESS / CM:g} cm), the gap a fraction "
            "of the planar peak without wall; the largest peak floor acceleration of any run: "
            f"{float(ds.peak_floor_accel.max()) / G:.1f} g. (a) orbits in plan with bumpers "
            "(dashed: the moats; filled: the first pair's bumpers); (b) plan / planar peaks, "
            "box 25-75%, whiskers 5-95%, above 1 the planar model underestimates; (c) the "
            "paper's gap-size conclusions against the gap.")


SHOWN = ((only_bumpers_amplify, "floor accel. amplified (only bumpers hit)"),
         (base_reduced, "base accel. reduced (bare wall hit)"),
         (drift_amplified, "drift amplified (a wall hit)"),
         (force_reduced, "impact force reduced (both hit)"))


def _shares(ax, ds):
    """Against the gap fraction: the share of the counted points where each gap-size claim
    holds, planar dashed, plan solid (no marker where nothing is counted)."""
    fracs = ds.gap_fraction.values
    for i, (rule, label) in enumerate(SHOWN):
        for model, style in (("planar", "--"), ("plan", "-")):
            held, counted, _ = counts(ds, rule)[model]
            n = counted.sum(axis=(0, 1))
            with np.errstate(invalid="ignore", divide="ignore"):
                share = np.where(n > 0, held.sum(axis=(0, 1)) / n, np.nan)
            ax.plot(fracs, share, ls=style, marker="o", ms=3, color=f"C{i}",
                    label=label if model == "plan" else None)
    ax.plot([], [], "k--", label="planar")
    ax.plot([], [], "k-", label="in plan")
    ax.axvline(GAP_FRACTION, color="0.6", lw=0.8, ls=":")
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel("seismic gap / planar peak without wall")
    ax.set_ylabel("share of the counted points where it holds")
    ax.set_title("the paper's gap-size conclusions against the gap\n(dotted: the paper's "
                 "rule)", fontsize=9)
    ax.legend(fontsize=6, loc="best")


def _moat(ax, gap, moat, color, bumpers=True):
    """The moat's outline at +-gap (cm) and, if `bumpers` and where they fit, the bumpers:
    N_BUMPERS pads of THICKNESS on each wall (on the circle: at 0, 90, 180 and 270 degrees),
    each drawn as a small filled rectangle standing on the wall."""
    if moat == "circular":
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(gap * np.cos(t), gap * np.sin(t), ls="--", lw=0.6, color=color)
    else:
        ax.plot([-gap, gap, gap, -gap, -gap], [-gap, -gap, gap, gap, -gap], ls="--", lw=0.6,
                color=color)
    if not (bumpers and fits(gap * CM)):
        return
    depth = THICKNESS / CM
    places = [0.0] if moat == "circular" else np.linspace(-0.6, 0.6, N_BUMPERS) * gap
    for sx, sy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        for along in places:
            ax.fill(*_pad(sx, sy, gap, depth, along, 0.04 * gap), color=color, lw=0)


def _pad(sx, sy, gap, depth, along, width):
    """The outline (x, y) in cm of a pad of `depth` on the wall with outward normal (sx, sy)
    at +-gap, centred `along` the wall, `width` wide."""
    inner, outer = gap - depth, gap
    lo, hi = along - width / 2, along + width / 2
    if sx:
        return [sx * inner, sx * outer, sx * outer, sx * inner], [lo, lo, hi, hi]
    return [lo, lo, hi, hi], [sy * inner, sy * outer, sy * outer, sy * inner]


recipe = Recipe(
    name="plan", figure="beyond the paper",
    summary="The paper's building and bumpers under record pairs in plan (coupled isolators, a "
            "square or circular moat) against the paper's planar model: how much the planar "
            "study underestimates, and whether the paper's gap-size conclusions hold in plan",
    compute=compute, plot=plot, check=check,
    chosen=("the 22 FEMA P695 far-field pairs (x: lower azimuth); angles 0-165 degrees every "
            f"15; gaps {', '.join(f'{f:g}' for f in FRACTIONS)} x the planar model's peak for "
            f"the component along the angle (the paper's rule: {GAP_FRACTION}); the same walls "
            "on every side; quick: 3 pairs, angles 0 and 90, gaps "
            f"{', '.join(f'{f:g}' for f in QUICK_FRACTIONS)} x"),
    records=(), options=options)
main = recipe.main
