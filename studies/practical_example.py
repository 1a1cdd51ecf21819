"""Figs. 9-13: the practical example, with and without rubber bumpers (paper section 4).

Kobe 1995 (KJMA 000) and San Fernando 1971 (Pacoima Dam 164). For each record the seismic gap
is 90% of the engine's own unconstrained peak isolator displacement, to the mm (the paper's
rule; it gives 15 and 24 cm from 16.7 and 26.8 cm). Three configurations per record: no
poundings (no wall), no bumpers (the bare linear viscoelastic wall at the gap, k 2500 kN/mm,
COR 0.5, the sweeps' baseline) and four 5 cm bumpers of 150 x 150 mm on each side
(0.36 kN/mm^2.65, k_w 1500 kN/mm, ultimate strain 0.8, clear gap = gap - 5 cm). The paper's
bumper, gap rule and gaps are read from studies.common.paper.

Archive: the peaks of the three configurations and, on a common time axis (histories every
2 ms), the base total acceleration (Figs. 9-10), the impact force and indentation (Fig. 11)
and the isolator displacement. Figure: base acceleration against time per record, force
against indentation with the 4 cm crush limit, peak floor accelerations and interstory
deflections per level (Figs. 12-13).

--workers and --scheduler serve the unconstrained runs that set the gaps; the histories of each
record (all three configurations in one engine batch) run in this process
(pipeline.histories).
"""
from __future__ import annotations

import numpy as np

from engine.units import CM, KN, G

from .common.paper import (
    GAP_FRACTION,
    N_BUMPERS,
    PRACTICAL_GAPS,
    PRACTICAL_UNCONSTRAINED,
    STRAIN,
    THICKNESS,
    WALL_K,
)
from .common.plot import (
    floor_labels,
    letter_panels,
    ordinal,
    plt,
    record_label,
    short_title,
    store_caption,
)
from .common.recipe import Recipe, Verdict

EVERY = 4  # integration steps per history sample: 2 ms at the default 0.5 ms step
HISTORY_SECONDS = 40.0  # s of history kept (longer if an impact happens later)
QUICK_SECONDS = 20.0  # --quick: only the first 20 s of each record (its strong motion)
AT_PAPER_GAP = "_at_paper_gap"  # suffix of the configurations run at the paper's gap
CONFIG_LABELS = {"no_pounding": "No poundings", "no_bumpers": "Without bumpers",
                 "bumpers": "With bumpers"}
CONFIG_STYLE = {"no_pounding": dict(color="0.35", lw=0.9),
                "no_bumpers": dict(color="tab:red", lw=0.8),
                "bumpers": dict(color="tab:blue", lw=0.8)}
MARKERS = {"no_pounding": "o", "no_bumpers": "s", "bumpers": "^"}  # peak profiles


def configurations(gap: float) -> dict[str, dict]:
    """The three configurations of section 4 at one seismic gap (m), in pipeline.sweep's
    vocabulary (pipeline.histories)."""
    from pipeline.grid import BASELINE, BASELINE_LAW

    return {
        "no_pounding": {"impact": "none"},
        "no_bumpers": {"impact": BASELINE_LAW, "gap": gap, **BASELINE},
        "bumpers": {"impact": "bumper", "gap": gap, "thickness": THICKNESS,
                    "n_bumpers": N_BUMPERS, "wall_k": WALL_K, "strain": STRAIN},
    }


