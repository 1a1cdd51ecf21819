"""The design study's verdicts: the paper's claims a bumper design speaks to (a layout that
meets the constraints and mitigates the pounding; cavities; a flexible wall; narrow gaps),
each counted the one way (pipeline.assess.outcomes.count)."""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM, KN_PER_MM, G

from ..common.recipe import Verdict
from .archive import flagged_text, table_lines
from .space import CRITERIA, DESIGN, MCE, REFERENCES, VARIABLES


def check(ds) -> list[Verdict]:
    """The search's result, and the paper's advice on cavities (5.3), soft walls (5.5) and
    bumpers at narrow gaps (6) asked of the evaluated candidates."""
    for line in [f"design gap {float(ds.attrs['design_gap']) / CM:.3g} cm = "
                 f"{float(ds.attrs['gap_over_D_M']):.3g} D_M (D_M {ds.attrs['D_M'] / CM:.3g} "
                 f"cm, D_TM {ds.attrs['D_TM'] / CM:.3g} cm); {ds.sizes['record']} pairs; "
                 f"{ds.sizes['candidate']} candidates",
                 f"criteria: {ds.attrs['criteria']}", f"bounds: {ds.attrs['bounds']}",
                 *table_lines(ds), f"optimum: {ds.attrs['optimum_nature']}",
                 shape_text(ds)]:
        print(line)
    return [_design_verdict(ds), _cavity_verdict(ds), _wall_verdict(ds), _narrow_verdict(ds)]


def shape_text(ds) -> str:
    """The shape factor of the chosen pads (the closest ones if none is feasible) and what it
    makes of their stiffness."""
    i = int(ds.attrs["closest_candidate"])
    which = "chosen" if int(ds.attrs["chosen_candidate"]) >= 0 else "closest (infeasible)"
    s, t = float(ds.shape_factor[i]), float(ds.thickness[i])
    return (f"shape factor of the {which} pads: S {s:.3g} (side {float(ds.side[i]) / CM:.3g} "
            f"cm, t {t / CM:.3g} cm): k_st {float(ds.shape_ratio[i]):.3g} x the paper's Eq. 11 "
            f"(Gent & Lindley, k = {float(ds.attrs['bumper_shape_k']):g}, against the "
            f"calibration pad's S {float(ds.attrs['bumper_shape_factor_cal']):g})")


DESIGN_CLAIM = ("A bumper layout meets the constraints at the gap and mitigates the pounding "
                "(paper 6: bumpers an effective measure for narrow gaps, against the response "
                "without them): agrees when the best feasible layout's objective is no worse "
                "than the bare wall's at the same gap")
"""The design verdict's claim and criterion (_design_verdict)."""


def _design_verdict(ds) -> Verdict:
    chosen = int(ds.attrs["chosen_candidate"])
    n_feasible = int(ds.feasible.sum())
    nature_text = ds.attrs["optimum_nature"]
    if chosen < 0:
        i = int(ds.attrs["closest_candidate"])
        fails = [c for c in CRITERIA if float(ds[f"margin_{c}"][i]) < -1e-12]
        over = int(ds.n_invalid_bumper_stress.isel(level=MCE, candidate=i))
        return Verdict("design", DESIGN_CLAIM,
                       f"none of {ds.sizes['candidate']} candidates does; the closest "
                       f"({ds.attrs['optimum']}) fails {', '.join(fails)}, its bumpers over "
                       f"the stress limit under {over} of {ds.sizes['record']} pairs at the "
                       f"MCE_R; {nature_text}", False,
                       {"closest": ds.attrs["optimum"], "fails": fails,
                        "shape_factor": float(ds.shape_factor[i]),
                        "shape_ratio": float(ds.shape_ratio[i])})
    over = int(ds.n_invalid_bumper_stress.isel(level=MCE, candidate=chosen))
    code = REFERENCES.index("code clearance D_TM")
    bare = REFERENCES.index("bare wall at the gap")
    objective = float(ds.objective[chosen])
    at_bare = float(ds["reference_" + objective_statistic(ds)][MCE, bare])
    at_code = float(ds["reference_" + objective_statistic(ds)][MCE, code])
    mitigates = objective <= at_bare
    return Verdict("design", DESIGN_CLAIM,
                   f"{n_feasible} of {ds.sizes['candidate']} candidates meet the constraints; "
                   f"the best, {ds.attrs['optimum']}, objective {objective / G:.3g} g "
                   f"{'within' if mitigates else 'above'} the bare wall's at the gap "
                   f"({at_bare / G:.3g} g); the code's design at D_TM, beside (not the "
                   f"criterion: the paper compares bumpers with the bare wall at the same gap, "
                   f"never with a wider one): {at_code / G:.3g} g, the layout "
                   f"{'within it' if objective <= at_code else f'{objective / at_code:.3g} x it'}"
                   f"; bumpers over "
                   f"the stress limit under {over} of {ds.sizes['record']} pairs at the MCE_R; "
                   f"flagged pairs at the MCE_R: "
                   f"{flagged_text(ds, '', 'candidate', chosen, MCE) or 'none'} (the code's "
                   f"design: {flagged_text(ds, 'reference_', 'reference', code, MCE) or 'none'})"
                   f"; optimum {nature_text}", mitigates,
                   {"chosen": ds.attrs["optimum"], "objective": objective,
                    "objective_bare_wall_at_gap": at_bare, "objective_code_design": at_code,
                    "optimum": json.loads(ds.attrs["optimum_bounds"]),
                    "shape_factor": float(ds.shape_factor[chosen]),
                    "shape_ratio": float(ds.shape_ratio[chosen])})


