"""The fragility recipe's figure: one panel per event (contact, crushed bumpers, each floor
acceleration threshold, the first drift thresholds), a curve per barrier and gap, and its
caption."""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM, G

from ..common.plot import plt

COLOURS = ("0.35", "C0", "C3")  # the colour of each barrier, BARRIERS order
GAP_STYLES = (("-", "o"), ("--", "s"), (":", "^"))  # line and marker of each gap, in order
TITLES = {"contact": "contact", "bumpers_crushed": "bumpers crushed"}


def title(event: str, thresholds: dict) -> str:
    """A panel's title: TITLES', or the threshold's value and component."""
    if event in TITLES:
        return TITLES[event]
    t = thresholds[event]
    short = event.removeprefix("floor_accel_").removeprefix("drift_").replace("_", " ")
    name = f" ({short})" if t["component"] else ""
    if event.startswith("floor_accel_"):
        return f"PFA > {t['value'] / G:g} g{name}"
    return f"drift > {100 * t['value']:g}%{name}"


def plot(ds):
    """One panel per event; a curve per barrier (colour) and gap (line and marker), named by
    a two-part legend below the panels."""
    from scipy.stats import norm

    from ..common.plot import letter_panels, short_title, store_caption

    thresholds = json.loads(ds.attrs["thresholds"])
    drift = [e for e in thresholds if e.startswith("drift_")][:2]
    shown = [e for e in (*TITLES, *[e for e in thresholds if e.startswith("floor_accel_")],
                         *drift) if e in ds.event.values]
    columns = (len(shown) + 1) // 2
    fig, axes = plt.subplots(2, columns, figsize=(2.4 * columns, 5.6), sharey=True,
                             squeeze=False)
    for ax in axes.ravel()[len(shown):]:
        ax.set_visible(False)
    axes = axes.ravel()[:len(shown)]
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
        ax.set_title(title(event, thresholds), fontsize=9)
        ax.set_xlabel("intensity, x MCE$_R$")
        ax.set_xlim(0, x[-1])
    for ax in axes[::columns]:
        ax.set_ylabel("probability of the event")
    barriers = [plt.Line2D([], [], color=c, lw=2, label=str(b))
                for b, c in zip(ds.barrier.values, COLOURS, strict=False)]
    gaps = [plt.Line2D([], [], color="k", ls=line, marker=mark, mfc="none",
                       label=f"gap {fraction:.2f} $D_M$")
            for fraction, (line, mark) in zip(ds.gap_fraction.values, GAP_STYLES,
                                              strict=False)]
    letter_panels(axes)
    short_title(fig, "Fragility of the moat with and without bumpers")
    store_caption(ds, caption(ds))
    fig.tight_layout(rect=(0, 0.08, 1, 1))
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
            "open markers: observed shares, pairs weighted per earthquake. Thresholds: the "
            "median capacities of the named components' first damage states (FEMA P-58).")
