"""Check the loss study's interval of the expected annual loss against full refits.

The loss study's paired bootstrap (pipeline.assess.annual_loss) moves a stripe's mean repair
cost given no collapse by the runs' own costs, relative, instead of refitting pelicun's demand
model for each resampling of the earthquakes. For a few of the collapse archive's resamplings
this tool does the refit: the runs of every drawn earthquake repeated as often as it is drawn,
the demand model fitted to them and every stripe assessed again (one pelicun assessment a
draw, about 40 s on 2 cores); it prints, per draw, the approximation's expected annual loss
and its ratio to the bare wall's at the same gap over the refit's, and writes them as JSON.

    python tools/check_eal_interval.py --collapse results/collapse.nc

It takes the loss study's options (the same site, building and pairs as the collapse archive)
and runs the loss study's simulations first (about 1.5 min at the default site). Costs in USD
of 2011.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

PROJECT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(PROJECT))

DRAWS = (3, 17, 101, 250, 433, 777)
"""The resamplings checked by default (indices into the collapse archive's 1000)."""


def arguments(argv):
    """The loss study's arguments (its parser's) with this tool's own: draws and report."""
    from studies import loss

    own = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], epilog="Every other option is the loss "
        "study's (python -m studies.loss --help); --collapse is required.")
    own.add_argument("--draws", type=int, nargs="+", default=list(DRAWS), metavar="K",
                     help="the resamplings to refit (indices into the collapse archive's "
                          f"draws; default {' '.join(map(str, DRAWS))})")
    own.add_argument("--report", default=str(PROJECT / "results" / "eal_interval_check.json"),
                     metavar="JSON", help="where the comparison goes (default "
                                          "results/eal_interval_check.json)")
    mine, rest = own.parse_known_args(argv)
    parser = loss.recipe.parser()
    args = parser.parse_args(rest)
    if not args.collapse:
        parser.error("--collapse: give the collapse archive whose resamplings are checked")
    args.draws, args.report = mine.draws, mine.report
    return args


def stripes(args):
    """The loss study's groups at every stripe and configuration: (peaks, standing runs (R, L,
    B, G) bool, the suite, the collapse archive, the levels, the stories' yield drift)."""
    import xarray as xr

    from pipeline.building_file import building_from
    from studies import loss
    from studies.common import collapse_ida as collapse

    args.building = building_from(args.building)
    args.samples = args.samples or loss.p58.SAMPLES
    fragility = xr.load_dataset(args.collapse)
    suite = collapse.oriented_suite(args)
    loss.same_basis(fragility, suite)
    counts = [int(b.split()[0]) for b in fragility.barrier.values[2:]]
    levels = np.array(loss.QUICK_LEVELS if args.quick else loss.LEVELS, float)
    peaks, _ = loss.run(suite, levels, fragility.gap.values, counts, args)
    height = np.asarray(suite.building.story_height, float)
    drift = float(np.median(np.asarray(suite.building.story_yield_drift) / height))
    return peaks, ~peaks["collapsed"].astype(bool), suite, fragility, levels, drift


def model_means(peaks, standing, repeat, drift, args):
    """(the fitted demand model's mean repair cost given no collapse (L, B, G), pelicun's
    output) with each run repeated `repeat` (R,) times in its stripe's demand model."""
    from pipeline.assess import loss as p58

    height = np.asarray(args.building.story_height, float)
    ratio = peaks["peak_interstory_drift_xy"] / height[:, None]
    shape = standing.shape[1:]
    groups = []
    for index in np.ndindex(shape):
        keep = standing[(slice(None), *index)]
        runs = np.repeat(np.flatnonzero(keep), repeat[keep])
        groups.append(p58.Group(peaks["peak_total_accel_xy"][(runs, *index)],
                                ratio[(runs, *index)], 0.0))
    out = p58.losses(groups, p58.read_inventory(args.inventory), stories=len(height),
                     floor_area=args.floor_area, yield_drift=drift, samples=args.samples,
                     seed=1)
    return out["repair_cost"].reshape(*shape, -1).mean(axis=-1), out


