"""What the studies beyond the paper (suite, fragility, design, plan) share on their command
lines and in their archives, declared once: the moat in plan (--moat), the wall's force
capacity (--wall-capacity-mn), the site and the scaling rule (--sms-g, --sm1-g, --tl, --rule),
the isolator properties' bound a study runs (--bound, --lambda-max, --lambda-min), the
superstructure (--stories, --r-i, --overstrength), the default
record pairs (the FEMA P695 far-field set) and the bare wall's description in the archives'
long names."""
from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from engine.results import WALLS
from engine.units import KN_PER_MM
from pipeline.motions.bounds import (
    BOUND_NAMES,
    BOUND_TEXT,
    DEFAULT_BOUND,
    LAMBDA_MAX,
    LAMBDA_MIN,
    PLAUSIBLE_FACTORS,
)
from pipeline.motions.code_suite import DEFAULT_RULE, RULE_TEXT, SITE
from pipeline.motions.lateral_systems import DEFAULT as DEFAULT_SYSTEM
from pipeline.motions.superstructure import COLLAPSE_DRIFT_RATIO

PAIR_SET = "far-field"
"""The FEMA P695 record set the studies run by default (pipeline.records.pair_names)."""
QUICK_PAIRS = 4
"""The pairs of a --quick suite or fragility run: the first of PAIR_SET."""


def add_backend(p) -> None:
    """--backend: the engine's time loop (engine.simulate's backend)."""
    from engine.backends import BACKENDS

    p.add_argument("--backend", choices=BACKENDS, default=None,
                   help="the engine's time loop: numba (the compiled kernel on every core), "
                        "numpy (the vectorised reference) or cuda (an NVIDIA GPU, one thread "
                        "per simulation, 10^6 a call; pip install -e \".[cuda]\"; the "
                        "planar and plan models) (default: numba)")


def add_moat(p) -> None:
    """--moat: the moat in plan, one of engine.results.WALLS (default rectangular)."""
    p.add_argument("--moat", choices=tuple(WALLS), default="rectangular",
                   help="the moat in plan: rectangular, walls normal to x and y at +- the gap "
                        "(default), or circular, a circle of radius the gap")


def add_wall_capacity(p, use: str = "the validity flag invalid_wall_force") -> None:
    """--wall-capacity-mn: the wall's force capacity in MN (default none: not checked); `use`
    says what the study does with it."""
    p.add_argument("--wall-capacity-mn", type=float, default=None, metavar="MN",
                   help=f"the moat wall's lateral capacity in MN, for {use} (default: none, "
                        "not checked)")


def wall_capacity(args) -> float | None:
    """--wall-capacity-mn in N (None: not given); SweepError unless positive."""
    from pipeline.errors import SweepError

    if args.wall_capacity_mn is None:
        return None
    if not args.wall_capacity_mn > 0:
        raise SweepError(f"--wall-capacity-mn must be positive, got {args.wall_capacity_mn:g}")
    return args.wall_capacity_mn * 1e6


def default_pairs(quick: bool, n_quick: int | Sequence[str],
                  record_set: str = PAIR_SET) -> list[str]:
    """The pairs of a FEMA P695 record set (default PAIR_SET, the far-field); quick: the first
    n_quick of them, or the pairs n_quick names (the far-field set's only)."""
    from pipeline.records import pair_names

    names = pair_names(record_set)
    if not quick:
        return names
    if isinstance(n_quick, int):
        return names[:n_quick]
    # named quick pairs are the far-field set's; another set's quick run takes as many of its own
    return list(n_quick) if record_set == PAIR_SET else names[:len(n_quick)]


def chosen_pairs(args, n_quick: int | Sequence[str]):
    """The pairs a study runs: --records, else `default_pairs(--quick, n_quick, --set)`, read
    from --records-dir or the library. Returns (pairs, names), as
    pipeline.checks.resolve_pairs."""
    from pipeline.checks import resolve_pairs

    return resolve_pairs(args.records or default_pairs(args.quick, n_quick, args.set),
                         args.records_dir)


