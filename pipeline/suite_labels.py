"""A code suite in the studies' archives: the variables, coordinates and attributes that say
how its pairs were scaled (pipeline.motions.code_suite makes the suite; this labels it)."""
from __future__ import annotations

import numpy as np

from .archive import variable
from .motions.code_suite import LEVELS, RULE_TEXT, CodeSuite


def archive_variables(suite: CodeSuite) -> tuple[dict, dict, dict]:
    """(data variables, coordinates, attributes) saying how the suite was scaled: each
    record's MCE_R factor and weight, the target and the suite's scaled spectrum over
    `period`, the rule, its clause and period range, the building's T_M, D_M, D_TM at the
    bound run (and at every bound, with the dashpot beside: DesignBasis.attributes)."""
    data = {
        "scale_factor": variable("record", suite.factors, "1",
                                 "the pair's factor at the MCE_R (both components)"),
        "record_weight": variable("record", suite.weights, "1",
                                  "1 / the number of pairs of the same earthquake, normalised "
                                  "to sum to the number of pairs (no event dominates)"),
    }
    coords = {"record_event": variable("record", np.array(suite.events), "1",
                                       "the pair's earthquake")}
    if suite.orientations is not None:
        coords["record_orientation"] = variable(
            "record", np.array(suite.orientations), "1", "the pair's orientation: its first "
            "component along x as recorded, or its components swapped (FEMA P695: each pair "
            "of a three-dimensional model run twice)")
    attrs = {"scaling_rule": suite.rule, "scaling_rule_text": RULE_TEXT[suite.rule],
             "target": suite.target.source, "T_M": suite.design.t_m,
             "D_M": suite.design.d_m, "D_TM": suite.design.d_tm,
             "beta_M": suite.design.beta_m, "S_MS_g": suite.site["s_ms"],
             "S_M1_g": suite.site["s_m1"], "T_L": suite.site["t_long"],
             "levels": ", ".join(f"{k} {v:.4g} x MCE_R" for k, v in LEVELS.items()),
             **suite.basis.attributes(),
             **({"superstructure": "the building's own stories (linear: the paper's model)"}
                if suite.superstructure is None else suite.superstructure.attributes())}
    if suite.scaled is not None:
        s = suite.scaled
        data["target_sa"] = variable("period", s.target, "m s-2",
                                     f"MCE_R target spectral acceleration, "
                                     f"{suite.target.component} (5% damping)")
        data["suite_sa"] = variable("period", s.suite, "m s-2",
                                    f"the scaled suite's {s.statistic} {s.spectrum} spectrum "
                                    "(5% damping)")
        coords["period"] = variable("period", s.periods, "s", "oscillator period")
        attrs.update({"scaling_clause": s.clause, "scaling_period_range_s": list(s.period_range),
                      "scaling_fraction": s.fraction, "scaling_worst_ratio": s.worst_ratio,
                      "scaling_enough_pairs": int(s.enough_pairs),
                      "scaling_excluded": "; ".join(f"{n}: {r}" for n, _, r in s.excluded)
                      or "none"})
    return data, coords, attrs