def compute(args):
    import xarray as xr

    import pipeline
    from pipeline.histories import concat_records, histories, segment
    from pipeline.records import resolve_records

    records, names = resolve_records(args.records, args.records_dir)
    if args.quick:
        records = [segment(rec, QUICK_SECONDS) for rec in records]
    free = pipeline.unconstrained_peaks(records, dt=args.dt, workers=args.workers,
                                        scheduler=args.scheduler, quiet=args.quiet,
                                        building=args.building, work_dir=args.work_dir,
                                        backend=args.backend)
    parts, gaps = [], []
    # Each paper record also runs at the paper's own gap, to tell the gap rule from the model.
    at_paper_gap = all(name in PRACTICAL_GAPS for name in names)
    for rec, name in zip(records, names, strict=True):
        peak = float(free.peak_isolator_disp.sel(record=name))
        gap = round(GAP_FRACTION * peak, 3)  # m, to the mm
        gaps.append(gap)
        configs = configurations(gap)
        if at_paper_gap:
            configs.update({f"{key}{AT_PAPER_GAP}": config for key, config in
                            configurations(PRACTICAL_GAPS[name]).items()
                            if key != "no_pounding"})
        parts.append(histories(rec, configs, dt=args.dt, every=EVERY, quiet=args.quiet,
                               building=args.building))
    ds = concat_records(parts, t_end=history_end(parts))
    # Only the base level of the acceleration histories is kept (Figs. 9-10): 5x smaller.
    base = ds.total_accel.sel(floor=0, drop=True)
    base.attrs = dict(ds.total_accel.attrs,
                      long_name="total (absolute) acceleration at the isolation level (base)")
    ds = ds.drop_vars("total_accel").assign(base_total_accel=base)
    unconstrained = free.peak_isolator_disp.sel(record=names)
    paper_gap = [PRACTICAL_GAPS.get(n, np.nan) for n in names]
    paper_free = [PRACTICAL_UNCONSTRAINED.get(n, np.nan) for n in names]
    ds["unconstrained_peak_isolator_disp"] = xr.Variable(
        "record", unconstrained.values,
        {"units": "m", "long_name": "peak isolator displacement without moat wall (engine)"})
    ds["chosen_gap"] = xr.Variable(
        "record", np.array(gaps),
        {"units": "m", "long_name": f"seismic gap: {GAP_FRACTION} x the unconstrained peak "
                                    "isolator displacement, to the mm"})
    ds["paper_gap"] = xr.Variable(
        "record", np.array(paper_gap),
        {"units": "m", "long_name": "the paper's seismic gap (section 4; NaN: not in the paper)"})
    ds["paper_unconstrained_peak_isolator_disp"] = xr.Variable(
        "record", np.array(paper_free),
        {"units": "m", "long_name": "the paper's unconstrained peak isolator displacement "
                                    "(section 4; NaN: not in the paper)"})
    ds.attrs["gap_rule"] = "; ".join(
        f"{name}: gap = {GAP_FRACTION} x {peak / CM:.2f} cm = {gap / CM:.1f} cm, clear gap with "
        f"bumpers {(gap - THICKNESS) / CM:.1f} cm"
        + (f" (paper: {PRACTICAL_GAPS[name] / CM:.0f} cm from "
           f"{PRACTICAL_UNCONSTRAINED[name] / CM:.1f} cm, clear gap "
           f"{(PRACTICAL_GAPS[name] - THICKNESS) / CM:.0f} cm)"
           if name in PRACTICAL_GAPS else "")
        for name, peak, gap in zip(names, unconstrained.values, gaps, strict=True))
    if args.quick:
        ds.attrs["quick_segment"] = f"first {QUICK_SECONDS:g} s of each record only"
    for line in ds.attrs["gap_rule"].split("; "):
        print(line)
    return ds


def history_end(parts) -> float:
    """s: HISTORY_SECONDS, or 5 s past the last impact of any record if that is later."""
    end = HISTORY_SECONDS
    for ds in parts:
        hit = ds.time.values[(ds.impact_force > 0).any("configuration").values]
        if hit.size:
            end = max(end, float(np.ceil(hit[-1] + 5.0)))
    return end


# --------------------------------------------------------------------------- figure