def bare_wall_text() -> str:
    """The bare wall as the archives describe it, 'linear law, k 2500 kN/mm, COR 0.5': the law
    and its parameters' names and defaults from pipeline.grid.BASELINE (the linear law's
    declaration), the stiffness in kN/mm."""
    from pipeline.grid import BASELINE, BASELINE_LAW, swept_parameter

    stiffness = swept_parameter(BASELINE_LAW, "wall_k").name
    restitution = swept_parameter(BASELINE_LAW, "cor").name.upper()
    return (f"{BASELINE_LAW} law, {stiffness} {BASELINE['wall_k'] / KN_PER_MM:g} kN/mm, "
            f"{restitution} {BASELINE['cor']:g}")


def site_options(p) -> None:
    """The site's and the rule's command-line options: the two-period spectrum's parameters
    (default None, read as SITE's by checked_site, so that a site-specific spectrum given
    beside them is told apart) or a site-specific spectrum's table."""
    p.add_argument("--sms-g", type=float, default=None, metavar="G",
                   help=f"MCE_R short-period spectral acceleration S_MS in g (default "
                        f"{SITE['s_ms']:g})")
    p.add_argument("--sm1-g", type=float, default=None, metavar="G",
                   help=f"MCE_R 1-s spectral acceleration S_M1 in g (default {SITE['s_m1']:g})")
    p.add_argument("--tl", type=float, default=None, metavar="S",
                   help=f"long-period transition period T_L in s (default {SITE['t_long']:g})")
    p.add_argument("--target-spectrum", type=Path, default=None, metavar="CSV",
                   help="a site-specific MCE_R spectrum (RotD100) instead of the two-period "
                        "one of --sms-g, --sm1-g, --tl: a CSV table with the columns "
                        "period_s and sa_g covering 0.2 to 5 s at least; S_MS and S_M1 come "
                        "from it by ASCE 7-22 section 21.4")
    p.add_argument("--rule", choices=tuple(RULE_TEXT), default=DEFAULT_RULE,
                   help="how the pairs are scaled: " + "; ".join(
                       f"{k}: {v}" for k, v in RULE_TEXT.items()))


def add_bound(p) -> None:
    """--bound: the isolator properties the study runs and takes its gaps from (default the
    lower bound: displacements, gaps, contact); --lambda-max, --lambda-min: the property
    modification factors on Q_d and K_d (pipeline.motions.bounds)."""
    p.add_argument("--bound", choices=BOUND_NAMES, default=DEFAULT_BOUND,
                   help="the isolator properties the building runs at and the code's D_M, "
                        "D_TM (the gaps) come from: " + "; ".join(
                            f"{k}: {v}" for k, v in BOUND_TEXT.items())
                        + f" (default {DEFAULT_BOUND}); T_M, D_M and D_TM at all three are "
                        "stored")
    p.add_argument("--lambda-max", type=float, default=LAMBDA_MAX, metavar="FACTOR",
                   help="upper-bound property modification factor on the isolators' "
                        "characteristic strength Q_d and post-yield stiffness K_d (friction "
                        "pendulum: the friction), ASCE 7-22 17.2.8.4 (default "
                        f"{LAMBDA_MAX:g}, not checked against the standard's text)")
    p.add_argument("--lambda-min", type=float, default=LAMBDA_MIN, metavar="FACTOR",
                   help="lower-bound property modification factor on Q_d and K_d (default "
                        f"{LAMBDA_MIN:g}, not checked against the standard's text)")


STORY_CHOICES = ("imk", "bilinear", "linear")
"""--stories: the code-designed building on the deteriorating or the hardening story law, or
the building's own stories (linear: the paper's model)."""


