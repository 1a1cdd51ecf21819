"""pipeline.motions.rules: every scaling rule module found, an unknown rule refused listing
them, and each rule keeping the pairs its scaling keeps."""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.motions import code_scaling as cs
from pipeline.motions import target as tg

# --- the rules' registry --------------------------------------------------------------------

def test_every_rule_module_is_found_and_an_unknown_rule_lists_them():
    """pipeline/motions/rules: each module on disk is a rule, in ORDER, with a one-line TEXT
    and a clause; another name is refused in one line that lists the rules."""
    from pathlib import Path

    from pipeline.motions import rules as scaling_rules

    folder = Path(scaling_rules.__file__).parent
    on_disk = {p.stem for p in folder.glob("*.py")} - {"__init__"}
    assert {m.__name__.rsplit(".", 1)[1] for m in scaling_rules.RULES.values()} == on_disk
    assert tuple(scaling_rules.RULES) == ("asce7", "p695", "displacement")
    for name, module in scaling_rules.RULES.items():
        assert module.NAME == name and scaling_rules.rule(name) is module
        assert module.TEXT and "\n" not in module.TEXT and module.CLAUSE
    assert scaling_rules.RULES["asce7"].CLAUSE == cs.ASCE7_22_ISOLATED.clause
    with pytest.raises(ValueError) as err:
        scaling_rules.rule("asce7-16")
    message = str(err.value)
    assert "\n" not in message and "'asce7-16'" in message
    assert all(repr(name) in message for name in scaling_rules.RULES)


def test_rule_modules_keep_the_pairs_their_scaling_keeps():
    """A code rule's factors are its ScaledPairs' factors, for the pairs it kept, in the
    suite's order (ScaledPairs.factors_of), whatever the scaling left out."""
    from types import SimpleNamespace

    from pipeline.motions import rules as scaling_rules

    class Pair:
        def __init__(self, accel, dt, name):
            self.accel, self.dt, self.name = accel, dt, name

    rng = np.random.default_rng(5)
    items = [Pair(rng.normal(size=(800, 2)) * (1 + i), 0.01, f"p{i}") for i in range(4)]
    flat = tg.TargetSpectrum.from_table([0.1, 5.0], [0.5, 0.5])
    design = SimpleNamespace(t_m=1.0, d_m=0.3, t_m_bounds=(1.0, 1.0))  # a DesignBasis' fields
    for name, scale in (("asce7", cs.asce7_isolated), ("p695", cs.fema_p695)):
        chosen, factors, scaled = scaling_rules.rule(name).factors(items, flat, design, None,
                                                                  None)
        assert chosen == [0, 1, 2, 3] and scaled.names == ("p0", "p1", "p2", "p3")
        np.testing.assert_array_equal(factors, scale(items, flat, 1.0).factors)
    limited = cs.asce7_isolated(items, flat, 1.0, limits=(1.0, 2.0))
    chosen, factors = limited.factors_of(items)
    assert chosen == [1, 2] and [n for n, _, _ in limited.excluded] == ["p0", "p3"]
    np.testing.assert_array_equal(factors, limited.factors)
