"""studies.plan's verdicts on the paper's gap-size conclusions, asked of the planar model and
of the building in plan side by side: each claim with the paper's quantifier, counted only at
the (pair, angle, gap) points where what it speaks of happens (see plan.py's docstring)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.assess.outcomes import (
    COUNT_TEXT,
    HELPED,
    NEUTRAL,
    QUANTIFIERS,
    TOLERANCE,
    count,
    effect,
)

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
    return amp > 1 + TOLERANCE, fit & _hit(sel, "bumpers") & ~_hit(sel, "bare wall"), amp


def base_reduced(sel, fit):
    """Where the bare wall is hit: the base's peak acceleration lower with bumpers."""
    amp = _amp(sel, "peak_base_accel")
    return amp < 1 - TOLERANCE, fit & _hit(sel, "bare wall"), amp


def floor_reduced(sel, fit):
    """Where the bare wall is hit: the largest peak floor acceleration lower with bumpers."""
    amp = _amp(sel, "peak_floor_accel")
    return amp < 1 - TOLERANCE, fit & _hit(sel, "bare wall"), amp


def drift_amplified(sel, fit):
    """Where the bumpers or the bare wall are hit: the largest interstory drift amplified."""
    amp = _amp(sel, "peak_interstory_drift")
    return amp > 1 + TOLERANCE, fit & (_hit(sel, "bumpers") | _hit(sel, "bare wall")), amp


def force_reduced(sel, fit):
    """Where both are hit: the largest impact force lower with bumpers than on the bare wall."""
    amp = _amp(sel, "max_impact_force")
    return amp < 1 - TOLERANCE, fit & _hit(sel, "bumpers") & _hit(sel, "bare wall"), amp


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
    Claim("5.1", "'For relatively wide seismic gap sizes the usage of rubber shock-absorbers "
          "may increase the response instead of reducing it. In particular, this may happen for "
          "seismic gap sizes where poundings would not occur without the incorporation of "
          "rubber bumpers' (the paper's conclusions; here: where only the bumpers are hit, the "
          "peak floor acceleration)", "may",
          "(pair, angle, gap) points where the bumpers are hit and the bare wall is not",
          only_bumpers_amplify),
    Claim("5.1", "Narrow gaps: bumpers can reduce the peak base acceleration (under the "
          "strongest motions)", "can",
          "(pair, angle, gap) points where the bare wall is hit (bumpers run)", base_reduced),
    Claim("5.1", "Interstory deflections are amplified by bumpers in most of the examined "
          "cases", "most",
          "(pair, angle, gap) points where the bumpers or the bare wall are hit (bumpers run)",
          drift_amplified),
    Claim("6", "'Employing rubber shock-absorbers at impact locations may reduce the maximum "
          "impact force'", "may",
          "(pair, angle, gap) points where both the bumpers and the bare wall are hit",
          force_reduced),
)


def events(ds) -> np.ndarray:
    """(R,) the earthquake of each pair: the archive's record_event if it has one, else the
    library's event of the pair's x component (record_source), else the pair itself (each pair
    its own earthquake)."""
    if "record_event" in ds.coords or "record_event" in ds:
        return np.asarray(ds.record_event.values).astype(str)
    names = [str(r) for r in ds.record.values]
    if "record_source" not in ds.coords and "record_source" not in ds:
        return np.array(names)
    try:
        from pipeline.records.library import library_index

        by_source = {e.source: e.event for e in library_index()}
    except Exception:  # noqa: BLE001  (no library: each pair its own earthquake)
        by_source = {}
    out = []
    for name, source in zip(names, ds.record_source.values, strict=True):
        x = str(source).split(";")[0].removeprefix("x:").strip()
        out.append(by_source.get(x, name))
    return np.array(out)


def counts(ds, rule) -> dict:
    """model -> (held, counted, amplification): two boolean arrays over (record, angle,
    gap_fraction), counted where the claim applies and the amplification leaves the
    tolerance band (ties outside), and the amplifications (-) at the counted points."""
    return {m: (held, counted & changed, amp)
            for m, (held, counted, amp, changed) in cases(ds, rule).items()}


def cases(ds, rule) -> dict:
    """model -> (held, applies, amplification, changed): boolean arrays over (record, angle,
    gap_fraction): the claim holds (beyond the tolerance), it applies (the walls hit as it
    says, bumpers run), the amplifications (-) at the counted points (applies and changed),
    and where the amplification leaves the tolerance band (ties: within it)."""
    fit = ds.bumpers_fit.transpose(*POINT).values.astype(bool)
    out = {}
    for model in MODELS:
        holds, applies, amp = rule(ds.sel(model=model), fit)
        changed = (amp < 1 - TOLERANCE) | (amp > 1 + TOLERANCE)
        out[model] = (holds & applies & changed, applies, amp[applies & changed], changed)
    return out