def add_stories(p, lateral_system: str = DEFAULT_SYSTEM) -> None:
    """--stories, --lateral-system (default `lateral_system`), --r-i, --overstrength: the
    superstructure a study runs (pipeline.motions.superstructure,
    pipeline.motions.lateral_systems)."""
    from pipeline.motions.lateral_systems import SYSTEMS
    from pipeline.motions.superstructure import OVERSTRENGTH, R_I, STORY_HEIGHT

    p.add_argument("--stories", choices=STORY_CHOICES, default=STORY_CHOICES[0],
                   help="the superstructure: imk (default) the building the code designs on "
                        "its isolation (ASCE 7-22 17.5.4-17.5.5: story strengths --overstrength "
                        "x the design shears) on deteriorating stories (modified IMK), with "
                        "P-Delta and collapse at a story drift of --collapse-drift of its "
                        f"height ({STORY_HEIGHT:g} m stories "
                        "unless the building gives heights); in plan each story's law acts "
                        "along x and y, uncoupled; bilinear: the same strengths, hardening "
                        "stories; linear: the building's own stories (the paper's model)")
    p.add_argument("--lateral-system", choices=tuple(SYSTEMS), default=lateral_system,
                   help="the designed stories' lateral system: "
                        + "; ".join(f"{name} {system.title}"
                                    + (" (default)" if name == lateral_system else "")
                                    for name, system in SYSTEMS.items())
                        + ". A steel system's stories (ASCE 7-22 Table 12.2-1) have each the "
                        "strength Omega_0 x its design shear and the stiffness at which it "
                        "yields at the system's drift (pipeline.motions.lateral_systems)")
    p.add_argument("--r-i", type=float, default=R_I, metavar="R_I",
                   help="the superstructure's response modification R_I, 1 to 2 (ASCE 7-22 "
                        f"17.5.4.2; default {R_I:g})")
    p.add_argument("--collapse-drift", type=float, default=COLLAPSE_DRIFT_RATIO,
                   metavar="RATIO",
                   help="the story drift ratio at which a designed story is taken as collapsed "
                        f"(default {COLLAPSE_DRIFT_RATIO:g}, Vamvatsikos & Cornell 2002's IDA "
                        "cap; Kitayama & Constantinou 2018 count 0.05), "
                        f"{PLAUSIBLE_COLLAPSE_DRIFT[0]:g} to {PLAUSIBLE_COLLAPSE_DRIFT[1]:g}")
    p.add_argument("--overstrength", type=float, default=None, metavar="FACTOR",
                   help="story strength over its design shear (default: the lateral "
                        f"system's Omega_0; {OVERSTRENGTH:g} on the building's own stories, a "
                        "stated choice, the overstrength factor of a steel special "
                        "concentrically braced frame)")


ISOLATOR_CHOICES = ("given", "designed-tfp", "designed-lrb")
"""--isolators: the building's own isolators, or triple friction pendulums or lead-rubber
bearings designed for the site (pipeline.motions.designed_isolation.DESIGNS, which a test holds
to these)."""


def add_isolators(p, default: str = ISOLATOR_CHOICES[0]) -> None:
    """--isolators (default `default`), --t-m: the isolation system a study runs (the
    building's own, or one designed for the site and a target period)."""
    from pipeline.motions.designed_isolation import TARGET_PERIOD

    mark = {choice: " (default)" if choice == default else "" for choice in ISOLATOR_CHOICES}
    p.add_argument("--isolators", choices=ISOLATOR_CHOICES, default=default,
                   help=f"the isolation system: given{mark['given']} the building's own "
                        "isolators (the paper's bilinear ones unless --building says "
                        f"otherwise); designed-tfp{mark['designed-tfp']}: triple friction "
                        "pendulums designed for the site, nominal T_M --t-m at the nominal "
                        "D_M, their restrainers beyond the lower bound's D_TM; "
                        f"designed-lrb{mark['designed-lrb']}: lead-rubber bearings (bilinear, "
                        "Q_d 6%% of the weight, K1 10 K2) designed alike, their capacity 10%% "
                        "beyond D_TM (pipeline.motions.designed_isolation), the building's "
                        "masses kept")
    p.add_argument("--t-m", type=float, default=TARGET_PERIOD, metavar="S",
                   help=f"the target effective period T_M of designed isolators at nominal "
                        f"properties, s (default {TARGET_PERIOD:g})")


