"""Fig. 22: peak responses of the building against the bumpers' coefficient of restitution.

Sylmar Converter; the seismic gap is 10% under the engine's own unconstrained peak isolator
displacement for the record (paper: 28.5 cm), 5 cm bumpers (clear gap 5 cm smaller, the
paper's 23.5 cm), four bumpers, k_w = 1500 kN/mm; COR 0.3 to 1.0. Peak floor accelerations (g)
per floor and interstory deflections (cm) per story, against the COR.
"""
from __future__ import annotations

import numpy as np

from engine.units import CM, G

from ._plot import FLOOR_LABELS, STORY_LABELS, plt, record_label
from ._recipe import Recipe, sweep_options

THICKNESS = 0.05  # m
GAP_FRACTION = 0.9  # of the unconstrained peak isolator displacement
NO_EFFECT = 0.05  # largest spread over the CORs, relative to the mean, read as 'no effect'


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
                                        records_dir=args.records_dir)
    peak = float(free.peak_isolator_disp.item())
    gap = round(GAP_FRACTION * peak, 3)  # m, to the mm
    ds = pipeline.sweep(gap=gap, thickness=THICKNESS, cor=cors(args.quick),
                        unconstrained=True, **options)
    ds.attrs.update(
        gap_rule=f"gap = {GAP_FRACTION} x unconstrained peak isolator displacement "
                 f"({peak / CM:.2f} cm) = {gap / CM:.1f} cm, to the mm; clear gap with "
                 f"{THICKNESS / CM:g} cm bumpers {(gap - THICKNESS) / CM:.1f} cm "
                 "(paper: 28.5 and 23.5 cm)",
        chosen_gap=gap, chosen_gap_units="m", clear_gap=round(gap - THICKNESS, 4),
        clear_gap_units="m")
    return ds


def plot(ds):
    fig, (left, right) = plt.subplots(1, 2, figsize=(7.5, 3.2))
    record = str(ds.record.values[0])
    cor = ds.cor.values
    accel = ds.peak_total_accel.sel(record=record) / G
    drift = ds.peak_interstory_drift.sel(record=record) / CM
    for floor, label in zip(ds.floor.values, FLOOR_LABELS, strict=True):
        left.plot(cor, accel.sel(floor=floor), marker="o", label=label)
    for story, label in zip(ds.story.values, STORY_LABELS, strict=True):
        right.plot(cor, drift.sel(story=story), marker="o", label=label)
    left.set_ylabel("Peak floor acceleration (g)")
    right.set_ylabel("Peak interstory deflection (cm)")
    for ax in (left, right):
        ax.set_xlabel("Coefficient of restitution of the bumpers")
        ax.set_ylim(bottom=0, top=ax.get_ylim()[1] * 1.35)
        ax.legend(loc="upper center", ncol=2)
    gap = float(ds.gap) / CM
    fig.suptitle(f"Fig. 22: peak responses vs the bumpers' coefficient of restitution\n"
                 f"{record_label(ds, record)}, seismic gap {gap:.1f} cm, "
                 f"{float(ds.thickness) / CM:g} cm bumpers (clear gap "
                 f"{gap - float(ds.thickness) / CM:.1f} cm)")
    fig.tight_layout()
    return fig


def check(ds) -> str:
    """Paper 5.6: the coefficient of restitution does not affect the peak responses."""
    record = ds.record.values[0]
    accel = ds.peak_total_accel.sel(record=record)
    drift = ds.peak_interstory_drift.sel(record=record)
    spreads = [(accel.max("cor") - accel.min("cor")) / accel.mean("cor"),
               (drift.max("cor") - drift.min("cor")) / drift.mean("cor")]
    worst = [float(s.max()) for s in spreads]
    floor = FLOOR_LABELS[int(spreads[0].values.argmax())].lower()
    story = STORY_LABELS[int(spreads[1].values.argmax())]
    dent = ds.max_indentation.sel(record=record) / CM
    delta_u = float(ds.strain * ds.thickness) / CM
    return (f"The COR does not affect the peak responses (paper 5.6); here, at a "
            f"{float(ds.gap) / CM:.1f} cm gap under {record}, over COR {ds.cor.values.min():g}-"
            f"{ds.cor.values.max():g}: peak floor accelerations vary by up to {worst[0]:.0%} "
            f"({floor}), interstory deflections by up to {worst[1]:.0%} ({story}) of their "
            f"mean -> {'agrees' if max(worst) < NO_EFFECT else 'differs'} "
            f"(no effect: < {NO_EFFECT:.0%}). "
            f"Maximum indentation {float(dent.min()):.2f}-{float(dent.max()):.2f} cm "
            f"(delta_u {delta_u:g} cm), {int(ds.n_impacts.max())} impacts at most.")


recipe = Recipe(
    name="restitution", figure="Fig. 22",
    summary="Peak floor accelerations and interstory deflections against the bumpers' "
            "coefficient of restitution (0.3-1.0), Sylmar Converter, gap 10% under its "
            "unconstrained peak isolator displacement, 5 cm bumpers",
    compute=compute, plot=plot, check=check, records=("sylmar_converter",),
    chosen="COR 0.3 to 1.0 every 0.1 (0.3, 0.6, 1.0 with --quick); the gap rounded to the mm; "
           "check: 'no effect' read as a spread over the CORs below 5% of the mean")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
