"""Beyond the paper: what bumpers to install for a given building and gap.

For a building (the paper's by default; --building FILE and/or NAME=VALUE settings, as every
command), a record set (default: the suite studies.suite runs, studies._suite_records, every
record scaled so that the building without wall reaches D) and a gap, search the bumper
thickness, count, cavity depth (paper 5.3) and moat-wall stiffness for the configuration that
minimises the median over the records of the largest peak floor acceleration, while the bumpers
stay uncrushed (max indentation <= delta_u) under at least a chosen fraction of the records
(default 84%). The search evaluates a coarse grid in one batched sweep, then a finer grid
around the best feasible configuration; every evaluated configuration is kept in the archive
(dimension `candidate`) with its statistics and the per-record peaks, next to the reference
without bumpers (the bare wall at the full gap).
"""
from __future__ import annotations

import json

import numpy as np

from engine.impact import LAWS
from engine.units import CM, KN_PER_MM, G
from pipeline.scaling import DEFAULT_DISPLACEMENT

from ._plot import plt
from ._recipe import Recipe, Verdict
from ._suite_records import ALL, chosen_records, scaled

GAP_RATIO = 0.8  # default gap / D: narrow enough that the bare wall is hit by most records
COARSE = {  # the first grid: m, m, -, N/m
    "thickness": (0.03, 0.05, 0.08, 0.12),
    "cavity": (0.0, 0.01, 0.02),
    "n_bumpers": (4, 8, 16, 32, 64),
    "wall_k": (5e8, 1.5e9, 2.5e9),
}
QUICK = {"thickness": (0.05, 0.08), "cavity": (0.0, 0.01), "n_bumpers": (4, 16),
         "wall_k": (5e8, 2.5e9)}
STEP = {"thickness": 1.25, "cavity": 0.005, "n_bumpers": 2 ** 0.5, "wall_k": 1.5}
SEARCHED = tuple(COARSE)
BEST_FEW = 5
_LAW = LAWS["bumper"].PARAMETERS  # strain and COR are not searched: the law's defaults


def options(p) -> None:
    p.add_argument("--displacement-cm", type=float, default=DEFAULT_DISPLACEMENT / CM,
                   metavar="CM", help="design displacement D the records are scaled to "
                                      f"(default {DEFAULT_DISPLACEMENT / CM:g} cm)")
    p.add_argument("--gap-cm", type=float, default=None, metavar="CM",
                   help=f"the seismic gap to design for (default {GAP_RATIO:g} D)")
    p.add_argument("--uncrushed", type=float, default=0.84, metavar="FRACTION",
                   help="least fraction of records under which the bumpers must stay "
                        "uncrushed (default 0.84)")
    p.add_argument("--no-scale", action="store_true",
                   help="run the records as given, not scaled to D")


def compute(args):
    import pipeline
    from pipeline.errors import SweepError

    if not 0 < args.uncrushed <= 1:
        raise SweepError(f"--uncrushed must be a fraction in (0, 1], got {args.uncrushed}")
    building = args.building
    D = args.displacement_cm * CM
    gap = GAP_RATIO * D if args.gap_cm is None else args.gap_cm * CM
    records = chosen_records(args.records)
    left_out = []
    if not args.no_scale:
        at_d = scaled(records, D, dt=args.dt, building=building, records_dir=args.records_dir,
                      quiet=args.quiet)
        records, left_out = at_d.records, at_d.excluded
        if not records:
            raise SweepError("no record could be scaled to D: nothing to design for")
    run = dict(records=records, records_dir=args.records_dir, dt=args.dt,
               workers=args.workers, scheduler=args.scheduler, quiet=args.quiet,
               building=building, work_dir=args.work_dir)
    grid = QUICK if args.quick else COARSE
    first = evaluate(pipeline.sweep(gap=gap, baseline=True, **grid, **run), stage=1)
    best = choose(first, args.uncrushed)
    second = evaluate(pipeline.sweep(gap=gap, **refined(first, best, gap), **run), stage=2)
    ds = merge(first, second)
    chosen = choose(ds, args.uncrushed)
    ds = ds.assign(rank=("candidate", ranking(ds, args.uncrushed),
                         {"units": "1", "long_name": "rank among the feasible "
                          "configurations by median peak floor acceleration (1 = chosen; "
                          "0 = infeasible)"}))
    ds.attrs.update(design_gap=gap, design_gap_units="m", design_displacement=D,
                    uncrushed_fraction_required=args.uncrushed,
                    chosen_candidate=int(chosen) if chosen is not None else -1,
                    records_scaled_to_D=int(not args.no_scale),
                    records_left_out=json.dumps([{"record": n, "factor_needed": f,
                                                  "reason": r} for n, f, r in left_out]))
    return ds


