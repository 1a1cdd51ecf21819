"""Plan (beyond the paper): the paper's building and bumpers under record pairs, moving in both
horizontal directions, against the planar model the paper uses.

For every pair (default: the 22 FEMA P695 far-field pairs) and incidence angle theta (0-165
degrees, every 15), the planar model runs the pair's component along theta (the paper's
model: one component, walls on either side of one axis) and the model in plan runs the whole
pair rotated by theta (engine.simulate with a record pair: coupled isolators, a square or
circular moat). Both at the paper's gap rule (section 4): gap = 0.9 x the planar model's peak
isolator displacement without wall, for that component; each without wall, against the bare
wall (the paper's baseline) and with the paper's bumpers (4 x 5 cm a side).

How much the planar study underestimates: the ratio plan / planar of the peak isolator
displacement (without wall), of the largest impact force and of the largest peak floor
acceleration (bumpers; where the planar model is hit), over pairs and angles. And whether the
paper's conclusion on bumpers at its gap (section 4, 5.1: they can reduce the peak base
acceleration against the bare wall) holds in plan.
"""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM, G

from ._paper import GAP_FRACTION, N_BUMPERS, THICKNESS
from ._plot import plt
from ._recipe import Recipe, Verdict

BARRIERS = ("none", "bare wall", "bumpers")
MODELS = ("planar", "plan")
ORBITS = 3  # pairs whose orbits (plan, bumpers, angle 0) the figure draws
MIN_CLEARANCE = 0.01  # m: the least clear gap in front of the bumpers for them to be run
QUANTILES = (0.16, 0.5, 0.84)


def default_pairs(quick: bool) -> list[str]:
    from pipeline.records import pair_names

    names = pair_names("far-field")
    return names[:3] if quick else names


def angles(quick: bool) -> np.ndarray:
    """Incidence angles in degrees: 0-165 every 15 (quick: 0 and 90)."""
    return np.array([0.0, 90.0]) if quick else np.arange(0.0, 180.0, 15.0)


def options(p) -> None:
    p.add_argument("--moat", choices=("rectangular", "circular"), default="rectangular",
                   help="the moat in plan: walls normal to x and y at +- the gap (default), or "
                        "a circle of radius the gap")


def compute(args):
    import engine
    from pipeline.errors import resolve_pairs

    pairs, names = resolve_pairs(args.records or default_pairs(args.quick), args.records_dir)
    thetas = angles(args.quick)
    dt = engine.DEFAULT_DT if args.dt is None else args.dt
    shape = (len(pairs), thetas.size, len(MODELS), len(BARRIERS))
    out = {name: np.zeros(shape) for name in ("peak_isolator_disp", "peak_floor_accel",
                                              "max_impact_force")}
    impacts = np.zeros(shape, dtype=np.int64)
    gaps = np.zeros(shape[:2])
    orbit_t, orbits = [], []
    rad = np.radians(thetas)
    for p, pair in enumerate(pairs):
        if not args.quiet:
            print(f"plan: {p + 1}/{len(pairs)} {names[p]}", flush=True)
        accel, acc_dt = pair.accel, pair.dt
        for a, theta in enumerate(rad):
            along = np.cos(theta) * accel[:, 0] - np.sin(theta) * accel[:, 1]
            free = engine.simulate(along, acc_dt, engine.Contact.none(1), args.building, dt)
            gaps[p, a] = GAP_FRACTION * free.peak_isolator_disp[0]
            walls = engine.Contact.concat([engine.Contact.none(1), bare(gaps[p, a]),
                                           bumpers(gaps[p, a])])
            planar = engine.simulate(along, acc_dt, walls, args.building, dt)
            _store(out, impacts, planar, p, a, 0, fits(gaps[p, a]))
        contact = engine.Contact.concat([c for g in gaps[p] for c in (
            engine.Contact.none(1), bare(g), bumpers(g))])
        history = engine.History([2], every=10) if p < ORBITS else None
        plan = engine.simulate(accel, acc_dt, contact, args.building, dt, history=history,
                               moat=args.moat, angle=np.repeat(thetas, len(BARRIERS)))
        for a in range(thetas.size):
            _store(out, impacts, plan, p, a, 1, fits(gaps[p, a]), slice(a * 3, a * 3 + 3))
        if history is not None:
            orbit_t.append(plan.history["time"])
            orbits.append(plan.history["isolator_disp"][0])
    return _dataset(out, impacts, gaps, names, pairs, thetas, orbit_t, orbits, args)


def bare(gap):
    """The paper's bare wall (the linear law at its defaults) at the gap, m."""
    import engine

    return engine.Contact.linear([gap])


def fits(gap) -> bool:
    """Whether the paper's bumpers fit in the gap (m) with room to spare: a weak record's
    0.9 x rule gives gaps the 5 cm pads would fill."""
    return gap > THICKNESS + MIN_CLEARANCE