def _model_numbers(c, held, counted, changed) -> dict:
    """One model's count (pipeline.assess.outcomes.Count) for the archive: held and counted
    cases (ints), the weights, ties and cases not counted beside."""
    return {**c.numbers(), "held": int((held & counted & changed).sum()),
            "counted": int((counted & changed).sum()), "verdict": verdict(c.verdict)}


def side_by_side(claim: Claim, ds, extra: str = "", numbers: dict | None = None) -> Verdict:
    """The claim judged in plan, with the planar model's count beside it: each by
    pipeline.assess.outcomes.count, a pair with its earthquake's weight once however many
    angles and gaps it runs at, ties and points without contact beside."""
    masks = cases(ds, claim.rule)
    ev = events(ds)
    fracs = ds.gap_fraction.values
    per_model, by_gap = {}, {}
    for model, (held, counted, amp, changed) in masks.items():
        c = count(claim.quantifier, held, counted, changed, events=ev)
        per_model[model] = {**_model_numbers(c, held, counted, changed),
                            "amplification": _spread(amp)}
        denominator = counted & changed
        by_gap[model] = {f"{f:g}": [int(held[..., i].sum()), int(denominator[..., i].sum())]
                         for i, f in enumerate(fracs)}
    return _verdict(claim.conclusion, _quoted(claim.claim, claim.quantifier), claim.points,
                    per_model, extra,
                    {"quantifier": per_model["plan"]["quantifier"],
                     "wording": claim.quantifier, "counted_at": claim.points,
                     **per_model, "by_gap_fraction": by_gap, **(numbers or {})})


def _quoted(claim: str, quantifier: str) -> str:
    """The claim as the paper words it, with the reading of its quantifier."""
    c = count(quantifier, [True], [True])
    return f"{claim} [{QUANTIFIERS[c.quantifier]}: {COUNT_TEXT[c.quantifier]}]"


def _verdict(conclusion, claim, points, per_model, extra, numbers) -> Verdict:
    def share(m):
        n, amp = per_model[m]["counted"], per_model[m].get("amplification")
        median = f", median x{amp['median']:.2f}" if amp else ""
        return f"{per_model[m]['held']}/{n}" + (f" ({per_model[m]['fraction']:.0%}{median})"
                                                 if per_model[m]["fraction"] is not None
                                                 else "")

    def beside(m):
        v = per_model[m]
        return (f"{v['pairs_counted']} pairs, {v['events_counted']} earthquakes, "
                f"{v['tie_cases']} ties within {TOLERANCE:.0%} not counted")

    plan = per_model["plan"]
    finding = (f"planar: {share('planar')} {points} ({per_model['planar']['verdict']}; "
               f"{beside('planar')}); in plan: {share('plan')} ({beside('plan')}; shares: "
               f"of the weight, each earthquake once){extra}")
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
    (pair, angle), the base amplification at the narrowest fraction below that at the widest
    by more than the tolerance (within it: a tie, beside), counted where the bumpers fit at
    both and a wall is hit at both (where nothing is hit at the widest, the amplification
    there is 1 by construction, not a comparison); a pair's angles share its earthquake's
    weight (pipeline.assess.outcomes.count)."""
    fit = ds.bumpers_fit.transpose(*POINT).values.astype(bool)
    narrow, wide = int(np.argmin(ds.gap_fraction.values)), int(np.argmax(ds.gap_fraction.values))
    ev = events(ds)
    per_model = {}
    for model in MODELS:
        sel = ds.sel(model=model)
        amp = _amp(sel, "peak_base_accel")
        hit = _hit(sel, "bumpers") | _hit(sel, "bare wall")
        counted = fit[..., narrow] & fit[..., wide] & hit[..., narrow] & hit[..., wide] \
            & (narrow != wide)
        compared = effect(amp[..., narrow], amp[..., wide])
        held, changed = compared == HELPED, compared != NEUTRAL
        c = count("most", held, counted, changed, events=ev)
        per_model[model] = _model_numbers(c, held, counted, changed)
    f_n, f_w = ds.gap_fraction.values[narrow], ds.gap_fraction.values[wide]
    points = (f"(pair, angle) points where the base acceleration is amplified less at gap "
              f"{f_n:g} than at {f_w:g} x the peak (counted: a wall hit at both)")
    return _verdict("6", _quoted("'Rubber bumpers seem to be more effective for relatively "
                                 "narrow seismic gaps, compared to the maximum induced "
                                 "displacement' (no quantifier; read as a tendency, as "
                                 "studies.suite does)", "most"), points, per_model, "",
                    {"quantifier": "most", "counted_at": points, **per_model,
                     "narrow_fraction": float(f_n), "wide_fraction": float(f_w)})