def plot(ds):
    records = [str(r) for r in ds.record.values]
    n = len(records)
    fig = plt.figure(figsize=(10, 2.8 * n + 5.4), layout="constrained")
    grid = fig.add_gridspec(n + 2, 4 * n, height_ratios=[1.7] * n + [1.3, 1.3])
    for i, record in enumerate(records):
        _plot_base_accel(fig.add_subplot(grid[i, :]), ds, record, fig_number=9 + i)
        _plot_force_indentation(fig.add_subplot(grid[n, 4 * i:4 * i + 4]), ds, record)
        _plot_peaks(fig.add_subplot(grid[n + 1, 4 * i:4 * i + 2]),
                    fig.add_subplot(grid[n + 1, 4 * i + 2:4 * i + 4]), ds, record,
                    fig_number=12 + i)
    handles = [plt.Line2D([], [], **dict(CONFIG_STYLE[c], lw=1.1), marker=MARKERS.get(c, "o"),
                          label=CONFIG_LABELS.get(c, c))
               for c in (str(c) for c in ds.configuration.values) if c in CONFIG_LABELS]
    fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), frameon=False)
    # lettered as read: row by row, left to right (not in the order they were drawn)
    letter_panels(sorted(fig.axes, key=lambda ax: (-round(ax.get_position().y1, 2),
                                                   ax.get_position().x0)))
    short_title(fig, "Practical example (paper section 4)")
    store_caption(ds, caption(ds))
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    quick = " [--quick: first part of each record only]" if ds.attrs.get("quick", 0) else ""
    return ("Practical example (paper section 4): no poundings, bare moat wall without "
            "bumpers, and four 5 cm rubber bumpers on each side" + quick + ". Per record: the "
            "base acceleration history (paper Figs. 9-10), the force-indentation loops (Fig. "
            "11) and the peak floor accelerations and interstory deflections (Figs. 12-13).")


def _gap_text(ds, record: str) -> str:
    gap = float(ds.chosen_gap.sel(record=record)) / CM
    paper = float(ds.paper_gap.sel(record=record)) / CM
    text = f"gap {gap:.1f} cm"
    if np.isfinite(paper):
        text += f" (paper {paper:.0f} cm)"
    return text + f", clear gap with bumpers {gap - THICKNESS / CM:.1f} cm"


def _plot_base_accel(ax, ds, record, fig_number):
    sel = ds.sel(record=record)
    end = float(sel.history_end)
    time = sel.time.values
    keep = time <= end
    base = sel.peak_total_accel.sel(floor=0) / G
    # Without bumpers behind (its spikes are the largest), no poundings in front.
    for config in ("no_bumpers", "bumpers", "no_pounding"):
        if config in ds.configuration.values:
            accel = sel.base_total_accel.sel(configuration=config).values[keep] / G
            peak = float(base.sel(configuration=config))
            ax.plot(time[keep], accel, **CONFIG_STYLE[config],
                    label=f"{CONFIG_LABELS[config]} (peak {peak:.2f} g)")
    handles, labels = ax.get_legend_handles_labels()
    order = [labels.index(x) for x in sorted(labels, key=_config_order)]
    ax.legend([handles[i] for i in order], [labels[i] for i in order], loc="upper right",
              ncol=3)
    low, high = ax.get_ylim()
    ax.set_ylim(low, high + 0.25 * (high - low))  # room for the legend
    ax.set_xlim(0, end)
    _zoom_on_impacts(ax, sel, time[keep])
    ax.set_xlabel("Time (s)")
    ax.set_ylabel("Base total\nacceleration (g)")
    ax.set_title(f"Fig. {fig_number}: {record_label(ds, record)}, {_gap_text(ds, record)}",
                 loc="left")


def _zoom_on_impacts(ax, sel, time):
    """An inset magnifying the poundings, which last a second or two of the record."""
    hit = time[(sel.impact_force.values[:, :time.size] > 0).any(axis=0)]
    if hit.size == 0:
        return
    start, stop = max(hit[0] - 0.5, 0.0), min(hit[-1] + 1.5, time[-1])
    if stop - start > 0.3 * time[-1]:
        return  # poundings spread over the record: the panel shows them already
    left = 0.57 if start + stop < time[-1] else 0.04  # on the side away from the poundings
    inset = ax.inset_axes([left, 0.22, 0.39, 0.52])
    window = (time >= start) & (time <= stop)
    low, high = np.inf, -np.inf
    for line in ax.get_lines():
        y = np.asarray(line.get_ydata())[window]
        inset.plot(time[window], y, color=line.get_color(), lw=line.get_linewidth())
        low, high = min(low, np.nanmin(y)), max(high, np.nanmax(y))
    margin = 0.05 * (high - low)
    inset.set_xlim(start, stop)
    inset.set_ylim(low - margin, high + margin)
    inset.tick_params(labelsize=6)
    inset.set_facecolor("white")
    ax.indicate_inset_zoom(inset, edgecolor="0.4")