def bumpers(gap):
    """The paper's bumpers (section 4) at the gap, m; no wall where they do not fit (the
    results are then NaN: see `fits`)."""
    import engine

    if not fits(gap):
        return engine.Contact.none(1)
    return engine.Contact.bumper([gap], thickness=THICKNESS, n_bumpers=N_BUMPERS)


def _store(out, impacts, result, p, a, model, fit, rows=slice(0, 3)):
    out["peak_isolator_disp"][p, a, model] = result.peak_isolator_disp[rows]
    out["peak_floor_accel"][p, a, model] = result.peak_total_accel[rows].max(axis=1)
    out["max_impact_force"][p, a, model] = result.max_impact_force[rows]
    impacts[p, a, model] = result.n_impacts[rows]
    if not fit:  # no bumpers were run: nothing to report for them
        for name in out:
            out[name][p, a, model, 2] = np.nan
        impacts[p, a, model, 2] = -1


def _dataset(out, impacts, gaps, names, pairs, thetas, orbit_t, orbits, args):
    from engine.results import quantity
    from pipeline.archive import labelled_dataset, variable

    dims = ("record", "angle", "model", "barrier")

    def peak(name, values, what):  # the engine's declaration, as this archive holds it
        q = quantity(name)
        return variable(dims, values, q.units, f"{q.long_name} ({what})")

    data = {
        "peak_isolator_disp": peak("peak_isolator_disp", out["peak_isolator_disp"],
                                   "plan: resultant"),
        "peak_floor_accel": peak("peak_total_accel", out["peak_floor_accel"],
                                 "the largest over the floors; plan: resultant"),
        "max_impact_force": peak("max_impact_force", out["max_impact_force"],
                                 "the largest over the walls"),
        "n_impacts": peak("n_impacts", impacts, "-1: the bumpers do not fit in the gap, "
                          "not run"),
        "gap": variable(("record", "angle"), gaps, "m",
                        f"seismic gap: {GAP_FRACTION} x the planar model's peak isolator "
                        "displacement without wall, for the component along the angle"),
    }
    n_t = max((t.size for t in orbit_t), default=0)
    if n_t:
        padded = np.full((len(orbits), n_t, 2), np.nan)
        for i, orbit in enumerate(orbits):
            padded[i, :orbit.shape[0]] = orbit
        data["orbit"] = variable(("orbit_record", "time", "direction"), padded, "m",
                                 "isolator displacement in plan with bumpers, angle 0 (NaN "
                                 "after the record ends)")
    coords = {
        "record": variable("record", np.array(names), "1", "record pair"),
        "record_source": variable("record", np.array([p.source for p in pairs]), "1",
                                  "where the pair's components were read from"),
        "angle": variable("angle", thetas, "degree", "incidence angle: the pair rotated "
                          "counterclockwise, x towards y (planar: the component along it)"),
        "model": variable("model", np.array(MODELS), "1", "planar: the paper's model under "
                          "the component along the angle; plan: the building in plan under "
                          "the rotated pair"),
        "barrier": variable("barrier", np.array(BARRIERS), "1", "what stops the slab: "
                            "nothing, the bare wall (linear law, k 2500 kN/mm, COR 0.5), or "
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
    fit = np.vectorize(fits)(gaps)
    ds["bumpers_fit"] = (("record", "angle"), fit.astype(np.int8),
                         {"units": "1", "long_name": f"1 where the bumpers fit in the gap with "
                          f"{MIN_CLEARANCE / CM:g} cm to spare (else not run: NaN)"})
    ds.attrs["plan_vs_planar"] = json.dumps(underestimates(ds))
    return ds


def ratios(ds) -> dict:
    """plan / planar of the quantities the planar study underestimates, each a flat array over
    (pair, angle), only where the planar model has something to compare (impacts)."""
    plan, planar = ds.sel(model="plan"), ds.sel(model="planar")
    hit = (planar.n_impacts.sel(barrier="bumpers") > 0).values
    force = (plan.max_impact_force / planar.max_impact_force).sel(barrier="bumpers").values
    accel = (plan.peak_floor_accel / planar.peak_floor_accel).sel(barrier="bumpers").values
    free = (plan.peak_isolator_disp / planar.peak_isolator_disp).sel(barrier="none").values
    return {"isolator displacement (no wall)": free.ravel(),
            "impact force (bumpers)": force[hit].ravel(),
            "peak floor acceleration (bumpers)": accel[hit].ravel()}


def underestimates(ds) -> dict:
    """Median, 16th and 84th percentiles and extremes of each ratio, with its count."""
    summary = {}
    for name, values in ratios(ds).items():
        if values.size:
            q = np.quantile(values, QUANTILES)
            summary[name] = {"points": int(values.size), "p16": float(q[0]),
                             "median": float(q[1]), "p84": float(q[2]),
                             "min": float(values.min()), "max": float(values.max())}
        else:
            summary[name] = {"points": 0}
    return summary


def check(ds) -> list[Verdict]:
    """Section 4 / 5.1: at the paper's gap, bumpers can reduce the peak base acceleration
    against the bare wall; does it hold in plan? The comparison counts only (pair, angle)
    points where the bare wall is hit."""
    out = []
    counts = {}
    for model in MODELS:
        sel = ds.sel(model=model)
        hit = (sel.n_impacts.sel(barrier="bare wall") > 0).values
        reduced = (sel.peak_floor_accel.sel(barrier="bumpers")
                   < sel.peak_floor_accel.sel(barrier="bare wall")).values & hit
        counts[model] = (int(reduced.sum()), int(hit.sum()))
    (r_planar, n_planar), (r_plan, n_plan) = counts["planar"], counts["plan"]
    summary = json.loads(ds.attrs["plan_vs_planar"])
    free = summary["isolator displacement (no wall)"]
    out.append(Verdict(
        "4, 5.1", "At the paper's gap (0.9 x the peak without wall), bumpers can reduce the "
        "peak floor acceleration against the bare wall",
        f"planar: at {r_planar}/{n_planar} (pair, angle) points where the bare wall is hit; "
        f"in plan: at {r_plan}/{n_plan}; the isolator's peak in plan is x{free['median']:.2f} "
        f"the planar one (median; 84th percentile x{free['p84']:.2f})",
        (r_plan > 0) if n_plan else None,
        {"reduced_planar": r_planar, "hit_planar": n_planar, "reduced_plan": r_plan,
         "hit_plan": n_plan, "plan_vs_planar": summary}))
    return out


def plot(ds):
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.6))
    if "orbit" in ds:
        for i, name in enumerate(ds.orbit_record.values):
            orbit = ds.orbit.sel(orbit_record=name).values / CM
            left.plot(orbit[:, 0], orbit[:, 1], lw=0.7, label=str(name))
            gap = float(ds.gap.sel(record=name, angle=0.0)) / CM
            _moat(left, gap, ds.attrs["moat"], f"C{i}")
        left.set_aspect("equal")
        left.set_xlabel("x (cm)")
        left.set_ylabel("y (cm)")
        left.set_title("isolator orbits in plan with bumpers, angle 0\n"
                       "dashed: each pair's moat (0.9 x the planar peak); bumpers: ticks")
        left.legend(fontsize=6, loc="upper right")
    data = ratios(ds)
    labels = [f"{name}\n({values.size} points)" for name, values in data.items()]
    right.boxplot([v if v.size else [np.nan] for v in data.values()], whis=(5, 95),
                  showfliers=True, flierprops={"markersize": 2})
    right.set_xticks(range(1, len(labels) + 1), labels, fontsize=7)
    right.axhline(1.0, color="k", lw=0.8, ls="--")
    right.set_ylabel("plan / planar")
    right.set_title(f"the building in plan against the planar model, {ds.sizes['record']} "
                    f"pairs x {ds.sizes['angle']} angles\nbox: 25-75%, whiskers 5-95%; "
                    "above 1, the planar study underestimates")
    fig.suptitle(f"Beyond the paper: record pairs in plan, {ds.attrs['moat']} moat, the "
                 f"paper's building and bumpers ({N_BUMPERS} x {THICKNESS / CM:g} cm), gap "
                 f"{GAP_FRACTION} x the planar peak; the largest peak floor acceleration "
                 f"of any run: {float(ds.peak_floor_accel.max()) / G:.1f} g", fontsize=8)
    fig.tight_layout()
    return fig


