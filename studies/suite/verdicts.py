"""studies.suite's verdicts: each of the paper's conclusions asked of the code-scaled pairs,
with its own quantifier, counted only where what it speaks of happens, pairs weighted per
earthquake, and the runs outside the model's range stated (see suite.py's docstring)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.units import CM, KN_PER_MM
from pipeline.assess.collapse_modes import collapse_numbers, collapse_text
from pipeline.assess.derived import crushed
from pipeline.assess.outcomes import (
    COUNT_TEXT,
    HELPED,
    HURT,
    NEUTRAL,
    QUANTIFIERS,
    amplification,
    count,
    effect,
)

from ..common.paper import DELTA_U, N_BUMPERS, STRAIN, THICKNESS, WALL_K
from ..common.recipe import Verdict, verdict
from .archive import (
    PREFIX,
    outside,
    runs,
)


@dataclass(frozen=True)
class Case:
    """A conclusion asked of the runs: held, counted (bool over POINT: the cases where what it
    speaks of happens) and changed (bool: the quantity changes beyond the tolerance; None for
    a yes/no claim); runs: the runs behind each case (dicts of `runs`: their flags "outside"
    and "outside_any", and their "collapse_mode", over POINT). Counted by
    pipeline.assess.outcomes.count: each pair
    carries its earthquake's weight once, with the fraction of its counted cases that hold;
    ties (not changed) and cases without what it speaks of outside the denominator, beside.
    by_record: kept for callers; the count is per pair for every claim."""

    held: np.ndarray
    counted: np.ndarray
    changed: np.ndarray | None
    runs: tuple
    by_record: bool = False
    unit: str = "cases (pair, level, gap)"


def judge(conclusion, claim, quantifier, points, case: Case, weights, levels,
          extra="", events=None) -> Verdict:
    """The Verdict of a claim with the paper's quantifier (its wording: "may", "can", "almost
    all" as outcomes.ALIASES), counted by pipeline.assess.outcomes.count over the cases where
    it applies and changes (ties and cases where it does not apply beside), each pair with
    its earthquake's weight once; the runs outside the model's range among them counted and
    stated, and the count without them."""
    c = count(quantifier, case.held, case.counted, case.changed, weights, events)
    changed = np.ones(case.counted.shape, bool) if case.changed is None else case.changed
    denominator = case.counted & changed
    flagged = case.counted & np.any([r["outside_any"] for r in case.runs], axis=0)
    kept = count(quantifier, case.held, case.counted & ~flagged, case.changed, weights, events)
    text = f"{c.text(case.unit)} ({points})"
    text += "; " + _outside_text(case, denominator)
    if (flagged & denominator).any():
        text += (f"; without them: {kept.fraction:.0%} of {kept.counted_cases} {case.unit}"
                 if kept.counted else "; without them: nothing left")
    by_level = {str(lv): [int((case.held & denominator)[:, i].sum()),
                          int(denominator[:, i].sum())] for i, lv in enumerate(levels)}
    return Verdict(conclusion, f"{claim} [{QUANTIFIERS[c.quantifier]}: {COUNT_TEXT[c.quantifier]}]",
                   text + extra, c.verdict,
                   {**c.numbers(), "counted_at": points, "counted": c.counted_cases,
                    "unit": case.unit, "not_counted_within_tolerance": c.tie_cases,
                    "fraction_inside_range": kept.fraction,
                    "verdict_inside_range": verdict(kept.verdict),
                    "held_counted_by_level": by_level,
                    **_outside_numbers(case, denominator)})


def _outside_numbers(case: Case, denominator) -> dict:
    """The runs behind the counted cases (len(case.runs) per case) and those outside the
    model's range, in all and per flag (a run can carry several flags), the collapses among
    them by mode (pipeline.assess.collapse_modes)."""
    kinds = {name: sum(int((denominator & r["outside"][name]).sum()) for r in case.runs)
             for name in case.runs[0]["outside"]}
    outside_runs = sum(int((denominator & r["outside_any"]).sum()) for r in case.runs)
    modes = collapse_numbers([np.where(denominator, r["collapse_mode"], 0) for r in case.runs])
    return {"runs": len(case.runs) * int(denominator.sum()),
            "runs_outside_range": outside_runs, "outside_by_flag": kinds,
            "collapse_modes": modes}


def _outside_text(case: Case, denominator) -> str:
    """'N of M runs outside the model's range (...)', the collapses by mode ('floor accel 1,
    2 collapsed (2 story drift, 0 isolator capacity, 0 numerical instability)')."""
    n = _outside_numbers(case, denominator)
    kinds = ", ".join(collapse_text(n["collapse_modes"]) if k == "invalid_collapse"
                      else f"{k.removeprefix('invalid_').replace('_', ' ')} {v}"
                      for k, v in n["outside_by_flag"].items() if v)
    return (f"{n['runs_outside_range']} of {n['runs']} runs outside the model's range"
            + (f" ({kinds})" if kinds else ""))