def _config_order(label: str) -> int:
    return next((i for i, text in enumerate(CONFIG_LABELS.values()) if label.startswith(text)),
                len(CONFIG_LABELS))


def _plot_force_indentation(ax, ds, record):
    sel = ds.sel(record=record)
    crush = np.nan
    for config in ("no_bumpers", "bumpers"):
        if config not in ds.configuration.values:
            continue
        c = sel.sel(configuration=config)
        indentation, force = c.indentation.values, c.impact_force.values
        contact = (indentation > 0) | (force > 0)
        # Each contact drawn from and back to zero: keep the samples next to a contact.
        near = contact | np.roll(contact, 1) | np.roll(contact, -1)
        near &= np.isfinite(indentation)
        ax.plot(np.where(near, indentation / CM, np.nan), np.where(near, force / KN, np.nan),
                **CONFIG_STYLE[config], label=CONFIG_LABELS[config])
        if config == "bumpers":
            crush = float(c.crush_indentation)
    if np.isfinite(crush):
        ax.axvline(crush / CM, color="k", ls="--", lw=0.8)
        ax.annotate(f"bumpers crushed:\n{crush / CM:g} cm = {STRAIN:g} x thickness",
                    (crush / CM, 0.75), xycoords=("data", "axes fraction"), xytext=(-4, 0),
                    textcoords="offset points", va="top", ha="right", fontsize=7)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper left", bbox_to_anchor=(0.12, 1.0))  # right of the bare-wall loops
    ax.set_xlabel("Indentation (cm)")
    ax.set_ylabel("Impact force (kN)")
    ax.set_title(f"Fig. 11: {record_label(ds, record)}", loc="left")


def _plot_peaks(ax_accel, ax_drift, ds, record, fig_number):
    sel = ds.sel(record=record)
    for config in (str(c) for c in ds.configuration.values if c in CONFIG_LABELS):
        c = sel.sel(configuration=config)
        style = dict(CONFIG_STYLE[config], lw=1.1, marker=MARKERS.get(str(config), "o"))
        ax_accel.plot(c.peak_total_accel.values / G, ds.floor.values, **style)
        ax_drift.plot(c.peak_interstory_drift.values / CM, ds.story.values, **style)
    floors = [label.split()[0] for label in floor_labels(ds.sizes["floor"])]  # "Base", "1st"
    ax_accel.set_yticks(ds.floor.values, floors)
    ax_drift.set_yticks(ds.story.values, [ordinal(i) for i in ds.story.values])
    ax_accel.set_xlabel("Peak floor acceleration (g)")
    ax_drift.set_xlabel("Peak interstory\ndeflection (cm)")
    ax_accel.set_ylabel("Level")
    ax_drift.set_ylabel("Story")
    for ax in (ax_accel, ax_drift):
        ax.set_xlim(left=0)
    name = record_label(ds, record).split("\n")[0]  # a stand-in's note: in Figs. 9-11's titles
    ax_accel.set_title(f"Fig. {fig_number}: {name}", loc="left")


# --------------------------------------------------------------------------- paper check

LITTLE = 0.8  # "not reduced much": with / without bumpers above this
CONSIDERABLE = 0.75  # "considerably reduced": with / without bumpers below this
# "Substantial" against "very small exceedance" of the crush indentation delta_u (section 4):
# past it by more, or less, than this multiple (1.1: 4 mm past the 4 cm of 5 cm bumpers).
SLIGHT_CRUSH = 1.1


