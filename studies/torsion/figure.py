"""studies.torsion's figure: the corners against the centre, the code's D_TM, the corners'
orbits and the force on the worst bumper."""
from __future__ import annotations

import numpy as np

from engine.units import CM

from ..common.plot import plt
from .verdicts import code_ratio, corner_ratio, pad_share, points_per_wall, spread


def caption(ds) -> str:
    return ("Torsion at the MCE_R: (a) the worst corner's peak over the centre's without wall "
            "(median and 16-84th percentiles over pairs and angles) against the code's D_TM / "
            "D_M; (b) the corners' and the centre's orbits (first pair, angle 0, the largest "
            "eccentricity) with D_M and D_TM; (c) the share of its wall's peak force the worst "
            "pad (and the bare wall's worst corner) carries, where they are hit; (d) the "
            "centre's peak over D_M and the worst corner's over D_TM, without wall.")


def plot(ds):
    fig, axes = plt.subplots(2, 2, figsize=(9, 7), layout="constrained")
    (a, b), (c, d) = axes
    eccs = ds.mass_offset_ratio.values
    w = ds.record_weight.values
    ratio = corner_ratio(ds)
    stats = [spread(ratio[:, i], w) for i in range(eccs.size)]
    a.errorbar(eccs * 100, [s["median"] for s in stats],
               yerr=[[s["median"] - s["p16"] for s in stats],
                     [s["p84"] - s["median"] for s in stats]], marker="o", capsize=3,
               label="measured (median, 16-84%)")
    a.plot(eccs * 100, code_ratio(ds), "k--", label="code D_TM / D_M")
    a.set_xlabel("mass centre offset (% of each plan dimension)")
    a.set_ylabel("worst corner / centre")
    a.set_title("(a) corners travel farther")
    a.legend(fontsize=7)

    centre, corners = ds.orbit_centre.values / CM, ds.orbit_corners.values / CM
    for k in range(corners.shape[1]):
        b.plot(corners[:, k, 0], corners[:, k, 1], lw=0.6, label="corners" if k == 0 else None)
    b.plot(centre[:, 0], centre[:, 1], "k", lw=0.9, label="centre")
    d_m, d_tm = float(ds.attrs["D_M"]) / CM, float(ds.D_TM.values[-1]) / CM
    for radius, ls, name in ((d_m, ":", "D_M"), (d_tm, "--", "D_TM")):
        b.add_patch(plt.Rectangle((-radius, -radius), 2 * radius, 2 * radius, fill=False,
                                  ls=ls, lw=0.8, label=name))
    b.set_aspect("equal")
    b.set_xlabel("x (cm)")
    b.set_ylabel("y (cm)")
    b.set_title(f"(b) orbits, e = {eccs[-1]:g}")
    b.legend(fontsize=7)

    for barrier, marker in (("bumpers", "o"), ("bare wall", "s")):
        share = pad_share(ds, barrier)
        for j, gap in enumerate(ds.gap.values):
            s = [spread(share[:, i, :, j], w) for i in range(eccs.size)]
            med = [np.nan if x["median"] is None else x["median"] for x in s]
            if not np.all(np.isnan(med)):  # no contact at this gap: nothing to draw
                c.plot(eccs * 100, med, marker=marker, label=f"{barrier} at {gap}")
        c.axhline(1 / points_per_wall(ds, barrier), ls=":", lw=0.8, color="0.4")
    c.set_ylim(0, 1.05)
    c.set_xlabel("mass centre offset (% of the plan)")
    c.set_ylabel("worst point's share of its wall's peak")
    c.set_title("(c) force on one pad (median; dotted: equal shares)")
    c.legend(fontsize=7)

    centre = ds.free_peak_isolator_disp.values / float(ds.attrs["D_M"])
    corner = ds.free_peak_corner_disp.values / ds.D_TM.values[None, :, None]
    for values, name, shift in ((centre, "centre / D_M", -0.4), (corner, "worst corner / D_TM",
                                                                  0.4)):
        s = [spread(values[:, i], w) for i in range(eccs.size)]
        d.errorbar(eccs * 100 + shift, [x["median"] for x in s],
                   yerr=[[x["median"] - x["p16"] for x in s], [x["p84"] - x["median"] for x in s]],
                   marker="o", capsize=3, ls="none", label=name)
    d.axhline(1.0, color="k", lw=0.8, ls="--")
    d.set_ylim(0, None)
    d.set_xlabel("mass centre offset (% of the plan)")
    d.set_ylabel("peak without wall / the code's")
    d.set_title("(d) against the code's D_M and D_TM (median, 16-84%)")
    d.legend(fontsize=7)
    return fig
