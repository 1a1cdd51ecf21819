"""Record pairs at code intensities, shared by the studies beyond the paper (fragility, suite,
design): a site's target spectrum, the isolated building's code quantities, and the pairs
scaled by a code's rule (pipeline.suite_labels: the archive variables that say how).

The default site is a high-seismicity one: S_MS = 1.5 g, S_M1 = 0.9 g, T_L = 8 s (ASCE 7's
two-period spectrum, e.g. site class D in coastal California; any site by --sms-g, --sm1-g,
--tl). Levels of intensity are fractions of the MCE_R spectrum: the design earthquake is 2/3 of
it (ASCE 7-22 section 11.4.5), the service level a third (a stated choice, about the 50% in
50 years motion of such sites). A pair's factor at a level is its MCE_R factor times the
level's fraction: the shape of the suite's spectrum is kept and its amplitude scaled, as an
incremental dynamic analysis does.

Rules (--rule), one module each in pipeline/motions/rules/ and read from its registry: "asce7"
(default; ASCE 7-22 chapter 17, pipeline.motions.code_scaling.asce7_isolated: the mean
maximum-direction spectrum not below the fraction of the target over the period range around
T_M), "p695" (FEMA P695: PGV normalisation, the median anchored at T_M) and "displacement"
(every pair scaled so that the building without wall reaches D_M in plan: kept as an explicit
option, labelled as removing the record-to-record scatter).

Pairs that share an earthquake are weighted 1 / (their number) in every statistic
(pipeline.motions.weights.event_weights): no event dominates, every pair still runs.

The building's code quantities are its design basis (pipeline.motions.bounds): T_M, D_M, D_TM
from the isolators' hysteresis (plus a declared isolation damper; the paper's isolation
dashpot shown beside, neither run nor counted: damping counted once) at upper-bound, nominal
and lower-bound isolator properties; a suite is made for one bound (the
lower by default: displacements, gaps, contact), whose building the study runs
(CodeSuite.building) and whose D_M, D_TM set its gaps; the ASCE 7 rule's period range runs from
0.75 T_M (upper bound) to 1.25 T_M (lower bound) whatever the bound run.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from . import rules as scaling_rules
from .bounds import DEFAULT_BOUND

SITE = {"s_ms": 1.5, "s_m1": 0.9, "t_long": 8.0}
"""The default site: S_MS g, S_M1 g, T_L s."""
LEVELS = {"service": 1 / 3, "design": 2 / 3, "MCE_R": 1.0}
"""Intensity levels as fractions of the MCE_R target."""
RULE_TEXT = {name: module.TEXT for name, module in scaling_rules.RULES.items()}
"""Rule name -> its one line (the --rule help and the archives' scaling_rule_text)."""
DEFAULT_RULE = next(iter(scaling_rules.RULES))
"""The rule a suite is scaled by unless told: the first of the registry (asce7)."""


@dataclass(frozen=True)
class CodeSuite:
    """Pairs scaled to the MCE_R by a rule: pairs (RecordPair), names, factors (R,) at the
    MCE_R, weights (R,) per earthquake, the target (pipeline.motions.target.TargetSpectrum), the
    building's code quantities at the bound run (design: pipeline.motions.target.IsolationDesign)
    and at every bound (basis: pipeline.motions.bounds.DesignBasis), the scaling (a
    pipeline.motions.code_scaling.ScaledPairs, or None for the displacement rule) and the rule.
    `building`: the engine.Building the study runs (at the bound's isolator properties; with
    superstructure, a pipeline.motions.superstructure.SuperstructureDesign, its stories those
    the code designs: `with_superstructure`); orientations: see the field."""

    pairs: list
    names: list
    factors: np.ndarray
    weights: np.ndarray
    events: list
    target: object
    design: object
    scaled: object
    rule: str
    site: dict
    basis: object
    superstructure: object = None
    orientations: tuple | None = None
    """Each record's orientation (ORIENTATIONS) where the suite runs both (both_orientations);
    None: each pair as recorded."""

    @property
    def building(self):
        """The engine.Building the study runs: the given one at the bound's properties, on
        the code-designed stories when the suite has a superstructure."""
        return self.basis.building if self.superstructure is None \
            else self.superstructure.building

    def with_superstructure(self, story_law: str, **options) -> CodeSuite:
        """This suite running the superstructure the code designs on its building
        (pipeline.motions.superstructure.for_basis); options: r_i, overstrength, p_delta,
        collapse_drift_ratio."""
        from .superstructure import for_basis

        design = for_basis(self.basis, story_law, **options)
        return dataclasses.replace(self, superstructure=design)


def code_suite(pairs, names, building, rule: str = DEFAULT_RULE, s_ms: float = SITE["s_ms"],
               s_m1: float = SITE["s_m1"], t_long: float = SITE["t_long"],
               dt: float | None = None, bound: str = DEFAULT_BOUND,
               factors=None, target=None) -> CodeSuite:
    """Scale the pairs (RecordPair) to the site's MCE_R by the rule (see the module
    docstring), for the building (engine.Building, at nominal properties) run at `bound`
    (pipeline.motions.bounds.BOUND_NAMES; factors: its PropertyFactors, default the module's).
    Pairs the rule excludes (factor limits) are dropped and listed in .scaled.excluded.
    target: None for the two-period spectrum of s_ms, s_m1, t_long (g, g, s); or a
    site-specific MCE_R TargetSpectrum (site_specific.read_target_table), whose S_MS and S_M1
    come from it (ASCE 7-22 21.4, site_specific.site_specific_parameters; s_ms, s_m1 and
    t_long are then not used, T_L NaN in the suite's site)."""
    from .bounds import design_basis
    from .site_specific import site_specific_parameters
    from .target import asce7_target
    from .weights import event_weights

    scaling = scaling_rules.rule(rule)  # ValueError listing the rules for another name
    if target is None:
        target = asce7_target(s_ms, s_m1, t_long, level="MCE_R")
    else:
        (s_ms, s_m1), t_long = site_specific_parameters(target), float("nan")
    # D_M and T_M from the isolators' hysteresis at each bound (ASCE 7-22 17.2.8.4, 17.5.3),
    # and the building run with the damping the design counts, once (bounds.run_building):
    # the paper's isolation dashpot, a damping no prototype test measures, is shown beside
    # (basis.with_dashpot), never run.
    basis = design_basis(s_m1, building, bound, factors)
    chosen, kept, scaled = scaling.factors(pairs, target, basis, basis.building, dt)
    pairs = [pairs[i] for i in chosen]
    names = [names[i] for i in chosen]
    events = [str(p.event) for p in pairs]
    return CodeSuite(pairs, names, kept, event_weights(events), events, target, basis.design,
                     scaled, rule, {"s_ms": s_ms, "s_m1": s_m1, "t_long": t_long}, basis)


ORIENTATIONS = ("as recorded", "components swapped")
"""The two orientations of a pair in a study that runs both: its first component along x, then
along y (FEMA P695 runs each pair of a three-dimensional model twice, its components swapped;
the clause was not checked against the text at hand)."""
SWAPPED = " swapped"
"""What a swapped pair's name adds to its own (the archive's record coordinate)."""


def both_orientations(suite: CodeSuite) -> CodeSuite:
    """The suite with each pair run twice: as recorded, then its components swapped (x along
    y: ORIENTATIONS), the second block's names ending in SWAPPED, each with its pair's MCE_R
    factor; the weights again 1 / the records of an earthquake (event_weights), so that the
    two orientations share their pair's weight and every earthquake still weighs the same."""
    from pipeline.records.record_pair import RecordPair

    from .weights import event_weights

    swapped = [RecordPair(name=f"{name}{SWAPPED}", x=p.y, y=p.x)
               for p, name in zip(suite.pairs, suite.names, strict=True)]
    events = [*suite.events, *suite.events]
    return dataclasses.replace(
        suite, pairs=[*suite.pairs, *swapped],
        names=[*suite.names, *(f"{n}{SWAPPED}" for n in suite.names)],
        factors=np.concatenate([suite.factors, suite.factors]),
        weights=event_weights(events), events=events,
        orientations=tuple(o for o in ORIENTATIONS for _ in suite.pairs))


def describe(suite: CodeSuite) -> str:
    """One line: the rule, the site, the bound run, T_M, D_M (and, beside, had the paper's
    isolation dashpot been counted) and the factors' spread."""
    f = suite.factors
    site = suite.site
    basis = suite.basis
    dashpot = "" if basis.with_dashpot is None else \
        f" ({basis.with_dashpot[basis.bound].d_m * 100:.3g} cm had the paper's isolation " \
        "dashpot been counted; it is not run)"
    at = f"T_L {site['t_long']:g} s" if np.isfinite(site["t_long"]) else suite.target.source
    return (f"{len(suite.pairs)} pairs scaled to the MCE_R by {suite.rule} (S_MS "
            f"{site['s_ms']:.3g} g, S_M1 {site['s_m1']:.3g} g, {at}); "
            f"{basis.bound}-bound isolator properties: T_M {suite.design.t_m:.3g} s, D_M "
            f"{suite.design.d_m * 100:.3g} cm{dashpot}, D_TM {suite.design.d_tm * 100:.3g} cm; "
            f"factors {f.min():.3g}-{f.max():.3g} (median {np.median(f):.3g})")
