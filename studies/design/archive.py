"""studies.design's archive: every evaluated candidate with its per-pair peaks, flags and
statistics per level, the references beside them, the optimum's nature, and the text tables
the verdicts and the command print from it (see design.py's docstring)."""
from __future__ import annotations

import json

import numpy as np

from engine.units import CM, G
from pipeline.assess import derived
from pipeline.assess.collapse_modes import collapse_numbers, collapse_text
from pipeline.motions.code_suite import LEVELS

from ..common.options import bare_wall_text
from .optimum import nature
from .search import STAT_TEXT, Search, bumper_members, describe, statistics
from .space import CRITERIA, OBJECTIVES, PEAKS, REFERENCES, VARIABLES


def dataset(search: Search, references: dict, rounds: int, args):
    """The archive: every candidate and reference, per pair and level, with the statistics,
    the constraints, the ranking and the optimum's nature."""
    from pipeline.archive import collapse_mode_coords, labelled_dataset, variable
    from pipeline.provenance import common_attributes, plan_attributes, run_attributes
    from pipeline.suite_labels import archive_variables

    problem, suite = search.problem, search.problem.suite
    judged = search.judged()
    ref_stats = statistics(references, suite.weights, search.bare)
    table = search.table
    t = table["thickness"]
    members = bumper_members(table, search.gap, search.strain, search.shape_k)
    data, coords, attrs = archive_variables(suite)
    coords.update({
        "record": variable("record", np.array(suite.names), "1", "record pair"),
        "level": variable("level", problem.levels, "1",
                          "intensity level: fraction of the MCE_R factors"),
        "level_name": variable("level", np.array(list(LEVELS)), "1", "intensity level"),
        "reference": variable("reference", np.array(REFERENCES), "1",
                              "reference designs: the building without wall; the bare wall "
                              f"({bare_wall_text()}) at the gap; the code's design, the bare "
                              "wall at the clearance D_TM"),
        **collapse_mode_coords(),
    })
    for name, (units, long_name) in VARIABLES.items():
        coords[name] = variable("candidate", table[name], units, long_name)
    per_candidate = {
        "cavity": ("m", "depth of the wall cavity holding each bumper", table["cavity_ratio"] * t),
        "side": ("m", "side of the square bumper, 4 S t", 4 * table["shape_factor"] * t),
        "bumper_area": ("m2", "contact area of one bumper", members.area),
        "shape_ratio": ("1", "the pads' static stiffness over the paper's Eq. 11, (1 + 2 k S^2) "
                        "/ (1 + 2 k S_cal^2) (Gent & Lindley 1959; the bumper law's "
                        "shape_ratio)", _shape_ratio(members)),
        "clear_gap": ("m", "clear gap in front of the bumpers, gap - (t - c)",
                      members.contact.clear_gap),
        "delta_u": ("m", "crush limit min(strain t, t - c)", members.contact.delta_u),
        "stage": ("1", "0: the coarse grid; i: round i of the pattern search", search.stage),
    }
    for name, (units, long_name, values) in per_candidate.items():
        data[name] = variable("candidate", values, units, long_name)
    dims = ("record", "level", "candidate")
    for name, values in search.peaks.items():
        data[name] = _peak_variable(dims, name, values)
        data[f"reference_{name}"] = _peak_variable(("record", "level", "reference"), name,
                                                   references[name])
    data["reference_gap"] = variable("reference", [np.inf, search.gap, suite.design.d_tm], "m",
                                     "the reference's gap (inf: no wall)")
    for name, values in judged["stats"].items():
        data[name] = _stat_variable(("level", "candidate"), name, values)
        data[f"reference_{name}"] = _stat_variable(("level", "reference"), name,
                                                   ref_stats[name])
    attrs["collapse_modes"] = json.dumps(
        {which: collapse_numbers(values["collapse_mode"])
         for which, values in (("candidates", search.peaks), ("references", references))})
    for name, margin in judged["margins"].items():
        data[f"margin_{name}"] = variable("candidate", margin, "1", f"how far inside the "
                                          f"{name} constraint (>= 0: met), fraction of the "
                                          "pairs' weight")
    data["feasible"] = variable("candidate", judged["feasible"].astype(np.int8), "1",
                                "1 where every constraint is met")
    floor = derived.quantity("peak_floor_accel")
    data["objective"] = variable("candidate", judged["objective"], floor.units,
                                 f"{OBJECTIVES[search.criteria.objective]} of the "
                                 f"{floor.long_name} at the MCE_R")
    data["rank"] = variable("candidate", judged["rank"], "1", "rank among the feasible "
                            "candidates (1 = chosen; 0 = infeasible)")
    best = search.best(judged)
    chosen = best if judged["feasible"][best] else -1
    found = nature(table, best, search.bounds, fails=_fails(judged),
                   scores=np.column_stack([judged["objective"], judged["secondary"]]))
    attrs.update(common_attributes("bumper design search (beyond the paper)"))
    attrs.update(run_attributes(problem.dt, problem.building))
    attrs.update(plan_attributes(problem.moat))
    attrs.update(
        design_gap=search.gap, design_gap_units="m", gap_over_D_M=search.gap / suite.design.d_m,
        objective=search.criteria.objective, criteria=search.criteria.text(),
        within_limits_required=search.criteria.within_limits,
        stress_limit_counted=int(search.criteria.stress_limit),
        service_contact_allowed=search.criteria.service_contact,
        hurt_design_allowed=search.criteria.hurt_design,
        validity_limits=problem.limits.describe(), bumper_stress_limit=problem.limits.bumper_stress,
        bounds=search.bounds.text(),
        usable_strain=search.bounds.usable(float(table["shape_factor"][best])),
        bumper_shape_k=search.shape_k,
        bumper_shape_factor_cal=_law().shape_factor_cal.default,
        wall_length=search.bounds.wall_length, D_S=search.bounds.clearance,
        search_rounds=rounds,
        chosen_candidate=chosen, closest_candidate=best,
        optimum_nature=found.text(), optimum_interior=int(found.interior),
        optimum_bounds=json.dumps(found.as_dict()),
        optimum=describe(table, best, search.shape_k))
    return labelled_dataset(data, coords, attrs)