def _moat(ax, gap, moat, color):
    """The moat's outline at +-gap (cm) and the bumpers' places (the walls' middles)."""
    if moat == "circular":
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(gap * np.cos(t), gap * np.sin(t), ls="--", lw=0.6, color=color)
    else:
        ax.plot([-gap, gap, gap, -gap, -gap], [-gap, -gap, gap, gap, -gap], ls="--", lw=0.6,
                color=color)
    t = THICKNESS / CM
    for sx, sy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        ax.plot(*_bumper(sx, sy, gap, t), color=color, lw=2)


def _bumper(sx, sy, gap, t):
    """A bumper on the wall with outward normal (sx, sy), drawn as a short thick tick of its
    thickness t (cm) at the wall's middle."""
    if sx:
        return [sx * (gap - t), sx * gap], [0.0, 0.0]
    return [0.0, 0.0], [sy * (gap - t), sy * gap]


recipe = Recipe(
    name="plan", figure="beyond the paper",
    summary="The paper's building and bumpers under record pairs in plan (coupled isolators, a "
            "square or circular moat) against the paper's planar model: how much the planar "
            "study underestimates",
    compute=compute, plot=plot, check=check,
    chosen=(f"the 22 FEMA P695 far-field pairs (x: lower azimuth); angles 0-165 degrees every "
            f"15; gap {GAP_FRACTION} x the planar model's peak for the component along the "
            "angle; the same walls on every side; quick: 3 pairs, angles 0 and 90"),
    records=(), options=options)
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