def isolated_building(args, target, factors):
    """The building a suite is designed for: --building as given, or on the isolators
    --isolators names (triple friction pendulums, lead-rubber bearings) designed for the
    site's S_M1 (of --sm1-g, or of the site-specific target) and --t-m. ValueError where the
    design cannot be met."""
    if getattr(args, "isolators", "given") == "given":
        return args.building
    from pipeline.motions.designed_isolation import designed_isolation
    from pipeline.motions.site_specific import site_specific_parameters

    s_m1 = args.sm1_g if target is None else site_specific_parameters(target)[0][1]
    if not (np.isfinite(args.t_m) and args.t_m > 0):
        raise ValueError(f"--t-m must be a positive period (s), got {args.t_m:g}")
    return designed_isolation(s_m1, args.building, args.t_m, factors,
                              kind=args.isolators).building


def property_factors(args):
    """The pipeline.motions.bounds.PropertyFactors of --lambda-max, --lambda-min (the
    module's defaults for a study without them); SweepError, one line, for factors the code
    does not allow (max >= 1 >= min > 0)."""
    from pipeline.errors import SweepError
    from pipeline.motions.bounds import PropertyFactors

    high = getattr(args, "lambda_max", LAMBDA_MAX)
    low = getattr(args, "lambda_min", LAMBDA_MIN)
    if not (math.isfinite(high) and high >= 1):
        raise SweepError(f"--lambda-max must be >= 1 (the upper bound's factor), got {high:g}")
    if not (math.isfinite(low) and 0 < low <= 1):
        raise SweepError(f"--lambda-min must be in (0, 1] (the lower bound's factor), got "
                         f"{low:g}")
    most, least = PLAUSIBLE_FACTORS
    if high > most or low < least:
        option, value, bound = ("--lambda-max", high, f"above {most:g}") if high > most \
            else ("--lambda-min", low, f"below {least:g}")
        raise SweepError(f"{option} {value:g} is implausible ({bound}: a bound no bearing's "
                         f"tests support); give the factor itself, e.g. {option} "
                         f"{LAMBDA_MAX if option == '--lambda-max' else LAMBDA_MIN:g}")
    return PropertyFactors.uniform(high, low)


def checked_gaps(gaps, design) -> np.ndarray:
    """A study's gaps (m), fractions of the code's D_M or D_TM (design: its IsolationDesign):
    SweepError, one line, naming the design where one lies beyond any moat (GAP's plausible
    range: the sweep would take it for a gap typed in cm)."""
    from engine.impact.parameters import GAP
    from pipeline.errors import SweepError

    gaps = np.asarray(gaps, dtype=float)
    if GAP.implausible(gaps).size:
        raise SweepError(f"the code's design gives D_M {design.d_m:.3g} m and D_TM "
                         f"{design.d_tm:.3g} m (T_M {design.t_m:.3g} s), and the study's gaps "
                         f"up to {gaps.max():.3g} m, beyond a plausible moat's gap, "
                         f"{GAP.plausible} m: check the site (--sm1-g, --sms-g), the bound "
                         "(--bound, --lambda-min) and the building's isolators")
    return gaps


SITE_OPTIONS = {  # attribute: (option, what, unit, largest plausible value)
    "sms_g": ("--sms-g", "S_MS", "g", 5.0),
    "sm1_g": ("--sm1-g", "S_M1", "g", 4.0),
    "tl": ("--tl", "T_L", "s", 20.0),
}
"""The site's options and the largest value a real site has (ASCE 7-22's maps and
site-specific spectra stay well below; beyond it, most likely a value in percent of g)."""


