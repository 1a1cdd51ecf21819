"""Fig. 16: peak responses against the seismic gap width for three bumper thicknesses.

Gap 15-45 cm (before bumpers: the clear gap is gap - t), four bumpers on each side,
k_w = 1500 kN/mm, Sylmar Converter and Pacoima Dam (the records that drive the isolation level
furthest). The paper does not state its three thicknesses: 3, 5 and 8 cm here. The bare wall
without bumpers at the full gap is dashed.
"""
from __future__ import annotations

from engine.units import CM, KN_PER_MM

from .common.paper import N_BUMPERS, WALL_K
from .common.peaks_vs_gap import accel_g, drift_cm, gaps, plot_vs_gap, spread, vs_gap_caption
from .common.recipe import Recipe, Verdict, sweep_options

THICKNESSES = (0.03, 0.05, 0.08)  # m: chosen, the paper does not state them
NARROW = 0.6  # "very narrow" gap: below this fraction of the unconstrained peak


def compute(args):
    import pipeline

    return pipeline.sweep(gap=gaps(args.quick), thickness=list(THICKNESSES),
                          n_bumpers=N_BUMPERS, wall_k=WALL_K, baseline=True,
                          unconstrained=True, **sweep_options(args))


TITLE = ("Fig. 16: peak responses vs seismic gap, bumper thickness t "
         f"({N_BUMPERS} bumpers, $k_w$ = {WALL_K / KN_PER_MM:g} kN/mm)")
"""The figure's one-line title (its caption: caption)."""


def plot(ds):
    return plot_vs_gap(ds, "thickness", lambda t: f"t = {t / CM:g} cm",
                       TITLE)


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return vs_gap_caption(TITLE)


def check(ds) -> list[Verdict]:
    """Paper 5.2: thicker bumpers lower the floor accelerations at very narrow gaps, hardly
    change them at medium and wide gaps, raise the interstory deflections; overall the
    thickness does not significantly affect the response."""
    accel, drift = accel_g(ds), drift_cm(ds)
    thin, thick = ds.thickness.values.min(), ds.thickness.values.max()
    names = f"t = {thick / CM:g} cm", f"t = {thin / CM:g} cm"
    narrow = ds.gap < NARROW * ds.unconstrained_peak_isolator_disp
    hit = (ds.n_impacts > 0).any("thickness")
    lower = accel.sel(thickness=thick) < accel.sel(thickness=thin)
    higher = drift.sel(thickness=thick) > drift.sel(thickness=thin)
    n_narrow, n_lower = int(narrow.sum()), int((lower & narrow).sum())
    wide = hit & ~narrow
    wide_spread = float(spread(accel, "thickness").where(wide).median())
    spread_a = float(spread(accel, "thickness").where(hit).median())
    spread_d = float(spread(drift, "thickness").where(hit).median())
    n_hit, n_higher = int(hit.sum()), int((higher & hit).sum())
    return [
        Verdict("5.2", f"Very narrow gaps (< {NARROW} x the unconstrained peak isolator "
                "displacement): thicker bumpers reduce the peak floor acceleration",
                f"{names[0]} below {names[1]} at {n_lower}/{n_narrow} such gaps",
                n_lower > n_narrow / 2 if n_narrow else None,
                {"narrow_points": n_narrow, "thicker_lower": n_lower}),
        Verdict("5.2", "Medium and wide gaps: negligible effect of the thickness on the "
                "acceleration", f"median spread over t {wide_spread:.0%} at the other gaps "
                "with impacts (negligible: < 10%)",
                wide_spread < 0.1 if bool(wide.any()) else None,
                {"median_spread": wide_spread, "threshold": 0.1}),
        Verdict("5.2", "Interstory deflections increase with the thickness",
                f"{names[0]} above {names[1]} at {n_higher}/{n_hit} gaps with impacts",
                n_higher > n_hit / 2 if n_hit else None,
                {"points_with_impacts": n_hit, "thicker_higher": n_higher}),
        Verdict("5.2", "Overall the thickness does not significantly affect the response",
                f"median spread over t {spread_a:.0%} (acceleration), {spread_d:.0%} "
                "(interstory deflection) at the gaps with impacts (not significant: < 15%)",
                max(spread_a, spread_d) < 0.15 if n_hit else None,
                {"median_spread_accel": spread_a, "median_spread_drift": spread_d,
                 "threshold": 0.15}),
    ]


recipe = Recipe(
    name="thickness", figure="Fig. 16",
    summary="Peak floor accelerations and interstory deflections against the seismic gap "
            "(15-45 cm) for three bumper thicknesses, Sylmar Converter and Pacoima Dam",
    compute=compute, plot=plot, check=check, records=("sylmar_converter", "pacoima"),
    chosen="thicknesses 3, 5 and 8 cm; gap step 1 cm (10 cm with --quick); check: 'very "
           "narrow' gap below 0.6 x the unconstrained peak isolator displacement, 'negligible' "
           "and 'not significant' median spreads over t below 10% and 15%")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
