"""studies.loss's figure: the median repair cost at the MCE_R, the expected annual loss and the
annual rate of pounding against the gap, one curve per barrier, and against the bare wall the
repair cost at the MCE_R by component group."""
from __future__ import annotations

from engine.units import CM

from ..common.plot import letter_panels, plt, store_caption


def plot(ds):
    """(a) the median repair cost at the MCE_R against the gap, one curve per barrier; (b) the
    expected annual loss; (c) the annual rate of pounding; (d) against the bare wall, the mean
    repair cost at the MCE_R given no collapse by component group (repair_cost_by_group),
    stacked."""
    fig, axes = plt.subplots(1, 4, figsize=(15.5, 3.8), constrained_layout=True)
    panels = ((ds.median_repair_cost_mce, 1e-6, "median repair cost at MCE_R (M$ 2011)"),
              (ds.expected_annual_loss, 1e-3, "expected annual loss (k$ 2011 / yr)"),
              (ds.annual_rate_contact, 1e4, "annual rate of pounding (x 10^-4 / yr)"))
    for ax, (values, scale, label) in zip(axes[:3], panels, strict=True):
        for k, barrier in enumerate(ds.barrier.values):  # the same colours in every panel
            ax.plot(ds.gap.values / CM, scale * values.sel(barrier=barrier).values,
                    marker="osD^vP"[k % 6], markerfacecolor="none", label=str(barrier))
        ax.set_xlabel("seismic gap (cm)")
        ax.set_ylabel(label)
    groups = ds.repair_cost_by_group.sel(barrier="bare wall").sel(level=1.0, method="nearest")
    axes[3].stackplot(ds.gap.values / CM, 1e-6 * groups.transpose("component_group", ...).values,
                      labels=[str(g) for g in ds.component_group.values])
    axes[3].set_xlabel("seismic gap (cm)")
    axes[3].set_ylabel("bare wall: MCE_R, no collapse (M$ 2011)")
    axes[0].legend(fontsize=8, ncol=2)
    axes[3].legend(fontsize=8)
    letter_panels(axes)
    store_caption(ds, caption(ds))
    return fig


def caption(ds) -> str:
    """The figure's caption (the archive's figure_caption)."""
    return ("Repair cost and annual rates of the building against the seismic gap, one curve "
            "per barrier (FEMA P-58 by pelicun). (a) the median repair cost at the MCE_R; (b) "
            "the expected annual loss over the hazard curve; (c) the mean annual frequency of "
            "pounding; (d) against the bare wall, the mean repair cost at the MCE_R given no "
            "collapse by component group, stacked (the moat and isolation plane's repairs among "
            f"them). Hazard: {ds.attrs['hazard']}.")
