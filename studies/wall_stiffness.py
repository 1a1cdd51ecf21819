"""Fig. 21: peak responses against the seismic gap width for three moat-wall stiffnesses.

Gap 15-45 cm, four 5 cm bumpers on each side (clear gap gap - 5 cm), the four paper records;
k_w, the post-yield stiffness of the bumper law (the wall behind the crushed rubber, Eq. 14),
2500, 1500 and 500 kN/mm. The bare wall without bumpers (2500 kN/mm) at the full gap is dashed.
"""
from __future__ import annotations

from engine.units import CM, KN_PER_MM

from .common.paper import FIG21_WALL_KS
from .common.peaks_vs_gap import gaps, lowered, plot_vs_gap, vs_gap_caption
from .common.recipe import Recipe, Verdict, sweep_options

SIGNIFICANT = 0.1  # mean relative reduction of the peak acceleration


def compute(args):
    import pipeline

    return pipeline.sweep(gap=gaps(args.quick), wall_k=list(FIG21_WALL_KS), baseline=True,
                          unconstrained=True, **sweep_options(args))


TITLE = ("Fig. 21: peak responses vs seismic gap, moat-wall stiffness $k_w$ "
         "(4 x 5 cm bumpers)")
"""The figure's one-line title (its caption: caption)."""


def plot(ds):
    return plot_vs_gap(ds, "wall_k", lambda k: f"$k_w$ = {k / KN_PER_MM:g} kN/mm",
                       TITLE)


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return vs_gap_caption(TITLE)


def check(ds) -> list[Verdict]:
    """Paper 5.5: a lower k_w significantly lowers the peak responses, the floor accelerations
    especially."""
    soft, stiff = ds.wall_k.values.min(), ds.wall_k.values.max()
    # k_w only acts where the bumpers are crushed past delta_u
    crushed = ds.max_indentation.max("wall_k") > float(ds.strain * ds.thickness)
    n = int(crushed.sum())
    counts, changes = lowered(ds, "wall_k", soft, stiff, crushed)
    untouched = [str(r) for r in ds.record.values if not crushed.sel(record=r).any()]
    return [Verdict(
        "5.5", "Lower k_w: significantly lower peak responses, especially floor accelerations",
        f"at the {n} (record, gap) points where the bumpers are crushed past delta_u = "
        f"{float(ds.strain * ds.thickness) / CM:g} cm (elsewhere k_w plays no part"
        f"{'; never under ' + ', '.join(untouched) if untouched else ''}), k_w = "
        f"{soft / KN_PER_MM:g} rather than {stiff / KN_PER_MM:g} kN/mm gives a lower peak "
        f"acceleration at {counts[0]}/{n} (mean {changes[0]:+.0%}) and a lower peak "
        f"interstory deflection at {counts[1]}/{n} (mean {changes[1]:+.0%}); significant: "
        f"acceleration down by more than {SIGNIFICANT:.0%} on average, and more than the "
        "deflection",
        (all(c > n / 2 for c in counts) and changes[0] < -SIGNIFICANT
         and changes[0] < changes[1]) if n else None,
        {"points": n, "lower_accel": counts[0], "lower_drift": counts[1],
         "mean_change_accel": changes[0], "mean_change_drift": changes[1],
         "records_never_crushed": untouched})]


recipe = Recipe(
    name="wall_stiffness", figure="Fig. 21",
    summary="Peak floor accelerations and interstory deflections against the seismic gap "
            "(15-45 cm) for moat-wall stiffnesses k_w 2500, 1500 and 500 kN/mm, all four records",
    compute=compute, plot=plot, check=check,
    chosen="gap step 1 cm (10 cm with --quick); check: 'significantly lower' read as a mean "
           "reduction of the peak acceleration over 10%, larger than the deflection's")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
