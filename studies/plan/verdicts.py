"""studies.plan's verdicts on the paper's gap-size conclusions, asked of the planar model and
of the building in plan side by side: each claim with the paper's quantifier, counted only at
the (pair, angle, gap) points where what it speaks of happens (see plan.py's docstring)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.assess.outcomes import QUANTIFIERS, judged

from ..common.recipe import Verdict, verdict

MODELS = ("planar", "plan")


POINT = ("record", "angle", "gap_fraction")  # a point the conclusions are counted at


def _hit(sel, barrier) -> np.ndarray:
    """(record, angle, gap_fraction) bool: the barrier is hit (-1, not run, is not)."""
    return (sel.n_impacts.sel(barrier=barrier) > 0).transpose(*POINT).values


def _amp(sel, name) -> np.ndarray:
    """(record, angle, gap_fraction): with bumpers / against the bare wall at the same gap (>1:
    the bumpers make it worse; NaN where they were not run)."""
    ratio = sel[name].sel(barrier="bumpers") / sel[name].sel(barrier="bare wall")
    return ratio.transpose(*POINT).values


def only_bumpers_amplify(sel, fit):
    """gap_size's 'wide gap': the bumpers are hit, the bare wall at that gap is not; there the
    largest peak floor acceleration is amplified."""
    amp = _amp(sel, "peak_floor_accel")
    return amp > 1, fit & _hit(sel, "bumpers") & ~_hit(sel, "bare wall"), amp


def base_reduced(sel, fit):
    """Where the bare wall is hit: the base's peak acceleration lower with bumpers."""
    amp = _amp(sel, "peak_base_accel")
    return amp < 1, fit & _hit(sel, "bare wall"), amp


def floor_reduced(sel, fit):
    """Where the bare wall is hit: the largest peak floor acceleration lower with bumpers."""
    amp = _amp(sel, "peak_floor_accel")
    return amp < 1, fit & _hit(sel, "bare wall"), amp


def drift_amplified(sel, fit):
    """Where the bumpers or the bare wall are hit: the largest interstory drift amplified."""
    amp = _amp(sel, "peak_interstory_drift")
    return amp > 1, fit & (_hit(sel, "bumpers") | _hit(sel, "bare wall")), amp


def force_reduced(sel, fit):
    """Where both are hit: the largest impact force lower with bumpers than on the bare wall."""
    amp = _amp(sel, "max_impact_force")
    return amp < 1, fit & _hit(sel, "bumpers") & _hit(sel, "bare wall"), amp


@dataclass(frozen=True)
class Claim:
    """A conclusion of the paper on the gap size: where (section), what (with the paper's
    quantifier, `QUANTIFIERS`), the points it is counted at, and the rule giving (holds,
    counted, amplification) over (record, angle, gap_fraction)."""

    conclusion: str
    claim: str
    quantifier: str
    points: str
    rule: object


CLAIMS = (
    Claim("5.1", "Wide gaps, where only the bumpers are hit: bumpers amplify the peak floor "
          "acceleration (the paper states it without quantifier; read, as gap_size does, as "
          "at every such point)", "every",
          "(pair, angle, gap) points where the bumpers are hit and the bare wall is not",
          only_bumpers_amplify),
    Claim("5.1", "Narrow gaps: bumpers can reduce the peak base acceleration (under the "
          "strongest motions)", "some",
          "(pair, angle, gap) points where the bare wall is hit (bumpers run)", base_reduced),
    Claim("5.1", "Interstory deflections are amplified by bumpers in most of the examined "
          "cases", "most",
          "(pair, angle, gap) points where the bumpers or the bare wall are hit (bumpers run)",
          drift_amplified),
    Claim("6", "Bumpers may reduce the maximum impact force", "some",
          "(pair, angle, gap) points where both the bumpers and the bare wall are hit",
          force_reduced),
)


def counts(ds, rule) -> dict:
    """model -> (held, counted, amplification): two boolean arrays over (record, angle,
    gap_fraction) and the amplifications (-) at the counted points."""
    fit = ds.bumpers_fit.transpose(*POINT).values.astype(bool)
    out = {}
    for model in MODELS:
        holds, counted, amp = rule(ds.sel(model=model), fit)
        out[model] = (holds & counted, counted, amp[counted])
    return out