def evaluate(ds, stage: int):
    """One sweep's configurations as a `candidate` dimension, with their statistics over the
    records."""
    import engine
    from pipeline.archive import variable

    present = [d for d in SEARCHED if d in ds.dims]
    peak = ds.peak_total_accel.max("floor")
    stacked = peak.stack(candidate=present).transpose("record", "candidate")
    indent = ds.max_indentation.stack(candidate=present).transpose("record", "candidate")
    config = {name: (stacked[name].values if name in present else
                     np.full(stacked.sizes["candidate"], float(ds[name])))
              for name in SEARCHED}
    gap = float(ds.gap)
    delta_u = engine.Contact.bumper(gap, thickness=config["thickness"], cavity=config["cavity"],
                                    n_bumpers=config["n_bumpers"], k_w=config["wall_k"]).delta_u
    crushed = indent.values > delta_u
    out = {
        "peak_floor_accel": variable(("record", "candidate"), stacked.values, "m s-2",
                                     "largest peak floor acceleration"),
        "crushed": variable(("record", "candidate"), crushed.astype(np.int8), "1",
                            "1 if the bumpers are crushed beyond delta_u under the record"),
        "delta_u": variable("candidate", delta_u, "m", "crush limit min(strain t, t - c_d)"),
        "stage": variable("candidate", np.full(delta_u.size, stage), "1",
                          "search stage: 1 coarse grid, 2 refinement around the best"),
    }
    coords = {name: ds[name].variable for name in ds.coords if ds[name].dims == ("record",)}
    for name in SEARCHED:
        units = ds[name].attrs["units"]
        coords[name] = variable("candidate", config[name], units, ds[name].attrs["long_name"])
    import xarray as xr

    result = xr.Dataset(out, coords=coords, attrs=ds.attrs)
    if "baseline_peak_total_accel" in ds:
        result["no_bumpers_peak_floor_accel"] = variable(
            "record", ds.baseline_peak_total_accel.max("floor").values, "m s-2",
            "largest peak floor acceleration without bumpers (bare wall at the full gap)")
    return result


def statistics(ds):
    """(median, 16th, 84th percentile of the peak floor acceleration over the records, m/s^2;
    fraction crushed) per candidate."""
    peak = ds.peak_floor_accel.values
    q16, med, q84 = np.quantile(peak, [0.16, 0.5, 0.84], axis=0)
    return med, q16, q84, ds.crushed.values.mean(axis=0)


def ranking(ds, uncrushed: float) -> np.ndarray:
    """(candidate,) rank of each feasible candidate, 0 for the infeasible: by median, then
    84th percentile; ties (k_w plays no part while the bumpers stay uncrushed) go to the
    stiffer wall, which needs no special construction."""
    med, _, q84, crushed = statistics(ds)
    feasible = crushed <= 1 - uncrushed + 1e-12
    rank = np.zeros(med.size, dtype=int)
    order = [i for i in np.lexsort((-ds.wall_k.values, q84, med)) if feasible[i]]
    rank[order] = np.arange(1, len(order) + 1)
    return rank


def choose(ds, uncrushed: float):
    """Index of the feasible candidate with the lowest median, or None."""
    rank = ranking(ds, uncrushed)
    return int(np.flatnonzero(rank == 1)[0]) if np.any(rank == 1) else None