def events(ds):
    """(R,) the pairs' earthquakes (record_event), None if the archive has none: the count
    then states no number of earthquakes (the weights, record_weight, are per earthquake)."""
    return ds.record_event.values if "record_event" in ds.coords or "record_event" in ds \
        else None


def paper_config(ds) -> tuple[int, float]:
    """The paper's bumpers (4) and wall (1500 kN/mm), or the nearest the grid has."""
    n = N_BUMPERS if N_BUMPERS in ds.n_bumpers else int(ds.n_bumpers.min())
    k = WALL_K if WALL_K in ds.wall_k else float(ds.wall_k[0])
    return n, k


def check(ds) -> list[Verdict]:
    """The paper's conclusions 5.1-5.6 and 6, each with the paper's quantifier, counted where
    what it speaks of happens; every verdict states its runs outside the model's range."""
    n_p, k_p = paper_config(ds)
    w, levels = ds.record_weight.values, ds.level.values.tolist()
    paper, bare = runs(ds, n_p, k_p), runs(ds, None)
    touch = paper["hit"] | bare["hit"]
    out = []

    def add(conclusion, claim, quantifier, points, case, extra=""):
        out.append(judge(conclusion, claim, quantifier, points, case, w, levels, extra,
                         events(ds)))

    floor = effect(paper["floor"], bare["floor"])
    add("5.1", "'For relatively wide seismic gap sizes the usage of rubber shock-absorbers "
        "may increase the response instead of reducing it. In particular, this may happen for "
        "seismic gap sizes where poundings would not occur without the incorporation of rubber "
        "bumpers' (the paper's conclusions; its section 5.1 states it without quantifier) "
        "(here: the largest peak floor acceleration)", "may",
        f"cases where the {n_p} bumpers are hit and the bare wall is not",
        Case(floor == HURT, paper["hit"] & ~bare["hit"], floor != NEUTRAL, (paper, bare)))
    base = effect(paper["base"], bare["base"])
    add("5.1", "For narrow gaps, under strong motions, bumpers can be beneficial (here: the "
        "peak base acceleration lower)", "can", "cases where the bare wall is hit",
        Case(base == HELPED, bare["hit"], base != NEUTRAL, (paper, bare)))
    ratio = effect(amplification(paper["base"], bare["base"]),
                   amplification(paper["upper"], bare["upper"]))
    add("5.1", "Bumpers are more beneficial for the base than for the floors above (the "
        "paper: 'suggest'; read as in most cases)", "most",
        "cases with contact: the base's amplification against the upper floors' largest",
        Case(ratio == HELPED, touch, ratio != NEUTRAL, (paper, bare)))
    drift = effect(paper["drift"], bare["drift"])
    add("5.1", "Interstory deflections are amplified by bumpers in most of the examined cases",
        "most", "cases with contact (bumpers or bare wall)",
        Case(drift == HURT, touch, drift != NEUTRAL, (paper, bare)))
    out += [_not_tested(ds, "5.2", "Bumper thickness hardly changes the response",
                        f"the suite keeps {THICKNESS / CM:g} cm (studies.design searches it)"),
            _not_tested(ds, "5.3", "A larger usable compression (strain, cavity) lowers the "
                        "responses", f"the suite keeps strain {STRAIN:g} and no cavity "
                        "(studies.design searches the cavity)")]
    out += _number_of_bumpers(ds, k_p, w, levels)
    softer, flexible = _wall_stiffness(ds, n_p, bare, w, levels)
    out += [softer, _not_tested(ds, "5.6", "The coefficient of restitution does not affect "
                                "the peaks", "the suite keeps the declared COR "
                                "(studies.restitution)"), flexible]
    force = effect(paper["force"], bare["force"])
    add("6", "'Employing rubber shock-absorbers at impact locations may reduce the maximum "
        "impact force'", "may", "cases where both the bumpers and the bare wall are hit",
        Case(force == HELPED, paper["hit"] & bare["hit"], force != NEUTRAL, (paper, bare)))
    out.append(narrow_more_effective(ds, paper, bare, w, levels))
    return out