def side_by_side(claim: Claim, ds, extra: str = "", numbers: dict | None = None) -> Verdict:
    """The claim judged in plan, with the planar model's count beside it."""
    masks = counts(ds, claim.rule)
    fracs = ds.gap_fraction.values
    per_model, by_gap = {}, {}
    for model, (held, counted, amp) in masks.items():
        h, n = int(held.sum()), int(counted.sum())
        per_model[model] = {"held": h, "counted": n, "fraction": h / n if n else None,
                            "verdict": verdict(judged(claim.quantifier, h, n)),
                            "amplification": _spread(amp)}
        by_gap[model] = {f"{f:g}": [int(held[..., i].sum()), int(counted[..., i].sum())]
                         for i, f in enumerate(fracs)}
    return _verdict(claim.conclusion, f"{claim.claim} [{QUANTIFIERS[claim.quantifier]}]",
                    claim.points, per_model, extra,
                    {"quantifier": claim.quantifier, "counted_at": claim.points,
                     **per_model, "by_gap_fraction": by_gap, **(numbers or {})})


def _verdict(conclusion, claim, points, per_model, extra, numbers) -> Verdict:
    def share(m):
        n, amp = per_model[m]["counted"], per_model[m].get("amplification")
        median = f", median x{amp['median']:.2f}" if amp else ""
        return f"{per_model[m]['held']}/{n}" + (f" ({per_model[m]['held'] / n:.0%}{median})"
                                                 if n else "")

    plan = per_model["plan"]
    finding = (f"planar: {share('planar')} {points} ({per_model['planar']['verdict']}); "
               f"in plan: {share('plan')}{extra}")
    return Verdict(conclusion, claim, finding,
                   None if plan["verdict"] == "not tested" else plan["verdict"] == "agrees",
                   numbers)


def _spread(amp) -> dict | None:
    """Median and extremes (-) of the amplifications at the counted points (None: none)."""
    if not amp.size:
        return None
    return {"median": float(np.median(amp)), "min": float(amp.min()), "max": float(amp.max())}


def narrow_more_effective(ds) -> Verdict:
    """Paper 6: bumpers more effective at narrow gaps compared with the displacement: per
    (pair, angle), the base amplification at the narrowest fraction below that at the widest,
    counted where the bumpers fit at both and a wall is hit at both (where nothing is hit at
    the widest, the amplification there is 1 by construction, not a comparison)."""
    fit = ds.bumpers_fit.transpose(*POINT).values.astype(bool)
    narrow, wide = int(np.argmin(ds.gap_fraction.values)), int(np.argmax(ds.gap_fraction.values))
    per_model = {}
    for model in MODELS:
        sel = ds.sel(model=model)
        amp = _amp(sel, "peak_base_accel")
        hit = _hit(sel, "bumpers") | _hit(sel, "bare wall")
        counted = fit[..., narrow] & fit[..., wide] & hit[..., narrow] & hit[..., wide] \
            & (narrow != wide)
        held = int((counted & (amp[..., narrow] < amp[..., wide])).sum())
        n = int(counted.sum())
        per_model[model] = {"held": held, "counted": n, "fraction": held / n if n else None,
                            "verdict": verdict(judged("most", held, n))}
    f_n, f_w = ds.gap_fraction.values[narrow], ds.gap_fraction.values[wide]
    points = (f"(pair, angle) points where the base acceleration is amplified less at gap "
              f"{f_n:g} than at {f_w:g} x the peak (counted: a wall hit at both)")
    return _verdict("6", "Bumpers seem more effective at gaps narrow compared with the induced "
                    "displacement (no quantifier in the paper; read as a tendency, as "
                    f"studies.suite does) [{QUANTIFIERS['most']}]", points, per_model, "",
                    {"quantifier": "most", "counted_at": points, **per_model,
                     "narrow_fraction": float(f_n), "wide_fraction": float(f_w)})