def compare(args) -> list[dict]:
    """Per checked draw: the approximation's EAL and its ratio to the bare wall's over a full
    refit's, per barrier and gap."""
    from pipeline.assess import annual_loss, hazard
    from pipeline.assess.collapse import resampled_weights

    peaks, standing, suite, fragility, levels, drift = stripes(args)
    args.building = suite.building
    full, out = model_means(peaks, standing, np.ones(standing.shape[0], int), drift, args)
    runs = annual_loss.runs_in_place(out["run_repair_cost"], standing)
    weights = np.asarray(suite.weights, float)
    mce = fragility.collapse_probability_draws.transpose("draw", "barrier", "gap_fraction")
    draws = resampled_weights(weights, suite.events, draws=mce.sizes["draw"])
    beta = fragility.beta_total.transpose("barrier", "gap_fraction").values
    s_mt = float(suite.target.at(suite.design.t_m))
    curve = hazard.from_table(args.hazard) if args.hazard else hazard.default(s_mt)
    bare = list(fragility.barrier.values).index("bare wall")
    found = []
    for d in args.draws:
        p_c = annual_loss.stripe_collapse(levels, mce.values[[d]], beta)
        times = np.rint(draws[:, d] / weights).astype(int)  # how often its earthquake is drawn
        refit, _ = model_means(peaks, standing, times, drift, args)
        approx = annual_loss.given_no_collapse(full, runs, standing, weights, draws[:, [d]])
        eal = {name: annual_loss.annual_loss(levels * s_mt, annual_loss.stripe_means(
            p_c, given, out["replacement_cost"]), curve)[0]
            for name, given in (("refit", refit[None]), ("approx", approx))}
        ratio = {k: v / v[bare] for k, v in eal.items()}
        found.append({"draw": d, "barrier": [str(b) for b in fragility.barrier.values],
                      "gap_fraction": fragility.gap_fraction.values.tolist(),
                      "eal_approx_over_refit": (eal["approx"] / eal["refit"]).tolist(),
                      "ratio_approx_over_refit": (ratio["approx"] / ratio["refit"]).tolist()})
        print(f"draw {d}: EAL approximation / refit {np.min(eal['approx'] / eal['refit']):.3f}"
              f"-{np.max(eal['approx'] / eal['refit']):.3f}, its ratio to the bare wall's "
              f"{np.min(ratio['approx'] / ratio['refit']):.3f}"
              f"-{np.max(ratio['approx'] / ratio['refit']):.3f}", flush=True)
    return found


def main(argv=None) -> int:
    args = arguments(sys.argv[1:] if argv is None else argv)
    found = compare(args)
    e = np.abs(np.log([f["eal_approx_over_refit"] for f in found]))
    r = np.abs(np.log([f["ratio_approx_over_refit"] for f in found]))
    summary = {"draws": len(found), "eal_within": [float(np.exp(-e.max())),
                                                   float(np.exp(e.max()))],
               "eal_median_abs_log": float(np.median(e)),
               "ratio_within": [float(np.exp(-r.max())), float(np.exp(r.max()))],
               "ratio_median_abs_log": float(np.median(r)),
               "ratio_abs_log_90": float(np.quantile(r, 0.9))}
    print(f"over {len(found)} draws and every configuration: the EAL within "
          f"{summary['eal_within'][0]:.2f}-{summary['eal_within'][1]:.2f} of a refit's (median "
          f"{summary['eal_median_abs_log']:.1%}); its ratio to the bare wall's within "
          f"{summary['ratio_within'][0]:.2f}-{summary['ratio_within'][1]:.2f} (median "
          f"{summary['ratio_median_abs_log']:.1%}, 90% within "
          f"{summary['ratio_abs_log_90']:.1%})")
    report = Path(args.report)
    report.parent.mkdir(parents=True, exist_ok=True)
    report.write_text(json.dumps({"summary": summary, "draws": found}, indent=1))
    print("wrote", report)
    return 0


if __name__ == "__main__":
    sys.exit(main())