def _number_of_bumpers(ds, k_p, w, levels) -> list[Verdict]:
    """5.4: more bumpers raise the peaks in almost all cases; with the most bumpers the
    indentation stays within delta_u for all examined excitations (every pair)."""
    from pipeline.assess.validity import RUBBER_STRESS_LIMIT

    if ds.n_bumpers.size < 2:
        return [_not_tested(ds, "5.4", "The number of bumpers", "one count in the grid")]
    few, many = int(ds.n_bumpers.min()), int(ds.n_bumpers.max())
    a, b = runs(ds, many, k_p), runs(ds, few, k_p)
    more = effect(a["floor"], b["floor"])
    stress = ds.bumper_stress.sel(n_bumpers=many, wall_k=k_p).where(
        ds.n_impacts.sel(n_bumpers=many, wall_k=k_p) > 0)
    extra = (f"; their largest contact stress {float(stress.max()) / 1e6:.3g} MPa (limit "
             f"{RUBBER_STRESS_LIMIT / 1e6:.3g} MPa, shape factor "
             f"{float(ds.bumper_shape_factor):.2f}; a crushed bumper is always above the "
             "limit)" if bool(stress.notnull().any()) else "")
    return [
        judge("5.4", f"'By increasing the number of bumpers ... the maximum responses ... "
              f"increase in almost all examined cases' (here: {many} rather than {few}, the "
              "largest peak floor acceleration)", "almost all",
              f"cases where the {few} or the {many} bumpers are hit",
              Case(more == HURT, a["hit"] | b["hit"], more != NEUTRAL, (a, b)), w, levels,
              events=events(ds)),
        judge("5.4", f"'For the case of using {many} bumpers the indentation does not exceed "
              f"the limit of {DELTA_U / CM:g} cm for all examined earthquake excitations' (the "
              "crush limit)", "all",
              f"cases where the {many} bumpers are hit (a pair fails where they are crushed "
              "at one level and gap)", Case(~crushed(a["indentation"], DELTA_U), a["hit"], None,
                                            (a,), by_record=True), w, levels, extra,
              events(ds))]


