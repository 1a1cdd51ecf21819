"""Fig. 18: peak responses against the seismic gap width for three ultimate compressive strains
of the bumper rubber.

Gap 15-45 cm, four 5 cm bumpers on each side (clear gap gap - 5 cm), k_w = 1500 kN/mm, the four
paper records. Past delta_u = eps_u x 5 cm the slab bears on the wall through the crushed rubber
(Eq. 14). The paper does not state its strains: 0.6, 0.8 (its default) and 1.0 here. The bare
wall without bumpers at the full gap is dashed.
"""
from __future__ import annotations

from engine.units import CM

from .common.paper import THICKNESS
from .common.peaks_vs_gap import gaps, lowered, plot_vs_gap, vs_gap_caption
from .common.recipe import Recipe, Verdict, sweep_options

STRAINS = (0.6, 0.8, 1.0)  # chosen, the paper does not state them (0.8: its default, _paper)


def compute(args):
    import pipeline

    return pipeline.sweep(gap=gaps(args.quick), thickness=THICKNESS, strain=list(STRAINS),
                          baseline=True, unconstrained=True, **sweep_options(args))


TITLE = ("Fig. 18: peak responses vs seismic gap, ultimate compressive strain "
         "$\\varepsilon_u$ of the bumpers (4 x 5 cm)")
"""The figure's one-line title (its caption: caption)."""


def plot(ds):
    return plot_vs_gap(ds, "strain", lambda e: f"$\\varepsilon_u$ = {e:g}",
                       TITLE)


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return vs_gap_caption(TITLE)


def check(ds) -> list[Verdict]:
    """Paper 5.3: both floor accelerations and interstory deflections decrease as the ultimate
    compressive strain increases."""
    low, high = ds.strain.values.min(), ds.strain.values.max()
    # eps_u can only matter where some bumper is compressed past the smallest delta_u
    crushed = ds.max_indentation.max("strain") > low * float(ds.thickness)
    n = int(crushed.sum())
    counts, changes = lowered(ds, "strain", high, low, crushed)
    return [Verdict(
        "5.3", "Both peak floor accelerations and interstory deflections decrease as eps_u "
        "increases",
        f"at the {n} (record, gap) points where the bumpers are compressed past the smallest "
        f"delta_u = {low:g} x {float(ds.thickness) / CM:g} cm (elsewhere eps_u plays no part), "
        f"eps_u = {high:g} rather than {low:g} gives a lower peak acceleration at "
        f"{counts[0]}/{n} (mean {changes[0]:+.0%}) and a lower peak interstory deflection at "
        f"{counts[1]}/{n} (mean {changes[1]:+.0%})",
        all(c > n / 2 for c in counts) if n else None,
        {"points": n, "lower_accel": counts[0], "lower_drift": counts[1],
         "mean_change_accel": changes[0], "mean_change_drift": changes[1]})]


recipe = Recipe(
    name="strain", figure="Fig. 18",
    summary="Peak floor accelerations and interstory deflections against the seismic gap "
            "(15-45 cm) for three ultimate compressive strains of 5 cm bumpers, all four records",
    compute=compute, plot=plot, check=check,
    chosen="ultimate strains 0.6, 0.8 and 1.0; gap step 1 cm (10 cm with --quick)")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