def check(ds) -> list[Verdict]:
    """Section 4: Kobe, bumpers hardly lower the peak base acceleration (crushed well past
    4 cm) and amplify the interstory deflections; San Fernando, bumpers considerably lower the
    base acceleration (slightly crushed), which stays above the no-pounding response."""
    out = []
    quick = " [--quick: first part of each record only]" if ds.attrs.get("quick", 0) else ""
    cases = [case for case in ("", AT_PAPER_GAP)
             if f"bumpers{case}" in ds.configuration.values]
    for record, case in ((str(r), case) for r in ds.record.values for case in cases):
        sel = ds.sel(record=record)
        base = sel.peak_total_accel.sel(floor=0)
        free, bare, bump = (float(base.sel(configuration=c)) for c in
                            ("no_pounding", f"no_bumpers{case}", f"bumpers{case}"))
        ratio = bump / bare
        crush = float(sel.crush_indentation.sel(configuration=f"bumpers{case}"))
        indent = float(sel.max_indentation.sel(configuration=f"bumpers{case}"))
        drift = sel.peak_interstory_drift
        drift_ratio = (drift.sel(configuration=f"bumpers{case}")
                       / drift.sel(configuration=f"no_bumpers{case}")).values
        gap = float(sel.gap.sel(configuration=f"bumpers{case}"))
        rule = "the paper's gap" if case else f"{GAP_FRACTION} x unconstrained peak"
        numbers = {"gap": gap, "gap_source": rule, "paper_gap": float(sel.paper_gap),
                   "base_accel_no_pounding": free, "base_accel_no_bumpers": bare,
                   "base_accel_bumpers": bump, "base_accel_ratio": ratio,
                   "max_indentation": indent, "crush_indentation": crush,
                   "drift_ratio": drift_ratio.tolist()}
        head = (f"{record}, gap {gap / CM:.1f} cm ({rule}){quick}: peak base acceleration "
                f"{free / G:.2f} g (no poundings), {bare / G:.2f} g (no bumpers), "
                f"{bump / G:.2f} g (bumpers, x{ratio:.2f}); indentation {indent / CM:.1f} cm "
                f"against {crush / CM:g} cm; interstory deflections x{drift_ratio.min():.2f}-"
                f"x{drift_ratio.max():.2f}")
        if record == "kobe":
            claims = [
                ("Kobe: bumpers do not reduce the peak base acceleration much "
                 f"(with / without > {LITTLE})", ratio > LITTLE),
                (f"Kobe: bumpers crushed substantially past delta_u (> {SLIGHT_CRUSH} x delta_u)",
                 indent > SLIGHT_CRUSH * crush),
                ("Kobe: bumpers amplify the interstory deflections (some story above x1)",
                 bool((drift_ratio > 1).any())),
            ]
        elif record == "pacoima":
            claims = [
                ("San Fernando: bumpers considerably reduce the peak base acceleration "
                 f"(with / without < {CONSIDERABLE})", ratio < CONSIDERABLE),
                ("San Fernando: it stays above the no-pounding response", bump > free),
                ("San Fernando: bumpers crushed only very slightly past delta_u "
                 f"(< {SLIGHT_CRUSH} x delta_u)",
                 indent < SLIGHT_CRUSH * crush),
                ("San Fernando: first-story deflection slightly lower with bumpers",
                 bool(drift_ratio[0] < 1)),
            ]
        else:
            claims = [(f"{record}: not a record of the paper's section 4", None)]
        out += [Verdict("4", claim, head, ok, numbers) for claim, ok in claims]
    return out


recipe = Recipe(
    name="practical_example", figure="Figs. 9-13",
    summary="The practical example: base acceleration histories, force-indentation loops "
            "and peak responses with no poundings, without bumpers and with four 5 cm rubber "
            "bumpers, Kobe and San Fernando, gap 10% under the unconstrained peak (and the "
            "paper's gaps)",
    compute=compute, plot=plot, check=check, records=("kobe", "pacoima"),
    chosen=f"gap rounded to the mm; histories every {EVERY} integration steps (2 ms at the "
           f"default step), kept up to {HISTORY_SECONDS:g} s (or 5 s past the last impact), "
           f"base level only for the accelerations; --quick: first {QUICK_SECONDS:g} s of "
           f"each record; check: 'not much' = with / without bumpers > {LITTLE}, "
           f"'considerably' < {CONSIDERABLE}, 'substantially' / 'very slightly' crushed: "
           f"more / less than {SLIGHT_CRUSH} x delta_u; both records also run at the paper's "
           f"gaps ({' and '.join(f'{gap / CM:g}' for gap in PRACTICAL_GAPS.values())} cm)")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