def refined(first, best, gap: float) -> dict:
    """A finer grid around the best feasible candidate of the first stage (or, if none is
    feasible, the one crushed under the fewest records)."""
    if best is None:
        best = int(np.argmin(statistics(first)[3]))
    at = {name: float(first[name].values[best]) for name in SEARCHED}
    t = at["thickness"]
    grid = {
        "thickness": sorted({t / STEP["thickness"], t, t * STEP["thickness"]}),
        "n_bumpers": sorted({max(1, round(at["n_bumpers"] / STEP["n_bumpers"])),
                             int(at["n_bumpers"]),
                             round(at["n_bumpers"] * STEP["n_bumpers"])}),
        "wall_k": sorted({at["wall_k"] / STEP["wall_k"], at["wall_k"],
                          at["wall_k"] * STEP["wall_k"]}),
    }
    # cavities shallower than the thinnest bumper, and bumpers that leave a clear gap
    t_min = min(grid["thickness"])
    grid["cavity"] = sorted({c for c in (at["cavity"] - STEP["cavity"], at["cavity"],
                                         at["cavity"] + STEP["cavity"])
                             if 0 <= c < 0.9 * t_min})
    grid["thickness"] = [x for x in grid["thickness"] if x - min(grid["cavity"]) < 0.9 * gap]
    return {name: np.round(values, 6).tolist() for name, values in grid.items()}


def merge(first, second):
    import xarray as xr

    second = second.drop_vars([v for v in ("no_bumpers_peak_floor_accel",) if v in second])
    ds = xr.concat([first, second], dim="candidate", data_vars="minimal",
                   coords="minimal", compat="override", combine_attrs="override")
    med, q16, q84, crushed = statistics(ds)
    reference = ds.no_bumpers_peak_floor_accel.values
    ds["median_peak_floor_accel"] = ("candidate", med, {
        "units": "m s-2", "long_name": "median over the records of the largest peak floor "
        "acceleration"})
    ds["p16_peak_floor_accel"] = ("candidate", q16, {
        "units": "m s-2", "long_name": "16th percentile over the records"})
    ds["p84_peak_floor_accel"] = ("candidate", q84, {
        "units": "m s-2", "long_name": "84th percentile over the records"})
    ds["fraction_crushed"] = ("candidate", crushed, {
        "units": "1", "long_name": "fraction of records crushing the bumpers beyond delta_u"})
    ds["median_amplification"] = ("candidate", np.median(
        ds.peak_floor_accel.values / reference[:, None], axis=0), {
        "units": "1", "long_name": "median over the records of the largest peak floor "
        "acceleration with these bumpers / without bumpers"})
    return ds


def describe(ds, i: int) -> str:
    return (f"t {float(ds.thickness[i]) / CM:g} cm, cavity {float(ds.cavity[i]) / CM:g} cm, "
            f"{int(ds.n_bumpers[i])} bumpers, k_w {float(ds.wall_k[i]) / KN_PER_MM:g} kN/mm")


def table(ds) -> list[str]:
    """The best few feasible candidates and the reference, as text lines."""
    lines = [f"{'rank':>4}  {'configuration':58s} {'median g':>8} {'16-84% g':>13} "
             f"{'crushed':>7} {'x none':>6}"]
    order = np.argsort(np.where(ds["rank"].values > 0, ds["rank"].values, 10 ** 9))
    for i in order[:BEST_FEW]:
        if ds["rank"].values[i] == 0:
            break
        lines.append(f"{int(ds['rank'][i]):4d}  {describe(ds, i):58s} "
                     f"{float(ds.median_peak_floor_accel[i]) / G:8.3f} "
                     f"{float(ds.p16_peak_floor_accel[i]) / G:6.3f}-"
                     f"{float(ds.p84_peak_floor_accel[i]) / G:6.3f} "
                     f"{float(ds.fraction_crushed[i]):7.0%} "
                     f"{float(ds.median_amplification[i]):6.2f}")
    ref = ds.no_bumpers_peak_floor_accel.values
    lines.append(f"{'-':>4}  {'no bumpers (bare wall at the full gap)':58s} "
                 f"{np.median(ref) / G:8.3f} {np.quantile(ref, 0.16) / G:6.3f}-"
                 f"{np.quantile(ref, 0.84) / G:6.3f} {'-':>7} {1:6.2f}")
    return lines


