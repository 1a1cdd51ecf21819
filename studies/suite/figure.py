"""studies.suite's figure: the fans of the amplification, the maps of helped minus hurt with
"no contact" hatched, and the outcome bars per level and gap (see suite.py's docstring)."""
from __future__ import annotations

import numpy as np

from engine.units import CM, KN_PER_MM
from pipeline.assess.outcomes import QUANTILES

from ..common.paper import THICKNESS
from ..common.plot import letter_panels, plt, short_title, store_caption
from .archive import OUTCOMES, RESPONSES
from .verdicts import all_outside_numbers, paper_config


def plot(ds):
    fig, axes = plt.subplots(2, 3, figsize=(13, 8), layout="constrained")
    top = "MCE_R" if "MCE_R" in ds.level.values else str(ds.level.values[-1])
    n_p, k_p = paper_config(ds)
    for ax, name in zip(axes[0], RESPONSES, strict=True):
        _fan(ax, ds, name, top, n_p)
    limits = np.array([ax.get_ylim() for ax in axes[0]])  # one scale: the fans are compared
    for ax in axes[0]:
        ax.set_ylim(limits[:, 0].min(), limits[:, 1].max())
    axes[0, 0].set_ylabel("amplification (bumpers / bare wall)")
    axes[0, 0].legend(fontsize=6)
    net = _net(ds, "floor_accel").sel(level=top)
    rows = [(axes[1, 0], net.sel(wall_k=k_p).transpose("n_bumpers", "gap_fraction"),
             [str(n) for n in ds.n_bumpers.values], "bumpers per side",
             f"$k_w$ {k_p / KN_PER_MM:g} kN/mm"),
            (axes[1, 1], net.sel(n_bumpers=n_p).transpose("wall_k", "gap_fraction"),
             [f"{k / KN_PER_MM:g}" for k in ds.wall_k.values], "$k_w$ (kN/mm)",
             f"{n_p} bumpers")]
    touched = _touched(ds).sel(level=top)
    for ax, field, labels, ylabel, fixed in rows:
        share = touched.sel(wall_k=k_p) if ylabel.startswith("bumpers") \
            else touched.sel(n_bumpers=n_p)
        mesh = draw_map(ax, field.values, share.transpose(*field.dims).values)
        ax.set_yticks(range(len(labels)), labels)
        ax.set_xticks(range(ds.sizes["gap_fraction"]), _gap_labels(ds), fontsize=6)
        ax.set_ylabel(ylabel)
        ax.set_xlabel("gap / D_M")
        ax.set_title(f"(helped - hurt) / pairs with contact, {top}, {fixed}")
    bar = fig.colorbar(mesh, ax=axes[1, :2], shrink=0.8, ticks=[-1, -0.5, 0, 0.5, 1])
    bar.ax.set_yticklabels(["−1 all hurt", "−0.5", "0 neutral", "0.5", "1 all helped"])
    bar.ax.legend(handles=[no_contact_handle()], loc="upper center",
                  bbox_to_anchor=(0.5, -0.04), frameon=False, handlelength=1.5)
    _outcome_bars(axes[1, 2], ds, n_p, k_p)
    letter_panels(axes)
    short_title(fig, f"{ds.sizes['record']} record pairs in plan: "
                     f"{THICKNESS / CM:g} cm bumpers against the bare wall at the same gap")
    store_caption(ds, caption(ds))
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    n = all_outside_numbers(ds)
    return (f"{ds.sizes['record']} record pairs scaled by "
            f"{ds.attrs.get('scaling_rule', '?')} (T_M {ds.attrs.get('T_M', np.nan):.2f} s, "
            f"D_M {ds.attrs.get('D_M', np.nan) / CM:.1f} cm), in plan: {THICKNESS / CM:g} cm "
            "bumpers against the bare wall at the same gap; "
            f"{n['runs_outside_range']} of {n['runs']} runs outside the model's range. "
            "(a)-(c) amplification (bumpers / bare wall) of the peak responses, weighted median "
            "and 16-84% band, over the pairs with contact, hollow where most have a run "
            "outside the model's range; (d), (e) (helped - hurt) / pairs with contact of the "
            "largest floor acceleration, in each cell the % of the pairs with contact; (f) "
            "the outcomes of the largest floor acceleration. Pairs weighted per earthquake.")


def _gap_labels(ds) -> list[str]:
    return [f"{f:.2f}" + ("\nD_TM" if c else "") for f, c in
            zip(ds.gap_fraction.values, ds.code_clearance.values, strict=True)]