def _law():
    """The bumper law's declaration."""
    from engine.impact import LAWS

    return LAWS["bumper"].PARAMETERS


def _shape_ratio(members) -> np.ndarray:
    """(K,) the candidates' shape ratio, as the bumper law computes it from their columns."""
    from engine.impact import LAWS

    c = members.columns
    return LAWS["bumper"].shape_ratio(c["area"], c["thickness"], c["shape_k"])


def _fails(judged) -> list[list[str]]:
    """(K,) the constraints each candidate fails."""
    margins = judged["margins"]
    return [[c for c in CRITERIA if margins[c][i] < -1e-12]
            for i in range(judged["objective"].size)]


def _peak_variable(dims, name, values):
    from pipeline.archive import collapse_mode_variable, variable
    from pipeline.assess import validity

    if name in PEAKS:
        units, long_name = PEAKS[name]
        return variable(dims, values, units, long_name)
    if name == "collapse_mode":  # the engine's codes, as the sweeps label them
        return collapse_mode_variable(dims, values)
    if name == "crushed":  # a bool, stored as 0 / 1
        q = derived.quantity(name)
        return variable(dims, values.astype(np.int8), q.units, q.long_name)
    return variable(dims, values.astype(np.int8), "1", f"1 where {validity.FLAGS[name]}")


def _stat_variable(dims, name, values):
    from pipeline.archive import variable
    from pipeline.assess import validity

    if name in STAT_TEXT:
        units, long_name = STAT_TEXT[name]
        return variable(dims, values, units, long_name)
    if name == "n_invalid_collapse_by_mode":
        return variable(("mode", *dims), values, "1", "number of pairs where the run "
                        "collapsed, by how it collapsed (collapse_mode)")
    flag = name.removeprefix("n_")
    return variable(dims, values, "1", f"number of pairs where {validity.FLAGS[flag]}")


def _line(label: str, ds, prefix: str, dim: str, i: int) -> list[str]:
    """Rows of the table for one candidate or reference, one per level."""
    lines = []
    for lev, name in enumerate(ds.level_name.values):
        def at(stat, lev=lev):
            return float(ds[f"{prefix}{stat}"].isel(level=lev, **{dim: i}))
        flagged = flagged_text(ds, prefix, dim, i, lev)
        lines.append(f"{label if lev == 0 else '':54.54s} {name:>7} "
                     f"{at('median_peak_floor_accel') / G:6.3f} "
                     f"{at('p16_peak_floor_accel') / G:6.3f}-"
                     f"{at('p84_peak_floor_accel') / G:<6.3f} "
                     f"{at('fraction_uncrushed'):7.0%} {at('fraction_within_stress'):6.0%} "
                     f"{at('fraction_contact'):7.0%} "
                     f"{at('fraction_helped'):6.0%} {at('fraction_hurt'):5.0%}  "
                     f"{flagged or '-'}")
    return lines


def flagged_text(ds, prefix: str, dim: str, i: int, level: int) -> str:
    """The pairs each validity flag counts for a candidate or reference at a level, the
    collapses by mode: 'bumper_stress 3, 1 collapsed (1 story drift, 0 isolator capacity, 0
    numerical instability)' ('' when none)."""
    from pipeline.assess import validity

    at = {"level": level, dim: i}
    counts = {name: int(ds[f"{prefix}n_{name}"].isel(**at)) for name in validity.FLAGS}
    modes = collapse_numbers(ds[f"{prefix}collapse_mode"].isel(**at).values)
    return ", ".join(collapse_text(modes) if name == "invalid_collapse"
                     else f"{name.removeprefix('invalid_')} {n}" for name, n in counts.items() if n)


def table_lines(ds, best_few: int = 3) -> list[str]:
    """The chosen design (and the next ranks), the closest one if none is feasible, and the
    references, at every level, as text."""
    lines = [f"{'design':54s} {'level':>7} {'median':>6} {'16-84% (g)':>13} "
             f"{'uncrush':>7} {'stress':>6} {'contact':>7} {'helped':>6} {'hurt':>5}  "
             "flagged pairs"]
    rank = ds["rank"].values
    order = [int(i) for i in np.argsort(np.where(rank > 0, rank, 10 ** 9))[:best_few]
             if rank[i] > 0]
    if not order:
        order = [int(ds.attrs["closest_candidate"])]
        lines.append("no feasible candidate; the closest to feasible:")
    table = {v: ds[v].values for v in VARIABLES}
    for i in order:
        label = (f"#{rank[i]} " if rank[i] else "") + describe(table, i)
        lines += _line(label, ds, "", "candidate", i)
    for j, name in enumerate(REFERENCES):
        gap = float(ds.reference_gap[j])
        label = name + ("" if not np.isfinite(gap) else f" ({gap / CM:.3g} cm)")
        lines += _line(label, ds, "reference_", "reference", j)
    return lines
