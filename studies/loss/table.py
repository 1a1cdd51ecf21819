"""The loss study's decision table: gap x barrier -> P(collapse | MCE_R), the median repair
cost at the MCE_R, the expected annual loss with its paired interval and the annual rate of
pounding, and beside each row what a reader must know of it (runs outside the model's range,
an EAL that is a bound); under it the repair cost's shares by component group."""
from __future__ import annotations

from engine.units import CM
from pipeline.assess import loss as p58


def decision_table(ds) -> str:
    """The decision table: gap x barrier -> P(collapse | MCE_R), median cost, EAL, pounding."""
    lines = [f"{'gap':>8} {'barrier':>11} {'P(coll|MCE_R)':>14} {'median cost MCE_R':>18} "
             f"{'EAL':>10} {'EAL 95%':>13} {'pounding /yr':>13}"]
    for g, gap in enumerate(ds.gap.values):
        for b, barrier in enumerate(ds.barrier.values):
            at = dict(barrier=b, gap_fraction=g)
            lines.append(
                f"{gap / CM:6.1f}cm {barrier:>11} "
                f"{'<=' if str(ds.collapse_probability_bound[at].values) != 'exact' else '':>2}"
                f"{100 * float(ds.collapse_probability[at]):11.1f}% "
                f"{float(ds.median_repair_cost_mce[at]) / 1e6:14.2f} M$ "
                f"{'<=' if _eal_bounded(ds, at) else '':>2}"
                f"{float(ds.expected_annual_loss[at]) / 1e3:5.1f} k$ "
                f"{_interval(ds, at):>13} "
                f"{float(ds.annual_rate_contact[at]):13.2e}" + _why(ds, at))
    if "repair_cost_by_group" in ds:  # what pounding damages: the acceleration-sensitive
        mce = ds.repair_cost_by_group.sel(level=1.0, method="nearest")
        share = 100 * mce / mce.sum("component_group")
        lines.append("the mean repair cost at the MCE_R given no collapse (repair_cost_by_group): "
                     + ", ".join(f"{g} {float(share[i].min()):.0f}-{float(share[i].max()):.0f}%"
                                 for i, g in enumerate(ds.component_group.values)))
    return "\n".join(lines)


def _interval(ds, at) -> str:
    """A row's EAL interval in k$ (expected_annual_loss_interval; an archive before it:
    blank)."""
    if "expected_annual_loss_interval" not in ds:
        return ""
    low, high = ds.expected_annual_loss_interval[at].values / 1e3
    return f"[{low:.1f}-{high:.1f}]"


def _eal_bounded(ds, at) -> bool:
    """Whether a row's EAL is an upper bound (expected_annual_loss_bound; an archive before
    it: never)."""
    return "expected_annual_loss_bound" in ds \
        and str(ds.expected_annual_loss_bound[at].values) != "exact"


def _why(ds, at) -> str:
    """Beside a row's numbers: its runs outside the model's range, why an EAL is a bound."""
    said = []
    outside = int(ds.runs_outside_range[at].sum())
    if outside:
        said.append(f"{outside} runs outside the model's range, in as computed")
    if _eal_bounded(ds, at):
        few = ds.level.values[ds.loss_bounded[at].values.astype(bool)]
        said.append(f"EAL at most: fewer than {p58.MIN_RUNS} runs standing at "
                    + ", ".join(f"{level:g}" for level in few) + " x MCE_R, their loss given no "
                    "collapse bounded by the replacement")
    return f"  ({'; '.join(said)})" if said else ""