def checked_site(args) -> None:
    """Refuse a site option no real site has, in one line naming the option, its unit and,
    for a spectral value in percent, the conversion, or site options given beside
    --target-spectrum (SweepError; before any compute); the options not given take SITE's
    values."""
    from pipeline.errors import SweepError

    given = [SITE_OPTIONS[name][0] for name in SITE_OPTIONS if getattr(args, name) is not None]
    if getattr(args, "target_spectrum", None) is not None and given:
        raise SweepError(f"--target-spectrum is the site's whole MCE_R spectrum: give it or "
                         f"{', '.join(given)}, not both")
    for name, key in zip(SITE_OPTIONS, ("s_ms", "s_m1", "t_long"), strict=True):
        if getattr(args, name) is None:
            setattr(args, name, SITE[key])
    for name, (option, what, unit, largest) in SITE_OPTIONS.items():
        value = getattr(args, name)
        if not (math.isfinite(value) and value > 0):
            raise SweepError(f"{option}: {what} must be positive ({unit}), got {value:g}")
        if value > largest:
            hint = (f": give {unit} ({value:g}% g is {value / 100:g} g)"
                    if unit == "g" and value / 100 <= largest else "")
            raise SweepError(f"{option} {value:g} {unit} is implausible for {what} (above "
                             f"{largest:g} {unit}){hint}")


PLAUSIBLE_COLLAPSE_DRIFT = (0.01, 0.2)
"""The story drift ratios at which a study may take a story as collapsed: from 1% (a story
barely past yield) to 20% (beyond any frame's tested drift; a percent typed as a ratio, 5 for
0.05, is refused)."""


def checked_collapse_drift(value: float) -> float:
    """--collapse-drift within PLAUSIBLE_COLLAPSE_DRIFT (SweepError, one line, otherwise)."""
    from pipeline.errors import SweepError

    low, high = PLAUSIBLE_COLLAPSE_DRIFT
    if not (math.isfinite(value) and low <= value <= high):
        hint = f": give a ratio ({value:g}% is {value / 100:g})" if low <= value / 100 <= high \
            else ""
        raise SweepError(f"--collapse-drift {value:g} is implausible (outside [{low:g}, "
                         f"{high:g}], a story drift ratio){hint}")
    return value


def checked_overstrength(value: float) -> float:
    """--overstrength within PLAUSIBLE_OVERSTRENGTH (SweepError, one line, otherwise)."""
    from pipeline.errors import SweepError
    from pipeline.motions.superstructure import PLAUSIBLE_OVERSTRENGTH

    low, high = PLAUSIBLE_OVERSTRENGTH
    if not (math.isfinite(value) and low <= value <= high):
        raise SweepError(f"--overstrength {value:g} is implausible (outside [{low:g}, "
                         f"{high:g}]: a story's strength over its design shear, at most the "
                         "largest Omega_0 of ASCE 7-22 Table 12.2-1)")
    return value


def scaled_suite(args, pairs, names):
    """The pairs scaled to the site's MCE_R by --rule (pipeline.motions.code_suite), for the
    building run at --bound (a study without add_bound's options: the nominal bound, the
    building as given) on the superstructure of --stories (without add_stories: the
    building's own stories), the site options checked first; SweepError, one line, for what the
    rule refuses. The study runs the suite's `building` (CodeSuite.building); its archive
    says the design basis (pipeline.suite_labels.archive_variables), which the recipe
    prints."""
    from pipeline.errors import SweepError
    from pipeline.motions.code_suite import code_suite
    from pipeline.motions.site_specific import read_target_table

    checked_site(args)
    factors = property_factors(args)
    try:
        table = getattr(args, "target_spectrum", None)
        target = None if table is None else read_target_table(table)
    except ValueError as err:
        raise SweepError(f"--target-spectrum: {err}") from None
    try:
        building = isolated_building(args, target, factors)
        suite = code_suite(pairs, names, building, args.rule, args.sms_g, args.sm1_g,
                           args.tl, args.dt, bound=getattr(args, "bound", "nominal"),
                           factors=factors, target=target)
        stories = getattr(args, "stories", "linear")
        if stories != "linear":
            if args.overstrength is not None:
                checked_overstrength(args.overstrength)
            drift = checked_collapse_drift(getattr(args, "collapse_drift",
                                                   COLLAPSE_DRIFT_RATIO))
            suite = suite.with_superstructure(
                stories, r_i=args.r_i, overstrength=args.overstrength,
                lateral_system=getattr(args, "lateral_system", DEFAULT_SYSTEM),
                collapse_drift_ratio=drift)
        return suite
    except ValueError as err:
        raise SweepError(str(err)) from err