def _wall_stiffness(ds, n_p, bare, w, levels) -> list[Verdict]:
    """5.5: a softer wall lowers the peak floor accelerations (where the bumpers are crushed:
    only there does the wall behind them act); 6: with a flexible wall both floor
    accelerations and interstory deflections fall below those without bumpers."""
    if ds.wall_k.size < 2:
        return [_not_tested(ds, c, "The stiffness of the moat wall", "one k_w in the grid")
                for c in ("5.5", "6")]
    soft, stiff = float(ds.wall_k.min()), float(ds.wall_k.max())
    a, b = runs(ds, n_p, soft), runs(ds, n_p, stiff)
    lower = effect(a["floor"], b["floor"])
    either = crushed(a["indentation"], DELTA_U) | crushed(b["indentation"], DELTA_U)
    floor, drift = effect(a["floor"], bare["floor"]), effect(a["drift"], bare["drift"])
    return [
        judge("5.5", "A more flexible moat wall significantly reduces the peak floor "
              f"accelerations (here: k_w {soft / KN_PER_MM:g} rather than "
              f"{stiff / KN_PER_MM:g} kN/mm; stated without quantifier, read as in most "
              "cases)", "most", f"cases where the {n_p} bumpers are crushed with either wall "
              "(only there does the wall behind them act)",
              Case(lower == HELPED, either, lower != NEUTRAL, (a, b)), w, levels,
              events=events(ds)),
        judge("6", "With a relatively flexible moat wall both floor accelerations and "
              "interstory deflections are reduced compared with no bumpers (here: k_w "
              f"{soft / KN_PER_MM:g} kN/mm against the bare wall; read as in most cases)",
              "most", "cases with contact (bumpers or bare wall); changed: either quantity",
              Case((floor == HELPED) & (drift == HELPED), a["hit"] | bare["hit"],
                   (floor != NEUTRAL) | (drift != NEUTRAL), (a, bare)), w, levels,
              events=events(ds))]


def narrow_more_effective(ds, paper, bare, w, levels) -> Verdict:
    """6: bumpers more effective at gaps narrow compared with the induced displacement. Per
    pair and level, among the gaps where contact occurs (bumpers or bare wall), the base
    amplification at the narrowest of them against the widest of them: never a gap where
    nothing is hit (amplification 1 by construction)."""
    amp = amplification(paper["base"], bare["base"])
    touch = paper["hit"] | bare["hit"]
    idx = np.arange(touch.shape[-1])
    has = touch.sum(axis=-1) >= 2
    narrow = np.where(touch, idx, idx.size).min(axis=-1).clip(max=idx.size - 1)
    wide = np.where(touch, idx, -1).max(axis=-1).clip(min=0)

    def at(values, where):
        return np.take_along_axis(values, where[..., None], axis=-1)[..., 0]

    narrower = effect(at(amp, narrow), at(amp, wide))

    def at_gap(r, where):  # a configuration's run flags at one chosen gap per (pair, level)
        flags = {k: _expand(at(v, where)) for k, v in r["outside"].items()}
        return {"outside": flags, "outside_any": np.any(list(flags.values()), axis=0),
                "collapse_mode": _expand(at(r["collapse_mode"], where))}

    case = Case(_expand(narrower == HELPED), _expand(has), _expand(narrower != NEUTRAL),
                tuple(at_gap(r, g) for r in (paper, bare) for g in (narrow, wide)),
                unit="cases (pair, level)")
    return judge("6", "Bumpers seem more effective for relatively narrow seismic gaps, "
                 "compared with the induced displacement (read as in most cases)", "most",
                 "(pair, level) with contact at two gaps at least: the base amplification at "
                 "the narrowest gap with contact lower than at the widest with contact", case,
                 w, levels, events=events(ds))


def _expand(value) -> np.ndarray:
    """A (record, level) array as (record, level, 1): one case per pair and level."""
    return np.asarray(value)[..., None]


def _not_tested(ds, conclusion, claim, why) -> Verdict:
    """A conclusion the suite does not vary, with the count of all runs outside the range."""
    return Verdict(conclusion, claim, f"not tested: {why}; {_all_outside(ds)}", None,
                   {"all_runs_outside_range": all_outside_numbers(ds)})


def all_outside_numbers(ds) -> dict:
    """Runs of the whole archive (every configuration) and those outside the model's range."""
    total, bad = 0, 0
    for config in PREFIX:
        flagged = outside(ds, config)
        total, bad = total + flagged.size, bad + int(flagged.sum())
    return {"runs": total, "runs_outside_range": bad}


def _all_outside(ds) -> str:
    n = all_outside_numbers(ds)
    return f"of all runs, {n['runs_outside_range']} of {n['runs']} outside the model's range"
