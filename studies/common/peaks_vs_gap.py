"""Figs. 16, 18, 19, 21: peak responses against the seismic gap width, one line per value of
the varied bumper parameter, the building without bumpers (bare wall) dashed.

Shared by the thickness, strain, n_bumpers and wall_stiffness recipes (and gap_size, Figs.
14-15, for the gap grid): their gap grid over the paper's range (studies.common.paper), their figure
(rows: peak floor acceleration in g, the largest over the floors, and peak interstory
deflection in cm, the largest over the stories; columns: records) and the envelopes their
checks compare.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from engine.units import CM, KN_PER_MM, G

from .paper import GAP_RANGE_CM
from .plot import letter_panels, plt, record_label, short_title, store_caption

MARKERS = ("o", "s", "^", "D", "v", "P")


def gaps(quick: bool) -> np.ndarray:
    """m: the paper's 15 to 45 cm (GAP_RANGE_CM) every cm (every 10 cm with --quick), as in
    Figs. 14-21."""
    low, high = GAP_RANGE_CM
    return np.round(np.arange(low, high + 1, 10 if quick else 1) * CM, 4)


def accel_g(ds, prefix: str = ""):
    """Peak total floor acceleration in g, the largest over the floors."""
    from pipeline.assess.derived import largest_floor_accel

    return largest_floor_accel(ds[prefix + "peak_total_accel"]) / G


def drift_cm(ds, prefix: str = ""):
    """Peak interstory deflection in cm, the largest over the stories."""
    return ds[prefix + "peak_interstory_drift"].max("story") / CM


def spread(da, dim: str):
    """(max - min) / mean over `dim`: how much the varied parameter moves a peak."""
    return (da.max(dim) - da.min(dim)) / da.mean(dim)


def plot_vs_gap(ds, dim: str, label: Callable[[float], str], title: str,
         indentation_limit: float | None = None):
    """Rows: peak floor acceleration (g), peak interstory deflection (cm) and, when
    indentation_limit (m) is given, maximum indentation (cm) with that limit drawn; columns:
    records; one line per value of `dim`, the no-bumper baseline dashed; `title` one line,
    the rest in the caption (vs_gap_caption)."""
    rows = [("Peak floor\nacceleration (g)", accel_g, True),
            ("Peak interstory\ndeflection (cm)", drift_cm, True)]
    if indentation_limit is not None:
        rows.append(("Maximum\nindentation (cm)", indentation_cm, False))
    records = [str(r) for r in ds.record.values]
    height = 0.7 + 2.0 * len(rows)  # inches: rows plus title and legend
    # sharey by row: a row's panels (the records) show one quantity, read against each other
    fig, axes = plt.subplots(len(rows), len(records), sharex=True, sharey="row", squeeze=False,
                             figsize=(1.2 + 2.6 * len(records), height))
    gap_cm = ds.gap.values / CM
    for col, record in enumerate(records):
        axes[0, col].set_title(record_label(ds, record))
        for row, (ylabel, quantity, with_baseline) in enumerate(rows):
            ax = axes[row, col]
            values = quantity(ds).sel(record=record)
            for i, value in enumerate(ds[dim].values):
                ax.plot(gap_cm, values.sel({dim: value}), marker=MARKERS[i % len(MARKERS)],
                        markevery=max(1, gap_cm.size // 8), label=label(float(value)))
            if with_baseline:
                ax.plot(gap_cm, quantity(ds, "baseline_").sel(record=record), "k--",
                        label="No bumpers")
            else:
                ax.axhline(indentation_limit / CM, color="r", lw=0.9, ls=":",
                           label=f"Limit $\\delta_u$ = {indentation_limit / CM:g} cm")
            if col == 0:
                ax.set_ylabel(ylabel)
        axes[-1, col].set_xlabel("Seismic gap (cm)")
    for ax in axes[:, 0]:  # after every column is drawn: a row's shared limits cover them all
        ax.set_ylim(bottom=0)
    legend = {}
    for ax in axes[:, 0]:
        for handle, text in zip(*ax.get_legend_handles_labels(), strict=True):
            legend.setdefault(text, handle)
    letter_panels(axes)
    short_title(fig, title)
    store_caption(ds, vs_gap_caption(title))
    fig.tight_layout(rect=(0, 0.3 / height, 1, 1))
    fig.legend(legend.values(), legend.keys(), loc="lower center", ncol=len(legend),
               frameon=False)
    return fig


def vs_gap_caption(title: str) -> str:
    """The caption of a plot_vs_gap figure titled `title`."""
    from pipeline.grid import BASELINE

    return (f"{title}. Rows: peak floor acceleration, the largest over the floors; peak "
            "interstory deflection, the largest over the stories (and, where drawn, the "
            "maximum indentation against the bumpers' limit); columns: records, panels of a "
            "row on one scale. Dashed: no bumpers (bare wall, "
            f"{BASELINE['wall_k'] / KN_PER_MM:g} kN/mm, at the full gap).")


def lowered(ds, dim: str, new, old, where) -> tuple[list[int], list[float]]:
    """How `dim` = new rather than old changes the peak floor acceleration and the peak
    interstory deflection at the points `where`: ([points lowered], [mean relative change])."""
    counts, changes = [], []
    for quantity in (accel_g(ds), drift_cm(ds)):
        lower = quantity.sel({dim: new}) < quantity.sel({dim: old})
        counts.append(int((lower & where).sum()))
        changes.append(float((quantity.sel({dim: new}) / quantity.sel({dim: old}) - 1)
                             .where(where).mean()))
    return counts, changes


def indentation_cm(ds, prefix: str = ""):
    """Maximum indentation at the moat wall in cm."""
    return ds[prefix + "max_indentation"] / CM


def ranges(grid, selected) -> str:
    """'15-18, 22' style text for the runs of consecutive selected grid values."""
    runs, start = [], None
    for value, chosen, following in zip(grid, selected, list(selected[1:]) + [False],
                                        strict=True):
        if chosen and start is None:
            start = value
        if chosen and not following:
            runs.append(f"{start:g}" if start == value else f"{start:g}-{value:g}")
            start = None
    return ", ".join(runs) or "none"