def objective_statistic(ds) -> str:
    """The statistic the objective takes: median_peak_floor_accel or p84_peak_floor_accel."""
    return f"{ds.attrs['objective']}_peak_floor_accel"


def _paired(ds, name: str, low, high):
    """Pairs of candidates equal but in `name` (low vs high value): (objective at low,
    at high), (P,) each."""
    others = [v for v in VARIABLES if v != name]
    key = {tuple(np.round([float(ds[v][i]) for v in others], 9)): i
           for i in range(ds.sizes["candidate"]) if high(float(ds[name][i]))}
    pairs = [(i, key[k]) for i in range(ds.sizes["candidate"]) if low(float(ds[name][i]))
             and (k := tuple(np.round([float(ds[v][i]) for v in others], 9))) in key]
    obj = ds.objective.values
    return np.array([obj[i] for i, _ in pairs]), np.array([obj[j] for _, j in pairs])


def _compare(conclusion, claim, ds, name, low, high, what, quantifier="most") -> Verdict:
    """A claim that `low` beats `high` in `name`, asked of every pair of candidates that differ
    only there, counted by pipeline.assess.outcomes.count (the quantifier as the paper words
    it: "can" for the cavities, "most" read where it gives none): each pair of candidates one
    case of weight 1 (its objective is already a statistic over every earthquake), ties within
    the tolerance outside the denominator and stated beside."""
    from pipeline.assess import outcomes

    a, b = _paired(ds, name, low, high)
    effect = outcomes.effect(a, b)
    c = outcomes.count(quantifier, effect == outcomes.HELPED, np.ones(a.shape, bool),
                       effect != outcomes.NEUTRAL)
    return Verdict(conclusion, f"{claim} [{outcomes.QUANTIFIERS[c.quantifier]}: "
                   f"{outcomes.COUNT_TEXT[c.quantifier]}]",
                   f"{what}: the objective lower in {c.held_cases} of {c.counted_cases} pairs of "
                   f"candidates differing only there and changing by more than "
                   f"{outcomes.TOLERANCE:.0%} ({a.size} pairs in all, {c.tie_cases} within the "
                   f"tolerance, not counted)", c.verdict,
                   {"pairs": int(a.size), "counted": c.counted_cases, "held": c.held_cases,
                    **c.numbers()})


def _cavity_verdict(ds) -> Verdict:
    return _compare("5.3", "'The use of rubber bumpers can be more effective when they are "
                    "attached in cavities on the moat wall' (here: the objective lower with a "
                    "cavity than without)", ds, "cavity_ratio", lambda r: r > 0,
                    lambda r: r == 0, "a cavity against none", "can")


def _wall_verdict(ds) -> Verdict:
    lo, hi = float(ds.wall_k.min()), float(ds.wall_k.max())
    return _compare("5.5", "'The maximum responses, and especially the maximum floor "
                    "accelerations, ... are significantly reduced when the linear post-yield "
                    "stiffness takes relatively low values' (a flexible moat wall; no "
                    "quantifier, read as in most cases)", ds, "wall_k",
                    lambda k: k == lo, lambda k: k == hi,
                    f"k_w {lo / KN_PER_MM:.4g} against {hi / KN_PER_MM:.4g} kN/mm")


NARROW_CLAIM = ("'Rubber bumpers seem to be more effective for relatively narrow seismic gaps' "
                "(paper 6; here: the chosen design lowers the largest peak floor acceleration "
                "against the bare wall at the gap at the MCE_R; read as in most cases)")


def _narrow_verdict(ds) -> Verdict:
    """Paper 6 asked of the chosen design against the bare wall at the gap, per pair at the
    MCE_R, counted by pipeline.assess.outcomes.count ("most"): pairs where contact occurs in
    one of the two, ties within the tolerance outside the denominator, each pair with its
    earthquake's weight (record_weight); the design level beside."""
    from pipeline.assess import outcomes

    claim = (f"{NARROW_CLAIM} [{outcomes.QUANTIFIERS['most']}: "
             f"{outcomes.COUNT_TEXT['most']}]")
    i = int(ds.attrs["chosen_candidate"])
    if i < 0:
        return Verdict("6", claim, "no feasible design to ask", None)
    bare = REFERENCES.index("bare wall at the gap")
    weights = ds.record_weight.values if "record_weight" in ds else None
    events = ds.record_event.values if "record_event" in ds.coords else None
    at = {}
    for lev in (DESIGN, MCE):
        mine = ds.isel(level=lev, candidate=i)
        ref = ds.isel(level=lev, reference=bare)
        effect = outcomes.with_collapse(
            outcomes.effect(mine.peak_floor_accel.values, ref.reference_peak_floor_accel.values),
            mine.invalid_collapse.values.astype(bool),
            ref.reference_invalid_collapse.values.astype(bool))
        applies = outcomes.where_contact(mine.n_impacts.values, ref.reference_n_impacts.values)
        at[lev] = outcomes.count("most", effect == outcomes.HELPED, applies,
                                 effect != outcomes.NEUTRAL, weights, events)
    c, d = at[MCE], at[DESIGN]
    hurt = float(ds.fraction_hurt[MCE, i])
    return Verdict("6", claim,
                   f"the chosen design against the bare wall at the gap, at the MCE_R: "
                   f"{c.text('pairs')}; {hurt:.0%} of all the weight hurt; at the design level: "
                   f"{d.text('pairs')}", c.verdict,
                   {"MCE_R": c.numbers(), "design": d.numbers()})
