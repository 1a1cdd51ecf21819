"""Fig. 22: peak responses of the building against the bumpers' coefficient of restitution.

Sylmar Converter, 5 cm bumpers, four of them, k_w = 1500 kN/mm; COR 0.3 to 1.0; two seismic
gaps: 10% under the engine's own unconstrained peak isolator displacement for the record (the
paper's rule), and the paper's stated 28.5 cm (clear gaps 5 cm smaller; the paper's values:
studies.common.paper). Peak floor accelerations (g) per floor and interstory deflections (cm) per
story, against the COR.

The paper finds no effect of the COR; here the responses rise with it. To see why, the
recipe also follows each run's impacts in time (pipeline.histories): which impact produces
the peak base acceleration, the first impact's peak force, and the approach speed of the
first two impacts. The COR acts in restitution only, so the first impact does not depend on
it; but the peak comes from the second impact, after the slab rebounds off the first with a
speed that the COR sets.
"""
from __future__ import annotations

import numpy as np

from engine.units import CM, G

from .common.paper import GAP_FRACTION, RESTITUTION_GAP, THICKNESS
from .common.plot import (
    floor_labels,
    letter_panels,
    plt,
    record_label,
    short_title,
    store_caption,
    story_labels,
)
from .common.recipe import Recipe, Verdict, sweep_options

NO_EFFECT = 0.05  # largest spread over the CORs, relative to the mean, read as 'no effect'
IMPACTS_KEPT = 2  # approach speeds stored for the first two impacts


def cors(quick: bool) -> np.ndarray:
    """0.3 to 1.0 every 0.1 (0.3, 0.6, 1.0 with --quick)."""
    return np.array([0.3, 0.6, 1.0]) if quick else np.round(np.arange(3, 11) / 10, 1)


def compute(args):
    import pipeline
    from pipeline.errors import SweepError

    options = sweep_options(args)
    if len(options["records"]) != 1:
        raise SweepError("restitution: the gap follows one record's unconstrained peak; "
                         f"give one record, not {len(options['records'])}")
    free = pipeline.unconstrained_peaks(options["records"], dt=args.dt,
                                        workers=min(args.workers, 1),
                                        scheduler=args.scheduler,
                                        records_dir=args.records_dir,
                                        building=args.building, work_dir=args.work_dir)
    peak = float(free.peak_isolator_disp.item())
    gap = round(GAP_FRACTION * peak, 3)  # m, to the mm
    gaps = sorted({gap, RESTITUTION_GAP})
    ds = pipeline.sweep(gap=gaps, thickness=THICKNESS, cor=cors(args.quick),
                        unconstrained=True, **options)
    ds = ds.assign(impact_sequence(ds, options["records"][0], args))
    sources = {gap: f"{GAP_FRACTION} x unconstrained peak"}
    sources[RESTITUTION_GAP] = " and ".join(filter(None, [sources.get(RESTITUTION_GAP),
                                                          "the paper's"]))
    ds.coords["gap_source"] = ("gap", np.array([sources[g] for g in ds.gap.values], dtype=str),
                               {"long_name": "where the gap comes from: the paper's rule "
                                "applied to this engine, or the paper's gap"})
    ds.attrs.update(
        gap_rule=f"gap = {GAP_FRACTION} x unconstrained peak isolator displacement "
                 f"({peak / CM:.2f} cm) = {gap / CM:.1f} cm, to the mm; clear gap with "
                 f"{THICKNESS / CM:g} cm bumpers {(gap - THICKNESS) / CM:.1f} cm "
                 f"(paper: {RESTITUTION_GAP / CM:g} and {(RESTITUTION_GAP - THICKNESS) / CM:g} "
                 "cm, also run)",
        chosen_gap=gap, chosen_gap_units="m", clear_gap=round(gap - THICKNESS, 4),
        clear_gap_units="m")
    return ds