def _fan(ax, ds, name, level, n_p):
    """Median and 16-84% of the amplification against the gap, one line per wall; hollow
    markers where most of the pairs with contact have a run outside the model's range."""
    x = ds.gap_fraction.values
    low, middle, high = QUANTILES
    for k, color in zip(ds.wall_k.values, ("C0", "C1", "C2"), strict=False):
        at = {"level": level, "n_bumpers": n_p, "wall_k": k}
        q = ds.amplification_quantile.sel(response=name, **at)
        median = q.sel(quantile=middle).values
        ax.fill_between(x, q.sel(quantile=low), q.sel(quantile=high), color=color, alpha=0.15,
                        lw=0)
        ax.plot(x, median, color=color, label=f"$k_w$ {k / KN_PER_MM:g} kN/mm")
        mostly_outside = ds.counted_outside_range.sel(**at).values > 0.5
        ax.plot(x[~mostly_outside], median[~mostly_outside], "o", color=color)
        ax.plot(x[mostly_outside], median[mostly_outside], "o", mfc="white", color=color)
    code = x[ds.code_clearance.values == 1]
    for c in code:
        ax.axvline(c, color="0.5", lw=0.8, ls=":")
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.set_xlabel("gap / D_M (dotted: D_TM)")
    ax.set_title(f"{RESPONSES[name]}\n{level}, {n_p} bumpers: weighted median, 16-84%")


def _net(ds, name):
    """(level, gap, n, k): (share helped - share hurt) / share with contact; NaN: no contact."""
    s = ds.outcome_share.sel(response=name)
    counted = 1 - s.sel(outcome="no_contact")
    return ((s.sel(outcome="helped") - s.sel(outcome="hurt")) / counted).where(counted > 0)


def _touched(ds):
    """(level, gap, n, k) weighted share of the pairs with contact."""
    return 1 - ds.outcome_share.sel(response="floor_accel", outcome="no_contact")


NO_CONTACT = {"facecolor": "0.88", "edgecolor": "0.55", "hatch": "////", "lw": 0}


OUTCOME_COLORS = {"helped": "tab:green", "neutral": "gold", "hurt": "tab:red",
                  "no_contact": "0.85"}


def no_contact_handle():
    """The legend handle of the cells where no pair touches the wall."""
    from matplotlib.patches import Patch

    return Patch(**NO_CONTACT, label="no contact")


def draw_map(ax, values, touched=None):
    """Cells of `values` (rows, gap columns) coloured from all hurt (-1, red) through neutral
    (0, yellow) to all helped (+1, green); NaN cells (no contact) grey and hatched; each cell
    with contact labelled with `touched` (share of the pairs with contact) in %. Returns the
    image, for the colour bar."""
    from matplotlib.patches import Rectangle

    masked = np.ma.masked_invalid(values)
    image = ax.imshow(masked, origin="lower", aspect="auto", vmin=-1, vmax=1, cmap="RdYlGn")
    for row, col in zip(*np.nonzero(np.ma.getmaskarray(masked)), strict=True):
        ax.add_patch(Rectangle((col - 0.5, row - 0.5), 1, 1, **NO_CONTACT))
    if touched is not None:
        for row, col in zip(*np.nonzero(~np.ma.getmaskarray(masked)), strict=True):
            ax.text(col, row, f"{touched[row, col]:.0%}", ha="center", va="center", fontsize=5)
    ax.grid(False)
    return image


def _outcome_bars(ax, ds, n_p, k_p):
    """Stacked weighted shares helped / neutral / hurt / no contact of the largest floor
    acceleration, per level and gap, the paper's bumpers."""
    s = ds.outcome_share.sel(response="floor_accel", n_bumpers=n_p, wall_k=k_p)
    n_g = ds.sizes["gap_fraction"]
    ticks, labels = [], []
    for i, level in enumerate(ds.level.values):
        x = i * (n_g + 1) + np.arange(n_g)
        bottom = np.zeros(n_g)
        for outcome in OUTCOMES:
            v = s.sel(level=level, outcome=outcome).values
            ax.bar(x, v, bottom=bottom, color=OUTCOME_COLORS[outcome], width=0.85,
                   label=outcome.replace("_", " ") if i == 0 else None,
                   **({"hatch": "////", "edgecolor": "0.55", "lw": 0}
                      if outcome == "no_contact" else {}))
            bottom += v
        ticks += list(x)
        labels += [f"{f:.2f}" for f in ds.gap_fraction.values]
        ax.text(x.mean(), 1.02, str(level), ha="center", fontsize=7)
    ax.set_xticks(ticks, labels, rotation=90, fontsize=5)
    ax.set_ylim(0, 1.22)
    ax.set_xlabel("gap / D_M, per level")
    ax.set_ylabel("weighted share of the pairs")
    ax.set_title(f"largest floor acceleration, {n_p} bumpers, $k_w$ {k_p / KN_PER_MM:g} "
                 f"kN/mm:\nhelped / neutral (±2%) / hurt / no contact")
    ax.legend(fontsize=6, loc="upper center", ncols=4, frameon=False)
    ax.grid(False)
