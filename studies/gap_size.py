"""Figs. 14-15: amplification of the peak responses by rubber bumpers, against the gap width.

Gap 15-45 cm, the four paper records. With bumpers: four 5 cm bumpers on each side (the
practical example's, studies.common.paper), so the clear gap is 5 cm smaller; without: the bare
linear viscoelastic wall at the full gap. Amplification = peak with bumpers / peak without (>
1: bumpers hurt).
"""
from __future__ import annotations

import numpy as np

from engine.units import CM

from .common.paper import N_BUMPERS, THICKNESS
from .common.peaks_vs_gap import gaps, ranges
from .common.plot import (
    building_text,
    floor_labels,
    letter_panels,
    plt,
    record_label,
    records_text,
    short_title,
    shown,
    store_caption,
    story_labels,
)
from .common.recipe import Recipe, Verdict, sweep_options


def compute(args):
    import pipeline

    return pipeline.sweep(gap=gaps(args.quick), thickness=THICKNESS, n_bumpers=N_BUMPERS,
                          baseline=True, unconstrained=True, **sweep_options(args))


def plot(ds):
    # sharey by row: a row's panels show one quantity, read against each other
    fig, axes = plt.subplots(2, 5, figsize=(10, 4.2), sharex=True, sharey="row")
    gap_cm = ds.gap.values / CM
    # Five floors and four stories fit (the paper's building whole); of a taller building the
    # base, the roof and levels spread between.
    panels = [("amplification_total_accel", "floor", floor_labels(ds.sizes["floor"]), axes[0],
               shown(ds.sizes["floor"], 5)),
              ("amplification_interstory_drift", "story", story_labels(ds.sizes["story"]),
               axes[1], shown(ds.sizes["story"], 4))]
    for name, dim, labels, row, which in panels:
        for ax, position in zip(row, which, strict=False):
            index, label = ds[dim].values[position], labels[position]
            for record in ds.record.values:
                ax.plot(gap_cm, ds[name].sel(record=record, **{dim: index}),
                        marker="o", label=record_label(ds, str(record)))
            ax.axhline(1.0, color="k", lw=0.8, ls="--")
            ax.set_title(label)
        row[0].set_ylabel("Amplification of peak\nfloor acceleration" if dim == "floor"
                          else "Amplification of peak\ninterstory deflection")
    for ax in axes[1]:
        ax.set_xlabel("Seismic gap (cm)")
    axes[1, 4].axis("off")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    axes[1, 4].legend(handles, labels, loc="center", frameon=False)
    letter_panels(axes)
    short_title(fig, "Amplification by rubber bumpers against the seismic gap "
                     "(paper Figs. 14-15)")
    store_caption(ds, caption(ds))
    fig.tight_layout()
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption): what it shows, for a reader
    without the paper."""
    return ("; ".join(title_lines(ds)[:-1]) + ". (a)-(e): floors, (f)-(i): stories; each "
            "row's panels share one scale; paper Figs. 14-15.")


def title_lines(ds) -> list[str]:
    """What the figure shows, for a reader without the paper: the ratio plotted, against what,
    for which bumpers, building and records; last, the paper's figures."""
    n, t = int(ds.n_bumpers), float(ds.thickness) / CM
    return ["Amplification by rubber bumpers of the peak floor accelerations (top) and "
            "interstory deflections (bottom), against the seismic gap",
            f"amplification = peak with {n} bumpers of {t:g} cm per side (clear gap = gap "
            f"\u2212 {t:g} cm) / peak against the bare moat wall; above 1, bumpers make "
            "it worse",
            f"{building_text(ds)}, {records_text(ds.sizes['record'])} (legend)",
            "paper Figs. 14-15"]


HELPED_RECORDS = ("sylmar_converter", "pacoima")  # where the paper sees bumpers help (5.1)


def check(ds) -> list[Verdict]:
    """Paper 5.1: bumpers amplify the response at wide gaps, where the bare wall is not hit;
    they help at narrow gaps under the strongest motions (Sylmar Converter, San Fernando), at
    the base more than above."""
    accel = ds.amplification_total_accel
    worst = accel.max("floor")
    base_amp = accel.sel(floor=0)
    gap_cm = ds.gap.values / CM
    only_bumpers = (ds.baseline_n_impacts == 0) & (ds.n_impacts > 0)
    per_record, helped_at = {}, {}
    for record in (str(r) for r in ds.record.values):
        wide = only_bumpers.sel(record=record).values
        helped = base_amp.sel(record=record).values < 1
        helped_at[record] = gap_cm[helped].tolist()
        per_record[record] = {
            "unconstrained_peak_isolator_disp": float(
                ds.unconstrained_peak_isolator_disp.sel(record=record)),
            "gaps_only_bumpers_hit_cm": gap_cm[wide].tolist(),
            "amplified_there": int((worst.sel(record=record).values[wide] > 1).sum()),
            "gaps_base_accel_reduced_cm": helped_at[record]}
    wide_all = only_bumpers.values
    amplified = worst.values[wide_all]
    wide = Verdict(
        "5.1", "Wide gaps (only the bumpers are hit): bumpers amplify the peak floor "
        "acceleration",
        f"amplification > 1 at {int((amplified > 1).sum())}/{amplified.size} such (record, gap) "
        f"points, smallest {amplified.min() if amplified.size else float('nan'):.2f}",
        bool(np.all(amplified > 1)) if amplified.size else None,
        {"points": int(amplified.size), "amplified": int((amplified > 1).sum()),
         "smallest_amplification": float(amplified.min()) if amplified.size else None,
         "per_record": per_record})
    strong = [r for r in HELPED_RECORDS if r in helped_at]
    narrow = Verdict(
        "5.1", "Narrow gaps: bumpers can reduce the peak base acceleration under the strongest "
        "motions, Sylmar Converter and San Fernando",
        "; ".join(f"{r}: reduced at gaps {ranges(gap_cm, np.isin(gap_cm, helped_at[r]))} cm"
                  for r in strong) or "neither record run",
        all(helped_at[r] for r in strong) if strong else None,
        {"gaps_base_accel_reduced_cm": {r: helped_at[r] for r in strong}})
    return [wide, narrow]


recipe = Recipe(
    name="gap_size", figure="Figs. 14-15",
    summary="Amplification of peak floor accelerations and interstory deflections by four "
            "5 cm rubber bumpers, against the seismic gap (15-45 cm), all four records",
    compute=compute, plot=plot, check=check,
    chosen="gap step 1 cm (10 cm with --quick)")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