def impact_sequence(ds, record, args) -> dict:
    """Per (record, gap, cor): the impact holding the peak base acceleration, the first
    impact's peak force and indentation, and the approach speeds of the first impacts, from
    time histories (every integration step) of the same runs."""
    from pipeline.archive import variable
    from pipeline.histories import histories

    configs = {f"{g}_{c}": {"impact": "bumper", "gap": float(g), "thickness": THICKNESS,
                            "cor": float(c)}
               for g in ds.gap.values for c in ds.cor.values}
    hist = histories(record, configs, dt=args.dt, every=1, records_dir=args.records_dir,
                     quiet=args.quiet, building=args.building)
    shape = (1, ds.sizes["gap"], ds.sizes["cor"])
    out = {"peak_accel_impact": np.zeros(shape, int), "first_impact_max_force": np.zeros(shape),
           "first_impact_max_indentation": np.zeros(shape),
           "impact_speed": np.full((*shape, IMPACTS_KEPT), np.nan)}
    dt = float(hist.time[1] - hist.time[0])
    for i, g in enumerate(ds.gap.values):
        for j, c in enumerate(ds.cor.values):
            h = hist.sel(configuration=f"{g}_{c}")
            force, u0 = h.impact_force.values, h.isolator_disp.values
            contact = force > 0
            starts = np.flatnonzero(contact[1:] & ~contact[:-1]) + 1
            ends = np.append(starts[1:], contact.size)  # each impact up to the next one
            peak = int(np.abs(h.total_accel.sel(floor=0).values).argmax())
            inside = (starts <= peak) & (peak < ends) & contact[peak]
            out["peak_accel_impact"][0, i, j] = int(np.flatnonzero(inside)[0]) + 1 \
                if inside.any() else 0
            if starts.size:
                first = slice(starts[0], ends[0])
                out["first_impact_max_force"][0, i, j] = force[first].max()
                out["first_impact_max_indentation"][0, i, j] = h.indentation.values[first].max()
            for k, start in enumerate(starts[:IMPACTS_KEPT]):
                out["impact_speed"][0, i, j, k] = abs(u0[start] - u0[start - 1]) / dt
    dims = ("record", "gap", "cor")
    return {
        "peak_accel_impact": variable(dims, out["peak_accel_impact"], "1",
                                      "impact (1 = first) during which the peak base "
                                      "acceleration occurs (0: outside any impact)"),
        "first_impact_max_force": variable(dims, out["first_impact_max_force"], "N",
                                           "largest force of the first impact"),
        "first_impact_max_indentation": variable(dims, out["first_impact_max_indentation"],
                                                 "m", "largest indentation of the first impact"),
        "impact_speed": variable((*dims, "impact"), out["impact_speed"], "m s-1",
                                 "approach speed of the slab at the start of each impact "
                                 "(first two; NaN: no such impact)"),
        "impact": variable("impact", np.arange(1, IMPACTS_KEPT + 1), "1",
                           "impact number (1 = first)"),
    }


GAP_LINESTYLES = ("-", "--", ":", "-.")  # per gap, widest first: solid for the widest
NEUTRAL = "0.35"  # legend colour of a line style that applies to every level


def gap_styles(ds) -> dict[float, dict]:
    """The one style table of the figure: the line style of each gap (m), widest solid, used
    by the plotted lines and by their legend entries alike."""
    widest_first = sorted(ds.gap.values.tolist(), reverse=True)
    return {gap: {"ls": GAP_LINESTYLES[k % len(GAP_LINESTYLES)], "marker": "o"}
            for k, gap in enumerate(widest_first)}


def gap_legend_label(ds, gap: float) -> str:
    """A gap's legend entry: "gap 29.5 cm: 0.9 × unconstrained peak"."""
    if "gap_source" not in ds.coords:
        return f"gap {gap / CM:.1f} cm"
    # the archive writes "0.9 x ..."; figures write the multiplication sign
    return f"gap {gap / CM:.1f} cm: {ds.gap_source.sel(gap=gap).item().replace(' x ', ' × ')}"


def plot(ds):
    fig, (left, right) = plt.subplots(1, 2, figsize=(7.5, 3.8))
    record = str(ds.record.values[0])
    cor = ds.cor.values
    accel = ds.peak_total_accel.sel(record=record) / G
    drift = ds.peak_interstory_drift.sel(record=record) / CM
    styles = gap_styles(ds)
    panels = [(left, accel, "floor", floor_labels(ds.sizes["floor"])),
              (right, drift, "story", story_labels(ds.sizes["story"]))]
    for ax, peaks, dim, labels in panels:
        for i, (level, label) in enumerate(zip(ds[dim].values, labels, strict=True)):
            for k, (gap, style) in enumerate(styles.items()):
                # one colour per level; its legend entry is its first (widest gap's) line
                ax.plot(cor, peaks.sel({dim: level, "gap": gap}), color=f"C{i}",
                        label=label if k == 0 else "_nolegend_", **style)
        ax.legend(loc="upper center", ncol=2, handlelength=3)
        ax.set_xlabel("Coefficient of restitution of the bumpers")
        ax.set_ylim(bottom=0, top=ax.get_ylim()[1] * 1.35)
    left.set_ylabel("Peak floor acceleration (g)")
    right.set_ylabel("Peak interstory deflection (cm)")
    fig.legend(handles=[plt.Line2D([], [], color=NEUTRAL, label=gap_legend_label(ds, gap),
                                   **style) for gap, style in styles.items()],
               loc="lower center", ncol=len(styles), handlelength=4, frameon=False)
    letter_panels((left, right))
    short_title(fig, "Fig. 22: peak responses vs the bumpers' coefficient of restitution")
    store_caption(ds, caption(ds))
    fig.tight_layout(rect=(0, 0.3 / fig.get_figheight(), 1, 1))  # the gaps' legend below
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    record = str(ds.record.values[0])
    gaps = " and ".join(f"{g / CM:.1f}" for g in sorted(gap_styles(ds)))
    return ("Fig. 22: peak responses against the bumpers' coefficient of restitution, "
            f"{record_label(ds, record)}, {float(ds.thickness) / CM:g} cm bumpers, seismic "
            f"gaps {gaps} cm (line styles, legend below). (a) peak floor accelerations, one "
            "colour per floor; (b) peak interstory deflections, one colour per story.")


