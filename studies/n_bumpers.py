"""Figs. 19-20: peak responses and maximum indentation against the seismic gap width for 4, 8,
16 and 32 bumpers on each side.

Gap 15-45 cm, 5 cm bumpers (clear gap gap - 5 cm; 4 to 32 bumpers in parallel:
0.36 to 2.85 kN/mm^2.65), k_w = 1500 kN/mm, the four paper records. Fig. 19: peak floor
acceleration and interstory deflection, the bare wall without bumpers dashed; Fig. 20: maximum
indentation, with the bumpers' capacity 0.8 x 5 cm = 4 cm drawn.
"""
from __future__ import annotations

import numpy as np

from engine.units import CM, KN_PER_MM, MM

from .common.paper import FIG19_COUNTS, STRAIN, THICKNESS, WALL_K
from .common.peaks_vs_gap import accel_g, drift_cm, gaps, plot_vs_gap, ranges, vs_gap_caption
from .common.recipe import Recipe, Verdict, sweep_options

LIMIT = STRAIN * THICKNESS  # m: delta_u, 4 cm
ALMOST_ALL = 0.75  # share of the points for 'almost all cases'
READING = 0.01  # 'stays below delta_u' to within 1% of it (0.4 mm): how far Fig. 20 reads


def compute(args):
    import pipeline

    return pipeline.sweep(gap=gaps(args.quick), thickness=THICKNESS, strain=STRAIN,
                          n_bumpers=list(FIG19_COUNTS), wall_k=WALL_K, baseline=True,
                          unconstrained=True, **sweep_options(args))


TITLE = ("Figs. 19-20: peak responses and maximum indentation vs seismic gap, "
         f"number of {THICKNESS / CM:g} cm bumpers per side ($k_w$ = "
         f"{WALL_K / KN_PER_MM:g} kN/mm)")
"""The figure's one-line title (its caption: caption)."""


def plot(ds):
    return plot_vs_gap(ds, "n_bumpers", lambda n: f"{n:g} bumpers",
                       TITLE, indentation_limit=LIMIT)


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return vs_gap_caption(TITLE)


def check(ds) -> list[Verdict]:
    """Paper 5.4: more bumpers raise the peak responses in almost all cases, except at some
    very narrow gaps where few bumpers are crushed past delta_u; more bumpers, smaller maximum
    indentation; with 32 bumpers it stays below 4 cm under every record."""
    accel, drift, dent = accel_g(ds), drift_cm(ds), ds.max_indentation
    few, many = ds.n_bumpers.values.min(), ds.n_bumpers.values.max()
    hit = (ds.n_impacts > 0).any("n_bumpers")
    n = int(hit.sum())
    higher = [q.sel(n_bumpers=many) > q.sel(n_bumpers=few) for q in (accel, drift)]
    counts = [int((h & hit).sum()) for h in higher]
    exception = hit & ~(higher[0] & higher[1])
    n_exceptions = int(exception.sum())
    crushed = exception & (dent.sel(n_bumpers=few) > LIMIT)
    gap_cm = ds.gap.values / CM
    where = {str(r): gap_cm[exception.sel(record=r).values].tolist() for r in ds.record.values
             if exception.sel(record=r).any()}
    where_text = "; ".join(f"{r} {ranges(gap_cm, np.isin(gap_cm, g))}"
                           for r, g in where.items())
    shrinking = int(((dent.diff("n_bumpers") < 0).all("n_bumpers") & hit).sum())
    worst = dent.sel(n_bumpers=many).max("gap")
    over = float(worst.max()) - LIMIT
    per_record = {str(r): float(worst.sel(record=r)) for r in ds.record.values}
    return [
        Verdict("5.4", "More bumpers raise the peak responses in almost all cases",
                f"{many} rather than {few} bumpers give a higher peak acceleration at "
                f"{counts[0]}/{n} and a higher peak interstory deflection at {counts[1]}/{n} "
                f"(record, gap) points with impacts (almost all: >= {ALMOST_ALL:.0%})",
                min(counts) >= ALMOST_ALL * n if n else None,
                {"points": n, "higher_accel": counts[0], "higher_drift": counts[1]}),
        Verdict("5.4", "Except at some very narrow gaps, where fewer bumpers are crushed past "
                "delta_u", f"{n_exceptions} exceptions (gaps in cm: {where_text or 'none'}), "
                f"{int(crushed.sum())} of them with {few} bumpers past delta_u = "
                f"{LIMIT / CM:g} cm",
                int(crushed.sum()) > n_exceptions / 2 if n_exceptions else None,
                {"exceptions": n_exceptions, "crushed_there": int(crushed.sum()),
                 "exception_gaps_cm": where}),
        Verdict("5.4", "More bumpers, smaller maximum indentation",
                f"it shrinks at every doubling at {shrinking}/{n} points with impacts",
                shrinking >= ALMOST_ALL * n if n else None,
                {"points": n, "shrinking": shrinking}),
        Verdict("5.4", f"With {many} bumpers the indentation stays below {LIMIT / CM:g} cm for "
                "every record", "largest " + ", ".join(f"{r} {v / CM:.3f}" for r, v in
                                                        per_record.items()) + " cm"
                + (f", {over / MM:.2f} mm over" if over > 0 else "")
                + f" (below: to within {READING:.0%} of it, {READING * LIMIT / MM:.1f} mm)",
                over <= READING * LIMIT,
                {"largest_indentation": per_record, "limit": LIMIT, "over": over,
                 "tolerance": READING * LIMIT}),
    ]


recipe = Recipe(
    name="n_bumpers", figure="Figs. 19-20",
    summary="Peak floor accelerations, interstory deflections and maximum indentation against "
            "the seismic gap (15-45 cm) for 4, 8, 16 and 32 bumpers per side, all four records",
    compute=compute, plot=plot, check=check,
    chosen="gap step 1 cm (10 cm with --quick); check: 'almost all' read as 75% of the "
           "(record, gap) points with impacts, 'below 4 cm' to within 1% (0.4 mm, the "
           "reading precision of Fig. 20)")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
