"""The rules that scale record pairs to a site's MCE_R, one module each: every module in this
folder is a rule, found here as the isolator and impact laws are found (engine/registry.py), so
a new rule is a new module here and nothing else; pipeline.motions.code_suite reads its --rule
choices and their help from RULES.

A rule module holds:
    NAME: str, ORDER: int     its name (the --rule choice, the archives' scaling_rule) and its
                              place in listings
    TEXT: str                 one line saying what it does (the --rule help, the archives'
                              scaling_rule_text)
    CLAUSE: str               the clause of the standard it implements, or why it is none
    factors(pairs, target, design, building, dt) -> (chosen, factors, scaled)
        pairs: records.RecordPair list (.accel (N, 2) m/s^2, .dt s, .name); target: the MCE_R
        target (pipeline.motions.target.TargetSpectrum); design: the building's design basis
        (pipeline.motions.bounds.DesignBasis: t_m s, d_m m, d_tm m at the bound run, t_m_bounds
        (T_M upper bound, T_M lower bound) s); building: the engine.Building run (at that
        bound's isolator properties); dt: integration step (s) of any engine run, None for
        engine.DEFAULT_DT.
        chosen: indices (list of int) of the pairs kept, in their order; factors (K,) -: each
        kept pair's factor at the MCE_R (both components); scaled: the
        pipeline.motions.code_scaling.ScaledPairs that justifies them, or None when the rule has no
        spectra to show.

The codes' arithmetic (spectra of pairs, the factors of each clause) is
pipeline.motions.code_scaling's, pure arrays; a rule module declares the rule and applies it to a
suite.
"""
from __future__ import annotations

import sys
from types import ModuleType

from engine.registry import discover

RULE_INTERFACE = ("NAME", "ORDER", "TEXT", "CLAUSE", "factors")
"""What every rule module defines."""

RULES: dict[str, ModuleType] = discover(sys.modules[__name__], RULE_INTERFACE)
"""Scaling rule name -> its module, in ORDER."""


def rule(name: str) -> ModuleType:
    """The module of the scaling rule `name`; ValueError, one line listing the rules, for
    another name."""
    if name not in RULES:
        raise ValueError(f"unknown scaling rule {name!r}; choose one of {tuple(RULES)}")
    return RULES[name]