def plot(ds):
    fig, ax = plt.subplots(figsize=(6, 4.2), layout="constrained")
    med = ds.median_peak_floor_accel.values / G
    crushed = ds.fraction_crushed.values
    for stage, marker in ((1, "o"), (2, "s")):
        sel = ds.stage.values == stage
        points = ax.scatter(crushed[sel], med[sel], c=np.log2(ds.n_bumpers.values[sel]),
                            marker=marker, s=14, cmap="viridis", vmin=1, vmax=7,
                            label="coarse grid" if stage == 1 else "refinement")
    fig.colorbar(points, ax=ax, label="log2(bumpers per side)")
    limit = 1 - float(ds.attrs["uncrushed_fraction_required"])
    ax.axvline(limit, color="k", ls=":", lw=0.8, label=f"crushed under {limit:.0%} of records")
    ax.axhline(np.median(ds.no_bumpers_peak_floor_accel.values) / G, color="k", ls="--",
               lw=0.8, label="no bumpers (median)")
    chosen = int(ds.attrs["chosen_candidate"])
    if chosen >= 0:
        ax.plot(crushed[chosen], med[chosen], marker="*", ms=14, color="C3", ls="none",
                label="chosen: " + describe(ds, chosen))
    ax.set_xlabel("fraction of records crushing the bumpers")
    ax.set_ylabel("median largest peak floor acceleration (g)")
    ax.set_title(f"Bumper design at a {float(ds.attrs['design_gap']) / CM:g} cm gap, "
                 f"{ds.sizes['record']} records")
    ax.legend(fontsize=6)
    return fig


def check(ds) -> list[Verdict]:
    """The chosen design against the paper's advice (5.3 cavities, 5.5 soft wall), and the
    benefit over the bare wall."""
    for line in table(ds):
        print(line)
    chosen = int(ds.attrs["chosen_candidate"])
    if chosen < 0:
        return [Verdict("design", "A feasible bumper design exists", "no configuration keeps "
                        "the bumpers uncrushed under enough records", False)]
    c = {name: float(ds[name][chosen]) for name in SEARCHED}
    med = ds.median_peak_floor_accel.values
    cavity = ds.cavity.values > 0
    best_cav = float(med[cavity].min()) if cavity.any() else None
    best_none = float(med[~cavity].min()) if (~cavity).any() else None
    soft, stiff = ds.wall_k.values == ds.wall_k.values.min(), \
        ds.wall_k.values == ds.wall_k.values.max()
    best_soft, best_stiff = float(med[soft].min()), float(med[stiff].min())
    amp = float(ds.median_amplification[chosen])
    return [
        Verdict("5.3", "Bumpers set in cavities (using more of the rubber) lower the responses",
                f"lowest median peak floor acceleration among all evaluated designs: "
                f"{best_cav / G:.3f} g with a cavity, {best_none / G:.3f} g without"
                if best_cav is not None and best_none is not None else "not both evaluated",
                (best_cav < best_none) if best_cav is not None and best_none is not None
                else None, {"best_with_cavity": best_cav, "best_without_cavity": best_none}),
        Verdict("5.5", "A flexible moat wall is an effective mitigation measure",
                f"lowest median peak floor acceleration with k_w "
                f"{float(ds.wall_k.min()) / KN_PER_MM:g} kN/mm {best_soft / G:.3f} g, with "
                f"{float(ds.wall_k.max()) / KN_PER_MM:g} kN/mm {best_stiff / G:.3f} g"
                + (" (equal: the best designs keep the bumpers uncrushed, where k_w plays "
                   "no part)" if best_soft == best_stiff else ""),
                None if best_soft == best_stiff else bool(best_soft < best_stiff),
                {"best_soft_wall": best_soft, "best_stiff_wall": best_stiff}),
        Verdict("6", "Bumpers, well chosen, reduce the floor accelerations against the bare "
                "wall", f"chosen design ({describe(ds, chosen)}): median amplification "
                f"{amp:.2f}", bool(amp < 1), {"chosen": c, "median_amplification": amp}),
    ]


recipe = Recipe(
    name="design", figure="beyond the paper",
    summary="Bumper design search: thickness, count, cavity depth and wall stiffness that "
            "minimise the median peak floor acceleration over a record suite scaled to D, "
            "with the bumpers uncrushed under a chosen fraction of the records",
    compute=compute, plot=plot, check=check, records=(ALL,), options=options,
    chosen=f"gap {GAP_RATIO:g} D, D = {DEFAULT_DISPLACEMENT / CM:g} cm; coarse grid thickness "
           "3-12 cm, cavity 0-2 cm, 4-64 bumpers, k_w 500-2500 kN/mm, then a 3-point "
           f"refinement of each around the best; strain {_LAW['strain'].default:g} and COR "
           f"{_LAW['cor'].default:g} (the law's defaults)")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