def check(ds) -> list[Verdict]:
    """Paper 5.6: the coefficient of restitution does not affect the peak responses; the
    approach phase and the maximum impact force do not depend on it (restitution only)."""
    record = ds.record.values[0]
    out = []
    for gap in ds.gap.values:
        sel = ds.sel(record=record, gap=gap)
        accel, drift = sel.peak_total_accel, sel.peak_interstory_drift
        spreads = [(accel.max("cor") - accel.min("cor")) / accel.mean("cor"),
                   (drift.max("cor") - drift.min("cor")) / drift.mean("cor")]
        worst = [float(s.max()) for s in spreads]
        floor = floor_labels(ds.sizes["floor"])[int(spreads[0].values.argmax())].lower()
        story = story_labels(ds.sizes["story"])[int(spreads[1].values.argmax())]
        dent = sel.max_indentation
        impact = sel.peak_accel_impact.values
        speed = sel.impact_speed
        delta_u = float(ds.strain * ds.thickness)
        out.append(Verdict(
            "5.6", f"The COR does not affect the peak responses (gap {gap / CM:.1f} cm: "
            f"{str(sel.gap_source.values)})",
            f"under {record}, over COR {ds.cor.values.min():g}-{ds.cor.values.max():g}: peak "
            f"floor accelerations vary by up to {worst[0]:.0%} ({floor}), interstory "
            f"deflections by up to {worst[1]:.0%} ({story}) of their mean (no effect: < "
            f"{NO_EFFECT:.0%}); the peak base acceleration comes from impact "
            f"#{'/'.join(str(i) for i in sorted(set(impact.tolist())))}; approach speed of "
            f"the second impact {float(speed.sel(impact=2).min()):.3f}-"
            f"{float(speed.sel(impact=2).max()):.3f} m/s (the first "
            f"{float(speed.sel(impact=1).min()):.3f} m/s at every COR); maximum indentation "
            f"{float(dent.min()) / CM:.2f}-{float(dent.max()) / CM:.2f} cm (delta_u "
            f"{delta_u / CM:g} cm)",
            max(worst) < NO_EFFECT,
            {"gap": float(gap), "spread_accel": worst[0], "spread_drift": worst[1],
             "threshold": NO_EFFECT, "peak_accel_impact": impact,
             "impact_speed": speed.values, "max_indentation": dent.values,
             "delta_u": delta_u}))
    first = ds.first_impact_max_force.sel(record=record)
    spread = float(((first.max("cor") - first.min("cor")) / first.mean("cor")).max())
    overall = ds.max_impact_force.sel(record=record)
    overall_spread = float(((overall.max("cor") - overall.min("cor"))
                            / overall.mean("cor")).max())
    out.append(Verdict(
        "5.6", "The maximum impact force does not depend on the COR, which acts in "
        "restitution only",
        f"the first impact's largest force varies by {spread:.1e} of its mean over the CORs "
        f"(unaffected: < 1e-3); the largest force of the whole run, from a later impact, by "
        f"{overall_spread:.0%}", spread < 1e-3,
        {"first_impact_force_spread": spread, "run_max_force_spread": overall_spread}))
    return out


recipe = Recipe(
    name="restitution", figure="Fig. 22",
    summary="Peak floor accelerations and interstory deflections against the bumpers' "
            "coefficient of restitution (0.3-1.0), Sylmar Converter, gap 10% under its "
            "unconstrained peak isolator displacement, 5 cm bumpers",
    compute=compute, plot=plot, check=check, records=("sylmar_converter",),
    chosen="COR 0.3 to 1.0 every 0.1 (0.3, 0.6, 1.0 with --quick); the gap rounded to the mm, "
           "and the paper's 28.5 cm; check: 'no effect' read as a spread over the CORs below "
           "5% of the mean")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
